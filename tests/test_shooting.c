/* Shooting for periodic orbits (shooting.h).
 *
 * - Logistic map x -> r x (1 - x) at r = 3.9 (chaotic): the unstable
 *   fixed point 1 - 1/r, the unstable 2-cycle
 *   (r + 1 -+ sqrt((r + 1)(r - 3)))/(2r) with multiplier 4 + 2r - r^2,
 *   and orbits of periods 3, 4, 5, 7, 8 from points of the attractor, each checked
 *   against an independent long double evaluation; single shooting,
 *   multiple shooting with the dense and the KLU backend: same answers.
 * - bk2, driver moving, alpha = 2.9, beta = 1, phi = 1.25, V = 0.019
 *   (the chaotic attractor of the symmetric v-cascade): unstable orbits
 *   of periods 2..32 by multiple shooting from near returns of the
 *   attractor, verified by evaluating d_(i+1) - f(d_i) again; seeds where
 *   multiple shooting converges and single shooting does not.  At
 *   V = 0.019 the attractor is only mildly unstable (multipliers of the
 *   period-32 orbits up to ~2e2); at V = 0.0175, still chaotic before the
 *   jump to single-block slips near 0.017, period-32 orbits with
 *   multipliers above 1e6 converge.
 * - Neutral orbits (V = 0.0165: a period-2 orbit of single-block slips)
 *   are SC_ENEUTRAL with a message saying the orbit lies in a family.
 * - Error paths.
 *
 * Tolerances: the "default" accuracy stops Newton with steps within
 * 1e-13 (1 + |d|) and residuals within 1e-13; Newton's last step being
 * quadratic, the orbits are exact to the rounding of f (a few 1e-17 for
 * |d| ~ 0.05, a few 1e-16 for the logistic map), amplified for a single
 * point by at most 1/|1 - multiplier|.  The assertions below use 1e-14
 * (the aim of the brief) where the answer is exact. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/shooting.h"
#include "test_util.h"

static sc_map *logistic(double r) {
  sc_map *m = NULL;
  sc_msg msg = {""};
  sc_map_alloc("logistic", NULL, &m, &msg);
  sc_map_set_param_by_name(m, "r", r, &msg);
  return m;
}

/* |f^p(x) - x| in long double, and the long double multiplier. */
static long double logistic_check(long double x, long double r, int p,
                                  long double *mult) {
  long double y = x, d = 1;
  for (int k = 0; k < p; k++) {
    d *= r * (1 - 2 * y);
    y = r * y * (1 - y);
  }
  *mult = d;
  return fabsl(y - x);
}

/* Smallest period q dividing p with d_(i+q) = d_i for all i. */
static int min_period(const double *d, int p) {
  for (int q = 1; q < p; q++) {
    if (p % q) continue;
    int same = 1;
    for (int i = 0; i + q < p && same; i++)
      if (fabs(d[i + q] - d[i]) > 1e-10) same = 0;
    if (same) return q;
  }
  return p;
}

static const char *method_name(sc_shoot_method me, const sc_linsolve_type *t) {
  if (me == SC_SHOOT_SINGLE) return "single";
  return t == sc_linsolve_klu ? "multiple/klu" : "multiple/dense";
}

