/* The two-block Burridge-Knopoff model of MODEL.md: exact closed-form
 * flows in every mode, certified event location (src/hybrid/guard.c),
 * the event map f(d) with derivatives propagated through the flows and
 * across events in forward mode (src/hybrid/dual.h), and trajectories.
 * Numerical flows (GSL odeiv2) for the same model live in
 * bk2_numerical.c and share the event logic here.  The derivation of
 * every formula is in docs/derivations.md. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

#include "hybrid/dual.h"
#include "models/bk2_impl.h"
#include "models/bk2_quad.h"
#include "hybrid/hybrid_impl.h"
#include "slipcont/hybrid.h"

static const sc_param_info bk2_params[] = {
    {"alpha", 3, 0, 1e6, 1, 0, "coupling spring / driver spring, k_c/k", NULL},
    {"beta", 1, 0, 1e6, 1, 0, "static friction of block 2 / block 1", NULL},
    {"phi", 1.25, 1, 1e6, 1, 0, "static / kinetic friction ratio, 1/mu", NULL},
    {"v", 0.025, 0, 1e3, 0, 0, "driver velocity V (dimensionless)", "V"},
};

static const sc_option_info bk2_options[] = {
    {"driver",
     {"moving", "frozen", NULL},
     "the driver keeps moving during slips, or stops (assumption 1)"},
    {"friction",
     {"coulomb", "velocity-weakening", NULL},
     "kinetic friction: constant mu T_i, or T_i / (1 + |U_i - V_s|)"},
    {"flows",
     {"exact", "numerical", NULL},
     "closed-form flows, or GSL odeiv2 integration"},
};

double sc_bk2_dstar(double alpha, double beta) {
  return (beta - 1) / (1 + 2 * alpha);
}

/* Slip phases of one block alone last less than one period; a phase of
 * both blocks is quasi-periodic, so a horizon is needed: this many periods
 * of its slow mode (frequency 1) without a re-stick make f undefined. */
#define SLIP12_PERIODS 16

static int bk2_setup(void *vinst, const double *p, const int *opt,
                     const sc_accuracy *acc, sc_msg *msg) {
  bk2_inst *b = vinst;
  b->alpha = p[0];
  b->beta = p[1];
  b->phi = p[2];
  b->v = p[3];
  b->frozen = opt[0] == 1;
  b->vw = opt[1] == 1;
  b->numerical = opt[2] == 1 || b->vw;
  b->acc = *acc;
  b->mu = 1 / b->phi;
  b->w1 = sqrt(1 + b->alpha);
  b->w2 = sqrt(1 + 2 * b->alpha);
  b->vs = b->frozen ? 0 : b->v;
  b->dstar = sc_bk2_dstar(b->alpha, b->beta);
  sc_bk2_dparams(b, 0, &b->p0); /* value-only evaluations start from it */
  if (b->vw && b->frozen)
    return sc_fail(msg, SC_EINVAL,
                   "bk2: friction = velocity-weakening with driver = frozen "
                   "is ill posed (a slip cannot start; MODEL.md): use "
                   "driver = moving");
  if (b->vw)
    /* The numerical path integrates it, but its start (K = T at zero
     * relative velocity, so the re-stick guard has a double root at the
     * onset) is not yet handled or validated: refuse rather than guess. */
    return sc_fail(msg, SC_EINVAL,
                   "bk2: friction = velocity-weakening is not available yet "
                   "(valid: coulomb)");
  if (b->numerical && acc->precision == SC_PRECISION_QUAD)
    return sc_fail(msg, SC_EINVAL,
                   "bk2: precision = quad needs flows = exact (the numerical "
                   "flows are double only)");
  if (b->numerical) return sc_bk2_num_setup(b, msg);
  return SC_OK;
}

static void bk2_release(void *vinst) { sc_bk2_num_release(vinst); }

/* ---- parameters as duals ------------------------------------------- */

