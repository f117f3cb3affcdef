/* Pseudo-arclength continuation on maps with exact answers.
 *
 * - Logistic map x -> r x (1 - x): the first six period doublings
 *   r_1 .. r_6, each located as the flip (multiplier -1) of the
 *   period-2^(k-1) branch continued in r, against references computed
 *   here by an independent long double Newton solve of
 *   {f^m(x) - x = 0, (f^m)'(x) + 1 = 0}; r_1 = 3 and r_2 = 1 + sqrt 6
 *   exactly; the period-3 fold at r = 1 + 2 sqrt 2.
 * - Cubic map x -> x + mu1 + mu2 x - x^3 at mu2 = 0.75 continued in mu1:
 *   folds at mu1 = +-2 (mu2/3)^(3/2) = +-0.25 (x = -+0.5), flips where
 *   1 + mu2 - 3x^2 = -1 (x = +-sqrt(11/12)); the fold curve in
 *   (mu1, mu2) = (-2x^3, 3x^2) through the cusp at the origin; the flip
 *   curve (mu1, mu2) = (2x - 2x^3, 3x^2 - 2).
 * - Step control, rejection of a test function that jumps sign, error
 *   paths, both linear-solver backends.
 *
 * Accuracy: the corrector stops when its last step is within
 * newton_atol + newton_rtol |u| = 1e-13 (1 + |u|) ("default" preset); the
 * step before that was about its square root, so the corrected point is
 * exact to rounding in F.  The location stops when its last secant step in
 * arclength is within the same tolerance; the secant converges
 * superlinearly, so the located point's arclength error is far below that.
 * What is left is rounding in evaluating f^m and its derivative.  The
 * tolerances below are stated per assertion. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/continuation.h"
#include "slipcont/map.h"
#include "test_util.h"

/* ------------------------------------------------------------------ */
/* g = f^m through the sc_map API                                      */
/* ------------------------------------------------------------------ */

typedef struct {
  sc_map *m;
  int period;
  int second; /* cubic only: supply g_xx, g_xp analytically (order 2) */
} map_ctx;

static int map_fn(double x, const double *p, int order, sc_map1d_jet *jet,
                  void *user) {
  map_ctx *c = user;
  size_t np = sc_map_nparam(c->m);
  for (size_t i = 0; i < np; i++)
    if (sc_map_get_param(c->m, i) != p[i] &&
        sc_map_set_param(c->m, i, p[i], NULL))
      return 1; /* outside the parameter range: recoverable */
  sc_map_value v;
  int st = sc_map_iterate(c->m, x, c->period, order ? SC_EVAL_DERIV : 0, &v,
                          NULL);
  if (st) return st == SC_EUNDEF || st == SC_ENONFINITE ? 1 : -1;
  jet->g = v.f;
  jet->gx = v.dfdd;
  for (size_t i = 0; i < np; i++) jet->gp[i] = v.dfdp[i];
  if (order >= 2) {
    /* sc_map has no second derivatives; for the cubic (period 1) they
     * are g_xx = -6x, g_x,mu1 = 0, g_x,mu2 = 1. */
    if (!c->second) return -1;
    jet->gxx = -6 * x;
    jet->gxp[0] = 0;
    jet->gxp[1] = 1;
  }
  return 0;
}

/* ------------------------------------------------------------------ */
/* Independent references: long double Newton on                        */
/* {f^m(x) - x = 0, (f^m)'(x) + sigma = 0}, sigma = +1 flip, -1 fold.   */
/* ------------------------------------------------------------------ */

static void logistic_jets(long double x, long double r, int m,
                          long double out[5]) {
  /* x_k and its derivatives a = dx_k/dx0, b = dx_k/dr, c = d2x_k/dx0^2,
   * e = d2x_k/dx0 dr, by the chain rule through x -> r x (1 - x). */
  long double a = 1, b = 0, c = 0, e = 0;
  for (int k = 0; k < m; k++) {
    long double fx = r * (1 - 2 * x), fr = x * (1 - x), fxx = -2 * r,
                fxr = 1 - 2 * x;
    long double a1 = fx * a, b1 = fx * b + fr, c1 = fxx * a * a + fx * c,
                e1 = fxx * a * b + fxr * a + fx * e;
    x = r * x * (1 - x);
    a = a1, b = b1, c = c1, e = e1;
  }
  out[0] = x, out[1] = a, out[2] = b, out[3] = c, out[4] = e;
}

/* Refine (x, r) in long double; returns the final Newton step size. */
static long double logistic_reference(long double *x, long double *r, int m,
                                      long double sigma) {
  long double step = 1;
  for (int it = 0; it < 60; it++) {
    long double j[5];
    logistic_jets(*x, *r, m, j);
    long double g1 = j[0] - *x, g2 = j[1] + sigma;
    long double a11 = j[1] - 1, a12 = j[2], a21 = j[3], a22 = j[4];
    long double det = a11 * a22 - a12 * a21;
    long double dx = -(g1 * a22 - a12 * g2) / det;
    long double dr = -(a11 * g2 - a21 * g1) / det;
    *x += dx;
    *r += dr;
    step = fabsl(dx) + fabsl(dr);
    if (step < 1e-18L * (1 + fabsl(*r))) break;
  }
  return step;
}

/* ------------------------------------------------------------------ */
/* Helpers                                                              */
/* ------------------------------------------------------------------ */

static sc_accuracy acc_default(void) {
  sc_accuracy a;
  sc_accuracy_preset(&a, "default", NULL);
  return a;
}

