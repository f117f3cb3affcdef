/* Velocity-weakening friction next to its edges: d* (both blocks at their
 * thresholds) and the crossing-sliding borders (a re-stick at the other
 * block's threshold), where one block comes loose a moment after the
 * other, or just after the other has re-stuck.  The map's numerical flows
 * (precise preset) against an integration of this file's own: a
 * long-double Taylor series of order TAYLOR_ORDER with the physics of
 * docs/model.md written out, events found on the series itself (sign changes
 * on a fine sampling of each step, then bisection), and the re-stick rule
 * stated as the motion gives it: a block that has started to slip moves
 * slower than the surface, U_i - Vs < 0, until U_i climbs back to Vs; its
 * re-stick is the first upward zero of U_i - Vs after the minimum of U_i
 * (U_i' rising through zero), never the start of the slip itself.
 *
 * Known answer (alpha 2.5, beta 2, V 0.05, gamma 1): next to d* = 1/6
 * block 2 comes loose about 1e-6 after block 1 and the motion is 1-12-1
 * (d < d*) or 2-12-1 (d > d*), f(d) about 0.13677; never a lone slip with
 * f = d. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "slipcont/slipcont.h"
#include "test_util.h"

/* Series order and step: the coefficients of the free motion fall like
 * (w h)^k / k! with w = sqrt(1 + 2 alpha) < 3 here, so at h = 1/64 the
 * truncation is ~ (3/64)^24 / 24! ~ 1e-56, far below long double's
 * rounding (~1e-19): the series is exact to rounding. */
#define TAYLOR_ORDER 24
#define TAYLOR_STEP (1.0L / 64)
/* Samples per step for the sign changes of a guard: two roots of one
 * guard closer than TAYLOR_STEP / 32 ~ 5e-4 would be missed, which only
 * a grazing gives (none is tested here). */
#define SAMPLES 32
/* Bisection of a root on the series: to long double's resolution. */
#define BISECT 80
#define MAX_PHASES 40
#define HORIZON 200.0L

typedef struct {
  long double alpha, beta, gamma, vs;
} ref_par;

typedef struct {
  long double y[2], u[2];
  int slip[2]; /* block i slips */
  int left[2]; /* block i has passed the minimum of U_i since its start */
} ref_state;

/* The series of one slip phase at state x: c[q][k], q = y1, y2, u1, u2. */
static void series(const ref_par *p, const ref_state *x,
                   long double c[4][TAYLOR_ORDER + 1]) {
  long double K[2][TAYLOR_ORDER + 1], Q[2][TAYLOR_ORDER + 1];
  const long double T[2] = {1, p->beta}, a = p->alpha;
  for (int i = 0; i < 2; i++) {
    c[i][0] = x->y[i];
    c[2 + i][0] = x->u[i];
  }
  for (int k = 0; k < TAYLOR_ORDER; k++) {
    for (int i = 0; i < 2; i++) {
      int j = 1 - i;
      c[i][k + 1] = c[2 + i][k] / (k + 1);
      if (!x->slip[i]) {
        c[2 + i][k + 1] = 0;
        continue;
      }
      /* K = T / q, q = 1 + gamma (Vs - U) on the slipping side U <= Vs */
      Q[i][k] = k == 0 ? 1 + p->gamma * (p->vs - c[2 + i][0])
                       : -p->gamma * c[2 + i][k];
      long double s = k == 0 ? T[i] : 0;
      for (int m = 1; m <= k; m++) s -= Q[i][m] * K[i][k - m];
      K[i][k] = s / Q[i][0];
      long double S = (1 + a) * c[i][k] - a * c[j][k];
      c[2 + i][k + 1] = (K[i][k] - S) / (k + 1);
    }
  }
}

static long double poly(const long double *c, int n, long double t) {
  long double v = c[n];
  for (int k = n - 1; k >= 0; k--) v = v * t + c[k];
  return v;
}

/* guard g(t) of a kind: 0, 1 re-stick of block i (U_i - Vs), 2, 3 its
 * acceleration U_i' (the minimum), 4 the stuck block's S_j - T_j. */
static long double guard(const ref_par *p, const ref_state *x,
                         long double c[4][TAYLOR_ORDER + 1], int kind,
                         long double t) {
  if (kind < 2) return poly(c[2 + kind], TAYLOR_ORDER, t) - p->vs;
  if (kind < 4) {
    long double d[TAYLOR_ORDER];
    for (int k = 0; k < TAYLOR_ORDER; k++)
      d[k] = (k + 1) * c[2 + kind - 2][k + 1];
    return poly(d, TAYLOR_ORDER - 1, t);
  }
  int j = x->slip[0] ? 1 : 0;
  long double T = j ? p->beta : 1;
  return (1 + p->alpha) * poly(c[j], TAYLOR_ORDER, t) -
         p->alpha * poly(c[1 - j], TAYLOR_ORDER, t) - T;
}