static void test_logistic(void) {
  printf("--- logistic map, r = 3.9\n");
  const double r = 3.9;
  sc_map *m = logistic(r);
  sc_msg msg = {""};
  struct {
    sc_shoot_method me;
    const sc_linsolve_type *ls;
  } how[3] = {{SC_SHOOT_SINGLE, NULL},
              {SC_SHOOT_MULTIPLE, NULL},
              {SC_SHOOT_MULTIPLE, NULL}};
  how[1].ls = sc_linsolve_dense;
  how[2].ls = sc_linsolve_klu;
  /* Period 1 and 2: closed forms. */
  double x2lo = (r + 1 - sqrt((r + 1) * (r - 3))) / (2 * r);
  double x2hi = (r + 1 + sqrt((r + 1) * (r - 3))) / (2 * r);
  for (int k = 0; k < 3; k++) {
    sc_shoot *s = NULL;
    sc_shoot_result res;
    int st = sc_shoot_alloc(m, 1, how[k].me, how[k].ls, &s, &msg);
    st = st ? st : sc_shoot_solve(s, 0.7, &res, &msg);
    char what[128];
    snprintf(what, sizeof what, "fixed point (%s): status",
             method_name(how[k].me, how[k].ls));
    tu_int(what, st, SC_OK);
    snprintf(what, sizeof what, "fixed point (%s) = 1 - 1/r",
             method_name(how[k].me, how[k].ls));
    tu_close(what, res.d, 1 - 1 / r, 1e-14);
    snprintf(what, sizeof what, "fixed point (%s) multiplier 2 - r",
             method_name(how[k].me, how[k].ls));
    tu_close(what, res.multiplier, 2 - r, 1e-13);
    sc_shoot_free(s);

    st = sc_shoot_alloc(m, 2, how[k].me, how[k].ls, &s, &msg);
    st = st ? st : sc_shoot_solve(s, 0.3, &res, &msg);
    snprintf(what, sizeof what, "2-cycle (%s): status",
             method_name(how[k].me, how[k].ls));
    tu_int(what, st, SC_OK);
    const double *o = sc_shoot_orbit(s);
    double lo = fmin(o[0], o[1]), hi = fmax(o[0], o[1]);
    snprintf(what, sizeof what, "2-cycle (%s): low point",
             method_name(how[k].me, how[k].ls));
    tu_close(what, lo, x2lo, 1e-14);
    snprintf(what, sizeof what, "2-cycle (%s): high point",
             method_name(how[k].me, how[k].ls));
    tu_close(what, hi, x2hi, 1e-14);
    snprintf(what, sizeof what, "2-cycle (%s): multiplier 4 + 2r - r^2",
             method_name(how[k].me, how[k].ls));
    tu_close(what, res.multiplier, 4 + 2 * r - r * r, 1e-12);
    tu_true(!res.stable, "2-cycle (%s) unstable",
            method_name(how[k].me, how[k].ls));
    sc_shoot_free(s);
  }
  /* Periods 3..8 (no near return of the first 4000 iterates converges to
   * a genuine 6-cycle) from near returns of the chaotic orbit. */
  double x[4000];
  x[0] = 0.3;
  sc_map_value v;
  for (int k = 1; k < 4000; k++) {
    sc_map_eval(m, x[k - 1], SC_EVAL_VALUE, &v, &msg);
    x[k] = v.f;
  }
  const int plist[] = {3, 4, 5, 7, 8};
  for (int ip = 0; ip < 5; ip++) {
    int p = plist[ip], found = 0;
    for (int k = 100; k + p < 4000 && !found; k++) {
      if (fabs(x[k + p] - x[k]) > 1e-3) continue;
      sc_shoot *sd, *sk;
      sc_shoot_result rd, rk;
      sc_shoot_alloc(m, p, SC_SHOOT_MULTIPLE, sc_linsolve_dense, &sd, &msg);
      sc_shoot_alloc(m, p, SC_SHOOT_MULTIPLE, sc_linsolve_klu, &sk, &msg);
      int a = sc_shoot_solve_orbit(sd, x + k, &rd, &msg);
      int b = sc_shoot_solve_orbit(sk, x + k, &rk, &msg);
      if (a == SC_OK && b == SC_OK && min_period(sc_shoot_orbit(sd), p) == p) {
        found = 1;
        long double mult;
        long double err = logistic_check(rd.d, r, p, &mult);
        printf("  period %d from x[%d]: d = %.17g, multiplier %.6g, %d "
               "iterations\n",
               p, k, rd.d, rd.multiplier, rd.iterations);
        /* x in [0, 1], f' <= r: f^p(x) - x carries the rounding of the
         * double x (1.1e-16) times |1 - multiplier|. */
        tu_true((double)err <= 1e-14 * fabs(1 - (double)mult) + 1e-15,
                "period %d: |f^%d(d) - d| = %.3Lg in long double (tol "
                "1e-14 |1 - multiplier|)",
                p, p, err);
        tu_rel("period multiplier against long double", rd.multiplier,
               (double)mult, 1e-12);
        /* Dense and KLU solve the same cyclic system: the same orbit to
         * rounding in the LU factors (a few ulps of d). */
        double dmax = 0;
        for (int i = 0; i < p; i++)
          dmax = fmax(dmax, fabs(sc_shoot_orbit(sd)[i] -
                                 sc_shoot_orbit(sk)[i]));
        tu_close("dense and KLU orbits agree", dmax, 0, 1e-15);
      }
      sc_shoot_free(sd);
      sc_shoot_free(sk);
    }
    tu_true(found, "an orbit of minimal period %d from a near return", p);
  }
  sc_map_free(m);
}

