/* Period detection: exact sequences fed by hand, the logistic map at r
 * with known attractors, the near-flip rule, and bk2 points whose
 * periods docs/model.md states. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "slipcont/period.h"
#include "test_util.h"

/* Pushes until a period is accepted (at most n), returning the period and
 * the number of pushes made in *pushes. */
static int feed(sc_period *pd, const double *seq, int len, int n,
                int *pushes) {
  int p = 0;
  for (int k = 1; k <= n && !p; k++) {
    p = sc_period_push(pd, seq[k % len]);
    *pushes = k;
  }
  return p;
}

static void exact_sequences(void) {
  sc_msg msg;
  sc_period *pd = NULL;
  tu_int("alloc max 16 confirm 4", sc_period_alloc(16, 4, 1e-6, &pd, &msg),
         SC_OK);
  int pushes = 0;
  /* A cycle of 3 exactly repeated: run[3] reaches confirm * 3 = 12 at
   * iterate 3 + 12 - 1 = 14, the earliest a period-3 can be confirmed. */
  const double c3[3] = {0.125, 2.385, -1.75};
  sc_period_reset(pd, c3[0]);
  tu_int("exact 3-cycle: period", feed(pd, c3, 3, 1000, &pushes), 3);
  tu_int("exact 3-cycle: accepted at iterate (confirm+1)*3 - 1", pushes, 14);
  tu_int("push after acceptance keeps the period", sc_period_push(pd, 99.0),
         3);
  /* Constant sequence: period 1 after confirm = 4 equal differences. */
  const double c1[1] = {2.385};
  sc_period_reset(pd, c1[0]);
  tu_int("constant: period", feed(pd, c1, 1, 1000, &pushes), 1);
  tu_int("constant: accepted at iterate 4", pushes, 4);
  /* Zero extent: the tolerance floor is 0 at x = 0, and exact zeros
   * still repeat. */
  const double z[1] = {0.0};
  sc_period_reset(pd, 0.0);
  tu_int("all zeros: period 1", feed(pd, z, 1, 1000, &pushes), 1);
  tu_close("all zeros: tolerance", sc_period_tol(pd), 0, 0);
  /* A period-16 cycle is detected; a 17-cycle is not (max 16). */
  double c16[17];
  for (int i = 0; i < 17; i++) c16[i] = sin(2.385 * i * i + i);
  sc_period_reset(pd, c16[0]);
  tu_int("exact 16-cycle", feed(pd, c16, 16, 1000, &pushes), 16);
  sc_period_reset(pd, c16[0]);
  tu_int("exact 17-cycle is high (0)", feed(pd, c16, 17, 1000, &pushes), 0);
  /* Quasi-periodic: rotation by the golden mean never repeats. */
  double qp[2000];
  const double theta = (sqrt(5.0) - 1) / 2;
  const double two_pi = 8 * atan(1.0);
  for (int i = 0; i < 2000; i++) qp[i] = cos(two_pi * theta * i);
  sc_period_reset(pd, qp[0]);
  tu_int("golden-mean rotation: high", feed(pd, qp, 2000, 1999, &pushes), 0);
  /* A 2-cycle whose points differ by less than the tolerance counts as
   * period 1; the tolerance is rtol times the extent (1e-6 * 1 here). */
  sc_period_reset(pd, 0.0);
  sc_period_push(pd, 1.0); /* extent 1 from the transient */
  const double tiny2[2] = {0.5, 0.5 + 5e-7};
  tu_int("2-cycle below rtol*extent reads as period 1",
         feed(pd, tiny2, 2, 1000, &pushes), 1);
  sc_period_reset(pd, 0.0);
  sc_period_push(pd, 1.0);
  const double small2[2] = {0.5, 0.5 + 5e-6};
  tu_int("2-cycle above rtol*extent reads as period 2",
         feed(pd, small2, 2, 1000, &pushes), 2);
  tu_close("tolerance = rtol * extent + floor", sc_period_tol(pd),
           1e-6 * 1.0 + SC_PERIOD_FLOOR_ULPS * DBL_EPSILON * 1.0, 1e-22);
  tu_close("extent = max - min over the orbit", sc_period_extent(pd), 1.0,
           0);
  sc_period_free(pd);

  /* A 2-cycle within the tolerance whose lag-1 differences drop by
   * exactly 2 tol from one cycle to the next (the most a confirmed window
   * allows) is accepted; as computed they drop by an ulp more, which a
   * test on how much they change would have taken for a transient
   * (period.c, accept()).  rtol = 2^-10 and the extent 2 make tol
   * 2^-9 + 8 eps; u + tol and v - tol are exact. */
  const double u = -0x1.0059cb7a00b39p-1, v = 0x1.00e9eda601d3ep-1;
  const double tl = 0x1.0000000001p-9;
  const double drop[8] = {-1, 1, v, u, v, u + tl, v - tl, u + tl};
  tu_true(drop[5] - u == tl && v - drop[6] == tl &&
              (drop[6] - drop[5]) < (drop[4] - drop[3]) - 2 * tl,
          "lag-1 differences drop by 2 tol, by more as computed");
  tu_int("alloc max 2 confirm 2",
         sc_period_alloc(2, 2, 0x1p-10, &pd, &msg), SC_OK);
  sc_period_reset(pd, drop[0]);
  int got = 0;
  for (int k = 1; k < 8 && !got; k++) {
    got = sc_period_push(pd, drop[k]);
    pushes = k;
  }
  tu_close("tolerance 2^-9 + 8 eps", sc_period_tol(pd), tl, 0);
  tu_int("2 tol drop: period 2", got, 2);
  tu_int("2 tol drop: accepted with x7 (lag 2 passes from x4)", pushes, 7);
  sc_period_free(pd);

  /* Error paths. */
  tu_int("max_period 0 refused", sc_period_alloc(0, 4, 1e-6, &pd, &msg),
         SC_EINVAL);
  tu_true(pd == NULL && strstr(msg.text, "max-period") != NULL,
          "message names max-period: %s", msg.text);
  tu_int("max_period 257 refused",
         sc_period_alloc(SC_PERIOD_MAX + 1, 4, 1e-6, &pd, &msg), SC_EINVAL);
  tu_int("confirm 0 refused", sc_period_alloc(16, 0, 1e-6, &pd, &msg),
         SC_EINVAL);
  tu_int("confirm 65 refused",
         sc_period_alloc(16, SC_PERIOD_MAX_CONFIRM + 1, 1e-6, &pd, &msg),
         SC_EINVAL);
  sc_period_free(NULL); /* a no-op, as free() */
  tu_int("rtol NaN refused", sc_period_alloc(16, 4, NAN, &pd, &msg),
         SC_EINVAL);
  tu_int("rtol 0.5 refused", sc_period_alloc(16, 4, 0.5, &pd, &msg),
         SC_EINVAL);
}

