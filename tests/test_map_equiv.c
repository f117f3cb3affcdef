/* The event map with the current first-root search against the same map
 * with the search it replaced (tests/ref/guard_v0.c, frozen), point by
 * point: same status, same itinerary, |f - f_ref| <= 1e-13 and, with
 * derivatives, |f' - f'_ref| <= 1e-10 max(1, |f'_ref|) for df/dd and every
 * df/dp.  Docs: docs/performance.md (event map), docs/events.md.
 *
 *   test_map_equiv [N]     compare at least N evaluations (default 60000:
 *                          the ctest; `cmake --build B --target
 *                          map_equiv_full` runs N = 1e7)
 *
 * The points, reproducible from a fixed seed, per random parameter set
 * (alpha in [0.5, 20], beta 1 or in [1, 20], phi 1.25 or in [1.05, 3],
 * V in [0, 0.05], driver moving or frozen):
 *   - an orbit from d0 = 0 or 0.02 (the workloads of sweeps and charts);
 *   - uniform d over the range of GSP displacements;
 *   - grazing and switching points: between two d of different
 *     itineraries, the border is bisected to 1e-15 and the map compared
 *     at 1e-6 .. 1e-14 on both sides of it (re-stick guards that reach or
 *     miss zero by about as much: graze margins down to ~1e-14).
 * Half the evaluations carry derivatives (the dual path), half only values
 * (the plain path).  Where a root is ill conditioned (small slope against
 * the guard's size: grazing, slow threshold crossings, near-ties), two
 * correct searches may return different points of the root's window, and
 * f, f' and even the itinerary (a tie) may then differ by more than the
 * plain bounds: see compare() for the allowances, each derived from the
 * reference's own spread.  An itinerary that differs beyond that spread
 * fails the test unless the current map reports a border of the iterate
 * within rounding (1024 eps (S + V), the accuracy promise's rule: either
 * side may be taken there) or quad takes the current map's itinerary
 * (then the reference erred); both are counted and shown. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/bk2_impl.h"
#include "models/bk2_quad.h"
#include "ref/guard_v0.h"
#include "slipcont/map.h"
#include "test_util.h"

/* Speeds of the blocks are below this in every slip of the sampled
 * ranges (|U_i| <= max(T_i) / w1 + V, T_i <= 20). */
#define EQUIV_VEL 20.0
/* Differences up to this many times the reference's own spread J (see
 * ref_jitter) are accepted where the plain bounds fail: J samples the
 * spread with all roots moved at once, which can cancel; 100 is what the
 * 1e7 run needs for all but 1.6e-5 of the f' values. */
#define EQUIV_JIT 100.0

static unsigned long long rng = 0x2545f4914f6cdd1dULL;
static double uni(double lo, double hi) {
  rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
  return lo + (hi - lo) * (double)(rng >> 11) / 9007199254740992.0;
}

typedef struct {
  long n, nderiv, status_diff, itin_diff, f_diff, df_diff, ill;
  long border; /* itineraries the moved reference also shows */
  long ref_wrong; /* itineraries where quad sides with the current map */
  long on_border; /* itineraries that differ within rounding of a border */
  long near_graze[16]; /* points by decade of graze margin: 1e-k, k < 16 */
  double f_max, df_max;
  double worst_p[4], worst_d;
} stats;

typedef struct {
  bk2_inst *now, *ref;
} pair;

/* How well the roots taken in one evaluation are determined: a root is
 * certified only to within the rounding bound E of g (8 eps times the
 * terms' sizes, docs/events.md) over its slope: two correct searches may
 * return any points of that window.  The searches are wrapped to record,
 * per evaluation, the widest window W. */
static double win_t;

static double window(const sc_guard *g, const sc_root *r) {
  double size = fabs(g->c0) + fabs(g->c1) * r->t;
  for (int k = 0; k < g->n; k++)
    size += hypot(g->a[k], g->b[k]) * (1 + g->w[k] * r->t);
  double E = 8 * DBL_EPSILON * size;
  return r->bracket + (r->slope != 0 ? E / fabs(r->slope) : HUGE_VAL);
}

static void note_window(const sc_guard *g, const sc_root *r) {
  if (r->found) win_t = fmax(win_t, window(g, r));
}