static sc_map *bk2_moving(double v) {
  sc_map *m = NULL;
  sc_msg msg = {""};
  sc_map_alloc("bk2", NULL, &m, &msg);
  sc_map_set_option(m, "driver", "moving", &msg);
  sc_map_set_param_by_name(m, "alpha", 2.9, &msg);
  sc_map_set_param_by_name(m, "beta", 1, &msg);
  sc_map_set_param_by_name(m, "phi", 1.25, &msg);
  sc_map_set_param_by_name(m, "v", v, &msg);
  return m;
}

/* Max over the orbit of |d_(i+1) - f(d_i)|, evaluated afresh. */
static double orbit_defect(sc_map *m, const double *d, int p) {
  double e = 0;
  sc_map_value v;
  for (int i = 0; i < p; i++) {
    if (sc_map_eval(m, d[i], SC_EVAL_VALUE, &v, NULL)) return HUGE_VAL;
    e = fmax(e, fabs(d[(i + 1) % p] - v.f));
  }
  return e;
}

static void test_chaotic(double vdrive, const int *periods, int nper,
                         int maxtries, double min_mult, int want_msns) {
  printf("--- bk2 chaotic attractor, driver moving, V = %g\n", vdrive);
  sc_map *m = bk2_moving(vdrive);
  sc_msg msg = {""};
  enum { N = 3000 };
  static double x[N];
  sc_map_value v;
  x[0] = 0.02;
  for (int k = 0; k < 500; k++) {
    sc_map_eval(m, x[0], SC_EVAL_VALUE, &v, &msg);
    x[0] = v.f;
  }
  for (int k = 1; k < N; k++) {
    sc_map_eval(m, x[k - 1], SC_EVAL_VALUE, &v, &msg);
    x[k] = v.f;
  }
  int msns = 0;
  double maxmult = 0;
  for (int ip = 0; ip < nper; ip++) {
    int p = periods[ip];
    sc_shoot *ss, *sm, *sk;
    sc_shoot_alloc(m, p, SC_SHOOT_SINGLE, NULL, &ss, &msg);
    sc_shoot_alloc(m, p, SC_SHOOT_MULTIPLE, NULL, &sm, &msg);
    sc_shoot_alloc(m, p, SC_SHOOT_MULTIPLE, sc_linsolve_klu, &sk, &msg);
    int tries = 0, ok = 0, bad = 0, genuine = 0;
    double worst = 0, pmax = 0, dk = 0;
    for (int k = 0; k + p < N && tries < maxtries; k++) {
      /* A near return: the attractor passes within 1e-3 of where it
       * was p iterates before (|d| ~ 0.02). */
      if (fabs(x[k + p] - x[k]) > 1e-3) continue;
      tries++;
      sc_shoot_result rm, rs;
      int a = sc_shoot_solve_orbit(sm, x + k, &rm, &msg);
      int b = sc_shoot_solve(ss, x[k], &rs, &msg);
      if (a != SC_OK) continue;
      ok++;
      const double *o = sc_shoot_orbit(sm);
      double e = orbit_defect(m, o, p);
      worst = fmax(worst, e);
      if (e > 1e-14) bad++;
      if (min_period(o, p) == p) genuine++;
      pmax = fmax(pmax, fabs(rm.multiplier));
      if (b != SC_OK) msns++;
      if (p == periods[nper - 1] && tries <= 5) {
        sc_shoot_result rk;
        if (sc_shoot_solve_orbit(sk, x + k, &rk, &msg) == SC_OK)
          for (int i = 0; i < p; i++)
            dk = fmax(dk, fabs(sc_shoot_orbit(sk)[i] - o[i]));
        else
          dk = HUGE_VAL;
      }
    }
    maxmult = fmax(maxmult, pmax);
    printf("  period %2d (%s): %d seeds, %d converged (%d of minimal "
           "period %d), largest |multiplier| %.4g, worst defect %.3g\n",
           p, sc_linsolve_type_name(sc_shoot_linsolve_type(sm)), tries, ok,
           genuine, p, pmax, worst);
    tu_true(ok >= 1 && ok * 2 >= tries,
            "period %d: multiple shooting converged from %d of %d near "
            "returns (want at least half)",
            p, ok, tries);
    tu_true(genuine >= 1, "period %d: an orbit of minimal period %d", p, p);
    /* An orbit solves d_(i+1) = f(d_i) to the rounding of f (|d| ~ 0.03:
     * a few 1e-18 per evaluation). */
    tu_close("worst defect max |d_(i+1) - f(d_i)|", worst, 0, 1e-14);
    tu_int("converged orbits with a defect above 1e-14", bad, 0);
    if (p == periods[nper - 1])
      tu_close("dense/automatic and KLU orbits agree", dk, 0, 1e-15);
    sc_shoot_free(ss);
    sc_shoot_free(sm);
    sc_shoot_free(sk);
  }
  printf("  seeds where multiple shooting converged and single shooting "
         "did not: %d; largest |multiplier| %.4g\n",
         msns, maxmult);
  tu_true(maxmult >= min_mult, "largest |multiplier| %.4g >= %.3g", maxmult,
          min_mult);
  if (want_msns)
    tu_true(msns >= 1,
            "multiple shooting converged where single shooting failed "
            "(%d seeds)",
            msns);
  sc_map_free(m);
}