void sc_bk2_dparams(const bk2_inst *b, int nd, bk2_dpar *P) {
  P->nd = nd;
  P->alpha = sc_dvar(b->alpha, 1, nd);
  P->beta = sc_dvar(b->beta, 2, nd);
  sc_dual phi = sc_dvar(b->phi, 3, nd);
  P->mu = sc_ddiv(sc_dconst(1, nd), phi, nd);
  P->k1 = P->mu;
  P->k2 = sc_dmul(P->beta, P->mu, nd);
  P->t2 = P->beta;
  P->v = sc_dvar(b->v, 4, nd);
  P->vs = b->frozen ? sc_dconst(0, nd) : P->v;
  P->w1 = sc_dsqrt(sc_daddc(P->alpha, 1), nd);
  P->w2 = sc_dsqrt(sc_daddc(sc_dscale(P->alpha, 2, nd), 1), nd);
}

/* Spring forces S1 = (1+alpha) Y1 - alpha Y2, S2 = (1+alpha) Y2 - alpha Y1. */
static sc_dual spring(const bk2_dpar *P, sc_dual ya, sc_dual yb) {
  int nd = P->nd;
  return sc_dadd(ya, sc_dmul(P->alpha, sc_dsub(ya, yb, nd), nd), nd);
}

/* ---- the forced oscillator q'' + w^2 q = F0 + F1 t ------------------- */

/* Coefficients of q(t) = s0 + s1 t + A cos(w t) + B sin(w t). */
typedef struct {
  sc_dual s0, s1, A, B, w;
} osc;

static osc osc_make(sc_dual q0, sc_dual p0, sc_dual F0, sc_dual F1, sc_dual w,
                    int nd) {
  osc o;
  sc_dual w2 = sc_dmul(w, w, nd);
  o.s0 = sc_ddiv(F0, w2, nd);
  o.s1 = sc_ddiv(F1, w2, nd);
  o.A = sc_dsub(q0, o.s0, nd);
  o.B = sc_ddiv(sc_dsub(p0, o.s1, nd), w, nd);
  o.w = w;
  return o;
}

/* q(t), q'(t) and q''(t) at a plain time t (derivatives at fixed t). */
static void osc_at(const osc *o, double t, int nd, sc_dual *q, sc_dual *p,
                   double *acc) {
  sc_dual wt = sc_dscale(o->w, t, nd), s, c;
  sc_dsincos(wt, nd, &s, &c);
  sc_dual Ac = sc_dmul(o->A, c, nd), Bs = sc_dmul(o->B, s, nd);
  *q = sc_dadd(sc_daxpy(o->s0, t, o->s1, nd), sc_dadd(Ac, Bs, nd), nd);
  *p = sc_dadd(o->s1,
               sc_dmul(o->w,
                       sc_dsub(sc_dmul(o->B, c, nd), sc_dmul(o->A, s, nd), nd),
                       nd),
               nd);
  if (acc) *acc = -o->w.v * o->w.v * (Ac.v + Bs.v);
}

/* Guard pieces: q(t) and q'(t) as c0 + c1 t + a cos + b sin, scaled. */
static void guard_add_q(sc_guard *g, const osc *o, double scale) {
  g->c0 += scale * o->s0.v;
  g->c1 += scale * o->s1.v;
  g->w[g->n] = o->w.v;
  g->a[g->n] = scale * o->A.v;
  g->b[g->n] = scale * o->B.v;
  g->n++;
}

static void guard_add_qdot(sc_guard *g, const osc *o, double scale) {
  double w = o->w.v;
  g->c0 += scale * o->s1.v;
  g->w[g->n] = w;
  g->a[g->n] = scale * w * o->B.v;
  g->b[g->n] = -scale * w * o->A.v;
  g->n++;
}

/* ---- one mode ------------------------------------------------------- */

/* The flow of one slip mode from x0, in closed form. */
typedef struct {
  int mode;
  osc o1, o2;     /* SLIP1/SLIP2: o1 the slipping block; SLIP12: sum, dif */
  bk2_state x0;
} mode_flow;

