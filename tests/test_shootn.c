/* Shooting in n dimensions (sc_shootn): the Henon map's fixed points and
 * period-2 orbit and the generalized Henon map's fixed points against
 * their closed forms, with their multipliers; single and multiple
 * shooting, dense and KLU, give one answer; deflation keeps Newton away
 * from a known orbit; the one-dimensional logistic map agrees with
 * sc_shoot; failures come with their reason; the n-dimensional orbit
 * rules (common.h). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/shooting.h"
#include "test_util.h"

/* Newton converges quadratically to the tolerances of
 * sc_map_solver_accuracy() (1e-12 and below); the closed forms are
 * evaluated in double with errors of a few ulps: 1e-12 bounds both. */
static const double TOL = 1e-12;

static sc_map *henon(double a, double b) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("henon", NULL, &m, &msg);
  sc_map_set_param_by_name(m, "a", a, &msg);
  sc_map_set_param_by_name(m, "b", b, &msg);
  return m;
}

/* Roots of z^2 - t z + d = 0 by decreasing modulus (re, im). */
static void quad_roots(double t, double d, double *re, double *im) {
  double disc = t * t - 4 * d;
  if (disc >= 0) {
    double r1 = 0.5 * (t + sqrt(disc)), r2 = 0.5 * (t - sqrt(disc));
    if (fabs(r2) > fabs(r1)) {
      double x = r1;
      r1 = r2;
      r2 = x;
    }
    re[0] = r1, re[1] = r2, im[0] = im[1] = 0;
  } else {
    re[0] = re[1] = 0.5 * t;
    im[0] = 0.5 * sqrt(-disc);
    im[1] = -im[0];
  }
}

static void check_mults(const char *what, const sc_shootn *s,
                        const double *re, const double *im) {
  const double *r, *i;
  sc_shootn_multipliers(s, &r, &i);
  char w[160];
  for (int k = 0; k < 2; k++) {
    snprintf(w, sizeof w, "%s: multiplier %d real part", what, k + 1);
    tu_close(w, r[k], re[k], TOL);
    snprintf(w, sizeof w, "%s: multiplier %d imaginary part", what, k + 1);
    tu_close(w, i[k], im[k], TOL);
  }
}

/* Henon fixed points x = (-(1 - b) +- sqrt((1 - b)^2 + 4 a)) / (2 a),
 * y = b x; Jacobian [[-2 a x, 1], [b, 0]]: trace -2 a x, det -b. */
static void henon_fixed(sc_shoot_method meth, const sc_linsolve_type *ls) {
  const double a = 1.4, b = 0.3;
  sc_map *m = henon(a, b);
  sc_shootn *s;
  sc_msg msg;
  if (!tu_true(sc_shootn_alloc(m, 1, meth, ls, &s, &msg) == SC_OK, "alloc: %s",
               msg.text))
    return;
  for (int sign = -1; sign <= 1; sign += 2) {
    double x = (-(1 - b) + sign * sqrt((1 - b) * (1 - b) + 4 * a)) / (2 * a);
    double x0[2] = {x + 0.05, b * x - 0.03};
    sc_shootn_result res;
    int st = sc_shootn_solve(s, x0, &res, &msg);
    char w[120];
    snprintf(w, sizeof w, "henon fixed point %+d (%s)", sign,
             meth == SC_SHOOT_SINGLE ? "single" : "multiple");
    if (!tu_true(st == SC_OK, "%s: %s", w, msg.text)) continue;
    const double *o = sc_shootn_orbit(s);
    tu_close(w, o[0], x, TOL);
    tu_close(w, o[1], b * x, TOL);
    tu_true(res.residual <= TOL, "%s: residual %g", w, res.residual);
    tu_true(res.reason == SC_SHOOTN_CONVERGED, "%s: reason", w);
    double re[2], im[2];
    quad_roots(-2 * a * x, -b, re, im);
    check_mults(w, s, re, im);
    tu_int(w, res.stable, 0); /* both are saddles at a = 1.4 */
    tu_close(w, res.multiplier, re[0], TOL);
  }
  sc_shootn_free(s);
  sc_map_free(m);
}