static void test_neutral(void) {
  printf("--- neutral orbits (single-block slips, V = 0.0165)\n");
  sc_map *m = bk2_moving(0.0165);
  sc_msg msg = {""};
  double x = 0.02;
  sc_map_value v;
  for (int k = 0; k < 2000; k++) {
    sc_map_eval(m, x, SC_EVAL_VALUE, &v, &msg);
    x = v.f;
  }
  sc_map_eval(m, x, SC_EVAL_DERIV, &v, &msg);
  tu_true(v.neutral, "the attractor at V = 0.0165 is made of neutral "
                     "iterates");
  for (int k = 0; k < 2; k++) {
    sc_shoot *s;
    sc_shoot_result res;
    sc_shoot_alloc(m, 2, k ? SC_SHOOT_SINGLE : SC_SHOOT_MULTIPLE, NULL, &s,
                   &msg);
    /* A guess off the orbit, still on the same pieces. */
    int st = sc_shoot_solve(s, x + 1e-4, &res, &msg);
    printf("  %s: %s\n", k ? "single" : "multiple", msg.text);
    tu_int("neutral orbit: SC_ENEUTRAL", st, SC_ENEUTRAL);
    tu_true(strstr(msg.text, "is on a continuous family") != NULL,
            "message says d is on a continuous family");
    tu_int("result marked neutral", res.neutral, 1);
    tu_close("neutral multiplier exactly 1", res.multiplier, 1, 0);
    /* f^2(d) - d = c1 + c2 = 0 by the symmetry of beta = 1, to the
     * rounding of two iterates. */
    tu_close("family gap f^2(d) - d", res.family_gap, 0, 1e-15);
    sc_shoot_free(s);
  }
  /* Period 1 on the same piece: f(d) - d = c != 0, not on a family. */
  sc_shoot *s;
  sc_shoot_result res;
  sc_shoot_alloc(m, 1, SC_SHOOT_SINGLE, NULL, &s, &msg);
  int st = sc_shoot_solve(s, x, &res, &msg);
  tu_int("period 1 on a neutral piece: SC_ENEUTRAL", st, SC_ENEUTRAL);
  tu_true(strstr(msg.text, "no period-1 orbit through d") != NULL &&
              strstr(msg.text, "family") == NULL,
          "message says there is no orbit, and no family (%s)", msg.text);
  tu_true(fabs(res.family_gap) > 1e-3, "gap f(d) - d = %.3g is not zero",
          res.family_gap);
  sc_shoot_free(s);
  sc_map_free(m);
}

