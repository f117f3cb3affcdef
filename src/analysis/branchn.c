/* Branches of periodic orbits of n-dimensional maps in one parameter
 * (branchn.h): the run over its queue of segments, each a pseudo-arclength
 * continuation of the fixed-point system of g = f^m (mapn_system.h), the
 * points with their multipliers, and the storage.  The special points and
 * the switching are in branchn_special.c; docs/maps.md, "Branches". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/branchn_impl.h"

const char *sc_branchn_label_text(sc_branchn_label l) {
  static const char *const t[] = {"LP", "PD", "NS", "NN", "BP", "EP"};
  if ((unsigned)l >= SC_PTN_GR && l < SC_PTN_NLABELS)
    return sc_border_label((sc_border_kind)(l - SC_PTN_GR));
  return (unsigned)l <= SC_PTN_EP ? t[l] : "??";
}

/* ------------------------------------------------------------------ */
/* g = f^m and the multipliers                                          */

int sc_bn_jet(const double *x, const double *p, int order, sc_mapn_jet *jet,
              void *user) {
  bn_jet_ctx *c = user;
  for (size_t q = 0; q < c->np; q++)
    if (sc_map_get_param(c->m, q) != p[q] &&
        sc_map_set_param(c->m, q, p[q], NULL))
      return 1; /* outside the parameter's range: shrink the step */
  unsigned flags = order >= 2   ? SC_EVAL_DERIV2
                   : order == 1 ? SC_EVAL_DERIV
                                : 0;
  if (sc_map_iterate_n_ex(c->m, x, c->period, flags, c->force, NULL, NULL,
                          c->v, NULL))
    return 1; /* undefined or not finite: recoverable */
  size_t n = c->v->n, np = c->np;
  memcpy(jet->g, c->v->f, n * sizeof *jet->g);
  if (order >= 1) {
    memcpy(jet->gx, c->v->J, n * n * sizeof *jet->gx);
    memcpy(jet->gp, c->v->fp, np * n * sizeof *jet->gp);
  }
  if (order >= 2) {
    memcpy(jet->gxx, c->v->H, n * n * n * sizeof *jet->gxx);
    memcpy(jet->gxp, c->v->Jp, np * n * n * sizeof *jet->gxp);
  }
  return 0;
}

/* The workspace of the multipliers of period-m orbits. */
static int multipliers_work(sc_branchn *b, int period, sc_msg *msg) {
  if (b->pw && b->pw_period == period) return SC_OK;
  sc_product_eigs_work_free(b->pw);
  free(b->Jk);
  free(b->Aptr);
  b->pw = NULL;
  size_t n = b->n, m = (size_t)period;
  b->Jk = malloc(m * n * n * sizeof *b->Jk);
  b->Aptr = malloc(m * sizeof *b->Aptr);
  if (!b->Jk || !b->Aptr)
    return sc_fail(msg, SC_ENOMEM, "branch: out of memory (period %d)",
                   period);
  for (size_t k = 0; k < m; k++) b->Aptr[k] = b->Jk + k * n * n;
  b->pw_period = period;
  return sc_product_eigs_work_alloc(n, m, &b->pw, msg);
}

/* The multipliers of the period-m orbit through x at parameter p: the
 * eigenvalues of the product of the m Jacobians along it, by decreasing
 * modulus (sc_product_eigs_compute(): the product is never formed). */
int sc_bn_multipliers(sc_branchn *b, int period, const double *x, double p,
                      double *re, double *im, sc_msg *msg) {
  int st = multipliers_work(b, period, msg);
  if (st) return st;
  if ((st = sc_map_set_param(b->m, b->param, p, msg))) return st;
  double xk[BN_MAXN];
  size_t n = b->n;
  memcpy(xk, x, n * sizeof *xk);
  for (int k = 0; k < period; k++) {
    st = sc_map_eval_n_ex(b->m, xk, SC_EVAL_DERIV,
                          b->jc.force ? &b->jc.force[k] : NULL, NULL, NULL,
                          b->v1, msg);
    if (st) return st;
    memcpy(b->Jk + (size_t)k * n * n, b->v1->J, n * n * sizeof *b->Jk);
    memcpy(xk, b->v1->f, n * sizeof *xk);
  }
  return sc_product_eigs_compute(b->pw, b->Aptr, re, im, NULL, NULL, msg);
}

