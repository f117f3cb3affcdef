/* The closed-form flows of the bk2 model (`flows = exact`, bk2_impl.h):
 * in every slip mode the motion is a sum of sinusoids and a linear drift,
 * so the guards are known in closed form and their first roots are
 * located by the certified search of src/hybrid/guard.c.  A phase on
 * duals (derivatives in d and the parameters) and a value-only fast path
 * for plain evaluations that computes the same numbers.  The derivation
 * of every formula is in docs/derivations.md. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

#include "hybrid/dual.h"
#include "models/bk2_impl.h"
#include "hybrid/hybrid_impl.h"
#include "slipcont/hybrid.h"

/* Slip phases of one block alone last less than one period; a phase of
 * both blocks is quasi-periodic, so a horizon is needed: this many periods
 * of its slow mode (frequency 1) without a re-stick make f undefined. */
#define SLIP12_PERIODS 16


/* cos and sin of oscillator k's w t at the root r of a guard of this
 * flow, when the search left them (a guard's term k is oscillator k, the
 * same frequency: guard_restick, guard_threshold): {cos, sin} into
 * cs[2k], cs[2k+1]; returns cs, or NULL (libm at t then). */
static const double *event_trig(const sc_root *r, int mode, double *cs) {
  int need = mode == SC_BK2_SLIP12 ? 2 : 1;
  if (!r || r->ntrig < need) return NULL;
  for (int k = 0; k < need; k++) cs[2 * k] = r->cs[k], cs[2 * k + 1] = r->sn[k];
  return cs;
}

/* A horizon past which the guard keeps one sign (or its pattern repeats):
 * one period for a pure sinusoid, the time the linear term needs to
 * dominate otherwise. */
static double guard_horizon(const sc_guard *g) {
  double wmin = HUGE_VAL;
  for (int k = 0; k < g->n; k++)
    if (g->w[k] < wmin) wmin = g->w[k]; /* fmin without the libm call */
  double period = 2 * SC_PI / wmin;
  if (g->c1 != 0) {
    double amp = 0; /* (>= the amplitude: enough here) */
    for (int k = 0; k < g->n; k++) amp += fabs(g->a[k]) + fabs(g->b[k]);
    return (fabs(g->c0) + amp) / fabs(g->c1) + period;
  }
  if (g->n == 1) return 1.01 * period;
  return SLIP12_PERIODS * period;
}

/* ---- guards beyond their first root ------------------------------------ */

/* Most roots of a guard's derivative walked through in one phase: a slip
 * of both blocks lasts at most SLIP12_PERIODS slow periods, in which the
 * fast mode (w2 / w1 times faster) turns a few dozen times for the
 * parameter ranges of docs/model.md; past this the walk gives up and says
 * so (a border is then missing from the list, and the code is dropped). */
#define WALK_MAX 512

/* g(t0 + s) as a guard in s (angle addition on each sinusoid). */
static sc_guard guard_shift(const sc_guard *g, double t0) {
  sc_guard h = *g;
  h.c0 = g->c0 + g->c1 * t0;
  for (int k = 0; k < g->n; k++) {
    double s = sin(g->w[k] * t0), c = cos(g->w[k] * t0);
    h.a[k] = g->a[k] * c + g->b[k] * s;
    h.b[k] = g->b[k] * c - g->a[k] * s;
  }
  return h;
}

/* g' as a guard. */
static sc_guard guard_prime(const sc_guard *g) {
  sc_guard h = {0};
  h.c0 = g->c1;
  h.n = g->n;
  for (int k = 0; k < g->n; k++) {
    h.w[k] = g->w[k];
    h.a[k] = g->w[k] * g->b[k];
    h.b[k] = -g->w[k] * g->a[k];
  }
  return h;
}

/* The first root of g in (t0, tmax]; skip: g(t0) = 0 by construction.
 * Returns 1 found, 0 none, < 0 for a malformed guard. */
static int next_root(const sc_guard *g, double t0, double tmax, int skip,
                     double atol, double rtol, sc_root *r) {
  if (!(tmax > t0)) return 0;
  sc_guard h = t0 > 0 ? guard_shift(g, t0) : *g;
  if (sc_guard_first_root(&h, tmax - t0, skip, atol + rtol * t0, rtol, r))
    return -1;
  if (!r->found) return 0;
  r->t += t0;
  if (t0 > 0) r->ntrig = 0; /* its cos and sin are of t - t0 */
  return 1;
}

/* The first root of g after t0 at which g rises through zero (or touches
 * it): a guard's event.  Roots where g falls are passed. */
