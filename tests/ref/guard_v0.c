/* FROZEN REFERENCE, test-only: the certified first-root search exactly as
 * src/hybrid/guard.c had it before the grid march, renamed
 * sc_guard_first_root_v0 and self-contained (its own evaluation), so that
 * tests/test_map_equiv.c can run the map with the earlier search beside
 * the current one.  Do not edit: it is the yardstick.
 *
 * Certified first-root location for guards made of a linear term and
 * sinusoids (hybrid.h, docs/events.md).
 *
 * The march covers (0, tmax] by intervals [t, t + h].  Write s = time from
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
#include "slipcont/hybrid.h"
#include "ref/guard_v0.h"

/* Rounding bound on one evaluation of g: a few ulps of each term's size,
 * the sinusoids' arguments w t included (their rounding grows with t). */
#define GUARD_ROUND_ULPS 8.0
/* Iterations of the bracketed Newton refinement: bisection alone halves a
 * bracket of length <= tmax down to 1 ulp within ~1100 steps; Newton ends
 * far sooner, so this cap is never the reason to stop in practice. */
#define GUARD_MAX_REFINE 200

static void v0_guard_eval(const sc_guard *g, double t, double *g0, double *g1,
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

/* Sizes of the guard's terms, computed once per search: the rounding
 * bound at t is GUARD_ROUND_ULPS eps (|c0| + |c1| t + amp + wamp t). */
typedef struct {
  double c0, c1, amp, wamp;
} guard_size;

/* The sizes, and each sinusoid's amplitude into amp[] (one hypot each). */
static guard_size guard_sizes(const sc_guard *g, double *amp) {
  guard_size z = {fabs(g->c0), fabs(g->c1), 0, 0};
  for (int k = 0; k < g->n; k++) {
    amp[k] = hypot(g->a[k], g->b[k]);
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

/* Bracketed Newton on [lo, hi] where g(lo), g(hi) differ in sign and g is
 * monotone: start from the secant point; stop when g is within rounding of
 * zero, or when a Newton step inside the bracket is below the tolerance
 * (convergence is quadratic there, so the step itself bounds the error,
 * and the slope at the last point is the root's to O(step)). */
static void refine(const sc_guard *g, const guard_size *z, double lo,
                   double glo, double dlo, double hi, double ghi, double dhi,
                   double atol, double rtol, sc_root *out) {
  /* Start from the root of the cubic Hermite interpolant of g and g' at
   * both ends (a few Newton steps on the cubic, no trigonometry), which
   * is far closer than the secant point: one or two Newton steps on g
   * then suffice. */
  double h = hi - lo, t = lo - glo * h / (ghi - glo);
  if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
  {
    double c1 = dlo, dg = ghi - glo;
    double c2 = (3 * dg / h - 2 * dlo - dhi) / h;
    double c3 = (dlo + dhi - 2 * dg / h) / (h * h);
    double s = t - lo;
    for (int it = 0; it < 4; it++) {
      double p = glo + s * (c1 + s * (c2 + s * c3));
      double dp = c1 + s * (2 * c2 + 3 * s * c3);
      double sn = dp != 0 ? s - p / dp : s;
      if (!(sn > 0 && sn < h)) break;
      s = sn;
    }
    t = lo + s;
  }
  double v = 0, d = 0, bracket = hi - lo;
  for (int it = 0; it < GUARD_MAX_REFINE; it++) {
    v0_guard_eval(g, t, &v, &d, NULL);
    if (fabs(v) <= round_at(z, t)) {
      bracket = 0;
      break;
    }
    if ((v > 0) == (glo > 0)) lo = t, glo = v;
    else hi = t;
    double tn = t - v / d;
    if (d != 0 && tn > lo && tn < hi) {
      if (fabs(tn - t) <= tol_at(tn, atol, rtol)) {
        bracket = fabs(tn - t);
        t = tn;
        break;
      }
      t = tn;
    } else {
      t = 0.5 * (lo + hi);
    }
    bracket = hi - lo;
    if (bracket <= tol_at(hi, atol, rtol)) break;
  }
  out->t = t;
  out->bracket = bracket;
  out->found = 1;
  out->slope = d;
}

/* A single sinusoid and a constant: roots in closed form.  g = c0 +
 * R cos(w t - phi).  Ascending roots sit at w t = phi - theta, descending
 * ones at phi + theta (mod 2 pi), cos theta = -c0 / R.  Returns 0 when the
 * case is degenerate and the march should decide. */
static int closed_form(const sc_guard *g, const guard_size *z, double R,
                       double tmax, int skip_start, sc_root *out) {
  double a = g->a[0], b = g->b[0], w = g->w[0], c0 = g->c0;
  double E = round_at(z, 0);
  if (R <= E) return 0;
  double gap = R - fabs(c0);
  if (gap < -E) return 1; /* never reaches zero: out says not found */
  double phi = atan2(b, a);
  const double twopi = 2 * SC_PI;
  double asc, desc;
  if (gap <= E) {
    /* touches: cos(w t - phi) = -sign(c0) */
    asc = desc = c0 < 0 ? phi : phi + SC_PI;
    out->tangent = 1;
  } else {
    double theta = atan2(sqrt(gap * (R + fabs(c0))), -c0);
    asc = phi - theta;
    desc = phi + theta;
  }
  asc = fmod(asc, twopi);
  if (asc < 0) asc += twopi;
  desc = fmod(desc, twopi);
  if (desc < 0) desc += twopi;
  double alpha;
  if (skip_start) {
    double g1;
    v0_guard_eval(g, 0, NULL, &g1, NULL);
    if (g1 == 0 || out->tangent) return 0;
    /* the start root is of the type of g'(0): the next is the other type */
    alpha = g1 < 0 ? asc : desc;
    if (alpha * 1 <= 4 * DBL_EPSILON * twopi) alpha += twopi;
  } else {
    alpha = fmin(asc, desc);
  }
  double t = alpha / w;
  if (t <= tmax) {
    out->found = 1;
    out->t = t;
    v0_guard_eval(g, t, NULL, &out->slope, NULL);
    out->bracket = out->tangent ? 0 : E / fmax(fabs(out->slope), DBL_MIN);
  }
  return 1;
}

int sc_guard_first_root_v0(const sc_guard *g, double tmax, int skip_start,
                        double atol, double rtol, sc_root *out) {
  out->found = out->tangent = 0;
  out->t = tmax;
  out->bracket = 0;
  out->slope = 0;
  out->steps = 0;
  if (!g || g->n < 0 || g->n > SC_GUARD_MAXFREQ || !isfinite(g->c0) ||
      !isfinite(g->c1) || !(tmax > 0) || !isfinite(tmax) || !(atol > 0) ||
      !(rtol >= 0))
    return SC_EINVAL;
  double wmax = 0;
  for (int k = 0; k < g->n; k++) {
    if (!(g->w[k] > 0) || !isfinite(g->w[k]) || !isfinite(g->a[k]) ||
        !isfinite(g->b[k]))
      return SC_EINVAL;
    wmax = fmax(wmax, g->w[k]);
  }
  /* A guard that starts within rounding of zero: a root at 0 if it moves
   * up through zero there (the events of docs/model.md are all upward
   * crossings), otherwise the start root is skipped. */
  double amp[SC_GUARD_MAXFREQ];
  guard_size z = guard_sizes(g, amp); /* once per search */
  guard_terms e;
  eval_terms(g, 0, &e);
  double g0 = e.g0, g1 = e.g1, g2 = e.g2;
  if (fabs(g0) <= round_at(&z, 0)) {
    int upward = g1 > 0 || (g1 == 0 && g2 > 0);
    if (!skip_start && upward) {
      out->found = 1;
      out->t = 0;
      out->slope = g1;
      return SC_OK;
    }
    skip_start = 1;
  }
  if (g->n == 1 && g->c1 == 0 &&
      closed_form(g, &z, amp[0], tmax, skip_start, out))
    return SC_OK;
  out->tangent = 0;
  /* The bound M3 on the third derivative, term by term. */
  double M3 = 0, m3[SC_GUARD_MAXFREQ];
  for (int k = 0; k < g->n; k++) {
    double w = g->w[k];
    m3[k] = amp[k] * w * w * w;
    M3 += m3[k];
  }
  /* First trial step: a quarter of the fastest period, or all of tmax. */
  double h = wmax > 0 ? fmin(tmax, 0.5 * SC_PI / wmax) : tmax;
  double t = 0;
  int at_start_root = skip_start;
  while (t < tmax) {
    h = min2(h, tmax - t);
    out->steps++;
    double E = round_at(&z, t + h);
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
      out->tangent = fabs(g1) * tol_at(t, atol, rtol) <= E;
      return SC_OK;
    }
    /* (A) no root in [t, t+h]: the quadratic with the global remainder,
     * or failing that (with several frequencies) the bound that takes
     * some terms by their amplitude. */
    if (!at_start_root &&
        (quad_min(sigma, g0, g1, g2, h) - M3 * h * h * h / 6 > E ||
         (g->n > 1 && amplitude_bound(g, &e, amp, m3, sigma, t, h) > E))) {
      t += h;
      eval_terms(g, t, &e);
      g0 = e.g0, g1 = e.g1, g2 = e.g2;
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
          return SC_OK;
        }
        refine(g, &z, t, g0, g1, t + h, ge, ge1, atol, rtol, out);
        return SC_OK;
      }
      at_start_root = 0;
      t += h;
      e = eh;
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
        eval_terms(g, t, &e);
        g0 = e.g0, g1 = e.g1, g2 = e.g2;
        continue;
      }
      out->found = 1;
      out->tangent = 1;
      out->t = t + 0.5 * h;
      out->bracket = h;
      v0_guard_eval(g, out->t, NULL, &out->slope, NULL);
      return SC_OK;
    }
  }
  return SC_OK;
}
