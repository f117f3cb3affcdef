/* Branches of periodic orbits of an event map in one parameter: the
 * fixed-point system of f^m continued by the pseudo-arclength layer
 * (continuation.h) along one itinerary code at a time (forced, so f^m is
 * smooth along a segment), folds and flips from its test functions, and
 * the model's borders watched as test functions and located by Newton's
 * method on their defining systems.  See branch.h and docs/branches.md.
 *
 * A segment runs in named steps: segment_start() (the first point, its
 * codes and borders), then per accepted point segment_accept() (record,
 * joins, falls in period), border_crossed() (detect), locate_border()
 * (Newton), hand_over() (the orbit on the other side), and the fallback
 * locate_by_bisection() where the corrector cannot go on. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/border_list.h"
#include "slipcont/branch.h"
#include "slipcont/continuation.h"
#include "slipcont/shooting.h"

const char *sc_point_label_text(sc_point_label l) {
  static const char *t[] = {"LP", "PD", "GR", "CS", "SW", "BR", "TT", "EP"};
  return (unsigned)l < sizeof t / sizeof t[0] ? t[l] : "??";
}

sc_point_label sc_point_label_of_border(sc_border_kind k) {
  switch (k) {
  case SC_BORDER_GRAZING: return SC_PT_GR;
  case SC_BORDER_CROSSING: return SC_PT_CS;
  case SC_BORDER_SWITCHING: return SC_PT_SW;
  case SC_BORDER_BOTH: return SC_PT_BR;
  default: return SC_PT_TT;
  }
}

const char *sc_location_method_text(sc_location_method l) {
  static const char *t[] = {"newton", "bisection", "not-located", ""};
  return (unsigned)l < sizeof t / sizeof t[0] ? t[l] : "";
}

/* The smallest arclength step, relative to hmax: the corrector stops
 * this close to where a forced event disappears, and the bisection with
 * shooting takes over (it locates to newton_atol + newton_rtol |p|). */
#define HMIN_REL 1e-6

/* Parameter offset beyond a located bifurcation at which the orbit on
 * the other side is sought, relative to 1 + |p|: well above the location
 * tolerance (1e-13), small enough that the new orbit is still close to
 * the old one. */
#define CROSS_REL 1e-7

/* An orbit found beyond a bifurcation continues the old one if each of
 * its points lies within this many parameter offsets of an old point
 * (orbit points move with slopes dd/dp of order one to a hundred). */
#define CLOSE_FACTOR 1e3

/* Newton iterations on a border's defining system: from the linear
 * interpolation between two accepted points it converges quadratically
 * in a handful; more means it is not converging. */
#define BORDER_NEWTON_MAX 40

/* A border located by Newton must lie between the two accepted points
 * that bracket its sign change, up to this fraction of their distance
 * (the interpolated start is already inside). */
#define BRACKET_SLACK 0.5

/* How far (relative to 1 + |p|) a border located by Newton from the far
 * side may lie from a bisection bracket and still be the border that
 * bracket found: well below the distance between distinct special
 * points of a branch (1e-4 and more on the chapter's examples). */
#define BISECTION_REACH 1e-6

/* A located fold or flip test is accepted within this many times the
 * preset's residual tolerance (or the continuation layer's default,
 * 1e-8, if larger): the multiplier carries the rounding of f^m times its
 * own conditioning. */
#define TEST_ATOL_FACTOR 1e3

/* Notes longer than this are cut. */
#define NOTE_LEN 640

typedef struct {
  int branch, period, stable;
  double p, d, multiplier;
  double dmin; /* smallest orbit point: the same for every cyclic shift */
  char itin[SC_ITIN_LEN];
} point_rec;

typedef struct {
  sc_point_label label;
  int branch, period;
  double p, d, multiplier, degeneracy, residual, error;
  sc_location_method method;
  int iterations;
  char border[SC_BORDER_NAME];
  char note[NOTE_LEN];
} special_rec;

typedef struct {
  int period, direction;
  double p, d;
  double offset; /* > 0: started this far beyond a located point, which
                    may be moved further if the start fails */
  char origin[96];
} job;

/* What the callbacks of the continuation layer read. */
typedef struct {
  sc_map *m;
  size_t param;
  int period;
  const sc_itin_code *force; /* the segment's codes (a model with borders) */
  char itin[SC_ITIN_LEN];    /* the piece being continued */
  int lock;                  /* 1: stay on that piece (a piecewise-smooth
                                model whose codes could not be forced);
                                0: a smooth map, or forced codes */
} g_ctx;

struct sc_orbit_branch {
  sc_map *m;
  sc_orbit_branch_spec sp;
  size_t npts, cap_pts, nsp, cap_sp;
  point_rec *pts;
  special_rec *sps;
  int nomem;   /* a point or special point could not be stored */
  size_t nduplicate; /* special points met again by another segment */
  job *jobs;
  int njobs, nbranches;
  job *starts; /* added starts (direction unused) */
  int nstarts;
  double *orbit; /* scratch: orbit points, up to max_period + 1 */
  double *seed;
  double *orb_a; /* scratch: the orbit on the known side of a DIB */
  double *orb_c; /* scratch: the orbit at the current point */
  double *orb_f; /* the orbit at the first point of the segment */
  sc_itin_code *codes;  /* the segment's codes (max_period + 2) */
  sc_itin_code *codes2; /* scratch codes */
  sc_itin_code *codes3; /* scratch codes */
  sc_itin_code *codes4; /* a border's defining codes (its own code in) */
  sc_border_list bl_prev, bl_cur, bl_tmp; /* borders (grow as needed) */
  sc_accuracy acc; /* the map's, its Newton tolerances no tighter than the
                      map's precision (sc_map_precision()) */
  sc_shoot **shooters; /* multiple shooting by period, made on first use
                          (max_period + 2 entries) */
  g_ctx ctx;
};

int sc_orbit_branch_alloc(sc_map *m, const sc_orbit_branch_spec *spec,
                          sc_orbit_branch **out, sc_msg *msg) {
  *out = NULL;
  if (!m || !spec)
    return sc_fail(msg, SC_EINVAL, "sc_orbit_branch_alloc: no map or spec");
  const sc_orbit_branch_spec *s = spec;
  if (s->param >= sc_map_nparam(m))
    return sc_fail(msg, SC_EINVAL,
                   "sc_orbit_branch_alloc: param = %zu (valid: [0, %zu))",
                   s->param, sc_map_nparam(m));
  if (!isfinite(s->from) || !isfinite(s->to) || s->from == s->to)
    return sc_fail(msg, SC_EINVAL,
                   "sc_orbit_branch_alloc: from = %g, to = %g (valid: "
                   "finite, different)",
                   s->from, s->to);
  if (isinf(s->d0))
    return sc_fail(msg, SC_EINVAL, "sc_orbit_branch_alloc: d0 = %g (valid: "
                                   "finite, or NaN for no start at from)",
                   s->d0);
  if (s->period < 1 || s->period > 4096)
    return sc_fail(msg, SC_EINVAL,
                   "sc_orbit_branch_alloc: period = %d (valid: [1, 4096])",
                   s->period);
  if (s->max_points < 2 || s->max_points > 10000000)
    return sc_fail(msg, SC_EINVAL,
                   "sc_orbit_branch_alloc: max_points = %ld (valid: [2, "
                   "10000000])",
                   s->max_points);
  if (s->max_branches < 1 || s->max_branches > 1000)
    return sc_fail(msg, SC_EINVAL,
                   "sc_orbit_branch_alloc: max_branches = %d (valid: [1, "
                   "1000])",
                   s->max_branches);
  if (s->max_period < s->period || s->max_period > 4096)
    return sc_fail(msg, SC_EINVAL,
                   "sc_orbit_branch_alloc: max_period = %d (valid: [period, "
                   "4096])",
                   s->max_period);
  if (!(s->h0 >= 0) || !(s->hmax >= 0) || !isfinite(s->h0) ||
      !isfinite(s->hmax))
    return sc_fail(msg, SC_EINVAL,
                   "sc_orbit_branch_alloc: h0 = %g, hmax = %g (valid: >= 0, "
                   "0 for automatic)",
                   s->h0, s->hmax);
  sc_orbit_branch *b = calloc(1, sizeof *b);
  if (!b) return sc_fail(msg, SC_ENOMEM, "sc_orbit_branch_alloc: no memory");
  b->m = m;
  b->sp = *spec;
  b->cap_pts = 256;
  b->cap_sp = 64;
  size_t np = (size_t)s->max_period + 2;
  b->pts = calloc(b->cap_pts, sizeof *b->pts);
  b->sps = calloc(b->cap_sp, sizeof *b->sps);
  b->jobs = calloc((size_t)s->max_branches, sizeof *b->jobs);
  b->starts = calloc((size_t)s->max_branches, sizeof *b->starts);
  b->orbit = calloc(np, sizeof *b->orbit);
  b->seed = calloc(np, sizeof *b->seed);
  b->orb_a = calloc(np, sizeof *b->orb_a);
  b->orb_c = calloc(np, sizeof *b->orb_c);
  b->orb_f = calloc(np, sizeof *b->orb_f);
  b->codes = calloc(np, sizeof *b->codes);
  b->codes2 = calloc(np, sizeof *b->codes2);
  b->codes3 = calloc(np, sizeof *b->codes3);
  b->codes4 = calloc(np, sizeof *b->codes4);
  b->shooters = calloc(np, sizeof *b->shooters);
  sc_border_list *bl[3] = {&b->bl_prev, &b->bl_cur, &b->bl_tmp};
  for (int k = 0; k < 3; k++) {
    bl[k]->cap = 16 * np;
    bl[k]->b = calloc(bl[k]->cap, sizeof *bl[k]->b);
  }
  if (!b->pts || !b->sps || !b->jobs || !b->starts || !b->orbit ||
      !b->seed || !b->orb_a || !b->orb_c || !b->orb_f || !b->codes ||
      !b->codes2 || !b->codes3 || !b->codes4 || !b->shooters || !b->bl_prev.b ||
      !b->bl_cur.b || !b->bl_tmp.b) {
    sc_orbit_branch_free(b);
    return sc_fail(msg, SC_ENOMEM, "sc_orbit_branch_alloc: no memory for "
                                   "period %d",
                   s->max_period);
  }
  *out = b;
  return SC_OK;
}

