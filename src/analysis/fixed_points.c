/* Every period-m orbit in an interval of d, without a start guess: split
 * the interval into pieces of constant itinerary of f^m, bracket the roots
 * of f^m(d) - d on each piece, polish them by safeguarded Newton, report
 * each orbit once.  See orbits.h. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/orbits.h"


/* Bisections of a bracket, far more than the 53 halvings of a double
 * interval: a guard against a loop, never reached. */
#define MAX_BISECT 200

/* Pieces located between two grid points at most (a guard). */
#define MAX_PIECES_PER_STEP 10000

typedef struct {
  int period, neutral, stable;
  double multiplier, lo, hi, residual;
  double *d;
  char *itin;
} orbit_rec;

struct sc_orbit_set {
  size_t n, cap;
  orbit_rec *o;
  size_t npieces, nlower, nundef;
};

/* One sample of f^m. */
typedef struct {
  double x;
  int st; /* SC_OK, or the map's failure */
  sc_map_value v;
} sample;

typedef struct {
  sc_map *m;
  int period;
  /* Newton, the gaps and the one equality rule: no tighter than the map's
   * precision (sc_map_solver_accuracy()), as in shooting and branches */
  const sc_accuracy *acc;
  /* the ends of a piece of constant itinerary: the map's own accuracy,
   * so that an orbit on a piece's end (d* of the symmetric model, d = 0)
   * does not fall into the gap left between two pieces */
  const sc_accuracy *edge;
  sc_orbit_set *set;
  double *pts;  /* period scratch points */
  char *itin;   /* scratch itinerary text */
  size_t itin_len;
  sc_msg *msg;
} search;

static double tol_x(const sc_accuracy *acc, double x) {
  return acc->newton_atol + acc->newton_rtol * fabs(x);
}

static int eval(search *s, double x, sample *out) {
  out->x = x;
  sc_msg em;
  out->st = sc_map_iterate(s->m, x, s->period,
                           SC_EVAL_DERIV | SC_EVAL_ITINERARY, &out->v, &em);
  if (out->st == SC_EUNDEF || out->st == SC_ENONFINITE ||
      out->st == SC_ENOCONV) {
    s->set->nundef++;
    return SC_OK;
  }
  if (out->st) return sc_fail(s->msg, out->st, "%s", em.text);
  return SC_OK;
}

/* Whether two samples lie on one piece of constant itinerary.  The same
 * itinerary at both ends is not enough: a piece can come back after
 * another between two samples (A, a sliver of B, A again), and then the
 * gap g = f^m(d) - d jumps in between.  On one smooth piece whose slope
 * g' has one sign at both ends, g moves that way; moving the other way, g
 * has jumped: two pieces, told apart by the bisection of the caller (the
 * mirror image of such a pair, met in the other order by the scan, was
 * found while the pair itself was not). */
static int same_piece(const sample *a, const sample *b) {
  if (a->st != SC_OK || b->st != SC_OK) return a->st != SC_OK && b->st != SC_OK;
  if (strcmp(a->v.itinerary, b->v.itinerary) != 0) return 0;
  double sa = a->v.dfdd - 1, sb = b->v.dfdd - 1;
  double dg = (b->v.f - b->x) - (a->v.f - a->x);
  if (a->v.neutral || b->v.neutral) return 1;
  return !((sa > 0 && sb > 0 && dg < 0) || (sa < 0 && sb < 0 && dg > 0));
}

static int grow(sc_orbit_set *set) {
  if (set->n < set->cap) return SC_OK;
  size_t cap = set->cap ? 2 * set->cap : 16;
  orbit_rec *o = realloc(set->o, cap * sizeof *o);
  if (!o) return SC_ENOMEM;
  set->o = o;
  set->cap = cap;
  return SC_OK;
}

/* The orbit of x: points (period of them) into s->pts, itineraries of
 * single iterates joined by ';' into s->itin; its minimal period. */