/* Continue a fixed-point branch of f^period until the first special
 * point of test @p want ("fold" = 0, "flip" = 1); returns its u. */
typedef struct {
  map_ctx ctx;
  sc_map1d_system sys;
} fixed_system; /* must outlive a branch that uses it */

static int find_special(sc_map *m, int period, double x0, double r0,
                        const sc_cont_settings *set, size_t want,
                        double u_out[2], fixed_system *fs, sc_branch **keep) {
  fs->ctx = (map_ctx){m, period, 0};
  fs->sys = (sc_map1d_system){.fn = map_fn, .user = &fs->ctx,
                              .kind = SC_MAP1D_FIXED,
                              .np = sc_map_nparam(m), .ifree = {0, 0}};
  for (size_t i = 0; i < fs->sys.np; i++) fs->sys.p[i] = sc_map_get_param(m, i);
  sc_cont_problem pb;
  sc_msg msg = {""};
  sc_map1d_problem(&fs->sys, &pb, &msg);
  sc_branch *b = NULL;
  sc_accuracy acc = acc_default();
  int st = sc_branch_alloc(&pb, set, &acc, &b, &msg);
  double u0[2] = {x0, r0};
  if (!st) st = sc_branch_set(b, u0, &msg);
  while (st == SC_OK || st == SC_CONTINUE || st == SC_SPECIAL) {
    if (st == SC_SPECIAL &&
        (size_t)sc_branch_location(b)->test == want)
      break;
    st = sc_branch_step(b, &msg);
  }
  if (st != SC_SPECIAL) printf("  find_special: status %d: %s\n", st, msg.text);
  memcpy(u_out, sc_branch_point(b), 2 * sizeof(double));
  if (keep) *keep = b;
  else sc_branch_free(b);
  return st;
}

/* A point on the attractor of f at parameter r (after many iterates). */
static double attractor_point(sc_map *m, double r, int iterations) {
  sc_map_set_param(m, 0, r, NULL);
  double x = 0.5;
  sc_map_value v;
  for (int k = 0; k < iterations; k++) {
    sc_map_eval(m, x, SC_EVAL_VALUE, &v, NULL);
    x = v.f;
  }
  return x;
}

/* ------------------------------------------------------------------ */
/* The logistic cascade                                                 */
/* ------------------------------------------------------------------ */

static void test_cascade(const sc_linsolve_type *ls, int kmax) {
  printf("--- logistic period-doubling cascade (%s)\n",
         sc_linsolve_type_name(ls));
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("logistic", NULL, &m, &msg);
  /* A second, offline reference: the same 2-equation system solved by
   * Newton in 50-digit arithmetic (Python mpmath 1.3), rounded to double.
   * (A value often quoted for r_5, 3.568759419544776, is off by 9.5e-13.) */
  const double mp50[6] = {3.0, 3.44948974278317809819728407471,
                          3.5440903595519228536159659866,
                          3.56440726609543259777355758653,
                          3.56875941954382643129821028003,
                          3.5696916098013967142882687063};
  double rk[7] = {0};
  for (int k = 1; k <= kmax; k++) {
    int period = 1 << (k - 1);
    /* Start inside the stable window of period 2^(k-1), (r_(k-1), r_k):
     * its width w shrinks by Feigenbaum's delta = 4.669 from one period to
     * the next; half way in, the orbit is nearly superstable. */
    double w = k == 1 ? 2 : k == 2 ? 0.45 : (rk[k - 1] - rk[k - 2]) / 4.669;
    double r0 = k == 1 ? 2.8 : rk[k - 1] + 0.5 * w;
    double x0 = attractor_point(m, r0, 20000);
    sc_cont_settings set;
    sc_cont_settings_default(&set);
    set.h0 = w / 40;
    set.hmax = w / 8;
    set.pmax = 4;
    set.linsolve = ls;
    double u[2];
    fixed_system fs;
    int st = find_special(m, period, x0, r0, &set, 1, u, &fs, NULL);
    char what[96];
    snprintf(what, sizeof what, "r_%d located (period-%d flip)", k, period);
    tu_int(what, st, SC_SPECIAL);
    long double xr = u[0], rr = u[1];
    long double last = logistic_reference(&xr, &rr, period, 1);
    /* The reference Newton converged to long double rounding. */
    tu_true(last < 1e-17L, "r_%d reference converged (last step %.3Lg)", k,
            last);
    /* Tolerance: the flip parameter of f^m is well conditioned in r (the
     * Jacobian of the 2x2 system is regular), so rounding of f^m in double
     * (m terms of a few eps each, amplified by at most the partial
     * products of f' along the orbit) leaves r within a few 1e-15; 1e-13
     * is the aim of the brief and still leaves a margin of ten. */
    snprintf(what, sizeof what, "r_%d against long double reference", k);
    tu_close(what, u[1], (double)rr, 1e-13);
    /* The two references agree to the rounding of the long double solve
     * converted to double: half an ulp of r, 2.3e-16, plus a margin. */
    snprintf(what, sizeof what, "r_%d long double reference vs mpmath", k);
    tu_close(what, (double)rr, mp50[k - 1], 5e-16);
    snprintf(what, sizeof what, "r_%d against mpmath reference", k);
    tu_close(what, u[1], mp50[k - 1], 1e-13);
    if (k == 1) tu_close("r_1 = 3 exactly", u[1], 3, 1e-13);
    if (k == 2) tu_close("r_2 = 1 + sqrt 6 exactly", u[1], 1 + sqrt(6), 1e-13);
    rk[k] = u[1];
  }
  sc_map_free(m);
}

