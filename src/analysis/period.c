/* Period detection on an orbit of a one-dimensional map: the rule is
 * stated in include/slipcont/period.h and docs/charts.md.
 *
 * The confirmation test is evaluated lazily.  For each lag p the detector
 * keeps the latest iterate lf[p] known to fail (|x_j - x_{j-p}| > tol_j,
 * with tol_j the tolerance after x_j was pushed), so p cannot be confirmed
 * before iterate lf[p] + confirm p.  Lag p is looked at only from then
 * on: the differences since it was last looked at are checked newest
 * first, back to the window of the last confirm p iterates, and the
 * newest failure found moves lf[p] on.  A lag that keeps failing is
 * looked at about once every confirm p iterates instead of every iterate,
 * and the smallest confirmed lag comes out at the same iterate as with a
 * run counter per lag, since only the newest failure in the window
 * matters.  Tolerances are kept per iterate so that each difference is
 * compared with the tolerance of its own iterate, as a run counter does.
 * Due times are kept in a timing wheel of bit sets, one slot per ring
 * slot.
 *
 * The settling test's block maxima are taken in batches, not at every
 * push: once the iterates not yet looked at fill the ring but for its
 * longest lag (cap - maxp of them), each lag runs through them at once
 * (settle()), and sc_period_settling() runs through the rest on copies.
 * Maxima and block ends are those of a push-by-push update, so the
 * answer is the same (tests/test_period.c checks it against a reference
 * that updates at every push); per push it cost 10% of a chart's run in
 * a loop over the lags and a wheel of block ends. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "slipcont/period.h"
#include "period_impl.h"

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
  long cap;      /* ring capacity: (confirm + 1) maxp + SETTLE_BLOCK
                    iterates, more than any due time lies ahead; the
                    settling test's batches take up to cap - maxp */
  int nw;        /* 64-bit words in a set of lags 0..maxp */
  long slot;     /* ring slot of the newest iterate: n - 1 modulo cap */
  double *rev;   /* the last cap iterates, twice, in reverse: x_{k-i} at
                    rev[cap - 1 - slot + i] for 0 <= i < cap */
  double *tolk;  /* tol_k, the tolerance after x_k, laid out as rev */
  long n;        /* iterates pushed, x0 included */
  double lo, hi; /* extent of the orbit so far */
  double amax;   /* largest |x| so far */
  double tol;
  int found;     /* accepted period, 0 while none */
  /* Confirmation: per lag p the newest failing iterate known (or an
   * iterate before a window known to pass), the iterate up to which the
   * differences were looked at, and the due time lf + confirm p. */
  long *lf, *seen, *due_at;
  uint64_t *due;      /* lags with due_at <= the newest iterate */
  uint64_t *wheel_c;  /* cap sets: lags falling due at that slot */
  /* Settling (sc_period_settling()): per lag p, the largest lag-p
   * difference of the current block of blk[p] iterates and of the one
   * before, how many blocks in a row the maximum decreased, and the
   * iterate that ends the current block; all of them up to the iterate
   * sdone (the ones after it are taken in the next batch, settle()). */
  long *blk, *streak, *bnext;
  double *blk_max, *prev_max;
  long sdone;
};

int sc_period_check_args(const char *who, int max_period, int confirm,
                         double rtol, sc_msg *msg) {
  if (max_period < 1 || max_period > SC_PERIOD_MAX)
    return sc_fail(msg, SC_EINVAL, "%s: max-period = %d (valid: 1..%d)", who,
                   max_period, SC_PERIOD_MAX);
  if (confirm < 1 || confirm > SC_PERIOD_MAX_CONFIRM)
    return sc_fail(msg, SC_EINVAL, "%s: confirm = %d (valid: 1..%d)", who,
                   confirm, SC_PERIOD_MAX_CONFIRM);
  if (!(rtol >= DBL_EPSILON && rtol <= SC_PERIOD_MAX_RTOL))
    return sc_fail(msg, SC_EINVAL, "%s: period-rtol = %g (valid: [%g, %g])",
                   who, rtol, DBL_EPSILON, SC_PERIOD_MAX_RTOL);
  return SC_OK;
}

