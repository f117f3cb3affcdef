/* Period detection on an orbit of a one-dimensional map: the rule is
 * stated in include/slipcont/chart.h and docs/charts.md. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "slipcont/chart.h"

/* Iterates in one block of the settling test: at least this many, a
 * whole number of cycles. */
#define SETTLE_BLOCK 8
/* Blocks compared, and how far their decay ratios may differ (relative
 * to the largest): a transient converging to a period-p orbit shrinks its
 * lag-p differences by the same factor every block (the multiplier to a
 * power), a chaotic orbit does not do so block after block. */
#define SETTLE_BLOCKS 4

struct sc_period {
  int maxp;      /* largest period detected */
  int confirm;   /* confirmation cycles */
  double rtol;   /* tolerance relative to the extent */
  long cap;      /* ring capacity: (confirm + 1) maxp + 1 iterates */
  double *ring;  /* the last cap iterates; x_k at ring[k % cap] */
  long *run;     /* run[p]: consecutive latest k with |x_k - x_{k-p}| <= tol */
  long n;        /* iterates pushed, x0 included */
  double lo, hi; /* extent of the orbit so far */
  double amax;   /* largest |x| so far */
  double tol;
  int found;     /* accepted period, 0 while none */
  /* Settling (sc_period_settling()): per lag p, the largest lag-p
   * difference of the current block of blk[p] iterates and of the one
   * before, and how many blocks in a row the maximum decreased. */
  long *blk, *blk_pos, *streak;
  double *blk_max, *prev_max;
};

int sc_period_alloc(int max_period, int confirm, double rtol,
                    sc_period **out, sc_msg *msg) {
  *out = NULL;
  if (max_period < 1 || max_period > SC_PERIOD_MAX)
    return sc_fail(msg, SC_EINVAL,
                   "sc_period_alloc: max-period = %d (valid: 1..%d)",
                   max_period, SC_PERIOD_MAX);
  if (confirm < 1 || confirm > SC_PERIOD_MAX_CONFIRM)
    return sc_fail(msg, SC_EINVAL,
                   "sc_period_alloc: confirm = %d (valid: 1..%d)", confirm,
                   SC_PERIOD_MAX_CONFIRM);
  if (!(rtol >= DBL_EPSILON && rtol <= 0.1))
    return sc_fail(msg, SC_EINVAL,
                   "sc_period_alloc: period-rtol = %g (valid: [%g, 0.1])",
                   rtol, DBL_EPSILON);
  sc_period *pd = calloc(1, sizeof *pd);
  if (!pd) goto fail;
  pd->maxp = max_period;
  pd->confirm = confirm;
  pd->rtol = rtol;
  pd->cap = (long)(confirm + 1) * max_period + 1;
  pd->ring = malloc((size_t)pd->cap * sizeof *pd->ring);
  pd->run = calloc((size_t)max_period + 1, sizeof *pd->run);
  pd->blk = calloc((size_t)max_period + 1, sizeof *pd->blk);
  pd->blk_pos = calloc((size_t)max_period + 1, sizeof *pd->blk_pos);
  pd->streak = calloc((size_t)max_period + 1, sizeof *pd->streak);
  pd->blk_max = calloc((size_t)max_period + 1, sizeof *pd->blk_max);
  pd->prev_max = calloc((size_t)max_period + 1, sizeof *pd->prev_max);
  if (!pd->ring || !pd->run || !pd->blk || !pd->blk_pos || !pd->streak ||
      !pd->blk_max || !pd->prev_max)
    goto fail;
  for (int p = 1; p <= max_period; p++)
    pd->blk[p] = (long)p * ((SETTLE_BLOCK + p - 1) / p);
  sc_period_reset(pd, 0);
  *out = pd;
  return SC_OK;
fail:
  sc_period_free(pd);
  return sc_fail(msg, SC_ENOMEM, "sc_period_alloc: out of memory");
}

