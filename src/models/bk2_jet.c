/* Exact second (and d-d-x third) derivatives of bk2's event map.
 *
 * The ordinary evaluation (sc_bk2_eval_jet(), bk2_map.c) finds the phases
 * of the iterate: their modes and durations, and from the next mode the
 * event that ends each (bk2_rules.h).  This file replays those phases in jet arithmetic (src/hybrid/jet.h)
 * over the directions (d, alpha, beta, phi, v): the closed-form flows of
 * docs/model.md with jet coefficients, and each event time tau as a jet found
 * by Newton's method on the guard, g(tau) = 0, started at the known root.
 * Each Newton step at least doubles the order to which the jet of tau is
 * exact (orders 1, 3, 7), so SC_BK2_JET_NEWTON steps give the exact
 * event-time sensitivities up to third order: the higher-order analogue
 * of the saltation terms, with no formula of its own to derive
 * (docs/curves.md).  The state at the event is the flow evaluated at the
 * jet time; a block that re-sticks takes U = V_s. */
#include <math.h>
#include <string.h>

#include "hybrid/jet.h"
#include "models/bk2_jet.h"

/* Newton steps in jet arithmetic per event time: two make the jets exact
 * to third order; the third costs little and absorbs the rounding of the
 * root's value. */
#define SC_BK2_JET_NEWTON 3

#define ND 5 /* d, alpha, beta, phi, v */

typedef struct {
  sc_jet alpha, beta, mu, k1, k2, t2, vs, w1, w2;
} jpar;

typedef struct {
  sc_jet y1, y2, u1, u2;
} jstate;

/* q(t) = s0 + s1 t + A cos(w t) + B sin(w t), the solution of
 * q'' + w^2 q = F0 + F1 t with q(0) = q0, q'(0) = p0. */
typedef struct {
  sc_jet s0, s1, A, B, w;
} josc;

typedef struct {
  int mode;
  josc o1, o2; /* SLIP1/2: the slipping block; SLIP12: sum and difference */
  jstate x0;
} jflow;

static void jparams(const bk2_inst *b, jpar *P) {
  P->alpha = sc_jvar(b->alpha, 1, ND);
  P->beta = sc_jvar(b->beta, 2, ND);
  P->mu = sc_jinv(sc_jvar(b->phi, 3, ND), ND);
  P->k1 = P->mu;
  P->k2 = sc_jmul(P->beta, P->mu, ND);
  P->t2 = P->beta;
  P->vs = b->frozen ? sc_jconst(0) : sc_jvar(b->v, 4, ND);
  P->w1 = sc_jsqrt(sc_jaddc(P->alpha, 1), ND);
  P->w2 = sc_jsqrt(sc_jaddc(sc_jscale(P->alpha, 2, ND), 1), ND);
}

static josc osc_make(sc_jet q0, sc_jet p0, sc_jet F0, sc_jet F1, sc_jet w) {
  josc o;
  sc_jet iw2 = sc_jinv(sc_jmul(w, w, ND), ND);
  o.s0 = sc_jmul(F0, iw2, ND);
  o.s1 = sc_jmul(F1, iw2, ND);
  o.A = sc_jsub(q0, o.s0, ND);
  o.B = sc_jdiv(sc_jsub(p0, o.s1, ND), w, ND);
  o.w = w;
  return o;
}

/* q, q' and q'' at the jet time t. */
static void osc_at(const josc *o, const sc_jet *t, sc_jet *q, sc_jet *p,
                   sc_jet *a) {
  sc_jet s, c;
  sc_jsincos(sc_jmul(o->w, *t, ND), ND, &s, &c);
  sc_jet Ac = sc_jmul(o->A, c, ND), Bs = sc_jmul(o->B, s, ND);
  sc_jet osc = sc_jadd(Ac, Bs, ND);
  *q = sc_jadd(sc_jadd(o->s0, sc_jmul(o->s1, *t, ND), ND), osc, ND);
  sc_jet rot = sc_jsub(sc_jmul(o->B, c, ND), sc_jmul(o->A, s, ND), ND);
  *p = sc_jadd(o->s1, sc_jmul(o->w, rot, ND), ND);
  *a = sc_jscale(sc_jmul(sc_jmul(o->w, o->w, ND), osc, ND), -1, ND);
}