/* ------------------------------------------------------------------ */
/* Storage                                                              */

int sc_bn_grow(void **arr, size_t *cap, size_t need, size_t size) {
  if (need <= *cap) return 0;
  size_t nc = *cap ? 2 * *cap : 64;
  while (nc < need) nc *= 2;
  void *p = realloc(*arr, nc * size);
  if (!p) return -1;
  *arr = p;
  *cap = nc;
  return 0;
}

bn_special *sc_bn_new_special(sc_branchn *b) {
  if (sc_bn_grow((void **)&b->sps, &b->spcap, b->nsp + 1, sizeof *b->sps))
    return NULL;
  bn_special *s = &b->sps[b->nsp++];
  memset(s, 0, sizeof *s);
  s->coef = s->theta = s->kappa = s->residual = s->error = NAN;
  for (size_t i = 0; i < BN_MAXN; i++) s->x[i] = s->re[i] = s->im[i] = NAN;
  return s;
}

int sc_bn_push_job(sc_branchn *b, const bn_job *j) {
  if (sc_bn_grow((void **)&b->jobs, &b->jobcap, b->njobs + 1, sizeof *b->jobs))
    return SC_ENOMEM;
  b->jobs[b->njobs++] = *j;
  return SC_OK;
}

/* The deciding multiplier: the one of largest modulus, its value if
 * real, its modulus if complex; stable when every modulus is below 1. */
static void deciding(const double *re, const double *im, double *mult,
                     int *stable) {
  *mult = im[0] == 0 ? re[0] : hypot(re[0], im[0]);
  *stable = hypot(re[0], im[0]) < 1;
}

static int add_point(sc_branchn *b, int branch, int period, const double *u,
                     sc_msg *msg) {
  if (sc_bn_grow((void **)&b->pts, &b->ptcap, b->npts + 1, sizeof *b->pts))
    return sc_fail(msg, SC_ENOMEM, "branch: out of memory (%zu points)",
                   b->npts);
  bn_point *pt = &b->pts[b->npts];
  size_t n = b->n;
  memset(pt, 0, sizeof *pt);
  pt->branch = branch;
  pt->period = period;
  pt->p = u[n];
  memcpy(pt->x, u, n * sizeof *u);
  sc_msg m2;
  if (sc_bn_multipliers(b, period, u, u[n], pt->re, pt->im, &m2)) {
    for (size_t i = 0; i < n; i++) pt->re[i] = pt->im[i] = NAN;
    pt->mult = NAN;
  } else {
    deciding(pt->re, pt->im, &pt->mult, &pt->stable);
  }
  b->npts++;
  if (b->sp.progress && b->sp.progress(b->sp.progress_ctx, b->npts))
    return sc_fail(msg, SC_ECALLBACK, "branch: stopped at point %zu",
                   b->npts);
  return SC_OK;
}

/* An end row (EP) at u with its reason, @p what then @p more. */
static int add_end(sc_branchn *b, int branch, int period, const double *u,
                   const char *what, const char *more) {
  bn_special *s = sc_bn_new_special(b);
  if (!s) return SC_ENOMEM;
  s->label = SC_PTN_EP;
  s->branch = branch;
  s->period = period;
  s->method = SC_LOC_NONE;
  memcpy(s->x, u, b->n * sizeof *u);
  s->p = u[b->n];
  sc_msg m2;
  if (sc_bn_multipliers(b, period, s->x, s->p, s->re, s->im, &m2))
    for (size_t i = 0; i < b->n; i++) s->re[i] = s->im[i] = NAN;
  snprintf(s->note, sizeof s->note, "%.150s%.41s", what, more);
  return SC_OK;
}

/* ------------------------------------------------------------------ */
/* Allocation                                                           */