/* The logistic map from x0 = 0.2385 with a budget of 20000 iterates. */
static void logistic(void) {
  sc_msg msg;
  sc_map *m = NULL;
  sc_period *pd = NULL;
  tu_int("logistic alloc", sc_map_alloc("logistic", NULL, &m, &msg), SC_OK);
  double rtol = sc_map_accuracy(m)->period_rtol;
  tu_int("detector alloc", sc_period_alloc(16, 4, rtol, &pd, &msg), SC_OK);
  struct {
    double r;
    int period;
    const char *why;
  } cases[] = {
      {2.8, 1, "fixed point 1 - 1/r, multiplier -0.8"},
      {2.95, 1, "fixed point, multiplier -0.95: lag-2 decays ~20x faster, "
                "the near-flip rule must not report 2"},
      {3.2, 2, "after the flip at r = 3"},
      {3.44, 2, "just below the flip at 1 + sqrt 6 = 3.449: multiplier "
                "-0.95, not 4"},
      {3.5, 4, "after 1 + sqrt 6"},
      {3.56, 8, "period 8 window of the cascade [3.5441, 3.5644]"},
      {3.835, 3, "period-3 window after the fold at 1 + 2 sqrt 2"},
      {3.7, SC_PERIOD_HIGH, "chaos"},
      {4.0, SC_PERIOD_HIGH, "fully developed chaos"},
  };
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    sc_map_set_param(m, 0, cases[c].r, &msg);
    sc_period_result res;
    int st = sc_period_find(pd, m, 0.2385, 20000, &res, &msg);
    char what[160];
    snprintf(what, sizeof what, "r = %g: period (%s)", cases[c].r,
             cases[c].why);
    if (!tu_int(what, st ? st : res.period, cases[c].period)) continue;
    if (res.period == SC_PERIOD_HIGH) {
      tu_int("high uses the whole budget", res.iterations, 20000);
      continue;
    }
    /* Early stop: the periodic ones settle well before the budget. */
    tu_true(res.iterations < 5000, "r = %g: early stop after %ld iterates",
            cases[c].r, res.iterations);
    /* The final state is on the cycle: f^p(d) returns to d within the
     * tolerance (times a few for the contraction still under way). */
    sc_map_value v;
    sc_map_iterate(m, res.d, res.period, 0, &v, &msg);
    tu_close("f^p(d) = d", v.f, res.d, 4 * res.tol);
  }
  /* Exact fixed point at r = 2.8 and the 2-cycle at r = 3.2 (closed
   * forms). */
  sc_period_result res;
  sc_map_set_param(m, 0, 2.8, &msg);
  sc_period_find(pd, m, 0.2385, 20000, &res, &msg);
  tu_close("r = 2.8: d = 1 - 1/r", res.d, 1 - 1 / 2.8, 4 * res.tol);
  sc_map_set_param(m, 0, 3.2, &msg);
  sc_period_find(pd, m, 0.2385, 20000, &res, &msg);
  double s = sqrt((3.2 - 3) * (3.2 + 1));
  double a = (3.2 + 1 - s) / (2 * 3.2), b = (3.2 + 1 + s) / (2 * 3.2);
  tu_close("r = 3.2: d on the 2-cycle", fmin(fabs(res.d - a), fabs(res.d - b)),
           0, 4 * res.tol);
  /* Near the flip at r = 3 the fixed point's multiplier is 2 - r = -0.99:
   * 600 iterates leave the transient still converging ("not settled",
   * not chaos); 20000 settle it to period 1.  Chaos at r = 3.7 stays high
   * whatever the budget. */
  sc_map_set_param(m, 0, 2.99, &msg);
  sc_period_find(pd, m, 0.2385, 600, &res, &msg);
  tu_int("r = 2.99 with 600 iterates: not settled", res.period,
         SC_PERIOD_UNSETTLED);
  tu_int("settling towards period 1", sc_period_settling(pd), 1);
  sc_period_find(pd, m, 0.2385, 20000, &res, &msg);
  tu_int("r = 2.99 with 20000 iterates: period 1", res.period, 1);
  sc_map_set_param(m, 0, 3.7, &msg);
  for (long budget = 100; budget <= 100000; budget *= 10) {
    sc_period_find(pd, m, 0.2385, budget, &res, &msg);
    tu_int("r = 3.7 (chaos): high, not 'not settled'", res.period,
           SC_PERIOD_HIGH);
  }
  /* A budget too short to settle is high. */
  sc_map_set_param(m, 0, 3.56, &msg);
  sc_period_find(pd, m, 0.2385, 30, &res, &msg);
  tu_int("r = 3.56 with 30 iterates: high", res.period, SC_PERIOD_HIGH);
  tu_int("max_iter 0 refused", sc_period_find(pd, m, 0.2385, 0, &res, &msg),
         SC_EINVAL);
  tu_int("d0 NaN refused", sc_period_find(pd, m, NAN, 10, &res, &msg),
         SC_EINVAL);
  sc_period_free(pd);
  sc_map_free(m);
}

