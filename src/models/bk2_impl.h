/* Private to the bk2 model: its instance, parameters as duals, state,
 * and the pieces shared by the exact and the numerical flows. */
#ifndef SC_MODELS_BK2_IMPL_H
#define SC_MODELS_BK2_IMPL_H

#include "hybrid/dual.h"
#include "slipcont/hybrid.h"
#include "slipcont/models.h"

typedef struct bk2_num bk2_num; /* numerical-flow workspace (GSL) */

/* Parameters: alpha, beta, phi, v, gamma (velocity weakening only). */
#define BK2_NPARAM 5

/* Parameters as duals: direction 0 is d, 1..4 are alpha, beta, phi, v. */
typedef struct {
  int nd;
  sc_dual alpha, beta, mu, k1, k2, t2, v, vs, w1, w2;
} bk2_dpar;

typedef struct {
  double alpha, beta, phi, v, gamma;
  int frozen;    /* driver = frozen: Vs = 0 during slips */
  int vw;        /* friction = velocity-weakening */
  int numerical; /* flows = numerical (always with velocity weakening) */
  sc_accuracy acc;
  double mu, w1, w2, vs, dstar; /* derived */
  bk2_num *num;                 /* owned; NULL for exact flows */
  bk2_dpar p0;                  /* the parameters without derivatives */
  /* The first-root search of the exact flows: sc_guard_first_root, set
   * by bk2_setup; tests put a frozen earlier search here to check that a
   * faster one changes nothing but speed (tests/test_map_equiv.c). */
  int (*search)(const sc_guard *g, double tmax, int skip_start, double atol,
                double rtol, sc_root *out);
  /* The re-stick guard of block i in a slip that starts from a GSP does
   * not depend on d (its amplitude is (1 - mu) T_i / (1 + alpha)): its
   * guard and first root, found once by sc_bk2_first_restick() (exact
   * flows), and whether they are there. */
  /* Plain evaluations go through the dual path (nd = 0) instead of the
   * value-only path: set by tests that compare the two (they must give
   * bit-identical results); 0 after bk2_setup. */
  int dual_only;
  sc_guard first_g[2];
  sc_root first_r[2];
  int first_ok[2];
} bk2_inst;

/* Directions of the forward-mode derivatives: d and the parameters that
 * act (gamma only with velocity weakening). */
static inline int bk2_nd(const bk2_inst *b) {
  return b->vw ? 1 + BK2_NPARAM : BK2_NPARAM;
}


/* Positions and velocities of the two blocks. */
typedef struct {
  sc_dual y1, y2, u1, u2;
} bk2_state;

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

/* Event kinds of a code (see bk2_events).  BK2_EV_ATMAX on a re-stick:
 * the phase ends at the guard's (skip + 1)-th local maximum instead of a
 * root (a grazing's own defining system). */
enum { BK2_EV_RESTICK1 = 1, BK2_EV_RESTICK2, BK2_EV_THRESHOLD, BK2_EV_BOTH,
       BK2_EV_BOTH2, BK2_EV_ATMAX = 0x80 };
/* BK2_EV_BOTH, BK2_EV_BOTH2: both blocks re-stick at the root of block
 * 1's, block 2's guard. */
#define BK2_IS_BOTH(k) ((k) == BK2_EV_BOTH || (k) == BK2_EV_BOTH2)
#define BK2_GUARD_OF(k)                                                        \
  ((k) == BK2_EV_BOTH ? BK2_EV_RESTICK1 : (k) == BK2_EV_BOTH2 ? BK2_EV_RESTICK2 \
                                                               : (k))

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

/* Called after each slip phase with its mode, start state and duration. */
typedef int (*bk2_phase_fn)(void *ctx, int mode, const bk2_state *x0,
                            double duration);

void sc_bk2_dparams(const bk2_inst *b, int nd, bk2_dpar *P);
/* Fill first_g, first_r, first_ok with b->search (again after changing
 * the search). */
void sc_bk2_first_restick(bk2_inst *b);
int sc_bk2_onset(const bk2_inst *b, const bk2_dpar *P, sc_dual d,
                 bk2_state *x);
void sc_bk2_event_shift(const bk2_dpar *P, sc_dual gval, double slope,
                        const double acc[2], bk2_state *x);
/* Take the event of guard `kind` (1, 2: re-stick of block i; 3: threshold
 * of the stuck block) that ends a phase of `mode`, with x the state there
 * at fixed time, slope the guard's g' and acc the accelerations: shift
 * the sensitivities by the event time's, reset the velocity of a block
 * that sticks, and return the next mode. */
int sc_bk2_take_event(const bk2_dpar *P, int mode, int kind, double slope,
                      const double acc[2], bk2_state *x);
int sc_bk2_phase(const bk2_inst *b, const bk2_dpar *P, int mode, int fresh,
                 bk2_state *x, double *duration, bk2_events *ev,
                 sc_msg *msg);
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

/* Trajectory context helpers for the numerical sampler. */
int sc_bk2_traj_emit(void *traj_ctx, double t, const double s[4], int mode);
void sc_bk2_traj_advance(void *traj_ctx, double duration);
double sc_bk2_traj_dtau(void *traj_ctx);

/* Numerical flows (bk2_numerical.c). */
int sc_bk2_num_setup(bk2_inst *b, sc_msg *msg);
void sc_bk2_num_release(bk2_inst *b);
int sc_bk2_num_phase(const bk2_inst *b, const bk2_dpar *P, int mode,
                     int fresh, bk2_state *x, double *duration,
                     bk2_events *ev, sc_msg *msg);
int sc_bk2_num_sample(const bk2_inst *b, const bk2_dpar *P, int mode,
                      const bk2_state *x0, double duration, void *traj_ctx);

#endif
