/* Certified first-root location for guards made of a linear term and
 * sinusoids (hybrid.h, docs/events.md).
 *
 * A guard with one sinusoid and no linear term has its roots in closed
 * form.  Otherwise the grid march (below, "the grid march") samples the
 * guard at multiples of a twelfth of the fastest period, with cos and sin
 * carried by rotations, and decides each interval by cubic Hermite bounds;
 * the intervals it cannot decide go to the adaptive march described here,
 * which was once the whole search.  Two guards whose terms
 * differ only in sign (bk2's re-sticks in a slip of both blocks) are
 * marched together, each term computed once (sc_guard_first_root_pair,
 * at the end; docs/events.md, "Two guards at once").
 *
 * The adaptive march covers its span by intervals [t, t + h].  Write s = time from
 * t, g0, g1, g2 = g, g', g'' at t, M3 >= |g'''|.  Taylor's theorem gives
 *   |g(t+s) - (g0 + g1 s + g2 s^2/2)| <= M3 s^3 / 6,
 *   |g'(t+s) - (g1 + g2 s)|           <= M3 s^2 / 2.
 * An interval is accepted when one of these proves it:
 *   (A) no root: the quadratic keeps the sign of g0 with margin
 *       M3 h^3/6 + E (E bounds the rounding error of evaluating g);
 *   (B) at most one root: the linear model of g' keeps one sign with
 *       margin M3 h^2/2, so g is strictly monotone; a root then exists iff
 *       the endpoint values differ in sign, and it is unique.
 * Otherwise h is halved.  Below the time tolerance the interval holds a
 * point where g and g' are both within rounding of zero: a tangential
 * touch, reported as a root with `tangent` set.  No sample spacing is
 * ever assumed, so no root can be stepped over. */
#include <float.h>
#include <math.h>

#include "hybrid/hybrid_impl.h"
#include "hybrid/trig.h"
#include "slipcont/hybrid.h"

/* The pair march's two guards side by side in SSE2's two lanes, where
 * the target has them (every x86-64); elsewhere, or with
 * SC_GUARD_NO_LANES defined (tests/guard_scalar.c), the same steps one
 * guard at a time.  Either way the same numbers (below, "Two guards in
 * two lanes"; tests/test_guard.c compares the two bit for bit). */
#if defined(__SSE2__) && !defined(SC_GUARD_NO_LANES)
#include <emmintrin.h>
#define GUARD_PAIR_LANES 1
#else
#define GUARD_PAIR_LANES 0
#endif

/* Rounding bound on one evaluation of g: a few ulps of each term's size,
 * the sinusoids' arguments w t included (their rounding grows with t). */
#define GUARD_ROUND_ULPS 8.0
/* Iterations of the bracketed Newton refinement: bisection alone halves a
 * bracket of length <= tmax down to 1 ulp within ~1100 steps; Newton ends
 * far sooner, so this cap is never the reason to stop in practice. */
#define GUARD_MAX_REFINE 200
/* The refinement's Taylor certificate stops only where it bounds the
 * step's truncation error by this many ulps of the root, whatever
 * tolerance the search was asked for: the roots stay those of the
 * evaluations' rounding (as from the bound on Newton's error the
 * certificate replaced, whose threshold left Halley's error at ~dl^3,
 * far below an ulp), so that f is as smooth in d and p under every
 * preset (tests/test_jet.c differences f' at steps down to 1e-8). */
#define GUARD_CERT_ULPS 1.0

void sc_guard_eval(const sc_guard *g, double t, double *g0, double *g1,
                   double *g2) {
  double v = g->c0 + g->c1 * t, d1 = g->c1, d2 = 0;
  for (int k = 0; k < g->n; k++) {
    double w = g->w[k], s = sin(w * t), c = cos(w * t);
    double cv = g->a[k] * c + g->b[k] * s;
    v += cv;
    d1 += w * (g->b[k] * c - g->a[k] * s);
    d2 -= w * w * cv;
  }
  if (g0) *g0 = v;
  if (g1) *g1 = d1;
  if (g2) *g2 = d2;
}

double sc_guard_m3(const sc_guard *g) {
  double m = 0;
  for (int k = 0; k < g->n; k++)
    m += g->w[k] * g->w[k] * g->w[k] * hypot(g->a[k], g->b[k]);
  return m;
}

/* Sizes of the guard's terms, computed once per search: the rounding
 * bound at t is GUARD_ROUND_ULPS eps (|c0| + |c1| t + amp + wamp t). */
typedef struct {
  double c0, c1, amp, wamp;
} guard_size;

/* The sizes, and each sinusoid's amplitude into amp[] (coefficients are
 * far from overflow: sqrt of the sum of squares, not hypot). */
static inline guard_size guard_sizes(const sc_guard *g, int n, double *amp) {
  guard_size z = {fabs(g->c0), fabs(g->c1), 0, 0};
  for (int k = 0; k < n; k++) {
    amp[k] = sqrt(g->a[k] * g->a[k] + g->b[k] * g->b[k]);
    z.amp += amp[k];
    z.wamp += amp[k] * g->w[k];
  }
  return z;
}

static double round_at(const guard_size *z, double t) {
  return GUARD_ROUND_ULPS * DBL_EPSILON *
         (z->c0 + z->amp + (z->c1 + z->wamp) * fabs(t));
}

static double tol_at(double t, double atol, double rtol) {
  return atol + rtol * fabs(t);
}

/* g, g', g'' at t, and each sinusoid's own value and slope (the march's
 * interval tests bound each term separately). */
typedef struct {
  double g0, g1, g2;
  double v[SC_GUARD_MAXFREQ], d[SC_GUARD_MAXFREQ];
} guard_terms;

static void eval_terms(const sc_guard *g, double t, guard_terms *e) {
  e->g0 = g->c0 + g->c1 * t, e->g1 = g->c1, e->g2 = 0;
  for (int k = 0; k < g->n; k++) {
    double w = g->w[k], sn = sin(w * t), cs = cos(w * t);
    double v = g->a[k] * cs + g->b[k] * sn;
    double d = w * (g->b[k] * cs - g->a[k] * sn);
    e->v[k] = v, e->d[k] = d;
    e->g0 += v, e->g1 += d, e->g2 -= w * w * v;
  }
}

/* min of two numbers that are never NaN here (checked on entry): libm's
 * fmin is a call, for its NaN rules, in the hottest loop of the map. */
static inline double min2(double a, double b) { return a < b ? a : b; }

/* Minimum of sigma*(p0 + p1 s + p2 s^2/2) over s in [0, h]. */
static double quad_min(double sigma, double p0, double p1, double p2,
                       double h) {
  p0 *= sigma, p1 *= sigma, p2 *= sigma;
  double m = min2(p0, p0 + p1 * h + 0.5 * p2 * h * h);
  if (p2 > 0) {
    double s = -p1 / p2;
    if (s > 0 && s < h) m = min2(m, p0 + 0.5 * p1 * s);
  }
  return m;
}

/* A lower bound of sigma g on [t, t+h] in which each sinusoid enters
 * either by its Taylor quadratic with remainder m3_k h^3/6 or by its
 * amplitude (sigma term_k >= -R_k), whichever bounds it better: a fast
 * term of small amplitude then does not limit the step to a fraction of
 * its period.  Always valid; tried when the plain test (A) fails. */
static double amplitude_bound(const sc_guard *g, const guard_terms *e,
                              const double *amp, const double *m3,
                              double sigma, double t, double h) {
  double q0 = sigma * (g->c0 + g->c1 * t), q1 = sigma * g->c1, q2 = 0;
  double rem = 0, cst = 0, h3 = h * h * h / 6;
  for (int k = 0; k < g->n; k++) {
    double w2 = g->w[k] * g->w[k];
    double mt = quad_min(sigma, e->v[k], e->d[k], -w2 * e->v[k], h) -
                m3[k] * h3;
    if (-amp[k] > mt) {
      cst -= amp[k];
    } else {
      q0 += sigma * e->v[k], q1 += sigma * e->d[k];
      q2 -= sigma * w2 * e->v[k];
      rem += m3[k] * h3;
    }
  }
  return quad_min(1, q0, q1, q2, h) - rem + cst;
}

/* cos and sin of x for |x| <= GUARD_SMALL_ANGLE by their Taylor
 * polynomials in z = x^2 (through x^15 and x^16: the truncation is below
 * 1e-18, the rounding a few ulps, as libm's), several times cheaper than
 * a libm call.  Estrin's scheme (pairs, then z^2, z^4): the march and the
 * refinement wait for these values, and a Horner chain of eight
 * multiply-adds is twice as long. */
#define GUARD_SMALL_ANGLE 0.6
static inline void small_sincos(double x, double *s, double *c) {
  double z = x * x, z2 = z * z, z4 = z2 * z2;
  double s01 = -1.0 / 6 + z * (1.0 / 120);
  double s23 = -1.0 / 5040 + z * (1.0 / 362880);
  double s45 = -1.0 / 39916800 + z * (1.0 / 6227020800);
  double S = (s01 + z2 * s23) + z4 * (s45 + z2 * (-1.0 / 1307674368000));
  double c01 = -0.5 + z * (1.0 / 24), c23 = -1.0 / 720 + z * (1.0 / 40320);
  double c45 = -1.0 / 3628800 + z * (1.0 / 479001600);
  double c67 = -1.0 / 87178291200 + z * (1.0 / 20922789888000);
  double C = (c01 + z2 * c23) + z4 * (c45 + z2 * c67);
  *s = x + x * (z * S);
  *c = 1 + z * C;
}

/* cos and sin of x for |x| <= GUARD_TINY_ANGLE: Taylor through x^7 and
 * x^8 (the truncation is below 1e-22 of x), for the refinement's
 * iterates, which are that close to its anchor once it has converged. */
