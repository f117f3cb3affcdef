/* The first root of a guard with any number of sinusoids (hybrid.h,
 * sc_guard_long_first_root(); docs/chain.md, "Events").
 *
 * Every event of the chain is a guard that reaches zero from below.  At a
 * time t where g(t) < 0, Taylor's theorem with M2 >= |g''| everywhere
 * gives g(t + s) <= g(t) + g'(t) s + M2 s^2 / 2, so g stays negative until
 * the first positive zero of that quadratic: the march steps there, and
 * no root is ever stepped over.  Near a simple root the step is Newton's,
 * shortened by the curvature term, so the march converges from below
 * with the error squared at each step; at a maximum that only touches
 * zero, the steps shrink geometrically (by ~0.41 of the distance to the
 * maximum) until g passes it or comes within rounding of zero, which is
 * then a root (a touch: a grazing). */
#include <float.h>
#include <math.h>
#include <string.h>

#include "hybrid/trig.h"
#include "slipcont/hybrid.h"

/* Rounding bound on one evaluation of g: a few ulps of each term's size,
 * the sinusoids' arguments w t included (their rounding grows with t),
 * as guard.c's GUARD_ROUND_ULPS. */
#define LONG_ROUND_ULPS 8.0
#define LONG_TWO_PI 6.28318530717958647692

void sc_guard_long_eval(const sc_guard_long *g, double t, double *g0,
                        double *g1, double *g2) {
  double v0 = g->c0 + g->c1 * t, v1 = g->c1, v2 = 0;
  for (int k = 0; k < g->n; k++) {
    double w = g->w[k], c, s;
    sc_fast_sincos(w * t, &s, &c); /* within 2 ulps: LONG_ROUND_ULPS */
    double p = g->a[k] * c + g->b[k] * s, q = g->b[k] * c - g->a[k] * s;
    v0 += p;
    v1 += w * q;
    v2 -= w * w * p;
  }
  if (g0) *g0 = v0;
  if (g1) *g1 = v1;
  if (g2) *g2 = v2;
}

/* The guard's bounds: M2 >= |g''|, M3 >= |g'''| everywhere; sizes for
 * the rounding of g and g' at time t (size0 + size0t t, size1 + size1t t). */
typedef struct {
  double M2, M3, size0, size0t, size1, size1t;
} long_bounds;
_Static_assert(sizeof(long_bounds) ==
                   sizeof(((sc_guard_long_march *)0)->bounds),
               "a march keeps its guard's bounds");

/* The amplitudes are sqrt(a^2 + b^2), not hypot: a coefficient whose
 * square overflows (|a| > 1e154) makes a bound infinite, refused. */
static int long_bounds_make(const sc_guard_long *g, long_bounds *z) {
  *z = (long_bounds){0, 0, fabs(g->c0), fabs(g->c1), fabs(g->c1), 0};
  if (!isfinite(g->c0) || !isfinite(g->c1) || g->n < 0) return -1;
  for (int k = 0; k < g->n; k++) {
    double w = g->w[k], amp = sqrt(g->a[k] * g->a[k] + g->b[k] * g->b[k]);
    if (!(w > 0) || !isfinite(w) || !isfinite(amp)) return -1;
    z->M2 += w * w * amp;
    z->M3 += w * w * w * amp;
    z->size0 += amp;
    z->size0t += w * amp;
    z->size1 += w * amp;
    z->size1t += w * w * amp;
  }
  return isfinite(z->M3) && isfinite(z->size1t) ? 0 : -1;
}

/* The first time after a start on zero (g(t0) within rounding of 0) that
 * g can reach zero again, from g' < 0 (quadratic bound) or g' = 0 > g''
 * (cubic bound); 0 if g neither falls nor curves down there. */
static double leave_zero(const long_bounds *z, double g1, double g2,
                         double r1) {
  if (g1 < -r1) return z->M2 > 0 ? -2 * g1 / z->M2 : HUGE_VAL;
  if (g2 < 0) return z->M3 > 0 ? -3 * g2 / z->M3 : HUGE_VAL;
  return 0;
}

/* The step from a point where g = g0 < 0 with slope g1: the first zero of
 * g0 + g1 s + M2 s^2 / 2 (written without cancellation). */
static double safe_step(const long_bounds *z, double g0, double g1) {
  if (z->M2 > 0) return -2 * g0 / (g1 + sqrt(g1 * g1 - 2 * z->M2 * g0));
  return g1 > 0 ? -g0 / g1 : HUGE_VAL;
}

/* The start: g(0), and a start on zero handled (a root at 0, or the
 * first time g can come back to zero).  Returns 1 when the march is over
 * (a root at 0 in m->root), 0 to march on, or a status < 0. */
static int march_start(const sc_guard_long *g, const long_bounds *z,
                       int skip_start, sc_guard_long_march *m) {
  const double ulp = LONG_ROUND_ULPS * DBL_EPSILON;
  double g2;
  sc_guard_long_eval(g, 0, &m->g0, &m->g1, &g2);
  m->t = m->tsafe = 0;
  m->stage = SC_MARCH_AT;
  if (fabs(m->g0) <= ulp * z->size0) {
    double r1 = ulp * z->size1, g1 = m->g1;
    if (!skip_start && (g1 > r1 || (fabs(g1) <= r1 && g2 > 0))) {
      m->root = (sc_root_long){1, fabs(g1) <= r1, 0, g1, 0};
      m->stage = SC_MARCH_DONE;
      return 1;
    }
    double s = leave_zero(z, g1, g2, r1);
    if (!(s > 0)) return SC_ENOCONV;
    m->t = m->tsafe = s;
    m->stage = SC_MARCH_TO; /* g to be evaluated there */
  }
  return 0;
}

