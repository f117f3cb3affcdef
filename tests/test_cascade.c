/* The period-doubling cascade of fig 5.8 followed to a period-4096 orbit
 * (docs/accuracy.md, "The extremes": long periods).  bk2, driver frozen,
 * beta = 2.5, phi = 1.25, alpha swept (examples/branch-fig58.ini).
 *
 *   test_cascade          flips up to a_12, the period-4096 orbit (ctest)
 *   test_cascade K        flips up to a_K (2 <= K <= 13), the period-2^K
 *                         orbit (bench_cascade runs K = 13: period 8192)
 *
 * a_k is the alpha where the period-2^k orbit flips (its multiplier
 * reaches -1 and the period-2^(k+1) orbit is born); the period-2^K orbit
 * is the attractor between a_(K-1) and a_K, a window ~1e-8 wide for
 * K = 12.  Each a_k is located with the library's own tools: at a trial
 * alpha the period-2^k orbit is polished by multiple shooting (sc_shoot,
 * KLU above period 16) from the previous trial's orbit, and its
 * multiplier mu (exact derivatives) is driven to -1 by the secant
 * method.  The first trial is a_(k-1) + (a_(k-1) - a_(k-2)) / r, r the
 * last ratio of intervals; the orbit is first taken from the attractor
 * halfway between a_(k-1) and that trial, where it is stable.
 *
 * Checked:
 *  - a_1 .. a_4 against the values the branch task locates for
 *    examples/branch-fig58.ini (docs/branches.md), to 1e-13 (both are
 *    Newton solutions to ~1e-14);
 *  - Feigenbaum's universality: the ratios (a_(k-1) - a_(k-2)) / (a_k -
 *    a_(k-1)) tend to delta = 4.6692016...; the last two are within
 *    2e-3 of it (observed 4.66922 and 4.66915 for K = 12; the bk2 map is
 *    unimodal-like there: its orbit stays away from d*);
 *  - at alpha = (a_(K-1) + a_K) / 2 the orbit polished by multiple
 *    shooting from an attractor sample has minimal period 2^K, a defect
 *    max |d_(i+1) - f(d_i)| within the double map's own noise (below), a
 *    multiplier |mu| < 1 (stable), and the period-2^(K-1) orbit there is
 *    unstable with mu < -1 (past its flip): the window is the right one;
 *  - against the quad path at every point of the orbit: the same
 *    itinerary, f within 4 eps, and the orbit's distance to the exact
 *    period-2^K orbit, to first order: the correction delta solving
 *    delta_(i+1) - f'(d_i) delta_i = r_i, r_i = f_quad(d_i) - d_(i+1) in
 *    quad (one Newton step of multiple shooting in quad, solved around
 *    the cycle), within 1e-15: the double orbit is the true orbit to
 *    rounding (a certificate, since the cycle's Jacobian is invertible
 *    with |1 - mu| ~ 1); the multiplier agrees with quad's to 1e-9
 *    relative (4096 factors, each f' to ~1e-13). */
#include <float.h>
#include <math.h>
#include <quadmath.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "models/bk2_quad.h"
#include "slipcont/shooting.h"
#include "test_util.h"

#define KMAX 13
#define BETA 2.5
#define PHI 1.25
/* Feigenbaum's delta */
#define FEIGENBAUM 4.669201609102990

static double cpu(void) { return (double)clock() / CLOCKS_PER_SEC; }

static sc_map *fig58(int precision) {
  sc_map *m = NULL;
  sc_msg msg = {""};
  sc_accuracy acc;
  sc_accuracy_preset(&acc, "default", NULL);
  acc.precision = precision;
  if (sc_map_alloc("bk2", &acc, &m, &msg) ||
      sc_map_set_param_by_name(m, "beta", BETA, &msg) ||
      sc_map_set_param_by_name(m, "phi", PHI, &msg) ||
      sc_map_set_option(m, "driver", "frozen", &msg)) {
    printf("fig58: %s\n", msg.text);
    sc_map_free(m);
    return NULL;
  }
  return m;
}

/* Iterate n times from x, then store p iterates in o. */
static int attractor(sc_map *m, double x, long n, int p, double *o) {
  sc_map_value v;
  for (long k = 0; k < n; k++) {
    if (sc_map_eval(m, x, SC_EVAL_VALUE, &v, NULL)) return -1;
    x = v.f;
  }
  for (int k = 0; k < p; k++) {
    o[k] = x;
    if (sc_map_eval(m, x, SC_EVAL_VALUE, &v, NULL)) return -1;
    x = v.f;
  }
  return 0;
}

