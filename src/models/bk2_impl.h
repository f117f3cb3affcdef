/* Private to the bk2 model: its instance, parameters as duals, state,
 * the flows interface and the pieces shared by its two implementations.
 *
 * Layout of the model:
 *   bk2_map.c        the model interface (parameters, setup, evaluation),
 *                    the event loop on duals from one GSP to the next,
 *                    second derivatives (with bk2_jet.c), the borders
 *                    of a whole iterate and trajectories: flows-agnostic;
 *   bk2_event.c      what an event does to the state and its
 *                    sensitivities, and how borders are recorded, for
 *                    every flow;
 *   bk2.c            the closed-form flows (`flows = exact`), certified
 *                    event search, and their value-only fast path;
 *   bk2_numerical.c  the integrated flows (`flows = numerical`, GSL
 *                    odeiv2; velocity-weakening friction);
 *   bk2_jet.c        second derivatives: a replay in jets of the phases
 *                    the event loop found (called by bk2_map.c only);
 *   bk2_quad.c       quad precision, its own arithmetic;
 *   bk2_rules.h      the rules in no number type, which all of them read:
 *                    modes, the event table, the onset, names;
 *   bk2_flow.h       the closed-form physics written once for any number
 *                    type (instances here on duals and doubles, and in
 *                    bk2_jet.c on jets);
 *   bk2_loop.h       the event loop written once (instances in
 *                    bk2_map.c on duals and in bk2.c on doubles).
 * The event loop reaches a flow only through bk2_flows; the two flows
 * never call each other. */
#ifndef SC_MODELS_BK2_IMPL_H
#define SC_MODELS_BK2_IMPL_H

#include <string.h>

#include "hybrid/dual.h"
#include "hybrid/hybrid_impl.h"
#include "models/bk2_rules.h"
#include "slipcont/bk2.h"
#include "slipcont/hybrid.h"
#include "slipcont/models.h"

typedef struct bk2_num bk2_num; /* numerical-flow workspace (GSL) */
typedef struct bk2_flows bk2_flows;

/* Parameters: alpha, beta, phi, v, gamma (velocity weakening only). */
#define BK2_NPARAM 5

/* The fields of the parameter and state types, for any number type T
 * (bk2_flow.h): the parameters, the kinetic forces K_i and the threshold
 * T_2 (T_1 = 1), the driver's and a stuck block's velocities V and V_s,
 * the frequencies w1 = sqrt(1 + alpha), w2 = sqrt(1 + 2 alpha), their
 * inverses and inverse squares, and the drift s1 = alpha V_s / w1^2 of a
 * single block's slip (the flows multiply by these: a division on every
 * phase's chain from its start state to its guards, otherwise). */
#define BK2_PAR_FIELDS(T)                                                      \
  T alpha, beta, mu, k1, k2, t2, v, vs, w1, w2;                                \
  T rw1, rw1sq, rw2, rw2sq, s1
/* Positions and velocities of the two blocks. */
#define BK2_STATE_FIELDS(T) T y1, y2, u1, u2

/* Parameters as duals: direction 0 is d, 1..4 are alpha, beta, phi, v. */
typedef struct {
  int nd;
  BK2_PAR_FIELDS(sc_dual);
} bk2_dpar;

/* The state on duals. */
typedef struct {
  BK2_STATE_FIELDS(sc_dual);
} bk2_state;

/* Parameters and state on plain doubles (the value-only path). */
typedef struct {
  BK2_PAR_FIELDS(double);
} bk2_vpar;

typedef struct {
  BK2_STATE_FIELDS(double);
} bk2_vstate;

