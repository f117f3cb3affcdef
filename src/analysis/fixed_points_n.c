/* Periodic orbits of n-dimensional maps without a start guess: Newton
 * (sc_shootn) from a grid of a box and from points of the attractor,
 * period after period, with the orbits already found deflated; each
 * orbit once at its minimal period.  See orbits.h. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/orbits.h"

/* Grid points whose orbit is followed through the transient to give the
 * attractor starts: a few, so that an attractor of several pieces (or
 * several attractors) is met; more cost transients and add little, the
 * attractor points themselves being the starts. */
#define ATTRACTOR_SEEDS 4

typedef struct {
  int period, stable, in_box;
  double multiplier, residual;
  double *x, *re, *im, *start;
} rec;

struct sc_orbitn_set {
  size_t n;            /* state dimension */
  int lo, hi;          /* periods searched */
  rec *o;              /* every orbit recorded, in the box or not */
  size_t count, cap;
  size_t *order;       /* indices of the in-box orbits, sorted */
  size_t nshown;
  sc_orbitn_stats *stats; /* hi - lo + 1 */
  size_t ngrid, nattr;
};

typedef struct {
  sc_map *map;
  const sc_fixed_points_n_spec *sp;
  sc_orbitn_set *set;
  size_t n;
  double *starts;  /* nstarts n */
  size_t nstarts;
  double scale;    /* deflation length */
  sc_accuracy acc;
  sc_msg *msg;
} search;

static void rec_free(rec *r) {
  free(r->x);
  free(r->re);
  free(r->im);
  free(r->start);
}

void sc_orbitn_set_free(sc_orbitn_set *s) {
  if (!s) return;
  for (size_t i = 0; i < s->count; i++) rec_free(&s->o[i]);
  free(s->o);
  free(s->order);
  free(s->stats);
  free(s);
}

size_t sc_orbitn_set_count(const sc_orbitn_set *s) { return s->nshown; }

int sc_orbitn_set_get(const sc_orbitn_set *s, size_t i, sc_orbitn_info *o) {
  if (i >= s->nshown) return SC_EINVAL;
  const rec *r = &s->o[s->order[i]];
  *o = (sc_orbitn_info){.period = r->period, .x = r->x, .mult_re = r->re,
                        .mult_im = r->im, .multiplier = r->multiplier,
                        .stable = r->stable, .residual = r->residual,
                        .start = r->start, .in_box = r->in_box};
  return SC_OK;
}

void sc_orbitn_set_stats(const sc_orbitn_set *s, int period,
                         sc_orbitn_stats *out) {
  memset(out, 0, sizeof *out);
  if (period >= s->lo && period <= s->hi) *out = s->stats[period - s->lo];
}

void sc_orbitn_set_starts(const sc_orbitn_set *s, size_t *grid,
                          size_t *attractor) {
  *grid = s->ngrid;
  *attractor = s->nattr;
}

/* Lexicographic order of points a, b (n components). */
static int lex_cmp(const double *a, const double *b, size_t n) {
  for (size_t c = 0; c < n; c++)
    if (a[c] != b[c]) return a[c] < b[c] ? -1 : 1;
  return 0;
}

/* The orbit pts (m points) rotated to start at its smallest point. */
static void canonical(const double *pts, int m, size_t n, double *out) {
  int k0 = 0;
  for (int k = 1; k < m; k++)
    if (lex_cmp(pts + (size_t)k * n, pts + (size_t)k0 * n, n) < 0) k0 = k;
  for (int k = 0; k < m; k++)
    memcpy(out + (size_t)k * n, pts + (size_t)((k0 + k) % m) * n,
           n * sizeof *out);
}

static double max_abs(const double *x, size_t k) {
  double r = 0;
  for (size_t i = 0; i < k; i++) r = fmax(r, fabs(x[i]));
  return r;
}

/* The index of the recorded orbit equal to pts (period q), or -1. */
static long find_known(const search *s, const double *pts, int q) {
  double tol = sc_orbit_tol(&s->acc, max_abs(pts, (size_t)q * s->n));
  for (size_t i = 0; i < s->set->count; i++)
    if (s->set->o[i].period == q &&
        sc_orbit_same_n(s->set->o[i].x, pts, q, s->n, tol))
      return (long)i;
  return -1;
}

static int in_box(const search *s, const double *pts, int q) {
  if (!s->sp->from) return 1;
  for (int k = 0; k < q; k++) {
    int inside = 1;
    for (size_t c = 0; c < s->n && inside; c++) {
      double v = pts[(size_t)k * s->n + c];
      inside = v >= s->sp->from[c] && v <= s->sp->to[c];
    }
    if (inside) return 1;
  }
  return 0;
}