#define GUARD_TINY_ANGLE 0.015625
static inline void tiny_sincos(double x, double *s, double *c) {
  double z = x * x;
  *s = x * (1 + z * (-1.0 / 6 + z * (1.0 / 120 + z * (-1.0 / 5040))));
  *c = 1 + z * (-0.5 + z * (1.0 / 24 + z * (-1.0 / 720 + z * (1.0 / 40320))));
}

/* cos and sin of the angle x of one term near the anchor: the shortest
 * series that is exact to rounding, sc_fast_sincos beyond
 * GUARD_SMALL_ANGLE. */
static inline void near_sincos(double x, double *s, double *c) {
  double ax = fabs(x);
  if (ax <= GUARD_TINY_ANGLE) tiny_sincos(x, s, c);
  else if (ax <= GUARD_SMALL_ANGLE) small_sincos(x, s, c);
  else sc_fast_sincos(x, s, c);
}

/* g, g', g'' at t from cos and sin of each term. */
static inline void vals_from(const sc_guard *g, int n, double t,
                             const double *cs, const double *sn, double *v) {
  double g0 = g->c0 + g->c1 * t, g1 = g->c1, g2 = 0;
  for (int k = 0; k < n; k++) {
    double w = g->w[k];
    double a = g->a[k] * cs[k] + g->b[k] * sn[k];
    g0 += a;
    g1 += w * (g->b[k] * cs[k] - g->a[k] * sn[k]);
    g2 -= w * w * a;
  }
  v[0] = g0, v[1] = g1, v[2] = g2;
}

/* g, g', g'' at t near the anchor, where the arguments are wt0[] (the
 * rounded products w t0) and cos and sin of them c0[], s0[]: by angle
 * addition with the small angles fl(w t) - wt0 (a difference of two
 * rounded products, exact when they are close), so that cos and sin here
 * are those of the rounded argument fl(w t), as libm's cos(w * t), to a
 * few ulps of their value; they go into cs[], sn[].  (Far from the
 * anchor, sc_fast_sincos of fl(w t).) */
static inline void eval_near(const sc_guard *g, int n, const double *wt0,
                             const double *c0, const double *s0, double t,
                             double *v, double *d, double *d2, double *cs,
                             double *sn) {
  double g0 = g->c0 + g->c1 * t, g1 = g->c1, g2 = 0;
  for (int k = 0; k < n; k++) {
    double w = g->w[k], sx, cx, ck, sk, x = w * t - wt0[k];
    if (fabs(x) <= GUARD_SMALL_ANGLE) {
      near_sincos(x, &sx, &cx);
      ck = c0[k] * cx - s0[k] * sx, sk = s0[k] * cx + c0[k] * sx;
    } else {
      sc_fast_sincos(w * t, &sk, &ck);
    }
    cs[k] = ck, sn[k] = sk;
    double a = g->a[k] * ck + g->b[k] * sk;
    g0 += a, g2 -= w * w * a;
    g1 += w * (g->b[k] * ck - g->a[k] * sk);
  }
  *v = g0, *d = g1, *d2 = g2;
}

/* Bracketed Halley/Newton on [lo, hi] where g(lo), g(hi) differ in sign
 * and g is monotone (g' of one sign).  The start is the inverse cubic
 * Hermite interpolant: t as a cubic in g through (glo, lo) and (ghi, hi)
 * with slopes 1/g', evaluated at g = 0 (three independent divisions, no
 * iteration); it is within O(h^4) of the root, so that one or two steps
 * of Halley's iteration reach the tolerance.  Stop when g is within
 * rounding of zero, when a step inside the bracket is below the
 * tolerance (convergence is at least quadratic there, so the step bounds
 * the error, and the slope at the last point is the root's to O(step)),
 * or when a Taylor certificate puts the root within it (and within an
 * ulp: GUARD_CERT_ULPS) of the next point.  Each step has one division on
 * its critical path.  cos and sin of every term at the
 * returned root go to out->cs, out->sn (a few ulps: the flow at the event
 * takes them instead of calling libm). */
static inline void refine_n(const sc_guard *g, int n, const guard_size *z,
                            double M3, double lo, double glo, double dlo,
                            double hi, double ghi, double dhi, double atol,
                            double rtol, sc_root *out) {
  double t0, c0[SC_GUARD_MAXFREQ], s0[SC_GUARD_MAXFREQ], wt0[SC_GUARD_MAXFREQ];
  double h = hi - lo, rH = 1 / (ghi - glo), u = -glo * rH, t;
  {
    double u2 = u * u, u3 = u2 * u, ilo = 1 / dlo, ihi = 1 / dhi;
    double H = ghi - glo;
    t = lo + h * (3 * u2 - 2 * u3) +
        H * ((u3 - 2 * u2 + u) * ilo + (u3 - u2) * ihi);
    if (!(t > lo && t < hi)) t = lo + h * u; /* the secant's point */
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
  }
  /* cos and sin at the start, once (sc_fast_sincos, within 2 ulps; the
   * guard's rounding bound allows 8): the iterates stay close to it,
   * where angle addition with small angles is exact to a few ulps. */
  t0 = t;
  for (int k = 0; k < n; k++) {
    wt0[k] = g->w[k] * t0;
    sc_fast_sincos(wt0[k], &s0[k], &c0[k]);
  }
  double v = 0, d = 0, d2 = 0, bracket = hi - lo, te = t0, est = 0;
  double cs[SC_GUARD_MAXFREQ], sn[SC_GUARD_MAXFREQ];
  int how = 0; /* 1: |g| within rounding, 2: step below tol, 3: Taylor */
  for (int it = 0; it < GUARD_MAX_REFINE; it++) {
    if (it == 0) {
      /* at the anchor itself: cos and sin as they are (eval_near()'s
       * angle addition with the angle fl(w t0) - wt0 = 0 gives them back
       * unchanged), without the series and the rotation on the chain */
      double vv[3];
      for (int k = 0; k < n; k++) cs[k] = c0[k], sn[k] = s0[k];
      vals_from(g, n, t, cs, sn, vv);
      v = vv[0], d = vv[1], d2 = vv[2];
    } else {
      eval_near(g, n, wt0, c0, s0, t, &v, &d, &d2, cs, sn);
    }
    te = t;
    if (fabs(v) <= round_at(z, t)) {
      how = 1;
      break;
    }
    if ((v > 0) == (glo > 0)) lo = t, glo = v;
    else hi = t;
    /* Halley's step t - 2 g g' / (2 g'^2 - g g''), Newton's where its
     * correction factor (2 g'^2 - g g'') / (2 g'^2) is outside (1/2, 2) */
    double dd = d * d, den = 2 * dd - v * d2, num = 2 * v * d;
    if (!(den > dd && den < 4 * dd)) num = v, den = d;
    double tn = t - num / den;
    if (d != 0 && tn > lo && tn < hi) {
      double dl = fabs(tn - t), tol = tol_at(tn, atol, rtol);
      if (dl <= tol) {
        bracket = dl;
        t = tn;
        how = 2;
        break;
      }
      /* Taylor at t: with s = tn - t, g(tn) = q + R, q = g + g' s +
       * g'' s^2 / 2 (computed from the values here), |R| <= M3 dl^3 / 6.
       * Within 2 dl of t, |g'| >= m = |g'| - 2 dl (|g''| + M3 dl), so
       * if m > 0, g is monotone there and has its root within
       * est = (|q| + M3 dl^3 / 6) / m of tn; when est <= tolc (the
       * tolerance, or GUARD_CERT_ULPS of tn if smaller; < dl, so the root
       * is within 2 dl of t, where m holds) stop without evaluating g
       * again (the slope at tn is taken after the loop).  Halley's step
       * makes q of order dl^3, so one step from an iterate within ~1e-5
       * of the root is certified here (a bound on Newton's error alone,
       * |g''| dl^2 / |g'|, needed ~1e-7 and a third evaluation).  Tested
       * multiplied out: est m against tolc m. */
      double s = tn - t, q = v + s * (d + s * (0.5 * d2));
      double m = fabs(d) - 2 * dl * (fabs(d2) + M3 * dl);
      double estd = fabs(q) + M3 * dl * dl * dl * (1.0 / 6);
      double tolc = min2(tol, GUARD_CERT_ULPS * DBL_EPSILON * fabs(tn));
      if (m > 0 && estd <= tolc * m) {
        est = estd / m;
        t = tn;
        how = 3;
        break;
      }
      t = tn;
    } else {
      t = 0.5 * (lo + hi);
    }
    bracket = hi - lo;
    if (bracket <= tol_at(hi, atol, rtol)) break;
  }
  if (how == 3) bracket = est;
  else if (how == 1) bracket = 0;
  /* cos and sin at the returned t: from the last evaluation's, rotated;
   * after a certified step, the slope and curvature there from them (the
   * step is up to ~1e-5: the slope moved by g'' alone would be off by
   * M3 s^2 / 2, ~1e-10 of it, and f' with it) */
  if (t != te) {
    for (int k = 0; k < n; k++) {
      double sx, cx, ck = cs[k], sk = sn[k];
      near_sincos(g->w[k] * t - g->w[k] * te, &sx, &cx);
      cs[k] = ck * cx - sk * sx, sn[k] = sk * cx + ck * sx;
    }
    if (how == 3) {
      double vv[3];
      vals_from(g, n, t, cs, sn, vv);
      d = vv[1], d2 = vv[2];
    }
  }
  for (int k = 0; k < n; k++) out->cs[k] = cs[k], out->sn[k] = sn[k];
  out->ntrig = n;
  out->t = t;
  out->bracket = bracket;
  out->found = 1;
  out->slope = d;
  out->curv = d2;
}