static int check_spec(const sc_map *m, const sc_branchn_spec *sp,
                      sc_msg *msg) {
  size_t n = sc_map_dim(m);
  if (n > BN_MAXN)
    return sc_fail(msg, SC_EINVAL,
                   "branch: model %s has %zu state components (valid: at "
                   "most %d for n-dimensional branches)",
                   sc_map_type(m)->name, n, BN_MAXN);
  if (sc_map_has_borders(m))
    return sc_fail(msg, SC_EINVAL,
                   "branch: model %s has one-dimensional borders (its "
                   "branches are orbits.h's)",
                   sc_map_type(m)->name);
  if (sp->param >= sc_map_nparam(m))
    return sc_fail(msg, SC_EINVAL, "branch: parameter index %zu (valid: < "
                                   "%zu)", sp->param, sc_map_nparam(m));
  if (!(isfinite(sp->from) && isfinite(sp->to) && sp->from != sp->to))
    return sc_fail(msg, SC_EINVAL,
                   "branch: from = %.17g, to = %.17g (valid: finite, "
                   "different)", sp->from, sp->to);
  if (sp->period < 1 || sp->max_period < sp->period)
    return sc_fail(msg, SC_EINVAL,
                   "branch: period = %d (valid: [1, max_period = %d])",
                   sp->period, sp->max_period);
  if (sp->max_points < 2 || sp->max_branches < 1)
    return sc_fail(msg, SC_EINVAL,
                   "branch: max_points = %ld, max_branches = %d (valid: >= "
                   "2, >= 1)", sp->max_points, sp->max_branches);
  if (!sp->x0)
    return sc_fail(msg, SC_EINVAL, "branch: no start x0");
  if (sp->has_at && !((sp->at - sp->from) * (sp->at - sp->to) <= 0))
    return sc_fail(msg, SC_EINVAL,
                   "branch: at = %.17g outside [from, to] = [%.17g, %.17g]",
                   sp->at, sp->from, sp->to);
  for (size_t i = 0; i < n; i++)
    if (!isfinite(sp->x0[i]))
      return sc_fail(msg, SC_EINVAL, "branch: x0[%zu] = %g (valid: finite)",
                     i, sp->x0[i]);
  if (!(sp->h0 >= 0 && sp->hmax >= 0 && isfinite(sp->h0) &&
        isfinite(sp->hmax)))
    return sc_fail(msg, SC_EINVAL,
                   "branch: h0 = %g, hmax = %g (valid: finite, >= 0)", sp->h0,
                   sp->hmax);
  return SC_OK;
}

/* Steps by default: 40 steps across the interval at most, the first a
 * tenth of that (as the one-dimensional branch, orbits.h). */
#define HMAX_PARTS 40
#define H0_PARTS 10

int sc_branchn_alloc(sc_map *m, const sc_branchn_spec *spec, sc_branchn **out,
                     sc_msg *msg) {
  *out = NULL;
  int st = check_spec(m, spec, msg);
  if (st) return st;
  sc_branchn *b = calloc(1, sizeof *b);
  if (!b) return sc_fail(msg, SC_ENOMEM, "branch: out of memory");
  b->m = m;
  b->sp = *spec;
  b->n = sc_map_dim(m);
  b->np = sc_map_nparam(m);
  b->param = spec->param;
  memcpy(b->x0, spec->x0, b->n * sizeof *b->x0);
  b->sp.x0 = b->x0;
  sc_map_solver_accuracy(m, &b->acc);
  sc_cont_settings_default(&b->set);
  double range = fabs(spec->to - spec->from);
  b->set.hmax = spec->hmax > 0 ? spec->hmax : range / HMAX_PARTS;
  b->set.h0 = spec->h0 > 0 ? fmin(spec->h0, b->set.hmax)
                           : b->set.hmax / H0_PARTS;
  b->set.hmin = fmin(b->set.hmin, b->set.h0);
  b->set.pmin = fmin(spec->from, spec->to);
  b->set.pmax = fmax(spec->from, spec->to);
  b->set.max_points = spec->max_points;
  if ((st = sc_mapn_value_alloc(m, SC_EVAL_DERIV2, &b->v2, msg)) ||
      (st = sc_mapn_value_alloc(m, SC_EVAL_DERIV, &b->v1, msg))) {
    sc_branchn_free(b);
    return st;
  }
  b->jc = (bn_jet_ctx){.m = m, .v = b->v2, .period = spec->period,
                       .np = b->np};
  if ((st = sc_bn_border_alloc(b, msg))) {
    sc_branchn_free(b);
    return st;
  }
  *out = b;
  return SC_OK;
}