/* The fold of the period-3 orbit at r = 1 + 2 sqrt 2: continue the stable
 * period-3 branch down in r; the branch turns back there. */
static void test_period3_fold(void) {
  printf("--- logistic period-3 fold\n");
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("logistic", NULL, &m, &msg);
  double r0 = 3.832; /* near the superstable period-3 orbit */
  double x0 = attractor_point(m, r0, 20000);
  sc_cont_settings set;
  sc_cont_settings_default(&set);
  set.h0 = 1e-3;
  set.hmax = 1e-2;
  set.direction = -1;
  set.pmin = 3.8;
  double u[2];
  sc_branch *b;
  fixed_system fs;
  int st = find_special(m, 3, x0, r0, &set, 0, u, &fs, &b);
  tu_int("period-3 fold located", st, SC_SPECIAL);
  long double xr = u[0], rr = u[1];
  logistic_reference(&xr, &rr, 3, -1);
  /* At a fold r is quadratic in arclength, so an arclength error e moves
   * r by O(e^2): r is accurate to rounding in f^3; 1e-13 as for flips. */
  tu_close("period-3 fold r = 1 + 2 sqrt 2", u[1], 1 + 2 * sqrt(2), 1e-13);
  tu_close("period-3 fold r against long double reference", u[1], (double)rr,
           1e-13);
  /* The fold test is psi = g_x - 1: at the located point |psi| is within
   * test_atol (1e-8, the default). */
  tu_close("period-3 fold: multiplier - 1 at the located point",
           sc_branch_test_values(b)[0], 0, 1e-8);
  /* Past the fold the branch turns back up in r: the tangent's r
   * component changes sign there, so it is near zero at the fold
   * (|t_r| ~ the arclength error, far below 1e-6). */
  tu_close("period-3 fold: tangent r component", sc_branch_tangent(b)[1], 0,
           1e-6);
  st = sc_branch_step(b, &msg);
  tu_true(st == SC_CONTINUE && sc_branch_point(b)[1] > u[1],
          "after the fold the branch goes back up in r (r = %.17g)",
          sc_branch_point(b)[1]);
  sc_branch_free(b);
  sc_map_free(m);
}

/* ------------------------------------------------------------------ */
/* The cubic map                                                        */
/* ------------------------------------------------------------------ */

static void test_cubic_folds(const sc_linsolve_type *ls) {
  printf("--- cubic map in mu1 at mu2 = 0.75 (%s)\n", sc_linsolve_type_name(ls));
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("cubic", NULL, &m, &msg);
  sc_map_set_param(m, 1, 0.75, &msg);
  map_ctx ctx = {m, 1, 0};
  sc_map1d_system sys = {.fn = map_fn, .user = &ctx, .kind = SC_MAP1D_FIXED,
                         .np = 2, .p = {0, 0.75}, .ifree = {0, 0}};
  sc_cont_problem pb;
  sc_map1d_problem(&sys, &pb, &msg);
  sc_cont_settings set;
  sc_cont_settings_default(&set);
  set.h0 = 0.05;
  set.hmax = 0.2;
  set.pmax = 3;
  set.linsolve = ls;
  sc_accuracy acc = acc_default();
  sc_branch *b;
  sc_branch_alloc(&pb, &set, &acc, &b, &msg);
  double x0 = -1.5, u0[2] = {x0, x0 * x0 * x0 - 0.75 * x0};
  /* Expected special points in order along the S-shaped branch. */
  double xf = sqrt(11.0 / 12);
  struct {
    int test;
    double x, mu1;
  } want[4] = {{1, -xf, -xf * xf * xf + 0.75 * xf},
               {0, -0.5, 0.25},
               {0, 0.5, -0.25},
               {1, xf, xf * xf * xf - 0.75 * xf}};
  int st = sc_branch_set(b, u0, &msg), nfound = 0;
  while (st >= 0 && st != SC_END) {
    st = sc_branch_step(b, &msg);
    if (st == SC_SPECIAL && nfound < 4) {
      const double *u = sc_branch_point(b);
      int t = sc_branch_location(b)->test;
      char what[96];
      snprintf(what, sizeof what, "cubic special %d is a %s", nfound + 1,
               pb.test_names[want[nfound].test]);
      tu_int(what, t, want[nfound].test);
      /* Folds: mu1 is quadratic in arclength there, so it is exact to
       * rounding; x moves linearly with the arclength error, which the
       * superlinear location leaves far below 1e-13 (x is O(1)). */
      snprintf(what, sizeof what, "cubic special %d: mu1", nfound + 1);
      tu_close(what, u[1], want[nfound].mu1, 1e-13);
      snprintf(what, sizeof what, "cubic special %d: x", nfound + 1);
      tu_close(what, u[0], want[nfound].x, 1e-12);
      nfound++;
    }
  }
  tu_int("cubic branch ends at mu1 = 3", st, SC_END);
  tu_int("cubic special points found", nfound, 4);
  /* The end point is corrected with mu1 held at pmax exactly. */
  tu_close("cubic end point mu1", sc_branch_point(b)[1], 3, 0);
  double xe = sc_branch_point(b)[0];
  tu_close("cubic end point solves mu1 + mu2 x - x^3 = 0",
           3 + 0.75 * xe - xe * xe * xe, 0, 1e-13);
  printf("  points %lu, Newton %lu, F %lu, J %lu, rejected %lu, locate %lu,"
         " factor %lu, refactor %lu\n",
         sc_branch_npoints(b), sc_branch_nnewton(b), sc_branch_nfeval(b),
         sc_branch_njac(b), sc_branch_nrejected(b), sc_branch_nlocate(b),
         sc_linsolve_nfactor(sc_branch_linsolve(b)),
         sc_linsolve_nrefactor(sc_branch_linsolve(b)));
  tu_int("cubic special count", (long)sc_branch_nspecial(b), 4);
  sc_branch_free(b);
  sc_map_free(m);
}

