/* The extremes of the parameter ranges (docs/accuracy.md, "The
 * extremes"): alpha in [1e-3, 1e3], beta in [1e-2, 1e2], phi in
 * [1 + 1e-6, 1e3], V in [0, 1e2], both drivers, d next to d* (1e-15 ..
 * 1e-3 away), far from it, and next to grazing.  Every case must give an
 * answer within the promise of the preset against the quad path, or a
 * clear refusal (a status with a message): never NaN, never a GSP with a
 * block beyond its threshold (a missed event), never an itinerary that
 * differs from quad's away from a border.
 *
 *   test_extremes            the fast grid (ctest)
 *   test_extremes long [i]   the long sweep (bench_accuracy_extremes);
 *                            with i, only the i-th alpha (0..6), so
 *                            that the sweep can run as 7 processes
 *
 * Cases that fail on a known defect of the double path are listed in
 * `known[]` with the reason; they are printed and counted, not failed,
 * and the test fails if one of them starts to pass (so that the list is
 * kept honest when the defect is fixed). */
#include <float.h>
#include <math.h>
#include <quadmath.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "models/bk2_quad.h"
#include "slipcont/bk2.h"
#include "slipcont/map.h"
#include "test_util.h"

/* The promise of the default preset with exact flows (docs/accuracy.md):
 * |f - f_quad| <= PROMISE_F eps S (1 + |f'|) n, S = 1 + beta + (1 +
 * alpha)|d| the size of the onset state, n the number of slip phases:
 * the rounding of the onset state is carried to f with the gain f', and
 * each phase adds its own.  f' has the gain of f'' / f', which
 * grows like 1 / (distance to the border) next to d* (f' ~ |d - d*|^-1/2)
 * and next to grazing (f' ~ margin^-1/2): |f' - f'_quad| <= PROMISE_DF
 * eps S (1 + |f'|) / min(1, distance), the distance being the smallest
 * of |d - d*|, the graze margin and the threshold gap. */
#define PROMISE_F 64.0
#define PROMISE_DF 1024.0
/* Two itineraries (or a defined and an undefined map) may differ only
 * this close to a border, in units of eps S: the last bits of the onset
 * state decide the side. */
#define BORDER_ULPS 1024.0

typedef struct {
  double alpha, beta, phi, v;
  int frozen;
} pcase;

/* Slip phases per iterate before the map is undefined: fewer than the
 * preset's 256, since the slip cycles of V = 100 (every quad phase a
 * certified search) would dominate the time: 48 in the fast grid, 128 in
 * the long sweep. */
static int max_events = 48;
static long ncase, nok, nrefused, nborder, nknown;

static const char *drv(int frozen) { return frozen ? "frozen" : "moving"; }

static sc_map *make(const pcase *c, int precision) {
  sc_accuracy acc;
  sc_msg msg;
  sc_map *m;
  sc_accuracy_preset(&acc, "default", NULL);
  acc.precision = precision;
  acc.max_events = max_events;
  if (sc_map_alloc("bk2", &acc, &m, &msg)) return NULL;
  if (sc_map_set_param_by_name(m, "alpha", c->alpha, &msg) ||
      sc_map_set_param_by_name(m, "beta", c->beta, &msg) ||
      sc_map_set_param_by_name(m, "phi", c->phi, &msg) ||
      sc_map_set_param_by_name(m, "v", c->v, &msg) ||
      sc_map_set_option(m, "driver", drv(c->frozen), &msg)) {
    printf("make: %s\n", msg.text);
    sc_map_free(m);
    return NULL;
  }
  return m;
}

/* Known defects of the double path, found by this test and reported
 * (docs/accuracy.md, "Defects found"): a failing case matches an entry
 * when the failure is `bad`, its alpha, beta, phi are those given (0:
 * any), its V is (-1: any), its driver is (-1: either) and |d - d*| <=
 * dmax.  Each entry marked in_fast must be hit at least once by the fast
 * grid, so that a fix in the double path shows up here (then remove the
 * entry); the others occur in the long sweep only. */
typedef struct {
  const char *bad;
  double alpha, beta, phi, v;
  int frozen;
  double dmax;
  const char *why;
  int in_fast; /* 1: the fast grid must hit it */
} known_case;