static void test_errors(void) {
  printf("--- error paths\n");
  sc_map *m = logistic(3.9);
  sc_msg msg = {""};
  sc_shoot *s = (sc_shoot *)&msg;
  tu_int("period 0: SC_EINVAL",
         sc_shoot_alloc(m, 0, SC_SHOOT_SINGLE, NULL, &s, &msg), SC_EINVAL);
  tu_true(s == NULL, "no object on failure");
  printf("  message: %s\n", msg.text);
  tu_int("bad method: SC_EINVAL",
         sc_shoot_alloc(m, 2, (sc_shoot_method)7, NULL, &s, &msg), SC_EINVAL);
  sc_shoot_alloc(m, 2, SC_SHOOT_MULTIPLE, NULL, &s, &msg);
  sc_shoot_result res;
  tu_int("NaN guess: SC_EINVAL", sc_shoot_solve(s, NAN, &res, &msg),
         SC_EINVAL);
  sc_shoot_free(s);
  /* One Newton iteration cannot reach 1e-13 from a poor guess. */
  sc_accuracy acc;
  sc_accuracy_preset(&acc, "default", NULL);
  acc.newton_maxiter = 1;
  sc_map_set_accuracy(m, &acc, &msg);
  sc_shoot_alloc(m, 1, SC_SHOOT_SINGLE, NULL, &s, &msg);
  tu_int("maxiter 1: SC_ENOCONV", sc_shoot_solve(s, 0.6, &res, &msg),
         SC_ENOCONV);
  printf("  message: %s\n", msg.text);
  sc_shoot_free(s);
  /* The logistic fixed point x = 0 at r = 1 has multiplier exactly 1:
   * Newton's Jacobian f' - 1 vanishes there. */
  sc_accuracy_preset(&acc, "default", NULL);
  sc_map_set_accuracy(m, &acc, &msg);
  sc_map_set_param_by_name(m, "r", 2, &msg);
  sc_shoot_alloc(m, 1, SC_SHOOT_SINGLE, NULL, &s, &msg);
  tu_int("singular Jacobian at x = 0.25, r = 2: SC_ESING",
         sc_shoot_solve(s, 0.25, &res, &msg), SC_ESING);
  printf("  message: %s\n", msg.text);
  sc_shoot_free(s);
  sc_shoot_free(NULL);
  sc_map_free(m);
}

/* Long periods: the logistic map at r = 3.569945659, between the 12th and
 * 13th flips of its cascade (r_inf = 3.5699456718...), where the attractor
 * is a stable orbit of period 2^12 = 4096.  Multiple shooting (KLU, chosen
 * automatically above SC_SHOOT_DENSE_MAX) from the attractor's points
 * polishes it: minimal period 4096, every d_(i+1) = f(d_i) to rounding,
 * and a stable multiplier. */