int sc_period_alloc(int max_period, int confirm, double rtol,
                    sc_period **out, sc_msg *msg) {
  *out = NULL;
  int st = sc_period_check_args("sc_period_alloc", max_period, confirm, rtol,
                                msg);
  if (st) return st;
  sc_period *pd = calloc(1, sizeof *pd);
  if (!pd) goto fail;
  pd->maxp = max_period;
  pd->confirm = confirm;
  pd->rtol = rtol;
  /* Due times lie at most confirm maxp iterates ahead; the ring keeps
   * SETTLE_BLOCK more, so that a batch of the settling test (cap - maxp
   * iterates, settle()) is never shorter than a block of lag 1. */
  pd->cap = (long)(confirm + 1) * max_period + SETTLE_BLOCK;
  pd->nw = max_period / 64 + 1;
  size_t np = (size_t)max_period + 1, cap = (size_t)pd->cap;
  size_t nw = (size_t)pd->nw;
  pd->rev = calloc(2 * cap, sizeof *pd->rev);
  pd->tolk = calloc(2 * cap, sizeof *pd->tolk);
  pd->lf = calloc(np, sizeof *pd->lf);
  pd->seen = calloc(np, sizeof *pd->seen);
  pd->due_at = calloc(np, sizeof *pd->due_at);
  pd->due = calloc(nw, sizeof *pd->due);
  pd->wheel_c = calloc(cap * nw, sizeof *pd->wheel_c);
  pd->blk = calloc(np, sizeof *pd->blk);
  pd->streak = calloc(np, sizeof *pd->streak);
  pd->bnext = calloc(np, sizeof *pd->bnext);
  pd->blk_max = calloc(np, sizeof *pd->blk_max);
  pd->prev_max = calloc(np, sizeof *pd->prev_max);
  if (!pd->rev || !pd->tolk || !pd->lf || !pd->seen || !pd->due_at ||
      !pd->due || !pd->wheel_c || !pd->blk || !pd->streak ||
      !pd->bnext || !pd->blk_max || !pd->prev_max)
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
  free(pd->rev);
  free(pd->tolk);
  free(pd->lf);
  free(pd->seen);
  free(pd->due_at);
  free(pd->due);
  free(pd->wheel_c);
  free(pd->blk);
  free(pd->streak);
  free(pd->bnext);
  free(pd->blk_max);
  free(pd->prev_max);
  free(pd);
}

static void set_bit(uint64_t *set, int p) {
  set[p >> 6] |= (uint64_t)1 << (p & 63);
}

static void clear_bit(uint64_t *set, int p) {
  set[p >> 6] &= ~((uint64_t)1 << (p & 63));
}

/* The wheel's set for iterate t, t - n < cap (t >= n - 1). */
static uint64_t *wheel_at(const sc_period *pd, uint64_t *wheel, long t) {
  return wheel + (size_t)(t % pd->cap) * (size_t)pd->nw;
}

void sc_period_reset(sc_period *pd, double x0) {
  /* Take every lag off the wheel: lag p is in at most one of its sets,
   * the one of its pending due time. */
  for (int p = 1; p <= pd->maxp; p++)
    clear_bit(wheel_at(pd, pd->wheel_c, pd->due_at[p]), p);
  for (int w = 0; w < pd->nw; w++) pd->due[w] = 0;
  pd->slot = 0;
  pd->rev[pd->cap - 1] = pd->rev[2 * pd->cap - 1] = x0;
  pd->n = 1;
  pd->lo = pd->hi = x0;
  pd->amax = fabs(x0);
  pd->tol = SC_PERIOD_FLOOR_ULPS * DBL_EPSILON * pd->amax;
  pd->tolk[pd->cap - 1] = pd->tolk[2 * pd->cap - 1] = pd->tol;
  pd->found = 0;
  /* Lag p's blocks end with the iterates p - 1 + m blk[p], m >= 1. */
  for (int p = 0; p <= pd->maxp; p++) {
    pd->streak[p] = 0;
    pd->blk_max[p] = pd->prev_max[p] = 0;
    pd->bnext[p] = p - 1 + pd->blk[p];
  }
  pd->sdone = 0;
  /* Lag p's first difference is the one of x_p: as if x_{p-1} failed. */
  for (int p = 1; p <= pd->maxp; p++) {
    pd->lf[p] = pd->seen[p] = p - 1;
    pd->due_at[p] = (long)(pd->confirm + 1) * p - 1;
    set_bit(wheel_at(pd, pd->wheel_c, pd->due_at[p]), p);
  }
}

double sc_period_tol(const sc_period *pd) { return pd->tol; }
double sc_period_extent(const sc_period *pd) { return pd->hi - pd->lo; }

