/* Jets (src/hybrid/jet.h) and the exact second and third derivatives of
 * the event map: jet arithmetic against closed forms; bk2's f_dd, f_dp,
 * f_ddd, f_ddp against Richardson differences of exact lower derivatives
 * at hundreds of points (driver moving and frozen, beta 1, 2.5, 3.2,
 * near d* and near itinerary changes); the jets' first derivatives
 * against the duals'; NaN where f is not twice differentiable; the chain
 * rule for f^n; the smooth maps' closed forms. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hybrid/jet.h"
#include "models/bk2_jet.h"
#include "slipcont/bk2.h"
#include "slipcont/map.h"
#include "test_util.h"

/* ---- jet arithmetic --------------------------------------------------- */

/* f(x, y) = sin(x y) sqrt(x) / (1 + y) at (x, y) = (0.7385, 1.2385),
 * derivatives against their closed forms written out by hand through
 * u = sin(x y), w = sqrt(x), z = 1/(1 + y). */
static void test_jet_arith(void) {
  double x = 0.7385, y = 1.2385;
  sc_jet X = sc_jvar(x, 0, 2), Y = sc_jvar(y, 1, 2), s, c;
  sc_jsincos(sc_jmul(X, Y, 2), 2, &s, &c);
  sc_jet F = sc_jdiv(sc_jmul(s, sc_jsqrt(X, 2), 2), sc_jaddc(Y, 1), 2);
  double S = sin(x * y), C = cos(x * y), w = sqrt(x), z = 1 / (1 + y);
  /* u = sin(xy): u_x = yC, u_xx = -y^2 S, u_xxx = -y^3 C, u_y = xC,
   * u_xy = C - xyS, u_xxy = -2yS - xy^2 C. */
  double u = S, ux = y * C, uxx = -y * y * S, uxxx = -y * y * y * C;
  double uy = x * C, uxy = C - x * y * S, uxxy = -2 * y * S - x * y * y * C;
  double W = w, Wx = 0.5 / w, Wxx = -0.25 / (w * x), Wxxx = 0.375 / (w * x * x);
  /* g = u W; f = g z, z depends on y only: z_y = -z^2. */
  double g = u * W, gx = ux * W + u * Wx;
  double gxx = uxx * W + 2 * ux * Wx + u * Wxx;
  double gxxx = uxxx * W + 3 * uxx * Wx + 3 * ux * Wxx + u * Wxxx;
  double gy = uy * W, gxy = uxy * W + uy * Wx;
  double gxxy = uxxy * W + 2 * uxy * Wx + uy * Wxx;
  double zy = -z * z;
  tu_rel("jet f", F.v, g * z, 4 * DBL_EPSILON);
  tu_rel("jet f_x", F.g[0], gx * z, 16 * DBL_EPSILON);
  tu_rel("jet f_y", F.g[1], gy * z + g * zy, 16 * DBL_EPSILON);
  tu_rel("jet f_xx", F.h[0][0], gxx * z, 32 * DBL_EPSILON);
  tu_rel("jet f_xy", F.h[0][1], gxy * z + gx * zy, 32 * DBL_EPSILON);
  tu_rel("jet f_yx = f_xy", F.h[1][0], F.h[0][1], 4 * DBL_EPSILON);
  tu_rel("jet f_xxx", F.t[0], gxxx * z, 64 * DBL_EPSILON);
  tu_rel("jet f_xxy", F.t[1], gxxy * z + gxx * zy, 64 * DBL_EPSILON);
}

/* ---- bk2 ------------------------------------------------------------- */

typedef struct {
  double alpha, beta, v;
  const char *driver;
  double dlo, dhi;
} pset;

static const pset sets[] = {
    {2.9, 1, 0.02, "moving", -0.3, 0.3},
    {3.2196, 2.5, 0.025, "frozen", -0.25, 0.45},
    {5.7, 3.2, 0.025, "frozen", -0.2, 0.45},
    {3.3, 2.5, 0.03, "moving", -0.25, 0.45},
};
#define NSETS (sizeof sets / sizeof sets[0])

static sc_map *make(const pset *s) {
  sc_map *m;
  sc_msg msg;
  if (sc_map_alloc("bk2", NULL, &m, &msg)) return NULL;
  sc_map_set_param_by_name(m, "alpha", s->alpha, &msg);
  sc_map_set_param_by_name(m, "beta", s->beta, &msg);
  sc_map_set_param_by_name(m, "v", s->v, &msg);
  sc_map_set_option(m, "driver", s->driver, &msg);
  return m;
}