static int eval(bk2_inst *b, double d, unsigned flags, sc_map_value *out) {
  sc_msg msg;
  memset(out, 0, sizeof *out);
  return sc_model_bk2.eval(b, d, flags, out, &msg);
}

/* The smallest |m| of the borders of the iterate from d (models.h): of
 * every kind, or only the grazing ones; HUGE_VAL if there is none. */
static double border_min(bk2_inst *b, double d, int grazing_only) {
  sc_border bl[128];
  sc_border_list l = {bl, 128, 0};
  sc_map_value v;
  sc_msg msg;
  memset(&v, 0, sizeof v);
  if (sc_model_bk2.eval_ex(b, d, 0, NULL, NULL, &l, &v, &msg))
    return HUGE_VAL;
  double m = HUGE_VAL;
  for (size_t i = 0; i < l.n && i < l.cap; i++)
    if (!grazing_only || bl[i].kind == SC_BORDER_GRAZING)
      m = fmin(m, fabs(bl[i].value));
  return m;
}

/* Whether the iterate from d has a border within 1024 eps (S + V) of
 * zero, S = 1 + beta + (1 + alpha)|d| the size of the onset state: within
 * rounding of a border, where the accuracy promise lets either side be
 * taken (docs/accuracy.md, the rule of bench_iterates and test_extremes).
 * *m: the smallest |m|. */
static int on_border(bk2_inst *b, const double p[4], double d, double *m) {
  *m = border_min(b, d, 0);
  double S = 1 + p[1] + (1 + p[0]) * fabs(d);
  return *m <= 1024 * DBL_EPSILON * (S + p[3]);
}

/* The distance to grazing of an iterate, for the statistics of points
 * near grazing. */
static double graze_margin(bk2_inst *b, double d) {
  return border_min(b, d, 1);
}

static int search_now(const sc_guard *g, double tmax, int skip, double atol,
                      double rtol, sc_root *out) {
  int st = sc_guard_first_root(g, tmax, skip, atol, rtol, out);
  note_window(g, out);
  return st;
}

/* The current map searches the two guards of a slip of both blocks
 * together; the reference one after the other with its own search. */
static int search_pair_now(const sc_guard *g, double tmax, const int *skip,
                           double atol, double rtol, sc_guard_limit_fn limit,
                           void *ctx, sc_root *out) {
  int st = sc_guard_first_root_pair(g, tmax, skip, atol, rtol, limit, ctx,
                                    out);
  for (int i = 0; i < 2; i++) note_window(&g[i], &out[i]);
  return st;
}

static int search_ref(const sc_guard *g, double tmax, int skip, double atol,
                      double rtol, sc_root *out) {
  int st = sc_guard_first_root_v0(g, tmax, skip, atol, rtol, out);
  /* the earlier search had no curv: bk2 then evaluated g'' itself */
  if (!st && out->found) sc_guard_eval(g, out->t, NULL, NULL, &out->curv);
  note_window(g, out);
  return st;
}

/* The reference with every root moved toward jit_sign by its time
 * tolerance (atol + rtol t) plus its window, and its slope taken there
 * and moved by the rounding bound of g' (a slope from a closed form or
 * from another point of the window differs by that much):
 * how much the reference's own results move when its roots move as much
 * as their certification lets them. */
static int jit_sign, jit_alt;
static int search_jit(const sc_guard *g, double tmax, int skip, double atol,
                      double rtol, sc_root *out) {
  int st = sc_guard_first_root_v0(g, tmax, skip, atol, rtol, out);
  if (jit_alt) jit_sign = -jit_sign; /* guards of one phase move apart */
  if (!st && out->found && out->t > 0) {
    double W = window(g, out), E1 = fabs(g->c1);
    if (isfinite(W)) out->t += jit_sign * (atol + rtol * out->t + W);
    sc_guard_eval(g, out->t, NULL, &out->slope, &out->curv);
    /* and the slope by the rounding bound of g' */
    for (int k = 0; k < g->n; k++)
      E1 += hypot(g->a[k], g->b[k]) * g->w[k] * (1 + g->w[k] * out->t);
    out->slope += jit_sign * 8 * DBL_EPSILON * E1;
  }
  return st;
}

/* The reference's spread at d: largest change of f and of each
 * derivative under those moves, all roots one way or successive ones
 * opposite ways (which moves ties); *itin_ok set if one of them gives the
 * itinerary `itin`. */
