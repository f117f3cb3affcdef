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
 * (the plain path).  A point where the root of a guard is ill conditioned
 * (slope at the root within 1e-6, i.e. graze margin < 1e-9) may differ by
 * more than 1e-13 in f without either search being wrong: the root moves
 * by rounding/slope.  Such points are counted and their largest difference
 * printed, and must stay within 1e-13 + 1e-16 / sqrt(margin) (the root's
 * conditioning, with f' of order one). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/bk2_impl.h"
#include "ref/guard_v0.h"
#include "slipcont/map.h"
#include "test_util.h"

static unsigned long long rng = 0x2545f4914f6cdd1dULL;
static double uni(double lo, double hi) {
  rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
  return lo + (hi - lo) * (double)(rng >> 11) / 9007199254740992.0;
}

typedef struct {
  long n, nderiv, status_diff, itin_diff, f_diff, df_diff, ill, ill_bad;
  long near_graze[16]; /* points by decade of graze margin: 1e-k, k < 16 */
  double f_max, df_max, ill_max;
  double worst_p[4], worst_d;
} stats;

typedef struct {
  bk2_inst *now, *ref;
} pair;

static int setup(bk2_inst *b, const double p[4], int frozen,
                 int (*search)(const sc_guard *, double, int, double, double,
                               sc_root *)) {
  sc_accuracy acc;
  sc_msg msg;
  sc_accuracy_preset(&acc, "default", NULL);
  int opt[3] = {frozen, 0, 0};
  memset(b, 0, sizeof *b);
  int st = sc_model_bk2.setup(b, p, opt, &acc, &msg);
  b->search = search;
  return st;
}

static int eval(bk2_inst *b, double d, unsigned flags, sc_map_value *out) {
  sc_msg msg;
  memset(out, 0, sizeof *out);
  out->gsp_gap = out->graze_margin = out->dstar_dist = HUGE_VAL;
  return sc_model_bk2.eval(b, d, flags, out, &msg);
}

/* Compare both maps at d; returns the current map's value in *f (NaN if
 * undefined) and its itinerary in itin (may be NULL). */
static void compare(const pair *P, const double p[4], double d, stats *s,
                    double *f, char *itin) {
  unsigned flags = SC_EVAL_ITINERARY | (s->n % 2 ? SC_EVAL_DERIV : 0);
  sc_map_value a, r;
  int sa = eval(P->now, d, flags, &a), sr = eval(P->ref, d, flags, &r);
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
    if (s->itin_diff++ < 5)
      printf("  itinerary %s vs %s at alpha %.17g beta %.17g phi %.17g v "
             "%.17g d %.17g (graze margin %.3g)\n",
             a.itinerary, r.itinerary, p[0], p[1], p[2], p[3], d,
             r.graze_margin);
    return;
  }
  double m = fmin(a.graze_margin, r.graze_margin);
  if (m > 0 && m < 1) {
    int k = (int)floor(-log10(m));
    if (k >= 0 && k < 16) s->near_graze[k]++;
  }
  double e = fabs(a.f - r.f);
  /* the root's conditioning: slope ~ sqrt(margin), time error ~ eps/slope */
  int illc = m < 1e-9;
  if (illc) {
    s->ill++;
    s->ill_max = fmax(s->ill_max, e);
    if (e > 1e-13 + 1e-16 / sqrt(m)) s->ill_bad++;
  } else {
    if (e > s->f_max) {
      s->f_max = e;
      memcpy(s->worst_p, p, sizeof s->worst_p);
      s->worst_d = d;
    }
    if (e > 1e-13 && s->f_diff++ < 5)
      printf("  f %.17g vs %.17g at alpha %.17g beta %.17g phi %.17g v "
             "%.17g d %.17g\n",
             a.f, r.f, p[0], p[1], p[2], p[3], d);
  }
  if (flags & SC_EVAL_DERIV) {
    s->nderiv++;
    double da[5] = {a.dfdd, a.dfdp[0], a.dfdp[1], a.dfdp[2], a.dfdp[3]};
    double dr[5] = {r.dfdd, r.dfdp[0], r.dfdp[1], r.dfdp[2], r.dfdp[3]};
    for (int k = 0; k < 5; k++) {
      if (isnan(da[k]) && isnan(dr[k])) continue;
      double rel = fabs(da[k] - dr[k]) / fmax(1, fabs(dr[k]));
      if (!(rel <= 1e-10) && !illc) {
        if (s->df_diff++ < 5)
          printf("  df[%d] %.17g vs %.17g at alpha %.17g beta %.17g phi "
                 "%.17g v %.17g d %.17g\n",
                 k, da[k], dr[k], p[0], p[1], p[2], p[3], d);
      }
      if (!illc && rel > s->df_max) s->df_max = rel;
    }
  }
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
  if (setup(&now, p, frozen, sc_guard_first_root) ||
      setup(&ref, p, frozen, sc_guard_first_root_v0))
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
  printf("ill-conditioned roots (graze margin < 1e-9): %ld, largest "
         "|f - f_ref| %.3g\n",
         s.ill, s.ill_max);
  tu_int("status differs", (int)s.status_diff, 0);
  tu_int("itinerary differs", (int)s.itin_diff, 0);
  tu_int("f differs by more than 1e-13", (int)s.f_diff, 0);
  tu_int("f' differs by more than 1e-10 relative", (int)s.df_diff, 0);
  tu_int("ill-conditioned roots beyond their conditioning", (int)s.ill_bad,
         0);
  /* the sample must reach the grazing cases it is meant to test */
  long deep = 0;
  for (int k = 9; k < 16; k++) deep += s.near_graze[k];
  tu_true(deep > 0, "points with graze margin below 1e-9: %ld", deep);
  return tu_finish();
}
