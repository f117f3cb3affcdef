/* Private to the bk2 model: its closed-form physics written once, for any
 * number type (docs/model.md, derived in docs/derivations.md): the
 * parameters and the constants derived from them, the onset state of a
 * slip from a global stick phase, the springs, the forced oscillator of
 * each slip mode and the state it reaches at a time, the guard of each
 * event at a state, what an event does to the velocities (bk2_rules.h's
 * table), and the coefficients of the guards the certified search takes.
 *
 * This file is a body included once per number type, after defining:
 *   BK2_FN(name)  the instance's name for `name` (bk2_ on duals)
 *   BK2_NUM       the number type: double, sc_dual or sc_jet
 *   BK2_TIME      the type of a time in the flows: double, or sc_jet for
 *                 event times that carry derivatives (bk2_jet.c)
 *   BK2_ACC       the type of an acceleration: double (duals shift their
 *                 sensitivities with the value alone), or sc_jet
 *   BK2_PAR, BK2_STATE  the parameter and state types, made of BK2_NUMs
 *                 (fields: BK2_PAR_FIELDS, BK2_STATE_FIELDS, bk2_impl.h)
 *   BK2_ND(P)     the live derivative directions of P (an int)
 *   BK2_SET_ND(P, nd)   record them in P
 * and the arithmetic, each with `nd` (an int in scope) where it needs it:
 *   N_CONST(c) N_VAR(v, dir) N_VAL(a) N_ADD(a, b) N_SUB(a, b) N_MUL(a, b)
 *   N_SCALE(a, s) N_ADDC(a, c) N_INV(a) N_SQRT(a)
 *   N_TMUL(a, t)      a t, t a BK2_TIME
 *   N_TAXPY(a, t, b)  a + t b
 *   N_SINCOS(a, s, c), N_SINCOS_AT(a, sv, cv, s, c)  sin and cos of a
 *                 into *s and *c (the second with their values given)
 *   N_ACC(w, q)       -w^2 q as a BK2_ACC
 *   A_ZERO A_ADD(a, b) A_SUB(a, b) A_SCALE(a, s)  on BK2_ACCs
 * Every instance computes its values by the same operations in the same
 * order, so the plain doubles of the value-only path are bit for bit the
 * values of the duals (tests/test_bk2_value.c), and the jets' those of
 * both.  The body undefines all of these at its end. */

#ifndef SC_MODELS_BK2_FLOW_ONCE
#define SC_MODELS_BK2_FLOW_ONCE

#include <math.h>

#include "hybrid/hybrid_impl.h"
#include "models/bk2_rules.h"
#include "slipcont/hybrid.h"

/* g and g' at t = 0, as sc_guard_eval(g, 0, ...) computes them, with the
 * same operations in the same order (so bit for bit the same), but with
 * sin(w 0) = w 0 (a signed zero) and cos(w 0) = 1 written out in place of
 * two libm calls a term: every phase takes them once or twice.  A
 * frequency that is not finite goes to sc_guard_eval (its NaNs). */
static inline void bk2_guard_at_zero(const sc_guard *g, double *g0,
                                     double *g1) {
  double v = g->c0 + g->c1 * 0.0, d1 = g->c1;
  for (int k = 0; k < g->n; k++) {
    double w = g->w[k], s = w * 0.0, c = 1.0;
    if (!isfinite(w)) {
      sc_guard_eval(g, 0, g0, g1, NULL);
      return;
    }
    v += g->a[k] * c + g->b[k] * s;
    d1 += w * (g->b[k] * c - g->a[k] * s);
  }
  *g0 = v, *g1 = d1;
}

/* The stuck block's threshold guard at the onset of a slip from a GSP:
 * its value at 0 as the onset formula gives it, (1 + 2 alpha)(d - d*) up
 * to sign, not as rounding builds it from the state (next to d* the sign
 * can flip, and the other block's trigger be missed). */
static inline void bk2_set_onset_gap(sc_guard *g, double gap) {
  double g0, g1;
  bk2_guard_at_zero(g, &g0, &g1);
  g->c0 += gap - g0;
}

#endif

/* ---- parameters, onset, springs, events --------------------------------- */

/* The parameters of b as numbers with nd directions: d (0, set by the
 * caller), alpha, beta, phi, v (1..4). */
