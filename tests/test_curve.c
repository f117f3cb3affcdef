/* Fold and flip curves and their codimension-two points, exact answers:
 * the cubic map's fold curve 27 mu1^2 = 4 mu2^3 with its cusp at the
 * origin, the gpd map's flip curve mu1 = 0 with its generalized flip at
 * the origin; sc_curve_locate() on both; a bk2 fold curve whose points
 * satisfy the defining system; bad input. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "slipcont/curve.h"
#include "test_util.h"

typedef struct {
  double worst; /* largest violation of the closed form */
  long n;
  int ncp, ngpd, ntp, nep;
  sc_curve_special cp, gpd;
  int which; /* 0 cubic, 1 gpd */
  double coef_sign_pos, coef_sign_neg;
} collect;

static int on_point(void *ctx, const sc_curve_point *p) {
  collect *c = ctx;
  double e;
  if (c->which == 0) {
    /* on the fold: mu2 = 3 x^2, mu1 = -2 x^3 */
    e = fmax(fabs(p->y - 3 * p->d * p->d), fabs(p->x + 2 * p->d * p->d * p->d));
  } else {
    /* the flip of x = 0: mu1 = 0, x = 0, coefficient mu2 */
    e = fmax(fmax(fabs(p->x), fabs(p->d)), fabs(p->coefficient - p->y));
    if (p->coefficient > 0) c->coef_sign_pos++;
    if (p->coefficient < 0) c->coef_sign_neg++;
  }
  c->worst = fmax(c->worst, e);
  c->n++;
  return 0;
}

static int on_special(void *ctx, const sc_curve_special *s) {
  collect *c = ctx;
  printf("  %s x %.17g y %.17g d %.17g coef %.3g res %.3g: %s\n", s->label,
         s->x, s->y, s->d, s->coefficient, s->residual, s->note);
  if (!strcmp(s->label, "CP")) c->ncp++, c->cp = *s;
  if (!strcmp(s->label, "GPD")) c->ngpd++, c->gpd = *s;
  if (!strcmp(s->label, "TP")) c->ntp++;
  if (!strcmp(s->label, "EP")) c->nep++;
  return 0;
}

static void test_cubic(void) {
  sc_map *m;
  sc_map_alloc("cubic", NULL, &m, NULL);
  /* start near the fold at x = 0.6385: mu2 = 3 x^2, mu1 = -2 x^3 */
  double x = 0.6385;
  sc_map_set_param(m, 0, -2 * x * x * x + 0.01, NULL);
  sc_map_set_param(m, 1, 3 * x * x, NULL);
  sc_curve_settings s;
  sc_curve_settings_default(&s);
  s.type = SC_CURVE_FOLD;
  s.ix = 0, s.iy = 1;
  s.xlo = -2, s.xhi = 2, s.ylo = -1, s.yhi = 2;
  s.h0 = 1e-2, s.hmax = 5e-2;
  collect c = {0};
  sc_curve_output out = {on_point, on_special, &c};
  sc_curve_stats st;
  sc_msg msg;
  int rc = sc_curve_trace(m, &s, x + 0.01, &out, &st, &msg);
  tu_int("cubic fold trace status", rc, SC_OK);
  tu_true(c.n >= 50, "cubic fold: %ld points", c.n);
  /* Newton to newton_ftol 1e-12 per point; the closed form's error is
   * the residual times the system's condition (~1 here) */
  tu_close("cubic fold: max |27 mu1^2 = 4 mu2^3 violation| (via x)", c.worst, 0,
           1e-12);
  tu_int("cubic fold: one cusp", c.ncp, 1);
  tu_close("cusp mu1", c.cp.x, 0, 1e-12);
  tu_close("cusp mu2", c.cp.y, 0, 1e-12);
  tu_close("cusp x", c.cp.d, 0, 1e-12);
  tu_int("cubic fold: no turning point other than the cusp", c.ntp, 0);
  tu_int("cubic fold: two ends", c.nep, 2);
  sc_map_free(m);
}