static mode_flow flow_make(const bk2_dpar *P, int mode, const bk2_state *x0) {
  int nd = P->nd;
  mode_flow f;
  f.mode = mode;
  f.x0 = *x0;
  if (mode == SC_BK2_SLIP1) {
    /* Y1'' = mu - (1+alpha) Y1 + alpha (Y20 + Vs t) */
    f.o1 = osc_make(x0->y1, x0->u1,
                    sc_dadd(P->k1, sc_dmul(P->alpha, x0->y2, nd), nd),
                    sc_dmul(P->alpha, P->vs, nd), P->w1, nd);
  } else if (mode == SC_BK2_SLIP2) {
    f.o1 = osc_make(x0->y2, x0->u2,
                    sc_dadd(P->k2, sc_dmul(P->alpha, x0->y1, nd), nd),
                    sc_dmul(P->alpha, P->vs, nd), P->w1, nd);
  } else {
    /* Sum'' + Sum = mu (1 + beta), Dif'' + w2^2 Dif = mu (1 - beta) */
    f.o1 = osc_make(sc_dadd(x0->y1, x0->y2, nd), sc_dadd(x0->u1, x0->u2, nd),
                    sc_dadd(P->k1, P->k2, nd), sc_dconst(0, nd),
                    sc_dconst(1, nd), nd);
    f.o2 = osc_make(sc_dsub(x0->y1, x0->y2, nd), sc_dsub(x0->u1, x0->u2, nd),
                    sc_dsub(P->k1, P->k2, nd), sc_dconst(0, nd), P->w2, nd);
  }
  return f;
}

/* State at time t of the mode, and the accelerations (values). */
static void flow_at(const bk2_dpar *P, const mode_flow *f, double t,
                    bk2_state *x, double acc[2]) {
  int nd = P->nd;
  sc_dual q, p;
  double a;
  if (f->mode == SC_BK2_SLIP1) {
    osc_at(&f->o1, t, nd, &q, &p, &a);
    x->y1 = q, x->u1 = p;
    x->y2 = sc_daxpy(f->x0.y2, t, P->vs, nd);
    x->u2 = P->vs;
    acc[0] = a, acc[1] = 0;
  } else if (f->mode == SC_BK2_SLIP2) {
    osc_at(&f->o1, t, nd, &q, &p, &a);
    x->y2 = q, x->u2 = p;
    x->y1 = sc_daxpy(f->x0.y1, t, P->vs, nd);
    x->u1 = P->vs;
    acc[0] = 0, acc[1] = a;
  } else {
    sc_dual q2, p2;
    double a2;
    osc_at(&f->o1, t, nd, &q, &p, &a);
    osc_at(&f->o2, t, nd, &q2, &p2, &a2);
    x->y1 = sc_dscale(sc_dadd(q, q2, nd), 0.5, nd);
    x->y2 = sc_dscale(sc_dsub(q, q2, nd), 0.5, nd);
    x->u1 = sc_dscale(sc_dadd(p, p2, nd), 0.5, nd);
    x->u2 = sc_dscale(sc_dsub(p, p2, nd), 0.5, nd);
    acc[0] = 0.5 * (a + a2), acc[1] = 0.5 * (a - a2);
  }
}

/* The re-stick guard U_i - Vs of slipping block i (1 or 2). */
static sc_guard guard_restick(const bk2_dpar *P, const mode_flow *f, int i) {
  sc_guard g = {0};
  g.c0 = -P->vs.v;
  if (f->mode != SC_BK2_SLIP12) {
    guard_add_qdot(&g, &f->o1, 1);
  } else {
    guard_add_qdot(&g, &f->o1, 0.5);
    guard_add_qdot(&g, &f->o2, i == 1 ? 0.5 : -0.5);
  }
  return g;
}

/* The threshold guard S_j - T_j of the stuck block j while the other
 * slips alone: S_j = (1+alpha)(Yj0 + Vs t) - alpha q(t). */
static sc_guard guard_threshold(const bk2_dpar *P, const mode_flow *f) {
  sc_guard g = {0};
  double a = P->alpha.v;
  int j = f->mode == SC_BK2_SLIP1 ? 2 : 1;
  double yj0 = j == 2 ? f->x0.y2.v : f->x0.y1.v;
  double tj = j == 2 ? P->t2.v : 1;
  g.c0 = (1 + a) * yj0 - tj;
  g.c1 = (1 + a) * P->vs.v;
  guard_add_q(&g, &f->o1, -a);
  return g;
}

/* A horizon past which the guard keeps one sign (or its pattern repeats):
 * one period for a pure sinusoid, the time the linear term needs to
 * dominate otherwise. */