static inline void BK2_FN(load_params)(const bk2_inst *b, int nd, BK2_PAR *P) {
  (void)nd;
  BK2_SET_ND(P, nd);
  P->alpha = N_VAR(b->alpha, 1);
  P->beta = N_VAR(b->beta, 2);
  BK2_NUM phi = N_VAR(b->phi, 3);
  P->mu = N_INV(phi);
  P->k1 = P->mu;
  P->k2 = N_MUL(P->beta, P->mu);
  P->t2 = P->beta;
  P->v = N_VAR(b->v, 4);
  P->vs = b->frozen ? N_CONST(0) : P->v;
  P->w1 = N_SQRT(N_ADDC(P->alpha, 1));
  P->w2 = N_SQRT(N_ADDC(N_SCALE(P->alpha, 2), 1));
  P->rw1 = N_INV(P->w1);
  P->rw1sq = N_INV(N_MUL(P->w1, P->w1));
  P->rw2 = N_INV(P->w2);
  P->rw2sq = N_INV(N_MUL(P->w2, P->w2));
  P->s1 = N_MUL(N_MUL(P->alpha, P->vs), P->rw1sq);
}

/* The onset state of a slip of `mode` from the GSP of displacement d
 * (bk2_onset_block()): the block at its threshold, the other d away, both
 * moving with V_s. */
static inline void BK2_FN(onset_state)(const BK2_PAR *P, BK2_NUM d, int mode,
                                       BK2_STATE *x) {
  int nd = BK2_ND(P);
  (void)nd;
  if (bk2_onset_block(mode) == 1) {
    x->y1 = N_ADDC(N_MUL(P->alpha, d), 1);
    x->y2 = N_ADD(x->y1, d);
  } else {
    x->y2 = N_SUB(P->beta, N_MUL(P->alpha, d));
    x->y1 = N_SUB(x->y2, d);
  }
  x->u1 = x->u2 = P->vs;
}

/* Spring force S_a = (1 + alpha) Y_a - alpha Y_b on block a. */
static inline BK2_NUM BK2_FN(spring)(const BK2_PAR *P, BK2_NUM ya,
                                     BK2_NUM yb) {
  int nd = BK2_ND(P);
  (void)nd;
  return N_ADD(ya, N_MUL(P->alpha, N_SUB(ya, yb)));
}

/* The guard of event `kind` that ends a phase of `mode`, at state x (at
 * fixed time): U_i - V_s of a re-stick, S_j - T_j of the stuck block's
 * threshold. */
static inline BK2_NUM BK2_FN(guard_value)(const BK2_PAR *P, int mode,
                                          int kind, const BK2_STATE *x) {
  int nd = BK2_ND(P);
  (void)nd;
  kind = BK2_GUARD_OF(kind);
  if (kind == BK2_EV_RESTICK1) return N_SUB(x->u1, P->vs);
  if (kind == BK2_EV_RESTICK2) return N_SUB(x->u2, P->vs);
  if (mode == SC_BK2_SLIP1)
    return N_SUB(BK2_FN(spring)(P, x->y2, x->y1), P->t2);
  return N_ADDC(BK2_FN(spring)(P, x->y1, x->y2), -1);
}

/* The event `kind` ends a phase of `mode` at state x: the blocks that
 * stick take U = V_s; returns the next mode (bk2_rules.h's table). */
static inline int BK2_FN(stick)(const BK2_PAR *P, int mode, int kind,
                                BK2_STATE *x) {
  int next = bk2_next_mode(mode, kind), stuck = bk2_stuck_blocks(mode, next);
  if (stuck & 1) x->u1 = P->vs;
  if (stuck & 2) x->u2 = P->vs;
  return next;
}

/* ---- the forced oscillator q'' + w^2 q = F0 + F1 t ---------------------- */

/* Coefficients of q(t) = s0 + s1 t + A cos(w t) + B sin(w t). */
typedef struct {
  BK2_NUM s0, s1, A, B, w;
} BK2_FN(osc);

/* The oscillator from q(0) = q0, q'(0) = p0, with the force's constant
 * F0, the drift s1 = F1 / w^2 (a parameter), and rw = 1 / w, rw2 =
 * 1 / w^2: s0 = F0 / w^2, B = (p0 - s1) / w by products. */
static inline BK2_FN(osc)
    BK2_FN(osc_make)(BK2_NUM q0, BK2_NUM p0, BK2_NUM F0, BK2_NUM s1,
                     BK2_NUM w, BK2_NUM rw, BK2_NUM rw2, int nd) {
  (void)nd;
  BK2_FN(osc) o;
  o.s0 = N_MUL(F0, rw2);
  o.s1 = s1;
  o.A = N_SUB(q0, o.s0);
  o.B = N_MUL(N_SUB(p0, o.s1), rw);
  o.w = w;
  return o;
}

/* q(t), q'(t) and q''(t); cs: NULL, or cos and sin of w t (cs[0],
 * cs[1]) as the root search left them at an event. */