static int orbit_of(search *s, double x, int *minper) {
  sc_map_value v;
  s->itin[0] = '\0';
  size_t used = 0;
  double y = x;
  *minper = s->period;
  for (int i = 0; i < s->period; i++) {
    s->pts[i] = y;
    int st = sc_map_eval(s->m, y, SC_EVAL_ITINERARY, &v, s->msg);
    if (st) return st;
    int k = snprintf(s->itin + used, s->itin_len - used, "%s%s",
                     i ? ";" : "", v.itinerary);
    if (k > 0) used += (size_t)k;
    if (used > s->itin_len - 1) used = s->itin_len - 1;
    y = v.f;
  }
  /* The one minimal-period rule (common.h). */
  *minper = sc_orbit_minimal_period(s->pts, s->period, sc_orbit_tol(s->acc, x));
  return SC_OK;
}

/* Index of the smallest point of s->pts. */
static int smallest(const search *s) {
  int k = 0;
  for (int i = 1; i < s->period; i++)
    if (s->pts[i] < s->pts[k]) k = i;
  return k;
}

/* Record the orbit through x (a polished root), unless it is a shift of
 * one already recorded or has a smaller period. */
static int record(search *s, double x, const sc_map_value *v, int neutral,
                  double lo, double hi) {
  int minper, st = orbit_of(s, x, &minper);
  if (st == SC_EUNDEF || st == SC_ENONFINITE || st == SC_ENOCONV) {
    s->set->nundef++;
    return SC_OK;
  }
  if (st) return st;
  if (minper < s->period) {
    s->set->nlower++;
    return SC_OK;
  }
  int m = s->period, k0 = smallest(s);
  double tol = sc_orbit_tol(s->acc, s->pts[k0]); /* one equality rule */
  for (size_t j = 0; j < s->set->n; j++) {
    const orbit_rec *o = &s->set->o[j];
    if (o->neutral != neutral) continue;
    if (neutral) {
      /* A family: one of its shifts has a point in this family's piece. */
      for (int i = 0; i < m; i++)
        if (s->pts[i] >= o->lo - tol && s->pts[i] <= o->hi + tol)
          return SC_OK;
      continue;
    }
    if (sc_orbit_same(o->d, s->pts, m, tol)) return SC_OK;
  }
  if (grow(s->set)) return sc_fail(s->msg, SC_ENOMEM, "out of memory");
  orbit_rec *o = &s->set->o[s->set->n];
  memset(o, 0, sizeof *o);
  o->d = malloc((size_t)m * sizeof *o->d);
  /* Rotate the itinerary text with the points: split at ';'. */
  o->itin = malloc(s->itin_len);
  if (!o->d || !o->itin) {
    free(o->d);
    free(o->itin);
    return sc_fail(s->msg, SC_ENOMEM, "out of memory");
  }
  for (int i = 0; i < m; i++) o->d[i] = s->pts[(k0 + i) % m];
  {
    const char *p = s->itin;
    for (int i = 0; i < k0 && p; i++) {
      p = strchr(p, ';');
      if (p) p++;
    }
    if (!p) p = s->itin;
    size_t head = (size_t)(p - s->itin);
    if (head) snprintf(o->itin, s->itin_len, "%s;%.*s", p,
                       (int)(head - 1), s->itin);
    else snprintf(o->itin, s->itin_len, "%s", s->itin);
  }
  o->period = m;
  o->neutral = neutral;
  o->multiplier = neutral ? 1 : v->dfdd;
  o->stable = !neutral && fabs(o->multiplier) < 1;
  o->lo = neutral ? lo : o->d[0];
  o->hi = neutral ? hi : o->d[0];
  o->residual = fabs(v->f - x);
  s->set->n++;
  return SC_OK;
}

/* A root of g = f^m(d) - d in [a, b] (g(a) g(b) < 0, one piece): Newton
 * with the exact derivative, safeguarded by bisection. */