/* Henon period 2: x1 + x2 = (1 - b) / a, x1 x2 = ((1 - b)^2 - a) / a^2
 * (from (1 - b) x2 = 1 - a x1^2 and (1 - b) x1 = 1 - a x2^2), so
 * x = ((1 - b) +- sqrt(4 a - 3 (1 - b)^2)) / (2 a), real for
 * a > 3 (1 - b)^2 / 4; y1 = b x2, y2 = b x1.  The product of the
 * Jacobians has trace 4 a^2 x1 x2 + 2 b and determinant b^2. */
static void henon_period2(sc_shoot_method meth, const sc_linsolve_type *ls) {
  const double a = 1.4, b = 0.3;
  sc_map *m = henon(a, b);
  sc_shootn *s;
  sc_msg msg;
  sc_shootn_alloc(m, 2, meth, ls, &s, &msg);
  double r = sqrt(4 * a - 3 * (1 - b) * (1 - b));
  double x1 = ((1 - b) + r) / (2 * a), x2 = ((1 - b) - r) / (2 * a);
  double x0[2] = {x1 - 0.02, b * x2 + 0.02};
  sc_shootn_result res;
  char w[120];
  snprintf(w, sizeof w, "henon period 2 (%s, %s)",
           meth == SC_SHOOT_SINGLE ? "single" : "multiple",
           ls ? sc_linsolve_type_name(ls) : "auto");
  if (tu_true(sc_shootn_solve(s, x0, &res, &msg) == SC_OK, "%s: %s", w,
              msg.text)) {
    const double *o = sc_shootn_orbit(s);
    tu_close(w, o[0], x1, TOL);
    tu_close(w, o[1], b * x2, TOL);
    tu_close(w, o[2], x2, TOL);
    tu_close(w, o[3], b * x1, TOL);
    double re[2], im[2];
    quad_roots(4 * a * a * x1 * x2 + 2 * b, b * b, re, im);
    check_mults(w, s, re, im);
  }
  sc_shootn_free(s);
  sc_map_free(m);
}

/* ghenon fixed points x = y = s, (1 - R) s^2 + (1 + beta) s - alpha = 0;
 * multipliers from trace (R - 2) s and determinant beta - R s.  At
 * alpha = 0.3, beta = 0.6, R = 0.4 the smaller root has a complex pair. */
static void ghenon_fixed(void) {
  const double al = 0.3, be = 0.6, R = 0.4;
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("ghenon", NULL, &m, &msg);
  sc_map_set_param_by_name(m, "alpha", al, &msg);
  sc_map_set_param_by_name(m, "beta", be, &msg);
  sc_map_set_param_by_name(m, "R", R, &msg);
  double A = 1 - R, B = 1 + be, disc = sqrt(B * B + 4 * A * al);
  double roots[2] = {(-B + disc) / (2 * A), (-B - disc) / (2 * A)};
  for (int meth = SC_SHOOT_SINGLE; meth <= SC_SHOOT_MULTIPLE; meth++) {
    sc_shootn *s;
    sc_shootn_alloc(m, 1, (sc_shoot_method)meth, NULL, &s, &msg);
    for (int k = 0; k < 2; k++) {
      double sv = roots[k], x0[2] = {sv + 0.03, sv - 0.02};
      sc_shootn_result res;
      char w[120];
      snprintf(w, sizeof w, "ghenon fixed point s = %.6f (method %d)", sv,
               meth);
      if (!tu_true(sc_shootn_solve(s, x0, &res, &msg) == SC_OK, "%s: %s", w,
                   msg.text))
        continue;
      const double *o = sc_shootn_orbit(s);
      tu_close(w, o[0], sv, TOL);
      tu_close(w, o[1], sv, TOL);
      double re[2], im[2];
      quad_roots((R - 2) * sv, be - R * sv, re, im);
      check_mults(w, s, re, im);
      tu_int(w, res.stable, hypot(re[0], im[0]) < 1);
      if (k == 0) tu_true(im[0] > 0, "%s: the test wants a complex pair", w);
    }
    sc_shootn_free(s);
  }
  sc_map_free(m);
}