/* Record the orbit of period q just solved by sh (its first q points). */
static int record(search *s, const sc_shootn *sh, int q,
                  const sc_shootn_result *res, const double *start) {
  sc_orbitn_set *set = s->set;
  size_t n = s->n;
  if (set->count == set->cap) {
    size_t cap = set->cap ? 2 * set->cap : 32;
    rec *o = realloc(set->o, cap * sizeof *o);
    if (!o) return sc_fail(s->msg, SC_ENOMEM, "fixed points: out of memory");
    set->o = o;
    set->cap = cap;
  }
  rec *r = &set->o[set->count];
  memset(r, 0, sizeof *r);
  r->x = malloc((size_t)q * n * sizeof *r->x);
  r->re = malloc(n * sizeof *r->re);
  r->im = malloc(n * sizeof *r->im);
  r->start = malloc(n * sizeof *r->start);
  if (!r->x || !r->re || !r->im || !r->start) {
    rec_free(r);
    return sc_fail(s->msg, SC_ENOMEM, "fixed points: out of memory");
  }
  canonical(sc_shootn_orbit(sh), q, n, r->x);
  memcpy(r->start, start, n * sizeof *start);
  r->period = q;
  r->residual = res->residual;
  r->in_box = in_box(s, r->x, q);
  set->count++;
  return SC_OK;
}

/* Multipliers of the recorded orbit r of a lower period q than the
 * shooting's m (those of f^m are the q-periodic ones to the power m / q):
 * the eigenvalues of the product of the q Jacobians at its points. */
static int orbit_multipliers(search *s, rec *r) {
  size_t n = s->n, q = (size_t)r->period;
  double *J = malloc(q * n * n * sizeof *J);
  const double **A = malloc(q * sizeof *A);
  sc_mapn_value *v = NULL;
  int st = sc_mapn_value_alloc(s->map, SC_EVAL_DERIV, &v, s->msg);
  if (!st && (!J || !A)) st = sc_fail(s->msg, SC_ENOMEM, "out of memory");
  for (size_t k = 0; k < q && !st; k++) {
    st = sc_map_eval_n(s->map, r->x + k * n, SC_EVAL_DERIV, v, s->msg);
    if (!st) memcpy(J + k * n * n, v->J, n * n * sizeof *J);
    A[k] = J + k * n * n;
  }
  if (!st) st = sc_product_eigs(n, q, A, r->re, r->im, s->msg);
  if (!st) {
    double mod = hypot(r->re[0], r->im[0]);
    r->multiplier = r->im[0] == 0 ? r->re[0] : mod;
    r->stable = mod < 1;
  }
  sc_mapn_value_free(v);
  free(J);
  free(A);
  return st;
}

/* What a converged start found: a new orbit, a known one, a lower period
 * outside the range. */
static int classify(search *s, sc_shootn *sh, int m,
                    const sc_shootn_result *res, const double *start,
                    sc_orbitn_stats *st) {
  size_t n = s->n;
  const double *pts = sc_shootn_orbit(sh);
  double tol = sc_orbit_tol(&s->acc, max_abs(pts, (size_t)m * n));
  int q = sc_orbit_minimal_period_n(pts, m, n, tol);
  if (find_known(s, pts, q) >= 0) {
    st->known++;
    return SC_OK;
  }
  int err = record(s, sh, q, res, start);
  if (err) return err;
  rec *r = &s->set->o[s->set->count - 1];
  if (q == m) {
    const double *re, *im;
    sc_shootn_multipliers(sh, &re, &im);
    memcpy(r->re, re, n * sizeof *re);
    memcpy(r->im, im, n * sizeof *im);
    r->multiplier = res->multiplier;
    r->stable = res->stable;
  } else if ((err = orbit_multipliers(s, r))) {
    return err;
  }
  if (q < s->sp->period_lo) {
    r->in_box = 0; /* kept to be deflated, not shown */
    st->lower++;
  } else if (!r->in_box) {
    st->outside++;
  } else {
    st->found++;
  }
  /* later starts of this period are kept away from it */
  return sc_shootn_deflate(sh, r->x, q, s->scale, s->msg);
}