void sc_branchn_free(sc_branchn *b) {
  if (!b) return;
  sc_mapn_value_free(b->v2);
  sc_mapn_value_free(b->v1);
  sc_product_eigs_work_free(b->pw);
  free(b->Jk);
  free(b->Aptr);
  free(b->pts);
  free(b->sps);
  free(b->jobs);
  sc_bn_border_free(b);
  free(b);
}

/* ------------------------------------------------------------------ */
/* Segments                                                             */

int sc_bn_make_system(sc_branchn *b, sc_mapn_kind kind, sc_mapn_system **out,
                      sc_msg *msg) {
  sc_mapn_def d = {.fn = sc_bn_jet, .user = &b->jc, .kind = kind,
                   .n = b->n, .np = b->np, .nfree = 1,
                   .ifree = {(int)b->param, 0}};
  for (size_t q = 0; q < b->np; q++) d.p[q] = b->psave[q];
  return sc_mapn_system_alloc(&d, out, msg);
}

/* Why a segment ended: the text of its EP row. */
static void end_reason(const sc_branchn *b, const sc_branch *br, int st,
                       const sc_msg *m2, char *buf, size_t len) {
  if (st == SC_END)
    snprintf(buf, len, "%s",
             (long)sc_branch_npoints(br) >= b->set.max_points
                 ? "max-points reached"
                 : "end of the parameter interval");
  else
    snprintf(buf, len, "continuation stopped: %.150s", m2->text);
}

/* A sign change of the LP or BP test whose location the branch rejected:
 * at a branch point the corrector's bordered matrix [F_u; t^T] is
 * singular, so the arclength location fails exactly there.  The point is
 * sought by Newton on its own system from the midpoint of the step. */
static int rejected_special(sc_branchn *b, sc_branch *br, int bi, int period,
                            const double *uprev, sc_msg *msg) {
  const sc_cont_location *L = sc_branch_location(br);
  if (L->accepted || (L->test != SC_MAPN_TEST_LP && L->test != SC_MAPN_TEST_BP))
    return SC_OK;
  size_t n = b->n;
  double um[BN_MAXN + 1], tt[BN_MAXN + 1];
  const double *u = sc_branch_point(br);
  for (size_t i = 0; i <= n; i++) um[i] = (uprev[i] + u[i]) / 2;
  memcpy(tt, sc_branch_tangent(br), (n + 1) * sizeof *tt);
  return sc_bn_special(b, bi, period, um, tt, L->test, msg);
}

/* The itinerary of f^m at u into buf ("" if the map fails there); the
 * return value: the evaluation's slip phases (0 for a smooth map, whose
 * itinerary is symbolic only, as the logistic map's L and R). */
static int itinerary_at(sc_branchn *b, int period, const double *u,
                        char *buf, size_t len) {
  buf[0] = '\0';
  if (sc_map_set_param(b->m, b->param, u[b->n], NULL) ||
      sc_map_iterate_n(b->m, u, period, SC_EVAL_ITINERARY, b->v1, NULL))
    return 0;
  snprintf(buf, len, "%s", b->v1->itinerary);
  return b->v1->nphases;
}

/* On an event map (slip phases in its evaluation), a point whose
 * itinerary of f^m is not the segment start's: the map is not smooth
 * between them (a border the n-dimensional branch does not watch), so
 * the segment ends before it with a row that says so. */
static int itinerary_changed(sc_branchn *b, int bi, int period,
                             const char *itin0, const double *uprev,
                             const double *u, int *changed) {
  char itin[SC_ITIN_LEN], why[BN_NOTE]; /* at most 150 characters of it
                                           go into the note (add_end) */
  *changed = 0;
  if (!*itin0) return SC_OK; /* a smooth map: nothing to watch */
  itinerary_at(b, period, u, itin, sizeof itin);
  *changed = strcmp(itin, itin0) != 0;
  if (!*changed) return SC_OK;
  snprintf(why, sizeof why,
           "the itinerary changes between %.10g and %.10g (%.32s to %.32s): "
           "not smooth there; ",
           uprev[b->n], u[b->n], itin0, itin);
  return add_end(b, bi, period, uprev, why, "not passed");
}