/* The fold curve (g - x, g_x - 1) = 0 in (x, mu1, mu2): the curve
 * (x, -2x^3, 3x^2) through the cusp at the origin, where g_xx = -6x
 * vanishes. */
static void test_cusp(void) {
  printf("--- cubic fold curve and cusp\n");
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("cubic", NULL, &m, &msg);
  map_ctx ctx = {m, 1, 1};
  sc_map1d_system sys = {.fn = map_fn, .user = &ctx, .kind = SC_MAP1D_FOLD,
                         .np = 2, .p = {0, 0}, .ifree = {0, 1}};
  sc_cont_problem pb;
  int st = sc_map1d_problem(&sys, &pb, &msg);
  tu_int("fold-curve problem built", st, SC_OK);
  sc_cont_settings set;
  sc_cont_settings_default(&set);
  set.h0 = 0.05;
  set.hmax = 0.1;
  set.direction = -1; /* mu2 decreases towards the cusp */
  set.pmax = 0.9;
  sc_accuracy acc = acc_default();
  sc_branch *b;
  sc_branch_alloc(&pb, &set, &acc, &b, &msg);
  double u0[3] = {-0.5, 0.25, 0.75};
  st = sc_branch_set(b, u0, &msg);
  double maxdev = 0;
  int cusps = 0;
  while (st >= 0 && st != SC_END) {
    st = sc_branch_step(b, &msg);
    const double *u = sc_branch_point(b);
    maxdev = fmax(maxdev, fabs(u[1] + 2 * u[0] * u[0] * u[0]));
    maxdev = fmax(maxdev, fabs(u[2] - 3 * u[0] * u[0]));
    if (st == SC_SPECIAL) {
      cusps++;
      tu_int("cusp: test function", sc_branch_location(b)->test, 0);
      /* x is located to the location's arclength error (superlinear
       * secant steps below 1e-13); mu1 = -2x^3 and mu2 = 3x^2 are then
       * far smaller still. */
      tu_close("cusp x", u[0], 0, 1e-13);
      tu_close("cusp mu1", u[1], 0, 1e-13);
      tu_close("cusp mu2", u[2], 0, 1e-13);
    }
  }
  tu_int("fold curve ends at mu2 = 0.9 past the cusp", st, SC_END);
  tu_int("one cusp", cusps, 1);
  tu_true(sc_branch_point(b)[0] > 0, "the curve went through the cusp to "
          "x > 0 (x = %.17g)", sc_branch_point(b)[0]);
  /* Every point solves the fold system to the corrector tolerance: the
   * residual is at most newton_ftol = 1e-13 and the Jacobian is O(1). */
  tu_close("fold curve: max deviation from (-2x^3, 3x^2)", maxdev, 0, 1e-12);
  sc_branch_free(b);

  /* The flip curve (g - x, g_x + 1) = 0: (x, 2x - 2x^3, 3x^2 - 2). */
  sys.kind = SC_MAP1D_FLIP;
  sc_map1d_problem(&sys, &pb, &msg);
  set.direction = -1;
  set.pmax = 1.5;
  set.pmin = -2.5;
  set.max_points = 200;
  sc_branch_alloc(&pb, &set, &acc, &b, &msg);
  double v0[3] = {-1, 0, 1};
  st = sc_branch_set(b, v0, &msg);
  maxdev = 0;
  double xmax = -1;
  while (st >= 0 && st != SC_END) {
    st = sc_branch_step(b, &msg);
    const double *u = sc_branch_point(b);
    xmax = fmax(xmax, u[0]);
    maxdev = fmax(maxdev, fabs(u[1] - (2 * u[0] - 2 * u[0] * u[0] * u[0])));
    maxdev = fmax(maxdev, fabs(u[2] - (3 * u[0] * u[0] - 2)));
  }
  tu_int("flip curve ends", st, SC_END);
  tu_true(xmax > 0.5, "flip curve crossed x = 0 (max x %.3g)", xmax);
  tu_close("flip curve: max deviation from (2x - 2x^3, 3x^2 - 2)", maxdev, 0,
           1e-12);
  sc_branch_free(b);
  sc_map_free(m);
}

/* ------------------------------------------------------------------ */
/* Step control, rejection, errors                                      */
/* ------------------------------------------------------------------ */

/* The line x = r (n = 1), with switches to provoke failures. */
typedef struct {
  int fail_beyond;  /* F fails recoverably when r > limit */
  double limit;
  int nan_beyond;   /* F returns NaN when r > limit */
  int fatal;        /* F returns -1 */
  double jump_at;   /* test 1 jumps from -0.5 to +0.5 there */
  unsigned long nfail;
} line_ctx;

static int line_f(const double *u, double *F, void *user) {
  line_ctx *c = user;
  if (c->fatal) return -1;
  if (c->fail_beyond && u[1] > c->limit) {
    c->nfail++;
    return 1;
  }
  F[0] = u[0] - u[1] + 0.1 * (u[0] - u[1]) * (u[0] - u[1]);
  if (c->nan_beyond && u[1] > c->limit) F[0] = NAN;
  return 0;
}