static int upward_root(const sc_guard *g, double t0, double tmax, int skip,
                       double atol, double rtol, sc_root *r) {
  for (int it = 0; it < WALK_MAX; it++) {
    int st = next_root(g, t0, tmax, skip, atol, rtol, r);
    if (st <= 0) return st;
    if (r->slope > 0 || r->tangent) return 1;
    t0 = r->t;
    skip = 1;
  }
  return -2;
}

/* The local maxima of g in (0, tend): returns their number (-1: malformed,
 * -2: more than WALK_MAX), the time of the highest in *tbest (g there in
 * *gbest) and of the n-th (from 1) in *tnth when nth > 0. */
static int guard_maxima(const sc_guard *g, double tend, double atol,
                        double rtol, int nth, double *tnth, double *tbest,
                        double *gbest) {
  sc_guard gp = guard_prime(g);
  int n = 0, skip = 0;
  double t = 0;
  *gbest = -HUGE_VAL;
  for (int it = 0; it < WALK_MAX; it++) {
    sc_root r;
    int st = next_root(&gp, t, tend, skip, atol, rtol, &r);
    if (st < 0) return -1;
    if (st == 0 || r.t >= tend) return n;
    if (r.slope < 0) { /* g' falls through zero: a maximum of g */
      double gv;
      sc_guard_eval(g, r.t, &gv, NULL, NULL);
      n++;
      if (n == nth) *tnth = r.t;
      if (gv > *gbest) *gbest = gv, *tbest = r.t;
    }
    t = r.t;
    skip = 1;
  }
  return -2;
}

/* The guard of event kind k on duals at fixed time t: its sensitivity to
 * d and the parameters there. */
static sc_dual guard_dual(const bk2_dpar *P, const bk2_mode_flow *f,
                          int kind, double t) {
  bk2_state xs;
  double a2[2];
  bk2_flow_at(P, f, t, NULL, &xs, a2);
  return bk2_guard_value(P, f->mode, kind, &xs);
}

/* An event time t (root of the guard of kind k, slope g') as a dual:
 * dt = -dg / g' at fixed time. */
static sc_dual event_time(const bk2_dpar *P, const bk2_mode_flow *f, int kind,
                          double t, double slope) {
  sc_dual g = guard_dual(P, f, kind, t), r = sc_dconst(t, P->nd);
  for (int k = 0; k < P->nd; k++) r.d[k] = slope != 0 ? -g.d[k] / slope : NAN;
  return r;
}


/* The borders of one exact slip phase that ends at T by guard `first`:
 * the highest local maximum of every guard before T (grazing of a
 * re-stick, touch of a threshold), and for every other re-stick guard the
 * time from the phase's event to its own first rise through zero
 * (crossing-sliding against a threshold, both re-sticks at once against a
 * re-stick).  The threshold gap after a re-stick is added by the caller
 * for exact and numerical flows alike. */