static void test_gpd(void) {
  sc_map *m;
  sc_map_alloc("gpd", NULL, &m, NULL);
  sc_map_set_param(m, 0, 0.02, NULL);
  sc_map_set_param(m, 1, 0.4385, NULL);
  sc_curve_settings s;
  sc_curve_settings_default(&s);
  s.type = SC_CURVE_FLIP;
  s.ix = 0, s.iy = 1;
  s.xlo = -1, s.xhi = 1, s.ylo = -0.7, s.yhi = 0.8;
  s.h0 = 1e-2, s.hmax = 5e-2;
  collect c = {0};
  c.which = 1;
  sc_curve_output out = {on_point, on_special, &c};
  sc_curve_stats st;
  sc_msg msg;
  int rc = sc_curve_trace(m, &s, 0.01, &out, &st, &msg);
  tu_int("gpd flip trace status", rc, SC_OK);
  tu_true(c.n >= 20, "gpd flip: %ld points", c.n);
  tu_close("gpd flip: max violation of mu1 = 0, x = 0, c = mu2", c.worst, 0,
           1e-12);
  tu_int("gpd flip: one generalized flip", c.ngpd, 1);
  tu_close("GPD mu1", c.gpd.x, 0, 1e-12);
  tu_close("GPD mu2", c.gpd.y, 0, 1e-12);
  tu_close("GPD x", c.gpd.d, 0, 1e-12);
  tu_true(c.coef_sign_pos > 0 && c.coef_sign_neg > 0,
          "coefficient positive (supercritical) for mu2 > 0 and negative "
          "beyond: %g, %g points",
          c.coef_sign_pos, c.coef_sign_neg);
  /* curve traced from mu2 = 0.4385 upwards first: c goes + to - on the
   * second branch, so the note names the change met going down */
  tu_true(strstr(c.gpd.note, "critical") != NULL, "GPD note: %s", c.gpd.note);
  sc_map_free(m);
}

/* sc_curve_locate on the cubic's cusp from a nearby guess: the
 * certificate is the residual, converged quadratically or nearly. */
typedef struct {
  sc_map *m;
} jctx;

static int cubic_jet(double x, const double *p, sc_curve_jet *j, void *u) {
  (void)u;
  j->g = x + p[0] + p[1] * x - x * x * x;
  j->gx = 1 + p[1] - 3 * x * x;
  j->gxx = -6 * x;
  j->gxxx = -6;
  j->gp[0] = 1, j->gp[1] = x;
  j->gxp[0] = 0, j->gxp[1] = 1;
  j->gxxp[0] = j->gxxp[1] = 0;
  return 0;
}

static void test_locate(void) {
  sc_curve_map1d sys = {cubic_jet, NULL, SC_CURVE_FOLD, 2, {0, 0}, {0, 1}};
  sc_curve_system cs;
  sc_msg msg;
  tu_int("map1d system", sc_curve_map1d_system(&sys, &cs, &msg), SC_OK);
  double u[3] = {0.05, 0.003, 0.02};
  sc_accuracy acc;
  sc_accuracy_preset(&acc, "default", NULL);
  sc_curve_cert cert;
  int rc = sc_curve_locate(&cs, 0, u, &acc, &cert, &msg);
  tu_int("locate CP status", rc, SC_OK);
  tu_close("CP x", u[0], 0, 1e-14);
  tu_close("CP mu1", u[1], 0, 1e-14);
  tu_close("CP mu2", u[2], 0, 1e-14);
  tu_true(cert.residual <= acc.newton_ftol && cert.iterations <= 8,
          "certificate: residual %g in %d iterations", cert.residual,
          cert.iterations);
  /* bad input */
  rc = sc_curve_locate(&cs, 7, u, &acc, &cert, &msg);
  tu_true(rc == SC_EINVAL && strstr(msg.text, "test 7"), "bad test index: %s",
          msg.text);
  sys.ifree[1] = 0;
  rc = sc_curve_map1d_system(&sys, &cs, &msg);
  tu_true(rc == SC_EINVAL && strstr(msg.text, "both free"), "equal free: %s",
          msg.text);
}

/* bk2, fig 5.8's period-6 window (driver frozen): the fold curve of f^6
 * closes on itself; each point, re-evaluated independently, satisfies
 * f^6(d) = d and (f^6)' = 1 to 1e-10; the turning points are not cusps
 * (coefficient far from 0) and the curve has no cusp. */
typedef struct {
  sc_map *m;
  double worst;
  long n;
  int ntp, ncp;
  double tp_min_coef;
  double tp[8][2]; /* alpha, beta of the turning points */
} bk2c;