static jflow flow_make(const jpar *P, int mode, const jstate *x0) {
  jflow f;
  f.mode = mode;
  f.x0 = *x0;
  sc_jet zero = sc_jconst(0);
  sc_jet F1 = sc_jmul(P->alpha, P->vs, ND);
  if (mode == SC_BK2_SLIP1) {
    f.o1 =
        osc_make(x0->y1, x0->u1,
                 sc_jadd(P->k1, sc_jmul(P->alpha, x0->y2, ND), ND), F1, P->w1);
  } else if (mode == SC_BK2_SLIP2) {
    f.o1 =
        osc_make(x0->y2, x0->u2,
                 sc_jadd(P->k2, sc_jmul(P->alpha, x0->y1, ND), ND), F1, P->w1);
  } else {
    f.o1 = osc_make(sc_jadd(x0->y1, x0->y2, ND), sc_jadd(x0->u1, x0->u2, ND),
                    sc_jadd(P->k1, P->k2, ND), zero, sc_jconst(1));
    f.o2 = osc_make(sc_jsub(x0->y1, x0->y2, ND), sc_jsub(x0->u1, x0->u2, ND),
                    sc_jsub(P->k1, P->k2, ND), zero, P->w2);
  }
  return f;
}

/* The state and the accelerations at the jet time t. */
static void flow_at(const jpar *P, const jflow *f, const sc_jet *t, jstate *x,
                    sc_jet acc[2]) {
  sc_jet q, p, a;
  osc_at(&f->o1, t, &q, &p, &a);
  if (f->mode == SC_BK2_SLIP1 || f->mode == SC_BK2_SLIP2) {
    sc_jet ys = sc_jadd(f->mode == SC_BK2_SLIP1 ? f->x0.y2 : f->x0.y1,
                        sc_jmul(P->vs, *t, ND), ND);
    if (f->mode == SC_BK2_SLIP1) {
      x->y1 = q, x->u1 = p, x->y2 = ys, x->u2 = P->vs;
      acc[0] = a, acc[1] = sc_jconst(0);
    } else {
      x->y2 = q, x->u2 = p, x->y1 = ys, x->u1 = P->vs;
      acc[1] = a, acc[0] = sc_jconst(0);
    }
    return;
  }
  sc_jet q2, p2, a2;
  osc_at(&f->o2, t, &q2, &p2, &a2);
  x->y1 = sc_jscale(sc_jadd(q, q2, ND), 0.5, ND);
  x->y2 = sc_jscale(sc_jsub(q, q2, ND), 0.5, ND);
  x->u1 = sc_jscale(sc_jadd(p, p2, ND), 0.5, ND);
  x->u2 = sc_jscale(sc_jsub(p, p2, ND), 0.5, ND);
  acc[0] = sc_jscale(sc_jadd(a, a2, ND), 0.5, ND);
  acc[1] = sc_jscale(sc_jsub(a, a2, ND), 0.5, ND);
}

/* S_a = (1 + alpha) Y_a - alpha Y_b */
static sc_jet spring(const jpar *P, const sc_jet *ya, const sc_jet *yb) {
  return sc_jadd(*ya, sc_jmul(P->alpha, sc_jsub(*ya, *yb, ND), ND), ND);
}

/* The guard of event `kind` (1, 2: re-stick of block i; 3: threshold of
 * the stuck block) and its time derivative, at state x with
 * accelerations acc. */
