/* Certified first-root location (src/hybrid/guard.c) against an
 * independent dense search, on random guards and on constructed
 * near-tangent cases that reach zero by 1e-12 or miss it by 1e-12; the
 * cos and sin a root hands over (sc_root's cs, sn, from the refinement
 * and from the closed form) against libm at the root; the search's own sin and cos (src/hybrid/trig.h) against libm. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hybrid/hybrid_impl.h"
#include "guard_scalar.h"
#include "hybrid/trig.h"
#include "slipcont/hybrid.h"
#include "test_util.h"

/* A reproducible uniform deviate in [lo, hi) (tests own their RNG state). */
static unsigned long long rng = 0x9e3779b97f4a7c15ULL;
static double uni(double lo, double hi) {
  rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
  return lo + (hi - lo) * (double)(rng >> 11) / 9007199254740992.0;
}

static double geval(const sc_guard *g, double t) {
  double v;
  sc_guard_eval(g, t, &v, NULL, NULL);
  return v;
}

/* Independent reference: sample every `h`; a sign change brackets a root;
 * between samples, a local maximum of a negative stretch is found by
 * golden-section search and a non-negative maximum counts as a root.  Far
 * slower than the certified march, and with no bound used anywhere. */
static double dense_first_root(const sc_guard *g, double tmax, int skip) {
  const double h = 1e-3;
  double t0 = skip ? h * 1e-3 : 0, g0 = geval(g, t0);
  if (skip) g0 = geval(g, t0);
  for (double t1 = t0 + h;; t1 += h) {
    if (t1 > tmax) t1 = tmax;
    double g1 = geval(g, t1);
    if ((g0 > 0) != (g1 > 0) || g1 == 0) {
      double lo = t0, hi = t1, glo = g0;
      for (int i = 0; i < 200; i++) {
        double m = 0.5 * (lo + hi), gm = geval(g, m);
        if ((gm > 0) == (glo > 0)) lo = m, glo = gm;
        else hi = m;
      }
      return 0.5 * (lo + hi);
    }
    /* a touch inside (t0, t1) without a sign change at the samples: only
     * possible where g turns toward zero, i.e. g' changes sign there */
    double d0, d1;
    sc_guard_eval(g, t0, NULL, &d0, NULL);
    sc_guard_eval(g, t1, NULL, &d1, NULL);
    if ((d0 > 0) == (d1 > 0)) {
      if (t1 >= tmax) return -1;
      t0 = t1, g0 = g1;
      continue;
    }
    double a = t0, b = t1, phi = 0.5 * (sqrt(5.0) - 1);
    double sign = g0 > 0 ? -1 : 1; /* look for the extremum toward zero */
    for (int i = 0; i < 100; i++) {
      double c = b - phi * (b - a), d = a + phi * (b - a);
      if (sign * geval(g, c) > sign * geval(g, d)) b = d;
      else a = c;
    }
    double te = 0.5 * (a + b);
    if (sign * geval(g, te) >= 0 && te > t0 && te < t1) return te;
    if (t1 >= tmax) return -1;
    t0 = t1, g0 = g1;
  }
}

/* sc_fast_sincos against libm: within SC_FAST_TRIG_ULPS ulps of 1 on
 * random arguments in [-1000, 1000], next to multiples of pi/2 (where the
 * reduction cancels) and at 0; libm's own values beyond its range. */
static void test_fast_sincos(void) {
  double worst = 0;
  for (int i = 0; i < 1000000; i++) {
    double x = i % 4 == 0   ? uni(-1000, 1000)
               : i % 4 == 1 ? uni(-2, 2)
               : i % 4 == 2 ? uni(-40, 40)
                            : (double)(i % 1000 - 500) * (SC_PI / 2) *
                                  (1 + uni(-1e-15, 1e-15));
    double s, c;
    sc_fast_sincos(x, &s, &c);
    worst = fmax(worst, fmax(fabs(s - sin(x)), fabs(c - cos(x))));
  }
  tu_true(worst <= SC_FAST_TRIG_ULPS * DBL_EPSILON,
          "fast sincos: largest difference from libm %.3g (bound %.3g)",
          worst, SC_FAST_TRIG_ULPS * DBL_EPSILON);
  double s, c;
  sc_fast_sincos(0, &s, &c);
  tu_true(s == 0 && c == 1, "fast sincos at 0: (%g, %g)", s, c);
  sc_fast_sincos(3e7, &s, &c);
  tu_true(s == sin(3e7) && c == cos(3e7), "fast sincos beyond its range: libm");
}

/* One ulp of the exact value v (long double), in double. */
static double ulp_of(long double v) {
  double d = (double)v;
  return nextafter(fabs(d), INFINITY) - fabs(d);
}