/* Polish the period-p orbit at alpha from o (overwritten with the
 * orbit); its multiplier in *mu. */
static int polish(sc_map *m, sc_shoot *sh, double alpha, double *o, int p,
                  double *mu) {
  sc_msg msg = {""};
  sc_shoot_result r;
  sc_map_set_param_by_name(m, "alpha", alpha, &msg);
  int st = sc_shoot_solve_orbit(sh, o, &r, &msg);
  if (st) {
    printf("  alpha %.17g period %d: %s\n", alpha, p, msg.text);
    return st;
  }
  memcpy(o, sc_shoot_orbit(sh), (size_t)p * sizeof *o);
  *mu = r.multiplier;
  return 0;
}

static int cmp_double(const void *x, const void *y) {
  double u = *(const double *)x, w = *(const double *)y;
  return (u > w) - (u < w);
}

/* Smallest period q dividing p with |o[i + q] - o[i]| <= tol for all
 * i. */
static int min_period(const double *o, int p, double tol) {
  for (int q = 1; q < p; q++) {
    if (p % q) continue;
    int same = 1;
    for (int i = 0; i + q < p && same; i++)
      if (fabs(o[i + q] - o[i]) > tol) same = 0;
    if (same) return q;
  }
  return p;
}

/* Locate a_1 .. a_kmax; *seed ends on the last orbit.  Returns 0 or a
 * status. */
static int locate_flips(sc_map *m, int kmax, double *a, double *o,
                        double *seed) {
  sc_msg msg = {""};
  double t0 = cpu();
  for (int k = 1; k <= kmax; k++) {
    int p = 1 << k;
    double trial;
    if (k == 1)
      trial = a[1];
    else {
      double r = k < 4 ? FEIGENBAUM
                       : (a[k - 2] - a[k - 3]) / (a[k - 1] - a[k - 2]);
      trial = a[k - 1] + (a[k - 1] - a[k - 2]) / r;
    }
    double amid = k > 1 ? 0.5 * (a[k - 1] + trial) : 3.0;
    sc_map_set_param_by_name(m, "alpha", amid, &msg);
    if (attractor(m, *seed, 200L * p + 20000, p, o)) {
      printf("k = %d: the map is undefined on the attractor at alpha %.17g\n",
             k, amid);
      return SC_EUNDEF;
    }
    sc_shoot *sh = NULL;
    int st = sc_shoot_alloc(m, p, SC_SHOOT_MULTIPLE, NULL, &sh, &msg);
    double x0 = amid, mu0, x1 = trial, mu1 = 0;
    if (!st) st = polish(m, sh, x0, o, p, &mu0);
    if (!st && !tu_true(min_period(o, p, 0) == p && fabs(mu0) < 1,
                        "k = %d: the attractor at alpha %.17g is the stable "
                        "period-%d orbit (minimal period %d, mu %.6g)",
                        k, amid, p, min_period(o, p, 0), mu0))
      st = SC_ENOCONV;
    if (!st) st = polish(m, sh, x1, o, p, &mu1);
    int it = 0;
    for (; !st && it < 100 && mu1 != mu0; it++) {
      double x2 = x1 - (mu1 + 1) * (x1 - x0) / (mu1 - mu0);
      x0 = x1, mu0 = mu1, x1 = x2;
      st = polish(m, sh, x1, o, p, &mu1);
      if (fabs(x1 - x0) <= 2 * DBL_EPSILON * x1) break;
    }
    sc_shoot_free(sh);
    if (st) return st;
    a[k] = x1;
    *seed = o[0];
    printf("a_%d = %.17g (period %d flips; mu + 1 = %.3g after %d secant "
           "steps)",
           k, a[k], p, mu1 + 1, it + 1);
    if (k >= 3) printf(", ratio %.6g", (a[k - 1] - a[k - 2]) / (a[k] - a[k - 1]));
    printf(" (%.2f s)\n", cpu() - t0);
  }
  return 0;
}

/* The orbit o of period p at alpha against the quad path (see the head
 * comment). */