void sc_orbit_branch_free(sc_orbit_branch *b) {
  if (!b) return;
  free(b->pts);
  free(b->sps);
  free(b->jobs);
  free(b->starts);
  free(b->orbit);
  free(b->seed);
  free(b->orb_a);
  free(b->orb_c);
  free(b->orb_f);
  free(b->codes);
  free(b->codes2);
  free(b->codes3);
  free(b->codes4);
  free(b->bl_prev.b);
  free(b->bl_cur.b);
  free(b->bl_tmp.b);
  if (b->shooters)
    for (int q = 0; q <= b->sp.max_period + 1; q++)
      sc_shoot_free(b->shooters[q]);
  free(b->shooters);
  free(b);
}

size_t sc_orbit_branch_npoints(const sc_orbit_branch *b) { return b->npts; }
size_t sc_orbit_branch_nspecial(const sc_orbit_branch *b) { return b->nsp; }
int sc_orbit_branch_nbranches(const sc_orbit_branch *b) {
  return b->nbranches;
}

int sc_orbit_branch_point(const sc_orbit_branch *b, size_t i,
                          sc_orbit_point_info *pt) {
  if (i >= b->npts) return SC_EINVAL;
  const point_rec *r = &b->pts[i];
  *pt = (sc_orbit_point_info){.branch = r->branch, .period = r->period,
                               .p = r->p, .d = r->d,
                               .multiplier = r->multiplier,
                               .stable = r->stable, .itinerary = r->itin};
  return SC_OK;
}

int sc_orbit_branch_special(const sc_orbit_branch *b, size_t i,
                            sc_orbit_special_info *sp) {
  if (i >= b->nsp) return SC_EINVAL;
  const special_rec *r = &b->sps[i];
  *sp = (sc_orbit_special_info){.label = r->label, .branch = r->branch,
                          .period = r->period, .p = r->p, .d = r->d,
                          .multiplier = r->multiplier,
                          .degeneracy = r->degeneracy,
                          .residual = r->residual, .error = r->error,
                          .method = r->method, .iterations = r->iterations,
                          .border = r->border, .note = r->note};
  return SC_OK;
}

int sc_orbit_branch_add_start(sc_orbit_branch *b, double p, double d,
                              int period, sc_msg *msg) {
  double lo = fmin(b->sp.from, b->sp.to), hi = fmax(b->sp.from, b->sp.to);
  if (!(p >= lo && p <= hi) || !isfinite(d) || period < 1 ||
      period > b->sp.max_period)
    return sc_fail(msg, SC_EINVAL,
                   "sc_orbit_branch_add_start: p = %g, d = %g, period = %d "
                   "(valid: p in [%g, %g], d finite, period in [1, %d])",
                   p, d, period, lo, hi, b->sp.max_period);
  if (b->nstarts >= b->sp.max_branches)
    return sc_fail(msg, SC_ENOMEM,
                   "sc_orbit_branch_add_start: more than max_branches = %d "
                   "starts",
                   b->sp.max_branches);
  b->starts[b->nstarts++] = (job){.period = period, .p = p, .d = d};
  return SC_OK;
}

/* ------------------------------------------------------------------ */

static int set_p(sc_map *m, size_t i, double p) {
  if (sc_map_get_param(m, i) == p) return SC_OK;
  return sc_map_set_param(m, i, p, NULL);
}

/* g = f^m for the continuation layer: along the segment's codes (forced),
 * or on the piece of itinerary ctx->itin only when codes cannot be
 * forced (leaving it is a recoverable failure, so such a segment never
 * crosses a discontinuity of f^m). */
static int g_fn(double x, const double *p, int order, sc_map1d_jet *jet,
                void *user) {
  g_ctx *c = user;
  if (set_p(c->m, c->param, p[c->param])) return 1;
  sc_map_value v;
  unsigned fl = (order ? SC_EVAL_DERIV : 0) | (c->lock ? SC_EVAL_ITINERARY : 0);
  int st = sc_map_iterate_ex(c->m, x, c->period, fl, c->force, NULL, NULL, &v,
                             NULL);
  if (st) return st == SC_EUNDEF || st == SC_ENONFINITE || st == SC_ENOCONV
                     ? 1
                     : -1;
  if (c->lock && (strcmp(v.itinerary, c->itin) != 0 || v.neutral)) return 1;
  if (c->force && v.neutral) return 1;
  jet->g = v.f;
  jet->gx = v.dfdd;
  size_t np = sc_map_nparam(c->m);
  for (size_t i = 0; i < np && i < SC_MAP1D_MAXPARAM; i++)
    jet->gp[i] = v.dfdp[i];
  if (order >= 2) return -1; /* not used by the FIXED system */
  return 0;
}

/* Grow an array of `size`-byte records to hold one more; 0 on failure. */
static int grow(void **a, size_t *cap, size_t n, size_t size) {
  if (n < *cap) return 1;
  void *q = realloc(*a, 2 * *cap * size);
  if (!q) return 0;
  memset((char *)q + *cap * size, 0, *cap * size);
  *a = q;
  *cap *= 2;
  return 1;
}

static void add_point(sc_orbit_branch *b, int branch, int period, double p,
                      double d, const sc_map_value *v, double dmin) {
  if (!grow((void **)&b->pts, &b->cap_pts, b->npts, sizeof *b->pts)) {
    b->nomem = 1;
    return;
  }
  point_rec *r = &b->pts[b->npts++];
  r->dmin = dmin;
  r->branch = branch;
  r->period = period;
  r->p = p;
  r->d = d;
  r->multiplier = v->dfdd;
  r->stable = fabs(v->dfdd) < 1;
  snprintf(r->itin, sizeof r->itin, "%s", v->itinerary);
}

/* Orbits of the same period are the same within SAME_ORBIT_TOL (below),
 * or, for a map known only to its precision P (numerical flows), this
 * many times P. */
#define SAME_ORBIT_PREC 100.0

/* Two special points of one label and period this close in the
 * parameter (relative to 1 + |p|, or the map's precision) are one point
 * met by two branch segments: a flip reached again from the doubled
 * branch, a closed curve traversed from two starts. */
#define SAME_POINT_REL 1e-7

static special_rec *add_special(sc_orbit_branch *b, sc_point_label l,
                                int branch, int period, double p, double d,
                                double mult, double deg) {
  if (l != SC_PT_EP) {
    double tol = SAME_POINT_REL * (1 + fabs(p)) + SAME_ORBIT_PREC *
                                                      sc_map_precision(b->m);
    for (size_t i = 0; i < b->nsp; i++)
      if (b->sps[i].label == l && b->sps[i].period == period &&
          fabs(b->sps[i].p - p) <= tol && b->sps[i].method != SC_LOC_FAILED) {
        b->nduplicate++;
        return NULL; /* reported once; the caller writes nothing more */
      }
  }
  if (!grow((void **)&b->sps, &b->cap_sp, b->nsp, sizeof *b->sps)) {
    b->nomem = 1;
    return NULL;
  }
  special_rec *r = &b->sps[b->nsp++];
  memset(r, 0, sizeof *r);
  *r = (special_rec){.label = l, .branch = branch, .period = period, .p = p,
                     .d = d, .multiplier = mult, .degeneracy = deg,
                     .residual = NAN, .error = NAN,
                     .method = l == SC_PT_EP ? SC_LOC_NONE : SC_LOC_NEWTON};
  return r;
}

/* An end point with its reason. */
static void add_end(sc_orbit_branch *b, int branch, int period, double p,
                    double d, double mult, const char *fmt, const char *a,
                    const char *c) {
  special_rec *r = add_special(b, SC_PT_EP, branch, period, p, d, mult, NAN);
  if (r) snprintf(r->note, sizeof r->note, fmt, a ? a : "", c ? c : "");
}

static int push_job(sc_orbit_branch *b, int period, double p, double d,
                    int direction, double offset, const char *origin) {
  if (b->njobs >= b->sp.max_branches) return 0;
  job *j = &b->jobs[b->njobs++];
  *j = (job){.period = period, .direction = direction, .p = p, .d = d,
             .offset = offset};
  snprintf(j->origin, sizeof j->origin, "%s", origin);
  return 1;
}

/* Shoot a period-q orbit at parameter p from the orbit points seed[0..q-1]
 * (multiple shooting); the orbit into b->orbit. */