static int polish(search *s, const sample *a, const sample *b) {
  double lo = a->x, hi = b->x, glo = a->v.f - a->x;
  sample c = *a;
  double x = 0.5 * (lo + hi);
  int st = eval(s, x, &c);
  if (st) return st;
  for (int it = 0; it < MAX_BISECT; it++) {
    if (c.st != SC_OK) break;
    double g = c.v.f - c.x, gd = c.v.dfdd - 1;
    if ((g < 0) == (glo < 0)) lo = c.x, glo = g;
    else hi = c.x;
    double ftol = s->acc->newton_ftol * fmax(1, fabs(c.v.dfdd));
    double xn = c.x - g / gd;
    int newton_ok = isfinite(xn) && xn > lo && xn < hi;
    if (!newton_ok) xn = 0.5 * (lo + hi);
    double step = fabs(xn - c.x);
    int done = (step <= tol_x(s->acc, c.x) && fabs(g) <= ftol) ||
               hi - lo <= tol_x(s->acc, c.x) || g == 0;
    if (done && (!newton_ok || g == 0)) break;
    /* The last Newton step is taken too: it squares the error. */
    if ((st = eval(s, xn, &c))) return st;
    if (done) break;
  }
  if (c.st != SC_OK) return SC_OK; /* undefined inside a piece: skip */
  /* The polished point must keep the piece's itinerary. */
  if (strcmp(c.v.itinerary, a->v.itinerary) != 0) return SC_OK;
  return record(s, c.x, &c.v, 0, 0, 0);
}

/* Where rounding d itself (DBL_EPSILON |d|) exceeds newton_ftol, a gap
 * f^m(d) - d of zero says nothing (d = 1e300 absorbs any shift): no orbit
 * is reported there, the point counts as undefined. */
static int unresolved(const search *s, double x) {
  return DBL_EPSILON * fabs(x) > s->acc->newton_ftol;
}

/* Roots between two samples of one piece. */
static int bracket(search *s, const sample *a, const sample *b) {
  if (a->st != SC_OK || b->st != SC_OK || a->v.neutral) return SC_OK;
  double ga = a->v.f - a->x, gb = b->v.f - b->x;
  if (ga == 0) {
    if (!unresolved(s, a->x)) return record(s, a->x, &a->v, 0, 0, 0);
    s->set->nundef++;
    return SC_OK;
  }
  if (gb == 0 || (ga < 0) == (gb < 0)) return SC_OK;
  return polish(s, a, b);
}

/* The end of a piece [lo, hi] whose samples were all neutral with the
 * gap f^m(d) - d of @p last: a family when the gap vanishes. */
static int end_piece(search *s, double lo, const sample *last,
                     int all_neutral) {
  s->set->npieces++;
  if (last->st != SC_OK || !all_neutral) return SC_OK;
  if (fabs(last->v.f - last->x) > s->acc->newton_ftol) return SC_OK;
  if (unresolved(s, lo) || unresolved(s, last->x)) {
    s->set->nundef++;
    return SC_OK;
  }
  double mid = 0.5 * (lo + last->x);
  sample c;
  int st = eval(s, mid, &c);
  if (st) return st;
  if (c.st != SC_OK) return SC_OK;
  return record(s, mid, &c.v, 1, lo, last->x);
}

static int by_first_point(const void *pa, const void *pb) {
  const orbit_rec *a = pa, *b = pb;
  return (a->d[0] > b->d[0]) - (a->d[0] < b->d[0]);
}