/* sc_atan2 against long double's atan2l (64-bit significand: its own
 * error is 1/2048 of a double's ulp): within SC_ATAN2_ULPS ulps of the
 * result on 4e6 arguments spread over every octant, next to the axes and
 * diagonals and to the table's points (where the reduction's difference
 * is smallest), over 60 binades of scale; libm's own values at zeros,
 * infinities, NaN and extreme ratios. */
static void test_atan2(void) {
  double worst = 0, wx = 0, wy = 0;
  for (int i = 0; i < 4000000; i++) {
    double ang = uni(-SC_PI, SC_PI), rad = ldexp(1, (int)uni(-30, 30));
    double x = rad * cos(ang), y = rad * sin(ang);
    if (i % 5 == 1) y = x * (1 + uni(-1e-12, 1e-12)); /* a diagonal */
    if (i % 5 == 2) y = x * uni(-1e-9, 1e-9);         /* an axis */
    if (i % 5 == 3) /* next to a table point k / 32 of the ratio */
      y = x * ((double)(i % 33) / 32 + uni(-1e-14, 1e-14)) *
          (i % 2 ? 1 : -1);
    if (i % 5 == 4) x = y * uni(-1e-6, 1e-6);         /* the other axis */
    long double ref = atan2l((long double)y, (long double)x);
    double e = (double)fabsl((long double)sc_atan2(y, x) - ref) / ulp_of(ref);
    if (e > worst) worst = e, wx = x, wy = y;
  }
  tu_true(worst <= SC_ATAN2_ULPS,
          "sc_atan2: largest error %.3f ulps, at (y, x) = (%.17g, %.17g) "
          "(bound %.1f)",
          worst, wy, wx, SC_ATAN2_ULPS);
  const double sp[][2] = {{0, 1},       {-0.0, 1},     {0, -1},
                          {-0.0, -1},   {1, 0},        {-1, 0},
                          {0, 0},       {INFINITY, 1}, {1, -INFINITY},
                          {NAN, 1},     {1e-320, 1},   {1, 1e300},
                          {1e300, 1e-300}, {1e-200, 1e120},
                          {-1e120, 1e-200}};
  int same = 1;
  for (size_t i = 0; i < sizeof sp / sizeof sp[0]; i++) {
    double a = sc_atan2(sp[i][0], sp[i][1]), b = atan2(sp[i][0], sp[i][1]);
    if (!(a == b && signbit(a) == signbit(b)) && !(isnan(a) && isnan(b)))
      same = 0;
  }
  tu_true(same, "sc_atan2: libm's values at zeros, infinities, NaN and "
                "extreme ratios");
}

/* The pair search's limit in these tests: the earlier root plus a fixed
 * margin (bk2's is twice the tie tolerance; a long one here lets the
 * later guard's root be found too). */
static double pair_margin;
static double pair_limit(void *ctx, const sc_guard *g, const sc_root *r) {
  (void)ctx, (void)g;
  return r->t + pair_margin;
}

/* Two guards searched together (sc_guard_first_root_pair) against the
 * dense search of each: the earlier root is the first root of its guard;
 * the later guard's root is found exactly when it lies within the limit
 * of the earlier one, and is then its first root.  Pairs of bk2's shape
 * (the second term's sign flipped, the second guard often starting at a
 * zero it skips: a block that has just started to slip), pairs with
 * every sign kept or both flipped, and guards that do not pair (searched
 * one after the other).  Near-tangent pairs: the later guard touches
 * zero by +-1e-12 just after the earlier root. */