typedef struct {
  double alpha, beta, phi, v, gamma;
  int frozen;    /* driver = frozen: Vs = 0 during slips */
  int vw;        /* friction = velocity-weakening */
  int numerical; /* flows = numerical (always with velocity weakening) */
  const bk2_flows *flows; /* exact or numerical, chosen by bk2_setup */
  sc_accuracy acc;
  double mu, w1, w2, vs, dstar; /* derived */
  /* The parameters are beyond what double resolves (bk2_setup): every
   * double evaluation is refused with the reason. */
  int unresolved;
  bk2_num *num;                 /* owned; NULL for exact flows */
  bk2_dpar p0;                  /* the parameters without derivatives */
  bk2_vpar pv;                  /* the same on plain doubles */
  /* The first-root search of the exact flows: sc_guard_first_root, set
   * by bk2_setup; tests put a frozen earlier search here to check that a
   * faster one changes nothing but speed (tests/test_map_equiv.c). */
  int (*search)(const sc_guard *g, double tmax, int skip_start, double atol,
                double rtol, sc_root *out);
  /* The two re-stick guards of a slip of both blocks, searched together:
   * sc_guard_first_root_pair, set by bk2_setup; NULL: one after the other
   * with `search` (the frozen earlier search of tests/test_map_equiv.c). */
  int (*search_pair)(const sc_guard *g, double tmax, const int *skip,
                     double atol, double rtol, sc_guard_limit_fn limit,
                     void *ctx, sc_root *out);
  /* Plain evaluations go through the dual path (nd = 0) instead of the
   * value-only path: set by tests that compare the two (they must give
   * bit-identical results); 0 after bk2_setup. */
  int dual_only;
  /* The re-stick guard of block i in a slip that starts from a GSP does
   * not depend on d (its amplitude is (1 - mu) T_i / (1 + alpha)): its
   * guard and first root, found once by sc_bk2_first_restick() (exact
   * flows), the root's window (first_event()), the size of the numbers the
   * guard was built from (same_guard()), and whether they are there. */
  sc_guard first_g[2];
  sc_root first_r[2];
  double first_w[2];
  double first_bsize[2];
  int first_ok[2];
} bk2_inst;

/* Directions of the forward-mode derivatives: d and the parameters that
 * act (gamma only with velocity weakening). */
static inline int bk2_nd(const bk2_inst *b) {
  return b->vw ? 1 + BK2_NPARAM : BK2_NPARAM;
}


/* sin and cos of the dual a whose values are given (sv, cv): those the
 * root search left at an event, in place of libm's (sc_dsincos), with
 * the same derivative parts. */
static inline void bk2_dsincos_at(sc_dual a, double sv, double cv, int nd,
                                  sc_dual *s, sc_dual *c) {
  *s = a;
  *c = a;
  s->v = sv;
  c->v = cv;
  for (int k = 0; k < nd; k++) {
    s->d[k] = cv * a.d[k];
    c->d[k] = -sv * a.d[k];
  }
}

/* The closed-form physics on duals: bk2_load_params, bk2_onset_state,
 * bk2_spring, bk2_guard_value, bk2_stick, bk2_flow_make, bk2_flow_at,
 * bk2_phase_guards, ... (bk2_flow.h). */
#define BK2_FN(name) bk2_##name
#define BK2_NUM sc_dual
#define BK2_TIME double
#define BK2_ACC double
#define BK2_PAR bk2_dpar
#define BK2_STATE bk2_state
#define BK2_ND(P) ((P)->nd)
#define BK2_SET_ND(P, n) ((P)->nd = (n))
#define N_CONST(c) sc_dconst(c, nd)
#define N_VAR(x, dir) sc_dvar(x, dir, nd)
#define N_VAL(a) ((a).v)
#define N_ADD(a, b) sc_dadd(a, b, nd)
#define N_SUB(a, b) sc_dsub(a, b, nd)
#define N_MUL(a, b) sc_dmul(a, b, nd)
#define N_SCALE(a, s) sc_dscale(a, s, nd)
#define N_ADDC(a, c) sc_daddc(a, c)
#define N_INV(a) sc_ddiv(sc_dconst(1, nd), a, nd)
#define N_SQRT(a) sc_dsqrt(a, nd)
#define N_TMUL(a, t) sc_dscale(a, t, nd)
#define N_TAXPY(a, t, b) sc_daxpy(a, t, b, nd)
#define N_SINCOS(a, s, c) sc_dsincos(a, nd, s, c)
#define N_SINCOS_AT(a, sv, cv, s, c) bk2_dsincos_at(a, sv, cv, nd, s, c)
#define N_ACC(w, q) (-(w).v * (w).v * (q).v)
#define A_ZERO 0
#define A_ADD(a, b) ((a) + (b))
#define A_SUB(a, b) ((a) - (b))
#define A_SCALE(a, s) ((s) * (a))
#include "models/bk2_flow.h"