int sc_fixed_points_find(sc_map *m, const sc_fixed_points_spec *spec,
                         sc_orbit_set **out, sc_msg *msg) {
  *out = NULL;
  if (!m || !spec)
    return sc_fail(msg, SC_EINVAL, "sc_fixed_points_find: no map or spec");
  if (spec->period < 1 || spec->period > 100000)
    return sc_fail(msg, SC_EINVAL,
                   "sc_fixed_points_find: period = %d (valid: [1, 100000])",
                   spec->period);
  if (!isfinite(spec->from) || !isfinite(spec->to) ||
      !(spec->from < spec->to))
    return sc_fail(msg, SC_EINVAL,
                   "sc_fixed_points_find: from = %g, to = %g (valid: "
                   "finite, from < to)",
                   spec->from, spec->to);
  if (spec->steps < 2)
    return sc_fail(msg, SC_EINVAL,
                   "sc_fixed_points_find: steps = %zu (valid: >= 2)",
                   spec->steps);
  sc_orbit_set *set = calloc(1, sizeof *set);
  sc_accuracy acc; /* no tighter than the map's precision */
  sc_map_solver_accuracy(m, &acc);
  search s = {.m = m, .period = spec->period, .acc = &acc,
              .edge = sc_map_accuracy(m),
              .set = set, .msg = msg};
  s.itin_len = (size_t)spec->period * (SC_ITIN_LEN + 1) + 1;
  s.pts = malloc((size_t)spec->period * sizeof *s.pts);
  s.itin = malloc(s.itin_len);
  int st = SC_OK;
  if (!set || !s.pts || !s.itin) {
    st = sc_fail(msg, SC_ENOMEM, "sc_fixed_points_find: out of memory");
    goto done;
  }
  sample cur, nxt, lo, hi, mid;
  double piece_lo = spec->from;
  if ((st = eval(&s, spec->from, &cur))) goto done;
  int all_neutral = cur.st == SC_OK && cur.v.neutral;
  for (size_t j = 1; j < spec->steps; j++) {
    double x = sc_grid(spec->from, spec->to, spec->steps, j, SC_GRID_LINEAR);
    if ((st = eval(&s, x, &nxt))) goto done;
    for (int guard = 0;; guard++) {
      if (same_piece(&cur, &nxt)) {
        if ((st = bracket(&s, &cur, &nxt))) goto done;
        all_neutral = all_neutral && nxt.st == SC_OK && nxt.v.neutral;
        cur = nxt;
        break;
      }
      if (guard >= MAX_PIECES_PER_STEP) {
        st = sc_fail(msg, SC_EINTERNAL,
                     "sc_fixed_points_find: more than %d itinerary changes "
                     "between d = %.17g and %.17g",
                     MAX_PIECES_PER_STEP, cur.x, nxt.x);
        goto done;
      }
      /* Locate the end of cur's piece by bisection: lo stays on it. */
      lo = cur;
      hi = nxt;
      for (int it = 0; it < MAX_BISECT; it++) {
        if (hi.x - lo.x <= tol_x(s.edge, lo.x)) break;
        double xm = 0.5 * (lo.x + hi.x);
        if (xm <= lo.x || xm >= hi.x) break;
        if ((st = eval(&s, xm, &mid))) goto done;
        if (same_piece(&lo, &mid)) {
          if ((st = bracket(&s, &lo, &mid))) goto done;
          all_neutral = all_neutral && mid.st == SC_OK && mid.v.neutral;
          lo = mid;
        } else {
          hi = mid;
        }
      }
      if ((st = end_piece(&s, piece_lo, &lo, all_neutral))) goto done;
      cur = hi;
      piece_lo = hi.x;
      all_neutral = cur.st == SC_OK && cur.v.neutral;
    }
  }
  if ((st = end_piece(&s, piece_lo, &cur, all_neutral))) goto done;
  if (set->n) qsort(set->o, set->n, sizeof *set->o, by_first_point);
done:
  free(s.pts);
  free(s.itin);
  if (st) {
    sc_orbit_set_free(set);
    return st;
  }
  *out = set;
  return SC_OK;
}

size_t sc_orbit_set_count(const sc_orbit_set *s) { return s->n; }
size_t sc_orbit_set_npieces(const sc_orbit_set *s) { return s->npieces; }
size_t sc_orbit_set_nlower(const sc_orbit_set *s) { return s->nlower; }
size_t sc_orbit_set_nundefined(const sc_orbit_set *s) { return s->nundef; }

int sc_orbit_set_get(const sc_orbit_set *s, size_t i, sc_orbit_info *o) {
  if (i >= s->n) return SC_EINVAL;
  const orbit_rec *r = &s->o[i];
  *o = (sc_orbit_info){.period = r->period, .neutral = r->neutral,
                       .multiplier = r->multiplier, .stable = r->stable,
                       .lo = r->lo, .hi = r->hi, .residual = r->residual,
                       .d = r->d, .itinerary = r->itin};
  return SC_OK;
}

void sc_orbit_set_free(sc_orbit_set *s) {
  if (!s) return;
  for (size_t i = 0; i < s->n; i++) {
    free(s->o[i].d);
    free(s->o[i].itin);
  }
  free(s->o);
  free(s);
}