static void ref_jitter(const pair *P, double d, unsigned flags,
                       const sc_map_value *r, const char *itin, double J[6],
                       int *itin_ok) {
  char seen[SC_ITIN_LEN] = "";
  for (int run = 0; run < 4; run++) {
    sc_map_value b;
    jit_sign = run % 2 ? 1 : -1;
    jit_alt = run >= 2;
    P->ref->search = search_jit;
    sc_bk2_first_restick(P->ref);
    int st = eval(P->ref, d, flags | SC_EVAL_ITINERARY, &b);
    P->ref->search = search_ref;
    sc_bk2_first_restick(P->ref);
    if (st) continue;
    /* the itinerary `itin`, or two different ones among the moves: the
     * reference's own itinerary is not determined here */
    if (itin_ok && (strcmp(b.itinerary, itin) == 0 ||
                    (seen[0] && strcmp(b.itinerary, seen) != 0)))
      *itin_ok = 1;
    strcpy(seen, b.itinerary);
    if (strcmp(b.itinerary, r->itinerary) != 0) continue;
    double vb[6] = {b.f, b.dfdd, b.dfdp[0], b.dfdp[1], b.dfdp[2], b.dfdp[3]};
    double vr[6] = {r->f, r->dfdd, r->dfdp[0], r->dfdp[1], r->dfdp[2],
                    r->dfdp[3]};
    for (int i = 0; i < 6; i++)
      if (isfinite(vb[i]) && isfinite(vr[i]))
        J[i] = fmax(J[i], fabs(vb[i] - vr[i]));
  }
}

static int setup(bk2_inst *b, const double p[4], int frozen,
                 int (*search)(const sc_guard *, double, int, double, double,
                               sc_root *)) {
  sc_accuracy acc;
  sc_msg msg;
  sc_accuracy_preset(&acc, "default", NULL);
  int opt[3] = {frozen, 0, 0};
  memset(b, 0, sizeof *b);
  const double q[5] = {p[0], p[1], p[2], p[3], 1}; /* gamma: unused */
  int st = sc_model_bk2.setup(b, q, opt, &acc, &msg);
  b->search = search;
  b->search_pair = search == search_now ? search_pair_now : NULL;
  if (!st) sc_bk2_first_restick(b); /* with this search */
  return st;
}


/* Compare both maps at d; returns the current map's value in *f (NaN if
 * undefined) and its itinerary in itin (may be NULL). */
