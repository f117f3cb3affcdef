/* Branches of periodic orbits of an event map in one parameter: the
 * fixed-point system of f^m continued by the pseudo-arclength layer
 * (continuation.h) on one piece of constant itinerary at a time, folds
 * and flips from its test functions, discontinuity-induced bifurcations
 * located by bisection in the parameter with shooting and classified by
 * sc_dib_classify().  See branch.h and docs/branches.md. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/branch.h"
#include "slipcont/continuation.h"
#include "slipcont/shooting.h"

const char *sc_point_label_text(sc_point_label l) {
  static const char *t[] = {"LP", "PD", "GR", "CS", "SW", "DI", "EP"};
  return (unsigned)l < sizeof t / sizeof t[0] ? t[l] : "??";
}

/* The smallest arclength step, relative to hmax: the corrector stops
 * this close to an itinerary boundary and the bisection with shooting
 * takes over (it locates to newton_atol + newton_rtol |p|). */
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
  double p, d, multiplier, degeneracy, width;
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
  char itin[SC_ITIN_LEN]; /* the piece being continued */
  int lock;               /* 1: stay on that piece (a piecewise-smooth
                             model); 0: a smooth map (logistic, cubic),
                             whose itinerary is a symbolic label only */
} g_ctx;

struct sc_orbit_branch {
  sc_map *m;
  sc_orbit_branch_spec sp;
  size_t npts, cap_pts, nsp, cap_sp;
  point_rec *pts;
  special_rec *sps;
  job *jobs;
  int njobs, nbranches;
  job *starts; /* added starts (direction unused) */
  int nstarts;
  double *orbit; /* scratch: orbit points, up to max_period + 1 */
  double *seed;
  double *orb_a; /* scratch: the orbit on the known side of a DIB */
  double *orb_c; /* scratch: the orbit at the current point */
  double *orb_f; /* the orbit at the first point of the segment */
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
  if (!isfinite(s->d0))
    return sc_fail(msg, SC_EINVAL, "sc_orbit_branch_alloc: d0 = %g (valid: "
                                   "finite)", s->d0);
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
  b->cap_pts = (size_t)s->max_points * (size_t)s->max_branches;
  b->cap_sp = 8 * (size_t)s->max_branches + 64;
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
  b->shooters = calloc(np, sizeof *b->shooters);
  if (!b->pts || !b->sps || !b->jobs || !b->starts || !b->orbit ||
      !b->seed || !b->orb_a || !b->orb_c || !b->orb_f || !b->shooters) {
    sc_orbit_branch_free(b);
    return sc_fail(msg, SC_ENOMEM, "sc_orbit_branch_alloc: no memory for "
                                   "%zu points",
                   b->cap_pts);
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
                          .degeneracy = r->degeneracy, .width = r->width,
                          .note = r->note};
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

/* g = f^m for the continuation layer, on the piece of itinerary ctx->itin
 * only: leaving it is a recoverable failure (the step is shrunk), so a
 * branch segment never crosses a discontinuity of f^m. */
static int g_fn(double x, const double *p, int order, sc_map1d_jet *jet,
                void *user) {
  g_ctx *c = user;
  if (set_p(c->m, c->param, p[c->param])) return 1;
  sc_map_value v;
  int st = sc_map_iterate(c->m, x, c->period,
                          (order ? SC_EVAL_DERIV : 0) | SC_EVAL_ITINERARY, &v,
                          NULL);
  if (st) return st == SC_EUNDEF || st == SC_ENONFINITE || st == SC_ENOCONV
                     ? 1
                     : -1;
  if (c->lock && (strcmp(v.itinerary, c->itin) != 0 || v.neutral)) return 1;
  jet->g = v.f;
  jet->gx = v.dfdd;
  size_t np = sc_map_nparam(c->m);
  for (size_t i = 0; i < np && i < SC_MAP1D_MAXPARAM; i++)
    jet->gp[i] = v.dfdp[i];
  if (order >= 2) return -1; /* not used by the FIXED system */
  return 0;
}

static void add_point(sc_orbit_branch *b, int branch, int period, double p,
                      double d, const sc_map_value *v, double dmin) {
  if (b->npts >= b->cap_pts) return;
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

static special_rec *add_special(sc_orbit_branch *b, sc_point_label l,
                                int branch, int period, double p, double d,
                                double mult, double deg) {
  if (b->nsp >= b->cap_sp) return NULL;
  special_rec *r = &b->sps[b->nsp++];
  memset(r, 0, sizeof *r);
  *r = (special_rec){.label = l, .branch = branch, .period = period, .p = p,
                     .d = d, .multiplier = mult, .degeneracy = deg};
  return r;
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

/* The orbit of d (period q) by iterating, into out. */
static int iterate_orbit(sc_orbit_branch *b, double d, int q, double *out) {
  sc_map_value v;
  out[0] = d;
  for (int i = 1; i < q; i++) {
    int st = sc_map_eval(b->m, out[i - 1], SC_EVAL_VALUE, &v, NULL);
    if (st) return st;
    out[i] = v.f;
  }
  return SC_OK;
}

static int minimal_period(const double *o, int q, double tol) {
  for (int k = 1; k < q; k++)
    if (q % k == 0 && fabs(o[k] - o[0]) <= tol) return k;
  return q;
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

/* Locate where the piece @p itin of the period-m orbit ends, between pa
 * (orbit points orb_a, on the piece) and pb = pa + dir * width (beyond).
 * Returns SC_OK with the bracket [pa, pb] and orb_a updated, or
 * SC_ENOCONV if the piece does not end within the offsets tried. */
static int locate_dib(sc_orbit_branch *b, int m, const char *itin,
                      double *pa, double *pb, double *orb_a, double hmin) {
  const sc_accuracy *acc = sc_map_accuracy(b->m);
  double p0 = *pa, dir = *pb > *pa ? 1 : -1, pmin = fmin(b->sp.from, b->sp.to),
         pmax = fmax(b->sp.from, b->sp.to);
  sc_shoot_result res;
  /* An offset beyond which the piece has ended: grow from hmin. */
  double w = 4 * hmin, lo = p0, hi = NAN;
  for (int k = 0; k < 40; k++, w *= 2) {
    double p = p0 + dir * w;
    if (p < pmin || p > pmax) p = dir > 0 ? pmax : pmin;
    int st = shoot_at(b, m, p, orb_a, &res);
    if (st != SC_OK || strcmp(res.itinerary, itin) != 0) {
      hi = p;
      break;
    }
    lo = p;
    memcpy(orb_a, b->orbit, (size_t)m * sizeof *orb_a);
    if (p == pmin || p == pmax || w > 1e-2 * (pmax - pmin)) break;
  }
  if (isnan(hi)) return SC_ENOCONV;
  /* Bisection: lo on the piece, hi beyond. */
  for (int it = 0; it < 200; it++) {
    if (fabs(hi - lo) <= acc->newton_atol + acc->newton_rtol * fabs(lo))
      break;
    double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    int st = shoot_at(b, m, mid, orb_a, &res);
    if (st == SC_OK && strcmp(res.itinerary, itin) == 0) {
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

/* After a located DIB at [pa, pb] (orbit orb of period m on the pa side):
 * classify, record, and look for the orbit on the other side. */
/* The first iterate whose itinerary differs between the f^m itineraries
 * @p a and @p c ('|'-separated): "iterate K: A -> C", or "" if none. */
static void first_change(const char *a, const char *c, char *out,
                         size_t len) {
  out[0] = '\0';
  for (int k = 1; *a || *c; k++) {
    size_t na = strcspn(a, "|"), nc = strcspn(c, "|");
    if (na != nc || strncmp(a, c, na) != 0) {
      snprintf(out, len, "iterate %d: %.*s -> %.*s", k, (int)na, a, (int)nc,
               c);
      return;
    }
    a += na + (a[na] == '|');
    c += nc + (c[nc] == '|');
  }
}

static int handle_dib(sc_orbit_branch *b, int branch, int m, const char *itin,
                      double pa, double pb, double *orb, int dir) {
  sc_map_value va, vb;
  int ha = 0, hb = 0;
  if (!set_p(b->m, b->sp.param, pa) &&
      !sc_map_iterate(b->m, orb[0], m, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &va,
                      NULL))
    ha = 1;
  if (!set_p(b->m, b->sp.param, pb) &&
      !sc_map_iterate(b->m, orb[0], m, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &vb,
                      NULL))
    hb = 1;
  double deg;
  char note[NOTE_LEN], what[NOTE_LEN];
  sc_point_label l = sc_dib_classify(ha ? &va : NULL, hb ? &vb : NULL, &deg,
                                     what, sizeof what);
  char change[160] = "";
  if (hb) first_change(itin, vb.itinerary, change, sizeof change);
  snprintf(note, sizeof note, "%.250s; orbit itinerary %.150s%s%.150s", what,
           itin, change[0] ? "; f^m from it beyond the point: " : "",
           change);
  special_rec *r = add_special(b, l, branch, m, pa, orb[0],
                               ha ? va.dfdd : NAN, deg);
  if (r) r->width = fabs(pb - pa);
  /* The other side: period m, m - 1, m + 1, seeded from each old point. */
  double pc = pb + dir * CROSS_REL * (1 + fabs(pb));
  double tol = CLOSE_FACTOR * CROSS_REL * (1 + fabs(pb)) +
               CLOSE_FACTOR * fabs(pb - pa);
  const int qs[3] = {m, m - 1, m + 1};
  for (int iq = 0; iq < 3; iq++) {
    int q = qs[iq];
    if (q < 1 || q > b->sp.max_period) continue;
    for (int k = 0; k < m; k++) {
      if (set_p(b->m, b->sp.param, pc)) break;
      if (iterate_orbit(b, orb[k], q, b->seed)) continue;
      sc_shoot_result res;
      if (shoot_at(b, q, pc, b->seed, &res) != SC_OK) continue;
      if (q == m && strcmp(res.itinerary, itin) == 0) continue;
      if (minimal_period(b->orbit, q, 1e-9) != q) continue;
      if (!close_orbits(b->orbit, q, orb, m, tol)) continue;
      char origin[96];
      snprintf(origin, sizeof origin, "%s at %.10g", sc_point_label_text(l),
               pa);
      int queued = push_job(b, q, pc, b->orbit[0], dir, fabs(pc - pb),
                            origin);
      if (r)
        snprintf(r->note, sizeof r->note,
                 "%.400s; %sthe branch continues with period %d (itinerary "
                 "%.120s beyond)",
                 note, queued ? "" : "not followed (max-branches): ", q,
                 res.itinerary);
      return SC_OK;
    }
  }
  if (r)
    snprintf(r->note, sizeof r->note,
             "%.300s; no orbit on the other side: the branch ends here", note);
  return SC_END;
}

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
        if (minimal_period(b->orbit, 2 * m, 1e-9) != 2 * m) continue;
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
    if (close_orbits(b->orbit, period, b->orb_c, period, SAME_ORBIT_TOL))
      return r->branch;
  }
  return -1;
}

/* One segment: continue the period-m orbit through (d, p) in direction
 * dir on its piece; then handle whatever ended it. */
static int run_segment(sc_orbit_branch *b, const job *jb, int branch,
                       sc_msg *msg) {
  sc_map *m = b->m;
  int period = jb->period;
  double range = fabs(b->sp.to - b->sp.from);
  sc_map_value v;
  if (set_p(m, b->sp.param, jb->p))
    return sc_fail(msg, SC_EINVAL, "branch: %s = %.17g out of range",
                   sc_map_type(m)->params[b->sp.param].name, jb->p);
  int st = sc_map_iterate(m, jb->d, period, SC_EVAL_DERIV | SC_EVAL_ITINERARY,
                          &v, msg);
  if (st) return st;
  /* A model that reports no margin has no discontinuities. */
  int smooth = !isfinite(v.gsp_gap) && !isfinite(v.graze_margin) &&
               !isfinite(v.dstar_dist);
  b->ctx = (g_ctx){.m = m, .param = b->sp.param, .period = period,
                   .lock = !smooth};
  snprintf(b->ctx.itin, sizeof b->ctx.itin, "%s", v.itinerary);
  sc_map1d_system sys = {.fn = g_fn, .user = &b->ctx, .kind = SC_MAP1D_FIXED,
                         .np = sc_map_nparam(m), .ifree = {(int)b->sp.param, 0}};
  for (size_t i = 0; i < sys.np; i++) sys.p[i] = sc_map_get_param(m, i);
  sc_cont_problem pb;
  if ((st = sc_map1d_problem(&sys, &pb, msg))) return st;
  sc_cont_settings set;
  sc_cont_settings_default(&set);
  set.hmax = b->sp.hmax > 0 ? b->sp.hmax : range / 40;
  set.h0 = b->sp.h0 > 0 ? fmin(b->sp.h0, set.hmax) : set.hmax / 10;
  set.hmin = set.hmax * HMIN_REL;
  set.pmin = fmin(b->sp.from, b->sp.to);
  set.pmax = fmax(b->sp.from, b->sp.to);
  set.direction = jb->direction;
  set.max_points = b->sp.max_points;
  set.linsolve = b->sp.linsolve;
  /* Starts next to a flip or a switching are ill conditioned at fixed
   * parameter: let the start move along the branch instead. */
  set.start_free = 1;
  sc_branch *br = NULL;
  if ((st = sc_branch_alloc(&pb, &set, sc_map_accuracy(m), &br, msg)))
    return st;
  double u0[2] = {jb->d, jb->p};
  st = sc_branch_set(br, u0, msg);
  /* A start just beyond a located point may sit where the orbit is
   * nearly singular (f' grows like |d - d*|^(-1/2) near a switching):
   * move it further along, ten times at a time. */
  double off = jb->offset;
  for (int k = 0; st && off > 0 && k < 4; k++) {
    double p1 = jb->p + jb->direction * 9 * off;
    off *= 10;
    if (p1 < set.pmin || p1 > set.pmax || set_p(m, b->sp.param, p1)) break;
    if (iterate_orbit(b, jb->d, period, b->seed)) break;
    sc_shoot_result res;
    /* The orbit found must still be of minimal period `period`: next to a
     * flip the doubled period-m/2 orbit has the same itinerary and is a
     * fixed point of f^period too, and continuing it would follow the
     * old branch twice over. */
    if (shoot_at(b, period, p1, b->seed, &res) != SC_OK ||
        strcmp(res.itinerary, b->ctx.itin) != 0 ||
        minimal_period(b->orbit, period, 1e-9) != period)
      continue;
    u0[0] = b->orbit[0];
    u0[1] = p1;
    st = sc_branch_set(br, u0, msg);
  }
  if (st) {
    special_rec *r = add_special(b, SC_PT_EP, branch, period, jb->p, jb->d,
                                 v.dfdd, NAN);
    if (r)
      snprintf(r->note, sizeof r->note, "start failed (%s): %.300s",
               sc_strerror(st), msg ? msg->text : "");
    sc_branch_free(br);
    return SC_OK;
  }
  double last_p = jb->p, last_d = jb->d, last_t = jb->direction;
  double p_first = NAN, dmin_first = NAN, prev_p = NAN;
  int moved = 0;
  for (;;) {
    const double *u = sc_branch_point(br);
    set_p(m, b->sp.param, u[1]);
    double dmin = u[0];
    int have_orbit = !iterate_orbit(b, u[0], period, b->orb_c);
    if (have_orbit)
      for (int k = 1; k < period; k++) dmin = fmin(dmin, b->orb_c[k]);
    /* A period-m segment whose orbit has fallen to a divisor of m has
     * left its branch for a lower-period one crossing it (the doubled
     * orbit at a flip): stop rather than follow the old branch again. */
    int q = have_orbit && period > 1
                ? minimal_period(b->orb_c, period, 1e-9 * (1 + fabs(u[0])))
                : period;
    if (q < period) {
      /* Follow the lower-period branch from here instead, both ways, with
       * its own period (joins() stops it where it was computed before). */
      char origin[96];
      snprintf(origin, sizeof origin, "period-%d segment at %.10g", period,
               u[1]);
      int pushed = push_job(b, q, u[1], u[0], 1, 0, origin);
      pushed += push_job(b, q, u[1], u[0], -1, 0, origin);
      special_rec *r = add_special(b, SC_PT_EP, branch, period, u[1], u[0],
                                   NAN, NAN);
      if (r)
        snprintf(r->note, sizeof r->note,
                 "the orbit's minimal period fell to %d: the segment met the "
                 "period-%d branch and ends here%s",
                 q, q, pushed ? "; that branch is followed" : "");
      break;
    }
    set_p(m, b->sp.param, u[1]);
    if (sc_map_iterate(m, u[0], period, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v,
                       NULL) == SC_OK)
      add_point(b, branch, period, u[1], u[0], &v, dmin);
    if (isnan(p_first)) {
      p_first = u[1], dmin_first = dmin;
      memcpy(b->orb_f, b->orb_c, (size_t)period * sizeof *b->orb_f);
    }
    if (fabs(u[1] - p_first) + fabs(dmin - dmin_first) > 4 * set.hmax)
      moved = 1;
    int jn = joins(b, branch, period, u[1], dmin, p_first, dmin_first,
                   set.hmax, moved);
    /* Back at the start after going away: the step from the previous
     * point crosses the start's parameter, and the orbit there, followed
     * by shooting from this point, is the start's orbit. */
    if (jn < 0 && moved && (prev_p - p_first) * (u[1] - p_first) <= 0) {
      sc_shoot_result res;
      memcpy(b->orb_a, b->orb_c, (size_t)period * sizeof *b->orb_a);
      if (shoot_at(b, period, p_first, b->orb_a, &res) == SC_OK &&
          close_orbits(b->orbit, period, b->orb_f, period, SAME_ORBIT_TOL))
        jn = branch;
    }
    prev_p = u[1];
    if (jn >= 0) {
      special_rec *r = add_special(b, SC_PT_EP, branch, period, u[1], u[0],
                                   v.dfdd, NAN);
      if (r) {
        if (jn == branch)
          snprintf(r->note, sizeof r->note,
                   "the branch closes on itself (a closed curve of orbits)");
        else
          snprintf(r->note, sizeof r->note,
                   "the branch joins branch %d, already computed", jn);
      }
      break;
    }
    last_p = u[1];
    last_d = u[0];
    last_t = sc_branch_tangent(br)[1];
    if (b->sp.progress && b->sp.progress(b->sp.progress_ctx, b->npts)) {
      sc_branch_free(br);
      return sc_fail(msg, SC_ECALLBACK, "branch: stopped by the caller");
    }
    st = sc_branch_step(br, msg);
    if (st == SC_CONTINUE) continue;
    if (st == SC_SPECIAL) {
      const double *us = sc_branch_point(br);
      int test = sc_branch_location(br)->test;
      set_p(m, b->sp.param, us[1]);
      sc_map_iterate(m, us[0], period, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v,
                     NULL);
      sc_point_label l = test == 0 ? SC_PT_LP : SC_PT_PD;
      special_rec *r = add_special(b, l, branch, period, us[1], us[0], v.dfdd,
                                   sc_branch_test_values(br)[test]);
      if (r) {
        const sc_cont_location *loc = sc_branch_location(br);
        r->width = 0;
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
                             : "; no period-doubled orbit found (or "
                               "max-branches)");
        }
      }
      continue;
    }
    if (st == SC_END) {
      const double *ue = sc_branch_point(br);
      set_p(m, b->sp.param, ue[1]);
      double emin = ue[0];
      if (!iterate_orbit(b, ue[0], period, b->orb_c))
        for (int k = 1; k < period; k++) emin = fmin(emin, b->orb_c[k]);
      if (sc_map_iterate(m, ue[0], period, SC_EVAL_DERIV | SC_EVAL_ITINERARY,
                         &v, NULL) == SC_OK)
        add_point(b, branch, period, ue[1], ue[0], &v, emin);
      int maxed = (long)sc_branch_npoints(br) >= b->sp.max_points;
      special_rec *r = add_special(b, SC_PT_EP, branch, period, ue[1], ue[0],
                                   v.dfdd, NAN);
      if (r)
        snprintf(r->note, sizeof r->note, "%s",
                 maxed ? "max-points reached"
                       : "end of the parameter interval");
      break;
    }
    if (st == SC_ENOCONV) {
      /* The corrector cannot go on: an itinerary boundary (or a region
       * where the map is undefined) is within about hmin ahead. */
      int dir = last_t > 0 ? 1 : last_t < 0 ? -1 : jb->direction;
      double pa = last_p, pbnd = last_p + dir;
      set_p(m, b->sp.param, pa);
      double *orb = b->orb_a;
      if (iterate_orbit(b, last_d, period, orb) ||
          locate_dib(b, period, b->ctx.itin, &pa, &pbnd, orb, set.hmin) !=
              SC_OK) {
        special_rec *r = add_special(b, SC_PT_EP, branch, period, last_p,
                                     last_d, NAN, NAN);
        if (r)
          snprintf(r->note, sizeof r->note,
                   "the corrector failed and no itinerary change was found "
                   "ahead: %.300s",
                   msg ? msg->text : "");
        break;
      }
      handle_dib(b, branch, period, b->ctx.itin, pa, pbnd, orb, dir);
      break;
    }
    /* Errors. */
    special_rec *r = add_special(b, SC_PT_EP, branch, period, last_p, last_d,
                                 NAN, NAN);
    if (r)
      snprintf(r->note, sizeof r->note, "error %s: %.300s", sc_strerror(st),
               msg ? msg->text : "");
    break;
  }
  sc_branch_free(br);
  return SC_OK;
}

int sc_orbit_branch_run(sc_orbit_branch *b, sc_msg *msg) {
  sc_map *m = b->m;
  double saved = sc_map_get_param(m, b->sp.param);
  b->npts = b->nsp = 0;
  b->njobs = b->nbranches = 0;
  /* The starting orbit, polished by multiple shooting at p = from. */
  int st = sc_map_set_param(m, b->sp.param, b->sp.from, msg);
  if (st) return st;
  sc_shoot *s = NULL;
  sc_shoot_result res;
  st = sc_shoot_alloc(m, b->sp.period, SC_SHOOT_MULTIPLE, NULL, &s, msg);
  if (!st) st = sc_shoot_solve(s, b->sp.d0, &res, msg);
  sc_shoot_free(s);
  if (st) {
    sc_map_set_param(m, b->sp.param, saved, NULL);
    return st;
  }
  push_job(b, b->sp.period, b->sp.from, res.d, b->sp.to > b->sp.from ? 1 : -1,
           0, "start");
  for (int k = 0; k < b->nstarts; k++) {
    const job *a = &b->starts[k];
    if (sc_map_set_param(m, b->sp.param, a->p, msg)) continue;
    s = NULL;
    st = sc_shoot_alloc(m, a->period, SC_SHOOT_MULTIPLE, NULL, &s, msg);
    if (!st) st = sc_shoot_solve(s, a->d, &res, msg);
    sc_shoot_free(s);
    if (st) {
      special_rec *r = add_special(b, SC_PT_EP, -1, a->period, a->p, a->d,
                                   NAN, NAN);
      if (r)
        snprintf(r->note, sizeof r->note, "added start not found: %.300s",
                 msg ? msg->text : "");
      continue;
    }
    push_job(b, a->period, a->p, res.d, 1, 0, "added start");
    push_job(b, a->period, a->p, res.d, -1, 0, "added start");
  }
  st = SC_OK;
  for (int j = 0; j < b->njobs; j++) {
    job jb = b->jobs[j];
    b->nbranches++;
    st = run_segment(b, &jb, j, msg);
    if (st) break;
  }
  sc_map_set_param(m, b->sp.param, saved, NULL);
  return st;
}