/* The loop of one segment from its corrected start: points, special
 * points, its end row.  A segment handed over at a border (@p on_border)
 * starts on it, where the natural itinerary may be neither side's (two
 * events at one instant: a tie): its itinerary is watched from its first
 * step on. */
static int segment_loop(sc_branchn *b, sc_branch *br, int bi, int period,
                        int on_border, sc_msg *msg) {
  size_t n = b->n;
  double uprev[BN_MAXN + 1];
  char itin0[SC_ITIN_LEN];
  if (!itinerary_at(b, period, sc_branch_point(br), itin0, sizeof itin0))
    itin0[0] = '\0'; /* smooth: its itinerary is not watched */
  int st = add_point(b, bi, period, sc_branch_point(br), msg), changed = 0;
  while (st == SC_OK) {
    sc_msg m2 = {{0}};
    unsigned long nrej = sc_branch_nrejected_special(br);
    memcpy(uprev, sc_branch_point(br), (n + 1) * sizeof *uprev);
    int rc = sc_branch_step(br, &m2);
    const double *u = sc_branch_point(br);
    if (rc == SC_CONTINUE || rc == SC_SPECIAL || rc == SC_END) {
      int crossed = 0;
      double ub[BN_MAXN + 1];
      if (b->borders)
        st = sc_bn_border_step(b, bi, period, uprev, u, &crossed, ub, msg);
      /* beyond a border the orbit is not real: the segment ends at it */
      if (!st && crossed == 1) st = add_point(b, bi, period, ub, msg);
      if (st || crossed) break;
      if (on_border && *itin0 && !itinerary_at(b, period, u, itin0,
                                               sizeof itin0))
        itin0[0] = '\0';
      on_border = 0;
      st = itinerary_changed(b, bi, period, itin0, uprev, u, &changed);
      if (st || changed) break;
      st = add_point(b, bi, period, u, msg);
    }
    if (!st && sc_branch_nrejected_special(br) > nrej)
      st = rejected_special(b, br, bi, period, uprev, msg);
    if (st) break;
    if (rc == SC_SPECIAL) {
      double uu[BN_MAXN + 1], tt[BN_MAXN + 1];
      memcpy(uu, u, (n + 1) * sizeof *uu);
      memcpy(tt, sc_branch_tangent(br), (n + 1) * sizeof *tt);
      st = sc_bn_special(b, bi, period, uu, tt, sc_branch_location(br)->test,
                         msg);
      continue;
    }
    if (rc == SC_CONTINUE) continue;
    char why[BN_NOTE];
    end_reason(b, br, rc, &m2, why, sizeof why);
    if (add_end(b, bi, period, sc_branch_point(br), why, ""))
      st = sc_fail(msg, SC_ENOMEM, "branch: out of memory");
    break;
  }
  return st;
}

/* One segment: its system, the corrected start, the loop.  A start that
 * is not found ends the segment with a row (and is the run's error when
 * it is the first). */