static void compare(const pair *P, const double p[4], double d, stats *s,
                    double *f, char *itin) {
  unsigned flags = SC_EVAL_ITINERARY | (s->n % 2 ? SC_EVAL_DERIV : 0);
  sc_map_value a, r;
  win_t = 0;
  int sa = eval(P->now, d, flags, &a), sr = eval(P->ref, d, flags, &r);
  double W = win_t;
  s->n++;
  if (f) *f = sa ? NAN : a.f;
  if (itin) strcpy(itin, sa ? "" : a.itinerary);
  if (sa != sr) {
    if (s->status_diff++ < 5)
      printf("  status %d vs %d at alpha %.17g beta %.17g phi %.17g v "
             "%.17g d %.17g\n",
             sa, sr, p[0], p[1], p[2], p[3], d);
    return;
  }
  if (sa) return;
  if (strcmp(a.itinerary, r.itinerary) != 0) {
    /* A tie of two events decided at the time tolerance (two re-sticks
     * of a symmetric slip, say) may go either way: excused if the
     * reference itself goes the other way, or two ways, with its roots
     * moved within their windows. */
    double J0[6] = {0};
    int amb = 0;
    ref_jitter(P, d, flags, &r, a.itinerary, J0, &amb);
    if (amb) {
      s->border++;
      return;
    }
    /* Within rounding of a border either side may be taken */
    double bm;
    if (on_border(P->now, p, d, &bm)) {
      if (s->on_border++ < 5)
        printf("  itinerary %s vs %s within rounding of a border (|m| = "
               "%.3g) at alpha %.17g beta %.17g phi %.17g v %.17g d %.17g\n",
               a.itinerary, r.itinerary, bm, p[0], p[1], p[2], p[3], d);
      return;
    }
    /* Otherwise quad arbitrates: where it takes the current map's
     * itinerary, the frozen reference was the one that erred (counted and
     * shown, not a failure); where it takes the reference's, or neither,
     * the current map is wrong. */
    sc_map_value q;
    sc_msg qmsg;
    memset(&q, 0, sizeof q);
    if (sc_bk2_quad_eval(p[0], p[1], p[2], p[3], P->now->frozen,
                         P->now->acc.max_events, d, SC_EVAL_ITINERARY, &q,
                         &qmsg) == SC_OK &&
        strcmp(q.itinerary, a.itinerary) == 0) {
      if (s->ref_wrong++ < 5)
        printf("  reference's itinerary %s wrong by quad (current and quad: "
               "%s) at alpha %.17g beta %.17g phi %.17g v %.17g d %.17g\n",
               r.itinerary, a.itinerary, p[0], p[1], p[2], p[3], d);
      return;
    }
    if (s->itin_diff++ < 5)
      printf("  itinerary %s vs %s at alpha %.17g beta %.17g phi %.17g v "
             "%.17g d %.17g (graze margin %.3g)\n",
             a.itinerary, r.itinerary, p[0], p[1], p[2], p[3], d,
             graze_margin(P->now, d));
    return;
  }
  double m = graze_margin(P->now, d);
  if (m > 0 && m < 1) {
    int k = (int)floor(-log10(m));
    if (k >= 0 && k < 16) s->near_graze[k]++;
  }
  double e = fabs(a.f - r.f);
  /* Two correct searches may return any point of a root's window W
   * (rounding of g over its slope): f may differ by EQUIV_VEL W, the
   * event time's error times a bound on the blocks' speeds.  Near grazing
   * and crossing-sliding, f' is a sum of terms in 1/g' and 1/g'^2 and
   * moves under perturbations of the roots as small as their tolerance:
   * where the plain bounds fail, the reference's own spread J (per output)
   * when its roots move by their tolerance is measured, and EQUIV_JIT J
   * allowed. */
  double fallow = 1e-13 + EQUIV_VEL * W;
  double J[6] = {0};
  int plain = e <= 1e-13, jit = 0;
  if (e > fallow) {
    ref_jitter(P, d, flags, &r, NULL, J, NULL);
    jit = 1;
    fallow = fmax(fallow, 1e-13 + EQUIV_JIT * J[0]);
  }
  if (e > s->f_max) {
    s->f_max = e;
    memcpy(s->worst_p, p, sizeof s->worst_p);
    s->worst_d = d;
  }
  if (e > fallow && s->f_diff++ < 5)
    printf("  f %.17g vs %.17g (allowed %.3g) at alpha %.17g beta %.17g "
           "phi %.17g v %.17g d %.17g\n",
           a.f, r.f, fallow, p[0], p[1], p[2], p[3], d);
  if (flags & SC_EVAL_DERIV) {
    s->nderiv++;
    double da[5] = {a.dfdd, a.dfdp[0], a.dfdp[1], a.dfdp[2], a.dfdp[3]};
    double dr[5] = {r.dfdd, r.dfdp[0], r.dfdp[1], r.dfdp[2], r.dfdp[3]};
    for (int k = 0; k < 5; k++) {
      if (isnan(da[k]) && isnan(dr[k])) continue;
      double rel = fabs(da[k] - dr[k]) / fmax(1, fabs(dr[k]));
      double dallow = 1e-10;
      if (!(rel <= dallow)) {
        plain = 0;
        if (!jit) ref_jitter(P, d, flags, &r, NULL, J, NULL);
        jit = 1;
        dallow += EQUIV_JIT * J[k + 1] / fmax(1, fabs(dr[k]));
      }
      if (!(rel <= dallow) && s->df_diff++ < 5)
        printf("  df[%d] %.17g vs %.17g (allowed %.3g) at alpha %.17g beta "
               "%.17g phi %.17g v %.17g d %.17g\n",
               k, da[k], dr[k], dallow, p[0], p[1], p[2], p[3], d);
      if (rel > s->df_max) s->df_max = rel;
    }
  }
  if (!plain) s->ill++;
}

/* Bisect the border between da and db (different itineraries) and
 * compare at 1e-6 .. 1e-14 on both sides. */