static void test_pair(void) {
  int n = 600, wrong = 0, cases_later = 0, cases_both = 0, joint = 0;
  double worst = 0;
  for (int i = 0; i < n; i++) {
    sc_guard g[2];
    memset(g, 0, sizeof g);
    g[0].n = 2;
    g[0].w[0] = 1;
    g[0].w[1] = uni(1.5, 4.5);
    for (int k = 0; k < 2; k++) g[0].a[k] = uni(-1, 1), g[0].b[k] = uni(-1, 1);
    g[0].c1 = i % 5 == 0 ? uni(-0.1, 0.1) : 0;
    int shape = i % 4; /* 0, 1: bk2's; 2: signs (-, -) or (+, +); 3: none */
    g[1] = g[0];
    double s0 = shape == 2 && i % 8 == 2 ? 1 : -1, s1 = shape == 2 ? s0 : -1;
    if (shape < 3) {
      g[1].a[0] *= shape == 2 ? s0 : 1, g[1].b[0] *= shape == 2 ? s0 : 1;
      g[1].a[1] *= s1, g[1].b[1] *= s1;
    } else {
      g[1].a[1] = uni(-1, 1); /* not a pair */
    }
    int skip[2] = {0, shape == 1};
    /* the second guard starts at zero when it skips (c0 is shared) */
    g[0].c0 = skip[1] ? -(g[1].a[0] + g[1].a[1]) : uni(-2, 0.5);
    g[1].c0 = g[0].c0;
    pair_margin = i % 3 == 0 ? 0.5 : i % 3 == 1 ? 3 : 1e-9;
    double tmax = 20;
    sc_root r[2];
    if (sc_guard_first_root_pair(g, tmax, skip, 1e-15, 1e-14, pair_limit,
                                 NULL, r) != SC_OK) {
      wrong++;
      continue;
    }
    joint += shape < 3;
    double ref[2] = {dense_first_root(&g[0], tmax, skip[0]),
                     dense_first_root(&g[1], tmax, skip[1])};
    int e = ref[0] < 0 ? 1 : ref[1] < 0 ? 0 : ref[1] < ref[0];
    if (shape == 3) e = ref[0] < 0 ? 1 : 0; /* one after the other */
    if (ref[e] < 0) { /* neither has a root */
      wrong += r[0].found || r[1].found;
      continue;
    }
    int j = 1 - e;
    double lim = ref[e] + pair_margin;
    if (!r[e].found || fabs(r[e].t - ref[e]) > 1e-9) {
      wrong++;
      continue;
    }
    worst = fmax(worst, fabs(r[e].t - ref[e]));
    if (ref[j] >= 0 && fabs(ref[j] - lim) < 1e-9) continue; /* at the limit */
    int want = ref[j] >= 0 && ref[j] <= lim;
    cases_later += ref[j] >= 0 && !want;
    cases_both += want;
    if (r[j].found != want || (want && fabs(r[j].t - ref[j]) > 1e-9)) wrong++;
    /* a later root beyond the limit: not found, t the search's end */
    else if (!want && ref[j] >= 0 && r[j].t != r[e].t + pair_margin) wrong++;
    else if (want) worst = fmax(worst, fabs(r[j].t - ref[j]));
  }
  tu_true(joint >= n / 2 && cases_later >= n / 10 && cases_both >= n / 10,
          "pairs: %d searched jointly, later root beyond the limit in %d, "
          "within it in %d",
          joint, cases_later, cases_both);
  tu_int("pairs: roots missed, found beyond the limit or located elsewhere",
         wrong, 0);
  tu_true(worst <= 1e-12, "pairs: roots within %.3g of the dense search's",
          worst);

  /* Near tangency in a joint march: g[1] = c + A cos(t - t1) + B cos(w2
   * (t - t1)) reaches its highest maximum delta = +-1e-12 at t1, and g[0]
   * = c + A cos(t - t1) - B cos(w2 (t - t1)) stays below zero (it would
   * need both cosines at their extremes at once), so the touch is the
   * pair's only root. */
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    double delta = sgn * 1e-12, t1 = 1.001, w2 = sqrt(7.0);
    double A = 0.3, B = 0.2, c = delta - A - B;
    sc_guard g[2];
    memset(g, 0, sizeof g);
    g[0].n = 2, g[0].c0 = c;
    g[0].w[0] = 1, g[0].a[0] = A * cos(t1), g[0].b[0] = A * sin(t1);
    g[0].w[1] = w2, g[0].a[1] = -B * cos(w2 * t1);
    g[0].b[1] = -B * sin(w2 * t1);
    g[1] = g[0];
    g[1].a[1] = -g[0].a[1], g[1].b[1] = -g[0].b[1];
    int skip[2] = {0, 0};
    pair_margin = 1; /* the later search reaches well past t1 */
    sc_root r[2];
    int st = sc_guard_first_root_pair(g, 20, skip, 1e-15, 1e-14, pair_limit,
                                      NULL, r);
    tu_int("near-tangent pair: SC_OK", st, SC_OK);
    tu_true(dense_first_root(&g[0], 20, 0) < 0 && !r[0].found,
            "near-tangent pair: the other guard has no root, none found");
    if (delta > 0) {
      /* roots at t1 -+ sqrt(2 delta / kappa), kappa = A + B w2^2 */
      double s = sqrt(2 * delta / (A + B * w2 * w2));
      tu_true(r[1].found, "near-tangent pair, reaches zero by 1e-12: found "
                          "(t = %.17g)", r[1].t);
      tu_close("near-tangent pair: root time", r[1].t, t1 - s, 1e-8);
    } else {
      tu_true(!r[1].found, "near-tangent pair, misses zero by 1e-12: no "
                           "root (t = %g)", r[1].t);
    }
  }
  /* Malformed pairs are refused as single guards are. */
  {
    sc_guard g[2];
    memset(g, 0, sizeof g);
    g[0].n = 2, g[0].w[0] = 1, g[0].w[1] = 2, g[0].a[0] = NAN;
    g[1] = g[0];
    int skip[2] = {0, 0};
    sc_root r[2];
    tu_int("pair with a NaN coefficient refused",
           sc_guard_first_root_pair(g, 1, skip, 1e-15, 1e-14, pair_limit,
                                    NULL, r),
           SC_EINVAL);
    g[0].a[0] = g[1].a[0] = 1;
    tu_int("pair with an infinite horizon refused",
           sc_guard_first_root_pair(g, INFINITY, skip, 1e-15, 1e-14,
                                    pair_limit, NULL, r),
           SC_EINVAL);
  }
}

