/* Period detection on an orbit of an n-dimensional map: period.h's rule
 * with the differences and the extent in the max norm (docs/charts.md).
 *
 * Written the plain way, as the reference detector of tests/test_period.c:
 * a run counter and a block maximum per lag, updated at every push over
 * the ring of the last states.  The one-dimensional detector's lazy
 * confirmation saves a chart of bk2 a tenth of its time; for the maps of
 * a few components charted here the map costs more than this loop over
 * the lags, and with n = 1 both detectors give the same answers at the
 * same iterates (tests/test_period.c checks it). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/period.h"
#include "period_impl.h"

/* Iterates in one block of the settling test, and blocks compared: the
 * values of period.c (SETTLE_BLOCK, SETTLE_BLOCKS), for the same rule. */
#define SETTLE_BLOCK 8
#define SETTLE_BLOCKS 4

struct sc_periodn {
  size_t dim;
  int maxp, confirm;
  double rtol;
  long cap;      /* ring of states: (confirm + 2) maxp, enough for the
                    near-flip test's three cycles and their lag */
  double *ring;  /* cap states of dim components: x_k at (k % cap) dim */
  double *lo, *hi; /* per component, over the orbit so far */
  double amax;   /* largest |x_i| so far */
  double tol;
  long n;        /* states pushed, x0 included */
  int found;
  long *run, *blk, *pos, *streak;
  double *bmax, *prev;
};

int sc_periodn_alloc(size_t dim, int max_period, int confirm, double rtol,
                     sc_periodn **out, sc_msg *msg) {
  *out = NULL;
  if (dim < 1 || dim > SC_MAXDIM)
    return sc_fail(msg, SC_EINVAL, "sc_periodn_alloc: dim = %zu (valid: 1..%d)",
                   dim, SC_MAXDIM);
  int st = sc_period_check_args("sc_periodn_alloc", max_period, confirm,
                                rtol, msg);
  if (st) return st;
  sc_periodn *pd = calloc(1, sizeof *pd);
  if (!pd) goto fail;
  pd->dim = dim;
  pd->maxp = max_period;
  pd->confirm = confirm;
  pd->rtol = rtol;
  pd->cap = (long)(confirm + 2) * max_period + 1;
  size_t np = (size_t)max_period + 1;
  pd->ring = calloc((size_t)pd->cap * dim, sizeof *pd->ring);
  pd->lo = calloc(dim, sizeof *pd->lo);
  pd->hi = calloc(dim, sizeof *pd->hi);
  pd->run = calloc(np, sizeof *pd->run);
  pd->blk = calloc(np, sizeof *pd->blk);
  pd->pos = calloc(np, sizeof *pd->pos);
  pd->streak = calloc(np, sizeof *pd->streak);
  pd->bmax = calloc(np, sizeof *pd->bmax);
  pd->prev = calloc(np, sizeof *pd->prev);
  if (!pd->ring || !pd->lo || !pd->hi || !pd->run || !pd->blk || !pd->pos ||
      !pd->streak || !pd->bmax || !pd->prev)
    goto fail;
  for (int p = 1; p <= max_period; p++)
    pd->blk[p] = (long)p * ((SETTLE_BLOCK + p - 1) / p);
  *out = pd;
  return SC_OK;
fail:
  sc_periodn_free(pd);
  return sc_fail(msg, SC_ENOMEM, "sc_periodn_alloc: out of memory");
}

void sc_periodn_free(sc_periodn *pd) {
  if (!pd) return;
  free(pd->ring);
  free(pd->lo);
  free(pd->hi);
  free(pd->run);
  free(pd->blk);
  free(pd->pos);
  free(pd->streak);
  free(pd->bmax);
  free(pd->prev);
  free(pd);
}

/* State k (n - cap <= k < n). */
static const double *state(const sc_periodn *pd, long k) {
  return pd->ring + (size_t)(k % pd->cap) * pd->dim;
}

/* |x_j - x_{j-q}| in the max norm. */
static double dist(const sc_periodn *pd, long j, int q) {
  const double *a = state(pd, j), *b = state(pd, j - q);
  double m = 0;
  for (size_t i = 0; i < pd->dim; i++) {
    double d = fabs(a[i] - b[i]);
    m = d > m ? d : m;
  }
  return m;
}