/* A guard of one sinusoid and no drift, c0 + R cos(w t - phi), has its
 * roots in closed form: from a point t0 where it is below zero (the start,
 * or where a start on zero was left), the first root is the first
 * rising crossing w t = phi - acos(-c0 / R) + 2 pi k at or after t0, or,
 * when the top c0 + R is at or below zero but within rounding of it, the
 * first top at or after t0 (a touch).  The march would take ~5 steps to
 * the same root (within rounding).  The root goes into m->root, known
 * (stage SC_MARCH_KNOWN) until a tmax reaches it; t = HUGE_VAL for none. */
static void one_term(const sc_guard_long *g, const long_bounds *z,
                     sc_guard_long_march *m) {
  const double ulp = LONG_ROUND_ULPS * DBL_EPSILON, two_pi = LONG_TWO_PI;
  double w = g->w[0], R = z->size0 - fabs(g->c0), t0 = m->t;
  double phi = sc_atan2(g->b[0], g->a[0]), x = -g->c0 / R;
  /* the first angle base + 2 pi k at or after w t0 */
  double base = phi, top = 1;
  if (x < 1) base = phi - acos(fmax(x, -1.0)), top = 0;
  double k = ceil((w * t0 - base) / two_pi), t = (base + two_pi * k) / w;
  while (t < t0) t = (base + two_pi * ++k) / w;
  double r0 = ulp * (z->size0 + z->size0t * t);
  double slope = top ? 0 : w * R * sqrt(fmax(1 - x * x, 0.0));
  int found = !top || g->c0 + R >= -r0;
  double r1 = ulp * (z->size1 + z->size1t * t);
  int touch = top || slope <= r1 + sqrt(2 * r0 * z->M2);
  m->root = (sc_root_long){found, touch, found ? t : HUGE_VAL, slope, 1};
  m->steps = 1;
  m->stage = SC_MARCH_KNOWN;
}

int sc_guard_long_advance(const sc_guard_long *g, double tmax, int skip_start,
                          sc_guard_long_march *m, sc_root_long *out) {
  long_bounds z;
  if (!g || !m || !isfinite(tmax) || tmax < 0) return SC_EINVAL;
  if (m->stage == SC_MARCH_NEW) {
    if (long_bounds_make(g, &z)) return SC_EINVAL;
    memcpy(m->bounds, &z, sizeof z);
    m->steps = 0;
    int st = march_start(g, &z, skip_start, m);
    if (st < 0) return st;
    /* the closed form from below zero, or from a start on zero left
     * falling or at a top; the march's own ways elsewhere: a start above
     * zero is a root at once, and one rising from zero (skipped) is above
     * it where the march resumes, a root there */
    const double r = LONG_ROUND_ULPS * DBL_EPSILON;
    if (g->n == 1 && g->c1 == 0 &&
        (m->stage == SC_MARCH_TO ? m->g1 <= r * z.size1
                                 : m->stage == SC_MARCH_AT &&
                                       m->g0 < -r * z.size0))
      one_term(g, &z, m);
  } else
    memcpy(&z, m->bounds, sizeof z);
  if (m->stage == SC_MARCH_KNOWN) {
    if (!(m->root.t <= tmax)) {
      *out = (sc_root_long){0, 0, tmax, NAN, m->steps};
      return SC_OK;
    }
    m->stage = SC_MARCH_DONE;
  }
  if (m->stage == SC_MARCH_DONE) {
    *out = m->root;
    out->steps = m->steps;
    return SC_OK;
  }
  *out = (sc_root_long){0, 0, tmax, NAN, m->steps};
  const double ulp = LONG_ROUND_ULPS * DBL_EPSILON;
  if (m->stage == SC_MARCH_TO) {
    if (m->t > tmax) return SC_OK;
    sc_guard_long_eval(g, m->t, &m->g0, &m->g1, NULL);
    out->steps = ++m->steps;
    m->stage = SC_MARCH_AT;
  }
  /* g < 0 on [0, m->tsafe), up to rounding */
  for (;;) {
    double t = m->t, g0 = m->g0, g1 = m->g1;
    double r0 = ulp * (z.size0 + z.size0t * t);
    if (g0 >= -r0) {
      /* within rounding of zero, from below: the root; one Newton step
       * takes an overshoot of the last step back to the zero, never
       * before the last point known below it (a guard that starts above
       * zero, past its event, has its root at once).  A touch: g' no
       * larger than a parabola of curvature M2 has within rounding of
       * its top, sqrt(2 r0 M2). */
      double r1 = ulp * (z.size1 + z.size1t * t);
      if (g1 > r1 && g0 > 0) t = fmax(m->tsafe, t - g0 / g1);
      int touch = fabs(g1) <= r1 + sqrt(2 * r0 * z.M2);
      m->root = (sc_root_long){1, touch, t, g1, m->steps};
      m->stage = SC_MARCH_DONE;
      *out = m->root;
      return SC_OK;
    }
    double s = safe_step(&z, g0, g1);
    if (!(t + s <= tmax)) return SC_OK; /* none up to tmax */
    m->tsafe = t;
    m->t = t + s;
    sc_guard_long_eval(g, m->t, &m->g0, &m->g1, NULL);
    out->steps = ++m->steps;
    if (m->steps > SC_GUARD_LONG_MAXSTEPS) return SC_ENOCONV;
  }
}

int sc_guard_long_first_root(const sc_guard_long *g, double tmax,
                             int skip_start, sc_root_long *out) {
  sc_guard_long_march m = {.stage = SC_MARCH_NEW};
  return sc_guard_long_advance(g, tmax, skip_start, &m, out);
}