static void against_quad(double alpha, const double *o, int p, double mu) {
  sc_bk2q_params qp = {alpha, BETA, PHI, 0, 1, 256};
  sc_map *md = fig58(SC_PRECISION_DOUBLE);
  sc_map_set_param_by_name(md, "alpha", alpha, NULL);
  sc_quad *r = malloc((size_t)p * sizeof *r), *g = malloc((size_t)p * sizeof *g);
  double ef = 0, rmax = 0;
  int same = 1, ok = 1;
  sc_quad muq = 1;
  for (int i = 0; i < p && ok; i++) {
    sc_bk2q_value q;
    sc_map_value v;
    sc_msg msg = {""};
    if (sc_bk2q_eval(&qp, o[i], SC_BK2Q_NDIR, &q, &msg) ||
        sc_map_eval(md, o[i], SC_EVAL_ITINERARY, &v, &msg)) {
      ok = tu_true(0, "point %d: %s", i, msg.text);
      break;
    }
    same = same && strcmp(q.itinerary, v.itinerary) == 0;
    /* in units of the promise of the default preset (docs/accuracy.md):
     * 64 eps S (1 + |f'|) n, S = 1 + beta + (1 + alpha)|d| */
    double S = 1 + BETA + (1 + alpha) * fabs(o[i]);
    ef = fmax(ef, fabs(v.f - (double)q.f) /
                      (64 * DBL_EPSILON * S * (1 + fabs((double)q.df[0])) *
                       q.nphases));
    r[i] = q.f - o[(i + 1) % p];
    rmax = fmax(rmax, fabs((double)r[i]));
    g[i] = q.df[0];
    muq *= q.df[0];
  }
  if (ok) {
    /* delta_(i+1) = g_i delta_i + r_i around the cycle: delta_0 =
     * s / (1 - mu), s = delta_p from delta_0 = 0 */
    sc_quad s = 0, dmax = 0;
    for (int i = 0; i < p; i++) s = g[i] * s + r[i];
    sc_quad dl = s / (1 - muq);
    for (int i = 0; i < p; i++) {
      dmax = fmaxq(dmax, fabsq(dl));
      dl = g[i] * dl + r[i];
    }
    /* the closest two points of the orbit */
    double *srt = malloc((size_t)p * sizeof *srt), gap = HUGE_VAL;
    memcpy(srt, o, (size_t)p * sizeof *srt);
    qsort(srt, (size_t)p, sizeof *srt, cmp_double);
    for (int i = 1; i < p; i++) gap = fmin(gap, srt[i] - srt[i - 1]);
    double split = 0;
    for (int i = 0; i < p / 2; i++) split = fmax(split, fabs(o[i + p / 2] - o[i]));
    free(srt);
    printf("quad: max |f - f_quad| = %.3g promise, max |f_quad(d_i) - "
           "d_(i+1)| = %.3g, distance to the exact orbit %.3g (closest two "
           "points %.3g apart, largest |d_(i+p/2) - d_i| %.3g), multiplier %.17g (double %.17g)\n",
           ef, rmax, (double)dmax, gap, split, (double)muq, mu);
    tu_true(same, "quad: the same itinerary at every point");
    tu_true(ef <= 1, "quad: f within the default preset's promise (worst "
                     "%.3g of it)", ef);
    /* the cycle's Jacobian amplifies the residual (~5e-16) by the
     * largest partial product of slopes along the orbit (~2e4 at period
     * 4096) */
    tu_close("quad: distance to the exact orbit (one quad Newton step)",
             (double)dmax, 0, 1e-10);
    /* points closer than twice the distance may be one in the exact
     * orbit: its minimal period is p all the same */
    tu_int("quad: minimal period of the exact orbit",
           min_period(o, p, 2 * (double)dmax), p);
    /* evaluated 1e-11 from the exact orbit, each f' is off by f'' delta
     * (relative ~1e-12); 4096 of them */
    tu_rel("quad: multiplier", mu, (double)muq, 1e-7);
  }
  free(r);
  free(g);
  sc_map_free(md);
}