/* The same on plain doubles: bk2v_load_params, bk2v_flow_make, ... */
#define BK2_FN(name) bk2v_##name
#define BK2_NUM double
#define BK2_TIME double
#define BK2_ACC double
#define BK2_PAR bk2_vpar
#define BK2_STATE bk2_vstate
#define BK2_ND(P) 0
#define BK2_SET_ND(P, n) ((void)(P))
#define N_CONST(c) ((double)(c))
#define N_VAR(x, dir) (x)
#define N_VAL(a) (a)
#define N_ADD(a, b) ((a) + (b))
#define N_SUB(a, b) ((a) - (b))
#define N_MUL(a, b) ((a) * (b))
#define N_SCALE(a, s) ((a) * (s))
#define N_ADDC(a, c) ((a) + (c))
#define N_INV(a) (1 / (a))
#define N_SQRT(a) sqrt(a)
#define N_TMUL(a, t) ((a) * (t))
#define N_TAXPY(a, t, b) ((a) + (t) * (b))
#define N_SINCOS(a, s, c) (*(s) = sin(a), *(c) = cos(a))
#define N_SINCOS_AT(a, sv, cv, s, c) (*(s) = (sv), *(c) = (cv))
#define N_ACC(w, q) (-(w) * (w) * (q))
#define A_ZERO 0
#define A_ADD(a, b) ((a) + (b))
#define A_SUB(a, b) ((a) - (b))
#define A_SCALE(a, s) ((s) * (a))
#include "models/bk2_flow.h"

/* What one slip phase is asked to do and what it reveals.  In: `force`
 * (NULL: take the first event) is the phase's two code bytes, the ending
 * event kind (1, 2: re-stick of block i; 3: threshold of the stuck block;
 * 4, 5: both blocks re-stick, at block 1's, 2's root) and a count: 0 for
 * a root (the guard's first rise through zero), the local maxima passed
 * before the one that ends the phase with BK2_EV_ATMAX; `borders` (NULL: none wanted) receives the
 * phase's borders, named after `phase`.  Out: `rec`, the code bytes of
 * the phase followed (filled when `want_code`). */
typedef struct {
  int tangent;         /* a guard only touched zero */
  long steps;          /* root-finding intervals */
  const unsigned char *force;
  int want_code;
  unsigned char rec[2];
  sc_border_list *borders;
  int phase;
  /* The first phase after a GSP: the stuck block's S - T at its start,
   * exactly (1 + 2 alpha)(d - d*) up to sign, which the guard built from
   * the rounded onset state may get wrong in sign next to d*. */
  int onset;
  double onset_gap;
  /* borders whose own code differs from the iterate's in one phase
   * (sc_border.alt): filled in when the iterate's code is complete */
  struct {
    size_t idx;
    int phase;
    unsigned char c0, c1;
    int drop_next; /* the next phase (of length zero on the border) goes */
  } patch[8];
  int npatch;
} bk2_events;

/* The event at a local maximum of re-stick guard `kind` (g' = 0, g'' =
 * g2 there): shift the sensitivities by dt = -dg'/g'', stick the block,
 * and return the next mode (a grazing's own defining system). */
int sc_bk2_take_event_at_max(const bk2_dpar *P, int mode, int kind,
                             double g2, const double acc[2], bk2_state *x);
/* Give the border just added its own code: this phase's bytes replaced
 * by (c0, c1), and the next phase dropped if drop_next. */
void sc_bk2_patch(bk2_events *ev, int c0, int c1, int drop_next);

/* Append a border from a dual m (directions: d, alpha, beta, phi, v). */
void sc_bk2_border_add(sc_border_list *l, sc_border_kind kind,
                       const sc_dual *m, const char *name);

/* The refusal of an iterate that does not return to a GSP within
 * max-events slip phases (a slip cycle): SC_EUNDEF with the message. */
int sc_bk2_slip_cycle(const bk2_inst *b, sc_msg *msg);

/* Called after each slip phase with its mode, start state and duration. */
typedef int (*bk2_phase_fn)(void *ctx, int mode, const bk2_state *x0,
                            double duration);

/* Fill first_g, first_r, first_ok with b->search (again after changing
 * the search). */
void sc_bk2_first_restick(bk2_inst *b);
void sc_bk2_event_shift(const bk2_dpar *P, sc_dual gval, double slope,
                        const double acc[2], bk2_state *x);
/* Take the event `kind` (bk2_rules.h: a re-stick, a threshold, or both
 * re-sticks at once) that ends a phase of `mode`, with x the state there
 * at fixed time, slope the g' of its guard and acc the accelerations:
 * shift the sensitivities by the event time's, reset the velocity of the
 * blocks that stick, and return the next mode (the event table). */
int sc_bk2_take_event(const bk2_dpar *P, int mode, int kind, double slope,
                      const double acc[2], bk2_state *x);