static int run_segment(sc_branchn *b, const bn_job *j, sc_msg *msg) {
  int bi = b->nbranches++, period = j->period, dir = j->dir;
  b->jc.period = period;
  sc_mapn_system *sys = NULL;
  sc_branch *br = NULL;
  sc_cont_problem pb;
  sc_cont_settings set = b->set;
  double u[BN_MAXN + 1];
  sc_msg m2 = {{0}};
  memcpy(u, j->u, (b->n + 1) * sizeof *u);
  int st = sc_bn_make_system(b, SC_MAPN_FIXED, &sys, msg);
  if (!st) st = sc_mapn_system_problem(sys, &pb, msg);
  if (st) goto out;
  int found = 1;
  if (b->borders) found = sc_bn_segment_codes(b, j, &m2) == SC_OK;
  if (found && j->displaced)
    found = sc_bn_displaced_start(b, j, u, &dir, &m2) == 0;
  set.direction = dir;
  set.start_free = j->displaced;
  if ((st = sc_branch_alloc(&pb, &set, &b->acc, &br, msg))) goto out;
  if (found) found = sc_branch_set(br, u, &m2) == SC_OK;
  if (found && b->borders)
    found = sc_bn_border_start(b, period, sc_branch_point(br), &m2) == SC_OK;
  if (!found) {
    if (bi == 0) {
      st = sc_fail(msg, SC_ENOCONV, "no period-%d orbit found from it (%s)",
                   period, sc_msg_what(m2.text));
      goto out;
    }
    char why[BN_NOTE];
    snprintf(why, sizeof why, "no orbit found (%.160s)", sc_msg_what(m2.text));
    st = add_end(b, bi, period, j->u, j->why, why);
    goto out;
  }
  st = segment_loop(b, br, bi, period, j->handover != 0, msg);
out:
  sc_branch_free(br);
  sc_mapn_system_free(sys);
  return st;
}

int sc_branchn_run(sc_branchn *b, sc_msg *msg) {
  for (size_t q = 0; q < b->np; q++) b->psave[q] = sc_map_get_param(b->m, q);
  double at = b->sp.has_at ? b->sp.at : b->sp.from;
  bn_job first = {.period = b->sp.period,
                  .dir = b->sp.to > b->sp.from ? 1 : -1};
  memcpy(first.u, b->x0, b->n * sizeof *b->x0);
  first.u[b->n] = at;
  snprintf(first.why, sizeof first.why, "start");
  int st = sc_bn_push_job(b, &first);
  if (!st && at != b->sp.from) { /* inside: the other way too */
    bn_job back = first;
    back.dir = -first.dir;
    snprintf(back.why, sizeof back.why, "start, towards from: ");
    st = sc_bn_push_job(b, &back);
  }
  while (!st && b->jobnext < b->njobs) {
    bn_job j = b->jobs[b->jobnext++];
    if (b->nbranches >= b->sp.max_branches) {
      st = add_end(b, -1, j.period, j.u, j.why,
                   ": not continued (max-branches)");
      continue;
    }
    st = run_segment(b, &j, msg);
  }
  if (st == SC_ENOMEM) sc_fail(msg, st, "branch: out of memory");
  for (size_t q = 0; q < b->np; q++)
    sc_map_set_param(b->m, q, b->psave[q], NULL);
  return st;
}

/* ------------------------------------------------------------------ */
/* Getters                                                              */

size_t sc_branchn_dim(const sc_branchn *b) { return b->n; }
size_t sc_branchn_npoints(const sc_branchn *b) { return b->npts; }
size_t sc_branchn_nspecial(const sc_branchn *b) { return b->nsp; }
int sc_branchn_nbranches(const sc_branchn *b) { return b->nbranches; }
size_t sc_branchn_nduplicate(const sc_branchn *b) { return b->ndup; }

int sc_branchn_point_get(const sc_branchn *b, size_t i, sc_branchn_point *pt) {
  if (i >= b->npts) return SC_EINVAL;
  const bn_point *r = &b->pts[i];
  *pt = (sc_branchn_point){.branch = r->branch, .period = r->period,
                           .p = r->p, .x = r->x, .re = r->re, .im = r->im,
                           .multiplier = r->mult, .stable = r->stable};
  return SC_OK;
}

int sc_branchn_special_get(const sc_branchn *b, size_t i,
                           sc_branchn_special *sp) {
  if (i >= b->nsp) return SC_EINVAL;
  const bn_special *r = &b->sps[i];
  *sp = (sc_branchn_special){
      .label = r->label, .branch = r->branch, .period = r->period,
      .p = r->p, .x = r->x, .re = r->re, .im = r->im, .coef = r->coef,
      .theta = r->theta, .kappa = r->kappa, .residual = r->residual,
      .error = r->error, .iterations = r->iterations, .method = r->method,
      .note = r->note, .border = r->border};
  return SC_OK;
}