static void phase_borders(const bk2_dpar *P, const bk2_mode_flow *f, int fresh,
                          const sc_guard *g, const int *kind, int ng,
                          int first, int ekind, int atmax, int nbefore,
                          const sc_root *re, double tmax, double atol,
                          double rtol, bk2_events *ev) {
  int nd = P->nd;
  double T = re->t, tol = atol + rtol * T;
  char name[2 * SC_BORDER_NAME];
  const char *mn = bk2_mode_name(f->mode);
  sc_dual Td = event_time(P, f, ekind, T, re->slope);
  if (ekind == BK2_EV_RESTICK1 || ekind == BK2_EV_RESTICK2) {
    /* The hump the re-stick guard climbs into: its maximum just after the
     * root (at the root itself when the code ends the phase there).  It
     * vanishes at a grazing met from the side where the guard fires; the
     * border's own code ends the phase at that maximum, where the
     * defining system stays smooth. */
    double ta = T;
    int ok = atmax;
    if (!ok) {
      sc_guard gp = guard_prime(&g[first]);
      sc_root r;
      for (int it = 0, skip = 0; it < WALK_MAX && !ok; it++, skip = 1) {
        if (next_root(&gp, ta, ta + fmax(tmax, T), skip, atol, rtol, &r) != 1)
          break;
        ta = r.t;
        ok = r.slope < 0;
      }
    }
    if (ok) {
      sc_dual m = guard_dual(P, f, ekind, ta);
      snprintf(name, sizeof name, "%s max after the event, phase %d (slip %s)",
               bk2_guard_text(ekind), ev->phase, mn);
      sc_bk2_border_add(ev->borders, SC_BORDER_GRAZING, &m, name);
      sc_bk2_patch(ev, ekind | BK2_EV_ATMAX, nbefore, 0);
    }
  }
  for (int i = 0; i < ng; i++) {
    double tn, tb, gb;
    int nm = guard_maxima(&g[i], T - tol, atol, rtol, 0, &tn, &tb, &gb);
    if (nm > 0) {
      sc_dual m = sc_dscale(guard_dual(P, f, kind[i], tb), -1, nd);
      snprintf(name, sizeof name, "%s max, phase %d (slip %s)",
               bk2_guard_text(kind[i]), ev->phase, mn);
      sc_bk2_border_add(ev->borders,
                        kind[i] < 3 ? SC_BORDER_GRAZING : SC_BORDER_TOUCH,
                        &m, name);
    }
    if (i == first || kind[i] >= 3) continue;
    sc_root ri;
    int st = upward_root(&g[i], 0, fmax(tmax, 2 * T), fresh & kind[i], atol,
                         rtol, &ri);
    if (st != 1 || ri.tangent || !(ri.slope > 0)) continue;
    sc_dual m = sc_dsub(event_time(P, f, kind[i], ri.t, ri.slope), Td, nd);
    snprintf(name, sizeof name, "%s rise after the event, phase %d (slip %s)",
             bk2_guard_text(kind[i]), ev->phase, mn);
    sc_bk2_border_add(ev->borders,
                      ekind == BK2_EV_THRESHOLD ? SC_BORDER_CROSSING
                                                : SC_BORDER_BOTH,
                      &m, name);
    /* Both re-sticks at once: the border's own code ends this phase with
     * both blocks and drops the next one (the other block's slip alone,
     * of length zero there), so the system is smooth on both sides. */
    if (ekind != BK2_EV_THRESHOLD && !BK2_IS_BOTH(ekind))
      sc_bk2_patch(ev,
                   kind[first] == BK2_EV_RESTICK1 ? BK2_EV_BOTH : BK2_EV_BOTH2,
                   0, 1);
  }
}

/* Two guards built from different onsets differ by the rounding of the
 * states (positions of size ~1 + alpha |d|, a few ulps each, against
 * coefficients of size (1 - mu) T_i): ~50 eps of the guard's size, or
 * of the size of the numbers they are built from (build_size()). */
#define BK2_SAME_GUARD_EPS (50 * DBL_EPSILON)

/* The size of the numbers a slip's guards are built from: the positions
 * at its start and the springs' constant terms.  The re-stick guard of a
 * block that starts slipping from a GSP is d-free in exact arithmetic,
 * but its sine coefficient -w (y_i - s0), s0 = (k_i + alpha y_j) / w^2,
 * is a difference of such numbers: the guard built from a state carries
 * their rounding, a few ulps of this size times w, which at |d| >> 1 is
 * far above the rounding of the coefficient itself (its constant and
 * cosine terms come from the parameters alone, the same operations in
 * every onset). */
static inline double build_size(const bk2_vpar *P, double y1, double y2) {
  return 1 + fabs(y1) + fabs(y2) + fabs(P->k1) + fabs(P->k2);
}

/* Two guards equal up to the rounding of building them from a state:
 * within BK2_SAME_GUARD_EPS of their size, and the sine coefficients also
 * within that of w bsize (bsize: the two states' build_size() summed, for
 * the re-stick guards of GSP onsets; 0 otherwise). */
static SC_ALWAYS_INLINE int same_guard(const sc_guard *g, const sc_guard *h,
                                       double bsize) {
  if (g->n != 1 || h->n != 1 || g->c1 != 0 || h->c1 != 0 || g->w[0] != h->w[0])
    return 0;
  double tol =
      BK2_SAME_GUARD_EPS * (fabs(h->c0) + fabs(h->a[0]) + fabs(h->b[0]));
  return fabs(g->c0 - h->c0) <= tol && fabs(g->a[0] - h->a[0]) <= tol &&
         fabs(g->b[0] - h->b[0]) <= tol + BK2_SAME_GUARD_EPS * h->w[0] * bsize;
}

static double guard_horizon(const sc_guard *g);
static double root_window(const sc_guard *g, const sc_root *r);