/* Evaluate with second derivatives; itin receives the itinerary. */
static int ev2(sc_map *m, double d, sc_map_value *v) {
  return sc_map_eval(m, d, SC_EVAL_DERIV2 | SC_EVAL_ITINERARY, v, NULL);
}

/* A quantity q(d) of one evaluation (which: 0 f_d, 1 f_dd, 2 f_dp[k]). */
static double pick(const sc_map_value *v, int which, int k) {
  return which == 0 ? v->dfdd : which == 1 ? v->d2fdd2 : v->dfdp[k];
}

/* |R(h) - D(h/2)|: an estimate of the error of the unextrapolated
 * difference, so a bound on the extrapolated one's, set by rich_*(). */
static double rich_err;

/* Richardson-extrapolated central difference of pick(which, k) in d with
 * step h (error O(h^4)); NAN if an itinerary differs from `itin`. */
static double rich_d(sc_map *m, double d, double h, int which, int k,
                     const char *itin) {
  double D[2];
  for (int r = 0; r < 2; r++) {
    double hh = h / (1 << r);
    sc_map_value a, b;
    if (ev2(m, d + hh, &a) || ev2(m, d - hh, &b)) return NAN;
    if (strcmp(a.itinerary, itin) || strcmp(b.itinerary, itin)) return NAN;
    D[r] = (pick(&a, which, k) - pick(&b, which, k)) / (2 * hh);
  }
  rich_err = fabs(D[1] - D[0]) / 3; /* the extrapolation's own size */
  return (4 * D[1] - D[0]) / 3;
}

/* The same in parameter ip, relative step h. */
static double rich_p(sc_map *m, double d, int ip, double h, int which,
                     const char *itin) {
  double p0 = sc_map_get_param(m, (size_t)ip), D[2];
  for (int r = 0; r < 2; r++) {
    double hh = h * p0 / (1 << r);
    sc_map_value a, b;
    sc_map_set_param(m, (size_t)ip, p0 + hh, NULL);
    int fa = ev2(m, d, &a);
    sc_map_set_param(m, (size_t)ip, p0 - hh, NULL);
    int fb = ev2(m, d, &b);
    sc_map_set_param(m, (size_t)ip, p0, NULL);
    if (fa || fb || strcmp(a.itinerary, itin) || strcmp(b.itinerary, itin))
      return NAN;
    D[r] = (pick(&a, which, 0) - pick(&b, which, 0)) / (2 * hh);
  }
  rich_err = fabs(D[1] - D[0]) / 3;
  return (4 * D[1] - D[0]) / 3;
}

/* Worst relative error |exact - diff| / (|exact| + scale + 1e6 err)
 * over the checks: scale is the size of the quantity differenced divided
 * by the step (its rounding floor), err the difference's own error
 * estimate (large only within ~1e-6 of a grazing, where the stencil
 * cannot be both short and above rounding).  An error in a second-order
 * event term is of relative size one and still fails. */
static double worst[5];
static long nchecked[5], nskipped;
static double cur_d;

static void check(int slot, double exact, double diff, double scale) {
  if (isnan(diff)) {
    nskipped++;
    return;
  }
  double e = fabs(exact - diff) / (fabs(exact) + scale + 1e6 * rich_err);
  if (!(e <= worst[slot])) {
    worst[slot] = e;
    if (getenv("JET_DEBUG"))
      printf("slot %d d %.17g exact %.10g diff %.10g scale %g err %g\n", slot,
             cur_d, exact, diff, scale, rich_err);
  }
  nchecked[slot]++;
}

/* pchecks = 0: skip the differences in the parameters, whose stencil
 * cannot resolve a border 1e-5 away (the parameters move it); f_dp is
 * then checked through the symmetry f_dp = (f_p)_d alone. */