/* The cubic map diverges from large x: f overflows to infinity, the map
 * reports SC_ENONFINITE, and the point is undefined. */
static void divergent(void) {
  sc_msg msg;
  sc_map *m = NULL;
  sc_period *pd = NULL;
  sc_map_alloc("cubic", NULL, &m, &msg);
  sc_period_alloc(16, 4, 1e-6, &pd, &msg);
  sc_period_result res;
  tu_int("cubic from 3: status", sc_period_find(pd, m, 3.0, 1000, &res, &msg),
         SC_OK);
  tu_int("cubic from 3: undefined", res.period, SC_PERIOD_UNDEFINED);
  tu_int("cubic from 3: map status", res.map_status, SC_ENONFINITE);
  tu_true(res.iterations < 20 && isfinite(res.d),
          "stops at the failing iterate (%ld) with the last finite state",
          res.iterations);
  sc_period_free(pd);
  sc_map_free(m);
}

/* bk2 (docs/model.md, reference behaviours): alpha = 3, beta = 1, phi = 1.25,
 * v = 0.025 has a period-2 orbit with the driver moving and frozen. */
static void bk2(void) {
  sc_msg msg;
  sc_map *m = NULL;
  sc_period *pd = NULL;
  sc_map_alloc("bk2", NULL, &m, &msg);
  sc_map_set_param_by_name(m, "alpha", 3, &msg);
  sc_map_set_param_by_name(m, "beta", 1, &msg);
  sc_map_set_param_by_name(m, "phi", 1.25, &msg);
  sc_map_set_param_by_name(m, "v", 0.025, &msg);
  sc_period_alloc(16, 4, sc_map_accuracy(m)->period_rtol, &pd, &msg);
  const char *drivers[2] = {"moving", "frozen"};
  for (int k = 0; k < 2; k++) {
    sc_map_set_option(m, "driver", drivers[k], &msg);
    sc_period_result res;
    int st = sc_period_find(pd, m, 0.02, 2000, &res, &msg);
    char what[96];
    snprintf(what, sizeof what, "bk2 alpha 3 beta 1 driver %s: status",
             drivers[k]);
    tu_int(what, st, SC_OK);
    if (st) {
      printf("  message: %s\n", msg.text);
      continue;
    }
    snprintf(what, sizeof what, "bk2 alpha 3 beta 1 driver %s: period",
             drivers[k]);
    tu_int(what, res.period, 2);
    printf("  iterations %ld, d %.17g, tol %.3g\n", res.iterations, res.d,
           res.tol);
  }
  sc_period_free(pd);
  sc_map_free(m);
}