void sc_bk2_first_restick(bk2_inst *b) {
  for (int i = 1; i <= 2; i++) {
    bk2_vstate x;
    /* an onset of block i: any d on its side of d* */
    double d = i == 1 ? b->dstar - 1e-6 : b->dstar + 1e-6;
    int mode = BK2_ONSET_MODE(d, b->dstar);
    bk2v_onset_state(&b->pv, d, mode, &x);
    bk2v_mode_flow f = bk2v_flow_make(&b->pv, mode, &x);
    bk2v_guard_restick(&b->pv, &f, i, &b->first_g[i - 1]);
    b->first_bsize[i - 1] = build_size(&b->pv, x.y1, x.y2);
    b->first_r[i - 1].ntrig = 0;
    b->first_ok[i - 1] =
        mode == i &&
        b->search(&b->first_g[i - 1], guard_horizon(&b->first_g[i - 1]), 1,
                  b->acc.event_atol, b->acc.event_rtol,
                  &b->first_r[i - 1]) == SC_OK &&
        b->first_r[i - 1].found &&
        /* (so a phase with an equal guard, whose horizon is at least
         * this one, never needs its horizon to take the cached root:
         * first_event()) */
        b->first_r[i - 1].t <= guard_horizon(&b->first_g[i - 1]);
    if (b->first_ok[i - 1])
      b->first_w[i - 1] = root_window(&b->first_g[i - 1], &b->first_r[i - 1]);
  }
}

/* Rounding of a guard's value, in ulps of the size of its terms. */
#define ROOT_ROUND_ULPS 8.0

/* The interval a root is known in whatever the search's own bracket: the
 * rounding of g near it over its slope (two equal guards built from
 * different states, or searched over different horizons, may return
 * roots this far apart). */
static inline double root_window_n(const sc_guard *g, int n,
                                   const sc_root *r) {
  double t = r->t, size = fabs(g->c0) + fabs(g->c1) * t;
  for (int k = 0; k < n; k++)
    size += (fabs(g->a[k]) + fabs(g->b[k])) * (1 + g->w[k] * t);
  double E = ROOT_ROUND_ULPS * DBL_EPSILON * size;
  return r->bracket + (r->slope != 0 ? E / fabs(r->slope) : 0);
}

/* (with the number of terms a constant for bk2's guards, so that the
 * loop unrolls: the tie windows are taken in every phase) */
static double root_window(const sc_guard *g, const sc_root *r) {
  switch (g->n) {
  case 1:
    return root_window_n(g, 1, r);
  case 2:
    return root_window_n(g, 2, r);
  default:
    return root_window_n(g, g->n, r);
  }
}

/* root_window of root i, kept in rw[i] (negative: not yet computed). */
static inline double window_once(const sc_guard *g, const sc_root *r, int i,
                                 double *rw) {
  if (rw[i] < 0) rw[i] = root_window(&g[i], &r[i]);
  return rw[i];
}

/* A phase's guards g, their roots r and the roots' windows rw (computed
 * once, window_once()), with the event tolerances: first_event()'s. */
typedef struct {
  double atol, rtol;
  const sc_guard *g;
  const sc_root *r;
  double *rw;
} tie_ctx;

/* How far a later guard is searched past root r, whose window is w:
 * twice its tie tolerance, so that a tie with it is seen
 * (first_event()). */
static inline double past_tie(double atol, double rtol, const sc_root *r,
                              double w) {
  return r->t + 2 * (atol + rtol * r->t + w);
}

/* past_tie() as the pair search's limit (g: one of the phase's guards,
 * whose root it is). */
static double tie_limit(void *ctx, const sc_guard *g, const sc_root *r) {
  const tie_ctx *c = ctx;
  int i = (int)(g - c->g); /* r is c->r[i] */
  return past_tie(c->atol, c->rtol, r, window_once(c->g, c->r, i, c->rw));
}

/* A search refused the phase's guards. */
static int malformed_guard(int mode, sc_msg *msg) {
  return sc_fail(msg, SC_EINTERNAL,
                 "bk2: malformed guard in mode %d (parameters out of "
                 "range?)",
                 mode);
}

/* A phase's horizon: the largest of its guards' (fmax without the libm
 * call; a NaN one is left out, as fmax leaves it out). */
static double phase_horizon(const sc_guard *g, int ng) {
  double tmax = 0;
  for (int i = 0; i < ng; i++) {
    double hz = guard_horizon(&g[i]);
    if (hz > tmax) tmax = hz;
  }
  return tmax;
}

/* A re-stick guard U_i - Vs that starts within rounding of zero and
 * falls: block i began to slip just before this phase (U_i = Vs within
 * the rounding of the state, ~ eps V, and moving away from it), so the
 * root at 0 is a downward crossing, never a re-stick (events are upward
 * crossings): it is skipped as a fresh block's is.  The search's own
 * start test uses its rounding at 0 only, and its march a larger bound
 * that grows with the step, which took such a start for a root (at V =
 * 100, a block triggered 8e-8 into the other's slip: U_i - Vs = -8e-14
 * against a rounding of 4e-13; the block re-stuck beyond its threshold:
 * D5 in docs/accuracy.md).  The window is START_ROUND_ULPS of the terms'
 * size, a few times the search's step-grown bound. */
