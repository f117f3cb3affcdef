/* The n-dimensional map layer: the Henon and generalized Henon maps and
 * the chain rule of sc_map_iterate_n() against differences and closed
 * forms, the one-dimensional models through the same interface against
 * sc_map_iterate(), and the refusals. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/io.h"
#include "slipcont/map.h"
#include "test_util.h"

/* Central differences of order two have error ~ h^2 f''' + eps f / h:
 * with h = 1e-5 and the maps' moderate derivatives, ~1e-9 relative to
 * the entries' scale. */
static const double FD_H = 1e-5;
static const double FD_TOL = 2e-7;

/* Largest |a_i - b_i| over @p k entries, relative to max(1, |b|). */
static double maxdiff(const double *a, const double *b, size_t k) {
  double e = 0, s = 1;
  for (size_t i = 0; i < k; i++) s = fmax(s, fabs(b[i]));
  for (size_t i = 0; i < k; i++) e = fmax(e, fabs(a[i] - b[i]));
  return e / s;
}

/* Every derivative of f^k at x against central differences of the
 * next-lower derivative (f for J and fp, J for H and Jp, H for T). */
static void check_derivs(sc_map *m, const double *x, int k) {
  size_t n = sc_map_dim(m), np = sc_map_nparam(m);
  sc_mapn_value *v, *a, *b;
  sc_msg msg;
  sc_mapn_value_alloc(m, SC_EVAL_DERIV2, &v, &msg);
  sc_mapn_value_alloc(m, SC_EVAL_DERIV2, &a, &msg);
  sc_mapn_value_alloc(m, SC_EVAL_DERIV2, &b, &msg);
  if (!tu_true(sc_map_iterate_n(m, x, k, SC_EVAL_DERIV2, v, &msg) == SC_OK,
               "iterate: %s", msg.text))
    goto out;
  double fdJ[SC_DIM_TENSOR * SC_DIM_TENSOR], fdH[4096], fdT[65536];
  double xp[SC_DIM_TENSOR], xm[SC_DIM_TENSOR];
  for (size_t j = 0; j < n; j++) {
    memcpy(xp, x, n * sizeof *x);
    memcpy(xm, x, n * sizeof *x);
    xp[j] += FD_H;
    xm[j] -= FD_H;
    sc_map_iterate_n(m, xp, k, SC_EVAL_DERIV2, a, &msg);
    sc_map_iterate_n(m, xm, k, SC_EVAL_DERIV2, b, &msg);
    for (size_t i = 0; i < n; i++) {
      fdJ[i * n + j] = (a->f[i] - b->f[i]) / (2 * FD_H);
      for (size_t l = 0; l < n; l++)
        fdH[(i * n + l) * n + j] =
            (a->J[i * n + l] - b->J[i * n + l]) / (2 * FD_H);
      for (size_t l = 0; l < n; l++)
        for (size_t r = 0; r < n; r++)
          fdT[((i * n + l) * n + r) * n + j] =
              (a->H[(i * n + l) * n + r] - b->H[(i * n + l) * n + r]) /
              (2 * FD_H);
    }
  }
  char what[96];
  snprintf(what, sizeof what, "%s f^%d: J vs differences", sc_map_type(m)->name, k);
  tu_close(what, maxdiff(v->J, fdJ, n * n), 0, FD_TOL);
  snprintf(what, sizeof what, "%s f^%d: H vs differences of J", sc_map_type(m)->name, k);
  tu_close(what, maxdiff(v->H, fdH, n * n * n), 0, FD_TOL);
  snprintf(what, sizeof what, "%s f^%d: T vs differences of H", sc_map_type(m)->name, k);
  tu_close(what, maxdiff(v->T, fdT, n * n * n * n), 0, FD_TOL);
  for (size_t q = 0; q < np; q++) {
    double p0 = sc_map_get_param(m, q), fdp[SC_DIM_TENSOR], fdJp[256];
    sc_map_set_param(m, q, p0 + FD_H, &msg);
    sc_map_iterate_n(m, x, k, SC_EVAL_DERIV2, a, &msg);
    sc_map_set_param(m, q, p0 - FD_H, &msg);
    sc_map_iterate_n(m, x, k, SC_EVAL_DERIV2, b, &msg);
    sc_map_set_param(m, q, p0, &msg);
    for (size_t i = 0; i < n; i++) fdp[i] = (a->f[i] - b->f[i]) / (2 * FD_H);
    for (size_t i = 0; i < n * n; i++) fdJp[i] = (a->J[i] - b->J[i]) / (2 * FD_H);
    snprintf(what, sizeof what, "%s f^%d: f_p%zu vs differences", sc_map_type(m)->name, k, q);
    tu_close(what, maxdiff(v->fp + q * n, fdp, n), 0, FD_TOL);
    snprintf(what, sizeof what, "%s f^%d: J_p%zu vs differences", sc_map_type(m)->name, k, q);
    tu_close(what, maxdiff(v->Jp + q * n * n, fdJp, n * n), 0, FD_TOL);
  }
out:
  sc_mapn_value_free(v);
  sc_mapn_value_free(a);
  sc_mapn_value_free(b);
}

