/* Branches of periodic orbits of an event map in one parameter: the
 * fixed-point system of f^m continued by the pseudo-arclength layer
 * (continuation.h) along one itinerary code at a time (forced, so f^m is
 * smooth along a segment), folds and flips from its test functions, and
 * the model's borders watched as test functions and located by Newton's
 * method on their defining systems.  See orbits.h and docs/branches.md.
 *
 * This file: the object, its records, the orbit helpers shared by the
 * segment (branch_segment.c), border location (branch_border.c) and
 * switching (branch_switch.c), and the driver that runs the jobs. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/branch_orbit_impl.h"

const char *sc_point_label_text(sc_point_label l) {
  static const char *t[] = {"LP", "PD", "GR", "CS", "SW",
                            "BR", "TT", "IC", "UZ", "EP"};
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
  static const char *t[] = {"newton", "bisection", "not-located", "",
                            "degenerate"};
  return (unsigned)l < sizeof t / sizeof t[0] ? t[l] : "";
}

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
  if (s->nmarks > 1000 || (s->nmarks && !s->marks))
    return sc_fail(msg, SC_EINVAL,
                   "sc_orbit_branch_alloc: nmarks = %zu (valid: [0, 1000], "
                   "with marks)",
                   s->nmarks);
  for (size_t i = 0; i < s->nmarks; i++)
    if (!isfinite(s->marks[i]))
      return sc_fail(msg, SC_EINVAL,
                     "sc_orbit_branch_alloc: marks[%zu] = %g (valid: finite)",
                     i, s->marks[i]);
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
  b->cap_starts = (size_t)s->max_branches;
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

static int grow(void **a, size_t *cap, size_t n, size_t size);

int sc_orbit_branch_add_start(sc_orbit_branch *b, double p, double d,
                              int period, sc_msg *msg) {
  double lo = fmin(b->sp.from, b->sp.to), hi = fmax(b->sp.from, b->sp.to);
  if (!(p >= lo && p <= hi) || !isfinite(d) || period < 1 ||
      period > b->sp.max_period)
    return sc_fail(msg, SC_EINVAL,
                   "sc_orbit_branch_add_start: p = %g, d = %g, period = %d "
                   "(valid: p in [%g, %g], d finite, period in [1, %d])",
                   p, d, period, lo, hi, b->sp.max_period);
  /* Every start is kept, beyond max_branches too: one that finds no
   * room gets a row saying so, as a failed one does. */
  if (!grow((void **)&b->starts, &b->cap_starts, (size_t)b->nstarts,
            sizeof *b->starts))
    return sc_fail(msg, SC_ENOMEM,
                   "sc_orbit_branch_add_start: out of memory for %d starts",
                   b->nstarts + 1);
  b->starts[b->nstarts] =
      (job){.period = period, .p = p, .d = d, .group = b->nstarts};
  b->nstarts++;
  return SC_OK;
}

int sc_orbit_branch_group_starts(sc_orbit_branch *b, int n, sc_msg *msg) {
  if (n < 1 || n > b->nstarts)
    return sc_fail(msg, SC_EINVAL,
                   "branch: a group of %d starts (valid: 1 to the %d added)",
                   n, b->nstarts);
  for (int k = b->nstarts - n; k < b->nstarts; k++)
    b->starts[k].group = b->starts[b->nstarts - n].group;
  return SC_OK;
}

/* ------------------------------------------------------------------ */