/* Deflation: once the fixed point near the guess is deflated, Newton
 * from the same guess does not return to it. */
static void deflation(void) {
  const double a = 1.4, b = 0.3;
  sc_map *m = henon(a, b);
  sc_msg msg;
  for (int meth = SC_SHOOT_SINGLE; meth <= SC_SHOOT_MULTIPLE; meth++) {
    sc_shootn *s;
    sc_shootn_alloc(m, 1, (sc_shoot_method)meth, NULL, &s, &msg);
    double x0[2] = {0.7, 0.2};
    sc_shootn_result res;
    sc_shootn_solve(s, x0, &res, &msg);
    double known[2];
    memcpy(known, sc_shootn_orbit(s), sizeof known);
    tu_int("deflate: a divisor of the period only",
           sc_shootn_deflate(s, known, 2, 1, &msg), SC_EINVAL);
    tu_int("deflate: scale > 0", sc_shootn_deflate(s, known, 1, 0, &msg),
           SC_EINVAL);
    sc_shootn_deflate(s, known, 1, 1, &msg);
    int st = sc_shootn_solve(s, x0, &res, &msg);
    const double *o = sc_shootn_orbit(s);
    double other = (-(1 - b) - sqrt((1 - b) * (1 - b) + 4 * a)) / (2 * a);
    if (tu_true(st == SC_OK, "deflated solve (method %d): %s", meth,
                msg.text))
      tu_close("deflated: the other fixed point", o[0], other, TOL);
    /* deflating both: no root is left, Newton fails with a reason */
    sc_shootn_deflate(s, o, 1, 1, &msg);
    st = sc_shootn_solve(s, x0, &res, &msg);
    tu_true(st != SC_OK && res.reason != SC_SHOOTN_CONVERGED,
            "both deflated (method %d): fails (%d, %s)", meth, st,
            sc_shootn_reason_text(res.reason));
    sc_shootn_deflate_clear(s);
    st = sc_shootn_solve(s, x0, &res, &msg);
    tu_close("cleared: the first fixed point again", sc_shootn_orbit(s)[0],
             known[0], TOL);
    sc_shootn_free(s);
  }
  sc_map_free(m);
}

/* The logistic map (n = 1) through the n-dimensional shooting agrees with
 * the one-dimensional sc_shoot on its period-2 orbit. */
static void logistic_agrees(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("logistic", NULL, &m, &msg);
  sc_map_set_param_by_name(m, "r", 3.3, &msg);
  sc_shoot *s1;
  sc_shootn *sn;
  sc_shoot_alloc(m, 2, SC_SHOOT_SINGLE, NULL, &s1, &msg);
  sc_shootn_alloc(m, 2, SC_SHOOT_SINGLE, NULL, &sn, &msg);
  sc_shoot_result r1;
  sc_shootn_result rn;
  double x0 = 0.5;
  sc_shoot_solve(s1, x0, &r1, &msg);
  if (tu_true(sc_shootn_solve(sn, &x0, &rn, &msg) == SC_OK, "logistic: %s",
              msg.text)) {
    tu_close("logistic period 2: n-dim vs 1-d point", sc_shootn_orbit(sn)[0],
             r1.d, TOL);
    tu_close("logistic period 2: n-dim vs 1-d multiplier", rn.multiplier,
             r1.multiplier, TOL);
  }
  sc_shoot_free(s1);
  sc_shootn_free(sn);
  sc_map_free(m);
}

/* A long stable orbit: the period-7 window of Henon at a = 1.23, b = 0.3 (from 1.227 to
 * about 1.259 the attractor is a period-7 orbit);
 * multiple shooting with KLU and dense agree with single shooting. */