static int shoot_at(sc_orbit_branch *b, int q, double p, const double *seed,
                    sc_shoot_result *res) {
  if (set_p(b->m, b->sp.param, p) || q < 1 || q > b->sp.max_period + 1)
    return SC_EINVAL;
  /* One shooting object per period, kept for the whole run. */
  if (!b->shooters[q]) {
    int st = sc_shoot_alloc(b->m, q, SC_SHOOT_MULTIPLE, NULL,
                            &b->shooters[q], NULL);
    if (st) return st;
  }
  sc_shoot *s = b->shooters[q];
  int st = sc_shoot_solve_orbit(s, seed, res, NULL);
  if (st == SC_OK)
    memcpy(b->orbit, sc_shoot_orbit(s), (size_t)q * sizeof(double));
  return st;
}

/* The orbit of d (period q) by iterating, into out; along codes when
 * given. */
static int iterate_orbit_forced(sc_orbit_branch *b, double d, int q,
                                const sc_itin_code *codes, double *out) {
  sc_map_value v;
  out[0] = d;
  for (int i = 1; i < q; i++) {
    int st = sc_map_eval_ex(b->m, out[i - 1], SC_EVAL_VALUE,
                            codes ? &codes[i - 1] : NULL, NULL, NULL, &v,
                            NULL);
    if (st) return st;
    out[i] = v.f;
  }
  return SC_OK;
}

static int iterate_orbit(sc_orbit_branch *b, double d, int q, double *out) {
  return iterate_orbit_forced(b, d, q, NULL, out);
}


/* Every point of orbit a (na) within tol of a point of orbit c (nc). */
static int close_orbits(const double *a, int na, const double *c, int nc,
                        double tol) {
  for (int i = 0; i < na; i++) {
    int ok = 0;
    for (int k = 0; k < nc && !ok; k++) ok = fabs(a[i] - c[k]) <= tol;
    if (!ok) return 0;
  }
  return 1;
}

static int same_code(const sc_itin_code *a, const sc_itin_code *c) {
  return a->n == c->n && memcmp(a->c, c->c, (size_t)a->n) == 0;
}

/* Codes of q iterates equal (a aligned with c shifted by k). */
static int same_codes(const sc_itin_code *a, const sc_itin_code *c, int q,
                      int k) {
  for (int i = 0; i < q; i++)
    if (!same_code(&a[i], &c[(i + k) % q])) return 0;
  return 1;
}

/* f^m at (d, p) with every border (border_list.h); along `force` (NULL:
 * natural) with the codes into `codes`. */
static int orbit_borders(sc_orbit_branch *b, double d, int period,
                         const sc_itin_code *force, sc_itin_code *codes,
                         sc_border_list *bl, sc_map_value *v, sc_msg *msg) {
  return sc_border_list_iterate(b->m, d, period,
                                SC_EVAL_DERIV | SC_EVAL_ITINERARY, force,
                                codes, bl, v, msg);
}

/* ------------------------------------------------------------------ */
/* Locating a border: Newton on its defining system                     */

/* Rounding level of a Newton step on a border's system, in ulps of the
 * unknown: f^m is computed to a few ulps and the system's Jacobian
 * amplifies that near a grazing or a switching; a tolerance below it
 * (the "precise" preset) is met at that floor. */
#define BORDER_NOISE_ULPS 256.0

/* A Newton step on a border's system that is within tolerance, or at
 * the rounding floor. */
static int step_done(double dx, double x, const sc_accuracy *acc) {
  return sc_test_delta(dx, x, acc->newton_atol, acc->newton_rtol) == SC_OK ||
         fabs(dx) <= BORDER_NOISE_ULPS * DBL_EPSILON * (1 + fabs(x));
}

/* What locate_border() found. */
typedef struct {
  int ok;
  double p, d0;   /* the parameter and the orbit's first point */
  double dk;      /* the orbit point where the border is met */
  double m, F;    /* border and orbit residual at the solution */
  double step;    /* last Newton step in p (the error estimate) */
  double mult;    /* (f^m)' there */
  int iterations;
  char why[200];
} border_fix;

/* The border of `like` at (d, p) along the segment's codes. */
static int border_at(sc_orbit_branch *b, int period, double d, double p,
                     const sc_itin_code *codes, const sc_border *like,
                     sc_border *out, sc_map_value *v) {
  if (set_p(b->m, b->sp.param, p)) return SC_EINVAL;
  int st = orbit_borders(b, d, period, codes, NULL, &b->bl_tmp, v, NULL);
  if (st) return st;
  const sc_border *x = sc_border_list_find(&b->bl_tmp, like);
  if (!x) return SC_EUNDEF;
  *out = *x;
  return SC_OK;
}

/* Newton in (d0, p) on {f^m(d0) - d0 = 0, m_k(d0, p) = 0} from the
 * interpolation between (pa, da) and (pb, db); the codes are those of the
 * segment. */
static void newton_2d(sc_orbit_branch *b, int period, const sc_itin_code *codes,
                      const sc_border *like, double pa, double da, double ma,
                      double pb, double db, double mb, border_fix *fx) {
  const sc_accuracy *acc = &b->acc;
  size_t ip = b->sp.param;
  double t = ma / (ma - mb);
  if (!(t >= 0 && t <= 1)) t = 0.5;
  double p = pa + t * (pb - pa), d = da + t * (db - da);
  sc_map_value v;
  sc_border bd;
  for (int it = 0; it < BORDER_NEWTON_MAX; it++) {
    int st = border_at(b, period, d, p, codes, like, &bd, &v);
    if (st) {
      snprintf(fx->why, sizeof fx->why,
               "the defining system cannot be evaluated at %s = %.17g, "
               "d = %.17g (%s)",
               sc_map_type(b->m)->params[ip].name, p, d, sc_strerror(st));
      return;
    }
    double F = v.f - d;
    double J11 = v.dfdd - 1, J12 = v.dfdp[ip], J21 = bd.dd, J22 = bd.dp[ip];
    double det = J11 * J22 - J12 * J21;
    fx->m = bd.value, fx->F = F, fx->mult = v.dfdd, fx->iterations = it;
    if (!isfinite(det) || det == 0) {
      snprintf(fx->why, sizeof fx->why,
               "singular Jacobian of the defining system (det %.3g)", det);
      return;
    }
    double dd = (F * J22 - J12 * bd.value) / det;
    double dpp = (J11 * bd.value - F * J21) / det;
    d -= dd;
    p -= dpp;
    fx->step = fabs(dpp);
    if (step_done(dpp, p, acc) && step_done(dd, d, acc)) {
      /* the certificate: the system at the returned point */
      if (border_at(b, period, d, p, codes, like, &bd, &v)) {
        snprintf(fx->why, sizeof fx->why,
                 "the last Newton point cannot be evaluated");
        return;
      }
      fx->ok = 1;
      fx->p = p, fx->d0 = d, fx->m = bd.value, fx->F = v.f - d;
      fx->mult = v.dfdd, fx->iterations = it + 1;
      return;
    }
  }
  snprintf(fx->why, sizeof fx->why,
           "Newton did not converge in %d iterations (last step %.3g in "
           "the parameter)",
           BORDER_NEWTON_MAX, fx->step);
}

/* A border in the state itself (m = +-(d_k - d_on(p))): Newton in p on
 * G(p) = f^m(d_on(p)) - d_on(p) with the orbit started on the border at
 * iterate k (the codes rotated to start there).  The map may be singular
 * next to such a border, the orbit through it is not. */
static void newton_on_state(sc_orbit_branch *b, int period,
                            const sc_itin_code *codes, const sc_border *like,
                            double pa, double ma, double pb, double mb,
                            border_fix *fx) {
  const sc_accuracy *acc = &b->acc;
  size_t ip = b->sp.param;
  int k = like->iterate;
  for (int i = 0; i < period; i++) b->codes3[i] = codes[(i + k) % period];
  double t = ma / (ma - mb);
  if (!(t >= 0 && t <= 1)) t = 0.5;
  double p = pa + t * (pb - pa);
  sc_map_value v;
  for (int it = 0; it < BORDER_NEWTON_MAX; it++) {
    /* d_on(p): the border of any one iterate at p says where it is */
    sc_border_list *l = &b->bl_tmp;
    if (set_p(b->m, ip, p) ||
        sc_map_eval_ex(b->m, like->d_on, SC_EVAL_VALUE, NULL, NULL,
                       (l->n = 0, l), &v, NULL)) {
      snprintf(fx->why, sizeof fx->why, "cannot evaluate the map at %.17g",
               p);
      return;
    }
    double don = NAN, don_p = NAN;
    for (size_t i = 0; i < l->n && i < l->cap; i++)
      if (l->b[i].on_state) don = l->b[i].d_on, don_p = l->b[i].d_on_dp[ip];
    int st = sc_map_iterate_ex(b->m, don, period, SC_EVAL_DERIV, b->codes3,
                               NULL, NULL, &v, NULL);
    if (st || !isfinite(don)) {
      snprintf(fx->why, sizeof fx->why,
               "the orbit from the border cannot be evaluated at %.17g (%s)",
               p, sc_strerror(st));
      return;
    }
    double G = v.f - don;
    double Gp = v.dfdp[ip] + (v.dfdd - 1) * don_p;
    fx->F = G, fx->m = 0, fx->mult = v.dfdd, fx->iterations = it;
    if (!isfinite(Gp) || Gp == 0) {
      snprintf(fx->why, sizeof fx->why, "singular derivative (%.3g)", Gp);
      return;
    }
    double dp = G / Gp;
    if (fx->iterations > 0 && step_done(dp, p, acc)) {
      fx->ok = 1;
      fx->p = p, fx->dk = don, fx->step = fabs(dp);
      fx->iterations = it + 1;
      /* the orbit's first point: iterate back is not possible; report
       * the continued point by iterating forward the remaining steps */
      double *o = b->seed;
      if (iterate_orbit_forced(b, don, period, b->codes3, o) == SC_OK)
        fx->d0 = o[(period - k) % period];
      else
        fx->d0 = NAN;
      return;
    }
    p -= dp;
    fx->step = fabs(dp);
  }
  snprintf(fx->why, sizeof fx->why,
           "Newton did not converge in %d iterations (last step %.3g)",
           BORDER_NEWTON_MAX, fx->step);
}