static const known_case known[] = {
    /* D1 (one ulp below d* with beta >> 1 the stuck block's threshold
     * guard came out positive at t = 0 by rounding and the trigger was
     * missed) is fixed: the guard's value at the onset is the onset
     * formula's, (1 + 2 alpha)(d - d*). */
    /* D2 (alpha = 1000, beta = 1, V = 100: two synchronous re-sticks at
     * d* split, f = 5.3e-7 instead of 0) is fixed: the tie of two
     * re-sticks is decided with the roots' own uncertainty. */
    /* ... and 1e-12 from d* at V >= 1 with small alpha (long sweep), where
     * double and quad ordered two near-synchronous re-sticks differently:
     * they are within each other's rounding window, a both-re-stick
     * border within rounding, and are counted on a border since the test
     * sees those borders (the long sweep of 2026-11-24 has no defect). */
    /* D3, f' = NaN with SC_OK where an event slope rounds to 0, is fixed:
     * that evaluation now fails with SC_ENONFINITE and a message (a
     * refusal).  Its variant with V = 1e-12 next to d* (a trigger taken
     * at the onset, within rounding, with the slope (1 + alpha) V there:
     * f' 1e5 times too large) is fixed: the slope is the one at the root
     * of the guard's quadratic expansion. */
    /* D5 (alpha = 1e-3, beta = 10, phi = 1 + 1e-6, V = 100, 3e-6 to 9e-6
     * below d*: a block triggered 8e-8 into the other's slip re-stuck at
     * once, then stayed stuck 629 beyond its threshold) is fixed: a
     * re-stick guard that starts within rounding of zero and falls skips
     * its start root. */
    {NULL, 0, 0, 0, 0, 0, 0, NULL, 0},
};

/* (the list may be empty but for its end: loops stop at the NULL) */
#define NKNOWN (sizeof known / sizeof known[0])
static long known_hits[NKNOWN];

/* The entry of known[] that covers a failing case, or -1. */
static int known_index(const char *bad, const pcase *c, double d) {
  double dd = fabs(d - sc_bk2_dstar(c->alpha, c->beta));
  for (size_t i = 0; known[i].bad; i++) {
    const known_case *k = &known[i];
    if (strcmp(k->bad, bad) == 0 && (k->alpha == 0 || k->alpha == c->alpha) &&
        (k->beta == 0 || k->beta == c->beta) &&
        (k->phi == 0 || k->phi == c->phi) && (k->v < 0 || k->v == c->v) &&
        (k->frozen < 0 || k->frozen == c->frozen) && dd <= k->dmax)
      return (int)i;
  }
  return -1;
}

/* The distances to the borders an evaluation reports: |d - d*|, the
 * threshold gap at the last re-stick (negative: a crossing missed), the
 * smallest grazing margin, (double only) the smallest |m| of any border
 * of the itinerary (r of the f' promise) and of the other kinds
 * (crossing-sliding between an event and another guard's rise, both
 * re-sticks, touches: within rounding, a border either side of which
 * may be taken, as the tie rule does for two re-sticks within their
 * roots' rounding windows).
 * Double: from the model's borders (models.h); quad: from the quad
 * path's own margins. */
typedef struct {
  double dstar_dist, gsp_gap, graze_margin, any, other;
} margins;

static margins margins_double(sc_map *m, double d) {
  margins r = {HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL};
  sc_border bl[256];
  sc_border_list l = {bl, 256, 0};
  sc_map_value v;
  if (sc_map_eval_ex(m, d, SC_EVAL_VALUE, NULL, NULL, &l, &v, NULL)) return r;
  for (size_t i = 0; i < l.n && i < l.cap; i++) {
    double x = bl[i].value;
    r.any = fmin(r.any, fabs(x));
    if (bl[i].kind == SC_BORDER_BOTH || bl[i].kind == SC_BORDER_TOUCH ||
        (bl[i].kind == SC_BORDER_CROSSING &&
         strncmp(bl[i].name, "threshold gap", 13) != 0))
      r.other = fmin(r.other, fabs(x));
    if (bl[i].kind == SC_BORDER_SWITCHING) r.dstar_dist = fmin(r.dstar_dist, fabs(x));
    if (bl[i].kind == SC_BORDER_GRAZING) r.graze_margin = fmin(r.graze_margin, fabs(x));
    if (bl[i].kind == SC_BORDER_CROSSING && strncmp(bl[i].name, "threshold gap", 13) == 0)
      r.gsp_gap = fabs(x) < fabs(r.gsp_gap) ? x : r.gsp_gap;
  }
  return r;
}

static margins margins_quad(const pcase *c, double d) {
  margins r = {HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL};
  sc_bk2q_params p = {c->alpha, c->beta, c->phi, c->v, c->frozen, max_events};
  sc_bk2q_value q;
  if (sc_bk2q_eval(&p, d, 0, &q, NULL)) return r;
  r.dstar_dist = q.dstar_dist, r.gsp_gap = q.gsp_gap;
  r.graze_margin = q.graze_margin;
  return r;
}