/* Reference detector: the rule of chart.h written the plain way, a run
 * counter and a block maximum per lag updated on every iterate and the
 * whole orbit kept.  The detector must give the same period at the same
 * iterate, the same tolerance and the same settling answer. */
#define REF_LEN 1200
typedef struct {
  int maxp, confirm;
  double rtol, lo, hi, amax, tol;
  long n;
  int found;
  long deferred; /* pushes where the smallest confirmed p was deferred */
  double x[REF_LEN];
  long run[SC_PERIOD_MAX + 1], blk[SC_PERIOD_MAX + 1];
  long pos[SC_PERIOD_MAX + 1], streak[SC_PERIOD_MAX + 1];
  double bmax[SC_PERIOD_MAX + 1], prev[SC_PERIOD_MAX + 1];
} ref_period;

static void ref_reset(ref_period *r, double x0) {
  r->x[0] = x0;
  r->n = 1;
  r->lo = r->hi = x0;
  r->amax = fabs(x0);
  r->tol = SC_PERIOD_FLOOR_ULPS * DBL_EPSILON * r->amax;
  r->found = 0;
  r->deferred = 0;
  for (int p = 1; p <= r->maxp; p++) {
    r->run[p] = r->pos[p] = r->streak[p] = 0;
    r->bmax[p] = r->prev[p] = 0;
    r->blk[p] = p * ((8 + p - 1) / p);
  }
}

static double ref_lag_max(const ref_period *r, int q, long j0, long len) {
  double m = 0;
  for (long j = j0; j < j0 + len; j++)
    m = fmax(m, fabs(r->x[j] - r->x[j - q]));
  return m;
}

static int ref_accept(const ref_period *r, int p) {
  const int c = r->confirm;
  const long first = r->n - 1 - (long)(c + 1) * p + 1;
  for (int q = 1; q < p && c >= 3; q++) {
    if (p % q) continue;
    double l1 = ref_lag_max(r, q, first + (long)(c - 2) * p, p);
    double l2 = ref_lag_max(r, q, first + (long)(c - 1) * p, p);
    double l3 = ref_lag_max(r, q, first + (long)c * p, p);
    double d1 = l1 - l2, d2 = l2 - l3;
    if (d1 > 0 && d2 > 0 && d2 < d1 && l3 - d2 * d2 / (d1 - d2) <= r->tol)
      return 0;
  }
  return 1;
}

static int ref_push(ref_period *r, double x) {
  if (r->found) return r->found;
  long k = r->n++;
  r->x[k] = x;
  r->lo = fmin(r->lo, x);
  r->hi = fmax(r->hi, x);
  r->amax = fmax(r->amax, fabs(x));
  r->tol = r->rtol * (r->hi - r->lo) +
           SC_PERIOD_FLOOR_ULPS * DBL_EPSILON * r->amax;
  for (int p = 1; p <= r->maxp && p <= k; p++) {
    double dx = fabs(x - r->x[k - p]);
    r->run[p] = dx <= r->tol ? r->run[p] + 1 : 0;
    if (dx > r->bmax[p]) r->bmax[p] = dx;
    if (++r->pos[p] == r->blk[p]) {
      r->streak[p] = r->bmax[p] < r->prev[p] ? r->streak[p] + 1 : 0;
      r->prev[p] = r->bmax[p];
      r->bmax[p] = 0;
      r->pos[p] = 0;
    }
  }
  for (int p = 1; p <= r->maxp && p <= k; p++) {
    if (r->run[p] < (long)r->confirm * p) continue;
    if (ref_accept(r, p)) r->found = p;
    else r->deferred++;
    break;
  }
  return r->found;
}