static void long_orbit(void) {
  sc_map *m = henon(1.23, 0.3);
  sc_msg msg;
  sc_mapn_value *v;
  sc_mapn_value_alloc(m, SC_EVAL_VALUE, &v, &msg);
  double x[2] = {0.1, 0.1};
  for (int i = 0; i < 5000; i++) { /* onto the attractor */
    sc_map_eval_n(m, x, SC_EVAL_VALUE, v, &msg);
    memcpy(x, v->f, sizeof x);
  }
  const sc_linsolve_type *lss[3] = {NULL, sc_linsolve_dense, sc_linsolve_klu};
  double first[2] = {0, 0};
  for (int k = 0; k < 3; k++) {
    sc_shootn *s;
    sc_shootn_alloc(m, 7, k ? SC_SHOOT_MULTIPLE : SC_SHOOT_SINGLE, lss[k], &s,
                    &msg);
    sc_shootn_result res;
    if (!tu_true(sc_shootn_solve(s, x, &res, &msg) == SC_OK,
                 "period 7 (%d): %s", k, msg.text)) {
      sc_shootn_free(s);
      continue;
    }
    const double *o = sc_shootn_orbit(s);
    tu_int("period 7: minimal", sc_orbit_minimal_period_n(o, 7, 2, 1e-8), 7);
    tu_int("period 7: stable", res.stable, 1);
    /* det J = -b at every point: the multipliers' product is (-b)^7 */
    const double *re, *im;
    sc_shootn_multipliers(s, &re, &im);
    tu_rel("period 7: mu1 mu2 = (-b)^7",
           re[0] * re[1] - im[0] * im[1], pow(-0.3, 7), 1e-12);
    if (k == 0) memcpy(first, o, sizeof first);
    else {
      tu_close("period 7: x agrees across methods", o[0], first[0], TOL);
      tu_close("period 7: y agrees across methods", o[1], first[1], TOL);
    }
    sc_shootn_free(s);
  }
  sc_mapn_value_free(v);
  sc_map_free(m);
}

/* The period-7 orbit solved as a period-70 one: its multipliers are
 * those of period 7 to the tenth power, their product (-b)^70 = 2.5e-37
 * while the larger one is about 1e-3: forming the product of the 70
 * Jacobians would leave the smaller one at its rounding (DBL_EPSILON
 * times the larger); the periodic Schur decomposition keeps it to a
 * relative 1e-12 (70 factors of rounding). */
static void wide_multipliers(void) {
  sc_map *m = henon(1.23, 0.3);
  sc_msg msg;
  double x[2] = {0.1, 0.1};
  sc_shootn *s7, *s70;
  sc_shootn_alloc(m, 7, SC_SHOOT_SINGLE, NULL, &s7, &msg);
  sc_shootn_alloc(m, 70, SC_SHOOT_MULTIPLE, sc_linsolve_klu, &s70, &msg);
  sc_mapn_value *v;
  sc_mapn_value_alloc(m, SC_EVAL_VALUE, &v, &msg);
  for (int i = 0; i < 5000; i++) {
    sc_map_eval_n(m, x, SC_EVAL_VALUE, v, &msg);
    memcpy(x, v->f, sizeof x);
  }
  sc_shootn_result r7, r70;
  if (tu_true(sc_shootn_solve(s7, x, &r7, &msg) == SC_OK, "period 7: %s",
              msg.text) &&
      tu_true(sc_shootn_solve(s70, x, &r70, &msg) == SC_OK, "period 70: %s",
              msg.text)) {
    const double *re7, *im7, *re70, *im70;
    sc_shootn_multipliers(s7, &re7, &im7);
    sc_shootn_multipliers(s70, &re70, &im70);
    tu_true(im7[0] == 0, "period 7: real multipliers");
    tu_rel("period 70: mu1 mu2 = (-b)^70", re70[0] * re70[1], pow(0.3, 70),
           1e-12);
    tu_rel("period 70: mu2 = mu2(7)^10", re70[1], pow(re7[1], 10), 1e-12);
    tu_rel("period 70: mu1 = mu1(7)^10", re70[0], pow(re7[0], 10), 1e-12);
  }
  sc_mapn_value_free(v);
  sc_shootn_free(s7);
  sc_shootn_free(s70);
  sc_map_free(m);
}