static void locate_border(sc_orbit_branch *b, int period,
                          const sc_itin_code *codes, const sc_border *like,
                          double pa, double da, double ma, double pb,
                          double db, double mb, border_fix *fx) {
  memset(fx, 0, sizeof *fx);
  /* the border's own code for its iterate, where it has one */
  if (like->alt.n > 0) {
    sc_itin_code *c = b->codes4;
    for (int i = 0; i < period; i++) c[i] = codes[i];
    c[like->iterate] = like->alt;
    codes = c;
  }
  if (like->on_state)
    newton_on_state(b, period, codes, like, pa, ma, pb, mb, fx);
  else
    newton_2d(b, period, codes, like, pa, da, ma, pb, db, mb, fx);
  if (!fx->ok) return;
  /* It must lie between the two points that bracket the sign change. */
  double lo = fmin(pa, pb), hi = fmax(pa, pb);
  double w = BRACKET_SLACK * (hi - lo) + BISECTION_REACH * (1 + fabs(pa));
  if (fx->p < lo - w || fx->p > hi + w) {
    fx->ok = 0;
    snprintf(fx->why, sizeof fx->why,
             "Newton converged to %.17g, outside the bracket [%.17g, %.17g]",
             fx->p, lo, hi);
    return;
  }
  double *o = b->seed;
  if (!like->on_state) {
    if (set_p(b->m, b->sp.param, fx->p) ||
        iterate_orbit_forced(b, fx->d0, period, codes, o)) {
      fx->ok = 0;
      snprintf(fx->why, sizeof fx->why, "the located orbit cannot be "
                                        "iterated");
      return;
    }
    fx->dk = o[like->iterate];
  }
  /* The orbit located must be the segment's, not one of lower period
   * through the same border (bk2 with beta = 1: the synchronous orbit
   * d = d* = 0 is a fixed point of every f^m). */
  int q = sc_orbit_minimal_period(o, period, 1e-9 * (1 + fabs(o[0])));
  if (q < period) {
    fx->ok = 0;
    snprintf(fx->why, sizeof fx->why,
             "Newton converged to an orbit of minimal period %d, not %d", q,
             period);
  }
}

/* ------------------------------------------------------------------ */
/* Handing over to the other side of a located point                    */

/* The first iterate whose itinerary differs between the f^m itineraries
 * @p a and @p c ('|'-separated): "iterate K: A -> C", or "" if none. */
static void first_change(const char *a, const char *c, char *out,
                         size_t len) {
  char what[SC_ITIN_LEN * 2 + 8];
  int k = sc_first_change(a, c, '|', what, sizeof what);
  if (k) snprintf(out, len, "iterate %d: %.*s", k, (int)(len > 20 ? len - 20 : 0), what);
  else if (len) out[0] = '\0';
}

/* After a located point at p (orbit orb of period m on the segment's side,
 * codes cod, itinerary itin), look for the orbit on the other side (dir)
 * and queue it.  Writes what followed into the record's note. */
static int hand_over(sc_orbit_branch *b, special_rec *r, int m,
                     const sc_itin_code *cod, const char *itin, double p,
                     double *orb, int dir) {
  char base[NOTE_LEN];
  snprintf(base, sizeof base, "%s", r ? r->note : "");
  /* Offsets from CROSS_REL up: next to a switching with the driver
   * frozen f' grows like |d - d*|^(-1/2), and shooting needs the orbit a
   * little away from d*. */
  for (double off = CROSS_REL; off <= 1e3 * CROSS_REL; off *= 10) {
  double pc = p + dir * off * (1 + fabs(p));
  if (pc < fmin(b->sp.from, b->sp.to) || pc > fmax(b->sp.from, b->sp.to))
    break;
  double tol = CLOSE_FACTOR * off * (1 + fabs(p));
  const int qs[3] = {m, m - 1, m + 1};
  for (int iq = 0; iq < 3; iq++) {
    int q = qs[iq];
    if (q < 1 || q > b->sp.max_period) continue;
    for (int k = 0; k < m; k++) {
      if (set_p(b->m, b->sp.param, pc)) break;
      if (iterate_orbit(b, orb[k], q, b->seed)) continue;
      sc_shoot_result res;
      if (shoot_at(b, q, pc, b->seed, &res) != SC_OK) continue;
      if (q == m) {
        /* the same orbit still: not the other side */
        int same = strcmp(res.itinerary, itin) == 0;
        if (same && cod && sc_map_has_borders(b->m)) {
          sc_map_value v;
          same = orbit_borders(b, b->orbit[0], q, NULL, b->codes2,
                               &b->bl_tmp, &v, NULL) == SC_OK &&
                 same_codes(b->codes2, cod, q, k);
        }
        if (same) continue;
      }
      if (sc_orbit_minimal_period(b->orbit, q, 1e-9) != q) continue;
      if (!close_orbits(b->orbit, q, orb, m, tol)) continue;
      char origin[96];
      snprintf(origin, sizeof origin, "%s at %.10g",
               r ? sc_point_label_text(r->label) : "point", p);
      int queued = push_job(b, q, pc, b->orbit[0], dir, fabs(pc - p), origin);
      char change[160] = "";
      first_change(itin, res.itinerary, change, sizeof change);
      if (r)
        snprintf(r->note, sizeof r->note,
                 "%.360s; %sthe branch continues with period %d%s%.150s",
                 base, queued ? "" : "not followed (max-branches): ", q,
                 change[0] ? " (" : "", change);
      if (r && change[0]) strncat(r->note, ")", sizeof r->note - strlen(r->note) - 1);
      return SC_OK;
    }
  }
  }
  if (r)
    snprintf(r->note, sizeof r->note,
             "%.400s; no orbit on the other side: the branch ends here",
             base);
  return SC_END;
}

/* Record a located (or not located) border point. */
static special_rec *record_border(sc_orbit_branch *b, int branch, int period,
                                  const sc_border *bd, const border_fix *fx,
                                  double p_est, double d_est, double width) {
  sc_point_label l = sc_point_label_of_border(bd->kind);
  special_rec *r;
  if (fx->ok) {
    r = add_special(b, l, branch, period, fx->p, fx->dk, fx->mult, fx->m);
    if (!r) return NULL;
    r->residual = fmax(fabs(fx->F), fabs(fx->m));
    r->error = fx->step;
    r->iterations = fx->iterations;
    snprintf(r->note, sizeof r->note,
             "%s of iterate %d: %s; Newton on {f^%d(d) = d, border = 0}, %d "
             "iterations, residual %.2g",
             sc_point_label_text(l), bd->iterate + 1, bd->name, period,
             fx->iterations, r->residual);
  } else {
    r = add_special(b, l, branch, period, p_est, d_est, NAN, bd->value);
    if (!r) return NULL;
    r->method = SC_LOC_FAILED;
    r->error = width;
    snprintf(r->note, sizeof r->note,
             "NOT LOCATED: %s of iterate %d (%s) changed sign here but %s",
             sc_point_label_text(l), bd->iterate + 1, bd->name, fx->why);
  }
  snprintf(r->border, sizeof r->border, "%s", bd->name);
  return r;
}

/* ------------------------------------------------------------------ */
/* Fallback: bisection on a change of itinerary code                     */

/* Whether the natural orbit found by shooting at p from orb_a still has
 * the segment's codes (or itinerary, for a model without codes). */
static int on_piece(sc_orbit_branch *b, int m, double p, double *orb_a,
                    const sc_shoot_result *res) {
  (void)p;
  (void)orb_a;
  if (strcmp(res->itinerary, b->ctx.itin) != 0) return 0;
  if (!b->ctx.force) return 1;
  sc_map_value v;
  return orbit_borders(b, b->orbit[0], m, NULL, b->codes2, &b->bl_tmp, &v,
                       NULL) == SC_OK &&
         same_codes(b->codes2, b->codes, m, 0);
}

/* Locate where the piece of the period-m orbit ends, between pa (orbit
 * points orb_a, on the piece) and beyond in direction dir.  Returns SC_OK
 * with the bracket [pa, pb] and orb_a updated, or SC_ENOCONV if the piece
 * does not end within the offsets tried. */