int sc_ob_set_p(sc_map *m, size_t i, double p) {
  if (sc_map_get_param(m, i) == p) return SC_OK;
  return sc_map_set_param(m, i, p, NULL);
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

void sc_ob_add_point(sc_orbit_branch *b, int branch, int period, double p,
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

special_rec *sc_ob_add_special(sc_orbit_branch *b, sc_point_label l,
                               int branch, int period, double p, double d,
                               double mult, double deg) {
  /* Two special points of one label and period whose parameters agree by
   * the one equality rule (common.h: both are located by Newton to the
   * preset's tolerances) are one point met by two branch segments: a flip
   * reached again from the doubled branch, a closed curve traversed from
   * two starts. */
  if (l != SC_PT_EP && l != SC_PT_UZ) { /* UZ: by orbit (branch_marks.c) */
    double tol = sc_orbit_tol(&b->acc, p);
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
void sc_ob_add_end(sc_orbit_branch *b, int branch, int period, double p,
                   double d, double mult, const char *fmt, const char *a,
                   const char *c) {
  special_rec *r =
      sc_ob_add_special(b, SC_PT_EP, branch, period, p, d, mult, NAN);
  if (r) snprintf(r->note, sizeof r->note, fmt, a ? a : "", c ? c : "");
}

int sc_ob_push_job(sc_orbit_branch *b, int period, double p, double d,
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
int sc_ob_shoot_at(sc_orbit_branch *b, int q, double p, const double *seed,
                   sc_shoot_result *res) {
  if (sc_ob_set_p(b->m, b->sp.param, p) || q < 1 || q > b->sp.max_period + 1)
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
int sc_ob_iterate_orbit_forced(sc_orbit_branch *b, double d, int q,
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

int sc_ob_iterate_orbit(sc_orbit_branch *b, double d, int q, double *out) {
  return sc_ob_iterate_orbit_forced(b, d, q, NULL, out);
}


int sc_ob_minimal_period(const sc_orbit_branch *b, const double *orb, int m,
                         const sc_itin_code *codes) {
  int q = sc_orbit_minimal_period(orb, m, sc_orbit_tol(&b->acc, orb[0]));
  /* an orbit of period q follows q-periodic codes: one that shadows a
   * lower-period orbit within the tolerance (next to the period-4
   * switching of fig 5.8 a period-16 orbit passes 1.3e-6 from it, below
   * the fast preset's 1.2e-5) but not along its codes is not it */
  for (int j = q; codes && j < m; j += q)
    if (!sc_ob_same_codes(codes, codes + j, q, 0)) return m;
  return q;
}

int sc_ob_same_orbit(const sc_orbit_branch *b, const double *a,
                     const double *c, int m) {
  double x = 0;
  for (int i = 0; i < m; i++) x = fmax(x, fmax(fabs(a[i]), fabs(c[i])));
  return sc_orbit_same(a, c, m, sc_orbit_tol(&b->acc, x));
}

/* Every point of orbit a (na) within tol of a point of orbit c (nc). */
int sc_ob_close_orbits(const double *a, int na, const double *c, int nc,
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
int sc_ob_same_codes(const sc_itin_code *a, const sc_itin_code *c, int q,
                     int k) {
  for (int i = 0; i < q; i++)
    if (!same_code(&a[i], &c[(i + k) % q])) return 0;
  return 1;
}

/* f^m at (d, p) with every border (border_list.h); along `force` (NULL:
 * natural) with the codes into `codes`. */
int sc_ob_orbit_borders(sc_orbit_branch *b, double d, int period,
                        const sc_itin_code *force, sc_itin_code *codes,
                        sc_border_list *bl, sc_map_value *v, sc_msg *msg) {
  return sc_border_list_iterate(b->m, d, period,
                                SC_EVAL_DERIV | SC_EVAL_ITINERARY, force,
                                codes, bl, v, msg);
}

size_t sc_orbit_branch_nduplicate(const sc_orbit_branch *b) {
  return b->nduplicate;
}

void sc_orbit_branch_start_counts(const sc_orbit_branch *b, size_t *started,
                                  size_t *not_found, size_t *no_room) {
  *started = b->nstart_ok;
  *not_found = b->nstart_notfound;
  *no_room = b->nstart_noroom;
}

/* What a user can do about a start that is on no orbit (a row's note). */
#define START_HINT                                                         \
  "; the fixed-point task at this parameter value finds the orbits there " \
  "(or use starts = auto)"

/* Shoot added start a at its parameter: a->found, a->d_found, or a row
 * with the reason. */
static void shoot_start(sc_orbit_branch *b, job *a, sc_msg *msg) {
  sc_shoot *s = NULL;
  sc_shoot_result res;
  int st = sc_map_set_param(b->m, b->sp.param, a->p, msg);
  if (!st) st = sc_shoot_alloc(b->m, a->period, SC_SHOOT_MULTIPLE, NULL, &s,
                               msg);
  if (!st) st = sc_shoot_solve(s, a->d, &res, msg);
  sc_shoot_free(s);
  a->found = st == SC_OK;
  a->d_found = st == SC_OK ? res.d : NAN;
  if (st) {
    char why[SC_MSG_LEN];
    snprintf(why, sizeof why, "%s", msg ? msg->text : "");
    sc_ob_add_end(b, -1, a->period, a->p, a->d, NAN,
                  "added start not found: %.300s%s", why, START_HINT);
    b->nstart_notfound++;
  }
}

/* The added starts, group by group (sc_orbit_branch_group_starts()):
 * each found start is continued both ways, the found ones of a group all
 * or none: a start continued one way only, or one of a group without the
 * rest, would be treated unlike its twin (the mirror image of a symmetric
 * model, found in the same group).  One row for each start not found or
 * not continued. */
static void run_starts(sc_orbit_branch *b, sc_msg *msg) {
  for (int k = 0; k < b->nstarts;) {
    int end = k + 1, nfound = 0;
    while (end < b->nstarts && b->starts[end].group == b->starts[k].group)
      end++;
    for (int i = k; i < end; i++) {
      shoot_start(b, &b->starts[i], msg);
      nfound += b->starts[i].found;
    }
    int room = b->njobs + 2 * nfound <= b->sp.max_branches;
    for (int i = k; i < end; i++) {
      const job *a = &b->starts[i];
      if (!a->found) continue;
      if (!room) {
        sc_ob_add_end(b, -1, a->period, a->p, a->d_found, NAN,
                      "added start not continued: max-branches reached%s%s",
                      NULL, NULL);
        b->nstart_noroom++;
        continue;
      }
      sc_ob_push_job(b, a->period, a->p, a->d_found, 1, 0, "added start");
      sc_ob_push_job(b, a->period, a->p, a->d_found, -1, 0, "added start");
      b->nstart_ok++;
    }
    k = end;
  }
}

int sc_orbit_branch_run(sc_orbit_branch *b, sc_msg *msg) {
  sc_map *m = b->m;
  double saved = sc_map_get_param(m, b->sp.param);
  b->npts = b->nsp = 0;
  b->njobs = b->nbranches = 0;
  b->nomem = 0;
  b->nduplicate = 0;
  b->nstart_ok = b->nstart_notfound = b->nstart_noroom = 0;
  sc_map_solver_accuracy(m, &b->acc);
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
      sc_ob_add_end(b, -1, b->sp.period, b->sp.from, b->sp.d0, NAN,
                    "start not found: %.300s%s", why, START_HINT);
    } else {
      sc_ob_push_job(b, b->sp.period, b->sp.from, res.d,
                     b->sp.to > b->sp.from ? 1 : -1, 0, "start");
    }
  } else if (b->nstarts == 0) {
    sc_map_set_param(m, b->sp.param, saved, NULL);
    return sc_fail(msg, SC_EINVAL, "sc_orbit_branch_run: no start (d0 is "
                                   "NaN and no start was added)");
  }
  run_starts(b, msg);
  st = SC_OK;
  for (int j = 0; j < b->njobs; j++) {
    job jb = b->jobs[j];
    b->nbranches++;
    st = sc_ob_run_segment(b, &jb, j, msg);
    if (st) break;
  }
  sc_map_set_param(m, b->sp.param, saved, NULL);
  if (!st && b->nomem)
    return sc_fail(msg, SC_ENOMEM,
                   "branch: out of memory for points (%zu stored)", b->npts);
  return st;
}