static void check_point(sc_map *m, double d, double dstar, int pchecks) {
  sc_map_value v;
  if (ev2(m, d, &v)) return;
  if (isnan(v.d2fdd2)) return;
  cur_d = d;
  /* Steps small against the local length scale: the distance to d*
   * (where f' ~ |d - d*|^(-1/2) with the driver frozen) and the ratios
   * f'/f'', f''/f''' (which shrink like the distance to a grazing);
   * itinerary changes within the stencil skip the point.  The rounding
   * floor of a difference is ~1e-7 |q| / h where q is good to ~1e-13
   * relative (event times to event-rtol), and Richardson weights it by
   * ~1/h (the tolerance is 1e-6 of the floor).  First derivatives get
   * 1e-4 |q| / h: where an event's slope is small, its rounding makes f'
   * good to ~1e-10 only (alpha 5.7, beta 3.2, d near 0.15, itinerary
   * 1-12-2-12-1: second differences of f' 1e-9 apart 5.8e4 ulps rms and
   * 2.1e5 at most, 4.6e-11), so that the difference of f' there moves by
   * ~1e-6 of f'' with the last bits of the event times.  An error in a
   * second-order term is still of relative size ~0.1 against this. */
  double L = fabs(d - dstar);
  if (v.d2fdd2 != 0) L = fmin(L, fabs(v.dfdd / v.d2fdd2));
  if (v.d3fdd3 != 0) L = fmin(L, fabs(v.d2fdd2 / v.d3fdd3));
  double h = fmin(2e-4, 0.02 * L);
  check(0, v.d2fdd2, rich_d(m, d, h, 0, 0, v.itinerary),
        fabs(v.dfdd) * 1e-4 / h);
  check(1, v.d3fdd3, rich_d(m, d, h, 1, 0, v.itinerary),
        fabs(v.d2fdd2) * 1e-7 / h);
  for (int k = 0; k < 4; k++) {
    double p = sc_map_get_param(m, (size_t)k);
    /* parameters move the nearest border faster than d does */
    double hp = fmin(1e-5, 0.002 * L / p); /* relative */
    if (pchecks) {
      check(2, v.d2fddp[k], rich_p(m, d, k, hp, 0, v.itinerary),
            fabs(v.dfdd) * 1e-4 / (hp * p));
      check(3, v.d3fdd2p[k], rich_p(m, d, k, hp, 1, v.itinerary),
            fabs(v.d2fdd2) * 1e-7 / (hp * p));
    }
    /* symmetry of the Hessian: d/dd of f_p equals d/dp of f_d */
    check(4, v.d2fddp[k], rich_d(m, d, h, 2, k, v.itinerary),
          fabs(v.dfdp[k]) * 1e-4 / h);
  }
}

/* The grid, plus points near each itinerary change of the grid (located
 * by bisection) and near d*: there the derivatives grow without bound. */
static void test_bk2_differences(void) {
  for (size_t s = 0; s < NSETS; s++) {
    sc_map *m = make(&sets[s]);
    double dstar = sc_bk2_dstar(sets[s].alpha, sets[s].beta);
    int n = 60;
    char prev[SC_ITIN_LEN] = "";
    double dprev = NAN;
    for (int i = 0; i <= n; i++) {
      double d = sets[s].dlo + (sets[s].dhi - sets[s].dlo) * i / n + 1.2385e-4;
      check_point(m, d, dstar, 1);
      sc_map_value v;
      if (ev2(m, d, &v)) continue;
      if (i && strcmp(prev, v.itinerary) && !isnan(dprev)) {
        /* bisect the change to 1e-9, then test 1e-3..1e-6 away */
        double a = dprev, b = d;
        for (int it = 0; it < 40 && b - a > 1e-9; it++) {
          double c = 0.5 * (a + b);
          sc_map_value w;
          if (ev2(m, c, &w)) break;
          if (strcmp(w.itinerary, prev) == 0)
            a = c;
          else
            b = c;
        }
        for (double off = 1e-3; off >= 1e-6; off /= 10) {
          check_point(m, a - off, a, off > 2e-5);
          check_point(m, b + off, b, off > 2e-5);
        }
      }
      strcpy(prev, v.itinerary);
      dprev = d;
    }
    for (double off = 1e-2; off >= 1e-6; off /= 10) {
      check_point(m, dstar - off, dstar, 1);
      check_point(m, dstar + off, dstar, 1);
    }
    sc_map_free(m);
  }
  /* Richardson at these steps leaves ~1e-8 relative (O(h^4) truncation
   * against derivatives that grow like |d - d*|^(-n+1/2)); an error in a
   * second-order event term is of relative size one. */
  const char *what[5] = {"f_dd", "f_ddd", "f_ddp", "f_dddp", "f_dpd sym"};
  for (int k = 0; k < 5; k++) {
    char buf[96];
    snprintf(buf, sizeof buf, "bk2 %s vs Richardson (worst rel, %ld points)",
             what[k], nchecked[k]);
    /* parameter stencils are cut short near borders: 1e-5 there */
    tu_close(buf, worst[k], 0, k == 2 || k == 3 ? 1e-5 : 1e-6);
  }
  tu_true(nchecked[0] >= 200, "at least 200 points checked (%ld; %ld skipped)",
          nchecked[0], nskipped);
}