static int ref_settling(const ref_period *r) {
  for (int p = 1; p <= r->maxp; p++)
    if (r->streak[p] >= 4 && 2 * r->streak[p] * r->blk[p] >= r->n - 1 &&
        r->prev[p] > r->tol)
      return p;
  return 0;
}

static uint64_t rng_state = 0x2385u;
static double uniform(void) { /* xorshift64*, in [0, 1) */
  rng_state ^= rng_state >> 12;
  rng_state ^= rng_state << 25;
  rng_state ^= rng_state >> 27;
  return (double)((rng_state * 2685821657736338717u) >> 11) * 0x1p-53;
}
static int below(int n) { return (int)(uniform() * n); }

/* One test orbit of len iterates, of kind 0..5: random; a cycle of period
 * q with noise near the tolerance after a transient; a cycle of period q
 * approached geometrically, alternately from either side (a period-2q
 * transient: the near-flip test); the same with the extent jumping up
 * partway (the tolerance grows: differences must keep the verdict of
 * their own iterate); values from {0, 1, 2} in segments of random
 * periods; the period-2q transient again with one iterate kicked in the
 * second half, so that a deferred lag fails and the lags that waited
 * behind it are looked at (the branch "only the window matters" of
 * confirmed() in period.c, which kinds 0..4 never reach). */
static void orbit(int kind, int maxp, double rtol, double *x, int len) {
  double cyc[300];
  int q = 1 + below(maxp + 3 < 300 ? maxp + 3 : 300);
  for (int i = 0; i < q; i++) cyc[i] = 2 * uniform() - 1;
  const double noise[4] = {0, 0.3, 1, 3};
  const double lambda[5] = {0.3, 0.8, 0.95, 0.99, 0.999};
  double eps = noise[below(4)] * rtol, lam = lambda[below(5)];
  int t0 = below(len / 2), sign = below(2);
  double amp = uniform();
  for (int k = 0; k < len; k++) {
    switch (kind) {
    case 0:
      x[k] = 2 * uniform() - 1;
      break;
    case 1:
      x[k] = k < t0 ? 2 * uniform() - 1
                    : cyc[k % q] + eps * (2 * uniform() - 1);
      break;
    case 2:
    case 3: {
      double s = sign && (k / q) % 2 ? -1 : 1;
      x[k] = cyc[k % q] + s * amp * pow(lam, k) +
             eps * (2 * uniform() - 1);
      if (kind == 3 && k == t0) x[k] = 50 * (1 + uniform());
      break;
    }
    case 4:
      if (k == 0 || below(60) == 0) q = 1 + below(maxp + 1);
      x[k] = k >= q && below(8) ? x[k - q] : (double)below(3);
      break;
    default: /* kind 2, always alternating, without noise */
      x[k] = cyc[k % q] + ((k / q) % 2 ? -amp : amp) * pow(lam, k);
      break;
    }
  }
  if (kind == 5) { /* one iterate in the second half kicked by 1 to 3
                      tolerances */
    int t1 = len / 2 - 1 + t0;
    double lo = x[0], hi = x[0];
    for (int k = 1; k < t1; k++) {
      lo = fmin(lo, x[k]);
      hi = fmax(hi, x[k]);
    }
    x[t1] += (1 + 2 * uniform()) * rtol * (hi - lo) * (sign ? 1 : -1);
  }
}