/* refine_n with the number of terms a constant for bk2's guards. */
static void refine(const sc_guard *g, const guard_size *z, double M3,
                   double lo, double glo, double dlo, double hi, double ghi,
                   double dhi, double atol, double rtol, sc_root *out) {
  if (g->n == 1)
    refine_n(g, 1, z, M3, lo, glo, dlo, hi, ghi, dhi, atol, rtol, out);
  else if (g->n == 2)
    refine_n(g, 2, z, M3, lo, glo, dlo, hi, ghi, dhi, atol, rtol, out);
  else
    refine_n(g, g->n, z, M3, lo, glo, dlo, hi, ghi, dhi, atol, rtol, out);
}

/* 2 pi as a sum of two doubles (the second is 2 pi - fl(2 pi)). */
#define GUARD_TWO_PI_HI (2 * SC_PI)
#define GUARD_TWO_PI_LO 2.4492935982947064e-16

/* A single sinusoid and a constant: roots in closed form.  g = c0 +
 * R cos(w t - phi).  Ascending roots sit at w t = phi - theta, descending
 * ones at phi + theta (mod 2 pi), cos theta = -c0 / R.  Returns 0 when the
 * case is degenerate and the march should decide.
 *
 * The root's angle psi = phi -+ theta is that of a phase vector (x, y), the
 * product of (cos phi, sin phi) and (cos theta, -+ sin theta) times R^2: one
 * sc_atan2 (trig.h) gives psi, and (x, y) / |(x, y)| gives cos psi and sin psi
 * without sincos.  The root is t = alpha / w, alpha = psi or psi + 2 pi; the
 * flow at the event evaluates cos and sin of the rounded product fl(w t), which
 * differs from alpha by an ulp or two.  So the phase vector is turned by that
 * small angle fl(w t) - alpha (exact), less the rounding of alpha's 2 pi (kept
 * as a second double), to first order: the angle is below 1e-15, its square
 * below rounding.  What is left is sc_atan2's own error (below one ulp of |psi|
 * <= pi, 2 eps, where the root's window E / |g'| >= 8 eps / w allows 8 eps) and
 * a few roundings of the products: cos and sin within a few ulps of libm's
 * cos(w * t), sin(w * t) (tests/test_guard.c), handed over in out->cs, out->sn.
 * Inlined into each specialisation of a search (the compiler had stopped
 * inlining it there). */
static SC_ALWAYS_INLINE int closed_form(const sc_guard *g, const guard_size *z,
                                        double R, double tmax, int skip_start,
                                        sc_root *out) {
  double a = g->a[0], b = g->b[0], w = g->w[0], c0 = g->c0;
  double E = round_at(z, 0);
  if (R <= E) return 0;
  double gap = R - fabs(c0);
  if (gap < -E) return 1; /* never reaches zero: out says not found */
  /* The phase vector (x, y) of the first root's type (ascending if asc),
   * and its angle alpha in [0, 2 pi) (2 pi or a little more after a
   * skipped start root) as alpha + alo. */
  double x, y, alpha, alo = 0, rs = 0;
  int asc;
  if (gap <= E) {
    /* touches: cos(w t - phi) = -sign(c0) */
    if (skip_start) return 0;
    out->tangent = 1;
    asc = c0 + a < 0;
    x = c0 < 0 ? a : -a, y = c0 < 0 ? b : -b;
  } else {
    /* R sin(theta), from the squares (the square root of R^2 stays off
     * this chain) */
    rs = sqrt((a * a + b * b) - c0 * c0);
    if (skip_start) {
      double g1 = w * b; /* g'(0) */
      if (g1 == 0) return 0;
      /* the start root is of the type of g'(0): the next is the other */
      asc = g1 < 0;
    } else {
      /* from below zero the first root ascends, from above it descends */
      asc = c0 + a < 0;
    }
    if (asc) x = -a * c0 + b * rs, y = -b * c0 - a * rs;
    else x = -a * c0 - b * rs, y = a * rs - b * c0;
  }
  alpha = sc_atan2(y, x);
  if (alpha < 0) {
    /* Fast2Sum: |2 pi| > |alpha|, so the rounding of the sum is exact */
    double s = alpha + GUARD_TWO_PI_HI;
    alo = (alpha - (s - GUARD_TWO_PI_HI)) + GUARD_TWO_PI_LO;
    alpha = s;
  }
  if (skip_start && alpha * 1 <= 4 * DBL_EPSILON * GUARD_TWO_PI_HI) {
    double s = alpha + GUARD_TWO_PI_HI;
    alo += (alpha - (s - GUARD_TWO_PI_HI)) + GUARD_TWO_PI_LO;
    alpha = s;
  }
  double t = alpha * (1 / w); /* (1 / w waits on nothing: off the chain) */
  if (t <= tmax) {
    out->found = 1;
    out->t = t;
    /* cos and sin of fl(w t): the unit phase vector turned by the angle
     * d = fl(w t) - (alpha + alo) (|d| < 1e-15: cos d = 1, sin d = d) */
    double r = 1 / sqrt(x * x + y * y), cx = x * r, sy = y * r;
    double d = (w * t - alpha) - alo;
    out->cs[0] = cx - sy * d, out->sn[0] = sy + cx * d;
    out->ntrig = 1;
    /* at a root R cos(w t - phi) = -c0: g' = +-w R sin(theta) (ascending
     * or descending), g'' = w^2 c0 */
    if (out->tangent) sc_guard_eval(g, t, NULL, &out->slope, NULL);
    else out->slope = asc ? w * rs : -w * rs;
    out->curv = w * w * c0;
    /* fmax(|slope|, DBL_MIN), NaN included, without libm's call */
    double as = fabs(out->slope);
    out->bracket = out->tangent ? 0 : E / (as > DBL_MIN ? as : DBL_MIN);
  }
  return 1;
}

/* What the march needs to know about one guard, computed once per search. */
typedef struct {
  const sc_guard *g;
  guard_size z;
  double amp[SC_GUARD_MAXFREQ], m3[SC_GUARD_MAXFREQ], M3;
  double atol, rtol;
} guard_ctx;

/* The adaptive march on [t, tend], from the terms e at t: intervals are
 * halved until test (A) or (B) passes.  Returns 1 with *out filled when it
 * finds the first root there, 0 when [t, tend] holds none. */
static int march(const guard_ctx *c, double t, double tend, guard_terms *e,
                 int at_start_root, double h, sc_root *out) {
  const sc_guard *g = c->g;
  double atol = c->atol, rtol = c->rtol, M3 = c->M3;
  double g0 = e->g0, g1 = e->g1, g2 = e->g2;
  while (t < tend) {
    h = min2(h, tend - t);
    out->steps++;
    double E = round_at(&c->z, t + h);
    double sigma = g0 > 0 ? 1 : -1;
    if (at_start_root) {
      /* g(0) = 0 by construction: its sign just after 0 is that of g1,
       * or of g2 if g1 vanishes. */
      sigma = g1 != 0 ? (g1 > 0 ? 1 : -1) : (g2 > 0 ? 1 : -1);
    } else if (fabs(g0) <= E) {
      /* g is within rounding of zero here: a root at t. */
      out->found = 1;
      out->t = t;
      out->slope = g1;
      out->curv = g2;
      out->tangent = fabs(g1) * tol_at(t, atol, rtol) <= E;
      return 1;
    }
    /* (A) no root in [t, t+h]: the quadratic with the global remainder,
     * or failing that (with several frequencies) the bound that takes
     * some terms by their amplitude. */
    if (!at_start_root &&
        (quad_min(sigma, g0, g1, g2, h) - M3 * h * h * h / 6 > E ||
         (g->n > 1 &&
          amplitude_bound(g, e, c->amp, c->m3, sigma, t, h) > E))) {
      t += h;
      eval_terms(g, t, e);
      g0 = e->g0, g1 = e->g1, g2 = e->g2;
      h *= 2;
      continue;
    }
    /* (B) g strictly monotone on [t, t+h] */
    double d0 = g1, dh = g1 + g2 * h;
    if ((d0 > 0) == (dh > 0) && min2(fabs(d0), fabs(dh)) > M3 * h * h / 2) {
      guard_terms eh;
      eval_terms(g, t + h, &eh);
      double ge = eh.g0, ge1 = eh.g1, ge2 = eh.g2;
      if (!at_start_root && (ge * sigma <= 0 || fabs(ge) <= E)) {
        if (fabs(ge) <= E) {
          out->found = 1;
          out->t = t + h;
          out->slope = ge1;
          out->curv = ge2;
          return 1;
        }
        refine(g, &c->z, M3, t, g0, g1, t + h, ge, ge1, atol, rtol, out);
        return 1;
      }
      at_start_root = 0;
      t += h;
      *e = eh;
      g0 = ge, g1 = ge1, g2 = ge2;
      h *= 2;
      continue;
    }
    h *= 0.5;
    if (h <= tol_at(t, atol, rtol)) {
      /* Neither test can be passed over an interval below the tolerance:
       * g and g' are both within rounding of zero: a touch. */
      if (at_start_root) {
        /* degenerate start (g' = 0 too): step past it */
        at_start_root = 0;
        t += h;
        eval_terms(g, t, e);
        g0 = e->g0, g1 = e->g1, g2 = e->g2;
        continue;
      }
      out->found = 1;
      out->tangent = 1;
      out->t = t + 0.5 * h;
      out->bracket = h;
      sc_guard_eval(g, out->t, NULL, &out->slope, &out->curv);
      return 1;
    }
  }
  return 0;
}