/* Iterate k (0 <= n - cap < k < n). */
static double at(const sc_period *pd, long k) {
  return pd->rev[pd->cap - 1 - pd->slot + (pd->n - 1 - k)];
}

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
 * cycles L1, L2, L3.  On an orbit converging to period q, L decays
 * geometrically to 0; its limit L3 - (L2 - L3)^2 / ((L1 - L2) - (L2 - L3))
 * (Aitken) is then within tol of 0: defer p.  It takes 3 cycles after the
 * first one, so with fewer than 3 confirmation cycles p is accepted.
 *
 * How much L changes tells nothing more: since p is confirmed, every
 * lag-p difference of the window after its first cycle is within tol,
 * and a lag-q difference of one cycle differs from the one a cycle later
 * by at most two of them (triangle inequality), so L changes by at most
 * 2 tol a cycle.  A test "|L1 - L3| > 4 tol", or with 2 confirmation
 * cycles "L2 < L1 - 2 tol", can only be met by the rounding of the
 * computed differences: x = -1, 1, v, u, v, u + tol, v - tol, u + tol
 * with u near -1/2 and v near 1/2 makes L drop by exactly 2 tol and,
 * for some u and v, by one ulp more as computed (tests/test_period.c).
 * Such tests deferred a period on the last bit rather than on the orbit,
 * and no orbit of the test suite met them otherwise. */
static int accept(const sc_period *pd, int p) {
  const int c = pd->confirm;
  if (c < 3) return 1;
  const long last = pd->n - 1; /* newest iterate */
  const long first = last - (long)(c + 1) * p + 1;
  for (int q = 1; q < p; q++) {
    if (p % q) continue;
    double l1 = lag_max(pd, q, first + (long)(c - 2) * p, p);
    double l2 = lag_max(pd, q, first + (long)(c - 1) * p, p);
    double l3 = lag_max(pd, q, first + (long)c * p, p);
    double d1 = l1 - l2, d2 = l2 - l3;
    if (d1 > 0 && d2 > 0 && d2 < d1 &&
        l3 - d2 * d2 / (d1 - d2) <= pd->tol)
      return 0; /* geometric decay towards a period-q orbit */
  }
  return 1;
}

/* Looks at lag p after the iterate x_k: the differences of the iterates
 * since it was last looked at, newest first, back to the confirmation
 * window.  Returns whether p is confirmed; if not, p is put on the wheel
 * at its new due time. */
static int confirmed(sc_period *pd, int p, long k) {
  const long cp = (long)pd->confirm * p;
  const long cap = pd->cap, slot = pd->slot;
  const double *xr = pd->rev + (cap - 1 - slot); /* x_{k-i} = xr[i] */
  const double *tr = pd->tolk + (cap - 1 - slot); /* tol_{k-i} = tr[i] */
  long stop = pd->seen[p] + 1, lf = pd->lf[p];
  if (stop <= k - cp) { /* only the window matters: it starts after it */
    stop = k - cp + 1;
    lf = k - cp;
  }
  for (long i = 0; i <= k - stop; i++) {
    if (!(fabs(xr[i] - xr[i + p]) <= tr[i])) {
      lf = k - i;
      break;
    }
  }
  pd->seen[p] = k;
  pd->lf[p] = lf;
  long due = lf + cp;
  if (due <= k) return 1;
  pd->due_at[p] = due;
  clear_bit(pd->due, p);
  long s = slot + (due - k);
  if (s >= cap) s -= cap;
  set_bit(pd->wheel_c + (size_t)s * (size_t)pd->nw, p);
  return 0;
}

/* The settling test's blocks of every lag through the iterates x_k0 ..
 * x_k1, into the per-lag state streak, prev, bm, bnext (the detector's
 * own, or copies): each lag-p difference |x_k - x_{k-p}|, k >= p, goes
 * into its block's maximum, and at a block's end the maximum is compared
 * with the previous block's (a decrease extends the streak) and starts
 * again from 0, as a push-by-push update does.  The iterates k0 - maxp
 * .. k1 must all be in the ring: k1 - k0 < cap - maxp. */