int sc_bk2_iterate(const bk2_inst *b, const bk2_dpar *P, sc_dual d,
                   unsigned flags, bk2_state *x, sc_map_value *out,
                   bk2_phase_fn fn, void *ctx, sc_msg *msg);
/* As sc_bk2_iterate(), following the code `force` (NULL: natural),
 * reporting the code followed into `code` and the borders into `borders`
 * (each may be NULL; borders need P->nd = 5). */
int sc_bk2_iterate_ex(const bk2_inst *b, const bk2_dpar *P, sc_dual d,
                      unsigned flags, const sc_itin_code *force,
                      sc_itin_code *code, sc_border_list *borders,
                      bk2_state *x, sc_map_value *out, bk2_phase_fn fn,
                      void *ctx, sc_msg *msg);

/* One iterate with SC_EVAL_DERIV2 (bk2_map.c): the ordinary evaluation
 * (value, first derivatives, itinerary, borders), then the replay of its
 * phases in jet arithmetic (sc_bk2_jet_replay(), bk2_jet.h) that fills
 * d2fdd2, d2fddp, d3fdd3 and d3fdd2p.  Exact flows only (SC_EINVAL
 * otherwise).  The second derivatives are NaN where an event guard has
 * zero slope, or two re-sticks coincide: f is not twice differentiable
 * there.  grad (5 entries, may be NULL) receives the jet's own first
 * derivatives in (d, alpha, beta, phi, v), a cross-check of the duals'
 * (tests). */
int sc_bk2_eval_jet(const bk2_inst *b, double d, unsigned flags,
                    sc_map_value *out, double *grad, sc_msg *msg);
/* As sc_bk2_eval_jet() along a forced code, with the code followed and
 * the borders (sc_bk2_iterate_ex()); a code with an event at a guard's
 * maximum is refused (SC_EINVAL). */
int sc_bk2_eval_jet_ex(const bk2_inst *b, double d, unsigned flags,
                       const sc_itin_code *force, sc_itin_code *code,
                       sc_border_list *borders, sc_map_value *out,
                       double *grad, sc_msg *msg);

/* Where a trajectory goes: samples every dtau of slip time, times
 * counted from the start of the run (tau). */
typedef struct {
  double tau, dtau;
  int (*fn)(void *, double, const double *, int);
  void *ctx;
} bk2_traj;

/* Emit the state s (Y1, Y2, U1, U2) at time t into the phase. */
static inline int bk2_traj_emit(bk2_traj *c, double t, const double s[4],
                                int mode) {
  return c->fn(c->ctx, c->tau + t, s, mode) ? SC_ECALLBACK : SC_OK;
}

/* The flows of the model: what the event loop (bk2_map.c) asks of them.
 * Two implementations, sc_bk2_flows_exact (bk2.c) and
 * sc_bk2_flows_numerical (bk2_numerical.c). */
struct bk2_flows {
  const char *name; /* the value of `flows` */
  /* Prepare b for its parameters (b->flows is set): caches, workspaces.
   * Its release frees what it made; both may be called more than once. */
  int (*setup)(bk2_inst *b, sc_msg *msg);
  void (*release)(bk2_inst *b);
  /* One slip phase of `mode` (fresh: the blocks that start slipping)
   * from state x to its first event (the rules of bk2_events, taken
   * with sc_bk2_take_event*): x becomes the state after the event,
   * *duration the phase's length; returns the next mode or an error. */
  int (*phase)(const bk2_inst *b, const bk2_dpar *P, int mode, int fresh,
               bk2_state *x, double *duration, bk2_events *ev, sc_msg *msg);
  /* Sample a finished phase of `mode` from x0 lasting `duration` every
   * t->dtau and at its end, then advance t->tau by its duration. */
  int (*sample)(const bk2_inst *b, const bk2_dpar *P, int mode,
                const bk2_state *x0, double duration, bk2_traj *t);
  /* How far a map value can be from the exact one (0: rounding only). */
  double (*precision)(const bk2_inst *b);
  /* Optional (NULL: the event loop on duals with nd = 0): a plain
   * evaluation (no derivatives, forced code, code or borders) that gives
   * the same numbers faster. */
  int (*value)(const bk2_inst *b, double d, unsigned flags,
               sc_map_value *out, sc_msg *msg);
};

extern const bk2_flows sc_bk2_flows_exact;
extern const bk2_flows sc_bk2_flows_numerical;

#endif