/* One case: returns 1 if it passes. */
static int check_case(sc_map *md, sc_map *mq, const pcase *c, double d,
                      double border_dist, const char *where) {
  sc_map_value rd, rq;
  sc_msg m1 = {""}, m2 = {""};
  unsigned fl = SC_EVAL_DERIV | SC_EVAL_ITINERARY;
  int s1 = sc_map_eval(md, d, fl, &rd, &m1);
  int s2 = sc_map_eval(mq, d, fl, &rq, &m2);
  margins md_ = margins_double(md, d), mq_ = margins_quad(c, d);
  double S = 1 + c->beta + (1 + c->alpha) * fabs(d);
  double eps = DBL_EPSILON;
  double near = BORDER_ULPS * eps * S;
  /* the re-stick guards are velocities of size ~ 1 + V: their margins
   * are within rounding below BORDER_ULPS eps (S + V); so are the
   * threshold gaps, whose spring forces carry the stuck block's drift
   * V_s t over the phase (at V = 100 the gaps of alpha = 1e-3, beta = 10
   * round to ~1e-11: the long sweep) */
  double near_v = BORDER_ULPS * eps * (S + c->v);
  int border = border_dist <= 1e-12 * fmax(1, fabs(d)) ||
               md_.dstar_dist <= near || fabs(md_.gsp_gap) <= near_v ||
               md_.graze_margin <= near_v || md_.other <= near_v;
  if (!s2)
    border = border || mq_.dstar_dist <= near ||
             fabs(mq_.gsp_gap) <= near_v || mq_.graze_margin <= near_v;
  /* distance to the nearest border either path saw (f' promise) */
  double bd = fmin(fmin(md_.dstar_dist, md_.graze_margin),
                   fmin(fabs(md_.gsp_gap), md_.any));
  if (!s2)
    bd = fmin(bd, fmin(fmin(mq_.dstar_dist, mq_.graze_margin), fabs(mq_.gsp_gap)));
  if (s1)
    bd = s2 ? HUGE_VAL
            : fmin(fmin(mq_.dstar_dist, mq_.graze_margin), fabs(mq_.gsp_gap));
  bd = fmin(bd, border_dist);
  /* rounding accumulates over the slip phases of the iterate */
  double nph = s1 ? 1 : fmax(1, rd.nphases);
  const char *bad = NULL;
  char detail[SC_MSG_LEN + 32] = "";
  ncase++;
  if (s1) {
    /* a refusal: a negative status with a message */
    if (s1 > 0 || m1.text[0] == '\0')
      bad = "refusal without a message";
    else if (s2 == SC_OK && !border &&
             !strstr(m1.text, "beyond what double resolves"))
      /* (a refusal that names double's limit is the promise kept) */
      bad = "double refuses where quad answers, away from a border";
    else {
      nrefused++;
      return 1;
    }
  } else if (!isfinite(rd.f)) {
    bad = "f is not finite";
  } else if (md_.gsp_gap < -near_v) {
    snprintf(detail, sizeof detail,
             " (gsp gap %.3g: a threshold crossing "
             "was missed)",
             md_.gsp_gap);
    bad = "a block ends beyond its threshold";
  } else if (!isfinite(rd.dfdd) && !(md_.dstar_dist == 0 && c->v == 0) &&
             !(md_.dstar_dist == 0 && c->frozen)) {
    snprintf(detail, sizeof detail, " (quad f' = %.6g, graze margin %.3g)",
             s2 ? NAN : rq.dfdd, s2 ? NAN : mq_.graze_margin);
    bad = "f' is NaN where f is differentiable";
  } else if (s2) {
    /* quad refuses (a slip cycle): double may answer only next to a
     * border */
    if (border) {
      nborder++;
      return 1;
    }
    snprintf(detail, sizeof detail, " (quad: %s)", m2.text);
    bad = "double answers where quad refuses, away from a border";
  } else {
    double ef = fabs(rd.f - rq.f), gain = 1 + fabs(rq.dfdd);
    int same = strcmp(rd.itinerary, rq.itinerary) == 0;
    if (!same) {
      if (!border)
        bad = "itineraries differ away from a border";
      else if (mq_.dstar_dist <= near && ef > PROMISE_F * eps * S * gain * nph)
        /* f is continuous at d*: the other side gives the same f */
        bad = "itineraries differ at d* and f with them";
      else {
        nborder++;
        return 1;
      }
    } else if (ef > PROMISE_F * eps * S * gain * nph) {
      snprintf(detail, sizeof detail, " (|df| = %.3g > %.3g)", ef,
               PROMISE_F * eps * S * gain * nph);
      bad = "f outside the promise";
    } else if (isfinite(rq.dfdd) && isfinite(rd.dfdd) &&
               fabs(rd.dfdd - rq.dfdd) >
                   PROMISE_DF * eps * S * gain / fmin(1, bd)) {
      snprintf(detail, sizeof detail, " (|df'| = %.3g > %.3g)",
               fabs(rd.dfdd - rq.dfdd),
               PROMISE_DF * eps * S * gain / fmin(1, bd));
      bad = "f' outside the promise";
    }
  }
  if (!bad) {
    nok++;
    return 1;
  }
  int ki = known_index(bad, c, d);
  const char *why = ki >= 0 ? known[ki].why : NULL;
  if (ki >= 0) known_hits[ki]++;
  printf("%s %s%s: %s alpha=%.17g beta=%.17g phi=%.17g v=%.17g %s "
         "d=%.17g (d - d* = %.3g)\n"
         "     double: status %d f=%.17g f'=%.17g itinerary %s gap %.3g "
         "graze %.3g %s\n"
         "     quad:   status %d f=%.17g f'=%.17g itinerary %s gap %.3g "
         "graze %.3g %s\n",
         why ? "KNOWN" : "FAIL", bad, detail, where, c->alpha, c->beta, c->phi,
         c->v, drv(c->frozen), d, d - sc_bk2_dstar(c->alpha, c->beta), s1, rd.f,
         rd.dfdd, rd.itinerary, md_.gsp_gap, md_.graze_margin, m1.text, s2, rq.f,
         rq.dfdd, rq.itinerary, mq_.gsp_gap, mq_.graze_margin, m2.text);
  if (why) {
    nknown++;
    return 1;
  }
  return 0;
}