void sc_period_free(sc_period *pd) {
  if (!pd) return;
  free(pd->ring);
  free(pd->run);
  free(pd->blk);
  free(pd->blk_pos);
  free(pd->streak);
  free(pd->blk_max);
  free(pd->prev_max);
  free(pd);
}

void sc_period_reset(sc_period *pd, double x0) {
  pd->ring[0] = x0;
  pd->n = 1;
  pd->lo = pd->hi = x0;
  pd->amax = fabs(x0);
  for (int p = 0; p <= pd->maxp; p++) {
    pd->run[p] = 0;
    pd->blk_pos[p] = pd->streak[p] = 0;
    pd->blk_max[p] = pd->prev_max[p] = 0;
  }
  pd->tol = SC_PERIOD_FLOOR_ULPS * DBL_EPSILON * pd->amax;
  pd->found = 0;
}

double sc_period_tol(const sc_period *pd) { return pd->tol; }
double sc_period_extent(const sc_period *pd) { return pd->hi - pd->lo; }

/* Iterate k (0 <= n - cap < k < n). */
static double at(const sc_period *pd, long k) { return pd->ring[k % pd->cap]; }

/* Largest |x_j - x_{j-q}| for j in [j0, j0 + len). */
static double lag_max(const sc_period *pd, int q, long j0, long len) {
  double m = 0;
  for (long j = j0; j < j0 + len; j++)
    m = fmax(m, fabs(at(pd, j) - at(pd, j - q)));
  return m;
}

/* Period p is confirmed: accept it unless, for a proper divisor q of p,
 * the orbit is still converging to a period-q orbit.  Near a flip of a
 * period-q orbit (multiplier lambda = -1 + eps) the lag-2q differences of
 * the transient are ~eps/2 times the lag-q ones, so 2q is confirmed long
 * before q although the attractor has period q.
 *
 * With cycles t of the window (j in [first + t p, first + (t+1) p)) and
 * L_t the largest lag-q difference in cycle t, take the last three
 * cycles L1, L2, L3.  On a genuine period-p orbit L changes by at most
 * 2 (lag-p differences) per cycle, so |L1 - L3| <= 4 tol.  On an orbit
 * converging to period q, L decays geometrically to 0; its limit
 * L3 - (L2 - L3)^2 / ((L1 - L2) - (L2 - L3)) (Aitken) is then within
 * tol of 0, even while |L1 - L3| is also within 4 tol (the triangle
 * bound is tight in that case, so only the extrapolation tells the two
 * apart).  Defer p in that case, and while L still changes by more than
 * a genuine orbit allows.  With fewer than 3 confirmation cycles only the
 * last test is made (first against last cycle, 2 tol). */
static int accept(const sc_period *pd, int p) {
  const long last = pd->n - 1; /* newest iterate */
  const long first = last - (long)(pd->confirm + 1) * p + 1;
  const int c = pd->confirm;
  const double tol = pd->tol;
  for (int q = 1; q < p; q++) {
    if (p % q) continue;
    if (c < 3) {
      double a = lag_max(pd, q, first + p, p);
      double b = lag_max(pd, q, first + (long)c * p, p);
      if (b < a - 2 * tol) return 0;
      continue;
    }
    double l1 = lag_max(pd, q, first + (long)(c - 2) * p, p);
    double l2 = lag_max(pd, q, first + (long)(c - 1) * p, p);
    double l3 = lag_max(pd, q, first + (long)c * p, p);
    double d1 = l1 - l2, d2 = l2 - l3;
    if (d1 > 0 && d2 > 0 && d2 < d1 && l3 - d2 * d2 / (d1 - d2) <= tol)
      return 0; /* geometric decay towards a period-q orbit */
    if (fabs(l1 - l3) > 4 * tol) return 0; /* not settled */
  }
  return 1;
}

