/* Orbit branches: one segment, continued along one itinerary code, in
 * named steps: sc_ob_run_segment() runs segment_start() (the first point,
 * its codes and borders), then per accepted point sc_ob_border_crossed()
 * (detect, locate, hand over: branch_border.c) and segment_accept()
 * (record, joins, falls in period), the fold and flip points of the
 * continuation layer (segment_special()) and, where the corrector cannot
 * go on, sc_ob_locate_ahead() or the fallback sc_ob_fall_back()
 * (branch_switch.c).  See branch_orbit_impl.h. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/branch_orbit_impl.h"

/* The smallest arclength step, relative to hmax: the corrector stops
 * this close to where a forced event disappears, and the bisection with
 * shooting takes over (it locates to newton_atol + newton_rtol |p|). */
#define HMIN_REL 1e-6

/* A located fold or flip test is accepted within this many times the
 * preset's residual tolerance (or the continuation layer's default,
 * 1e-8, if larger): the multiplier carries the rounding of f^m times its
 * own conditioning. */
#define TEST_ATOL_FACTOR 1e3

/* Without a step given, the largest step is the parameter interval over
 * HMAX_AUTO_STEPS (40: a branch drawn from that many points at least, few
 * enough for a quick first look), the first step a tenth of it
 * (H0_AUTO_FRACTION: small enough for the corrector to converge from the
 * start's tangent). */
#define HMAX_AUTO_STEPS 40
#define H0_AUTO_FRACTION 10

/* A start just beyond a located point that fails is moved further from
 * that point, START_MOVE_GROWTH times its offset at a time, at most
 * START_MOVES times: from CROSS_REL (1e-7) up to 1e-3 relative, still
 * within the distance between distinct special points. */
#define START_MOVES 4
#define START_MOVE_GROWTH 10

/* A segment is not compared with its own start, nor a twin's, while
 * within TWIN_REACH_HMAX largest steps of it (in |dp| + |d_min|): a start
 * continued both ways would join its twin at once.  It has moved away
 * once beyond MOVED_HMAX largest steps (twice that reach, so that a
 * segment that turns back is not taken for closed at once). */
#define TWIN_REACH_HMAX 2
#define MOVED_HMAX 4

/* Candidates for a join: points of another branch within hmax in p whose
 * smallest orbit point is within JOIN_DMIN_ABS + JOIN_DMIN_SLOPE |dp| of
 * this one's.  A coarse screen only (orbit points move with slopes dd/dp
 * of order one to ten on the chapter's examples; 1e-3 covers the
 * corrector's error at a step): the orbits are then compared exactly. */
#define JOIN_DMIN_ABS 1e-3
#define JOIN_DMIN_SLOPE 10

double sc_ob_hmax(const sc_orbit_branch *b) {
  return b->sp.hmax > 0 ? b->sp.hmax
                        : fabs(b->sp.to - b->sp.from) / HMAX_AUTO_STEPS;
}

/* The current point as (d, p) = (x_0, p), and its tangent likewise:
 * with multiple shooting the point is (x_0, ..., x_{m-1}, p). */
static const double *seg_point(segment *S) {
  const double *u = sc_branch_point(S->br);
  if (!S->ms) return u;
  S->u2[0] = u[0], S->u2[1] = u[S->period];
  return S->u2;
}

static const double *seg_tangent(segment *S) {
  const double *t = sc_branch_tangent(S->br);
  if (!S->ms) return t;
  S->t2[0] = t[0], S->t2[1] = t[S->period];
  return S->t2;
}

/* The current point is the reference of the next step: with multiple
 * shooting its orbit and tangent are kept. */
static void seg_keep(segment *S) {
  if (!S->ms) return;
  size_t n = ((size_t)S->period + 1) * sizeof(double);
  memcpy(S->ms_last, sc_branch_point(S->br), n);
  memcpy(S->ms_tan, sc_branch_tangent(S->br), n);
}

/* f^m's value at the current point u (d, p) along the segment's codes:
 * with multiple shooting each iterate from its own point. */