static inline void BK2_FN(osc_at)(const BK2_FN(osc) *o, BK2_TIME t,
                                  const double *cs, int nd, BK2_NUM *q,
                                  BK2_NUM *p, BK2_ACC *acc) {
  (void)nd;
  BK2_NUM wt = N_TMUL(o->w, t), s, c;
  if (cs) N_SINCOS_AT(wt, cs[1], cs[0], &s, &c);
  else N_SINCOS(wt, &s, &c);
  BK2_NUM Ac = N_MUL(o->A, c), Bs = N_MUL(o->B, s), osc = N_ADD(Ac, Bs);
  *q = N_ADD(N_TAXPY(o->s0, t, o->s1), osc);
  *p = N_ADD(o->s1, N_MUL(o->w, N_SUB(N_MUL(o->B, c), N_MUL(o->A, s))));
  *acc = N_ACC(o->w, osc);
}

/* ---- one slip mode ------------------------------------------------------- */

/* The flow of one slip mode from x0, in closed form: o1 the slipping
 * block (SLIP1, SLIP2), or the modes Sum = Y1 + Y2 and Dif = Y1 - Y2
 * (o1, o2: SLIP12). */
typedef struct {
  int mode;
  BK2_FN(osc) o1, o2;
  BK2_STATE x0;
} BK2_FN(mode_flow);

static inline BK2_FN(mode_flow)
    BK2_FN(flow_make)(const BK2_PAR *P, int mode, const BK2_STATE *x0) {
  int nd = BK2_ND(P);
  BK2_FN(mode_flow) f;
  f.mode = mode;
  f.x0 = *x0;
  if (mode == SC_BK2_SLIP1) {
    /* Y1'' = mu - (1+alpha) Y1 + alpha (Y20 + Vs t) */
    f.o1 = BK2_FN(osc_make)(x0->y1, x0->u1,
                            N_ADD(P->k1, N_MUL(P->alpha, x0->y2)), P->s1,
                            P->w1, P->rw1, P->rw1sq, nd);
  } else if (mode == SC_BK2_SLIP2) {
    f.o1 = BK2_FN(osc_make)(x0->y2, x0->u2,
                            N_ADD(P->k2, N_MUL(P->alpha, x0->y1)), P->s1,
                            P->w1, P->rw1, P->rw1sq, nd);
  } else {
    /* Sum'' + Sum = mu (1 + beta), Dif'' + w2^2 Dif = mu (1 - beta) */
    BK2_NUM zero = N_CONST(0), one = N_CONST(1);
    f.o1 = BK2_FN(osc_make)(N_ADD(x0->y1, x0->y2), N_ADD(x0->u1, x0->u2),
                            N_ADD(P->k1, P->k2), zero, one, one, one, nd);
    f.o2 = BK2_FN(osc_make)(N_SUB(x0->y1, x0->y2), N_SUB(x0->u1, x0->u2),
                            N_SUB(P->k1, P->k2), zero, P->w2, P->rw2,
                            P->rw2sq, nd);
  }
  return f;
}

/* The state at time t of the mode and the accelerations; cs: NULL, or
 * the cos and sin of each oscillator's w t at t ({cos, sin} of o1, then
 * of o2) as the root search left them. */
static inline void BK2_FN(flow_at)(const BK2_PAR *P,
                                   const BK2_FN(mode_flow) *f, BK2_TIME t,
                                   const double *cs, BK2_STATE *x,
                                   BK2_ACC acc[2]) {
  int nd = BK2_ND(P);
  BK2_NUM q, p;
  BK2_ACC a;
  BK2_FN(osc_at)(&f->o1, t, cs, nd, &q, &p, &a);
  if (f->mode == SC_BK2_SLIP1) {
    x->y1 = q, x->u1 = p;
    x->y2 = N_TAXPY(f->x0.y2, t, P->vs);
    x->u2 = P->vs;
    acc[0] = a, acc[1] = A_ZERO;
  } else if (f->mode == SC_BK2_SLIP2) {
    x->y2 = q, x->u2 = p;
    x->y1 = N_TAXPY(f->x0.y1, t, P->vs);
    x->u1 = P->vs;
    acc[0] = A_ZERO, acc[1] = a;
  } else {
    BK2_NUM q2, p2;
    BK2_ACC a2;
    BK2_FN(osc_at)(&f->o2, t, cs ? cs + 2 : NULL, nd, &q2, &p2, &a2);
    x->y1 = N_SCALE(N_ADD(q, q2), 0.5);
    x->y2 = N_SCALE(N_SUB(q, q2), 0.5);
    x->u1 = N_SCALE(N_ADD(p, p2), 0.5);
    x->u2 = N_SCALE(N_SUB(p, p2), 0.5);
    acc[0] = A_SCALE(A_ADD(a, a2), 0.5), acc[1] = A_SCALE(A_SUB(a, a2), 0.5);
  }
}