static double guard_horizon(const sc_guard *g) {
  double amp = 0, wmin = HUGE_VAL;
  for (int k = 0; k < g->n; k++) {
    amp += fabs(g->a[k]) + fabs(g->b[k]); /* >= the amplitude: enough here */
    wmin = fmin(wmin, g->w[k]);
  }
  double period = 2 * SC_PI / wmin;
  if (g->c1 != 0) return (fabs(g->c0) + amp) / fabs(g->c1) + period;
  if (g->n == 1) return 1.01 * period;
  return SLIP12_PERIODS * period;
}

/* ---- the event logic, shared with numerical flows --------------------- */

/* Apply the event-time sensitivity: the guard gval (a dual evaluated at
 * fixed time) vanishes at the event, so dt = -dg / g' and the state moves
 * along its velocity: x += xdot dt. */
void sc_bk2_event_shift(const bk2_dpar *P, sc_dual gval, double slope,
                        const double acc[2], bk2_state *x) {
  int nd = P->nd;
  if (nd == 0) return;
  double dt[SC_NDIR];
  /* g' = 0: the event time is not differentiable (f' is infinite there,
   * MODEL.md: |d - d*|^(-1/2) at d* with V_s = 0): say so with NaN. */
  for (int k = 0; k < nd; k++) dt[k] = slope != 0 ? -gval.d[k] / slope : NAN;
  double xdot[4] = {x->u1.v, x->u2.v, acc[0], acc[1]};
  sc_dual *xs[4] = {&x->y1, &x->y2, &x->u1, &x->u2};
  for (int i = 0; i < 4; i++)
    for (int k = 0; k < nd; k++) xs[i]->d[k] += xdot[i] * dt[k];
}

int sc_bk2_take_event(const bk2_dpar *P, int mode, int kind, double slope,
                      const double acc[2], bk2_state *x) {
  int nd = P->nd;
  if (nd) {
    /* the guard on duals at fixed time: its sensitivity moves the event */
    sc_dual gv;
    if (kind == 1) gv = sc_dsub(x->u1, P->vs, nd);
    else if (kind == 2) gv = sc_dsub(x->u2, P->vs, nd);
    else if (mode == SC_BK2_SLIP1)
      gv = sc_dsub(spring(P, x->y2, x->y1), P->t2, nd);
    else
      gv = sc_daddc(spring(P, x->y1, x->y2), -1);
    sc_bk2_event_shift(P, gv, slope, acc, x);
  }
  switch (kind) {
  case 1:
    x->u1 = P->vs;
    return mode == SC_BK2_SLIP1 ? SC_BK2_STICK : SC_BK2_SLIP2;
  case 2:
    x->u2 = P->vs;
    return mode == SC_BK2_SLIP2 ? SC_BK2_STICK : SC_BK2_SLIP1;
  default:
    return SC_BK2_SLIP12;
  }
}

static void itin_add(char *itin, size_t *len, int mode, unsigned flags) {
  if (!(flags & SC_EVAL_ITINERARY)) return;
  const char *tok = mode == SC_BK2_SLIP1 ? "1" : mode == SC_BK2_SLIP2 ? "2"
                                                                        : "12";
  size_t need = strlen(tok) + (*len ? 1 : 0);
  if (*len + need + 4 >= SC_ITIN_LEN) {
    if (*len + 4 < SC_ITIN_LEN && strcmp(itin + *len - 3, "...") != 0) {
      strcpy(itin + *len, "...");
      *len += 3;
    }
    return;
  }
  if (*len) itin[(*len)++] = '-';
  strcpy(itin + *len, tok);
  *len += strlen(tok);
}

/* The state at the onset of the slip that ends the GSP of displacement d:
 * block 1 at threshold iff d < d* (MODEL.md "The event map"). */