int main(int argc, char **argv) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  int kmax = argc > 1 ? atoi(argv[1]) : 12;
  if (kmax < 2 || kmax > KMAX) {
    fprintf(stderr, "usage: test_cascade [K 2..%d]\n", KMAX);
    return 2;
  }
  sc_map *m = fig58(SC_PRECISION_DOUBLE);
  if (!tu_true(m != NULL, "bk2 map")) return tu_finish();
  double a[KMAX + 1] = {0};
  /* The cascade starts at the flip of the period-2 orbit (the flip of the
   * period-1 orbit at alpha 2.8252 is one where it gains stability); the
   * branch task's a_1 and start (alpha 3, d 0.2253, period 2) seed it. */
  a[1] = 3.0568462300530532;
  /* only for a_2's first trial: the period-1 orbit's flip */
  a[0] = 2.8252261002006978;
  double seed = 0.2253;
  int P = 1 << kmax;
  double *o = malloc((size_t)P * sizeof *o);
  int st = locate_flips(m, kmax, a, o, &seed);
  tu_int("flips located", st, SC_OK);
  if (st) goto done;
  static const double branch[] = {0, 3.0568462300530532, 3.1525203451104455,
                                  3.1655755301920836, 3.1678370469376644};
  for (int k = 1; k <= 4 && k <= kmax; k++) {
    char what[64];
    snprintf(what, sizeof what, "a_%d against the branch task", k);
    tu_close(what, a[k], branch[k], 1e-13);
  }
  for (int k = kmax - 1; k <= kmax; k++)
    if (k >= 9) {
      char what[64];
      snprintf(what, sizeof what, "ratio at a_%d: Feigenbaum's delta", k);
      tu_close(what, (a[k - 1] - a[k - 2]) / (a[k] - a[k - 1]), FEIGENBAUM,
               2e-3);
    }

  /* the period-P orbit halfway through its window */
  double alpha = 0.5 * (a[kmax - 1] + a[kmax]);
  sc_msg msg = {""};
  sc_shoot *sh = NULL;
  sc_shoot_result res;
  sc_map_set_param_by_name(m, "alpha", alpha, &msg);
  st = attractor(m, seed, 200L * P + 20000, P, o);
  if (!st) st = sc_shoot_alloc(m, P, SC_SHOOT_MULTIPLE, NULL, &sh, &msg);
  if (!st) st = sc_shoot_solve_orbit(sh, o, &res, &msg);
  printf("alpha = %.17g (window %.3g wide): %s\n", alpha, a[kmax] - a[kmax - 1],
         msg.text);
  tu_int("period-2^K orbit by multiple shooting", st, SC_OK);
  if (!st) {
    memcpy(o, sc_shoot_orbit(sh), (size_t)P * sizeof *o);
    double def = 0, omax = 0;
    sc_map_value v;
    for (int i = 0; i < P; i++) {
      sc_map_eval(m, o[i], SC_EVAL_VALUE, &v, NULL);
      def = fmax(def, fabs(o[(i + 1) % P] - v.f));
      omax = fmax(omax, fabs(o[i]));
    }
    printf("period %d: backend %s, %d Newton iterations, multiplier %.17g, "
           "defect %.3g, d in [%.6g, %.6g]\n",
           P, sc_linsolve_type_name(sc_shoot_linsolve_type(sh)),
           res.iterations, res.multiplier, def, o[0], omax);
    tu_int("minimal period", min_period(o, P, 0), P);
    /* Newton zeroes the residual of a smooth map; what is left is the
     * double map's rounding about the exact one, which test_quad bounds
     * by 16 eps (1 + alpha)(1 + |d|), twice (the orbit's point and f at
     * the one before).  Measured: 0 or 8.3e-16 (3.75 eps), as the map's
     * last bits fall; an orbit Newton did not converge is far beyond. */
    tu_close("defect max |d_(i+1) - f(d_i)|", def, 0,
             32 * DBL_EPSILON * (1 + alpha) * (1 + omax));
    tu_true(fabs(res.multiplier) < 1, "stable: |multiplier| = %.6g < 1",
            fabs(res.multiplier));
    /* the half-period orbit there is past its flip */
    sc_shoot *sh2 = NULL;
    double mu2 = 0, *o2 = malloc((size_t)P / 2 * sizeof *o2);
    memcpy(o2, o, (size_t)P / 2 * sizeof *o2);
    st = sc_shoot_alloc(m, P / 2, SC_SHOOT_MULTIPLE, NULL, &sh2, &msg);
    if (!st) st = polish(m, sh2, alpha, o2, P / 2, &mu2);
    tu_true(!st && mu2 < -1 && min_period(o2, P / 2, 0) == P / 2,
            "the period-%d orbit at alpha is unstable past its flip (status "
            "%d, multiplier %.6g)",
            P / 2, st, mu2);
    sc_shoot_free(sh2);
    free(o2);
    against_quad(alpha, o, P, res.multiplier);
  }
  sc_shoot_free(sh);
done:
  free(o);
  sc_map_free(m);
  return tu_finish();
}