/* ---- the guards of a phase, for the certified search --------------------- */

/* Guard pieces: q(t) and q'(t) as c0 + c1 t + a cos + b sin, scaled. */
static inline void BK2_FN(guard_add_q)(sc_guard *g, const BK2_FN(osc) *o,
                                       double scale) {
  g->c0 += scale * N_VAL(o->s0);
  g->c1 += scale * N_VAL(o->s1);
  g->w[g->n] = N_VAL(o->w);
  g->a[g->n] = scale * N_VAL(o->A);
  g->b[g->n] = scale * N_VAL(o->B);
  g->n++;
}

static inline void BK2_FN(guard_add_qdot)(sc_guard *g, const BK2_FN(osc) *o,
                                          double scale) {
  double w = N_VAL(o->w);
  g->c0 += scale * N_VAL(o->s1);
  g->w[g->n] = w;
  g->a[g->n] = scale * w * N_VAL(o->B);
  g->b[g->n] = -scale * w * N_VAL(o->A);
  g->n++;
}

/* The guards are built in place, and only their first n terms are set
 * (all that is ever read of them): zeroing and copying the whole struct
 * cost more than building it. */

/* The re-stick guard U_i - Vs of slipping block i (1 or 2). */
static inline void BK2_FN(guard_restick)(const BK2_PAR *P,
                                         const BK2_FN(mode_flow) *f, int i,
                                         sc_guard *g) {
  g->c0 = -N_VAL(P->vs);
  g->c1 = 0;
  g->n = 0;
  if (f->mode != SC_BK2_SLIP12) {
    BK2_FN(guard_add_qdot)(g, &f->o1, 1);
  } else {
    BK2_FN(guard_add_qdot)(g, &f->o1, 0.5);
    BK2_FN(guard_add_qdot)(g, &f->o2, i == 1 ? 0.5 : -0.5);
  }
}

/* The threshold guard S_j - T_j of the stuck block j while the other
 * slips alone: S_j = (1+alpha)(Yj0 + Vs t) - alpha q(t). */
static inline void BK2_FN(guard_threshold)(const BK2_PAR *P,
                                           const BK2_FN(mode_flow) *f,
                                           sc_guard *g) {
  double a = N_VAL(P->alpha);
  int j = f->mode == SC_BK2_SLIP1 ? 2 : 1;
  double yj0 = j == 2 ? N_VAL(f->x0.y2) : N_VAL(f->x0.y1);
  double tj = j == 2 ? N_VAL(P->t2) : 1;
  g->c0 = (1 + a) * yj0 - tj;
  g->c1 = (1 + a) * N_VAL(P->vs);
  g->n = 0;
  BK2_FN(guard_add_q)(g, &f->o1, -a);
}

/* The guards of the events that can end a phase of the flow f, in the
 * order bk2_phase_kinds() gives (their kinds into kind), the stuck
 * block's threshold set to onset_gap at 0 (bk2_set_onset_gap(); NaN: not
 * the onset of a slip from a GSP).  Returns their number. */
static inline int BK2_FN(phase_guards)(const BK2_PAR *P,
                                       const BK2_FN(mode_flow) *f, int fresh,
                                       double onset_gap, sc_guard g[2],
                                       int kind[2]) {
  int ng = bk2_phase_kinds(f->mode, fresh, kind);
  for (int i = 0; i < ng; i++) {
    if (kind[i] != BK2_EV_THRESHOLD) {
      BK2_FN(guard_restick)(P, f, kind[i], &g[i]);
    } else {
      BK2_FN(guard_threshold)(P, f, &g[i]);
      if (!isnan(onset_gap)) bk2_set_onset_gap(&g[i], onset_gap);
    }
  }
  return ng;
}

#undef BK2_FN
#undef BK2_NUM
#undef BK2_TIME
#undef BK2_ACC
#undef BK2_PAR
#undef BK2_STATE
#undef BK2_ND
#undef BK2_SET_ND
#undef N_CONST
#undef N_VAR
#undef N_VAL
#undef N_ADD
#undef N_SUB
#undef N_MUL
#undef N_SCALE
#undef N_ADDC
#undef N_INV
#undef N_SQRT
#undef N_TMUL
#undef N_TAXPY
#undef N_SINCOS
#undef N_SINCOS_AT
#undef N_ACC
#undef A_ZERO
#undef A_ADD
#undef A_SUB
#undef A_SCALE