/* The jets' first derivatives equal the duals' to rounding, and f_dd is
 * NaN exactly where f' is. */
static void test_bk2_grad(void) {
  double worst_g = 0;
  long n = 0, nan_mismatch = 0;
  for (size_t s = 0; s < NSETS; s++) {
    bk2_inst b;
    memset(&b, 0, sizeof b);
    double p[5] = {sets[s].alpha, sets[s].beta, 1.25, sets[s].v, 1};
    int opt[3] = {strcmp(sets[s].driver, "frozen") == 0, 0, 0};
    sc_accuracy acc;
    sc_accuracy_preset(&acc, "default", NULL);
    if (sc_model_bk2.setup(&b, p, opt, &acc, NULL)) continue;
    for (int i = 0; i <= 100; i++) {
      double d = sets[s].dlo + (sets[s].dhi - sets[s].dlo) * i / 100 + 3.7e-5;
      sc_map_value v1, v2;
      double g[5];
      memset(&v1, 0, sizeof v1);
      memset(&v2, 0, sizeof v2);
      if (sc_model_bk2.eval(&b, d, SC_EVAL_DERIV, &v1, NULL)) continue;
      if (sc_bk2_eval_jet(&b, d, SC_EVAL_DERIV, &v2, g, NULL)) continue;
      /* f'' must be NaN exactly where f' is */
      nan_mismatch += isnan(v1.dfdd) != isnan(v2.d2fdd2);
      if (isnan(g[0])) continue;
      double ref[5] = {v1.dfdd, v1.dfdp[0], v1.dfdp[1], v1.dfdp[2], v1.dfdp[3]};
      if (v1.neutral) ref[0] = g[0]; /* the duals are overridden to 1 */
      for (int k = 0; k < 5; k++)
        worst_g = fmax(worst_g, fabs(g[k] - ref[k]) / (1 + fabs(ref[k])));
      n++;
    }
    if (b.num) sc_model_bk2.release(&b);
  }
  /* the same closed forms in another order of operations */
  tu_close("bk2 jet gradient vs duals (worst rel)", worst_g, 0, 1e-12);
  tu_true(n >= 300, "gradient compared at %ld points", n);

  tu_int("points where exactly one of f', f'' is NaN", nan_mismatch, 0);
  /* At d* itself (frozen driver) both blocks start together: the map
   * is evaluated on the SLIP12 side, and f'' is finite where f' is. */
  pset fz = {3.2196, 2.5, 0.025, "frozen", 0, 0};
  sc_map *m = make(&fz);
  sc_map_value v;
  double ds = sc_bk2_dstar(fz.alpha, fz.beta);
  int st = ev2(m, ds, &v);
  tu_true(st == SC_OK && isnan(v.dfdd) == isnan(v.d2fdd2),
          "at d* (frozen): f' %g and f'' %g NaN together", v.dfdd, v.d2fdd2);
  /* Numerical flows refuse second derivatives with a message. */
  sc_msg msg;
  sc_map_set_option(m, "flows", "numerical", NULL);
  st = sc_map_eval(m, 0.01, SC_EVAL_DERIV2, &v, &msg);
  tu_true(st == SC_EINVAL && strstr(msg.text, "flows = exact"),
          "numerical flows refuse DERIV2: %d %s", st, msg.text);
  sc_map_free(m);
}

/* A neutral iterate (one block slips alone): f = d + c, so f'' = 0. */
static void test_bk2_neutral(void) {
  pset sym = {3, 1, 0.025, "moving", 0, 0};
  sc_map *m = make(&sym);
  int found = 0;
  for (int i = 0; i < 200 && !found; i++) {
    double d = -0.3 + 0.003 * i;
    sc_map_value v;
    if (ev2(m, d, &v) || !v.neutral) continue;
    found = 1;
    tu_close("neutral iterate f''", v.d2fdd2, 0, 0);
    tu_close("neutral iterate f'''", v.d3fdd3, 0, 0);
  }
  tu_true(found, "a neutral iterate found at beta = 1");
  sc_map_free(m);
}