/* ghenon's fixed point x = y = s, (1 - R) s^2 + (1 + beta) s - alpha = 0,
 * where the Jacobian has trace (R - 2) s and determinant beta - R s. */
static void check_ghenon_fixed_point(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("ghenon", NULL, &m, &msg);
  double al = 0.3, be = 0.4, R = 0.25;
  sc_map_set_param_by_name(m, "alpha", al, &msg);
  sc_map_set_param_by_name(m, "beta", be, &msg);
  sc_map_set_param_by_name(m, "R", R, &msg);
  double s = (-(1 + be) + sqrt((1 + be) * (1 + be) + 4 * (1 - R) * al)) /
             (2 * (1 - R));
  double x[2] = {s, s};
  sc_mapn_value *v;
  sc_mapn_value_alloc(m, SC_EVAL_DERIV, &v, &msg);
  tu_int("ghenon eval_n", sc_map_eval_n(m, x, SC_EVAL_DERIV, v, &msg), SC_OK);
  tu_close("ghenon fixed point x", v->f[0], s, 1e-15);
  tu_close("ghenon fixed point y", v->f[1], s, 1e-15);
  tu_close("ghenon trace", v->J[0] + v->J[3], (R - 2) * s, 1e-15);
  tu_close("ghenon determinant", v->J[0] * v->J[3] - v->J[1] * v->J[2],
           be - R * s, 1e-15);
  sc_mapn_value_free(v);
  sc_map_free(m);
}

/* A one-dimensional model read through the n-dimensional interface gives
 * the numbers of sc_map_iterate(): the same chain rule in another order,
 * so within a few rounding errors. */
static void check_1d(const char *model, double x, int k) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc(model, NULL, &m, &msg);
  sc_map_value w;
  sc_mapn_value *v;
  sc_mapn_value_alloc(m, SC_EVAL_DERIV2, &v, &msg);
  int s1 = sc_map_iterate(m, x, k, SC_EVAL_DERIV2 | SC_EVAL_ITINERARY, &w, &msg);
  int s2 = sc_map_iterate_n(m, &x, k, SC_EVAL_DERIV2 | SC_EVAL_ITINERARY, v, &msg);
  char what[96];
  snprintf(what, sizeof what, "%s f^%d both evaluate", model, k);
  tu_true(s1 == SC_OK && s2 == SC_OK, "%s: %d %d %s", what, s1, s2, msg.text);
  /* bitwise for f (the same operations), 1e-13 relative for the
   * derivatives (products taken in another order) */
  snprintf(what, sizeof what, "%s f^%d: f", model, k);
  tu_close(what, v->f[0], w.f, 0);
  snprintf(what, sizeof what, "%s f^%d: f'", model, k);
  tu_rel(what, v->J[0], w.dfdd, 1e-13);
  snprintf(what, sizeof what, "%s f^%d: f''", model, k);
  tu_rel(what, v->H[0], w.d2fdd2, 1e-13);
  snprintf(what, sizeof what, "%s f^%d: f'''", model, k);
  tu_rel(what, v->T[0], w.d3fdd3, 1e-12);
  for (size_t q = 0; q < sc_map_nparam(m); q++) {
    snprintf(what, sizeof what, "%s f^%d: df/dp%zu", model, k, q);
    tu_rel(what, v->fp[q], w.dfdp[q], 1e-13);
    snprintf(what, sizeof what, "%s f^%d: d2f/dx dp%zu", model, k, q);
    tu_rel(what, v->Jp[q], w.d2fddp[q], 1e-12);
  }
  snprintf(what, sizeof what, "%s f^%d: itinerary", model, k);
  tu_true(strcmp(v->itinerary, w.itinerary) == 0, "%s: '%s' vs '%s'", what,
          v->itinerary, w.itinerary);
  sc_mapn_value_free(v);
  sc_map_free(m);
}