/* First upward zero of guard `kind` in (0, h]: -1 if none. */
static long double up_root(const ref_par *p, const ref_state *x,
                           long double c[4][TAYLOR_ORDER + 1], int kind,
                           long double h) {
  long double t0 = 0, g0 = guard(p, x, c, kind, 0);
  for (int s = 1; s <= SAMPLES; s++) {
    long double t1 = h * s / SAMPLES, g1 = guard(p, x, c, kind, t1);
    if (g0 < 0 && g1 >= 0) {
      for (int it = 0; it < BISECT; it++) {
        long double m = (t0 + t1) / 2;
        if (guard(p, x, c, kind, m) < 0) t0 = m;
        else t1 = m;
      }
      return t1;
    }
    t0 = t1, g0 = g1;
  }
  return -1;
}

static void advance(ref_state *x, long double c[4][TAYLOR_ORDER + 1],
                    long double t) {
  for (int i = 0; i < 2; i++) {
    x->y[i] = poly(c[i], TAYLOR_ORDER, t);
    x->u[i] = poly(c[2 + i], TAYLOR_ORDER, t);
  }
}

/* One iterate of the map from the GSP of displacement d: f and the
 * itinerary, or NAN. */
static long double ref_map(const ref_par *p, double d, char *itin,
                           size_t len) {
  long double dl = d, dstar = (p->beta - 1) / (1 + 2 * p->alpha);
  ref_state x = {{0, 0}, {p->vs, p->vs}, {0, 0}, {0, 0}};
  if (dl < dstar) {
    x.y[0] = 1 + p->alpha * dl, x.y[1] = x.y[0] + dl, x.slip[0] = 1;
  } else if (dl > dstar) {
    x.y[1] = p->beta - p->alpha * dl, x.y[0] = x.y[1] - dl, x.slip[1] = 1;
  } else {
    x.y[0] = 1 + p->alpha * dl, x.y[1] = x.y[0] + dl;
    x.slip[0] = x.slip[1] = 1;
  }
  itin[0] = '\0';
  for (int ph = 0; ph < MAX_PHASES; ph++) {
    const char *name = x.slip[0] && x.slip[1] ? "12" : x.slip[0] ? "1" : "2";
    snprintf(itin + strlen(itin), len - strlen(itin), "%s%s", ph ? "-" : "",
             name);
    long double t = 0;
    int ended = 0;
    while (!ended && t < HORIZON) {
      long double c[4][TAYLOR_ORDER + 1];
      series(p, &x, c);
      long double h = TAYLOR_STEP, best = -1;
      int which = -1;
      for (int i = 0; i < 2; i++) {
        if (!x.slip[i]) continue;
        long double from = 0;
        if (!x.left[i]) {
          /* still leaving Vs: its minimum first */
          long double tm = up_root(p, &x, c, 2 + i, h);
          if (tm < 0) continue;
          from = tm;
        }
        /* the re-stick after the minimum, on the series from there */
        ref_state xm = x;
        long double cm[4][TAYLOR_ORDER + 1];
        advance(&xm, c, from);
        series(p, &xm, cm);
        long double tr = up_root(p, &xm, cm, i, h - from);
        if (tr >= 0 && (which < 0 || from + tr < best))
          best = from + tr, which = i;
      }
      if (!(x.slip[0] && x.slip[1])) {
        long double tt = up_root(p, &x, c, 4, h);
        if (tt >= 0 && (which < 0 || tt < best)) best = tt, which = 2;
      }
      /* the minimum of a leaving block within the step, if no event */
      long double tend = which >= 0 ? best : h;
      for (int i = 0; i < 2; i++)
        if (x.slip[i] && !x.left[i] && up_root(p, &x, c, 2 + i, tend) >= 0)
          x.left[i] = 1;
      advance(&x, c, tend);
      t += tend;
      if (which < 0) continue;
      ended = 1;
      if (which < 2) {
        x.slip[which] = 0, x.u[which] = p->vs;
      } else {
        int j = x.slip[0] ? 1 : 0;
        x.slip[j] = 1, x.left[j] = 0, x.u[j] = p->vs;
      }
    }
    if (!ended) return NAN;
    if (!x.slip[0] && !x.slip[1]) return x.y[1] - x.y[0];
  }
  return NAN;
}

static sc_map *vw_map(const ref_par *p) {
  sc_map *m;
  sc_msg msg;
  if (sc_map_alloc("bk2", NULL, &m, &msg)) return NULL;
  sc_map_set_param_by_name(m, "alpha", (double)p->alpha, &msg);
  sc_map_set_param_by_name(m, "beta", (double)p->beta, &msg);
  sc_map_set_param_by_name(m, "v", (double)p->vs, &msg);
  sc_map_set_option(m, "driver", "moving", &msg);
  sc_map_set_option(m, "friction", "velocity-weakening", &msg);
  sc_map_set_param_by_name(m, "gamma", (double)p->gamma, &msg);
  sc_accuracy acc;
  sc_accuracy_preset(&acc, "precise", NULL);
  sc_map_set_accuracy(m, &acc, NULL);
  return m;
}