/* Newton from every start for period m. */
static int search_period(search *s, int m) {
  sc_shootn *sh;
  int err = sc_shootn_alloc(s->map, m, s->sp->method, s->sp->linsolve, &sh,
                            s->msg);
  if (err) return err;
  for (size_t i = 0; i < s->set->count && !err; i++)
    if (m % s->set->o[i].period == 0)
      err = sc_shootn_deflate(sh, s->set->o[i].x, s->set->o[i].period,
                              s->scale, s->msg);
  sc_orbitn_stats *st = &s->set->stats[m - s->set->lo];
  for (size_t k = 0; k < s->nstarts && !err; k++) {
    const double *x0 = s->starts + k * s->n;
    sc_shootn_result res;
    sc_msg em;
    st->starts++;
    int e = sc_shootn_solve(sh, x0, &res, &em);
    if (e == SC_OK) {
      err = classify(s, sh, m, &res, x0, st);
    } else if (e == SC_ENOCONV || e == SC_ESING || e == SC_EUNDEF ||
               e == SC_ENONFINITE) {
      st->failed[res.reason]++;
    } else {
      err = sc_fail(s->msg, e, "%s", em.text);
    }
  }
  sc_shootn_free(sh);
  return err;
}

/* The grid starts, then the attractor starts, into s->starts. */
static int make_starts(search *s) {
  const sc_fixed_points_n_spec *sp = s->sp;
  size_t n = s->n, ngrid = 1;
  if (sp->start) {
    s->starts = malloc(n * sizeof *s->starts);
    if (!s->starts) return sc_fail(s->msg, SC_ENOMEM, "out of memory");
    memcpy(s->starts, sp->start, n * sizeof *s->starts);
    s->nstarts = 1;
    return SC_OK;
  }
  for (size_t c = 0; c < n; c++) ngrid *= sp->steps;
  size_t total = ngrid + sp->attractor;
  s->starts = malloc(total * n * sizeof *s->starts);
  sc_mapn_value *v = NULL;
  int st = sc_mapn_value_alloc(s->map, SC_EVAL_VALUE, &v, s->msg);
  if (!s->starts || st) {
    sc_mapn_value_free(v);
    return st ? st : sc_fail(s->msg, SC_ENOMEM, "out of memory");
  }
  for (size_t g = 0; g < ngrid; g++) {
    size_t idx = g;
    for (size_t c = 0; c < n; c++) {
      s->starts[g * n + c] = sc_grid(sp->from[c], sp->to[c], sp->steps,
                                     idx % sp->steps, SC_GRID_LINEAR);
      idx /= sp->steps;
    }
  }
  s->set->ngrid = s->nstarts = ngrid;
  /* Seeds spread over the grid (a stride through it); a seed whose
   * orbit leaves the map's domain or goes to infinity is replaced by
   * the next grid point. */
  size_t want = sp->attractor, seeds = 0, stride = ngrid / ATTRACTOR_SEEDS + 1;
  for (size_t t = 0; t < ngrid && want > 0 && seeds < ATTRACTOR_SEEDS; t++) {
    size_t g = (t * stride + t / ATTRACTOR_SEEDS) % ngrid;
    double x[SC_MAXDIM];
    memcpy(x, s->starts + g * n, n * sizeof *x);
    int ok = 1;
    for (long i = 0; i < sp->transient && ok; i++) {
      ok = sc_map_eval_n(s->map, x, SC_EVAL_VALUE, v, NULL) == SC_OK;
      if (ok) memcpy(x, v->f, n * sizeof *x);
    }
    if (!ok) continue;
    size_t take = want / (ATTRACTOR_SEEDS - seeds);
    if (take == 0) take = want;
    for (size_t i = 0; i < take && ok; i++) {
      ok = sc_map_eval_n(s->map, x, SC_EVAL_VALUE, v, NULL) == SC_OK;
      if (!ok) break;
      memcpy(x, v->f, n * sizeof *x);
      memcpy(s->starts + s->nstarts * n, x, n * sizeof *x);
      s->nstarts++;
      want--;
      s->set->nattr++;
    }
    seeds++;
  }
  sc_mapn_value_free(v);
  return SC_OK;
}