int sc_period_push(sc_period *pd, double x) {
  if (pd->found) return pd->found;
  long k = pd->n;
  long slot = k % pd->cap;
  pd->ring[slot] = x;
  pd->n = k + 1;
  if (x < pd->lo) pd->lo = x;
  if (x > pd->hi) pd->hi = x;
  if (fabs(x) > pd->amax) pd->amax = fabs(x);
  /* The extent only grows, so a difference that passed stays passed. */
  pd->tol = pd->rtol * (pd->hi - pd->lo) +
            SC_PERIOD_FLOOR_ULPS * DBL_EPSILON * pd->amax;
  int maxp = k < pd->maxp ? (int)k : pd->maxp;
  for (int p = 1; p <= maxp; p++) {
    long back = slot >= p ? slot - p : slot - p + pd->cap;
    double dx = fabs(x - pd->ring[back]);
    pd->run[p] = dx <= pd->tol ? pd->run[p] + 1 : 0;
    if (dx > pd->blk_max[p]) pd->blk_max[p] = dx;
    if (++pd->blk_pos[p] == pd->blk[p]) { /* a block of lag p is complete */
      pd->streak[p] = pd->blk_max[p] < pd->prev_max[p] ? pd->streak[p] + 1 : 0;
      pd->prev_max[p] = pd->blk_max[p];
      pd->blk_max[p] = 0;
      pd->blk_pos[p] = 0;
    }
  }
  for (int p = 1; p <= maxp; p++) {
    if (pd->run[p] < (long)pd->confirm * p) continue;
    /* Smallest confirmed period: accept it, or wait for the divisor the
     * orbit is converging to (a larger p would be a multiple of it). */
    if (accept(pd, p)) pd->found = p;
    break;
  }
  return pd->found;
}

int sc_period_find(sc_period *pd, sc_map *m, double d0, long max_iter,
                   sc_period_result *res, sc_msg *msg) {
  if (max_iter < 1 || !isfinite(d0))
    return sc_fail(msg, SC_EINVAL,
                   "sc_period_find: max_iter = %ld, d0 = %g (valid: >= 1, "
                   "finite)",
                   max_iter, d0);
  sc_period_reset(pd, d0);
  sc_map_value v;
  double x = d0;
  res->map_status = SC_OK;
  for (long k = 1; k <= max_iter; k++) {
    int st = sc_map_eval(m, x, SC_EVAL_VALUE, &v, msg);
    if (st == SC_EUNDEF || st == SC_ENONFINITE) {
      res->period = SC_PERIOD_UNDEFINED;
      res->iterations = k;
      res->d = x;
      res->tol = pd->tol;
      res->map_status = st;
      return SC_OK;
    }
    if (st) return st;
    x = v.f;
    int p = sc_period_push(pd, x);
    if (p) {
      res->period = p;
      res->iterations = k;
      res->d = x;
      res->tol = pd->tol;
      return SC_OK;
    }
  }
  res->period = sc_period_settling(pd) ? SC_PERIOD_UNSETTLED : SC_PERIOD_HIGH;
  res->iterations = max_iter;
  res->d = x;
  res->tol = pd->tol;
  return SC_OK;
}

/* See chart.h.  A transient converging to a period-p orbit shrinks its
 * lag-p differences block after block for as long as it lasts; a chaotic
 * orbit can do so only for a short episode (near an unstable periodic
 * orbit).  So: the smallest p whose block maxima decreased in each of the
 * last blocks covering at least half of the orbit (and at least
 * SETTLE_BLOCKS blocks), still above the tolerance. */
int sc_period_settling(const sc_period *pd) {
  for (int p = 1; p <= pd->maxp; p++) {
    long covered = pd->streak[p] * pd->blk[p];
    if (pd->streak[p] >= SETTLE_BLOCKS && 2 * covered >= pd->n - 1 &&
        pd->prev_max[p] > pd->tol)
      return p;
  }
  return 0;
}