static int locate_by_bisection(sc_orbit_branch *b, int m, double *pa,
                               double *pb, double *orb_a, double hmin,
                               int dir) {
  const sc_accuracy *acc = &b->acc;
  double p0 = *pa, pmin = fmin(b->sp.from, b->sp.to),
         pmax = fmax(b->sp.from, b->sp.to);
  sc_shoot_result res;
  /* An offset beyond which the piece has ended: grow from hmin. */
  double w = 4 * hmin, lo = p0, hi = NAN;
  for (int k = 0; k < 40; k++, w *= 2) {
    double p = p0 + dir * w;
    if (p < pmin || p > pmax) p = dir > 0 ? pmax : pmin;
    int st = shoot_at(b, m, p, orb_a, &res);
    if (st != SC_OK || !on_piece(b, m, p, orb_a, &res)) {
      hi = p;
      break;
    }
    lo = p;
    memcpy(orb_a, b->orbit, (size_t)m * sizeof *orb_a);
    if (p == pmin || p == pmax || w > 1e-2 * (pmax - pmin)) break;
  }
  if (isnan(hi)) return SC_ENOCONV;
  for (int it = 0; it < 200; it++) {
    if (fabs(hi - lo) <= acc->newton_atol + acc->newton_rtol * fabs(lo))
      break;
    double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    int st = shoot_at(b, m, mid, orb_a, &res);
    if (st == SC_OK && on_piece(b, m, mid, orb_a, &res)) {
      lo = mid;
      memcpy(orb_a, b->orbit, (size_t)m * sizeof *orb_a);
    } else {
      hi = mid;
    }
  }
  *pa = lo;
  *pb = hi;
  return SC_OK;
}

/* After a bisection bracket [pa, pb] (orbit orb on the segment's side):
 * the orbit just beyond, its borders, and the one that vanishes at the
 * bracket located by Newton from that side (where it is smooth).  Records
 * the point, hands over, and returns. */
static void after_bisection(sc_orbit_branch *b, int branch, int m, double pa,
                            double pb, double *orb, int dir) {
  const char *pname = sc_map_type(b->m)->params[b->sp.param].name;
  char itin[SC_ITIN_LEN];
  snprintf(itin, sizeof itin, "%s", b->ctx.itin);
  /* the orbit beyond the bracket, by shooting from the old one */
  sc_shoot_result res;
  int have = 0;
  double pc = pb + dir * CROSS_REL * (1 + fabs(pb));
  for (int k = 0; k < m && !have; k++) {
    if (set_p(b->m, b->sp.param, pc) || iterate_orbit(b, orb[k], m, b->seed))
      continue;
    have = shoot_at(b, m, pc, b->seed, &res) == SC_OK &&
           close_orbits(b->orbit, m, orb, m,
                        CLOSE_FACTOR * CROSS_REL * (1 + fabs(pb)));
  }
  border_fix best = {0};
  sc_border bbest;
  memset(&bbest, 0, sizeof bbest);
  if (have && sc_map_has_borders(b->m)) {
    sc_map_value v;
    double dc = b->orbit[0];
    if (orbit_borders(b, dc, m, NULL, b->codes2, &b->bl_cur, &v, NULL) ==
        SC_OK) {
      /* the border nearest to zero ahead (backwards from this side) */
      double tbest = HUGE_VAL;
      for (size_t i = 0; i < b->bl_cur.n && i < b->bl_cur.cap; i++) {
        const sc_border *x = &b->bl_cur.b[i];
        double rate = fabs(x->dp[b->sp.param]) + 1e-300;
        double t = x->value / rate;
        if (x->value >= 0 && t < tbest) tbest = t, bbest = *x;
      }
      if (isfinite(tbest)) {
        double mb = -bbest.value; /* mirror: a bracket for the interpolation */
        locate_border(b, m, b->codes2, &bbest, pc, dc, bbest.value, pa,
                      orb[0], mb, &best);
        /* Shooting fails next to a switching with the driver frozen (f'
         * grows like |d - d*|^(-1/2)), so the bisection can stop short of
         * the border by far more than its bracket: a certified solution
         * of the border's system this close is that border. */
        if (best.ok && fabs(best.p - pa) > 1e3 * fabs(pb - pa) +
                                               BISECTION_REACH *
                                                   (1 + fabs(pa))) {
          best.ok = 0;
          snprintf(best.why, sizeof best.why,
                   "Newton from the other side converged to %s = %.17g, "
                   "away from the bisection bracket",
                   pname, best.p);
        }
      }
    }
  }
  special_rec *r;
  if (best.ok) {
    r = record_border(b, branch, m, &bbest, &best, pa, orb[0], pb - pa);
    if (r) {
      size_t n = strlen(r->note);
      snprintf(r->note + n, sizeof r->note - n,
               " (found where the corrector stopped; located from the side "
               "where it is smooth, bisection bracket %.2g)",
               fabs(pb - pa));
    }
  } else {
    sc_point_label l = bbest.name[0] ? sc_point_label_of_border(bbest.kind)
                                     : SC_PT_GR;
    sc_map_value va;
    double mult = NAN;
    if (!set_p(b->m, b->sp.param, pa) &&
        !sc_map_iterate(b->m, orb[0], m, SC_EVAL_DERIV, &va, NULL))
      mult = va.dfdd;
    r = add_special(b, l, branch, m, pa, orb[0], mult,
                    bbest.name[0] ? bbest.value : NAN);
    if (r) {
      r->method = SC_LOC_BISECTION;
      r->error = fabs(pb - pa);
      snprintf(r->border, sizeof r->border, "%s", bbest.name);
      snprintf(r->note, sizeof r->note,
               "located by BISECTION (fallback) on a change of itinerary, "
               "bracket %.2g; %s%s%s",
               fabs(pb - pa),
               bbest.name[0] ? "nearest border beyond: " : "no border known",
               bbest.name, best.why[0] ? "; Newton: " : "");
      if (best.why[0])
        strncat(r->note, best.why, sizeof r->note - strlen(r->note) - 1);
    }
  }
  hand_over(b, r, m, b->ctx.force ? b->codes : NULL, itin, pa, orb, dir);
}

/* ------------------------------------------------------------------ */
/* Flips, joins                                                          */

/* At a located flip (p, d) of the period-m branch: the period-2m orbit
 * born there, sought on either side from d displaced along the
 * eigendirection (in one dimension: d itself). */
static int switch_flip(sc_orbit_branch *b, int m, double p, double d) {
  if (2 * m > b->sp.max_period) return 0;
  /* Offsets from the middle: small ones leave the new orbit nearly
   * degenerate (its multiplier is +1 at the flip), large ones may pass
   * the next bifurcation. */
  const double rel[4] = {1e-4, 1e-5, 1e-3, 1e-6};
  const double amp[3] = {0.3, 1, 0.1};
  for (int i = 0; i < 4; i++) {
    double dp = rel[i] * fmax(1, fabs(p)) * fabs(b->sp.to - b->sp.from) /
                (1 + fabs(b->sp.to - b->sp.from));
    for (int side = -1; side <= 1; side += 2) {
      double ps = p + side * dp;
      if (ps < fmin(b->sp.from, b->sp.to) || ps > fmax(b->sp.from, b->sp.to))
        continue;
      for (int ia = 0; ia < 6; ia++) {
        double eps = (ia % 2 ? -1 : 1) * sqrt(dp) * amp[ia / 2] * (1 + fabs(d));
        if (set_p(b->m, b->sp.param, ps)) continue;
        if (iterate_orbit(b, d + eps, 2 * m, b->seed)) continue;
        sc_shoot_result res;
        if (shoot_at(b, 2 * m, ps, b->seed, &res) != SC_OK) continue;
        if (sc_orbit_minimal_period(b->orbit, 2 * m, 1e-9) != 2 * m) continue;
        if (fabs(b->orbit[0] - d) > 100 * sqrt(dp) * (1 + fabs(d))) continue;
        char origin[96];
        snprintf(origin, sizeof origin, "PD at %.10g", p);
        return push_job(b, 2 * m, ps, b->orbit[0], side, dp, origin);
      }
    }
  }
  return 0;
}

/* Orbits of the same period on two branches are the same orbit when
 * their point sets agree to this: far above the shooting accuracy, far
 * below the distance between distinct orbits. */
#define SAME_ORBIT_TOL 1e-8


static double same_orbit_tol(const sc_orbit_branch *b) {
  return fmax(SAME_ORBIT_TOL, SAME_ORBIT_PREC * sc_map_precision(b->m));
}

size_t sc_orbit_branch_nduplicate(const sc_orbit_branch *b) {
  return b->nduplicate;
}

/* Whether the orbit at (p, b->orb_c) lies on a branch computed before
 * this one: returns that branch, or -1.  Points near this segment's
 * own start (within 2 hmax) are not compared, so that a start continued
 * both ways does not join its twin at once.  Candidates are the points
 * within hmax in p whose smallest orbit point is near; the orbit is then
 * followed from the candidate to p by shooting and compared as a point
 * set. */
static int joins(sc_orbit_branch *b, int branch, int period, double p,
                 double dmin, double p0, double d0, double hmax, int moved) {
  if (!moved && fabs(p - p0) + fabs(dmin - d0) <= 2 * hmax) return -1;
  for (size_t i = 0; i < b->npts; i++) {
    const point_rec *r = &b->pts[i];
    if (r->period != period || r->branch == branch) continue;
    double dp = fabs(r->p - p);
    if (dp > hmax || fabs(r->dmin - dmin) > 1e-3 + 10 * dp) continue;
    if (fabs(r->p - p0) + fabs(r->dmin - d0) <= 2 * hmax)
      continue; /* the twin's start: compared once this one moved on */
    if (set_p(b->m, b->sp.param, r->p) ||
        iterate_orbit(b, r->d, period, b->seed))
      continue;
    sc_shoot_result res;
    if (shoot_at(b, period, p, b->seed, &res) != SC_OK) continue;
    if (close_orbits(b->orbit, period, b->orb_c, period, same_orbit_tol(b)))
      return r->branch;
  }
  return -1;
}