int sc_bk2_onset(const bk2_inst *b, const bk2_dpar *P, sc_dual d,
                 bk2_state *x) {
  int nd = P->nd;
  int mode;
  if (d.v < b->dstar) {
    x->y1 = sc_daddc(sc_dmul(P->alpha, d, nd), 1);
    x->y2 = sc_dadd(x->y1, d, nd);
    mode = SC_BK2_SLIP1;
  } else {
    x->y2 = sc_dsub(P->beta, sc_dmul(P->alpha, d, nd), nd);
    x->y1 = sc_dsub(x->y2, d, nd);
    mode = d.v > b->dstar ? SC_BK2_SLIP2 : SC_BK2_SLIP12;
  }
  x->u1 = x->u2 = P->vs;
  return mode;
}

/* One slip phase with exact flows: find its end, the next mode, and the
 * state there.  `fresh` bit i-1: block i started slipping at this phase's
 * start (U_i = Vs by construction, so its re-stick guard starts at zero).
 * Returns the next mode, or a negative status. */
static int exact_phase(const bk2_inst *b, const bk2_dpar *P, int mode,
                       int fresh, bk2_state *x, double *duration,
                       bk2_events *ev, sc_msg *msg) {
  mode_flow f = flow_make(P, mode, x);
  const sc_accuracy *acc = &b->acc;
  double atol = acc->event_atol, rtol = acc->event_rtol;
  /* Candidate events: re-stick of each slipping block, threshold of the
   * stuck one. */
  sc_guard g[2];
  int kind[2], ng = 0; /* kind: 1, 2 re-stick of block i; 3 threshold */
  /* Later guards are searched only up to the earliest root so far, so
   * the likelier first event goes first: in SLIP12, the block that has
   * slipped longer (not fresh) usually re-sticks first. */
  int order[2] = {1, 2};
  if (mode == SC_BK2_SLIP12 && (fresh & 1) && !(fresh & 2))
    order[0] = 2, order[1] = 1;
  for (int k = 0; k < 2; k++) {
    int i = order[k];
    if (mode == i || mode == SC_BK2_SLIP12) {
      g[ng] = guard_restick(P, &f, i);
      kind[ng++] = i;
    }
  }
  if (mode != SC_BK2_SLIP12) {
    g[ng] = guard_threshold(P, &f);
    kind[ng++] = 3;
  }
  sc_root r[2];
  double tmax = 0;
  for (int i = 0; i < ng; i++) tmax = fmax(tmax, guard_horizon(&g[i]));
  int first = -1;
  for (int i = 0; i < ng; i++) {
    int skip = kind[i] < 3 && (fresh & kind[i]);
    double lim = first < 0 ? tmax : r[first].t + atol + rtol * r[first].t;
    int st = sc_guard_first_root(&g[i], lim, skip, atol, rtol, &r[i]);
    if (st)
      return sc_fail(msg, SC_EINTERNAL,
                     "bk2: malformed guard in mode %d (parameters out of "
                     "range?)",
                     mode);
    ev->steps += r[i].steps;
    if (r[i].found && (first < 0 || r[i].t < r[first].t)) first = i;
  }
  if (first < 0)
    return sc_fail(msg, SC_EUNDEF,
                   "no event within %.6g time units of slip mode %s: the "
                   "slip does not end",
                   tmax, mode == SC_BK2_SLIP12 ? "12" : mode == 1 ? "1" : "2");
  /* Ties within the event tolerance: re-sticks go first (MODEL.md); two
   * re-sticks at once end the slip of both blocks. */
  int both = 0;
  for (int i = 0; i < ng; i++) {
    if (i == first || !r[i].found) continue;
    double tol = atol + rtol * r[first].t;
    if (fabs(r[i].t - r[first].t) <= tol) {
      if (kind[first] == 3) first = i;
      else if (kind[i] < 3) both = 1;
    }
  }
  double t = r[first].t;
  double a2[2];
  flow_at(P, &f, t, x, a2);
  *duration = t;
  if (r[first].tangent) ev->tangent = 1;
  /* Grazing margin of a re-stick: the height slope^2 / (2 |g''|) that the
   * local maximum of U_i - Vs reaches above zero just after the root. */
  if (kind[first] < 3) {
    double gpp;
    sc_guard_eval(&g[first], t, NULL, NULL, &gpp);
    double h = gpp < 0 ? r[first].slope * r[first].slope / (2 * -gpp)
                       : HUGE_VAL;
    if (h < ev->graze_margin) {
      ev->graze_margin = h;
      ev->graze_block = kind[first];
      ev->graze_mode = mode;
    }
  }
  int next = sc_bk2_take_event(P, mode, kind[first], r[first].slope, a2, x);
  return both ? SC_BK2_STICK : next;
}