static void against_reference(void) {
  const int maxps[] = {1, 2, 3, 5, 8, 16, 17, 40, 64, 65, 130, 256};
  const int confirms[] = {1, 2, 3, 4, 5, 8};
  const double rtols[] = {1e-6, 1e-3};
  static ref_period ref;
  static double x[REF_LEN];
  long orbits = 0, pushes = 0, push_diff = 0, tol_diff = 0, settle_diff = 0;
  long mid = 0, mid_diff = 0;
  long found = 0, high = 0, unsettled = 0, deferred = 0;
  sc_msg msg;
  for (size_t a = 0; a < sizeof maxps / sizeof *maxps; a++)
    for (size_t b = 0; b < sizeof confirms / sizeof *confirms; b++)
      for (size_t c = 0; c < 2; c++) {
        sc_period *pd = NULL;
        if (sc_period_alloc(maxps[a], confirms[b], rtols[c], &pd, &msg)) {
          tu_true(0, "alloc: %s", msg.text);
          continue;
        }
        ref.maxp = maxps[a];
        ref.confirm = confirms[b];
        ref.rtol = rtols[c];
        for (int o = 0; o < 48; o++, orbits++) {
          int len = 50 + below(REF_LEN - 50);
          orbit(o % 6, maxps[a], rtols[c], x, len);
          sc_period_reset(pd, x[0]);
          ref_reset(&ref, x[0]);
          int p = 0, pr = 0;
          for (int k = 1; k < len && !pr; k++, pushes++) {
            p = sc_period_push(pd, x[k]);
            pr = ref_push(&ref, x[k]);
            if (p != pr) push_diff++;
            if (sc_period_tol(pd) != ref.tol) tol_diff++;
            /* the settling answer mid-orbit too: the detector takes its
             * blocks in batches, the reference at every push */
            if (!pr && k % 13 == 0) {
              mid++;
              if (sc_period_settling(pd) != ref_settling(&ref)) mid_diff++;
            }
          }
          deferred += ref.deferred;
          if (p != pr) continue; /* counted */
          if (pr) {
            found++;
            continue;
          }
          int s = sc_period_settling(pd);
          if (s != ref_settling(&ref)) settle_diff++;
          if (s) unsettled++;
          else high++;
        }
        sc_period_free(pd);
      }
  tu_int("pushes with a different answer than the reference", push_diff, 0);
  tu_int("pushes with a different tolerance", tol_diff, 0);
  tu_int("orbits with a different settling answer", settle_diff, 0);
  tu_int("mid-orbit settling answers that differ", mid_diff, 0);
  tu_true(mid > 10000, "settling asked mid-orbit %ld times", mid);
  printf("  %ld orbits, %ld pushes: %ld periodic, %ld high, %ld not "
         "settled, %ld pushes with a confirmed period deferred\n",
         orbits, pushes, found, high, unsettled, deferred);
  tu_true(found > orbits / 5 && high > orbits / 10 && unsettled > 20 &&
              deferred > 1000,
          "the orbits cover every class");
}

/* A lag p that falls due while a smaller lag is confirmed but deferred
 * waits: sc_period_push() looks at no lag above the smallest confirmed
 * one.  Looked at again more than confirm p iterates after its last look,
 * p has only its window checked (the branch "only the window matters" of
 * confirmed() in period.c).  The random orbits above take that branch
 * (kind 5) but hardly ever confirm p there; these orbits do, on either
 * side of the window's first iterate.  x_j = (-1)^j 0.99^j converges to
 * the fixed point 0 with multiplier -0.99: lag 2 is confirmed long before
 * lag 1 and deferred (near flip), lag 4 fails until iterate j4 and then
 * waits behind lag 2.  Iterate k is kicked so that lag 2 fails there and
 * lag 4 does not, and lag 4 is looked at with x_k:
 * - k = j4 + confirm 4: the last failure lies just before the window, so
 *   period 4 is accepted with x_k;
 * - k = j4 + confirm 4 - 1: it is the window's oldest difference, so
 *   period 4 comes one iterate later;
 * - k = j4 + confirm 4 + 40: the window starts well after it. */