/* Whether two results agree bit for bit in everything a search reports
 * (cos and sin only for the terms it says it filled). */
static int same_root(const sc_root *a, const sc_root *b) {
  if (a->found != b->found || a->tangent != b->tangent ||
      a->steps != b->steps || a->ntrig != b->ntrig)
    return 0;
  double x[4] = {a->t, a->bracket, a->slope, a->curv};
  double y[4] = {b->t, b->bracket, b->slope, b->curv};
  if (memcmp(x, y, sizeof x)) return 0;
  for (int k = 0; k < a->ntrig && k < SC_GUARD_MAXFREQ; k++)
    if (memcmp(&a->cs[k], &b->cs[k], sizeof(double)) ||
        memcmp(&a->sn[k], &b->sn[k], sizeof(double)))
      return 0;
  return 1;
}

/* The pair march decides both guards of a two-term pair in two SIMD
 * lanes where the target has them (src/hybrid/guard.c, "Two guards in
 * two lanes"); tests/guard_scalar.c is the same source with the lanes
 * compiled out.  Every result must agree bit for bit: bk2's chart shape
 * (no constant, no drift, frequencies 1 and sqrt(1 + 2 alpha), the fast
 * term the smaller), a driver's drift, every sign pattern, a guard that
 * starts at a zero it skips, short horizons (the step past tmax and the
 * tail), and near-tangent pairs (the adaptive march inside the grid). */
static void test_lanes(void) {
  int n = 20000, differ = 0, roots = 0, both = 0, tangent = 0, near = 0;
  for (int i = 0; i < n; i++) {
    sc_guard g[2];
    memset(g, 0, sizeof g);
    g[0].n = 2;
    double alpha = uni(1, 20), rs = uni(0.05, 0.5), rf = rs * uni(0.05, 1.5);
    double ps = uni(0, 6.283), pf = uni(0, 6.283);
    g[0].w[0] = 1, g[0].w[1] = sqrt(1 + 2 * alpha);
    g[0].a[0] = rs * cos(ps), g[0].b[0] = rs * sin(ps);
    g[0].a[1] = rf * cos(pf), g[0].b[1] = rf * sin(pf);
    int shape = i % 5;
    g[0].c0 = shape < 2 ? 0 : uni(-0.5, 0.1);
    g[0].c1 = shape == 3 ? uni(-0.05, 0.05) : 0;
    double s0 = i % 7 == 0 ? -1 : 1, s1 = i % 3 == 0 ? 1 : -1;
    g[1] = g[0];
    g[1].a[0] *= s0, g[1].b[0] *= s0, g[1].a[1] *= s1, g[1].b[1] *= s1;
    int skip[2] = {0, 0};
    if (shape == 1 || shape == 4) {
      /* one guard starts at zero (a block that has just started to slip):
       * the shared constant set so that guard j is 0 at t = 0 */
      int j = i % 2;
      g[0].c0 = g[1].c0 = -(g[j].a[0] + g[j].a[1]);
      skip[j] = 1;
    }
    if (i % 11 == 0) {
      /* near tangency: the first guard's highest point within 1e-12 of 0 */
      double t1 = uni(0.5, 3), d = uni(-1e-12, 1e-12);
      g[0].c1 = 0, skip[0] = skip[1] = 0;
      g[0].a[0] = rs * cos(t1), g[0].b[0] = rs * sin(t1);
      g[0].a[1] = rf * cos(g[0].w[1] * t1), g[0].b[1] = rf * sin(g[0].w[1] * t1);
      g[0].c0 = d - rs - rf;
      g[1] = g[0];
      g[1].a[1] = -g[0].a[1], g[1].b[1] = -g[0].b[1];
      near++;
    }
    double tmax = i % 4 == 0 ? uni(0.05, 2) : 20;
    pair_margin = i % 3 == 0 ? 0.5 : i % 3 == 1 ? 3 : 1e-9;
    sc_root r[2], q[2];
    memset(r, 0, sizeof r), memset(q, 0, sizeof q);
    int st = sc_guard_first_root_pair(g, tmax, skip, 1e-15, 1e-14,
                                      pair_limit, NULL, r);
    int sq = guard_scalar_first_root_pair(g, tmax, skip, 1e-15, 1e-14,
                                          pair_limit, NULL, q);
    if (st != sq || !same_root(&r[0], &q[0]) || !same_root(&r[1], &q[1]))
      differ++;
    roots += r[0].found || r[1].found;
    both += r[0].found && r[1].found;
    tangent += r[0].tangent || r[1].tangent;
  }
  tu_true(roots > n / 2 && both > n / 20 && near > n / 20,
          "lanes: %d pairs with a root, %d with both, %d near-tangent "
          "(%d touches)",
          roots, both, near, tangent);
  tu_int("lanes: pair searches that differ in any bit from the one-guard "
         "code",
         differ, 0);
}