#define START_ROUND_ULPS 64.0
static SC_ALWAYS_INLINE int falls_from_zero(const sc_guard *g) {
  double g0, g1, size = fabs(g->c0), wsize = fabs(g->c1);
  bk2_guard_at_zero(g, &g0, &g1);
  for (int k = 0; k < g->n; k++) {
    size += fabs(g->a[k]) + fabs(g->b[k]);
    wsize += g->w[k] * (fabs(g->a[k]) + fabs(g->b[k]));
  }
  return fabs(g0) <= START_ROUND_ULPS * DBL_EPSILON * size &&
         g1 < -ROOT_ROUND_ULPS * DBL_EPSILON * wsize;
}

/* Whether the search of a guard of kind `kind` skips a root at 0: a
 * re-stick guard of a block that starts slipping with the phase (fresh)
 * or falls from zero (falls_from_zero()); a threshold guard never. */
static SC_ALWAYS_INLINE int skips_start(int kind, int fresh,
                                        const sc_guard *g) {
  return kind < 3 && ((fresh & kind) || falls_from_zero(g));
}

/* The slope of the stuck block's threshold guard where it reaches zero,
 * for a trigger the search took at the onset itself: the guard's exact
 * value there, gap = (1 + 2 alpha)(d - d*) < 0 up to sign, lies within
 * the rounding of its terms (next to d* with V_s ~ 0: a double root at
 * d*), so the root is somewhere in the first ~sqrt(rounding / g'') of
 * the phase and g'(0) ~ (1 + alpha) V_s is not its slope.  The event
 * time is still within rounding (f keeps its promise), but f' = -dg/dd /
 * slope needs the slope at the root: from g = gap + g1 t + g2 t^2 / 2,
 * sqrt(g1^2 - 2 g2 gap) (the cubic term is below rounding over so short a
 * time).  NaN (f' refused with a message) if that quadratic never
 * reaches zero.  Both paths use it (f' and the tie windows of
 * first_event()), so they take the same event at the same time. */
static double onset_trigger_slope(const sc_guard *g, double gap) {
  double g1, g2;
  sc_guard_eval(g, 0, NULL, &g1, &g2);
  double s2 = g1 * g1 - 2 * g2 * gap;
  return s2 > 0 ? sqrt(s2) : NAN;
}

/* The first event of a phase among its guards g (kinds kind), searched
 * up to the phase's horizon tmax (phase_horizon(); NaN: computed here
 * when first needed, which a slip from a GSP whose re-stick comes from
 * the cache never does: two guards and three divisions saved in most
 * phases of a chart): later guards only up to the earliest root so far
 * (plus twice its tie tolerance: tie_limit()), the two re-sticks of a
 * slip of both blocks together (the later one only up to the earlier
 * one's limit), the first re-stick after a GSP from the per-parameter
 * cache; ties within the event tolerance, or within the intervals the two
 * roots are known to lie in (a root can be known no better than the
 * rounding of its guard over its slope): re-sticks go first
 * (docs/model.md), two re-sticks at once end the slip of both blocks (at
 * V = 100 and alpha = 1000 the synchronous re-sticks of beta = 1 are
 * ~1e-12 apart by rounding alone).  onset_gap: the stuck block's exact
 * threshold gap at a slip's onset from a GSP (NaN elsewhere): a trigger
 * taken at the onset itself gets the slope at its true root
 * (onset_trigger_slope()), also for the tie windows (its slope at 0,
 * ~ (1 + alpha) V_s, would make the window of a root known to ~1e-13
 * as long as the whole phase).  y1, y2: the positions at the phase's
 * start, whose build_size() same_guard() needs where it tests a GSP
 * onset's re-stick guard against the cache (and only there: it is not
 * computed in other phases).  The dual and the value-only paths share
 * it, so they take the same events.
 * Returns the index of the first event in g and r (*bothp: it ends the
 * slip of both blocks), or a negative status.  Inlined into both: in a
 * call of its own, moving its arguments and the search results cost 3% of
 * a chart's instructions. */