static void waiting_lag(void) {
  static ref_period ref;
  static double x[REF_LEN];
  const int confirms[] = {3, 4, 8};
  const int offsets[] = {0, -1, 40};
  const double rtol = 1e-3;
  sc_msg msg;
  for (size_t b = 0; b < sizeof confirms / sizeof *confirms; b++)
    for (size_t o = 0; o < sizeof offsets / sizeof *offsets; o++) {
      const int c = confirms[b], len = REF_LEN;
      for (int j = 0; j < len; j++) x[j] = (j % 2 ? -1 : 1) * pow(0.99, j);
      /* x0 and x1 set the extent; every later iterate lies inside it. */
      const double tol = rtol * (x[0] - x[1]) +
                         SC_PERIOD_FLOOR_ULPS * DBL_EPSILON * x[0];
      int j4 = 0;
      for (int j = 4; j < len; j++)
        if (!(fabs(x[j] - x[j - 4]) <= tol)) j4 = j;
      const int k = j4 + 4 * c + offsets[o];
      /* Outwards by tol + |x_k - x_{k-2}| + |x_{k-2} - x_{k-4}| / 2: lag 2
       * fails by half a lag-2 step, lag 4 passes by as much. */
      double d2 = fabs(x[k] - x[k - 2]), d4 = fabs(x[k - 2] - x[k - 4]);
      x[k] += (k % 2 ? -1 : 1) * (tol + d2 + d4 / 2);
      sc_period *pd = NULL;
      if (sc_period_alloc(8, c, rtol, &pd, &msg)) {
        tu_true(0, "alloc: %s", msg.text);
        continue;
      }
      ref.maxp = 8;
      ref.confirm = c;
      ref.rtol = rtol;
      sc_period_reset(pd, x[0]);
      ref_reset(&ref, x[0]);
      int p = 0, pr = 0, at = 0, at_ref = 0;
      long diff = 0;
      for (int i = 1; i < len && !(p && pr); i++) {
        p = sc_period_push(pd, x[i]);
        pr = ref_push(&ref, x[i]);
        diff += p != pr || sc_period_tol(pd) != ref.tol;
        if (p && !at) at = i;
        if (pr && !at_ref) at_ref = i;
      }
      char what[96];
      snprintf(what, sizeof what,
               "waiting lag, confirm %d, kick at j4 + %d: period", c,
               4 * c + offsets[o]);
      tu_int(what, p, 4);
      snprintf(what, sizeof what,
               "waiting lag, confirm %d, kick at j4 + %d: accepted at", c,
               4 * c + offsets[o]);
      tu_int(what, at, offsets[o] == -1 ? k + 1 : k);
      tu_true(diff == 0 && pr == p && at_ref == at,
              "waiting lag, confirm %d: the reference agrees on every "
              "push (%ld differ)",
              c, diff);
      /* Lag 4 waited behind lag 2 for longer than its window. */
      tu_true(ref.deferred > 4 * c, "lag 2 deferred on %ld pushes",
              ref.deferred);
      sc_period_free(pd);
    }
}

/* The n-dimensional detector: with n = 1 the same answers at the same
 * iterates as sc_period on the reference's test orbits (one rule, two
 * bookkeepings); with n = 2 the max norm: a second component that is
 * the first times 3 gives the answers of the first alone (differences
 * and tolerance 3 times as large), with fewer than 3 confirmation cycles
 * (with more, n > 1 adds its wait near a divisor's orbit); and a second
 * component of period 3 beside a first of period 2 gives period 6. */
static void periodn_against_period(void) {
  const int maxps[] = {1, 3, 16, 40};
  const int confirms[] = {1, 3, 4};
  static double x[REF_LEN], xy[2 * REF_LEN];
  long diff = 0, settle = 0, orbits = 0, found = 0, tdiff = 0;
  sc_msg msg;
  for (size_t a = 0; a < 4; a++)
    for (size_t b = 0; b < 3; b++) {
      sc_period *pd = NULL;
      sc_periodn *p1 = NULL, *p2 = NULL;
      sc_period_alloc(maxps[a], confirms[b], 1e-6, &pd, &msg);
      sc_periodn_alloc(1, maxps[a], confirms[b], 1e-6, &p1, &msg);
      sc_periodn_alloc(2, maxps[a], confirms[b], 1e-6, &p2, &msg);
      for (int o = 0; o < 60; o++, orbits++) {
        int len = 50 + below(REF_LEN - 50);
        orbit(o % 6, maxps[a], 1e-6, x, len);
        for (int k = 0; k < len; k++) xy[2 * k] = x[k], xy[2 * k + 1] = 3 * x[k];
        sc_period_reset(pd, x[0]);
        sc_periodn_reset(p1, x);
        sc_periodn_reset(p2, xy);
        int p = 0, q = 0, r = 0;
        for (int k = 1; k < len && !p; k++) {
          p = sc_period_push(pd, x[k]);
          q = sc_periodn_push(p1, x + k);
          r = sc_periodn_push(p2, xy + 2 * k);
          /* n = 2 waits also near a divisor's orbit (periodn.c,
           * NEAR_TOLS), a test that needs confirm >= 3 */
          diff += p != q || (confirms[b] < 3 && p != r);
          tdiff += sc_period_tol(pd) != sc_periodn_tol(p1);
        }
        found += p > 0;
        if (!p) settle += sc_period_settling(pd) != sc_periodn_settling(p1);
      }
      sc_period_free(pd);
      sc_periodn_free(p1);
      sc_periodn_free(p2);
    }
  tu_int("periodn: pushes that differ from sc_period (n = 1, 2)", diff, 0);
  tu_int("periodn: tolerances that differ (n = 1)", tdiff, 0);
  tu_int("periodn: settling answers that differ", settle, 0);
  tu_true(found > orbits / 4 && found < orbits, "periods found on %ld of %ld",
          found, orbits);
  sc_periodn *p2 = NULL;
  sc_periodn_alloc(2, 16, 4, 1e-9, &p2, &msg);
  double s[2] = {0.25, -1.5};
  sc_periodn_reset(p2, s);
  int got = 0, k;
  for (k = 1; k < 200 && !got; k++) {
    s[0] = k % 2 ? 0.75 : 0.25;
    s[1] = (double)(k % 3) - 1.5;
    got = sc_periodn_push(p2, s);
  }
  tu_int("periods 2 and 3 in two components: period 6", got, 6);
  /* confirmed when the first cycle and 4 more are there: the 30 states
   * x_0 .. x_29 */
  tu_int("confirmed at iterate 29", k - 1, 29);
  sc_periodn_free(p2);
}