/* The chain rule for f^n: second and third derivatives of f^3 against
 * differences of exact lower ones, on bk2 and on the logistic map. */
static void test_chain(void) {
  const char *models[2] = {"logistic", "bk2"};
  double x0[2] = {0.2385, -0.0153};
  for (int k = 0; k < 2; k++) {
    sc_map *m;
    sc_map_alloc(models[k], NULL, &m, NULL);
    if (k == 0)
      sc_map_set_param(m, 0, 3.7385, NULL);
    else {
      sc_map_set_param_by_name(m, "alpha", 3, NULL);
      sc_map_set_param_by_name(m, "v", 0.025, NULL);
    }
    int n = 3;
    double x = x0[k], h = 1e-5;
    sc_map_value v, a, b, a2, b2;
    unsigned fl = SC_EVAL_DERIV2;
    sc_map_iterate(m, x, n, fl, &v, NULL);
    sc_map_iterate(m, x + h, n, fl, &a, NULL);
    sc_map_iterate(m, x - h, n, fl, &b, NULL);
    sc_map_iterate(m, x + h / 2, n, fl, &a2, NULL);
    sc_map_iterate(m, x - h / 2, n, fl, &b2, NULL);
#define RICH(field)                                                            \
  ((4 * (a2.field - b2.field) / h - (a.field - b.field) / (2 * h)) / 3)
    double fdd = RICH(dfdd), fddd = RICH(d2fdd2), fdp = RICH(dfdp[0]);
    double fddp0 = RICH(d2fddp[0]);
#undef RICH
    char buf[80];
    snprintf(buf, sizeof buf, "%s f^3: f_dd vs differences", models[k]);
    tu_rel(buf, v.d2fdd2, fdd, 1e-7);
    snprintf(buf, sizeof buf, "%s f^3: f_ddd vs differences", models[k]);
    tu_rel(buf, v.d3fdd3, fddd, 1e-7);
    snprintf(buf, sizeof buf, "%s f^3: f_dp vs differences", models[k]);
    tu_rel(buf, v.d2fddp[0], fdp, 1e-7);
    snprintf(buf, sizeof buf, "%s f^3: f_ddp vs differences", models[k]);
    tu_rel(buf, v.d3fdd2p[0], fddp0, 1e-6);
    sc_map_free(m);
  }
}

/* The smooth maps' closed forms: gpd at x = 0.3385, mu = (0.2, -0.7). */
static void test_gpd(void) {
  sc_map *m;
  sc_map_alloc("gpd", NULL, &m, NULL);
  double mu1 = 0.2, mu2 = -0.7, x = 0.3385;
  sc_map_set_param(m, 0, mu1, NULL);
  sc_map_set_param(m, 1, mu2, NULL);
  sc_map_value v;
  sc_map_eval(m, x, SC_EVAL_DERIV2, &v, NULL);
  double x2 = x * x;
  tu_rel("gpd f", v.f, -(1 + mu1) * x + mu2 * x2 * x - x2 * x2 * x, 1e-15);
  tu_rel("gpd f_x", v.dfdd, -(1 + mu1) + 3 * mu2 * x2 - 5 * x2 * x2, 1e-15);
  tu_rel("gpd f_xx", v.d2fdd2, 6 * mu2 * x - 20 * x2 * x, 1e-15);
  tu_rel("gpd f_xxx", v.d3fdd3, 6 * mu2 - 60 * x2, 1e-15);
  tu_rel("gpd f_xmu2", v.d2fddp[1], 3 * x2, 1e-15);
  tu_rel("gpd f_xxmu2", v.d3fdd2p[1], 6 * x, 1e-15);
  /* the period-2 map at the flip (mu1 = 0) is x - 2 mu2 x^3 + O(x^5) */
  sc_map_set_param(m, 0, 0, NULL);
  sc_map_iterate(m, 0, 2, SC_EVAL_DERIV2, &v, NULL);
  tu_close("gpd f^2 at 0: f_x", v.dfdd, 1, 1e-15);
  tu_close("gpd f^2 at 0: f_xxx = -12 mu2", v.d3fdd3, -12 * mu2, 1e-14);
  sc_map_free(m);
}

int main(void) {
  test_jet_arith();
  test_gpd();
  test_chain();
  test_bk2_neutral();
  test_bk2_grad();
  test_bk2_differences();
  return tu_finish();
}