static void check_refusals(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("henon", NULL, &m, &msg);
  sc_map_value w;
  tu_int("sc_map_eval on a 2-d model is refused",
         sc_map_eval(m, 0.1, 0, &w, &msg), SC_EINVAL);
  tu_true(strstr(msg.text, "2 state components") != NULL, "message: %s",
          msg.text);
  sc_mapn_value *v;
  sc_mapn_value_alloc(m, 0, &v, &msg);
  double x[2] = {0.1, NAN};
  tu_int("non-finite state refused", sc_map_eval_n(m, x, 0, v, &msg), SC_EINVAL);
  tu_true(strstr(msg.text, "y = nan") != NULL, "message names y: %s", msg.text);
  x[1] = 0.2;
  tu_int("storage without J refused for derivatives",
         sc_map_eval_n(m, x, SC_EVAL_DERIV, v, &msg), SC_EINVAL);
  /* an orbit that escapes: henon at a = 1.4 from far away overflows */
  x[0] = 1e100;
  tu_int("overflow reported", sc_map_iterate_n(m, x, 3, 0, v, &msg),
         SC_ENONFINITE);
  sc_mapn_value_free(v);

  /* scene keys holding a state */
  sc_key_info k = {"d0", SC_KEY_STATE, 0, NULL, -HUGE_VAL, HUGE_VAL, 1, 1,
                   NULL, "start"};
  tu_int("state '0.1 -0.2' accepted", sc_key_check(&k, "0.1 -0.2", m, &msg),
         SC_OK);
  tu_int("state '0.1' refused", sc_key_check(&k, "0.1", m, &msg), SC_EINVAL);
  tu_true(strstr(msg.text, "write 2 numbers (x y)") != NULL, "message: %s",
          msg.text);
  tu_int("state '0.1 zz' refused", sc_key_check(&k, "0.1 zz", m, &msg),
         SC_EINVAL);
  tu_true(strstr(msg.text, "'zz' is not a number") != NULL, "message: %s",
          msg.text);
  sc_map_free(m);
  sc_map_alloc("logistic", NULL, &m, &msg);
  tu_int("1-d state '0.1 0.2' refused", sc_key_check(&k, "0.1 0.2", m, &msg),
         SC_EINVAL);
  sc_map_free(m);
}

/* The CSV form of states, orbit points and multipliers. */
static void check_csv(void) {
  sc_map *m;
  sc_msg msg;
  char *buf;
  size_t len;
  sc_map_alloc("henon", NULL, &m, &msg);
  FILE *f = open_memstream(&buf, &len);
  double x[4] = {0.5, -0.25, 1, 2}, re[2] = {-0.5, 0.25}, im[2] = {1.5, -1.5};
  sc_csv_state_header(f, m, "start_");
  fputc('|', f);
  sc_csv_state(f, x, 2);
  fputc('|', f);
  sc_csv_points(f, x, 2, 2);
  fputc('|', f);
  sc_csv_multipliers(f, re, im, 2);
  fputc('|', f);
  sc_csv_multipliers(f, x, NULL, 2);
  fclose(f);
  tu_true(strcmp(buf, "start_x1,start_x2|0.5,-0.25|0.5 -0.25;1 2|"
                      "-0.5+1.5i 0.25-1.5i|0.5 -0.25") == 0,
          "csv text: %s", buf);
  free(buf);
  sc_map_free(m);
  sc_map_alloc("bk2", NULL, &m, &msg);
  f = open_memstream(&buf, &len);
  sc_csv_state_header(f, m, "");
  fputc('|', f);
  sc_csv_points(f, x, 3, 1);
  fclose(f);
  tu_true(strcmp(buf, "d|0.5;-0.25;1") == 0, "1-d csv text: %s", buf);
  free(buf);
  sc_map_free(m);
}

int main(void) {
  check_csv();
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("henon", NULL, &m, &msg);
  double xh[2] = {0.3, -0.1};
  for (int k = 1; k <= 4; k++) check_derivs(m, xh, k);
  sc_map_free(m);
  sc_map_alloc("ghenon", NULL, &m, &msg);
  sc_map_set_param_by_name(m, "R", 0.7, &msg);
  double xg[2] = {0.2, 0.35};
  for (int k = 1; k <= 4; k++) check_derivs(m, xg, k);
  sc_map_free(m);
  check_ghenon_fixed_point();
  check_1d("logistic", 0.3, 5);
  check_1d("cubic", 0.4, 3);
  check_1d("gpd", 0.3, 4);
  check_1d("bk2", 0.2, 3);
  check_refusals();
  return tu_finish();
}