static void test_period4096(void) {
  printf("--- logistic: a period-4096 orbit by multiple shooting\n");
  enum { P = 4096 };
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("logistic", NULL, &m, &msg);
  sc_map_set_param(m, 0, 3.569945659, &msg);
  static double o[P];
  double x = 0.5;
  sc_map_value v;
  for (long k = 0; k < 2000000; k++) {
    sc_map_eval(m, x, SC_EVAL_VALUE, &v, NULL);
    x = v.f;
  }
  o[0] = x;
  for (int k = 1; k < P; k++) {
    sc_map_eval(m, o[k - 1], SC_EVAL_VALUE, &v, NULL);
    o[k] = v.f;
  }
  sc_shoot *sh = NULL;
  sc_shoot_result res;
  int st = sc_shoot_alloc(m, P, SC_SHOOT_MULTIPLE, NULL, &sh, &msg);
  if (!st) st = sc_shoot_solve_orbit(sh, o, &res, &msg);
  tu_int("period 4096: multiple shooting converged", st, SC_OK);
  if (!st) {
    const double *q = sc_shoot_orbit(sh);
    printf("  backend %s, multiplier %.6g\n",
           sc_linsolve_type_name(sc_shoot_linsolve_type(sh)), res.multiplier);
    tu_int("period 4096: minimal period", min_period(q, P), P);
    /* |d| < 1: rounding of f is a few 1e-16 per evaluation */
    tu_close("period 4096: worst defect max |d_(i+1) - f(d_i)|",
             orbit_defect(m, q, P), 0, 1e-14);
    tu_true(fabs(res.multiplier) < 1, "period 4096: stable (multiplier %.6g)",
            res.multiplier);
  }
  sc_shoot_free(sh);
  sc_map_free(m);
}

/* A start at a fold itself: the cubic map x + mu1 + mu2 x - x^3 at mu2 =
 * 3 x0^2, mu1 = 2 x0^3 has the double fixed point x0 (multiplier exactly
 * 1 there, Jacobian f' - 1 = 0 up to rounding).  Newton's step from x0
 * goes far (the residual, an ulp or so, over a Jacobian of rounding
 * size), and no halving of it lowers the residual: the start is already
 * within tolerance and must be taken as converged, not refused (a
 * branch started from a points.csv row of an LP starts exactly so). */
static void test_fold_start(void) {
  printf("--- a start at a fold\n");
  int ok = 0, n = 0;
  double worst = 0;
  for (int i = 0; i < 20; i++) {
    double x0 = 0.3 + 0.05 * i, mu2 = 3 * x0 * x0, mu1 = -2 * x0 * x0 * x0;
    sc_map *m = NULL;
    sc_msg msg = {""};
    sc_map_alloc("cubic", NULL, &m, &msg);
    sc_map_set_param_by_name(m, "mu1", mu1, &msg);
    sc_map_set_param_by_name(m, "mu2", mu2, &msg);
    for (int k = 0; k < 2; k++) {
      sc_shoot *s = NULL;
      sc_shoot_result res;
      int st = sc_shoot_alloc(m, 1, k ? SC_SHOOT_MULTIPLE : SC_SHOOT_SINGLE,
                              k ? sc_linsolve_dense : NULL, &s, &msg);
      st = st ? st : sc_shoot_solve(s, x0, &res, &msg);
      n++;
      if (st == SC_OK) {
        ok++;
        worst = fmax(worst, fabs(res.d - x0));
      } else {
        printf("  x0 = %.17g: %s\n", x0, msg.text);
      }
      sc_shoot_free(s);
    }
    sc_map_free(m);
  }
  tu_int("a start at a fold converges (single and multiple shooting)", ok, n);
  /* the double root is known to ~sqrt(eps): the residual is flat there */
  tu_true(worst <= 1e-7, "and stays at the fold: |d - x0| <= %.3g (1e-7)",
          worst);
}

int main(void) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  test_fold_start();
  test_period4096();
  test_logistic();
  const int p019[] = {2, 4, 8, 16, 24, 32};
  test_chaotic(0.019, p019, 6, 400, 100, 1);
  const int p0175[] = {32};
  test_chaotic(0.0175, p0175, 1, 400, 1e6, 0);
  test_neutral();
  test_errors();
  return tu_finish();
}