/* ---- the grid march ---------------------------------------------------
 * Samples at t_j = j dt, dt = a twelfth of the fastest period, with cos
 * and sin of every frequency carried from one sample to the next by a
 * rotation through w dt (no libm call per sample; the rounding bound
 * grows with the number of rotations).  Between two samples the guard is bounded by the cubic
 * Hermite interpolant of g, g' at both ends, whose error is at most
 * M4 dt^4/384 (M4 = sum R_k w_k^4 >= |g''''|), and g' likewise by that
 * of g', g'' (M5 dt^4/384).  An interval is accepted as root-free when
 * the cubic for g keeps the sign of g with that margin, or as holding
 * exactly one root when the cubic for g' keeps one sign with its margin
 * (then a sign change at the ends brackets the root for refine()).  An
 * interval that passes neither goes to the adaptive march above, which
 * decides that interval exactly as before (touches included); the grid
 * then goes on from exact values.  Every interval is
 * thus decided by a proof, and the intervals are contiguous from 0. */

/* Twelve samples per period of the fastest frequency: w dt = pi/6, the
 * Hermite remainder is 2e-4 of a term's amplitude, so only intervals
 * where g comes that close to zero (roots, near-touches) need more. */
#define GUARD_GRID_PER_PERIOD 12
/* cos and sin of pi/6, the fastest term's rotation per sample. */
#define GUARD_COS30 0.86602540378443864676
#define GUARD_SIN30 0.5
/* Each rotation adds at most GUARD_ROT_ULPS ulps to the error of cos and
 * sin (two products and a sum, with the rotation's own cos and sin within
 * half an ulp, and |(cos, sin)| within a few ulps of 1); the values
 * restart exact at 0, and within SC_FAST_TRIG_ULPS after every interval
 * the adaptive march decided. */
#define GUARD_ROT_ULPS 4.0

/* Three times the minimum of the Bernstein coefficients of the cubic
 * with values p0, p1 and slopes times the interval q0, q1 at the ends
 * (p0, p0 + q0/3, p1 - q1/3, p1): three times a lower bound of the cubic
 * over the interval (its graph lies in their convex hull).  Scaled by 3,
 * so that no division is on the march's path; compared with 3 margins. */
static inline double bern_min3(double p0, double q0, double p1, double q1) {
  double a0 = 3 * p0, a1 = 3 * p1;
  return min2(min2(a0, a1), min2(a0 + q0, a1 - q1));
}

/* Exact minimum over s in [0, h] of the cubic Hermite interpolant of
 * values p0, p1 and slopes q0, q1 (per unit time) at the ends. */
static double hermite_min(double p0, double q0, double p1, double q1,
                          double h) {
  double dg = (p1 - p0) / h;
  double c2 = (3 * dg - 2 * q0 - q1) / h;
  double c3 = (q0 + q1 - 2 * dg) / (h * h);
  double m = min2(p0, p1);
  /* p'(s) = q0 + 2 c2 s + 3 c3 s^2 */
  double A = 3 * c3, B = 2 * c2, C = q0, r[2];
  int nr = 0;
  if (A == 0) {
    if (B != 0) r[nr++] = -C / B;
  } else {
    double disc = B * B - 4 * A * C;
    if (disc >= 0) {
      double q = -0.5 * (B + (B >= 0 ? sqrt(disc) : -sqrt(disc)));
      r[nr++] = q / A;
      if (q != 0) r[nr++] = C / q;
    }
  }
  for (int i = 0; i < nr; i++)
    if (r[i] > 0 && r[i] < h)
      m = min2(m, p0 + r[i] * (q0 + r[i] * (c2 + r[i] * c3)));
  return m;
}

/* cos and sin of every term at t (sc_fast_sincos: within
 * SC_FAST_TRIG_ULPS of the exact values). */
static inline void anchor(const sc_guard *g, double t, double *cs,
                          double *sn) {
  for (int k = 0; k < g->n; k++) sc_fast_sincos(g->w[k] * t, &sn[k], &cs[k]);
}

/* Steps of the grid march: dt, 2 dt, 4 dt (a third of the fastest
 * period at most, where the Hermite remainder is 5% of an amplitude). */
#define GUARD_GRID_LEVELS 3

/* cos and sin of the fastest term's rotation at each level (pi/6, pi/3,
 * 2 pi/3), by double angles from those of pi/6: cos 2x = 1 - 2 sin^2 x,
 * sin 2x = 2 sin x cos x, as for the other terms, folded by the compiler
 * (in round-to-nearest doubles, as at run time). */
#define GUARD_C60 (1 - 2 * GUARD_SIN30 * GUARD_SIN30)
#define GUARD_S60 (2 * GUARD_SIN30 * GUARD_COS30)
static const double guard_rot_fast[GUARD_GRID_LEVELS][2] = {
    {GUARD_COS30, GUARD_SIN30},
    {GUARD_C60, GUARD_S60},
    {1 - 2 * GUARD_S60 * GUARD_S60, 2 * GUARD_S60 * GUARD_C60}};

/* cos, sin of w h for every term into c[], s[]: the Taylor series for
 * small angles, sc_fast_sincos otherwise. */
static void rotation(const sc_guard *g, double h, double *c, double *s) {
  for (int k = 0; k < g->n; k++) {
    double x = g->w[k] * h;
    if (x <= GUARD_SMALL_ANGLE) small_sincos(x, &s[k], &c[k]);
    else sc_fast_sincos(x, &s[k], &c[k]);
  }
}

/* Two guards searched together (sc_guard_first_root_pair): the second's
 * terms are the first's times sgn[k] = +-1, with the same c0, c1 and
 * frequencies, so the march computes each term once for both; and the
 * search limit of the guard whose root comes later. */
typedef struct {
  const sc_guard *gb;
  double sgn[SC_GUARD_MAXFREQ];
  sc_guard_limit_fn limit;
  void *ctx;
} guard_pair;

/* g, g', g'' of both guards of a pair at t, from cos and sin of each
 * term: each guard's values are those of vals_from() bit for bit (a
 * term times -1 is the negated term, exactly). */
static inline void vals_pair(const sc_guard *g, const double *sgn, int n,
                             double t, const double *cs, const double *sn,
                             double *va, double *vb) {
  double base = g->c0 + g->c1 * t;
  double g0 = base, g1 = g->c1, g2 = 0, h0 = base, h1 = g->c1, h2 = 0;
  for (int k = 0; k < n; k++) {
    double w = g->w[k];
    double a = g->a[k] * cs[k] + g->b[k] * sn[k];
    double d = w * (g->b[k] * cs[k] - g->a[k] * sn[k]), dd = w * w * a;
    g0 += a, g1 += d, g2 -= dd;
    h0 += sgn[k] * a, h1 += sgn[k] * d, h2 -= sgn[k] * dd;
  }
  va[0] = g0, va[1] = g1, va[2] = g2;
  vb[0] = h0, vb[1] = h1, vb[2] = h2;
}

#if GUARD_PAIR_LANES
/* ---- Two guards in two lanes ------------------------------------------
 * A pair of two-term guards (bk2's re-sticks in a slip of both blocks)
 * has each step's values and test (A) computed for both guards at once,
 * lane 0 the first guard, lane 1 the second.  Every lane operation is the
 * IEEE operation the one-guard code does on that guard's numbers, in the
 * same order (products, sums, minima: minpd(a, b) is a < b ? a : b, as
 * min2()), and sigma times a number (sigma = +-1) is that number with its
 * sign bit flipped or not, exactly, so the values and the decisions are
 * those of vals_pair() and grid_step(), bit for bit.  The lanes only ever
 * prove a step free of roots by test (A)'s Bernstein bound; any other
 * outcome (a start root, a value within rounding of zero, a bound that
 * fails) is left to grid_step() for each guard, from the same values. */
typedef struct {
  __m128d a, b, w, w2; /* term k's coefficients in lane k */
  __m128d s0, s1;      /* term k's sign in guard 0 and guard 1: (1, sgn_k) */
} pair_lanes;

/* Two numbers into the lanes from the scalars, not by a vector load of
 * the array: numbers stored one by one just before (a table filled by
 * this search, cos and sin at an anchor) reach a vector load only once
 * both stores have left the store buffer, a stall of some 15 cycles each
 * time.  (The compiler may still merge the two loads where it sees no
 * store in between; for the guard's frequencies it does, at no measured
 * cost.) */
static inline __m128d pair_load(const double *x) {
  return _mm_set_pd(x[1], x[0]);
}

static inline pair_lanes pair_lanes_make(const sc_guard *g,
                                         const double *sgn) {
  pair_lanes L;
  L.a = pair_load(g->a), L.b = pair_load(g->b);
  L.w = pair_load(g->w), L.w2 = _mm_mul_pd(L.w, L.w);
  L.s0 = _mm_set_pd(sgn[0], 1), L.s1 = _mm_set_pd(sgn[1], 1);
  return L;
}

/* g, g', g'' of both guards at t from cos and sin of the two terms (C, S:
 * term k in lane k), into G0, G1, G2 (guard i in lane i): vals_pair()
 * with n = 2. */
static inline void pair_vals(const pair_lanes *L, const sc_guard *g,
                             double t, __m128d C, __m128d S, __m128d *G0,
                             __m128d *G1, __m128d *G2) {
  __m128d ta = _mm_add_pd(_mm_mul_pd(L->a, C), _mm_mul_pd(L->b, S));
  __m128d td =
      _mm_mul_pd(L->w, _mm_sub_pd(_mm_mul_pd(L->b, C), _mm_mul_pd(L->a, S)));
  __m128d tdd = _mm_mul_pd(L->w2, ta);
  __m128d base = _mm_set1_pd(g->c0 + g->c1 * t);
  *G0 = _mm_add_pd(
      _mm_add_pd(base, _mm_mul_pd(_mm_unpacklo_pd(ta, ta), L->s0)),
      _mm_mul_pd(_mm_unpackhi_pd(ta, ta), L->s1));
  *G1 = _mm_add_pd(_mm_add_pd(_mm_set1_pd(g->c1),
                              _mm_mul_pd(_mm_unpacklo_pd(td, td), L->s0)),
                   _mm_mul_pd(_mm_unpackhi_pd(td, td), L->s1));
  *G2 = _mm_sub_pd(_mm_sub_pd(_mm_setzero_pd(),
                              _mm_mul_pd(_mm_unpacklo_pd(tdd, tdd), L->s0)),
                   _mm_mul_pd(_mm_unpackhi_pd(tdd, tdd), L->s1));
}