static int line_jac(const double *u, double *J, void *user) {
  (void)user;
  double d = u[0] - u[1];
  J[0] = 1 + 0.2 * d;
  J[1] = -1 - 0.2 * d;
  return 0;
}

/* psi_0 = r - 0.7 (a genuine zero), psi_1 jumps across r = jump_at
 * without passing through zero. */
static int line_test(const double *u, const double *t, double *psi,
                     void *user) {
  line_ctx *c = user;
  (void)t;
  psi[0] = u[1] - 0.7;
  psi[1] = u[1] < c->jump_at ? -0.5 - (c->jump_at - u[1])
                             : 0.5 + (u[1] - c->jump_at);
  return 0;
}

static sc_cont_problem line_problem(line_ctx *c) {
  sc_cont_problem pb = {.n = 1, .f = line_f, .jac = line_jac, .ntest = 2,
                        .test = line_test, .user = c};
  return pb;
}

static void test_step_control(void) {
  printf("--- step control\n");
  line_ctx c = {.fail_beyond = 1, .limit = 0.05, .jump_at = 10};
  sc_cont_problem pb = line_problem(&c);
  sc_cont_settings set;
  sc_cont_settings_default(&set);
  set.h0 = 0.1;
  set.hmax = 0.4;
  set.grow = 1.5;
  set.shrink = 0.5;
  set.pmax = 2;
  sc_accuracy acc = acc_default();
  sc_branch *b;
  sc_msg msg = {""};
  sc_branch_alloc(&pb, &set, &acc, &b, &msg);
  double u0[2] = {0, 0};
  sc_branch_set(b, u0, &msg);
  /* The first step predicts r = 0.1/sqrt 2 > 0.05: F fails, the step is
   * halved to 0.05 (r = 0.035), which converges at once (the predictor
   * lies on the line), so the step grows by 1.5 to 0.075. */
  int st = sc_branch_step(b, &msg);
  tu_int("step after a failure: accepted", st, SC_CONTINUE);
  tu_int("one rejected step", (long)sc_branch_nrejected(b), 1);
  tu_close("accepted arclength = h0 * shrink: r = 0.05 / sqrt 2",
           sc_branch_point(b)[1], 0.05 / sqrt(2), 1e-15);
  tu_close("next step = h0 * shrink * grow", sc_branch_step_size(b), 0.075,
           1e-15);
  tu_int("reason after success", sc_branch_reason(b), SC_CORR_CONVERGED);
  /* Beyond r = 0.05 every prediction fails: the branch creeps up to
   * r = 0.05 with shrinking steps, and stops with SC_ENOCONV naming the
   * reason once the step falls below hmin = 1e-10. */
  while ((st = sc_branch_step(b, &msg)) == SC_CONTINUE) continue;
  tu_int("steps below hmin: SC_ENOCONV", st, SC_ENOCONV);
  printf("  message: %s\n", msg.text);
  tu_true(strstr(msg.text, "callback") != NULL,
          "message names the corrector reason");
  tu_int("reason: callback", sc_branch_reason(b), SC_CORR_CALLBACK);
  /* The last accepted point lies within about hmin of r = 0.05 (the
   * failing step was below hmin, the one before it accepted). */
  tu_close("stopped just below r = 0.05", sc_branch_point(b)[1], 0.05, 1e-9);
  /* Steps grow to hmax on easy convergence: disarm the failure. */
  c.fail_beyond = 0;
  double hmaxseen = 0;
  while ((st = sc_branch_step(b, &msg)) == SC_CONTINUE || st == SC_SPECIAL)
    hmaxseen = fmax(hmaxseen, sc_branch_step_size(b));
  tu_int("line ends at pmax", st, SC_END);
  tu_close("steps grew to hmax", hmaxseen, 0.4, 0);
  sc_branch_free(b);

  /* Max iterations: a nonlinear predictor error with newton_maxiter = 1
   * cannot converge (the residual after one step is not within ftol);
   * the step shrinks until the predictor is exact enough... it never is
   * for one iteration with a curved branch, so SC_ENOCONV. */
  acc.newton_maxiter = 1;
  line_ctx c2 = {.jump_at = 10};
  pb = line_problem(&c2);
  sc_branch_alloc(&pb, &set, &acc, &b, &msg);
  double u1[2] = {-1.3, 0};
  st = sc_branch_set(b, u1, &msg);
  tu_int("maxiter 1 from a poor guess: SC_ENOCONV", st, SC_ENOCONV);
  tu_int("reason: max iterations", sc_branch_reason(b), SC_CORR_MAXITER);
  printf("  message: %s\n", msg.text);
  sc_branch_free(b);
}


/* F(x, r) = atan(x) - r: Newton on atan from |x| > 1.39 overshoots
 * further at every step. */
static int atan_f(const double *u, double *F, void *user) {
  (void)user;
  F[0] = atan(u[0]) - u[1];
  return 0;
}

static int atan_jac(const double *u, double *J, void *user) {
  (void)user;
  J[0] = 1 / (1 + u[0] * u[0]);
  J[1] = -1;
  return 0;
}