/* ------------------------------------------------------------------ */
/* One segment in named steps                                            */

typedef struct {
  const job *jb;
  int branch, period;
  sc_branch *br;
  sc_cont_settings set;
  double last_p, last_d, last_t, last_td, last_mult;
  double p_first, dmin_first, prev_p;
  int moved;
  unsigned long nrej; /* rejected LP/PD locations seen so far */
} segment;

/* The start: the codes of the orbit at the first point (forced from now
 * on where the model has them), the continuation problem and its start
 * (moved further along when the start next to a located point fails). */
static int segment_start(sc_orbit_branch *b, segment *S, sc_cont_problem *pb,
                         sc_map1d_system *sys, sc_msg *msg) {
  sc_map *m = b->m;
  const job *jb = S->jb;
  int period = S->period;
  sc_map_value v;
  if (set_p(m, b->sp.param, jb->p))
    return sc_fail(msg, SC_EINVAL, "branch: %s = %.17g out of range",
                   sc_map_type(m)->params[b->sp.param].name, jb->p);
  int forced = sc_map_has_borders(m);
  int st = forced ? orbit_borders(b, jb->d, period, NULL, b->codes,
                                  &b->bl_prev, &v, msg)
                  : sc_map_iterate(m, jb->d, period,
                                   SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v, msg);
  if (st) return st;
  for (int i = 0; forced && i < period; i++) forced = b->codes[i].n > 0;
  b->ctx = (g_ctx){.m = m, .param = b->sp.param, .period = period,
                   .force = forced ? b->codes : NULL,
                   .lock = sc_map_has_borders(m) && !forced};
  snprintf(b->ctx.itin, sizeof b->ctx.itin, "%s", v.itinerary);
  *sys = (sc_map1d_system){.fn = g_fn, .user = &b->ctx,
                           .kind = SC_MAP1D_FIXED, .np = sc_map_nparam(m),
                           .ifree = {(int)b->sp.param, 0}};
  for (size_t i = 0; i < sys->np; i++) sys->p[i] = sc_map_get_param(m, i);
  if ((st = sc_map1d_problem(sys, pb, msg))) return st;
  double range = fabs(b->sp.to - b->sp.from);
  sc_cont_settings *set = &S->set;
  sc_cont_settings_default(set);
  set->hmax = b->sp.hmax > 0 ? b->sp.hmax : range / 40;
  set->h0 = b->sp.h0 > 0 ? fmin(b->sp.h0, set->hmax) : set->hmax / 10;
  set->hmin = set->hmax * HMIN_REL;
  set->pmin = fmin(b->sp.from, b->sp.to);
  set->pmax = fmax(b->sp.from, b->sp.to);
  set->direction = jb->direction;
  set->max_points = b->sp.max_points;
  set->linsolve = b->sp.linsolve;
  /* A fold or flip test (a multiplier -+ 1) is known to the accuracy of
   * the map's derivative, which the preset sets: a looser preset must
   * not turn a fold into "not located". */
  set->test_atol = fmax(set->test_atol,
                        TEST_ATOL_FACTOR * b->acc.newton_ftol);
  /* Starts next to a flip or a switching are ill conditioned at fixed
   * parameter: let the start move along the branch instead. */
  set->start_free = 1;
  if ((st = sc_branch_alloc(pb, set, &b->acc, &S->br, msg)))
    return st;
  double u0[2] = {jb->d, jb->p};
  st = sc_branch_set(S->br, u0, msg);
  /* A start just beyond a located point may sit where the orbit is
   * nearly singular (f' grows like |d - d*|^(-1/2) near a switching):
   * move it further along, ten times at a time. */
  double off = jb->offset;
  for (int k = 0; st && off > 0 && k < 4; k++) {
    double p1 = jb->p + jb->direction * 9 * off;
    off *= 10;
    if (p1 < set->pmin || p1 > set->pmax || set_p(m, b->sp.param, p1)) break;
    if (iterate_orbit(b, jb->d, period, b->seed)) break;
    sc_shoot_result res;
    /* The orbit found must still be of minimal period `period`: next to a
     * flip the doubled period-m/2 orbit has the same itinerary and is a
     * fixed point of f^period too, and continuing it would follow the
     * old branch twice over. */
    if (shoot_at(b, period, p1, b->seed, &res) != SC_OK ||
        strcmp(res.itinerary, b->ctx.itin) != 0 ||
        sc_orbit_minimal_period(b->orbit, period, 1e-9) != period)
      continue;
    u0[0] = b->orbit[0];
    u0[1] = p1;
    st = sc_branch_set(S->br, u0, msg);
  }
  if (st) {
    char why[SC_MSG_LEN];
    snprintf(why, sizeof why, "%s", msg ? msg->text : "");
    add_end(b, S->branch, period, jb->p, jb->d, v.dfdd,
            "start failed (%s): %.300s", sc_strerror(st), why);
    return SC_END;
  }
  /* the borders at the corrected start are the reference */
  const double *u = sc_branch_point(S->br);
  if (b->ctx.force && set_p(m, b->sp.param, u[1]) == SC_OK)
    orbit_borders(b, u[0], period, b->codes, NULL, &b->bl_prev, &v, NULL);
  S->last_p = u[1], S->last_d = u[0], S->last_t = jb->direction;
  S->last_td = 0;
  S->last_mult = v.dfdd;
  S->p_first = S->dmin_first = S->prev_p = NAN;
  S->nrej = sc_branch_nrejected_special(S->br);
  return SC_OK;
}

/* Detect: a border of the orbit at (u) that changed sign since the last
 * accepted point (whose borders are in bl_prev).  Locates every such
 * border, records the one met first, hands over, and returns 1; 0 when
 * none changed sign.  The borders at u are left in bl_cur. */
static int border_crossed(sc_orbit_branch *b, segment *S, const double *u) {
  if (!b->ctx.force) return 0;
  int period = S->period;
  sc_map_value v;
  if (set_p(b->m, b->sp.param, u[1]) ||
      orbit_borders(b, u[0], period, b->codes, NULL, &b->bl_cur, &v, NULL))
    return 0; /* the corrector accepted it, so this does not happen */
  int dir = u[1] > S->last_p ? 1 : -1;
  border_fix best = {0}, fx;
  sc_border bbest, bfail;
  int nfail = 0, nchanged = 0;
  char whyfail[200] = "";
  double dist_best = HUGE_VAL;
  for (size_t i = 0; i < b->bl_cur.n && i < b->bl_cur.cap; i++) {
    const sc_border *c = &b->bl_cur.b[i];
    if (c->value > 0) continue;
    const sc_border *a = sc_border_list_find(&b->bl_prev, c);
    if (!a || !(a->value > 0)) continue;
    nchanged++;
    sc_border like = *c;
    locate_border(b, period, b->codes, &like, S->last_p, S->last_d, a->value,
                  u[1], u[0], c->value, &fx);
    if (!fx.ok) {
      if (!nfail) bfail = like, snprintf(whyfail, sizeof whyfail, "%s", fx.why);
      nfail++;
      continue;
    }
    double dist = fabs(fx.p - S->last_p);
    if (dist < dist_best) dist_best = dist, best = fx, bbest = like;
  }
  if (!nchanged) return 0;
  special_rec *r;
  double *orb = b->orb_a;
  if (best.ok) {
    r = record_border(b, S->branch, period, &bbest, &best, 0, 0, 0);
    if (r && nchanged > 1) {
      size_t n = strlen(r->note);
      snprintf(r->note + n, sizeof r->note - n,
               "; %d other border(s) changed sign in the same step, beyond "
               "it (the orbit there is not real)",
               nchanged - 1);
    }
    set_p(b->m, b->sp.param, best.p);
    if (iterate_orbit_forced(b, best.d0, period, b->codes, orb))
      memcpy(orb, b->orb_c, (size_t)period * sizeof *orb);
    hand_over(b, r, period, b->codes, b->ctx.itin, best.p, orb, dir);
    return 1;
  }
  /* None located: say so (the row is replaced if the fallback below
   * locates the point), and let the caller fall back to a bisection from
   * the last point. */
  fx = (border_fix){0};
  snprintf(fx.why, sizeof fx.why, "%s", whyfail);
  r = record_border(b, S->branch, period, &bfail, &fx, S->last_p, S->last_d,
                    fabs(u[1] - S->last_p));
  if (r && nfail > 1) {
    size_t n = strlen(r->note);
    snprintf(r->note + n, sizeof r->note - n,
             "; %d border(s) changed sign in this step, none located",
             nfail);
  }
  return 2;
}

/* Accept the point u: its minimal period, the record, joins and closing.
 * Returns 1 when the segment ends here. */