/* d next to d*, and far from it on the scale of the slips. */
static int near_dstar(sc_map *md, sc_map *mq, const pcase *c, int long_run) {
  static const double off[] = {1e-15, 1e-12, 1e-9, 1e-6, 1e-3};
  static const double far[] = {0.05, 0.3, 1};
  int fails = 0;
  double ds = sc_bk2_dstar(c->alpha, c->beta);
  double scale = (1 + c->beta) / (1 + c->alpha);
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    for (size_t i = 0; i < sizeof off / sizeof off[0]; i++) {
      if (!long_run && (i == 1 || i == 3)) continue;
      fails += !check_case(md, mq, c, ds + sgn * off[i] * fmax(1, fabs(ds)),
                           HUGE_VAL, "near d*");
    }
    for (size_t i = 0; i < sizeof far / sizeof far[0]; i++)
      fails +=
          !check_case(md, mq, c, ds + sgn * far[i] * scale, HUGE_VAL, "far");
  }
  fails += !check_case(md, mq, c, ds, HUGE_VAL, "at d*");
  return fails;
}

/* Borders other than d*: scan d for a change of the quad itinerary, locate
 * it by bisection in quad, and check both sides at 1e-15 .. 1e-3. */
static int near_grazing(sc_map *md, sc_map *mq, const pcase *c, int nscan,
                        int maxfound, int *found) {
  sc_bk2q_params qp = {c->alpha, c->beta, c->phi, c->v, c->frozen, max_events};
  double ds = sc_bk2_dstar(c->alpha, c->beta);
  double scale = (1 + c->beta) / (1 + c->alpha);
  int fails = 0;
  sc_bk2q_value a, b;
  double x0 = ds - scale, x1 = ds + scale;
  int sa = sc_bk2q_eval(&qp, x0, 0, &a, NULL);
  int here = 0;
  for (int i = 1; i <= nscan && here < maxfound; i++) {
    double x = x0 + (x1 - x0) * i / nscan,
           xp = x0 + (x1 - x0) * (i - 1) / nscan;
    int sb = sc_bk2q_eval(&qp, x, 0, &b, NULL);
    int change = !sa && !sb && strcmp(a.itinerary, b.itinerary) != 0 &&
                 !((xp < ds) != (x < ds));
    sc_bk2q_value lo_v = a;
    a = b;
    sa = sb;
    if (!change) continue;
    /* bisection in quad on the itinerary */
    sc_quad lo = xp, hi = x;
    for (int it = 0; it < 100 && hi - lo > 1e-22 * (1 + fabsq(hi)); it++) {
      sc_quad mid = (lo + hi) / 2;
      sc_bk2q_value r;
      if (sc_bk2q_eval(&qp, mid, 0, &r, NULL)) break;
      if (strcmp(r.itinerary, lo_v.itinerary) == 0)
        lo = mid;
      else
        hi = mid;
    }
    double dg = (double)((lo + hi) / 2);
    static const double off[] = {1e-15, 1e-12, 1e-9, 1e-6, 1e-3};
    for (int sgn = -1; sgn <= 1; sgn += 2)
      for (size_t k = 0; k < sizeof off / sizeof off[0]; k++)
        fails +=
            !check_case(md, mq, c, dg + sgn * off[k] * fmax(1, fabs(dg)),
                        off[k] * fmax(1, fabs(dg)), "near a grazing/crossing");
    (*found)++;
    here++;
  }
  return fails;
}