static int check_spec(const sc_map *m, const sc_fixed_points_n_spec *sp,
                      sc_msg *msg) {
  if (sp->period_lo < 1 || sp->period_hi < sp->period_lo ||
      sp->period_hi > SC_FIXED_POINTS_N_MAX_PERIOD)
    return sc_fail(msg, SC_EINVAL,
                   "sc_fixed_points_n_find: periods %d..%d (valid: 1 <= lo "
                   "<= hi <= %d)",
                   sp->period_lo, sp->period_hi,
                   SC_FIXED_POINTS_N_MAX_PERIOD);
  if (sp->method != SC_SHOOT_SINGLE && sp->method != SC_SHOOT_MULTIPLE)
    return sc_fail(msg, SC_EINVAL, "sc_fixed_points_n_find: method = %d",
                   (int)sp->method);
  if (sp->start) return SC_OK;
  size_t n = sc_map_dim(m);
  if (!sp->from || !sp->to)
    return sc_fail(msg, SC_EINVAL,
                   "sc_fixed_points_n_find: no box (from, to) and no start");
  for (size_t c = 0; c < n; c++)
    if (!isfinite(sp->from[c]) || !isfinite(sp->to[c]) ||
        !(sp->from[c] < sp->to[c]))
      return sc_fail(msg, SC_EINVAL,
                     "sc_fixed_points_n_find: from = %g, to = %g in component "
                     "%zu (valid: finite, from < to)",
                     sp->from[c], sp->to[c], c + 1);
  double total = pow((double)sp->steps, (double)n) + (double)sp->attractor;
  if (sp->steps < 2 || !(total <= SC_FIXED_POINTS_N_MAX_STARTS))
    return sc_fail(msg, SC_EINVAL,
                   "sc_fixed_points_n_find: steps = %zu, attractor = %zu: "
                   "%.3g starts (valid: steps >= 2, steps^%zu + attractor <= "
                   "%d)",
                   sp->steps, sp->attractor, total, n,
                   SC_FIXED_POINTS_N_MAX_STARTS);
  if (sp->transient < 0)
    return sc_fail(msg, SC_EINVAL,
                   "sc_fixed_points_n_find: transient = %ld (valid: >= 0)",
                   sp->transient);
  return SC_OK;
}

/* Order of recorded orbits a, b of set: by period, then first point. */
static int by_period_then_point(const sc_orbitn_set *set, size_t ia,
                                size_t ib) {
  const rec *a = &set->o[ia], *b = &set->o[ib];
  if (a->period != b->period) return a->period < b->period ? -1 : 1;
  return lex_cmp(a->x, b->x, set->n);
}

/* The in-box orbits in order (insertion sort: a few hundred orbits). */
static int sort_shown(sc_orbitn_set *set) {
  set->order = malloc((set->count + 1) * sizeof *set->order);
  if (!set->order) return SC_ENOMEM;
  for (size_t i = 0; i < set->count; i++) {
    if (!set->o[i].in_box) continue;
    size_t j = set->nshown++;
    set->order[j] = i;
    for (; j > 0; j--) {
      if (by_period_then_point(set, set->order[j - 1], set->order[j]) <= 0)
        break;
      size_t t = set->order[j];
      set->order[j] = set->order[j - 1];
      set->order[j - 1] = t;
    }
  }
  return SC_OK;
}

int sc_fixed_points_n_find(sc_map *m, const sc_fixed_points_n_spec *sp,
                           sc_orbitn_set **out, sc_msg *msg) {
  *out = NULL;
  if (!m || !sp)
    return sc_fail(msg, SC_EINVAL, "sc_fixed_points_n_find: no map or spec");
  int st = check_spec(m, sp, msg);
  if (st) return st;
  search s = {.map = m, .sp = sp, .n = sc_map_dim(m), .msg = msg};
  sc_map_solver_accuracy(m, &s.acc);
  s.set = calloc(1, sizeof *s.set);
  if (!s.set) return sc_fail(msg, SC_ENOMEM, "out of memory");
  s.set->n = s.n;
  s.set->lo = sp->period_lo;
  s.set->hi = sp->period_hi;
  s.set->stats = calloc((size_t)(sp->period_hi - sp->period_lo + 1),
                        sizeof *s.set->stats);
  if (!s.set->stats) {
    st = sc_fail(msg, SC_ENOMEM, "out of memory");
    goto done;
  }
  /* Deflation measures distances against the box's largest side. */
  s.scale = 1;
  if (!sp->start) {
    s.scale = 0;
    for (size_t c = 0; c < s.n; c++)
      s.scale = fmax(s.scale, sp->to[c] - sp->from[c]);
  }
  if ((st = make_starts(&s))) goto done;
  /* Increasing periods: every orbit found is deflated in the searches of
   * its multiples (a lower-period root of f^m is deflated as soon as it
   * is met). */
  for (int p = sp->period_lo; p <= sp->period_hi && !st; p++)
    st = search_period(&s, p);
  if (!st) st = sort_shown(s.set);
done:
  free(s.starts);
  if (st) {
    sc_orbitn_set_free(s.set);
    return st;
  }
  *out = s.set;
  return SC_OK;
}