static void failures(void) {
  sc_map *m = henon(1.4, 0.3);
  sc_msg msg;
  sc_shootn *s = NULL;
  tu_int("period 0 refused",
         sc_shootn_alloc(m, 0, SC_SHOOT_SINGLE, NULL, &s, &msg), SC_EINVAL);
  tu_int("method refused", sc_shootn_alloc(m, 1, 7, NULL, &s, &msg),
         SC_EINVAL);
  sc_shootn_alloc(m, 12, SC_SHOOT_SINGLE, NULL, &s, &msg);
  sc_shootn_result res;
  double far[2] = {1e10, 0}, nan2[2] = {NAN, 0};
  int st = sc_shootn_solve(s, far, &res, &msg);
  tu_true(st == SC_ENONFINITE && res.reason == SC_SHOOTN_UNDEFINED,
          "escape to infinity: status %d, reason %s", st,
          sc_shootn_reason_text(res.reason));
  tu_int("non-finite guess", sc_shootn_solve(s, nan2, &res, &msg), SC_EINVAL);
  sc_shootn_free(s);
  /* Period 128 in chaos: ||J_g|| ~ 1e23, J_g - I singular in rounding;
   * single shooting must not call a point with f^128(x) - x of order 1
   * an orbit (its tolerance grows with ||J_g|| only up to 1/sqrt(eps)). */
  sc_shootn_alloc(m, 128, SC_SHOOT_SINGLE, NULL, &s, &msg);
  double x[2] = {0.1, 0.1};
  sc_mapn_value *v;
  sc_mapn_value_alloc(m, SC_EVAL_VALUE, &v, &msg);
  for (int i = 0; i < 1000; i++) {
    sc_map_eval_n(m, x, SC_EVAL_VALUE, v, &msg);
    memcpy(x, v->f, sizeof x);
  }
  st = sc_shootn_solve(s, x, &res, &msg);
  tu_true(st != SC_OK || res.residual <= 1e-4,
          "period 128 in chaos: no orbit claimed without a certificate "
          "(status %d, residual %g)",
          st, res.residual);
  sc_mapn_value_free(v);
  sc_shootn_free(s);
  sc_map_free(m);
}

/* The n-dimensional orbit rules: a period-2 orbit written twice has
 * minimal period 2; a rotation is the same orbit; a change beyond the
 * tolerance is not. */
static void orbit_rules(void) {
  double a[8] = {1, 2, 3, 4, 1, 2, 3, 4}, b[4] = {3, 4, 1, 2};
  tu_int("minimal period n", sc_orbit_minimal_period_n(a, 4, 2, 1e-9), 2);
  tu_int("rotation is the same orbit", sc_orbit_same_n(a, b, 2, 2, 1e-9), 1);
  b[1] += 1e-6;
  tu_int("a component off is another orbit",
         sc_orbit_same_n(a, b, 2, 2, 1e-9), 0);
  a[5] += 1e-6;
  tu_int("second component decides the period",
         sc_orbit_minimal_period_n(a, 4, 2, 1e-9), 4);
}

int main(void) {
  henon_fixed(SC_SHOOT_SINGLE, NULL);
  henon_fixed(SC_SHOOT_MULTIPLE, NULL);
  henon_period2(SC_SHOOT_SINGLE, NULL);
  henon_period2(SC_SHOOT_MULTIPLE, sc_linsolve_dense);
  henon_period2(SC_SHOOT_MULTIPLE, sc_linsolve_klu);
  ghenon_fixed();
  deflation();
  logistic_agrees();
  long_orbit();
  wide_multipliers();
  failures();
  orbit_rules();
  return tu_finish();
}