void sc_periodn_reset(sc_periodn *pd, const double *x0) {
  memcpy(pd->ring, x0, pd->dim * sizeof *x0);
  pd->n = 1;
  pd->amax = 0;
  for (size_t i = 0; i < pd->dim; i++) {
    pd->lo[i] = pd->hi[i] = x0[i];
    pd->amax = fmax(pd->amax, fabs(x0[i]));
  }
  pd->tol = SC_PERIOD_FLOOR_ULPS * DBL_EPSILON * pd->amax;
  pd->found = 0;
  for (int p = 1; p <= pd->maxp; p++) {
    pd->run[p] = pd->pos[p] = pd->streak[p] = 0;
    pd->bmax[p] = pd->prev[p] = 0;
  }
}

double sc_periodn_tol(const sc_periodn *pd) { return pd->tol; }

/* Largest lag-q difference for j in [j0, j0 + len). */
static double lag_max(const sc_periodn *pd, int q, long j0, long len) {
  double m = 0;
  for (long j = j0; j < j0 + len; j++) m = fmax(m, dist(pd, j, q));
  return m;
}

/* A state of n > 1 components may spiral into a period-q orbit
 * (complex multipliers of modulus r): its lag-p differences, p a
 * multiple of q near a whole turn, fall under tol while its lag-q ones
 * are still about tol / (1 - r^p), and the decay of their maxima per
 * cycle is not geometric enough for the Aitken test (the spiral is an
 * ellipse sampled at drifting phases).  So p also waits while a proper
 * divisor's lag-q differences are within this many tolerances: a
 * transient with r^p < 0.999 does, and a period-p orbit whose points lie
 * within 1000 tolerances (1e-3 of the extent at the default
 * period-rtol) of a period-q orbit's is within about 1e-6 of a flip in
 * its parameter. */
#define NEAR_TOLS 1000.0

/* period.c's accept(): p waits while the orbit converges geometrically
 * to a period-q orbit, q a proper divisor of p (n > 1: or while it is
 * still near one, NEAR_TOLS). */
static int accept(const sc_periodn *pd, int p) {
  const int c = pd->confirm;
  if (c < 3) return 1;
  const long first = pd->n - 1 - (long)(c + 1) * p + 1;
  for (int q = 1; q < p; q++) {
    if (p % q) continue;
    double l1 = lag_max(pd, q, first + (long)(c - 2) * p, p);
    double l2 = lag_max(pd, q, first + (long)(c - 1) * p, p);
    double l3 = lag_max(pd, q, first + (long)c * p, p);
    double d1 = l1 - l2, d2 = l2 - l3;
    if (d1 > 0 && d2 > 0 && d2 < d1 && l3 - d2 * d2 / (d1 - d2) <= pd->tol)
      return 0;
    if (pd->dim > 1 && l3 <= NEAR_TOLS * pd->tol) return 0;
  }
  return 1;
}

int sc_periodn_push(sc_periodn *pd, const double *x) {
  if (pd->found) return pd->found;
  const long k = pd->n++;
  memcpy(pd->ring + (size_t)(k % pd->cap) * pd->dim, x, pd->dim * sizeof *x);
  double ext = 0;
  for (size_t i = 0; i < pd->dim; i++) {
    if (x[i] < pd->lo[i]) pd->lo[i] = x[i];
    if (x[i] > pd->hi[i]) pd->hi[i] = x[i];
    if (fabs(x[i]) > pd->amax) pd->amax = fabs(x[i]);
    ext = fmax(ext, pd->hi[i] - pd->lo[i]);
  }
  pd->tol = pd->rtol * ext + SC_PERIOD_FLOOR_ULPS * DBL_EPSILON * pd->amax;
  for (int p = 1; p <= pd->maxp && p <= k; p++) {
    double dx = dist(pd, k, p);
    pd->run[p] = dx <= pd->tol ? pd->run[p] + 1 : 0;
    if (dx > pd->bmax[p]) pd->bmax[p] = dx;
    if (++pd->pos[p] == pd->blk[p]) {
      pd->streak[p] = pd->bmax[p] < pd->prev[p] ? pd->streak[p] + 1 : 0;
      pd->prev[p] = pd->bmax[p];
      pd->bmax[p] = 0;
      pd->pos[p] = 0;
    }
  }
  for (int p = 1; p <= pd->maxp && p <= k; p++) {
    if (pd->run[p] < (long)pd->confirm * p) continue;
    if (accept(pd, p)) pd->found = p;
    break;
  }
  return pd->found;
}