static int segment_accept(sc_orbit_branch *b, segment *S, const double *u) {
  sc_map *m = b->m;
  int period = S->period;
  set_p(m, b->sp.param, u[1]);
  double dmin = u[0];
  int have_orbit =
      !iterate_orbit_forced(b, u[0], period, b->ctx.force, b->orb_c);
  if (have_orbit)
    for (int k = 1; k < period; k++) dmin = fmin(dmin, b->orb_c[k]);
  /* A period-m segment whose orbit has fallen to a divisor of m has
   * left its branch for a lower-period one crossing it (the doubled
   * orbit at a flip): stop rather than follow the old branch again. */
  int q = have_orbit && period > 1
              ? sc_orbit_minimal_period(b->orb_c, period, 1e-9 * (1 + fabs(u[0])))
              : period;
  if (q < period) {
    /* Follow the lower-period branch from here instead, both ways, with
     * its own period (joins() stops it where it was computed before). */
    char origin[96];
    snprintf(origin, sizeof origin, "period-%d segment at %.10g", period,
             u[1]);
    int pushed = push_job(b, q, u[1], u[0], 1, 0, origin);
    pushed += push_job(b, q, u[1], u[0], -1, 0, origin);
    /* The end is the last point of minimal period `period` (the segment
     * met the period-q branch between it and this one). */
    int first = isnan(S->p_first);
    special_rec *r = add_special(b, SC_PT_EP, S->branch, period,
                                 first ? u[1] : S->last_p,
                                 first ? u[0] : S->last_d, S->last_mult,
                                 NAN);
    if (r)
      snprintf(r->note, sizeof r->note,
               "the segment met the period-%d branch between here and "
               "%.12g, where the orbit's minimal period is %d: it ends "
               "here%s",
               q, u[1], q, pushed ? "; that branch is followed" : "");
    return 1;
  }
  sc_map_value v;
  set_p(m, b->sp.param, u[1]);
  if (sc_map_iterate_ex(m, u[0], period, SC_EVAL_DERIV | SC_EVAL_ITINERARY,
                        b->ctx.force, NULL, NULL, &v, NULL) == SC_OK) {
    add_point(b, S->branch, period, u[1], u[0], &v, dmin);
    S->last_mult = v.dfdd;
  }
  if (isnan(S->p_first)) {
    S->p_first = u[1], S->dmin_first = dmin;
    memcpy(b->orb_f, b->orb_c, (size_t)period * sizeof *b->orb_f);
  }
  if (fabs(u[1] - S->p_first) + fabs(dmin - S->dmin_first) > 4 * S->set.hmax)
    S->moved = 1;
  int jn = joins(b, S->branch, period, u[1], dmin, S->p_first, S->dmin_first,
                 S->set.hmax, S->moved);
  /* Back at the start after going away: the step from the previous
   * point crosses the start's parameter, and the orbit there, followed
   * by shooting from this point, is the start's orbit. */
  if (jn < 0 && S->moved &&
      (S->prev_p - S->p_first) * (u[1] - S->p_first) <= 0) {
    sc_shoot_result res;
    memcpy(b->orb_a, b->orb_c, (size_t)period * sizeof *b->orb_a);
    if (shoot_at(b, period, S->p_first, b->orb_a, &res) == SC_OK &&
        close_orbits(b->orbit, period, b->orb_f, period, same_orbit_tol(b)))
      jn = S->branch;
  }
  S->prev_p = u[1];
  if (jn >= 0) {
    special_rec *r = add_special(b, SC_PT_EP, S->branch, period, u[1], u[0],
                                 v.dfdd, NAN);
    if (r) {
      if (jn == S->branch)
        snprintf(r->note, sizeof r->note,
                 "the branch closes on itself (a closed curve of orbits)");
      else
        snprintf(r->note, sizeof r->note,
                 "the branch joins branch %d, already computed", jn);
    }
    return 1;
  }
  return 0;
}

static void fall_back(sc_orbit_branch *b, segment *S, const job *jb,
                      sc_msg *msg);

/* A fold or flip located by the continuation layer (unless a border lies
 * between it and the last point: then that border ends the segment and
 * the fold or flip, on the smooth extension beyond it, is not real). */
static int segment_special(sc_orbit_branch *b, segment *S) {
  sc_map *m = b->m;
  int period = S->period;
  const double *us = sc_branch_point(S->br);
  int bc = border_crossed(b, S, us);
  if (bc == 2) fall_back(b, S, S->jb, NULL);
  if (bc) return 1;
  int test = sc_branch_location(S->br)->test;
  sc_map_value v;
  set_p(m, b->sp.param, us[1]);
  sc_map_iterate_ex(m, us[0], period, SC_EVAL_DERIV | SC_EVAL_ITINERARY,
                    b->ctx.force, NULL, NULL, &v, NULL);
  sc_point_label l = test == 0 ? SC_PT_LP : SC_PT_PD;
  special_rec *r = add_special(b, l, S->branch, period, us[1], us[0], v.dfdd,
                               sc_branch_test_values(S->br)[test]);
  if (r) {
    const sc_cont_location *loc = sc_branch_location(S->br);
    r->residual = fabs(sc_branch_test_values(S->br)[test]);
    r->error = fabs(loc->ds);
    r->iterations = loc->iterations;
    snprintf(r->note, sizeof r->note,
             "%s: multiplier %+.17g (test function %.3g after %d "
             "location steps)",
             l == SC_PT_LP ? "fold" : "flip", v.dfdd, loc->psi,
             loc->iterations);
    if (l == SC_PT_PD && b->sp.switch_pd) {
      int n0 = b->njobs;
      int ok = switch_flip(b, period, us[1], us[0]);
      size_t n = strlen(r->note);
      snprintf(r->note + n, sizeof r->note - n, "%s",
               ok && b->njobs > n0
                   ? "; the period-doubled branch is followed"
               : 2 * period > b->sp.max_period
                   ? "; period doubling not followed (max-period)"
                   : "; no period-doubled orbit found (or max-branches)");
    }
  }
  /* this point is now the reference for the borders */
  sc_border_list t = b->bl_prev;
  b->bl_prev = b->bl_cur;
  b->bl_cur = t;
  S->last_p = us[1], S->last_d = us[0];
  return 0;
}

/* A sign change of the fold or flip test that the continuation layer
 * could not locate (a jump of the test function): reported, not dropped. */
static void segment_rejected(sc_orbit_branch *b, segment *S) {
  unsigned long n = sc_branch_nrejected_special(S->br);
  if (n == S->nrej) return;
  S->nrej = n;
  const sc_cont_location *loc = sc_branch_location(S->br);
  sc_point_label l = loc->test == 0 ? SC_PT_LP : SC_PT_PD;
  const double *u = sc_branch_point(S->br);
  special_rec *r = add_special(b, l, S->branch, S->period, u[1], u[0],
                               S->last_mult, loc->psi);
  if (r) {
    r->method = SC_LOC_FAILED;
    r->error = fabs(loc->width);
    snprintf(r->note, sizeof r->note,
             "NOT LOCATED: the %s test changed sign but its location "
             "ended with |test| = %.3g (a jump, not a zero)",
             l == SC_PT_LP ? "fold" : "flip", fabs(loc->psi));
  }
}

/* Where the corrector cannot go on from the last point A: the borders of
 * A whose zero lies just ahead along the tangent, each located by Newton
 * on its own defining system (a grazing met from the side where the
 * guard fires: with the event at the guard's maximum; a switching: with
 * the orbit started on d*).  Records the nearest certified one ahead,
 * hands over, and returns 1; 0 when none is found. */
static int locate_ahead(sc_orbit_branch *b, segment *S, int dir) {
  if (!b->ctx.force) return 0;
  int period = S->period;
  size_t ip = b->sp.param;
  border_fix best = {0}, fx;
  sc_border bbest;
  double reach = 8 * S->set.hmax;
  for (size_t i = 0; i < b->bl_prev.n && i < b->bl_prev.cap; i++) {
    const sc_border *x = &b->bl_prev.b[i];
    sc_border like = *x;
    if (x->on_state) {
      /* a border in the state is met tangentially by the branch (the
       * orbit point approaches d* like the square of the distance in the
       * parameter), so no rate predicts it: Newton from A itself, within
       * the reach ahead */
      if (!(x->value > 0)) continue;
      locate_border(b, period, b->codes, &like, S->last_p, S->last_d, 0,
                    S->last_p + dir * reach, S->last_d, -1, &fx);
    } else {
      double rate = x->dd * S->last_td + x->dp[ip] * S->last_t;
      double ds = x->value > 0 && rate < 0 ? -x->value / rate : HUGE_VAL;
      if (!(ds <= reach)) continue;
      double dpar = S->last_t * ds, dd = S->last_td * ds;
      locate_border(b, period, b->codes, &like, S->last_p, S->last_d,
                    x->value, S->last_p + 2 * dpar, S->last_d + 2 * dd,
                    -x->value, &fx);
    }
    /* A border in the state is met tangentially: the orbit point sits
     * within rounding of it over a stretch of the parameter (its
     * distance grows like the square of the parameter's), so the last
     * accepted point may lie a little past the solution. */
    double behind = (x->on_state ? BISECTION_REACH : 1e-12) *
                    (1 + fabs(S->last_p));
    if (!fx.ok || (fx.p - S->last_p) * dir < -behind) continue;
    if (!best.ok || fabs(fx.p - S->last_p) < fabs(best.p - S->last_p))
      best = fx, bbest = like;
  }
  if (!best.ok) return 0;
  special_rec *r = record_border(b, S->branch, period, &bbest, &best, 0, 0, 0);
  if (r) {
    size_t n = strlen(r->note);
    snprintf(r->note + n, sizeof r->note - n,
             "; met where the corrector stopped (the segment's smooth "
             "extension ends at it)");
  }
  double *orb = b->orb_a;
  const sc_itin_code *codes = bbest.alt.n > 0 ? b->codes4 : b->codes;
  if (bbest.on_state) {
    /* the orbit from the point on d*, rotated back to the segment's start */
    for (int i = 0; i < period; i++) orb[i] = NAN;
    set_p(b->m, ip, best.p);
    if (iterate_orbit_forced(b, best.dk, period, b->codes3, b->seed) == 0)
      for (int i = 0; i < period; i++)
        orb[(i + bbest.iterate) % period] = b->seed[i];
  } else {
    set_p(b->m, ip, best.p);
    iterate_orbit_forced(b, best.d0, period, codes, orb);
  }
  hand_over(b, r, period, b->codes, b->ctx.itin, best.p, orb, dir);
  return 1;
}