/* A border of the reference's itineraries in [lo, hi] (their itineraries
 * differ), by bisection down to adjacent doubles. */
static double border(const ref_par *p, double lo, double hi) {
  char ilo[256], ihi[256], im[256];
  ref_map(p, lo, ilo, sizeof ilo);
  ref_map(p, hi, ihi, sizeof ihi);
  if (!tu_true(strcmp(ilo, ihi) != 0, "a border in [%.17g, %.17g]: %s, %s",
               lo, hi, ilo, ihi))
    return NAN;
  while (nextafter(lo, hi) < hi) {
    double m = lo + (hi - lo) / 2;
    if (m <= lo || m >= hi) break;
    ref_map(p, m, im, sizeof im);
    if (strcmp(im, ilo) == 0) lo = m;
    else hi = m;
  }
  return lo;
}

/* The map against the reference at d, a distance `gap` from a border
 * db of the reference (db = NAN: none): the same itinerary and f within
 * tol.  Within BORDER_SLACK of a border the map may answer for the other
 * side (its event times are known to its precision, ~1e-12, so the
 * border to about that in d): then its answer must be the reference's
 * there, at the mirror point 2 db - d (f within tol plus its change over
 * 2 gap, |f'| < FPRIME_MAX on these pieces). */
#define BORDER_SLACK 1e-11
#define FPRIME_MAX 10.0
static int other_side;

static void compare(sc_map *m, const ref_par *p, double d, double db,
                    double tol, const char *where) {
  char ri[256], what[512];
  long double fr = ref_map(p, d, ri, sizeof ri);
  sc_map_value v;
  sc_msg msg;
  int st = sc_map_eval(m, d, SC_EVAL_ITINERARY, &v, &msg);
  snprintf(what, sizeof what, "%s, d = %.17g: itinerary (reference %s)",
           where, d, ri);
  if (st) {
    tu_true(0, "%s: the map failed: %s", what, msg.text);
    return;
  }
  double gap = fabs(d - db);
  if (strcmp(v.itinerary, ri) != 0 && gap <= BORDER_SLACK) {
    double dm = 2 * db - d;
    fr = ref_map(p, dm, ri, sizeof ri);
    snprintf(what, sizeof what,
             "%s, d = %.17g: itinerary (the other side's, reference %s at "
             "%.17g)", where, d, ri, dm);
    tol += FPRIME_MAX * 2 * gap;
    other_side++;
  }
  tu_true(strcmp(v.itinerary, ri) == 0, "%s: map %s", what, v.itinerary);
  snprintf(what, sizeof what, "%s, d = %.17g: f", where, d);
  tu_close(what, v.f, (double)fr, tol);
}

int main(void) {
  gsl_set_error_handler_off();
  const ref_par p = {2.5L, 2, 1, 0.05L};
  sc_map *m = vw_map(&p);
  /* The promise: the flows' precision over the few phases of an iterate,
   * times f's growth there (|f'| < FPRIME_MAX on these pieces: 4.6 next
   * to d*). */
  double tol = 3 * FPRIME_MAX * sc_map_precision(m);
  printf("tolerance on f: %.3g\n", tol);
  const double gaps[] = {1e-6, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
  const size_t ngaps = sizeof gaps / sizeof *gaps;
  long double dstar = (p.beta - 1) / (1 + 2 * p.alpha);
  for (size_t k = 0; k < ngaps; k++)
    for (int s = -1; s <= 1; s += 2)
      compare(m, &p, (double)(dstar + s * (long double)gaps[k]), NAN, tol,
              "next to d*");
  /* Crossing-sliding borders (a re-stick at the other block's threshold):
   * 1 | 1-12-2-12-1 (the first slip), 1-12-2-12-1 | 1-12-2 (the third),
   * 2-12-1 | 2 (the first, block 2 first). */
  const double brackets[][2] = {
      {0.1176, 0.11795}, {0.13895, 0.1393}, {0.2415, 0.24185}};
  for (size_t j = 0; j < sizeof brackets / sizeof *brackets; j++) {
    double db = border(&p, brackets[j][0], brackets[j][1]);
    if (isnan(db)) continue;
    char where[64];
    snprintf(where, sizeof where, "next to the border %.17g", db);
    for (size_t k = 0; k < ngaps; k++)
      for (int s = -1; s <= 1; s += 2)
        compare(m, &p, db + s * gaps[k], db, tol, where);
  }
  printf("%d answers for the other side of a border (within %g)\n",
         other_side, BORDER_SLACK);
  sc_map_free(m);
  return tu_finish();
}