static SC_ALWAYS_INLINE int first_event(const bk2_inst *b, int mode, int fresh,
                                        const sc_guard *g, const int *kind,
                                        int ng, double tmax, double onset_gap,
                                        double y1, double y2, sc_root *r,
                                        int *bothp, long *steps, sc_msg *msg) {
  double atol = b->acc.event_atol, rtol = b->acc.event_rtol;
  /* each root's window, computed once when first needed (ng <= 2:
   * phase_kinds) */
  double rw[2] = {-1, -1};
  int first = -1;
  /* A slip of both blocks: its two re-stick guards differ only in the
   * sign of the second oscillator's terms, and one march searches both
   * (sc_guard_first_root_pair), the later root up to tie_limit() of the
   * earlier, as below. */
  int paired = mode == SC_BK2_SLIP12 && ng == 2 && b->search_pair;
  if (paired) {
    int skip[2];
    for (int i = 0; i < 2; i++)
      skip[i] = skips_start(kind[i], fresh, &g[i]);
    if (isnan(tmax)) tmax = phase_horizon(g, ng);
    r[0].ntrig = r[1].ntrig = 0;
    tie_ctx tc = {atol, rtol, g, r, rw};
    if (b->search_pair(g, tmax, skip, atol, rtol, tie_limit, &tc, r))
      return malformed_guard(mode, msg);
    for (int i = 0; i < 2; i++) {
      *steps += r[i].steps;
      if (r[i].found && (first < 0 || r[i].t < r[first].t)) first = i;
    }
  }
  for (int i = 0; i < ng && !paired; i++) {
    int skip = skips_start(kind[i], fresh, &g[i]);
    double lim = first < 0 ? NAN
                           : past_tie(atol, rtol, &r[first],
                                      window_once(g, r, first, rw));
    int st = SC_OK;
    /* Without a root yet, the cached root is within tmax: tmax is at
     * least this guard's horizon, which equals the cached guard's (same
     * frequency, one term, no linear term: same_guard()), and the cached
     * root lies within that (sc_bk2_first_restick()). */
    if (skip && mode != SC_BK2_SLIP12 && b->first_ok[kind[i] - 1] &&
        (first < 0 || b->first_r[kind[i] - 1].t <= lim) &&
        same_guard(&g[i], &b->first_g[kind[i] - 1],
                   (fresh & kind[i]) ? build_size(&b->pv, y1, y2) +
                                           b->first_bsize[kind[i] - 1]
                                     : 0)) {
      /* the slip from a GSP: d-free, and so is the root's window (the
       * guards differ by rounding, the windows by 8 eps of that over the
       * slope: far below an ulp of the root) */
      r[i] = b->first_r[kind[i] - 1];
      rw[i] = b->first_w[kind[i] - 1];
    } else {
      if (first < 0) {
        if (isnan(tmax)) tmax = phase_horizon(g, ng);
        lim = tmax;
      }
      r[i].ntrig = 0; /* (a search that does not leave cos and sin) */
      st = b->search(&g[i], lim, skip, atol, rtol, &r[i]);
    }
    if (st) return malformed_guard(mode, msg);
    *steps += r[i].steps;
    if (kind[i] == BK2_EV_THRESHOLD && r[i].found && r[i].t == 0 &&
        onset_gap < 0)
      r[i].slope = onset_trigger_slope(&g[i], onset_gap);
    if (r[i].found && (first < 0 || r[i].t < r[first].t)) first = i;
  }
  if (first < 0 && isnan(tmax)) tmax = phase_horizon(g, ng);
  if (first < 0)
    return sc_fail(msg, SC_EUNDEF,
                   "no event within %.6g time units of slip mode %s: the "
                   "slip does not end",
                   tmax, bk2_mode_name(mode));
  int both = 0;
  for (int i = 0; i < ng; i++) {
    if (i == first || !r[i].found) continue;
    double tol = atol + rtol * r[first].t + window_once(g, r, first, rw) +
                 window_once(g, r, i, rw);
    if (fabs(r[i].t - r[first].t) <= tol) {
      if (kind[first] == BK2_EV_THRESHOLD) first = i;
      else if (kind[i] < 3) both = 1;
    }
  }
  *bothp = both;
  return first;
}

/* The end of a phase that follows the code `force` (its two bytes: the
 * event kind, and the local maxima of its guard to pass): the forced
 * guard's first rise through zero after its first `skip` local maxima,
 * or its (skip + 1)-th maximum (BK2_EV_ATMAX, *atmaxp set); the other
 * guards are not taken.  Returns the index of the guard in g (its root
 * in r), or a negative status; *bothp: the code ends the slip of both
 * blocks. */