static void settle(const sc_period *pd, long k0, long k1, long *streak,
                   double *prev, double *bm, long *bnext) {
  /* x_k = xr[n - 1 - k] */
  const double *xr = pd->rev + (pd->cap - 1 - pd->slot);
  const long last = pd->n - 1;
  for (int p = 1; p <= pd->maxp; p++) {
    double m = bm[p], pv = prev[p];
    long st = streak[p], nb = bnext[p], k = k0 > p ? k0 : p;
    while (k <= k1) {
      long e = nb < k1 ? nb : k1; /* this block's iterates k .. e */
      /* four maxima side by side (max is exact and ignores a NaN either
       * way: the same maximum as one chain, which waits on each compare) */
      double m1 = 0, m2 = 0, m3 = 0;
      long i = last - k, i1 = last - e;
      for (; i - 3 >= i1; i -= 4) {
        double d0 = fabs(xr[i] - xr[i + p]);
        double d1 = fabs(xr[i - 1] - xr[i - 1 + p]);
        double d2 = fabs(xr[i - 2] - xr[i - 2 + p]);
        double d3 = fabs(xr[i - 3] - xr[i - 3 + p]);
        m = d0 > m ? d0 : m;
        m1 = d1 > m1 ? d1 : m1;
        m2 = d2 > m2 ? d2 : m2;
        m3 = d3 > m3 ? d3 : m3;
      }
      for (; i >= i1; i--) {
        double dx = fabs(xr[i] - xr[i + p]);
        m = dx > m ? dx : m;
      }
      m1 = m2 > m1 ? m2 : m1;
      m1 = m3 > m1 ? m3 : m1;
      m = m1 > m ? m1 : m;
      if (e == nb) {
        st = m < pv ? st + 1 : 0;
        pv = m;
        m = 0;
        nb += pd->blk[p];
      }
      k = e + 1;
    }
    bm[p] = m, prev[p] = pv, streak[p] = st, bnext[p] = nb;
  }
}

int sc_period_push(sc_period *pd, double x) {
  if (pd->found) return pd->found;
  const long k = pd->n, cap = pd->cap;
  const int nw = pd->nw;
  long slot = pd->slot + 1;
  if (slot == cap) slot = 0;
  pd->slot = slot;
  pd->n = k + 1;
  double *xr = pd->rev + (cap - 1 - slot); /* x_{k-i} = xr[i] */
  xr[0] = xr[cap] = x;
  if (x < pd->lo) pd->lo = x;
  if (x > pd->hi) pd->hi = x;
  if (fabs(x) > pd->amax) pd->amax = fabs(x);
  /* The extent only grows, so a difference that passed stays passed. */
  pd->tol = pd->rtol * (pd->hi - pd->lo) +
            SC_PERIOD_FLOOR_ULPS * DBL_EPSILON * pd->amax;
  pd->tolk[cap - 1 - slot] = pd->tolk[2 * cap - 1 - slot] = pd->tol;
  /* The settling test's blocks, once the iterates not taken yet would
   * otherwise leave the ring. */
  if (k - pd->sdone >= cap - pd->maxp) {
    settle(pd, pd->sdone + 1, k, pd->streak, pd->prev_max, pd->blk_max,
           pd->bnext);
    pd->sdone = k;
  }
  /* Lags that fall due with x_k join the due set; the smallest confirmed
   * one is accepted, or waits for the divisor the orbit is converging to
   * (a larger p would be a multiple of it). */
  uint64_t *wc = pd->wheel_c + (size_t)slot * (size_t)nw;
  for (int w = 0; w < nw; w++) {
    pd->due[w] |= wc[w];
    wc[w] = 0;
  }
  for (int w = 0; w < nw; w++) {
    uint64_t m = pd->due[w];
    while (m) {
      int p = 64 * w + __builtin_ctzll(m);
      m &= m - 1;
      if (!confirmed(pd, p, k)) continue;
      if (accept(pd, p)) pd->found = p;
      return pd->found;
    }
  }
  return 0;
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

/* See period.h.  A transient converging to a period-p orbit shrinks its
 * lag-p differences block after block for as long as it lasts; a chaotic
 * orbit can do so only for a short episode (near an unstable periodic
 * orbit).  So: the smallest p whose block maxima decreased in each of the
 * last blocks covering at least half of the orbit (and at least
 * SETTLE_BLOCKS blocks), still above the tolerance. */
int sc_period_settling(const sc_period *pd) {
  /* the iterates after the last batch, on copies of the state */
  long streak[SC_PERIOD_MAX + 1], bnext[SC_PERIOD_MAX + 1];
  double prev[SC_PERIOD_MAX + 1], bm[SC_PERIOD_MAX + 1];
  for (int p = 1; p <= pd->maxp; p++) {
    streak[p] = pd->streak[p], bnext[p] = pd->bnext[p];
    prev[p] = pd->prev_max[p], bm[p] = pd->blk_max[p];
  }
  if (pd->n - 1 > pd->sdone)
    settle(pd, pd->sdone + 1, pd->n - 1, streak, prev, bm, bnext);
  for (int p = 1; p <= pd->maxp; p++) {
    long covered = streak[p] * pd->blk[p];
    if (streak[p] >= SETTLE_BLOCKS && 2 * covered >= pd->n - 1 &&
        prev[p] > pd->tol)
      return p;
  }
  return 0;
}