static int bk2_point(void *ctx, const sc_curve_point *p) {
  bk2c *c = ctx;
  sc_map *m2;
  sc_map_clone(c->m, &m2, NULL);
  sc_map_set_param_by_name(m2, "alpha", p->x, NULL);
  sc_map_set_param_by_name(m2, "beta", p->y, NULL);
  sc_map_value v;
  if (sc_map_iterate(m2, p->d, 6, SC_EVAL_DERIV, &v, NULL) == SC_OK)
    c->worst = fmax(c->worst, fmax(fabs(v.f - p->d), fabs(v.dfdd - 1)));
  else
    c->worst = HUGE_VAL;
  sc_map_free(m2);
  c->n++;
  return 0;
}

static int bk2_special(void *ctx, const sc_curve_special *s) {
  bk2c *c = ctx;
  printf("  %s alpha %.17g beta %.17g d %.17g coef %.6g res %.3g: %s\n",
         s->label, s->x, s->y, s->d, s->coefficient, s->residual, s->note);
  if (!strcmp(s->label, "TP")) {
    if (c->ntp < 8) c->tp[c->ntp][0] = s->x, c->tp[c->ntp][1] = s->y;
    c->ntp++;
    c->tp_min_coef = fmin(c->tp_min_coef, fabs(s->coefficient));
    tu_true(s->residual <= 1e-10, "TP residual %g <= 1e-10", s->residual);
  }
  if (!strcmp(s->label, "CP")) c->ncp++;
  return 0;
}

static void trace_bk2_period6(int multiple, bk2c *c, sc_curve_stats *st) {
  sc_map *m;
  sc_map_alloc("bk2", NULL, &m, NULL);
  sc_map_set_option(m, "driver", "frozen", NULL);
  sc_map_set_param_by_name(m, "alpha", 3.2196, NULL);
  sc_map_set_param_by_name(m, "beta", 2.5, NULL);
  sc_curve_settings s;
  sc_curve_settings_default(&s);
  s.period = 6;
  s.multiple = multiple;
  s.ix = 0, s.iy = 1;
  s.xlo = 2, s.xhi = 4.5, s.ylo = 1.5, s.yhi = 4;
  s.hmax = 0.05, s.h0 = 0.005;
  memset(c, 0, sizeof *c);
  c->m = m;
  c->tp_min_coef = HUGE_VAL;
  sc_curve_output out = {bk2_point, bk2_special, c};
  sc_msg msg;
  int rc = sc_curve_trace(m, &s, 0.10512, &out, st, &msg);
  tu_int(multiple ? "bk2 period 6, multiple shooting: status"
                  : "bk2 period 6, single shooting: status",
         rc, SC_OK);
  sc_map_free(m);
}

/* Multiple shooting traces the same closed curve: same turning points
 * (each located to the residual tolerance 1e-11 of two differently
 * conditioned systems: 1e-10 in the parameters), no cusp. */
static void test_bk2_multiple(void) {
  bk2c c1, c2;
  sc_curve_stats s1, s2;
  trace_bk2_period6(0, &c1, &s1);
  trace_bk2_period6(1, &c2, &s2);
  tu_true(s2.closed, "multiple shooting: the curve closes (%ld points)", c2.n);
  tu_close("multiple shooting: worst residual of f^6's system", c2.worst, 0,
           1e-10);
  tu_int("multiple shooting: as many turning points", c2.ntp, c1.ntp);
  tu_int("multiple shooting: no cusp", c2.ncp, 0);
  double worst = 0;
  for (int i = 0; i < c1.ntp && i < c2.ntp && i < 8; i++) {
    double best = HUGE_VAL;
    for (int k = 0; k < c2.ntp && k < 8; k++)
      best = fmin(best, fmax(fabs(c1.tp[i][0] - c2.tp[k][0]),
                             fabs(c1.tp[i][1] - c2.tp[k][1])));
    worst = fmax(worst, best);
  }
  tu_close("multiple vs single shooting: turning points (max |diff|)", worst, 0,
           1e-10);
}