int main(void) {
  test_fast_sincos();
  test_atan2();
  test_pair();
  /* Random guards of the shape bk2 produces: a constant, sometimes a
   * linear term, two incommensurate frequencies. */
  int misses = 0, wrong = 0, n = 300, ntrig = 0;
  double trig_err = 0;
  for (int i = 0; i < n; i++) {
    sc_guard g = {0};
    g.n = 2;
    g.w[0] = 1;
    g.w[1] = uni(1.5, 4.5);
    for (int k = 0; k < 2; k++) g.a[k] = uni(-1, 1), g.b[k] = uni(-1, 1);
    g.c0 = uni(-2, 0.5);
    g.c1 = i % 3 == 0 ? uni(-0.1, 0.1) : 0;
    double tmax = 20;
    sc_root r;
    int st = sc_guard_first_root(&g, tmax, 0, 1e-15, 1e-14, &r);
    double ref = dense_first_root(&g, tmax, 0);
    if (st != SC_OK) wrong++;
    if (ref >= 0 && !r.found) misses++;
    else if (ref >= 0 && fabs(r.t - ref) > 1e-9) wrong++;
    else if (ref < 0 && r.found && fabs(geval(&g, r.t)) > 1e-12) wrong++;
    /* cos and sin handed over: those of the rounded argument w t */
    if (r.found && r.ntrig) {
      ntrig++;
      for (int k = 0; k < r.ntrig; k++)
        trig_err = fmax(trig_err, fmax(fabs(r.cs[k] - cos(g.w[k] * r.t)),
                                       fabs(r.sn[k] - sin(g.w[k] * r.t))));
    }
  }
  tu_true(ntrig >= n / 4, "random guards: %d roots hand over cos and sin",
          ntrig);
  tu_true(trig_err <= 8 * DBL_EPSILON,
          "random guards: handed-over cos and sin within %.3g of libm's at "
          "the root (8 ulps)",
          trig_err);
  tu_int("random guards: roots missed against the dense search", misses, 0);
  tu_int("random guards: roots located elsewhere", wrong, 0);

  /* Horizons just short of and just past the first root (bk2 searches a
   * phase's second guard up to the first one's root): the step that
   * reaches past tmax may prove [t, tmax] root-free, but must never
   * report a root beyond tmax nor miss one before it.  tmax = r -+ 1e-9
   * and -+ 1e-3 (within a step of the root), and a tmax far below one
   * grid step. */
  int hz_wrong = 0, hz_cases = 0;
  for (int i = 0; i < 200; i++) {
    sc_guard g = {0};
    g.n = 1 + i % 2;
    g.w[0] = 1;
    g.w[1] = uni(1.5, 4.5);
    for (int k = 0; k < g.n; k++) g.a[k] = uni(-1, 1), g.b[k] = uni(-1, 1);
    g.c0 = uni(-2, 0.5);
    g.c1 = i % 3 == 0 ? uni(-0.1, 0.1) : 0;
    if (g.n == 1 && g.c1 == 0) g.c1 = 0.01; /* not the closed form */
    double r0 = dense_first_root(&g, 20, 0);
    if (r0 < 0.01) continue;
    const double off[5] = {-1e-3, -1e-9, 1e-9, 1e-3, 0};
    for (int j = 0; j < 5; j++) {
      double tmax = j < 4 ? r0 + off[j] : 1e-4 * r0;
      sc_root r;
      int st = sc_guard_first_root(&g, tmax, 0, 1e-15, 1e-14, &r);
      hz_cases++;
      if (st != SC_OK) hz_wrong++;
      else if (tmax > r0 ? !r.found || fabs(r.t - r0) > 1e-9
                         : r.found && (r.t > tmax ||
                                       fabs(geval(&g, r.t)) > 1e-12))
        hz_wrong++;
    }
  }
  tu_true(hz_cases >= 500, "horizons next to the root: %d cases", hz_cases);
  tu_int("horizons next to the root: roots missed, late or beyond tmax",
         hz_wrong, 0);

  /* Near tangency: g = c0 + A cos(w1 (t - t0)) + B cos(w2 (t - t0)) has
   * its highest maximum A + B + c0 = delta at t = t0. */
  double A = 0.3, B = 0.2, w1 = 1, w2 = sqrt(7.0), t0 = 2.385;
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    double delta = sgn * 1e-12;
    sc_guard g = {0};
    g.n = 2;
    g.c0 = delta - A - B;
    g.w[0] = w1, g.a[0] = A * cos(w1 * t0), g.b[0] = A * sin(w1 * t0);
    g.w[1] = w2, g.a[1] = B * cos(w2 * t0), g.b[1] = B * sin(w2 * t0);
    sc_root r;
    sc_guard_first_root(&g, 2 * t0, 0, 1e-15, 1e-14, &r);
    if (delta > 0) {
      /* roots at t0 -+ sqrt(2 delta / kappa), kappa = A w1^2 + B w2^2 */
      double s = sqrt(2 * delta / (A * w1 * w1 + B * w2 * w2));
      tu_true(r.found, "reaches zero by 1e-12: root found (t = %.17g)", r.t);
      /* the root itself is ill conditioned (sqrt of delta): 1e-8 */
      tu_close("near-tangent root time", r.t, t0 - s, 1e-8);
    } else {
      tu_true(!r.found, "misses zero by 1e-12: no root (found = %d, t = %g)",
              r.found, r.t);
    }
  }
  /* A touch late in a long march (about a thousand grid steps of
   * rotations before it, whose rounding the bounds must carry), with a
   * linear term; by 1e-10, as g itself is known only to ~2e-12 at t = 700
   * (the arguments w t round to ~2e-13): g = c0 + c1 (t - t0) + A cos(w1 (t - t0)) + B cos(w2 (t -
   * t0)) has its highest maximum c0 + A + B = delta at t0 when c1 = 0;
   * with c1 = 1e-4 the maximum moves by c1 / kappa and rises by
   * c1^2 / (2 kappa), so c0 absorbs that. */
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    double delta = sgn * 1e-10, T0 = 700.25, c1 = 1e-4;
    double kappa = A * w1 * w1 + B * w2 * w2;
    sc_guard g = {0};
    g.n = 2;
    g.c1 = c1;
    g.c0 = delta - A - B - c1 * c1 / (2 * kappa) - c1 * T0;
    g.w[0] = w1, g.a[0] = A * cos(w1 * T0), g.b[0] = A * sin(w1 * T0);
    g.w[1] = w2, g.a[1] = B * cos(w2 * T0), g.b[1] = B * sin(w2 * T0);
    sc_root r;
    sc_guard_first_root(&g, T0 + 1, 0, 1e-15, 1e-14, &r);
    /* the maximum is at T0 + c1 / kappa to first order; the roots lie
     * sqrt(2 delta / kappa) either side */
    double tmax_g = T0 + c1 / kappa;
    if (delta > 0) {
      tu_true(r.found, "late touch by 1e-10 with a linear term: found (t = "
                       "%.17g, %d steps)",
              r.t, r.steps);
      tu_close("late near-tangent root time", r.t,
               tmax_g - sqrt(2 * delta / kappa), 1e-7);
    } else {
      tu_true(!r.found, "late miss by 1e-10: no root (found = %d, t = %g)",
              r.found, r.t);
    }
  }
  /* A start root and a linear term (a threshold-like guard with the
   * march from a skipped zero): against the dense search. */
  {
    sc_guard g = {0};
    g.n = 1;
    g.c1 = 0.05;
    g.w[0] = 2.2, g.a[0] = 0.3, g.b[0] = -0.4;
    g.c0 = -0.3;
    sc_root r;
    sc_guard_first_root(&g, 30, 1, 1e-15, 1e-14, &r);
    double ref = dense_first_root(&g, 30, 1);
    tu_close("skip_start with a linear term (grid march)", r.t, ref, 1e-12);
    tu_close("slope returned at that root", r.slope,
             0.05 + 2.2 * (-0.4 * cos(2.2 * ref) - 0.3 * sin(2.2 * ref)),
             1e-9);
    double g2 = -2.2 * 2.2 * (0.3 * cos(2.2 * ref) - 0.4 * sin(2.2 * ref));
    /* g'' comes from the last refinement step: within M3 times it */
    tu_close("g'' returned at that root", r.curv, g2, 1e-6);
  }
  /* Single frequency and a constant: the closed form, near tangency too. */
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    sc_guard g = {0};
    g.n = 1;
    g.w[0] = 2.0;
    g.a[0] = 0.4 * cos(2.0 * t0), g.b[0] = 0.4 * sin(2.0 * t0);
    g.c0 = -0.4 + sgn * 1e-12;
    sc_root r;
    sc_guard_first_root(&g, t0 + 1, 0, 1e-15, 1e-14, &r);
    tu_true(sgn > 0 ? r.found && fabs(r.t - t0) < 1e-5 : !r.found,
            "single frequency, max %+g: found = %d at %.12g", sgn * 1e-12,
            r.found, r.t);
  }
  /* The closed form hands over cos and sin of the rounded argument
   * fl(w t) at its root, from the phase vector turned by fl(w t) - psi
   * (psi kept to more than a double after adding 2 pi): within 3 ulps of
   * libm's on random single-sinusoid guards, near tangency, after a
   * skipped start root (measured: 2.0; 4.0 without the second double of
   * psi, 7.6 without the turn). */
  {
    double worst = 0;
    int handed = 0, roots = 0, odd = 0;
    for (int i = 0; i < 300000; i++) {
      sc_guard g = {0};
      g.n = 1;
      g.w[0] = exp(uni(log(0.05), log(20)));
      g.a[0] = uni(-1, 1), g.b[0] = uni(-1, 1);
      double R = hypot(g.a[0], g.b[0]);
      int skip = i % 3 == 0;
      if (skip) g.c0 = -g.a[0];
      else if (i % 3 == 1)
        g.c0 = (i % 2 ? R : -R) * (1 - pow(10, -uni(1, 15)));
      else g.c0 = uni(-1.2 * R, 1.2 * R);
      sc_root r;
      sc_guard_first_root(&g, 1e3, skip, 1e-15, 1e-14, &r);
      if (!r.found) continue;
      roots++;
      if (r.ntrig != 1) {
        /* the closed form leaves a double root at a skipped start (g'(0)
         * = w b within rounding of 0) to the march, whose touches are
         * found without cos and sin */
        odd += !(skip && fabs(g.w[0] * g.b[0]) <= 1e-6 * g.w[0] * R);
        continue;
      }
      handed++;
      double x = g.w[0] * r.t;
      worst = fmax(worst,
                   fmax(fabs(r.cs[0] - cos(x)), fabs(r.sn[0] - sin(x))));
    }
    tu_true(roots > 250000 && handed >= roots - roots / 10000 && odd == 0,
            "closed form: %d of %d roots hand over cos and sin (the others "
            "double roots at a skipped start, left to the march; %d not)",
            handed, roots, odd);
    tu_true(worst <= 3 * DBL_EPSILON,
            "closed form: handed-over cos and sin within %.3g ulps of "
            "libm's at the root (3)",
            worst / DBL_EPSILON);
  }
  /* Closed-form roots near tangency (c0 within 1e-2 .. 1e-14 of the
   * amplitude R, where the root's angle hangs on sqrt(R^2 - c0^2)) against
   * Newton in long double: within the bracket the search reports (its
   * rounding over the slope).  Measured: the worst error 0.088 of the
   * bracket, whether R sin(theta) is taken from the squares, as now, or
   * as sqrt((R - |c0|)(R + |c0|)) (docs/performance.md, "What was
   * tried": the mean errors are 1.3-2.3 times smaller now). */
  {
    double worst = 0;
    int roots = 0, tried = 0;
    for (int e = 2; e <= 14; e++)
      for (int i = 0; i < 2000; i++, tried++) {
        sc_guard g = {0};
        g.n = 1;
        g.w[0] = uni(0.5, 3.5);
        double ph = uni(0, 2 * SC_PI), R = uni(0.1, 1.1);
        g.a[0] = R * cos(ph), g.b[0] = R * sin(ph);
        R = sqrt(g.a[0] * g.a[0] + g.b[0] * g.b[0]);
        g.c0 = (i % 2 ? R : -R) * (1 - pow(10, -e) * uni(1, 2));
        sc_root r;
        sc_guard_first_root(&g, 100, 0, 1e-15, 1e-14, &r);
        if (!r.found || r.tangent) continue;
        roots++;
        long double t = r.t, w = g.w[0];
        for (int k = 0; k < 40; k++) {
          long double v = g.c0 + g.a[0] * cosl(w * t) + g.b[0] * sinl(w * t);
          long double d = w * (g.b[0] * cosl(w * t) - g.a[0] * sinl(w * t));
          t -= v / d;
        }
        worst = fmax(worst, (double)fabsl(t - r.t) / r.bracket);
      }
    tu_true(roots >= tried - tried / 100 && worst <= 0.25,
            "closed form near tangency: %d roots of %d, the worst error "
            "%.3g of the bracket (0.25)",
            roots, tried, worst);
  }
  /* Skipping the root at the start: a slip starts on its re-stick guard
   * (U = Vs, U' < 0); the next root is one period of the free motion
   * later, minus the constant's share: cos(2 t) - 1 + ... here exactly
   * g = -0.1 + 0.1 cos(2 t) - 0.05 sin(2 t): roots at 0 and where
   * tan(t) = -1/2... verify with the dense search instead. */
  {
    sc_guard g = {0};
    g.n = 1;
    g.w[0] = 2;
    g.c0 = -0.1, g.a[0] = 0.1, g.b[0] = -0.05;
    sc_root r;
    sc_guard_first_root(&g, 10, 1, 1e-15, 1e-14, &r);
    double ref = dense_first_root(&g, 10, 1);
    tu_close("skip_start: next root (closed form)", r.t, ref, 1e-12);
    g.n = 2;
    g.w[1] = 3.1, g.a[1] = 0, g.b[1] = 0.01; /* now the march decides */
    g.a[0] = 0.1;
    sc_guard_first_root(&g, 10, 1, 1e-15, 1e-14, &r);
    ref = dense_first_root(&g, 10, 1);
    tu_close("skip_start: next root (march)", r.t, ref, 1e-12);
  }
  /* Error paths. */
  {
    sc_guard g = {0};
    sc_root r;
    g.n = 1, g.w[0] = -1;
    tu_int("negative frequency refused",
           sc_guard_first_root(&g, 1, 0, 1e-15, 1e-14, &r), SC_EINVAL);
    g.w[0] = 1, g.a[0] = NAN;
    tu_int("NaN coefficient refused",
           sc_guard_first_root(&g, 1, 0, 1e-15, 1e-14, &r), SC_EINVAL);
    g.a[0] = 1;
    tu_int("infinite horizon refused",
           sc_guard_first_root(&g, INFINITY, 0, 1e-15, 1e-14, &r), SC_EINVAL);
    /* the validity test goes through the sizes: each way a number can
     * fail it, and the largest coefficients that pass */
    struct {
      const char *what;
      double c0, c1, w, a, b;
      int st;
    } bad[] = {
        {"infinite c0 refused", INFINITY, 0, 1, 1, 0, SC_EINVAL},
        {"NaN c1 refused", 0, NAN, 1, 1, 0, SC_EINVAL},
        {"infinite b refused", 0, 0, 1, 0, -INFINITY, SC_EINVAL},
        {"NaN w with a zero amplitude refused", 0, 0, NAN, 0, 0, SC_EINVAL},
        {"infinite w with a zero amplitude refused", 0, 0, INFINITY, 0, 0,
         SC_EINVAL},
        {"zero frequency refused", 0, 0, 0, 1, 0, SC_EINVAL},
        {"coefficient whose square overflows refused", 0, 0, 1, 1e200, 0,
         SC_EINVAL},
        {"coefficients of 1e150 searched", 0.5e150, 0, 1, 1e150, 0, SC_OK},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
      g.c0 = bad[i].c0, g.c1 = bad[i].c1, g.w[0] = bad[i].w;
      g.a[0] = bad[i].a, g.b[0] = bad[i].b;
      tu_int(bad[i].what, sc_guard_first_root(&g, 10, 0, 1e-15, 1e-14, &r),
             bad[i].st);
    }
    /* g = 1e150 (1/2 + cos t): first root at 2 pi / 3 */
    tu_int("coefficients of 1e150: root found", r.found, 1);
    tu_close("coefficients of 1e150: root at 2 pi / 3", r.t, 2 * SC_PI / 3,
             1e-13);
    g.c0 = 0, g.c1 = 0, g.w[0] = 1, g.a[0] = 1, g.b[0] = 0;
    tu_int("atol 0 refused", sc_guard_first_root(&g, 1, 0, 0, 1e-14, &r),
           SC_EINVAL);
    tu_int("negative rtol refused",
           sc_guard_first_root(&g, 1, 0, 1e-15, -1, &r), SC_EINVAL);
  }
  /* last, so that its draws leave the other tests' random cases as
   * they were */
  test_lanes();
  return tu_finish();
}