/* g, g', g'' of both guards (guard i in lane i) into v[i][0..2]. */
static inline void pair_store(__m128d G0, __m128d G1, __m128d G2,
                              double (*v)[3]) {
  _mm_storel_pd(&v[0][0], G0), _mm_storeh_pd(&v[1][0], G0);
  _mm_storel_pd(&v[0][1], G1), _mm_storeh_pd(&v[1][1], G1);
  _mm_storel_pd(&v[0][2], G2), _mm_storeh_pd(&v[1][2], G2);
}

/* Test (A) of grid_step() for both guards, from g, g' at the step's start
 * (E0, E1) and end (F0, F1): bit i of the result is set when guard i's
 * start is not within rounding E of zero and the cubic of its g keeps the
 * start's sign by the Bernstein bound with margin marg (STEP_FREE in
 * grid_step() when the guard does not start at a root). */
static inline int pair_free(__m128d E0, __m128d E1, __m128d F0, __m128d F1,
                            double h, double E, double marg) {
  const __m128d sign = _mm_set1_pd(-0.0), H = _mm_set1_pd(h);
  const __m128d three = _mm_set1_pd(3), Ev = _mm_set1_pd(E);
  __m128d sb = _mm_and_pd(E0, sign); /* sigma's sign: g0 != 0 below */
  __m128d p0 = _mm_andnot_pd(sign, E0), p1 = _mm_xor_pd(F0, sb);
  __m128d q0 = _mm_mul_pd(_mm_xor_pd(E1, sb), H);
  __m128d q1 = _mm_mul_pd(_mm_xor_pd(F1, sb), H);
  __m128d a0 = _mm_mul_pd(three, p0), a1 = _mm_mul_pd(three, p1);
  __m128d m = _mm_min_pd(_mm_min_pd(a0, a1),
                         _mm_min_pd(_mm_add_pd(a0, q0), _mm_sub_pd(a1, q1)));
  __m128d ok = _mm_and_pd(_mm_cmpgt_pd(m, _mm_set1_pd(3 * marg)),
                          _mm_and_pd(_mm_cmpgt_pd(p1, Ev),
                                     _mm_cmpgt_pd(p0, Ev)));
  return _mm_movemask_pd(ok);
}
#endif

/* What one guard's step [t, t + h] of the grid march proves. */
enum { STEP_UNDECIDED, STEP_FREE, STEP_ROOT };

/* The tests of one step from values ve at its start and vf at its end
 * (g, g', g''): STEP_FREE, no root in (t, t + h] (the cubic of g keeps
 * its sign, or g is monotone without a sign change past a start root);
 * STEP_ROOT, exactly one (g monotone with a sign change: a bracket for
 * refine(); never on a step reaching `past` tmax, whose root may lie
 * beyond it); else STEP_UNDECIDED.  E, E1, E2: rounding of g, g', g'' at
 * the samples; rem0, rem1: the Hermite remainders of g and g'. */
static inline int grid_step(const double *ve, const double *vf, int start,
                            int past, double h, double E, double E1,
                            double E2, double rem0, double rem1) {
  double g0 = ve[0], G0 = vf[0];
  double sigma;
  if (start) {
    sigma = ve[1] != 0 ? (ve[1] > 0 ? 1 : -1) : (ve[2] > 0 ? 1 : -1);
  } else {
    sigma = g0 > 0 ? 1 : -1;
    if (fabs(g0) <= E) return STEP_UNDECIDED; /* at a root: the march's */
  }
  int same = !start && sigma * G0 > E;
  /* (A) no root: the cubic of g keeps its sign with margin (rounding
   * of the values and of the slopes times h; twice that for the exact
   * minimum, whose own arithmetic rounds too) */
  if (same) {
    double marg = rem0 + E + h * E1;
    if (bern_min3(sigma * g0, sigma * ve[1] * h, sigma * G0,
                  sigma * vf[1] * h) > 3 * marg ||
        hermite_min(sigma * g0, sigma * ve[1], sigma * G0, sigma * vf[1], h) >
            2 * marg)
      return STEP_FREE;
  }
  /* (B) g' keeps one sign: g strictly monotone on [t, t + h] */
  double s1 = ve[1] > 0 ? 1 : -1;
  double dmin3 =
      bern_min3(s1 * ve[1], s1 * ve[2] * h, s1 * vf[1], s1 * vf[2] * h);
  if (dmin3 > 3 * (rem1 + E1 + h * E2)) {
    if (same || (start && s1 == sigma && s1 * G0 > E))
      return STEP_FREE; /* monotone, no sign change past the start */
    if (!past && !start && sigma * G0 <= 0 && fabs(G0) > E) return STEP_ROOT;
  }
  return STEP_UNDECIDED;
}

/* Whether guard h, monotone over a grid step from t (where it is g0 != 0)
 * to tn, keeps the sign of g0 up to lim (< tn), given the root r of the
 * other guard of its pair in the same step (r <= lim), where cos and sin
 * of the shared terms are r->cs, r->sn: h there, bounded from its
 * rounding and moved to lim by the largest slope h can have, keeps that
 * sign.  Then h has no root up to lim (it is monotone on the step). */
static inline int pair_beyond(const guard_ctx *c, const sc_guard *h, int n,
                              double g0, const sc_root *r, double lim,
                              double tn) {
  if (r->ntrig != n || !(lim < tn) || !(lim >= r->t)) return 0;
  double v[3];
  vals_from(h, n, r->t, r->cs, r->sn, v);
  double sigma = g0 > 0 ? 1 : -1;
  return sigma * v[0] - (lim - r->t) * (c->z.c1 + c->z.wamp) >
         round_at(&c->z, lim);
}

/* Both guards of a pair have a root in the grid step [t, tn] (values ve
 * at t, vf at tn): the one whose secant point comes first is refined
 * first, and the other only if pair_beyond() cannot prove its root to lie
 * beyond the first's limit, where the march would drop it (two thirds of
 * such steps on the chart).  Returns the guard whose root comes first,
 * both refined; or -1 when the other's root is beyond the limit (out[] as
 * the march leaves it then: the other's t the limit).  Out of line: the
 * case is rare, and inlined it cost the march's loop its registers. */
static __attribute__((noinline)) int refine_both(
    const guard_ctx *c, const guard_pair *pr, const sc_guard *const *gg, int n,
    double t, double tn, double (*ve)[3], double (*vf)[3], sc_root *out) {
  int a = 0;
  if (ve[1][0] / (ve[1][0] - vf[1][0]) < ve[0][0] / (ve[0][0] - vf[0][0]))
    a = 1;
  int b = 1 - a;
  if (!out[a].found)
    refine(gg[a], &c->z, c->M3, t, ve[a][0], ve[a][1], tn, vf[a][0],
           vf[a][1], c->atol, c->rtol, &out[a]);
  double lim = pr->limit(pr->ctx, gg[a], &out[a]);
  if (pair_beyond(c, gg[b], n, ve[b][0], &out[a], lim, tn)) {
    out[b] = (sc_root){.t = lim, .steps = out[b].steps};
    return -1;
  }
  if (!out[b].found)
    refine(gg[b], &c->z, c->M3, t, ve[b][0], ve[b][1], tn, vf[b][0],
           vf[b][1], c->atol, c->rtol, &out[b]);
  return out[1].t < out[0].t; /* (a tie to guard 0, as the march's loop) */
}

/* The steps of grid_march_n(), inlined into it (always: the march's
 * loop keeps its values in registers). */

/* Rotations through w dt 2^m, all levels at once (a few products a term;
 * a test on every step cost more): the fastest term's are constants, the
 * others' from cos and sin of w dt by double angles. */
static inline __attribute__((always_inline)) void grid_rotations(
    const sc_guard *g, int n, double wmax, double dt,
    double (*rc)[SC_GUARD_MAXFREQ], double (*rs)[SC_GUARD_MAXFREQ]) {
  for (int k = 0; k < n; k++) {
    if (g->w[k] == wmax) {
      for (int l = 0; l < GUARD_GRID_LEVELS; l++)
        rc[l][k] = guard_rot_fast[l][0], rs[l][k] = guard_rot_fast[l][1];
      continue;
    }
    small_sincos(g->w[k] * dt, &rs[0][k], &rc[0][k]);
    for (int l = 1; l < GUARD_GRID_LEVELS; l++) {
      double cc = rc[l - 1][k], ss = rs[l - 1][k];
      rc[l][k] = 1 - 2 * ss * ss;
      rs[l][k] = 2 * ss * cc;
    }
  }
}

/* The march's bounds: the rounding of g, g', g'' at a sample (a
 * constant, a part growing with t, the arguments w t, and one growing
 * with the rotations since the last exact values, rerr ulps of cos and
 * sin), and the Hermite remainders' factors M4, M5. */
typedef struct {
  double e00, e01, e10, e11, e20, e21, r0, r1, r2, M4, M5;
} grid_bounds;