int main(int argc, char **argv) {
  int long_run = argc > 1 && strcmp(argv[1], "long") == 0;
  if (long_run) max_events = 128;
  static const double A_fast[] = {1e-3, 1, 1e3}, B_fast[] = {1e-2, 1, 1e2},
                      P_fast[] = {1 + 1e-6, 1.25, 1e3},
                      V_fast[] = {0, 1e-12, 0.025, 1e2};
  static const double A_long[] = {1e-3, 1e-2, 0.1, 1, 10, 100, 1e3},
                      B_long[] = {1e-2, 0.1, 1, 2.5, 10, 100},
                      P_long[] = {1 + 1e-6, 1.25, 10, 1e3},
                      V_long[] = {0, 1e-12, 0.025, 1, 100};
  const double *A = long_run ? A_long : A_fast, *B = long_run ? B_long : B_fast,
               *P = long_run ? P_long : P_fast, *V = long_run ? V_long : V_fast;
  int na = long_run ? 7 : 3, nb = long_run ? 6 : 3, np = long_run ? 4 : 3,
      nv = long_run ? 5 : 4;
  int fails = 0, grazings = 0, only = -1;
  if (long_run && argc > 2) only = atoi(argv[2]);
  for (int ia = 0; ia < na; ia++)
    for (int ib = 0; ib < nb; ib++)
      for (int ip = 0; ip < np; ip++)
        for (int iv = 0; iv < nv; iv++)
          for (int fr = 0; fr < 2; fr++) {
            /* with the driver frozen f does not depend on V */
            if ((fr && iv > 0) || (only >= 0 && ia != only)) continue;
            pcase c = {A[ia], B[ib], P[ip], V[iv], fr};
            sc_map *md = make(&c, SC_PRECISION_DOUBLE);
            sc_map *mq = make(&c, SC_PRECISION_QUAD);
            if (!tu_true(md && mq, "maps for alpha=%g beta=%g phi=%g v=%g",
                         c.alpha, c.beta, c.phi, c.v)) {
              sc_map_free(md);
              sc_map_free(mq);
              continue;
            }
            double t0 = (double)clock() / CLOCKS_PER_SEC;
            fails += near_dstar(md, mq, &c, long_run);
            /* grazing: every case in the long run; in the fast grid the
             * ones with phi = 1.25 (the reference chapter's) */
            if (long_run || ip == 1)
              fails += near_grazing(md, mq, &c, long_run ? 48 : 24,
                                    long_run ? 4 : 2, &grazings);
            double t1 = (double)clock() / CLOCKS_PER_SEC;
            if (long_run && t1 - t0 > 1)
              printf("slow case: %.2f s of CPU at alpha=%g beta=%g phi=%g "
                     "v=%g %s\n",
                     t1 - t0, c.alpha, c.beta, c.phi, c.v, drv(c.frozen));
            sc_map_free(md);
            sc_map_free(mq);
          }
  printf("extremes: %ld cases: %ld answered within the promise, %ld refused "
         "with a message, %ld on a border (either side), %ld known defects; "
         "%d borders located\n",
         ncase, nok, nrefused, nborder, nknown, grazings);
  tu_int("cases outside the promise (see FAIL lines above)", fails, 0);
  for (size_t i = 0; known[i].bad && !long_run; i++)
    tu_true(known_hits[i] > 0 || !known[i].in_fast,
            "known defect %zu seen %ld times (none: "
            "fixed? then remove it from known[]): %s",
            i, known_hits[i], known[i].why);
  tu_true(grazings >= (long_run ? 100 : 10), "borders found: %d", grazings);
  return tu_finish();
}