static void guard_at(const jpar *P, int mode, int kind, const jstate *x,
                     const sc_jet acc[2], sc_jet *g, sc_jet *gt) {
  if (kind == 1) {
    *g = sc_jsub(x->u1, P->vs, ND);
    *gt = acc[0];
  } else if (kind == 2) {
    *g = sc_jsub(x->u2, P->vs, ND);
    *gt = acc[1];
  } else if (mode == SC_BK2_SLIP1) {
    *g = sc_jsub(spring(P, &x->y2, &x->y1), P->t2, ND);
    *gt = spring(P, &x->u2, &x->u1);
  } else {
    *g = sc_jaddc(spring(P, &x->y1, &x->y2), -1);
    *gt = spring(P, &x->u1, &x->u2);
  }
}

static void fill_nan(sc_map_value *out, double *grad) {
  out->d2fdd2 = out->d3fdd3 = NAN;
  for (int k = 0; k < SC_MAXPARAM; k++)
    out->d2fddp[k] = out->d3fdd2p[k] = NAN;
  if (grad)
    for (int k = 0; k < ND; k++)
      grad[k] = NAN;
}

void sc_bk2_jet_replay(const bk2_inst *b, double d, const bk2_phase_log *L,
                       sc_map_value *out, double *grad) {
  jpar P;
  jparams(b, &P);
  /* The onset, as sc_bk2_onset() (the mode is the recorded one). */
  sc_jet dj = sc_jvar(d, 0, ND);
  jstate x;
  if (bk2_onset_block(L->mode[0]) == 1) {
    x.y1 = sc_jaddc(sc_jmul(P.alpha, dj, ND), 1);
    x.y2 = sc_jadd(x.y1, dj, ND);
  } else {
    x.y2 = sc_jsub(P.beta, sc_jmul(P.alpha, dj, ND), ND);
    x.y1 = sc_jsub(x.y2, dj, ND);
  }
  x.u1 = x.u2 = P.vs;
  for (int n = 0; n < L->n; n++) {
    int mode = L->mode[n];
    int next = n + 1 < L->n ? L->mode[n + 1] : SC_BK2_STICK;
    /* 0: both blocks re-stick at once (not twice differentiable) */
    int kind = bk2_event_between(mode, next);
    if (!kind) {
      fill_nan(out, grad);
      return;
    }
    jflow f = flow_make(&P, mode, &x);
    sc_jet tau = sc_jconst(L->dur[n]), g, gt, acc[2];
    for (int it = 0; it < SC_BK2_JET_NEWTON; it++) {
      flow_at(&P, &f, &tau, &x, acc);
      guard_at(&P, mode, kind, &x, acc, &g, &gt);
      if (gt.v == 0 || !isfinite(gt.v)) {
        /* A guard with zero slope: the event time is not differentiable
         * (docs/model.md: at grazing, or at d* with V_s = 0). */
        fill_nan(out, grad);
        return;
      }
      tau = sc_jsub(tau, sc_jdiv(g, gt, ND), ND);
      tau.v = L->dur[n]; /* the root of the ordinary evaluation */
    }
    flow_at(&P, &f, &tau, &x, acc);
    int stuck = bk2_stuck_blocks(mode, next);
    if (stuck & 1) x.u1 = P.vs;
    if (stuck & 2) x.u2 = P.vs;
  }
  sc_jet fj = sc_jsub(x.y2, x.y1, ND);
  if (out->neutral) {
    /* f = d + c(p) exactly (docs/model.md): no curvature in d. */
    out->d2fdd2 = out->d3fdd3 = 0;
    for (int k = 0; k < 4; k++)
      out->d2fddp[k] = out->d3fdd2p[k] = 0;
  } else {
    out->d2fdd2 = fj.h[0][0];
    out->d3fdd3 = fj.t[0];
    for (int k = 0; k < 4; k++) {
      out->d2fddp[k] = fj.h[0][k + 1];
      out->d3fdd2p[k] = fj.t[k + 1];
    }
  }
  if (grad)
    for (int k = 0; k < ND; k++)
      grad[k] = fj.g[k];
}