static inline __attribute__((always_inline)) grid_bounds grid_bounds_make(const guard_ctx *c,
                                                          int n, double wmax) {
  const sc_guard *g = c->g;
  double M4 = 0, M5 = 0, wamp2 = 0;
  for (int k = 0; k < n; k++) {
    double w = g->w[k];
    M4 += c->m3[k] * w;
    M5 += c->m3[k] * w * w;
    wamp2 += c->amp[k] * w * w;
  }
  const double ue = GUARD_ROUND_ULPS * DBL_EPSILON;
  return (grid_bounds){
      .e00 = ue * (c->z.c0 + c->z.amp), .e01 = ue * (c->z.c1 + c->z.wamp),
      .e10 = ue * (c->z.c1 + c->z.wamp), .e11 = ue * wmax * c->z.wamp,
      .e20 = ue * wamp2, .e21 = ue * wmax * wamp2,
      .r0 = DBL_EPSILON * c->z.amp, .r1 = DBL_EPSILON * c->z.wamp,
      .r2 = DBL_EPSILON * wamp2, .M4 = M4, .M5 = M5};
}

/* Per level: the step, its Hermite remainders, its rotation's ulps.  One
 * division: level l scales h by 2^l and the remainders by 16^l, exactly
 * (powers of two), so these equal the per-level formulas. */
static inline __attribute__((always_inline)) void grid_levels(double dt, double M4, double M5,
                                            double *hl, double *rem0l,
                                            double *rem1l, double *ulpl) {
  double h40 = dt * dt * dt * dt / 384;
  for (int l = 0; l < GUARD_GRID_LEVELS; l++) {
    double s = (double)(1 << l), s4 = s * s * s * s;
    hl[l] = dt * s, rem0l[l] = M4 * h40 * s4, rem1l[l] = M5 * h40 * s4;
    ulpl[l] = GUARD_ROT_ULPS + 4 * l;
  }
}

/* The adaptive march, from t to tend, for the guards still undecided at
 * the shortest grid step; returns 1 if one found a root. */
static inline __attribute__((always_inline)) int grid_undecided(
    const guard_ctx *c, const sc_guard *const *gg, int ng, double wmax,
    double t, double tend, const int *start, int *dec, sc_root *out) {
  int roots = 0;
  for (int i = 0; i < ng; i++) {
    if (dec[i] != STEP_UNDECIDED) continue;
    guard_ctx ci = *c;
    ci.g = gg[i];
    guard_terms ex;
    eval_terms(gg[i], t, &ex);
    if (march(&ci, t, tend, &ex, start[i],
              min2(tend - t, 0.5 * SC_PI / wmax), &out[i]))
      dec[i] = STEP_ROOT, roots = 1;
    else
      dec[i] = STEP_FREE;
  }
  return roots;
}

/* The roots bracketed by [t, tn] refined (the adaptive march's are
 * found), then the earliest decides; both guards of a pair with a root
 * in this grid step: refine_both().  Returns 1 when the march is done;
 * 0 when the later guard of a pair goes on alone up to *tmax. */
static inline __attribute__((always_inline)) int grid_roots(
    const guard_ctx *c, const guard_pair *pr, const sc_guard *const *gg,
    int n, int ng, int marched, double t, double tn, double (*ve)[3],
    double (*vf)[3], const int *dec, const int *start, int *live,
    int *alone, double *tmax, sc_root *out) {
  int e = -1;
  if (ng == 2 && !*alone && !marched && dec[0] == STEP_ROOT &&
      dec[1] == STEP_ROOT && !start[0] && !start[1]) {
    live[0] = live[1] = 0;
    e = refine_both(c, pr, gg, n, t, tn, ve, vf, out);
    if (e < 0) return 1;
  }
  for (int i = 0; i < ng; i++) {
    if (dec[i] != STEP_ROOT || !live[i]) continue;
    if (!out[i].found)
      refine(gg[i], &c->z, c->M3, t, ve[i][0], ve[i][1], tn, vf[i][0],
             vf[i][1], c->atol, c->rtol, &out[i]);
    live[i] = 0;
    if (e < 0 || out[i].t < out[e].t) e = i;
  }
  if (ng == 1 || *alone) return 1;
  int j = 1 - e;
  double lim = pr->limit(pr->ctx, gg[e], &out[e]);
  if (dec[j] == STEP_ROOT && out[j].t > lim) {
    /* beyond the later guard's limit: as if searched up to it */
    out[j] = (sc_root){.t = lim, .steps = out[j].steps};
  }
  if (!live[j] || !(tn < lim)) {
    if (live[j]) out[j].t = lim;
    return 1;
  }
  *tmax = lim; /* the later guard, alone from tn */
  *alone = 1;
  return 0;
}

/* g, g', g'' of one guard (ng = 1) or of both of a pair at t, from cos
 * and sin of each term, into v[0] (and v[1]). */
static inline __attribute__((always_inline)) void grid_vals(
    const sc_guard *g, const guard_pair *pr, int n, int ng, double t,
    const double *cs, const double *sn, double (*v)[3]) {
  if (ng == 1) vals_from(g, n, t, cs, sn, v[0]);
  else vals_pair(g, pr->sgn, n, t, cs, sn, v[0], v[1]);
}

/* The step's rotation of cos and sin (cs, sn into ncs, nsn; one term at
 * a time), then the values at its end tn into vf. */
static inline __attribute__((always_inline)) void grid_next(
    const sc_guard *g, const guard_pair *pr, int n, int ng, double tn,
    const double *cr, const double *sr, const double *cs, const double *sn,
    double *ncs, double *nsn, double (*vf)[3]) {
  for (int k = 0; k < n; k++) {
    ncs[k] = cs[k] * cr[k] - sn[k] * sr[k];
    nsn[k] = sn[k] * cr[k] + cs[k] * sr[k];
  }
  grid_vals(g, pr, n, ng, tn, ncs, nsn, vf);
}

/* The march's tables, made once a search: the rotations per level and
 * term (grid_rotations()), and per level the step, its Hermite
 * remainders and its rotation's ulps (grid_levels()). */
typedef struct {
  double rc[GUARD_GRID_LEVELS][SC_GUARD_MAXFREQ];
  double rs[GUARD_GRID_LEVELS][SC_GUARD_MAXFREQ];
  double hl[GUARD_GRID_LEVELS], rem0l[GUARD_GRID_LEVELS];
  double rem1l[GUARD_GRID_LEVELS], ulpl[GUARD_GRID_LEVELS];
} grid_tables;

/* A step's end tn, length h, Hermite remainders, rotation (cr, sr) and
 * the rotation's ulps: level m's from the tables, or, for the tail step
 * through tmax from t, all computed here (the rotation into ct, st). */
typedef struct {
  double h, tn, rem0, rem1, rot_ulps;
  const double *cr, *sr;
} grid_span;

static inline __attribute__((always_inline)) grid_span grid_span_make(
    const sc_guard *g, const grid_tables *T, const grid_bounds *B,
    int tail, int m, double t, double tn, double tmax, double *ct,
    double *st) {
  grid_span s;
  if (tail) {
    s.h = tmax - t, s.tn = tmax;
    rotation(g, s.h, ct, st);
    s.cr = ct, s.sr = st;
    s.rot_ulps = GUARD_ROT_ULPS + 4 * GUARD_GRID_LEVELS;
    double h4 = s.h * s.h * s.h * s.h / 384;
    s.rem0 = B->M4 * h4, s.rem1 = B->M5 * h4;
  } else {
    s.h = T->hl[m], s.tn = tn, s.rem0 = T->rem0l[m], s.rem1 = T->rem1l[m];
    s.rot_ulps = T->ulpl[m];
    s.cr = T->rc[m], s.sr = T->rs[m];
  }
  return s;
}

/* A shorter step after an undecided one: level m lowered, down to dt and
 * below the tail's length (which is not retried); returns 0 where the
 * step was dt already, or the tail. */
static inline __attribute__((always_inline)) int grid_shorter(
    int *m, long q, double dt, double tmax) {
  if (*m > 0) {
    --*m;
    while (*m > 0 && !((double)(q + (1L << *m)) * dt < tmax)) --*m;
    if ((double)(q + 1) * dt < tmax) return 1;
  }
  return 0;
}

/* The tests of one step for each live guard not proved free by the lanes
 * (bit i of freed: guard i), from the values ve at its start and vf at
 * its end, into dec[]; each live guard's step is counted.  Sets
 * *undecided where a guard is undecided, *roots where one has a root. */
static inline __attribute__((always_inline)) void grid_decide(
    const grid_bounds *B, int ng, const int *live, int freed,
    const int *start, int past, const grid_span *s, double E, double E1,
    double nerr, double (*ve)[3], double (*vf)[3], int *dec, sc_root *out,
    int *undecided, int *roots) {
  double E2 = NAN;
  for (int i = 0; i < ng; i++) {
    if (!live[i]) continue;
    out[i].steps++;
    if (freed >> i & 1) continue; /* dec[i] = STEP_FREE */
    if (isnan(E2)) E2 = B->e20 + B->e21 * s->tn + B->r2 * nerr;
    dec[i] = grid_step(ve[i], vf[i], start[i], past, s->h, E, E1, E2,
                       s->rem0, s->rem1);
    *undecided |= dec[i] == STEP_UNDECIDED;
    *roots |= dec[i] == STEP_ROOT;
  }
}

#if GUARD_PAIR_LANES
/* A pair of two-term guards in two lanes at one end of a step: g, g',
 * g'' (guard i in lane i) and cos and sin of the terms (term k in lane
 * k), carried in registers from step to step (cs[], sn[] hold them for
 * the code one term at a time): a vector load of two numbers just stored
 * one by one would wait for the stores. */
typedef struct {
  __m128d G0, G1, G2, C, S;
} lane_vals;

/* The lanes' values from the guards' ve and the terms' cs, sn. */
static inline __attribute__((always_inline)) lane_vals lane_vals_at(
    double (*ve)[3], const double *cs, const double *sn) {
  lane_vals v;
  v.G0 = _mm_set_pd(ve[1][0], ve[0][0]), v.G1 = _mm_set_pd(ve[1][1], ve[0][1]);
  v.G2 = _mm_set_pd(ve[1][2], ve[0][2]);
  v.C = pair_load(cs), v.S = pair_load(sn);
  return v;
}