static int forced_event(const bk2_inst *b, int mode, int fresh,
                        const sc_guard *g, const int *kind, int ng,
                        double tmax, const unsigned char *force, sc_root *r,
                        int *bothp, int *atmaxp, long *steps, sc_msg *msg) {
  double atol = b->acc.event_atol, rtol = b->acc.event_rtol;
  int want = force[0] & ~BK2_EV_ATMAX, skip = force[1], first = -1;
  int atmax = *atmaxp = (force[0] & BK2_EV_ATMAX) != 0;
  int gk = BK2_GUARD_OF(want);
  for (int i = 0; i < ng; i++)
    if (kind[i] == gk) first = i;
  if (first < 0 || (BK2_IS_BOTH(want) && mode != SC_BK2_SLIP12))
    return sc_fail(msg, SC_EINVAL,
                   "bk2: the forced itinerary code does not fit slip mode "
                   "%s (event %d)",
                   bk2_mode_name(mode), want);
  double ts = 0, tb, gb;
  int sk = kind[first] < 3 && (fresh & kind[first]);
  if (atmax) {
    /* end at the guard's (skip + 1)-th maximum: a grazing's system */
    int nm = kind[first] < 3 ? guard_maxima(&g[first], tmax, atol, rtol,
                                            skip + 1, &ts, &tb, &gb)
                             : -1;
    if (nm < skip + 1)
      return sc_fail(msg, SC_EUNDEF,
                     "bk2: the forced grazing event of slip mode %s needs "
                     "%d maxima of its guard, found %d",
                     bk2_mode_name(mode), skip + 1, nm);
    double g2;
    sc_guard_eval(&g[first], ts, NULL, NULL, &g2);
    r[first] = (sc_root){.found = 1, .t = ts, .slope = g2};
  } else if (skip > 0) {
    int nm = guard_maxima(&g[first], tmax, atol, rtol, skip, &ts, &tb, &gb);
    if (nm < skip)
      return sc_fail(msg, SC_EUNDEF,
                     "bk2: the forced event of slip mode %s needs %d "
                     "maxima of its guard, found %d",
                     bk2_mode_name(mode), skip, nm);
    sk = 0;
  }
  int st = atmax ? 1
                 : upward_root(&g[first], ts, tmax, sk, atol, rtol,
                               &r[first]);
  if (st < 0)
    return sc_fail(msg, SC_EINTERNAL,
                   "bk2: malformed guard in mode %d", mode);
  if (st == 0)
    return sc_fail(msg, SC_EUNDEF,
                   "bk2: the forced event (%s reaching zero) does not "
                   "occur in slip mode %s within %.6g time units",
                   bk2_guard_text(kind[first]), bk2_mode_name(mode), tmax);
  *steps += r[first].steps;
  *bothp = BK2_IS_BOTH(want);
  return first;
}

/* One slip phase with exact flows: find its end (the first event, or the
 * event the code forces), the next mode, and the state there.  `fresh`
 * bit i-1: block i started slipping at this phase's start (U_i = Vs by
 * construction, so its re-stick guard starts at zero).  Returns the next
 * mode, or a negative status. */
static int exact_phase(const bk2_inst *b, const bk2_dpar *P, int mode,
                       int fresh, bk2_state *x, double *duration,
                       bk2_events *ev, sc_msg *msg) {
  bk2_mode_flow f = bk2_flow_make(P, mode, x);
  double atol = b->acc.event_atol, rtol = b->acc.event_rtol;
  double onset_gap = ev->onset ? ev->onset_gap : NAN;
  sc_guard g[2];
  int kind[2], ng = bk2_phase_guards(P, &f, fresh, onset_gap, g, kind);
  sc_root r[2];
  double tmax = phase_horizon(g, ng);
  int both = 0, atmax = 0;
  int first = !ev->force
                  ? first_event(b, mode, fresh, g, kind, ng, tmax, onset_gap,
                                x->y1.v, x->y2.v, r, &both, &ev->steps, msg)
                  : forced_event(b, mode, fresh, g, kind, ng, tmax, ev->force,
                                 r, &both, &atmax, &ev->steps, msg);
  if (first < 0) return first;
  double t = r[first].t;
  int ekind = !both ? kind[first]
              : kind[first] == BK2_EV_RESTICK1 ? BK2_EV_BOTH
                                               : BK2_EV_BOTH2;
  int nbefore = 0;
  if (ev->want_code || ev->borders) {
    double tn, tb, gb;
    int nm = atmax ? ev->force[1]
                   : guard_maxima(&g[first], t - (atol + rtol * t), atol,
                                  rtol, 0, &tn, &tb, &gb);
    nbefore = nm < 0 ? 255 : nm > 254 ? 255 : nm;
    ev->rec[0] = (unsigned char)(ekind | (atmax ? BK2_EV_ATMAX : 0));
    /* A root is recorded as the guard's first rise through zero (skip 0),
     * not by the maxima before it: maxima below zero are born and die
     * (where g' and g'' vanish together) without any change of the
     * motion, and a count of them would change the code there. */
    ev->rec[1] = (unsigned char)(atmax ? nbefore : 0);
  }
  if (ev->borders)
    phase_borders(P, &f, fresh, g, kind, ng, first, ekind, atmax, nbefore,
                  &r[first], tmax, atol, rtol, ev);
  double a2[2], tb[4];
  bk2_flow_at(P, &f, t, event_trig(&r[first], mode, tb), x, a2);
  *duration = t;
  if (r[first].tangent) ev->tangent = 1;
  return atmax ? sc_bk2_take_event_at_max(P, mode, kind[first],
                                          r[first].slope, a2, x)
               : sc_bk2_take_event(P, mode, ekind, r[first].slope, a2, x);
}