/* The fallback from the last point: bisection on a change of itinerary
 * code, then the border that vanishes there located from the far side.
 * A "not located" row just written for this segment is replaced when the
 * fallback finds the point. */
static void fall_back(sc_orbit_branch *b, segment *S, const job *jb,
                      sc_msg *msg) {
  int period = S->period, branch = S->branch;
  int dir = S->last_t > 0 ? 1 : S->last_t < 0 ? -1 : jb->direction;
  double pa = S->last_p, pbnd = S->last_p + dir;
  set_p(b->m, b->sp.param, pa);
  double *orb = b->orb_a;
  char why[SC_MSG_LEN];
  snprintf(why, sizeof why, "%s", msg ? msg->text : "");
  size_t nsp0 = b->nsp;
  int failed_row = nsp0 > 0 && b->sps[nsp0 - 1].branch == branch &&
                   b->sps[nsp0 - 1].method == SC_LOC_FAILED;
  if (iterate_orbit_forced(b, S->last_d, period, b->ctx.force, orb) ||
      locate_by_bisection(b, period, &pa, &pbnd, orb, S->set.hmin, dir) !=
          SC_OK) {
    if (!failed_row)
      add_end(b, branch, period, S->last_p, S->last_d, S->last_mult,
              "the corrector failed and no itinerary change was found "
              "ahead: %.300s%s",
              why, NULL);
    else
      add_end(b, branch, period, S->last_p, S->last_d, S->last_mult,
              "the segment ends at the border it could not locate%s%s", NULL,
              NULL);
    return;
  }
  char keep[NOTE_LEN] = "";
  if (failed_row) {
    snprintf(keep, sizeof keep, "%s", b->sps[nsp0 - 1].note);
    b->nsp--; /* the bisection's row takes its place */
  }
  after_bisection(b, branch, period, pa, pbnd, orb, dir);
  if (failed_row && b->nsp > 0) {
    special_rec *r = &b->sps[b->nsp - 1];
    size_t n = strlen(r->note);
    snprintf(r->note + n, sizeof r->note - n, "; Newton at the sign change: "
             "%.200s", strstr(keep, "but ") ? strstr(keep, "but ") + 4 : keep);
  }
}

static int run_segment(sc_orbit_branch *b, const job *jb, int branch,
                       sc_msg *msg) {
  segment S = {.jb = jb, .branch = branch, .period = jb->period};
  sc_cont_problem pb;
  sc_map1d_system sys;
  int st = segment_start(b, &S, &pb, &sys, msg);
  if (st == SC_END || st) {
    sc_branch_free(S.br);
    return st == SC_END ? SC_OK : st;
  }
  int period = S.period;
  for (;;) {
    const double *u = sc_branch_point(S.br);
    int bc = border_crossed(b, &S, u);
    if (bc == 2) {
      fall_back(b, &S, jb, msg);
      break;
    }
    if (bc) break;
    if (segment_accept(b, &S, u)) break;
    /* this point is now the reference for the borders */
    sc_border_list t = b->bl_prev;
    b->bl_prev = b->bl_cur;
    b->bl_cur = t;
    S.last_p = u[1];
    S.last_d = u[0];
    S.last_t = sc_branch_tangent(S.br)[1];
    S.last_td = sc_branch_tangent(S.br)[0];
    if (b->sp.progress && b->sp.progress(b->sp.progress_ctx, b->npts)) {
      sc_branch_free(S.br);
      return sc_fail(msg, SC_ECALLBACK, "branch: stopped by the caller");
    }
    st = sc_branch_step(S.br, msg);
    segment_rejected(b, &S);
    if (st == SC_CONTINUE) continue;
    if (st == SC_SPECIAL) {
      if (segment_special(b, &S)) break;
      continue;
    }
    if (st == SC_END) {
      const double *ue = sc_branch_point(S.br);
      int bce = border_crossed(b, &S, ue);
      if (bce == 2) fall_back(b, &S, jb, msg);
      if (bce) break;
      if (segment_accept(b, &S, ue)) break;
      int maxed = (long)sc_branch_npoints(S.br) >= b->sp.max_points;
      add_end(b, branch, period, ue[1], ue[0], S.last_mult, "%s%s",
              maxed ? "max-points reached" : "end of the parameter interval",
              NULL);
      break;
    }
    if (st == SC_ENOCONV) {
      /* The corrector cannot go on: a forced event disappears (a grazing
       * met from the side where the guard fires), the map is undefined
       * ahead, or an itinerary boundary of an unforced segment. */
      int dir = S.last_t > 0 ? 1 : S.last_t < 0 ? -1 : jb->direction;
      if (locate_ahead(b, &S, dir)) break;
      fall_back(b, &S, jb, msg);
      break;
    }
    /* Errors. */
    add_end(b, branch, period, S.last_p, S.last_d, NAN, "error %s: %.300s",
            sc_strerror(st), msg ? msg->text : "");
    break;
  }
  sc_branch_free(S.br);
  return SC_OK;
}

int sc_orbit_branch_run(sc_orbit_branch *b, sc_msg *msg) {
  sc_map *m = b->m;
  double saved = sc_map_get_param(m, b->sp.param);
  b->npts = b->nsp = 0;
  b->njobs = b->nbranches = 0;
  b->nomem = 0;
  b->nduplicate = 0;
  b->acc = *sc_map_accuracy(m);
  double prec = sc_map_precision(m);
  b->acc.newton_atol = fmax(b->acc.newton_atol, prec);
  b->acc.newton_ftol = fmax(b->acc.newton_ftol, prec);
  /* The starting orbit, polished by multiple shooting at p = from.  Its
   * failure ends the run only when there is no other start. */
  int st = SC_OK;
  sc_shoot *s = NULL;
  sc_shoot_result res;
  if (!isnan(b->sp.d0)) {
    st = sc_map_set_param(m, b->sp.param, b->sp.from, msg);
    if (!st)
      st = sc_shoot_alloc(m, b->sp.period, SC_SHOOT_MULTIPLE, NULL, &s, msg);
    if (!st) st = sc_shoot_solve(s, b->sp.d0, &res, msg);
    sc_shoot_free(s);
    if (st && b->nstarts == 0) {
      sc_map_set_param(m, b->sp.param, saved, NULL);
      return st;
    }
    if (st) {
      char why[SC_MSG_LEN];
      snprintf(why, sizeof why, "%s", msg ? msg->text : "");
      add_end(b, -1, b->sp.period, b->sp.from, b->sp.d0, NAN,
              "start not found: %.300s%s", why, NULL);
    } else {
      push_job(b, b->sp.period, b->sp.from, res.d,
               b->sp.to > b->sp.from ? 1 : -1, 0, "start");
    }
  } else if (b->nstarts == 0) {
    sc_map_set_param(m, b->sp.param, saved, NULL);
    return sc_fail(msg, SC_EINVAL, "sc_orbit_branch_run: no start (d0 is "
                                   "NaN and no start was added)");
  }
  for (int k = 0; k < b->nstarts; k++) {
    const job *a = &b->starts[k];
    if (sc_map_set_param(m, b->sp.param, a->p, msg)) continue;
    s = NULL;
    st = sc_shoot_alloc(m, a->period, SC_SHOOT_MULTIPLE, NULL, &s, msg);
    if (!st) st = sc_shoot_solve(s, a->d, &res, msg);
    sc_shoot_free(s);
    if (st) {
      char why[SC_MSG_LEN];
      snprintf(why, sizeof why, "%s", msg ? msg->text : "");
      add_end(b, -1, a->period, a->p, a->d, NAN,
              "added start not found: %.300s%s", why, NULL);
      continue;
    }
    if (!push_job(b, a->period, a->p, res.d, 1, 0, "added start") ||
        !push_job(b, a->period, a->p, res.d, -1, 0, "added start"))
      add_end(b, -1, a->period, a->p, a->d, NAN,
              "added start not continued: max-branches reached%s%s", NULL,
              NULL);
  }
  st = SC_OK;
  for (int j = 0; j < b->njobs; j++) {
    job jb = b->jobs[j];
    b->nbranches++;
    st = run_segment(b, &jb, j, msg);
    if (st) break;
  }
  sc_map_set_param(m, b->sp.param, saved, NULL);
  if (!st && b->nomem)
    return sc_fail(msg, SC_ENOMEM,
                   "branch: out of memory for points (%zu stored)", b->npts);
  return st;
}