int sc_bk2_phase(const bk2_inst *b, const bk2_dpar *P, int mode, int fresh,
                 bk2_state *x, double *duration, bk2_events *ev,
                 sc_msg *msg) {
  if (b->numerical)
    return sc_bk2_num_phase(b, P, mode, fresh, x, duration, ev, msg);
  return exact_phase(b, P, mode, fresh, x, duration, ev, msg);
}

/* Which blocks start slipping when entering `next` from `mode`. */
static int fresh_blocks(int mode, int next) {
  if (mode == SC_BK2_STICK)
    return next == SC_BK2_SLIP1 ? 1 : next == SC_BK2_SLIP2 ? 2 : 3;
  if (next == SC_BK2_SLIP12) return mode == SC_BK2_SLIP1 ? 2 : 1;
  return 0;
}

/* Follow the motion from the GSP of displacement d to the next GSP. */
int sc_bk2_iterate(const bk2_inst *b, const bk2_dpar *P, sc_dual d,
                   unsigned flags, bk2_state *x, sc_map_value *out,
                   bk2_phase_fn fn, void *ctx, sc_msg *msg) {
  int nd = P->nd;
  int mode = sc_bk2_onset(b, P, d, x);
  int fresh = fresh_blocks(SC_BK2_STICK, mode);
  bk2_events ev = {.graze_margin = HUGE_VAL};
  size_t ilen = 0;
  out->itinerary[0] = '\0';
  out->dstar_dist = fabs(d.v - b->dstar);
  int first_mode = mode;
  for (int n = 0; n < b->acc.max_events; n++) {
    bk2_state x0 = *x;
    double dur;
    itin_add(out->itinerary, &ilen, mode, flags);
    int next = sc_bk2_phase(b, P, mode, fresh, x, &dur, &ev, msg);
    if (next < 0) return next;
    out->nphases++;
    if (fn) {
      int st = fn(ctx, mode, &x0, dur);
      if (st) return st;
    }
    if (next == SC_BK2_STICK) {
      sc_dual dn = sc_dsub(x->y2, x->y1, nd);
      out->f = dn.v;
      if (nd) {
        out->dfdd = dn.d[0];
        for (int k = 0; k < 4; k++) out->dfdp[k] = dn.d[k + 1];
      }
      /* One block slipping alone from a GSP: f(d) = d + c (MODEL.md),
       * f' = 1 exactly, whatever rounding says. */
      out->neutral = out->nphases == 1 && first_mode != SC_BK2_SLIP12;
      if (out->neutral && nd) out->dfdd = 1;
      double s1 = spring(P, x->y1, x->y2).v, s2 = spring(P, x->y2, x->y1).v;
      out->gsp_gap = fmin(1 - s1, b->beta - s2);
      out->gap_block = 1 - s1 <= b->beta - s2 ? 1 : 2;
      out->graze_margin = ev.graze_margin;
      out->graze_block = ev.graze_block;
      out->graze_mode = ev.graze_mode;
      return SC_OK;
    }
    fresh = fresh_blocks(mode, next);
    mode = next;
  }
  return sc_fail(msg, SC_EUNDEF,
                 "no return to a global stick phase after %d slip phases "
                 "(max-events): the motion settles on a slip cycle",
                 b->acc.max_events);
}

_Static_assert(1 + 4 <= SC_NDIR, "bk2 needs d and four parameters");

static int bk2_eval(void *vinst, double d, unsigned flags, sc_map_value *out,
                    sc_msg *msg) {
  const bk2_inst *b = vinst;
  if (b->acc.precision == SC_PRECISION_QUAD) /* bk2_quad.c */
    return sc_bk2_quad_eval(b->alpha, b->beta, b->phi, b->v, b->frozen,
                            b->acc.max_events, d, flags, out, msg);
  bk2_dpar P;
  int nd = (flags & SC_EVAL_DERIV) ? 5 : 0;
  if (nd) sc_bk2_dparams(b, nd, &P);
  else P = b->p0;
  bk2_state x;
  return sc_bk2_iterate(b, &P, sc_dvar(d, 0, nd), flags, &x, out, NULL, NULL,
                        msg);
}