/* ---- the value-only path -------------------------------------------------
 * Plain evaluations (SC_EVAL_VALUE, with or without the itinerary: sweeps,
 * charts, shooting residuals) with exact flows, no forced code and no
 * borders, on plain doubles.  The dual path with nd = 0 computes the same
 * numbers (its loops over directions are empty) but passes 48-byte duals
 * by value through every flow operation.  The flows are bk2_flow.h's on
 * doubles, the events first_event()'s: the same operations in the same
 * order as the dual path's .v parts, so the two give bit-identical f and
 * itineraries (tests/test_bk2_value.c checks it). */

/* exact_phase() without a forced code, code bytes or borders. */
static int value_phase(const bk2_inst *b, const bk2_vpar *P, int mode,
                       int fresh, double onset_gap, bk2_vstate *x,
                       sc_msg *msg) {
  bk2v_mode_flow f = bk2v_flow_make(P, mode, x);
  sc_guard g[2];
  int kind[2], ng = bk2v_phase_guards(P, &f, fresh, onset_gap, g, kind);
  sc_root r[2];
  int both = 0;
  long steps = 0;
  int first = first_event(b, mode, fresh, g, kind, ng, NAN, onset_gap,
                          x->y1, x->y2, r, &both, &steps, msg);
  if (first < 0) return first;
  double acc[2], tb[4];
  bk2v_flow_at(P, &f, r[first].t, event_trig(&r[first], mode, tb), x, acc);
  return bk2v_stick(P, mode, both ? BK2_EV_BOTH : kind[first], x);
}

/* The event loop on values (bk2_loop.h): no force, code, borders or
 * phase callback. */
#define BK2_LOOP_NAME value_loop
#define BK2_LOOP_FULL 0
#define BK2_LOOP_NUM double
#define BK2_LOOP_PAR bk2_vpar
#define BK2_LOOP_STATE bk2_vstate
#define BK2_LOOP_VAL(a) (a)
#define BK2_LOOP_ONSET(P, d, mode, x) bk2v_onset_state(P, d, mode, x)
#define BK2_LOOP_PHASE value_phase(b, P, mode, fresh, gap, x, msg)
#include "models/bk2_loop.h"

/* sc_bk2_iterate() on values: the flows' `value`. */
static int value_iterate(const bk2_inst *b, double d, unsigned flags,
                         sc_map_value *out, sc_msg *msg) {
  bk2_vstate x;
  return value_loop(b, &b->pv, d, flags, NULL, NULL, NULL, &x, out, NULL,
                    NULL, msg);
}

/* ---- the flows interface ------------------------------------------------ */

static int exact_setup(bk2_inst *b, sc_msg *msg) {
  (void)msg;
  sc_bk2_first_restick(b);
  return SC_OK;
}

static void exact_release(bk2_inst *b) { (void)b; }

/* Sample one finished slip phase every dtau and at its end. */
static int exact_sample(const bk2_inst *b, const bk2_dpar *P, int mode,
                        const bk2_state *x0, double dur, bk2_traj *c) {
  (void)b;
  bk2_mode_flow f = bk2_flow_make(P, mode, x0);
  double a2[2];
  bk2_state x;
  long n = (long)floor(dur / c->dtau);
  for (long i = 0; i <= n + 1; i++) {
    double t = i <= n ? i * c->dtau : dur;
    bk2_flow_at(P, &f, t, NULL, &x, a2);
    double s[4] = {x.y1.v, x.y2.v, x.u1.v, x.u2.v};
    if (bk2_traj_emit(c, t, s, mode)) return SC_ECALLBACK;
  }
  c->tau += dur;
  return SC_OK;
}

/* Closed forms: only rounding. */
static double exact_precision(const bk2_inst *b) {
  (void)b;
  return 0;
}

const bk2_flows sc_bk2_flows_exact = {
    .name = "exact",
    .setup = exact_setup,
    .release = exact_release,
    .phase = exact_phase,
    .sample = exact_sample,
    .precision = exact_precision,
    .value = value_iterate,
};