static void border(const pair *P, const double p[4], double da, double db,
                   const char *ia, stats *s) {
  sc_map_value v;
  for (int it = 0; it < 60 && fabs(db - da) > 1e-15 * fmax(1, fabs(da));
       it++) {
    double m = 0.5 * (da + db);
    int st = eval(P->now, m, SC_EVAL_ITINERARY, &v);
    if (!st && strcmp(v.itinerary, ia) == 0) da = m;
    else db = m;
  }
  for (int k = 6; k <= 14; k++) {
    double h = pow(10, -k);
    compare(P, p, da - h, s, NULL, NULL);
    compare(P, p, db + h, s, NULL, NULL);
  }
}

static void one_set(stats *s, long budget) {
  double p[4];
  p[0] = exp(uni(log(0.5), log(20)));
  p[1] = uni(0, 1) < 0.4 ? 1 : uni(1, 20);
  p[2] = uni(0, 1) < 0.5 ? 1.25 : uni(1.05, 3);
  p[3] = uni(0, 1) < 0.1 ? 0 : uni(0.001, 0.05);
  int frozen = uni(0, 1) < 0.5;
  static bk2_inst now, ref;
  pair P = {&now, &ref};
  if (setup(&now, p, frozen, search_now) || setup(&ref, p, frozen, search_ref))
    return;
  long end = s->n + budget;
  /* an orbit */
  double d = uni(0, 1) < 0.5 ? 0 : 0.02, f;
  for (int k = 0; k < budget / 3 && s->n < end; k++) {
    compare(&P, p, d, s, &f, NULL);
    if (isnan(f)) break;
    d = f;
  }
  /* uniform points, and the borders between neighbours */
  double span = 1.2 * (1 + p[1]) / (1 + 2 * p[0]);
  double dprev = 0;
  char iprev[SC_ITIN_LEN] = "", icur[SC_ITIN_LEN];
  int have = 0;
  while (s->n < end) {
    d = have ? dprev + uni(0, 0.05) * span : -span;
    if (d > span) break;
    compare(&P, p, d, s, &f, icur);
    if (have && icur[0] && iprev[0] && strcmp(icur, iprev) != 0)
      border(&P, p, dprev, d, iprev, s);
    dprev = d;
    strcpy(iprev, icur);
    have = 1;
  }
}

int main(int argc, char **argv) {
  long want = argc > 1 ? atol(argv[1]) : 60000;
  if (want < 1) want = 60000;
  stats s = {0};
  while (s.n < want) one_set(&s, 600);
  printf("compared %ld evaluations (%ld with derivatives)\n", s.n, s.nderiv);
  printf("by graze margin 1e-k (k = 0..15):");
  for (int k = 0; k < 16; k++) printf(" %ld", s.near_graze[k]);
  printf("\nlargest |f - f_ref| %.3g (alpha %.17g beta %.17g phi %.17g v "
         "%.17g d %.17g); largest relative f' difference %.3g\n",
         s.f_max, s.worst_p[0], s.worst_p[1], s.worst_p[2], s.worst_p[3],
         s.worst_d, s.df_max);
  printf("points beyond 1e-13 in f or 1e-10 in f' (within their allowances "
         "unless reported above): %ld; itineraries that differ where the "
         "reference's own is not determined within its root windows: %ld\n",
         s.ill, s.border);
  printf("itineraries that differ within rounding of a border: %ld; where "
         "quad takes the current map's (the reference erred): %ld\n",
         s.on_border, s.ref_wrong);
  tu_int("status differs", (int)s.status_diff, 0);
  tu_int("itinerary differs", (int)s.itin_diff, 0);
  tu_int("f differs by more than 1e-13 (+ 20 W, 100 J)", (int)s.f_diff, 0);
  /* f' where it is ill conditioned (a slope near zero at a root, or a
   * phase of near-zero length) is only checked against the reference's
   * spread, which the root moves of ref_jitter() sample crudely; at most
   * one evaluation in 2e4 may exceed it (measured over 1e7: 80 of 5e6
   * with derivatives, 1.6e-5; docs/performance.md). */
  tu_true(s.df_diff <= s.nderiv / 20000,
          "f' beyond 1e-10 relative (+ 100 J) at %ld of %ld evaluations "
          "(at most 1 in 2e4)",
          s.df_diff, s.nderiv);
  /* the sample must reach the grazing cases it is meant to test */
  long deep = 0;
  for (int k = 9; k < 16; k++) deep += s.near_graze[k];
  tu_true(deep > 0, "points with graze margin below 1e-9: %ld", deep);
  return tu_finish();
}