int sc_periodn_settling(const sc_periodn *pd) {
  for (int p = 1; p <= pd->maxp; p++)
    if (pd->streak[p] >= SETTLE_BLOCKS &&
        2 * pd->streak[p] * pd->blk[p] >= pd->n - 1 && pd->prev[p] > pd->tol)
      return p;
  return 0;
}

/* ------------------------------------------------------------------ */
/* The invariant-circle test (period.h)                                 */

/* An angle and the index of its point, as two doubles of the work. */
static int by_angle(const void *a, const void *b) {
  double u = *(const double *)a, v = *(const double *)b;
  return (u > v) - (u < v);
}

/* Length of the closed polygon through the @p cnt points of @p pts
 * sorted by angle (@p w: (angle, index) pairs); @p zero counts gaps
 * within tol. */
static double polygon(const double *pts, size_t dim, const double *w,
                      size_t cnt, double tol, size_t *zero) {
  double len = 0;
  for (size_t k = 0; k < cnt; k++) {
    const double *a = pts + (size_t)w[2 * k + 1] * dim;
    const double *b = pts + (size_t)w[2 * ((k + 1) % cnt) + 1] * dim;
    double dx = a[0] - b[0], dy = a[1] - b[1];
    if (zero && fmax(fabs(dx), fabs(dy)) <= tol) ++*zero;
    len += hypot(dx, dy);
  }
  return len;
}

/* The length of the closed polygon through the points i = i0, i0 + s,
 * ... (cnt of them) sorted by angle about (cx, cy), with w as work. */
static double sorted_length(const double *pts, size_t dim, size_t i0,
                            size_t s, size_t cnt, double cx, double cy,
                            double tol, double *w, size_t *zero) {
  for (size_t k = 0; k < cnt; k++) {
    size_t i = i0 + k * s;
    w[2 * k] = atan2(pts[i * dim + 1] - cy, pts[i * dim] - cx);
    w[2 * k + 1] = (double)i;
  }
  qsort(w, cnt, 2 * sizeof *w, by_angle);
  return polygon(pts, dim, w, cnt, tol, zero);
}

int sc_orbit_on_circle(const double *pts, size_t m, size_t dim, double tol,
                       double *work, double *ratio) {
  if (ratio) *ratio = NAN;
  if (m < 16 || dim < 2) return 0;
  m -= m % 2;
  double cx = 0, cy = 0;
  for (size_t i = 0; i < m; i++) {
    cx += pts[i * dim];
    cy += pts[i * dim + 1];
  }
  cx /= (double)m;
  cy /= (double)m;
  size_t zero = 0, h = m / 2;
  double lm = sorted_length(pts, dim, 0, 1, m, cx, cy, tol, work, &zero);
  /* The order: rank[i] of point i by angle; the ranks of the images
   * x_{k+1} of the points x_k taken by angle increase cyclically (one
   * descent, the wrap) on a circle the map turns, or decrease (one
   * ascent) on one it reverses. */
  double *rank = work + 2 * m;
  for (size_t k = 0; k < m; k++) rank[(size_t)work[2 * k + 1]] = (double)k;
  size_t desc = 0, cnt = 0;
  double first = -1, prev = -1;
  for (size_t k = 0; k < m; k++) {
    size_t i = (size_t)work[2 * k + 1];
    if (i + 1 == m) continue; /* the last point's image is not known */
    double r = rank[i + 1];
    if (prev >= 0) desc += r < prev;
    else first = r;
    prev = r;
    cnt++;
  }
  desc += first < prev; /* the wrap */
  size_t asc = cnt - desc;
  size_t disorder = desc < asc ? desc : asc;
  /* the halves: even and odd iterates (a chaotic attractor in bands
   * visited in turn has one band in each), the older and newer half */
  const size_t i0[4] = {0, 1, 0, h}, step[4] = {2, 2, 1, 1};
  double r = 0;
  for (int k = 0; k < 4; k++) {
    double lh = sorted_length(pts, dim, i0[k], step[k], h, cx, cy, tol, work,
                              NULL);
    r = fmax(r, lh > 0 ? lm / lh : HUGE_VAL);
  }
  if (ratio) *ratio = r;
  return 2 * zero < m && r < SC_CIRCLE_RATIO &&
         disorder <= 1 + m / SC_CIRCLE_TIES;
}