/* What the lanes hold from the march's start: the guards' coefficients
 * (L), the values at the first step's start (LE), the rotations per level
 * (LRC, LRS: term k in lane k). */
static inline __attribute__((always_inline)) void lane_start(
    const sc_guard *g, const double *sgn, const grid_tables *T,
    double (*ve)[3], const double *cs, const double *sn, pair_lanes *L,
    lane_vals *LE, __m128d *LRC, __m128d *LRS) {
  *L = pair_lanes_make(g, sgn), *LE = lane_vals_at(ve, cs, sn);
  for (int l = 0; l < GUARD_GRID_LEVELS; l++)
    LRC[l] = pair_load(T->rc[l]), LRS[l] = pair_load(T->rs[l]);
}

/* The step's end F from its start E: the rotation by RC, RS (term k in
 * lane k), then both guards' values at tn. */
static inline __attribute__((always_inline)) void lane_step(
    const pair_lanes *L, const sc_guard *g, double tn, const lane_vals *E,
    __m128d RC, __m128d RS, lane_vals *F) {
  F->C = _mm_sub_pd(_mm_mul_pd(E->C, RC), _mm_mul_pd(E->S, RS));
  F->S = _mm_add_pd(_mm_mul_pd(E->S, RC), _mm_mul_pd(E->C, RS));
  pair_vals(L, g, tn, F->C, F->S, &F->G0, &F->G1, &F->G2);
}

/* Test (A) for both guards where neither starts at a root (bit i of the
 * result: guard i proved free, pair_free()); the values reach ve, vf
 * only where a live guard is not so proved, as grid_step() and the
 * refinement read them there. */
static inline __attribute__((always_inline)) int lane_free(
    const lane_vals *E, const lane_vals *F, const int *start,
    const int *live, double h, double Er, double marg, double (*ve)[3],
    double (*vf)[3]) {
  int freed = pair_free(E->G0, E->G1, F->G0, F->G1, h, Er, marg) &
              ~(start[0] | start[1] << 1);
  if ((live[0] && !(freed & 1)) || (live[1] && !(freed & 2))) {
    pair_store(E->G0, E->G1, E->G2, ve);
    pair_store(F->G0, F->G1, F->G2, vf);
  }
  return freed;
}
#endif

/* The grid march of one guard (ng = 1: c->g into out[0]) or of a pair
 * (ng = 2: c->g and pr->gb, whose sizes are equal, into out[0], out[1]),
 * from 0 over (0, tmax]; start[i]: guard i starts at a root to skip.  One
 * guard: returns 1 with out[0] filled when a root is found.  A pair: both
 * march until one finds its first root (the earlier one when both do in
 * one step); the other goes on alone up to pr->limit of that root, as the
 * later guard of a phase is searched (bk2's first_event); returns 1. */
static inline int grid_march_n(const guard_ctx *c, const guard_pair *pr,
                               int n, int ng, double wmax, double tmax,
                               int *start, sc_root *out) {
  const sc_guard *g = c->g;
  const sc_guard *gg[2] = {g, ng == 2 ? pr->gb : g};
  double dt = 2 * SC_PI / (GUARD_GRID_PER_PERIOD * wmax);
  grid_tables T;
  grid_rotations(g, n, wmax, dt, T.rc, T.rs);
  double cs[SC_GUARD_MAXFREQ] = {0}, sn[SC_GUARD_MAXFREQ] = {0};
  for (int k = 0; k < n; k++) cs[k] = 1, sn[k] = 0;
  const grid_bounds B = grid_bounds_make(c, n, wmax);
  grid_levels(dt, B.M4, B.M5, T.hl, T.rem0l, T.rem1l, T.ulpl);
  /* g, g', g'' of each guard at the step's start (ve) and end (vf): two
   * buffers that trade places when the march moves on, not copied (a
   * copy compiled to a vector load of numbers just stored one by one
   * waits for the stores) */
  double vbuf[2][2][3];
  double(*ve)[3] = vbuf[0], (*vf)[3] = vbuf[1];
  int live[2] = {1, ng == 2}, alone = 0;
  grid_vals(g, pr, n, ng, 0, cs, sn, ve);
#if GUARD_PAIR_LANES
  /* a pair of two-term guards in two lanes (lane_start()) */
  const int lanes = ng == 2 && n == 2;
  pair_lanes L;
  __m128d LRC[GUARD_GRID_LEVELS], LRS[GUARD_GRID_LEVELS];
  lane_vals LE = {0};
  if (lanes) lane_start(g, pr->sgn, &T, ve, cs, sn, &L, &LE, LRC, LRS);
#endif
  /* t = q dt with one rounding (not a running sum, whose rounding would
   * grow with the steps while the rotations follow the exact sum) */
  double t = 0, rerr = 0;
  long q = 0;
  /* The first step is the longest (4 dt): most guards are far from zero
   * at the start, and one that is not fails the step's tests and halves
   * it, down to dt, as any step does.  Starting at dt cost a step or two
   * on every search (fig 5.6: 5.2 steps a two-term search, 2.2 a
   * threshold search; 4.1 and 1 now). */
  int m = GUARD_GRID_LEVELS - 1, past_tried = 0;
  while (t < tmax) {
    double ct[SC_GUARD_MAXFREQ], st[SC_GUARD_MAXFREQ]; /* a tail's rotation */
    double ncs[SC_GUARD_MAXFREQ], nsn[SC_GUARD_MAXFREQ]; /* cos, sin at tn */
    double tn = (double)(q + (1L << m)) * dt;
    /* A step that reaches past tmax is first tried whole (its rotation is
     * in the table): if it proves [t, tn] free of roots, so is [t, tmax].
     * Otherwise the tail step through tmax - t follows, as before. */
    int past = !(tn < tmax) && !past_tried;
    int tail = !(tn < tmax) && !past;
    const grid_span s =
        grid_span_make(g, &T, &B, tail, m, t, tn, tmax, ct, st);
    tn = s.tn;
    double nerr = rerr + s.rot_ulps;
    int dec[2] = {STEP_FREE, STEP_FREE}, undecided = 0, roots = 0, marched = 0;
#if GUARD_PAIR_LANES
    lane_vals LF = LE;
    if (lanes)
      lane_step(&L, g, tn, &LE, tail ? pair_load(s.cr) : LRC[m],
                tail ? pair_load(s.sr) : LRS[m], &LF);
    else
#endif
      grid_next(g, pr, n, ng, tn, s.cr, s.sr, cs, sn, ncs, nsn, vf);
    double E = B.e00 + B.e01 * tn + B.r0 * nerr;
    double E1 = B.e10 + B.e11 * tn + B.r1 * nerr;
    int freed = 0; /* guards proved free by the lanes (bit i: guard i) */
#if GUARD_PAIR_LANES
    if (lanes)
      freed = lane_free(&LE, &LF, start, live, s.h, E,
                        s.rem0 + E + s.h * E1, ve, vf);
#endif
    grid_decide(&B, ng, live, freed, start, past, &s, E, E1, nerr, ve, vf,
                dec, out, &undecided, &roots);
    if (past) {
      if (!undecided) break; /* (a past step brackets no root) */
      past_tried = 1;           /* the tail step from the same state */
      continue;
    }
    if (undecided) {
      /* a shorter step, then the adaptive march for the guards still
       * undecided */
      if (grid_shorter(&m, q, dt, tmax)) continue;
      /* [t, tn] is [t, tend] here: a step of dt, or the tail */
      double tend = min2((double)(q + 1) * dt, tmax);
      roots |= grid_undecided(c, gg, ng, wmax, t, tend, start, dec, out);
      marched = 1;
      tn = tend;
    }
    if (roots && grid_roots(c, pr, gg, n, ng, marched, t, tn, ve, vf, dec,
                            start, live, &alone, &tmax, out))
      return 1;
    for (int i = 0; i < ng; i++) start[i] = 0; /* on to tn */
    if (marched) {
      t = tn, q++;
      anchor(g, t, cs, sn), grid_vals(g, pr, n, ng, t, cs, sn, ve);
#if GUARD_PAIR_LANES
      if (lanes) LE = lane_vals_at(ve, cs, sn);
#endif
      rerr = SC_FAST_TRIG_ULPS, m = 0;
      continue;
    }
    past_tried = 0;
    t = tn, rerr = nerr;
    if (!tail) q += 1L << m;
#if GUARD_PAIR_LANES
    if (lanes) {
      LE = LF;
      if (m + 1 < GUARD_GRID_LEVELS) m++;
      continue;
    }
#endif
    for (int k = 0; k < n; k++) cs[k] = ncs[k], sn[k] = nsn[k];
    {
      double(*tmp)[3] = ve;
      ve = vf, vf = tmp;
    }
    if (m + 1 < GUARD_GRID_LEVELS) m++;
  }
  if (ng == 2)
    for (int i = 0; i < 2; i++)
      if (live[i]) out[i].t = tmax;
  return 0;
}

/* The march with the number of terms a constant, so that the compiler
 * unrolls its loops (bk2's guards have one or two terms). */
static int grid_march(const guard_ctx *c, double wmax, double tmax,
                      int at_start_root, sc_root *out) {
  int start[1] = {at_start_root};
  switch (c->g->n) {
  case 1:
    return grid_march_n(c, NULL, 1, 1, wmax, tmax, start, out);
  case 2:
    return grid_march_n(c, NULL, 2, 1, wmax, tmax, start, out);
  default:
    return grid_march_n(c, NULL, c->g->n, 1, wmax, tmax, start, out);
  }
}