/* The invariant-circle test on point sets with known answers. */
static void circle_test(void) {
  enum { M = 512 };
  static double pts[2 * M], work[3 * M];
  double r;
  const double pi = 3.14159265358979323846, rho = (sqrt(5) - 1) / 2;
  /* a rotation by the golden mean on an ellipse, off-centre: a circle */
  for (int k = 0; k < M; k++) {
    double t = 2 * pi * rho * k;
    pts[2 * k] = 2.385 + 1.5 * cos(t);
    pts[2 * k + 1] = -0.7 + 0.4 * sin(t) + 0.1 * cos(t);
  }
  tu_int("rotation on an ellipse: a circle",
         sc_orbit_on_circle(pts, M, 2, 1e-9, work, &r), 1);
  tu_true(r < 1.001, "its length ratio %.6f is about 1", r);
  /* the same turned backwards (an orientation-reversing circle map) */
  for (int k = 0; k < M; k++) pts[2 * k + 1] = -pts[2 * k + 1];
  tu_int("reflected: a circle too", sc_orbit_on_circle(pts, M, 2, 1e-9, work, &r),
         1);
  /* a period-7 orbit on it: periodic, not a circle */
  for (int k = 0; k < M; k++) {
    double t = 2 * pi * 3 * k / 7.0;
    pts[2 * k] = cos(t), pts[2 * k + 1] = sin(t);
  }
  tu_int("period 7: not a circle", sc_orbit_on_circle(pts, M, 2, 1e-9, work, &r),
         0);
  /* random points in a disk: scattered */
  for (int k = 0; k < M; k++) {
    double t = 2 * pi * uniform(), q = sqrt(uniform());
    pts[2 * k] = q * cos(t), pts[2 * k + 1] = q * sin(t);
  }
  tu_int("random points in a disk: not a circle",
         sc_orbit_on_circle(pts, M, 2, 1e-9, work, &r), 0);
  tu_true(r > 1.8, "their length ratio %.3f is about 2", r);
  /* the golden rotation on the circle but the points taken in a random
   * order: on the curve (length test) but out of order (order test) */
  for (int k = 0; k < M; k++) {
    double t = 2 * pi * uniform();
    pts[2 * k] = cos(t), pts[2 * k + 1] = sin(t);
  }
  tu_int("points on a circle visited out of order: not a circle",
         sc_orbit_on_circle(pts, M, 2, 1e-9, work, &r), 0);
  tu_true(r < 1.05, "while their length ratio %.4f is about 1", r);
  /* henon at a = 1.36, b = 0.26: chaotic (Lyapunov exponent about 0.06),
   * its attractor thin and closed like a curve (length ratio near 1) */
  double x = 0, y = 0;
  for (int k = 0; k < 1000 + M; k++) {
    double xn = 1 - 1.36 * x * x + y;
    y = 0.26 * x;
    x = xn;
    if (k >= 1000) pts[2 * (k - 1000)] = x, pts[2 * (k - 1000) + 1] = y;
  }
  tu_int("henon a = 1.36, b = 0.26: not a circle",
         sc_orbit_on_circle(pts, M, 2, 1e-9, work, &r), 0);
  tu_true(r < SC_CIRCLE_RATIO, "though its length ratio %.4f passes", r);
}

int main(void) {
  periodn_against_period();
  circle_test();
  exact_sequences();
  logistic();
  divergent();
  bk2();
  against_reference();
  waiting_lag();
  return tu_finish();
}