static int seg_value(sc_orbit_branch *b, segment *S, const double *u,
                     sc_map_value *v) {
  if (S->ms)
    return sc_ob_ms_eval(b, b->codes, S->period, sc_branch_point(S->br), NULL,
                         v, NULL, NULL);
  sc_ob_set_p(b->m, b->sp.param, u[1]);
  return sc_map_iterate_ex(b->m, u[0], S->period,
                           SC_EVAL_DERIV | SC_EVAL_ITINERARY, b->ctx.force,
                           NULL, NULL, v, NULL);
}

/* g = f^m for the continuation layer: along the segment's codes (forced),
 * or on the piece of itinerary ctx->itin only when codes cannot be
 * forced (leaving it is a recoverable failure, so such a segment never
 * crosses a discontinuity of f^m). */
static int g_fn(double x, const double *p, int order, sc_map1d_jet *jet,
                void *user) {
  g_ctx *c = user;
  if (sc_ob_set_p(c->m, c->param, p[c->param])) return 1;
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

/* Whether the orbit at (p, b->orb_c) lies on a branch computed before
 * this one: returns that branch, or -1.  Points near this segment's
 * own start (within 2 hmax) are not compared, so that a start continued
 * both ways does not join its twin at once.  Candidates are the points
 * within hmax in p whose smallest orbit point is near; the orbit is then
 * followed from the candidate to p by shooting and compared by the one
 * orbit-equality rule (sc_ob_same_orbit). */
static int joins(sc_orbit_branch *b, int branch, int period, double p,
                 double dmin, double p0, double d0, double hmax, int moved) {
  if (!moved && fabs(p - p0) + fabs(dmin - d0) <= TWIN_REACH_HMAX * hmax)
    return -1;
  for (size_t i = 0; i < b->npts; i++) {
    const point_rec *r = &b->pts[i];
    if (r->period != period || r->branch == branch) continue;
    double dp = fabs(r->p - p);
    if (dp > hmax || fabs(r->dmin - dmin) > JOIN_DMIN_ABS + JOIN_DMIN_SLOPE * dp)
      continue;
    if (fabs(r->p - p0) + fabs(r->dmin - d0) <= TWIN_REACH_HMAX * hmax)
      continue; /* the twin's start: compared once this one moved on */
    if (sc_ob_set_p(b->m, b->sp.param, r->p) ||
        sc_ob_iterate_orbit(b, r->d, period, b->seed))
      continue;
    sc_shoot_result res;
    if (sc_ob_shoot_at(b, period, p, b->seed, &res) != SC_OK) continue;
    if (sc_ob_same_orbit(b, b->orbit, b->orb_c, period)) return r->branch;
  }
  return -1;
}

/* The orbit of a multiple-shooting segment's start jb: shot (multiple)
 * from the iterates of jb->d, into b->orbit with the parameter after it;
 * its codes (b->codes), borders (b->bl_prev) and value (v) those of its
 * points, each iterate from its own: iterating f^m from d would carry
 * the error the switch is about.  1, or 0 where shooting fails (the
 * segment is then continued by single shooting, as before). */
static int ms_start_orbit(sc_orbit_branch *b, int period, const job *jb,
                          sc_map_value *v) {
  sc_shoot_result res;
  if (sc_ob_iterate_orbit(b, jb->d, period, b->seed) ||
      sc_ob_shoot_at(b, period, jb->p, b->seed, &res) != SC_OK)
    return 0;
  b->orbit[period] = jb->p;
  sc_map_value w;
  if (sc_ob_ms_eval(b, NULL, period, b->orbit, &b->bl_prev, &w, NULL,
                    b->codes2))
    return 0;
  for (int i = 0; i < period; i++)
    if (b->codes2[i].n <= 0) return 0;
  memcpy(b->codes, b->codes2, (size_t)period * sizeof *b->codes);
  *v = w;
  return 1;
}

/* The start: the codes of the orbit at the first point (forced from now
 * on where the model has them), the continuation problem and its start
 * (moved further along when the start next to a located point fails). */
static int segment_start(sc_orbit_branch *b, segment *S, sc_cont_problem *pb,
                         sc_map1d_system *sys, sc_msg *msg) {
  sc_map *m = b->m;
  const job *jb = S->jb;
  int period = S->period;
  sc_map_value v;
  if (sc_ob_set_p(m, b->sp.param, jb->p))
    return sc_fail(msg, SC_EINVAL, "branch: %s = %.17g out of range",
                   sc_map_type(m)->params[b->sp.param].name, jb->p);
  int forced = sc_map_has_borders(m);
  int st = forced ? sc_ob_orbit_borders(b, jb->d, period, NULL, b->codes,
                                        &b->bl_prev, &v, msg)
                  : sc_map_iterate(m, jb->d, period,
                                   SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v, msg);
  if (st) return st;
  for (int i = 0; forced && i < period; i++) forced = b->codes[i].n > 0;
  int ms = forced && sc_ob_ms_wanted(b, period, jb->d, v.dfdd) &&
           ms_start_orbit(b, period, jb, &v);
  b->ctx = (g_ctx){.m = m, .param = b->sp.param, .period = period,
                   .force = forced ? b->codes : NULL,
                   .lock = sc_map_has_borders(m) && !forced};
  snprintf(b->ctx.itin, sizeof b->ctx.itin, "%s", v.itinerary);
  *sys = (sc_map1d_system){.fn = g_fn, .user = &b->ctx,
                           .kind = SC_MAP1D_FIXED, .np = sc_map_nparam(m),
                           .ifree = {(int)b->sp.param, 0}};
  for (size_t i = 0; i < sys->np; i++) sys->p[i] = sc_map_get_param(m, i);
  /* an orbit that amplifies the map's error beyond what single shooting
   * resolves is continued by multiple shooting (branch_ms.c) */
  st = ms ? sc_ob_ms_problem(b, S, pb, msg) : sc_map1d_problem(sys, pb, msg);
  if (st) return st;
  sc_cont_settings *set = &S->set;
  sc_cont_settings_default(set);
  set->hmax = sc_ob_hmax(b);
  set->h0 = b->sp.h0 > 0 ? fmin(b->sp.h0, set->hmax)
                         : set->hmax / H0_AUTO_FRACTION;
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
  double u0s[2] = {jb->d, jb->p}, *u0 = S->ms ? S->ms_start : u0s;
  if (S->ms) memcpy(u0, b->orbit, ((size_t)period + 1) * sizeof *u0);
  st = sc_branch_set(S->br, u0, msg);
  /* A start just beyond a located point may sit where the orbit is
   * nearly singular (f' grows like |d - d*|^(-1/2) near a switching):
   * move it further along, START_MOVE_GROWTH times at a time. */
  double off = jb->offset;
  for (int k = 0; st && off > 0 && k < START_MOVES; k++) {
    /* jb->p is off beyond the located point: move to START_MOVE_GROWTH
     * times off beyond it */
    double p1 = jb->p + jb->direction * (START_MOVE_GROWTH - 1) * off;
    off *= START_MOVE_GROWTH;
    if (p1 < set->pmin || p1 > set->pmax || sc_ob_set_p(m, b->sp.param, p1))
      break;
    if (sc_ob_iterate_orbit(b, jb->d, period, b->seed)) break;
    sc_shoot_result res;
    /* The orbit found must still be of minimal period `period`: next to a
     * flip the doubled period-m/2 orbit has the same itinerary and is a
     * fixed point of f^period too, and continuing it would follow the
     * old branch twice over. */
    if (sc_ob_shoot_at(b, period, p1, b->seed, &res) != SC_OK ||
        strcmp(res.itinerary, b->ctx.itin) != 0 ||
        sc_ob_minimal_period(b, b->orbit, period, NULL) != period)
      continue;
    if (S->ms) {
      memcpy(u0, b->orbit, (size_t)period * sizeof *u0);
      u0[period] = p1;
    } else {
      u0[0] = b->orbit[0];
      u0[1] = p1;
    }
    st = sc_branch_set(S->br, u0, msg);
  }
  if (st) {
    char why[SC_MSG_LEN];
    snprintf(why, sizeof why, "%s", msg ? msg->text : "");
    sc_ob_add_end(b, S->branch, period, jb->p, jb->d, v.dfdd,
                  "start failed (%s): %.300s", sc_strerror(st), why);
    return SC_END;
  }
  /* the borders at the corrected start are the reference */
  const double *u = seg_point(S);
  if (S->ms)
    sc_ob_ms_eval(b, b->codes, period, sc_branch_point(S->br), &b->bl_prev,
                  &v, NULL, NULL);
  else if (b->ctx.force && sc_ob_set_p(m, b->sp.param, u[1]) == SC_OK)
    sc_ob_orbit_borders(b, u[0], period, b->codes, NULL, &b->bl_prev, &v, NULL);
  seg_keep(S);
  S->last_p = u[1], S->last_d = u[0], S->last_t = jb->direction;
  S->last_td = 0;
  S->last_mult = v.dfdd;
  S->p_first = S->dmin_first = S->prev_p = NAN;
  S->nrej = sc_branch_nrejected_special(S->br);
  return SC_OK;
}

/* Accept the point u: its minimal period, the record, joins and closing.
 * Returns 1 when the segment ends here. */
static int segment_accept(sc_orbit_branch *b, segment *S, const double *u) {
  sc_map *m = b->m;
  int period = S->period;
  sc_ob_set_p(m, b->sp.param, u[1]);
  double dmin = u[0];
  int have_orbit =
      S->ms ? (memcpy(b->orb_c, sc_branch_point(S->br),
                      (size_t)period * sizeof *b->orb_c),
               1)
            : !sc_ob_iterate_orbit_forced(b, u[0], period, b->ctx.force,
                                          b->orb_c);
  if (have_orbit)
    for (int k = 1; k < period; k++) dmin = fmin(dmin, b->orb_c[k]);
  /* A period-m segment whose orbit has fallen to a divisor of m has
   * left its branch for a lower-period one crossing it (the doubled
   * orbit at a flip): stop rather than follow the old branch again. */
  int q = have_orbit && period > 1 ? sc_ob_minimal_period(b, b->orb_c, period, b->ctx.force)
                                   : period;
  if (q < period) {
    /* Follow the lower-period branch from here instead, both ways, with
     * its own period (joins() stops it where it was computed before). */
    char origin[96];
    snprintf(origin, sizeof origin, "period-%d segment at %.10g", period,
             u[1]);
    int pushed = sc_ob_push_job(b, q, u[1], u[0], 1, 0, origin);
    pushed += sc_ob_push_job(b, q, u[1], u[0], -1, 0, origin);
    /* The end is the last point of minimal period `period` (the segment
     * met the period-q branch between it and this one). */
    int first = isnan(S->p_first);
    special_rec *r = sc_ob_add_special(
        b, SC_PT_EP, S->branch, period, first ? u[1] : S->last_p,
        first ? u[0] : S->last_d, S->last_mult, NAN);
    if (r)
      snprintf(r->note, sizeof r->note,
               "the segment met the period-%d branch between here and "
               "%.12g, where the orbit's minimal period is %d: it ends "
               "here%s",
               q, u[1], q, pushed ? "; that branch is followed" : "");
    return 1;
  }
  sc_map_value v;
  if (seg_value(b, S, u, &v) == SC_OK) {
    sc_ob_add_point(b, S->branch, period, u[1], u[0], &v, dmin);
    S->last_mult = v.dfdd;
  }
  if (isnan(S->p_first)) {
    S->p_first = u[1], S->dmin_first = dmin;
    memcpy(b->orb_f, b->orb_c, (size_t)period * sizeof *b->orb_f);
  }
  if (fabs(u[1] - S->p_first) + fabs(dmin - S->dmin_first) >
      MOVED_HMAX * S->set.hmax)
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
    if (sc_ob_shoot_at(b, period, S->p_first, b->orb_a, &res) == SC_OK &&
        sc_ob_same_orbit(b, b->orbit, b->orb_f, period))
      jn = S->branch;
  }
  if (b->sp.nmarks) sc_ob_marks(b, S, u);
  S->prev_p = u[1];
  if (jn >= 0) {
    special_rec *r = sc_ob_add_special(b, SC_PT_EP, S->branch, period, u[1],
                                       u[0], v.dfdd, NAN);
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

/* A fold or flip located by the continuation layer (unless a border lies
 * between it and the last point: then that border ends the segment and
 * the fold or flip, on the smooth extension beyond it, is not real). */
static int segment_special(sc_orbit_branch *b, segment *S) {
  int period = S->period;
  const double *us = seg_point(S);
  int bc = sc_ob_border_crossed(b, S, us);
  if (bc == 2) sc_ob_fall_back(b, S, S->jb, NULL);
  if (bc) return 1;
  int test = sc_branch_location(S->br)->test;
  sc_map_value v;
  seg_value(b, S, us, &v);
  sc_point_label l = test == 0 ? SC_PT_LP : SC_PT_PD;
  special_rec *r =
      sc_ob_add_special(b, l, S->branch, period, us[1], us[0], v.dfdd,
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
      int ok = sc_ob_switch_flip(b, period, us[1], us[0]);
      size_t n = strlen(r->note);
      snprintf(r->note + n, sizeof r->note - n, "%s",
               ok && b->njobs > n0
                   ? "; the period-doubled branch is followed"
               : 2 * period > b->sp.max_period
                   ? "; period doubling not followed (max-period)"
                   : "; no period-doubled orbit found (or max-branches)");
    }
  }
  if (b->sp.nmarks) sc_ob_marks(b, S, us);
  /* this point is now the reference for the borders */
  sc_border_list t = b->bl_prev;
  b->bl_prev = b->bl_cur;
  b->bl_cur = t;
  S->last_p = us[1], S->last_d = us[0];
  seg_keep(S);
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
  special_rec *r = sc_ob_add_special(b, l, S->branch, S->period, u[1], u[0],
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

int sc_ob_run_segment(sc_orbit_branch *b, const job *jb, int branch,
                      sc_msg *msg) {
  segment S = {.jb = jb, .branch = branch, .period = jb->period};
  sc_cont_problem pb;
  sc_map1d_system sys;
  int st = segment_start(b, &S, &pb, &sys, msg);
  if (st == SC_END || st) {
    sc_branch_free(S.br);
    sc_ob_ms_free(&S);
    return st == SC_END ? SC_OK : st;
  }
  int period = S.period;
  for (;;) {
    const double *u = seg_point(&S);
    int bc = sc_ob_border_crossed(b, &S, u);
    if (bc == 2) {
      sc_ob_fall_back(b, &S, jb, msg);
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
    S.last_t = seg_tangent(&S)[1];
    S.last_td = seg_tangent(&S)[0];
    seg_keep(&S);
    if (b->sp.progress && b->sp.progress(b->sp.progress_ctx, b->npts)) {
      sc_branch_free(S.br);
      sc_ob_ms_free(&S);
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
      const double *ue = seg_point(&S);
      int bce = sc_ob_border_crossed(b, &S, ue);
      if (bce == 2) sc_ob_fall_back(b, &S, jb, msg);
      if (bce) break;
      if (segment_accept(b, &S, ue)) break;
      int maxed = (long)sc_branch_npoints(S.br) >= b->sp.max_points;
      sc_ob_add_end(
          b, branch, period, ue[1], ue[0], S.last_mult, "%s%s",
          maxed ? "max-points reached" : "end of the parameter interval", NULL);
      break;
    }
    if (st == SC_ENOCONV) {
      /* The corrector cannot go on: a forced event disappears (a grazing
       * met from the side where the guard fires), the map is undefined
       * ahead, or an itinerary boundary of an unforced segment. */
      int dir = S.last_t > 0 ? 1 : S.last_t < 0 ? -1 : jb->direction;
      if (sc_ob_locate_ahead(b, &S, dir)) break;
      sc_ob_fall_back(b, &S, jb, msg);
      break;
    }
    /* Errors. */
    sc_ob_add_end(b, branch, period, S.last_p, S.last_d, NAN,
                  "error %s: %.300s", sc_strerror(st), msg ? msg->text : "");
    break;
  }
  sc_branch_free(S.br);
  sc_ob_ms_free(&S);
  return SC_OK;
}