/* ---- trajectories --------------------------------------------------- */

typedef struct {
  const bk2_inst *b;
  const bk2_dpar *P;
  double tau, dtau;
  int (*fn)(void *, double, const double *, int);
  void *ctx;
} traj_ctx;

static int emit(traj_ctx *c, double tau, const bk2_state *x, int mode) {
  double s[4] = {x->y1.v, x->y2.v, x->u1.v, x->u2.v};
  return c->fn(c->ctx, tau, s, mode) ? SC_ECALLBACK : SC_OK;
}

/* Sample one finished slip phase every dtau and at its end. */
static int traj_phase(void *vc, int mode, const bk2_state *x0, double dur) {
  traj_ctx *c = vc;
  const bk2_inst *b = c->b;
  if (b->numerical) return sc_bk2_num_sample(b, c->P, mode, x0, dur, c);
  mode_flow f = flow_make(c->P, mode, x0);
  double a2[2];
  bk2_state x;
  long n = (long)floor(dur / c->dtau);
  for (long i = 0; i <= n; i++) {
    double t = i * c->dtau;
    flow_at(c->P, &f, t, &x, a2);
    if (emit(c, c->tau + t, &x, mode)) return SC_ECALLBACK;
  }
  flow_at(c->P, &f, dur, &x, a2);
  if (emit(c, c->tau + dur, &x, mode)) return SC_ECALLBACK;
  c->tau += dur;
  return SC_OK;
}

int sc_bk2_traj_emit(void *vc, double t, const double s[4], int mode) {
  traj_ctx *c = vc;
  return c->fn(c->ctx, c->tau + t, s, mode) ? SC_ECALLBACK : SC_OK;
}

void sc_bk2_traj_advance(void *vc, double dur) { ((traj_ctx *)vc)->tau += dur; }

double sc_bk2_traj_dtau(void *vc) { return ((traj_ctx *)vc)->dtau; }

static int bk2_trajectory(void *vinst, double d, int iterations, double dtau,
                          int (*fn)(void *, double, const double *, int),
                          void *ctx, sc_msg *msg) {
  const bk2_inst *b = vinst;
  bk2_dpar P;
  sc_bk2_dparams(b, 0, &P);
  traj_ctx c = {b, &P, 0, dtau, fn, ctx};
  sc_map_value out;
  for (int k = 0; k < iterations; k++) {
    memset(&out, 0, sizeof out);
    bk2_state x;
    int st = sc_bk2_iterate(b, &P, sc_dconst(d, 0), 0, &x, &out, traj_phase,
                            &c, msg);
    if (st) return st;
    /* The global stick phase: both blocks move with V until the first
     * threshold; S_i grows at rate V.  With V = 0 it is passed at once
     * (quasi-static loading). */
    double s1 = spring(&P, x.y1, x.y2).v, s2 = spring(&P, x.y2, x.y1).v;
    double gap = fmax(0, fmin(1 - s1, b->beta - s2));
    double tstick = b->v > 0 ? gap / b->v : 0;
    x.u1 = x.u2 = sc_dconst(b->v, 0);
    long n = (long)floor(tstick / dtau);
    for (long i = 0; i <= n; i++) {
      bk2_state xs = x;
      xs.y1.v += b->v * i * dtau;
      xs.y2.v += b->v * i * dtau;
      if (emit(&c, c.tau + i * dtau, &xs, SC_BK2_STICK)) return SC_ECALLBACK;
    }
    c.tau += tstick;
    d = out.f;
  }
  return SC_OK;
}

const sc_model_type sc_model_bk2 = {
    .name = "bk2",
    .doc = "two-block Burridge-Knopoff stick-slip model (MODEL.md)",
    .state_name = "d",
    .state_label = "Y_2 - Y_1",
    .nparam = 4,
    .params = bk2_params,
    .noption = 3,
    .options = bk2_options,
    .inst_size = sizeof(bk2_inst),
    .setup = bk2_setup,
    .release = bk2_release,
    .eval = bk2_eval,
    .trajectory = bk2_trajectory,
};