static void test_diverging(void) {
  printf("--- diverging corrector\n");
  sc_cont_problem pb = {.n = 1, .f = atan_f, .jac = atan_jac};
  sc_accuracy acc = acc_default();
  sc_branch *b;
  sc_msg msg = {""};
  sc_branch_alloc(&pb, NULL, &acc, &b, &msg);
  double u0[2] = {3.0, 0};
  int st = sc_branch_set(b, u0, &msg);
  tu_int("atan from x = 3: SC_ENOCONV", st, SC_ENOCONV);
  tu_int("reason: diverging", sc_branch_reason(b), SC_CORR_DIVERGING);
  printf("  message: %s\n", msg.text);
  /* From x = 1 Newton converges to the root x = 0; the bordered
   * Jacobian [1/(1+x^2), -1; 0, 1] has det 1 there (sign +1, log 0). */
  double u1[2] = {1.0, 0};
  st = sc_branch_set(b, u1, &msg);
  tu_int("atan from x = 1: SC_OK", st, SC_OK);
  tu_close("atan root", sc_branch_point(b)[0], 0, 1e-15);
  int sign = 0;
  double logabs = 1;
  sc_branch_bordered_det(b, &sign, &logabs);
  tu_int("bordered det sign at the start", sign, 1);
  /* the start's tangent border is e_r: det [1/(1+x^2), -1; 0, 1] = 1 */
  tu_close("bordered log|det| at the start", logabs, 0, 1e-15);
  sc_branch_free(b);
  /* start_free: where the correction at fixed r diverges, the start is
   * corrected at fixed x instead and lands on the curve at r = atan 3. */
  sc_cont_settings set;
  sc_cont_settings_default(&set);
  set.start_free = 1;
  sc_branch_alloc(&pb, &set, &acc, &b, &msg);
  st = sc_branch_set(b, u0, &msg);
  tu_int("start_free: atan from x = 3: SC_OK", st, SC_OK);
  tu_close("start_free: x kept", sc_branch_point(b)[0], 3, 0);
  /* Newton in r on atan(3) - r: exact after one step up to rounding */
  tu_close("start_free: r = atan(3)", sc_branch_point(b)[1], atan(3.0),
           4e-16);
  sc_branch_free(b);
}


/* Folds of any branch from the tangent: psi = t[n] (the parameter
 * component of the unit tangent) changes sign at each turning point.  On
 * mu1 + 0.75 x - x^3 = 0 in (x, mu1) the turning points are mu1 = +-0.25. */
static int cubic_f(const double *u, double *F, void *user) {
  (void)user;
  F[0] = u[1] + 0.75 * u[0] - u[0] * u[0] * u[0];
  return 0;
}

static int cubic_jac(const double *u, double *J, void *user) {
  (void)user;
  J[0] = 0.75 - 3 * u[0] * u[0];
  J[1] = 1;
  return 0;
}

static int tangent_test(const double *u, const double *t, double *psi,
                        void *user) {
  (void)u, (void)user;
  psi[0] = t[1];
  return 0;
}

static void test_tangent_folds(void) {
  printf("--- folds from the tangent component\n");
  sc_cont_problem pb = {.n = 1, .f = cubic_f, .jac = cubic_jac, .ntest = 1,
                        .test = tangent_test};
  sc_cont_settings set;
  sc_cont_settings_default(&set);
  set.h0 = 0.05, set.hmax = 0.2, set.pmax = 1;
  sc_branch *b;
  sc_msg msg = {""};
  sc_branch_alloc(&pb, &set, NULL, &b, &msg);
  double u0[2] = {-1.5, -2.25};
  int st = sc_branch_set(b, u0, &msg), n = 0;
  const double want[2] = {0.25, -0.25};
  while (st >= 0 && st != SC_END) {
    st = sc_branch_step(b, &msg);
    if (st == SC_SPECIAL && n < 2) {
      /* mu1 is quadratic in arclength at a fold: exact to rounding */
      tu_close(n ? "second turning point mu1" : "first turning point mu1",
               sc_branch_point(b)[1], want[n], 1e-13);
      n++;
    }
  }
  tu_int("two turning points", n, 2);
  sc_branch_free(b);
}

static void test_rejection(void) {
  printf("--- special points: zero accepted, jump rejected\n");
  line_ctx c = {.jump_at = 0.4};
  sc_cont_problem pb = line_problem(&c);
  sc_cont_settings set;
  sc_cont_settings_default(&set);
  set.h0 = 0.03;
  set.hmax = 0.1;
  set.pmax = 1;
  sc_accuracy acc = acc_default();
  sc_branch *b;
  sc_msg msg = {""};
  sc_branch_alloc(&pb, &set, &acc, &b, &msg);
  double u0[2] = {0, 0};
  int st = sc_branch_set(b, u0, &msg), nspecial = 0;
  double r_special = NAN;
  while (st >= 0 && st != SC_END) {
    st = sc_branch_step(b, &msg);
    if (st == SC_SPECIAL) {
      nspecial++;
      r_special = sc_branch_point(b)[1];
      tu_int("the special point is the genuine zero (test 0)",
             sc_branch_location(b)->test, 0);
    }
  }
  tu_int("branch ends", st, SC_END);
  tu_int("one special point reported", nspecial, 1);
  /* psi_0 = r - 0.7 is linear in r: located to the arclength tolerance */
  tu_close("special point at r = 0.7", r_special, 0.7, 1e-13);
  tu_int("one sign change rejected (the jump)",
         (long)sc_branch_nrejected_special(b), 1);
  sc_branch_free(b);
}