static void test_bk2_period6(void) {
  sc_map *m;
  sc_map_alloc("bk2", NULL, &m, NULL);
  sc_map_set_option(m, "driver", "frozen", NULL);
  sc_map_set_param_by_name(m, "alpha", 3.2196, NULL);
  sc_map_set_param_by_name(m, "beta", 2.5, NULL);
  sc_curve_settings s;
  sc_curve_settings_default(&s);
  s.period = 6;
  s.ix = 0, s.iy = 1;
  s.xlo = 2, s.xhi = 4.5, s.ylo = 1.5, s.yhi = 4;
  s.hmax = 0.05, s.h0 = 0.005;
  bk2c c = {0};
  c.m = m;
  c.tp_min_coef = HUGE_VAL;
  sc_curve_output out = {bk2_point, bk2_special, &c};
  sc_curve_stats st;
  sc_msg msg;
  int rc = sc_curve_trace(m, &s, 0.10512, &out, &st, &msg);
  tu_int("bk2 period-6 fold curve status", rc, SC_OK);
  tu_true(st.closed, "the period-6 fold curve closes (%ld points)", c.n);
  tu_true(c.n >= 100, "at least 100 points (%ld)", c.n);
  tu_close("bk2 fold curve: worst |f^6(d) - d|, |(f^6)' - 1|", c.worst, 0,
           1e-10);
  tu_true(c.ntp >= 2, "turning points located: %d", c.ntp);
  /* the quadratic coefficient at the turning points is O(100): no cusp */
  tu_true(c.tp_min_coef > 1, "TP coefficients far from 0 (min %g)",
          c.tp_min_coef);
  tu_int("no cusp on the period-6 fold curve", c.ncp, 0);
  /* the start is the fold of the branch task (docs/branches.md) */
  sc_map_free(m);
}

/* The multiple-shooting Jacobian: its sparse (CSC) form holds exactly the
 * dense one's nonzeros, and both match differences of F (cubic map, u =
 * (x_0, x_1, x_2, mu1, mu2), periods 1 to 3). */
static void test_ms_jacobian(void) {
  for (size_t m = 1; m <= 3; m++) {
    sc_curve_ms_work *w;
    sc_curve_ms_work_alloc(m, &w, NULL);
    sc_curve_map1d_ms sys = {cubic_jet,     cubic_jet, NULL, NULL,
                             SC_CURVE_FLIP, m,         2,    {0, 0},
                             {0, 1},        w};
    sc_curve_system cs;
    sc_cont_problem sp;
    sc_msg msg;
    int rc = sc_curve_map1d_ms_system(&sys, &cs, &msg);
    rc |= sc_curve_map1d_ms_sparse(&sys, &sp, &msg);
    tu_int("ms systems built", rc, SC_OK);
    size_t n = m + 1, N = m + 2;
    double u[5] = {0.3385, -0.2385, 0.41, 0.1385, 0.7385}, J[20], Js[20], F1[4],
           F2[4];
    u[m] = 0.1385, u[m + 1] = 0.7385;
    cs.pb.jac(u, J, cs.pb.user);
    sp.jac(u, Js, sp.user);
    double worst_s = 0, worst_d = 0;
    int nnz = sp.jac_colptr[N], inpattern = 0;
    for (size_t j = 0; j < N; j++) {
      for (int k = sp.jac_colptr[j]; k < sp.jac_colptr[j + 1]; k++)
        worst_s = fmax(worst_s, fabs(Js[k] - J[sp.jac_rowind[k] * N + j]));
      double h = 1e-6, up[5], um[5];
      memcpy(up, u, sizeof u);
      memcpy(um, u, sizeof u);
      up[j] += h, um[j] -= h;
      cs.pb.f(up, F1, cs.pb.user);
      cs.pb.f(um, F2, cs.pb.user);
      for (size_t i = 0; i < n; i++) {
        double diff = (F1[i] - F2[i]) / (2 * h);
        worst_d = fmax(worst_d, fabs(diff - J[i * N + j]));
        if (J[i * N + j] != 0) {
          int found = 0;
          for (int k = sp.jac_colptr[j]; k < sp.jac_colptr[j + 1]; k++)
            found |= (size_t)sp.jac_rowind[k] == i;
          inpattern += found;
        }
      }
    }
    int nonzero = 0;
    for (size_t i = 0; i < n * N; i++)
      nonzero += J[i] != 0;
    tu_close("ms: sparse entries = dense entries", worst_s, 0, 0);
    tu_true(inpattern == nonzero && nnz >= nonzero,
            "ms period %zu: all %d nonzeros in the pattern (%d entries)", m,
            nonzero, nnz);
    /* central differences, h = 1e-6 on a cubic: error ~ h^2 */
    tu_close("ms: Jacobian vs differences of F", worst_d, 0, 1e-9);
    sc_curve_ms_work_free(w);
  }
}

int main(void) {
  test_ms_jacobian();
  test_locate();
  test_bk2_period6();
  test_bk2_multiple();
  test_cubic();
  test_gpd();
  return tu_finish();
}
