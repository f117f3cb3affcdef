/* Exact second (and d-d-x third) derivatives of bk2's event map.
 *
 * The ordinary evaluation (sc_bk2_eval_jet(), bk2_map.c) finds the phases
 * of the iterate: their modes and durations, and from the next mode the
 * event that ends each (bk2_rules.h).  This file replays those phases in
 * jet arithmetic (src/hybrid/jet.h) over the directions (d, alpha, beta,
 * phi, v): the closed-form flows of bk2_flow.h on jets, with the time a
 * jet too, and each event time tau as a jet found by Newton's method on
 * the guard, g(tau) = 0, started at the known root.  Each Newton step at
 * least doubles the order to which the jet of tau is exact (orders 1, 3,
 * 7), so SC_BK2_JET_NEWTON steps give the exact event-time sensitivities
 * up to third order: the higher-order analogue of the saltation terms,
 * with no formula of its own to derive (docs/curves.md).  The state at
 * the event is the flow evaluated at the jet time; a block that re-sticks
 * takes U = V_s. */
#include <math.h>
#include <string.h>

#include "hybrid/jet.h"
#include "models/bk2_jet.h"

/* Newton steps in jet arithmetic per event time: two make the jets exact
 * to third order; the third costs little and absorbs the rounding of the
 * root's value. */
#define SC_BK2_JET_NEWTON 3

#define ND SC_JET_NDIR /* d, alpha, beta, phi, v */
_Static_assert(SC_JET_NDIR == 1 + 4, "jets carry d and four parameters");

typedef struct {
  BK2_PAR_FIELDS(sc_jet);
} bk2_jpar;

typedef struct {
  BK2_STATE_FIELDS(sc_jet);
} bk2_jstate;

/* The closed-form physics on jets, times included: bk2j_load_params,
 * bk2j_onset_state, bk2j_flow_make, bk2j_flow_at, ... (bk2_flow.h). */
#define BK2_FN(name) bk2j_##name
#define BK2_NUM sc_jet
#define BK2_TIME sc_jet
#define BK2_ACC sc_jet
#define BK2_PAR bk2_jpar
#define BK2_STATE bk2_jstate
#define BK2_ND(P) ND
#define BK2_SET_ND(P, n) ((void)(P))
#define N_CONST(c) sc_jconst(c)
#define N_VAR(x, dir) sc_jvar(x, dir, ND)
#define N_VAL(a) ((a).v)
#define N_ADD(a, b) sc_jadd(a, b, ND)
#define N_SUB(a, b) sc_jsub(a, b, ND)
#define N_MUL(a, b) sc_jmul(a, b, ND)
#define N_SCALE(a, s) sc_jscale(a, s, ND)
#define N_ADDC(a, c) sc_jaddc(a, c)
#define N_INV(a) sc_jinv(a, ND)
#define N_SQRT(a) sc_jsqrt(a, ND)
#define N_TMUL(a, t) sc_jmul(a, t, ND)
#define N_TAXPY(a, t, b) sc_jadd(a, sc_jmul(b, t, ND), ND)
#define N_SINCOS(a, s, c) sc_jsincos(a, ND, s, c)
#define N_SINCOS_AT(a, sv, cv, s, c)                                           \
  (*(s) = sc_jcompose(&(a), sv, cv, -(sv), -(cv), ND),                         \
   *(c) = sc_jcompose(&(a), cv, -(sv), -(cv), sv, ND))
#define N_ACC(w, q) sc_jscale(sc_jmul(sc_jmul(w, w, ND), q, ND), -1, ND)
#define A_ZERO sc_jconst(0)
#define A_ADD(a, b) sc_jadd(a, b, ND)
#define A_SUB(a, b) sc_jsub(a, b, ND)
#define A_SCALE(a, s) sc_jscale(a, s, ND)
#include "models/bk2_flow.h"

/* The time derivative of the guard of event `kind` ending a phase of
 * `mode`, at state x with accelerations acc: U_i' of a re-stick, S_j'
 * of the stuck block's threshold. */
static sc_jet guard_rate(const bk2_jpar *P, int mode, int kind,
                         const bk2_jstate *x, const sc_jet acc[2]) {
  if (kind == BK2_EV_RESTICK1) return acc[0];
  if (kind == BK2_EV_RESTICK2) return acc[1];
  return mode == SC_BK2_SLIP1 ? bk2j_spring(P, x->u2, x->u1)
                              : bk2j_spring(P, x->u1, x->u2);
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
  bk2_jpar P;
  bk2j_load_params(b, ND, &P);
  /* The onset (the mode is the recorded one). */
  bk2_jstate x;
  bk2j_onset_state(&P, sc_jvar(d, 0, ND), L->mode[0], &x);
  for (int n = 0; n < L->n; n++) {
    int mode = L->mode[n];
    int next = n + 1 < L->n ? L->mode[n + 1] : SC_BK2_STICK;
    /* 0: both blocks re-stick at once (not twice differentiable) */
    int kind = bk2_event_between(mode, next);
    if (!kind) {
      fill_nan(out, grad);
      return;
    }
    bk2j_mode_flow f = bk2j_flow_make(&P, mode, &x);
    sc_jet tau = sc_jconst(L->dur[n]), acc[2];
    for (int it = 0; it < SC_BK2_JET_NEWTON; it++) {
      bk2j_flow_at(&P, &f, tau, NULL, &x, acc);
      sc_jet g = bk2j_guard_value(&P, mode, kind, &x),
             gt = guard_rate(&P, mode, kind, &x, acc);
      if (gt.v == 0 || !isfinite(gt.v)) {
        /* A guard with zero slope: the event time is not differentiable
         * (docs/model.md: at grazing, or at d* with V_s = 0). */
        fill_nan(out, grad);
        return;
      }
      tau = sc_jsub(tau, sc_jdiv(g, gt, ND), ND);
      tau.v = L->dur[n]; /* the root of the ordinary evaluation */
    }
    bk2j_flow_at(&P, &f, tau, NULL, &x, acc);
    bk2j_stick(&P, mode, kind, &x);
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