static void test_errors(void) {
  printf("--- error paths\n");
  line_ctx c = {.jump_at = 10};
  sc_cont_problem pb = line_problem(&c);
  sc_cont_settings set;
  sc_accuracy acc = acc_default();
  sc_branch *b = NULL;
  sc_msg msg = {""};
  struct {
    const char *what;
    void (*edit)(sc_cont_settings *);
  } bad[1];
  (void)bad;
  sc_cont_settings_default(&set);
  set.hmin = 2 * set.h0;
  tu_int("hmin > h0: SC_EINVAL", sc_branch_alloc(&pb, &set, &acc, &b, &msg),
         SC_EINVAL);
  printf("  message: %s\n", msg.text);
  tu_true(b == NULL, "no branch on failure");
  sc_cont_settings_default(&set);
  set.direction = 0;
  tu_int("direction 0: SC_EINVAL", sc_branch_alloc(&pb, &set, &acc, &b, &msg),
         SC_EINVAL);
  sc_cont_settings_default(&set);
  set.test_atol = NAN;
  tu_int("test_atol NaN: SC_EINVAL",
         sc_branch_alloc(&pb, &set, &acc, &b, &msg), SC_EINVAL);
  sc_cont_settings_default(&set);
  set.pmin = 1, set.pmax = 0;
  tu_int("pmin > pmax: SC_EINVAL", sc_branch_alloc(&pb, &set, &acc, &b, &msg),
         SC_EINVAL);
  sc_cont_settings_default(&set);
  set.shrink = 1;
  tu_int("shrink = 1: SC_EINVAL", sc_branch_alloc(&pb, &set, &acc, &b, &msg),
         SC_EINVAL);
  sc_accuracy bad_acc = acc;
  bad_acc.newton_atol = -1;
  tu_int("negative newton_atol: SC_EINVAL",
         sc_branch_alloc(&pb, NULL, &bad_acc, &b, &msg), SC_EINVAL);
  sc_cont_problem nof = pb;
  nof.f = NULL;
  tu_int("no F callback: SC_EINVAL", sc_branch_alloc(&nof, NULL, &acc, &b, &msg),
         SC_EINVAL);

  sc_cont_settings_default(&set);
  set.pmax = 1;
  sc_branch_alloc(&pb, &set, &acc, &b, &msg);
  tu_int("step before set: SC_EINVAL", sc_branch_step(b, &msg), SC_EINVAL);
  double out[2] = {2, 2};
  tu_int("initial parameter outside [pmin, pmax]: SC_EINVAL",
         sc_branch_set(b, out, &msg), SC_EINVAL);
  double nan0[2] = {NAN, 0};
  tu_int("NaN initial point: SC_EINVAL", sc_branch_set(b, nan0, &msg),
         SC_EINVAL);
  /* NaN from F at the start: the corrector cannot run. */
  c.nan_beyond = 1;
  c.limit = -1;
  double u0[2] = {0.1, 0.1};
  tu_int("NaN from F at the start: SC_ENOCONV", sc_branch_set(b, u0, &msg),
         SC_ENOCONV);
  tu_int("reason: callback", sc_branch_reason(b), SC_CORR_CALLBACK);
  /* NaN from F beyond r = 0.3: steps shrink to hmin, then SC_ENOCONV. */
  c.limit = 0.3;
  int st = sc_branch_set(b, u0, &msg);
  while (st == SC_OK || st == SC_CONTINUE) st = sc_branch_step(b, &msg);
  tu_int("NaN from F beyond r = 0.3: SC_ENOCONV", st, SC_ENOCONV);
  tu_true(sc_branch_point(b)[1] <= 0.3 && sc_branch_point(b)[1] > 0.29,
          "stopped just before r = 0.3 (r = %.17g)", sc_branch_point(b)[1]);
  printf("  message: %s\n", msg.text);
  /* A fatal callback failure stops at once. */
  c.nan_beyond = 0;
  sc_branch_set(b, u0, &msg);
  c.fatal = 1;
  tu_int("fatal callback: SC_ECALLBACK", sc_branch_step(b, &msg),
         SC_ECALLBACK);
  sc_branch_free(b);
  sc_branch_free(NULL);
}

/* The driver: every point passed to the callback, start and end marked. */
typedef struct {
  int start, regular, special, end;
} counts;

static int count_points(void *ctx, const sc_branch *b, sc_point_kind kind) {
  counts *c = ctx;
  (void)b;
  if (kind == SC_POINT_START) c->start++;
  if (kind == SC_POINT_REGULAR) c->regular++;
  if (kind == SC_POINT_SPECIAL) c->special++;
  if (kind == SC_POINT_END) c->end++;
  return 0;
}

static void test_solve_driver(void) {
  printf("--- driver\n");
  line_ctx c = {.jump_at = 10};
  sc_cont_problem pb = line_problem(&c);
  sc_cont_settings set;
  sc_cont_settings_default(&set);
  set.pmax = 1;
  sc_branch *b;
  sc_msg msg = {""};
  sc_branch_alloc(&pb, &set, NULL, &b, &msg);
  counts n = {0};
  double u0[2] = {0, 0};
  int st = sc_branch_solve(b, u0, count_points, &n, &msg);
  tu_int("driver: SC_OK", st, SC_OK);
  tu_true(n.start == 1 && n.end == 1 && n.special == 1 && n.regular > 3,
          "driver: start %d, regular %d, special %d, end %d", n.start,
          n.regular, n.special, n.end);
  tu_int("driver: points counted", (long)sc_branch_npoints(b),
         n.start + n.regular + n.special + n.end);
  sc_branch_free(b);
}