/* No root yet: the result of a search that finds none up to tmax. */
static inline void root_none(sc_root *out, double tmax) {
  out->found = out->tangent = 0;
  out->t = tmax;
  out->bracket = 0;
  out->slope = 0;
  out->curv = 0;
  out->steps = 0;
  out->ntrig = 0;
}

/* A search's context for g (c->g, c->z, c->amp, atol, rtol; c->M3 and
 * c->m3 are left to the search), and the fastest frequency of g (0
 * without sinusoids), or -1 if a search of g is not well posed: 0 <= n
 * <= SC_GUARD_MAXFREQ, w > 0, finite coefficients, tmax finite and > 0,
 * atol > 0, rtol >= 0.  Every search starts here, so the coefficients are
 * tested through the sizes the search needs anyway, not one by one: a
 * coefficient that is infinite or NaN makes the sum of the sizes infinite
 * or NaN (a w that is, with a zero amplitude, 0 * w = NaN), and so does
 * one whose square overflows (|a| > 1e154), which the sizes could not
 * bound anyway (a sum past DBL_MAX, refused as well). */
static inline double search_setup(const sc_guard *g, int n, double tmax,
                                  double atol, double rtol, guard_ctx *c) {
  if (!g || n < 0 || n > SC_GUARD_MAXFREQ || !(tmax > 0) ||
      !(tmax < INFINITY) || !(atol > 0) || !(rtol >= 0))
    return -1;
  c->g = g;
  c->z = guard_sizes(g, n, c->amp);
  c->atol = atol, c->rtol = rtol;
  double wmin = INFINITY, wmax = 0;
  for (int k = 0; k < n; k++) {
    double w = g->w[k];
    wmin = w < wmin ? w : wmin; /* (a NaN w is caught by the sizes) */
    wmax = w > wmax ? w : wmax;
  }
  double all = (c->z.c0 + c->z.c1) + (c->z.amp + c->z.wamp);
  return wmin > 0 && all < INFINITY ? wmax : -1;
}

/* sc_guard_first_root with the number of terms n a constant where it is
 * one (sc_guard_first_root()), g->n otherwise (g may be NULL then). */
static inline int first_root_n(const sc_guard *g, int n, double tmax,
                               int skip_start, double atol, double rtol,
                               sc_root *out) {
  root_none(out, tmax);
  guard_ctx c; /* sizes once per search */
  double wmax = search_setup(g, n, tmax, atol, rtol, &c);
  if (wmax < 0) return SC_EINVAL;
  /* g, g', g'' at 0 (cos = 1, sin = 0); the terms' own values are not
   * kept: only the march without sinusoids (n = 0) starts from them */
  double g0 = g->c0, g1 = g->c1, g2 = 0;
  for (int k = 0; k < n; k++) {
    double w = g->w[k], v = g->a[k];
    g0 += v, g1 += w * g->b[k], g2 -= w * w * v;
  }
  /* A guard that starts within rounding of zero: a root at 0 if it moves
   * up through zero there (the events of docs/model.md are all upward
   * crossings), otherwise the start root is skipped. */
  if (fabs(g0) <= round_at(&c.z, 0)) {
    int upward = g1 > 0 || (g1 == 0 && g2 > 0);
    if (!skip_start && upward) {
      out->found = 1;
      out->t = 0;
      out->slope = g1;
      out->curv = g2;
      return SC_OK;
    }
    skip_start = 1;
  }
  if (n == 1 && g->c1 == 0 &&
      closed_form(g, &c.z, c.amp[0], tmax, skip_start, out))
    return SC_OK;
  out->tangent = 0;
  /* Out of reach: |c0 + c1 t| stays above the sum of the amplitudes (and
   * the rounding) on all of [0, tmax], so g keeps the sign of c0. */
  if (!skip_start) {
    double lo = min2(fabs(g->c0), fabs(g->c0 + g->c1 * tmax));
    if ((g->c0 > 0) == (g->c0 + g->c1 * tmax > 0) &&
        lo > c.z.amp + round_at(&c.z, tmax))
      return SC_OK;
  }
  /* The bound M3 on the third derivative, term by term. */
  c.M3 = 0;
  for (int k = 0; k < n; k++) {
    double w = g->w[k];
    c.m3[k] = c.amp[k] * w * w * w;
    c.M3 += c.m3[k];
  }
  if (wmax > 0) grid_march(&c, wmax, tmax, skip_start, out);
  else {
    guard_terms e;
    e.g0 = g0, e.g1 = g1, e.g2 = g2;
    march(&c, 0, tmax, &e, skip_start, tmax, out);
  }
  return SC_OK;
}

int sc_guard_first_root(const sc_guard *g, double tmax, int skip_start,
                        double atol, double rtol, sc_root *out) {
  /* (bk2's guards have one or two terms: their loops unrolled) */
  if (g && g->n == 1)
    return first_root_n(g, 1, tmax, skip_start, atol, rtol, out);
  if (g && g->n == 2)
    return first_root_n(g, 2, tmax, skip_start, atol, rtol, out);
  return first_root_n(g, g ? g->n : 0, tmax, skip_start, atol, rtol, out);
}

/* Whether h is g with each term times +-1 (the same c0, c1 and
 * frequencies, two terms or more): the signs into sgn[]. */
static int guard_pairs(const sc_guard *g, const sc_guard *h, double *sgn) {
  if (g->n != h->n || g->n < 2 || g->n > SC_GUARD_MAXFREQ || g->c0 != h->c0 ||
      g->c1 != h->c1)
    return 0;
  for (int k = 0; k < g->n; k++) {
    if (g->w[k] != h->w[k]) return 0;
    if (h->a[k] == g->a[k] && h->b[k] == g->b[k]) sgn[k] = 1;
    else if (h->a[k] == -g->a[k] && h->b[k] == -g->b[k]) sgn[k] = -1;
    else return 0;
  }
  return 1;
}

/* The pair's search, with the later guard limited: guard j from
 * scratch, after guard i's root. */
static int pair_later(const sc_guard *g, int i, const int *skip, double atol,
                      double rtol, sc_guard_limit_fn limit, void *ctx,
                      sc_root *out) {
  int j = 1 - i;
  double lim = limit(ctx, &g[i], &out[i]);
  return sc_guard_first_root(&g[j], lim, skip[j], atol, rtol, &out[j]);
}

int sc_guard_first_root_pair(const sc_guard *g, double tmax, const int *skip,
                             double atol, double rtol, sc_guard_limit_fn limit,
                             void *ctx, sc_root *out) {
  guard_pair pr = {&g[1], {0}, limit, ctx};
  if (!guard_pairs(&g[0], &g[1], pr.sgn)) {
    /* one after the other: g[0] to tmax, g[1] up to the limit of g[0]'s
     * root */
    int st = sc_guard_first_root(&g[0], tmax, skip[0], atol, rtol, &out[0]);
    if (st || out[0].found)
      return st ? st : pair_later(g, 0, skip, atol, rtol, limit, ctx, out);
    return sc_guard_first_root(&g[1], tmax, skip[1], atol, rtol, &out[1]);
  }
  root_none(&out[0], tmax);
  root_none(&out[1], tmax);
  const sc_guard *ga = &g[0];
  int n = ga->n;
  /* one context: the guards' sizes are equal (and g[1] is finite where
   * g[0] is: the same numbers, +-) */
  guard_ctx c;
  double wmax = search_setup(ga, n, tmax, atol, rtol, &c);
  if (wmax < 0) return SC_EINVAL;
  /* each guard at 0, as sc_guard_first_root() takes it */
  double E0 = round_at(&c.z, 0);
  int sk[2] = {skip[0], skip[1]}, at0 = -1;
  for (int i = 0; i < 2; i++) {
    double g0 = ga->c0, g1 = ga->c1, g2 = 0;
    for (int k = 0; k < n; k++) {
      double w = ga->w[k], v = i ? pr.sgn[k] * ga->a[k] : ga->a[k];
      double b = i ? pr.sgn[k] * ga->b[k] : ga->b[k];
      g0 += v, g1 += w * b, g2 -= w * w * v;
    }
    if (!(fabs(g0) <= E0)) continue;
    if (!sk[i] && (g1 > 0 || (g1 == 0 && g2 > 0))) {
      out[i].found = 1;
      out[i].t = 0;
      out[i].slope = g1;
      out[i].curv = g2;
      if (at0 < 0) at0 = i;
    }
    sk[i] = 1;
  }
  if (at0 >= 0) /* a root at 0 is the earlier */
    return out[1 - at0].found
               ? SC_OK
               : pair_later(g, at0, skip, atol, rtol, limit, ctx, out);
  /* Out of reach (the same for both: one c0, c1, one size): |c0 + c1 t|
   * above the amplitudes and the rounding on all of [0, tmax]. */
  double lo = min2(fabs(ga->c0), fabs(ga->c0 + ga->c1 * tmax));
  int reach = !((ga->c0 > 0) == (ga->c0 + ga->c1 * tmax > 0) &&
                lo > c.z.amp + round_at(&c.z, tmax));
  if (!reach && !sk[0] && !sk[1]) return SC_OK;
  if (!reach && (!sk[0] || !sk[1])) {
    int j = sk[0] ? 0 : 1; /* the one that starts at zero is searched */
    return sc_guard_first_root(&g[j], tmax, skip[j], atol, rtol, &out[j]);
  }
  c.M3 = 0;
  for (int k = 0; k < n; k++) {
    double w = ga->w[k];
    c.m3[k] = c.amp[k] * w * w * w;
    c.M3 += c.m3[k];
  }
  if (n == 2) grid_march_n(&c, &pr, 2, 2, wmax, tmax, sk, out);
  else grid_march_n(&c, &pr, n, 2, wmax, tmax, sk, out);
  return SC_OK;
}