/* ------------------------------------------------------------------ */
/* Multiple shooting with a sparse Jacobian                             */
/* ------------------------------------------------------------------ */

/* A period-m orbit of the logistic map as m unknowns: u = (x_0 .. x_(m-1),
 * r), F_i = f(x_i) - x_(i+1 mod m).  The Jacobian is cyclic bidiagonal
 * plus the parameter column, given as a CSC pattern: column j holds rows
 * j - 1 (the -1 of F_(j-1)) and j (f'(x_j)), sorted; column m all rows. */
enum { SHOOT_MAXM = 16 };
typedef struct {
  int m;
  int cp[SHOOT_MAXM + 2];
  int ri[3 * SHOOT_MAXM];
} shoot_ctx;

static int shoot_f(const double *u, double *F, void *user) {
  const shoot_ctx *c = user;
  double r = u[c->m];
  for (int i = 0; i < c->m; i++)
    F[i] = r * u[i] * (1 - u[i]) - u[(i + 1) % c->m];
  return 0;
}

static int shoot_jac(const double *u, double *J, void *user) {
  const shoot_ctx *c = user;
  int m = c->m;
  double r = u[m];
  for (int j = 0; j < m; j++)
    for (int k = c->cp[j]; k < c->cp[j + 1]; k++)
      J[k] = c->ri[k] == j ? r * (1 - 2 * u[j]) : -1;
  for (int k = c->cp[m]; k < c->cp[m + 1]; k++) {
    int i = c->ri[k];
    J[k] = u[i] * (1 - u[i]);
  }
  return 0;
}

static int shoot_test(const double *u, const double *t, double *psi,
                      void *user) {
  const shoot_ctx *c = user;
  (void)t;
  double mult = 1;
  for (int i = 0; i < c->m; i++) mult *= u[c->m] * (1 - 2 * u[i]);
  psi[0] = mult + 1; /* multiplier -1: flip */
  return 0;
}

static void test_shooting(const sc_linsolve_type *ls, int m, double r0,
                          double rref) {
  printf("--- multiple shooting, period %d, sparse Jacobian (%s)\n", m,
         sc_linsolve_type_name(ls));
  shoot_ctx c = {.m = m};
  int k = 0;
  for (int j = 0; j < m; j++) {
    c.cp[j] = k;
    int lo = j == 0 ? j : j - 1, hi = j == 0 ? m - 1 : j;
    c.ri[k++] = lo;
    if (hi != lo) c.ri[k++] = hi;
  }
  c.cp[m] = k;
  for (int i = 0; i < m; i++) c.ri[k++] = i;
  c.cp[m + 1] = k;
  sc_cont_problem pb = {.n = (size_t)m, .f = shoot_f, .jac = shoot_jac,
                        .jac_colptr = c.cp, .jac_rowind = c.ri, .ntest = 1,
                        .test = shoot_test, .user = &c};
  sc_cont_settings set;
  sc_cont_settings_default(&set);
  set.h0 = 1e-3;
  set.hmax = 1e-2;
  set.pmax = 3.6;
  set.linsolve = ls;
  sc_accuracy acc = acc_default();
  sc_branch *b;
  sc_msg msg = {""};
  int st = sc_branch_alloc(&pb, &set, &acc, &b, &msg);
  tu_int("shooting branch allocated", st, SC_OK);
  if (st) {
    printf("  %s\n", msg.text);
    return;
  }
  sc_map *map;
  sc_map_alloc("logistic", NULL, &map, &msg);
  double u0[SHOOT_MAXM + 1];
  u0[0] = attractor_point(map, r0, 20000);
  sc_map_free(map);
  for (int i = 1; i < m; i++) u0[i] = r0 * u0[i - 1] * (1 - u0[i - 1]);
  u0[m] = r0;
  st = sc_branch_set(b, u0, &msg);
  while (st == SC_OK || st == SC_CONTINUE) st = sc_branch_step(b, &msg);
  tu_int("shooting: flip located", st, SC_SPECIAL);
  /* Same system as the period-m branch of f^m, written as m equations: the
   * same 1e-13 (see test_cascade). */
  tu_close("shooting: flip parameter", sc_branch_point(b)[m], rref, 1e-13);
  const sc_linsolve *l = sc_branch_linsolve(b);
  printf("  factor %lu, refactor %lu, solves %lu, Newton %lu\n",
         sc_linsolve_nfactor(l), sc_linsolve_nrefactor(l),
         sc_linsolve_nsolve(l), sc_branch_nnewton(b));
  tu_int("shooting: bordered system is sparse (nnz)", sc_linsolve_nnz(l),
         2 * m + m + (m + 1));
  sc_branch_free(b);
}

int main(void) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  test_cascade(sc_linsolve_dense, 6);
  test_cascade(sc_linsolve_klu, 2);
  test_period3_fold();
  test_cubic_folds(sc_linsolve_dense);
  test_cubic_folds(sc_linsolve_klu);
  test_cusp();
  /* r_3 and r_4 from the 50-digit references of test_cascade */
  test_shooting(sc_linsolve_klu, 4, 3.5, 3.5440903595519228536159659866);
  test_shooting(sc_linsolve_dense, 4, 3.5, 3.5440903595519228536159659866);
  test_shooting(sc_linsolve_klu, 8, 3.56, 3.56440726609543259777355758653);
  test_step_control();
  test_diverging();
  test_tangent_folds();
  test_rejection();
  test_errors();
  test_solve_driver();
  return tu_finish();
}
