/* Private to the chain model (docs/chain.md): the instance, its cache of
 * run bases, and the phase machinery shared by chain.c (the table, setup,
 * the onset and the event loop) and chain_phase.c (one slip phase: its
 * runs in closed form, its guards, its first events, the state and its
 * sensitivities at the end). */
#ifndef SC_MODELS_CHAIN_IMPL_H
#define SC_MODELS_CHAIN_IMPL_H

#include "slipcont/common.h"
#include "slipcont/hybrid.h"
#include "slipcont/models.h"

/* Most blocks (the option's range). */
#define CHAIN_MAXBLOCKS 256
/* Parameters in table order; beta_i for i = 2..5 is P_BETA2 + i - 2. */
enum { P_ALPHA, P_PHI, P_V, P_GAMMA, P_BETA2, CHAIN_NPARAM = P_BETA2 + 4 };
/* Blocks whose threshold is a parameter (beta2..beta5; block 1's is 1);
 * the others have threshold 1 (docs/chain.md, "Parameters"). */
#define CHAIN_PARAM_BLOCKS 5
/* Options in table order. */
enum { O_BLOCKS, O_TOPOLOGY, O_DRIVER, O_FRICTION, O_FLOWS };

/* The numerical flows' workspace (chain_vw.c). */
typedef struct chain_num chain_num;

/* A phase's horizon in turns of its slowest mode (frequencies are >= 1,
 * so a turn is <= 2 pi): a slip without any event for so long is taken
 * for a slip cycle that never returns to a global stick phase. */
#define CHAIN_HORIZON_TURNS 1000.0
#define CHAIN_TWO_PI 6.28318530717958647692

/* Shapes of a run's coupling matrix L (docs/chain.md, "Exact flows"):
 * a path whose two ends are coupled to stuck blocks (degree 2 at both
 * ends: inside an open chain, or any proper part of a ring); a path whose
 * first block is a free end of the open chain (degree 1 there; the run
 * at the other end uses it read backwards); the whole chain (open: free
 * ends at both; ring: the cycle). */
enum { SHAPE_INNER, SHAPE_END, SHAPE_WHOLE, CHAIN_NSHAPES };

/* A run's eigenbasis: L = Q diag(mu) Q^T, Q column-major (Q[i + k m] is
 * component i of eigenvector k). */
typedef struct {
  const double *Q, *mu;
} chain_basis;

/* One run of slipping blocks in a phase: blocks start, start + 1, ...,
 * start + m - 1 (mod N); row i of its basis is its element i, or element
 * m - 1 - i when rev (a run at the open chain's right end); its modes
 * are off .. off + m - 1 of the phase's modal arrays. */
typedef struct {
  int start, m, rev, off;
  chain_basis B;
} chain_run;

struct chain_bx; /* borders and itinerary codes (chain_border.c) */

/* The thresholds given as data (chain_thresholds.c, docs/chain.md
 * "Thresholds per block"): `thresholds`, `betas`, `threshold-seed`,
 * `threshold-range`, in the data table's order. */
enum { D_THRESHOLDS, D_BETAS, D_SEED, D_RANGE, CHAIN_NDATA };
typedef struct {
  int random;      /* thresholds = random */
  int nbetas;      /* values in betas (0: not given) */
  int seed_given, range_given;
  unsigned long long seed;
  double lo, hi;   /* the draw's range */
  /* the data's threshold of block i + 1 (T[0] = 1): betas, or the draw */
  double T[CHAIN_MAXBLOCKS];
} chain_data;

/* The data table and its callbacks (chain_thresholds.c). */
extern const sc_data_info chain_data_info[CHAIN_NDATA];
int chain_set_data(void *inst, size_t i, const char *value, sc_msg *msg);
int chain_data_params(void *inst, const int *opt, double *p,
                      unsigned char *which, sc_msg *msg);

/* The record of one evaluation's phases for its second derivatives
 * (chain_jet.c). */
typedef struct chain_log chain_log;

/* The record of one slip event while it is evaluated (chain_events.c);
 * NULL in the plain map. */
typedef struct chain_rec chain_rec;

typedef struct {
  int N, ring, frozen;
  chain_data data;
  chain_rec *rec;
  int vw;        /* friction = velocity-weakening */
  int numerical; /* flows = numerical (always with velocity weakening) */
  double alpha, phi, v, Vs, gamma;
  chain_num *num; /* the numerical flows' workspace, NULL for exact ones */
  double T[CHAIN_MAXBLOCKS], K[CHAIN_MAXBLOCKS];
  sc_accuracy acc;
  int alloc_N;        /* blocks the buffers below were sized for */
  /* bases computed at setup (N <= CHAIN_EAGER_BLOCKS): table[shape][m] */
  double *table;      /* their storage */
  chain_basis *eager; /* [CHAIN_NSHAPES * (N + 1)], NULL: bases per phase */
  double *scratch;    /* bases of one phase otherwise: N^2 + N doubles */
  double *lwork;      /* dsyev's workspace */
  int nlwork;
  /* one phase */
  chain_run *runs;
  int nruns;
  int *slip, *fresh;
  double *Y, *U, *Y0, *U0;
  double *lam, *om, *P0, *P1, *A, *B; /* per mode */
  double *cs, *sn;                    /* cos, sin of each mode at the event */
  double *gw, *ga, *gb; /* the terms of a phase's guards: N^2 + 2N each */
  /* sensitivities: columns d_1..d_(N-1), then the parameters */
  int P;
  double *TY, *TU;    /* [c N + i] */
  double *mz, *mzp;   /* one column's modal sensitivities, per mode */
  double *NY, *NU;    /* one column's sensitivities at the event */
  double *Ad;         /* accelerations at the event, per block */
  struct chain_bx *bx; /* an evaluation with borders or codes; NULL else */
  int onset_block;    /* the block the last onset placed the others from */
  chain_log *log;     /* SC_EVAL_DERIV2's record, NULL until asked for */
} chain_inst;

/* The event that ends a phase. */
typedef struct {
  int kind;     /* CHAIN_RESTICK or CHAIN_THRESHOLD */
  int block;    /* 0-based */
  double t;     /* the root */
  double slope; /* the guard's slope there */
  double u;     /* how well t is known: rounding over slope */
} chain_event;
enum { CHAIN_RESTICK = 0, CHAIN_THRESHOLD = 1 };

/* Degree of block j in the chain (its number of neighbours). */
static inline int chain_degree(const chain_inst *c, int j) {
  return c->ring ? 2 : (j > 0) + (j < c->N - 1);
}
/* Neighbours of block j into nb (at most 2); returns their number. */
static inline int chain_neighbours(const chain_inst *c, int j, int nb[2]) {
  int k = 0;
  if (c->ring) {
    nb[k++] = (j + c->N - 1) % c->N;
    nb[k++] = (j + 1) % c->N;
  } else {
    if (j > 0) nb[k++] = j - 1;
    if (j < c->N - 1) nb[k++] = j + 1;
  }
  return k;
}

/* Block of element i of run r, and the row of its basis. */
static inline int chain_run_block(const chain_inst *c, const chain_run *r,
                                  int i) {
  return (r->start + i) % c->N;
}
static inline int chain_run_row(const chain_run *r, int i) {
  return r->rev ? r->m - 1 - i : i;
}

/* The eigenbasis of a run's coupling matrix (from the table, or computed
 * into the phase's scratch at offset *used doubles). */
int chain_basis_of(chain_inst *c, int shape, int m, size_t *used,
                   chain_basis *out, sc_msg *msg);

/* One slip phase from the state in c->Y, c->U with the slipping set
 * c->slip (c->fresh: the blocks that started with it): the phase's runs,
 * their modal data, the first events (up to CHAIN_MAXBLOCKS in ev, their
 * number in *nev, the earliest first), the state at the end in c->Y,
 * c->U, and with deriv the sensitivities c->TY, c->TU carried to it.
 * Returns SC_OK or a negative status (SC_EUNDEF: no event). */
int chain_phase(chain_inst *c, int deriv, chain_event *ev, int *nev,
                sc_msg *msg);

/* The numerical flows (chain_vw.c, docs/chain.md "Velocity weakening"):
 * chain_num_setup() (re)makes c->num for c->N blocks and c->acc's ODE
 * tolerances; chain_num_release() frees it; chain_phase_num() is
 * chain_phase() by integration of the same equations with the friction
 * law of c->vw, the sensitivities by the variational equations;
 * chain_num_precision() is how well it knows f. */
int chain_num_setup(chain_inst *c, sc_msg *msg);
void chain_num_release(chain_inst *c);
int chain_phase_num(chain_inst *c, int deriv, chain_event *ev, int *nev,
                    sc_msg *msg);
double chain_num_precision(const chain_inst *c);

/* --- borders and itinerary codes (chain_border.c, docs/chain.md,
 * "Borders"); the evaluation without them never calls these. */

/* One iterate of the map (chain.c); with c->bx set, it follows and
 * records codes and appends borders through the hooks below. */
int chain_eval_n(void *inst, const double *d, unsigned flags,
                 sc_mapn_value *out, sc_msg *msg);
/* The model's eval_n_ex (models.h). */
int chain_eval_n_ex(void *inst, const double *d, unsigned flags,
                    const sc_itin_code *force, sc_itin_code *code,
                    sc_bordern_list *borders, sc_mapn_value *out,
                    sc_msg *msg);
/* Whether an evaluation with c->bx needs the sensitivities (borders). */
int chain_bx_deriv(const chain_inst *c);
/* The onset's hook: the starting blocks (forced or natural, in c->slip
 * and c->fresh), their code and the switching borders; gap[i] = T_i -
 * S_i at the end of the GSP; returns the block the positions are placed
 * from. */
int chain_bx_onset(chain_inst *c, const double *gap, int j);
/* The phase's hook, before the state at its end: the forced events in
 * place of ev (*nev of them, the first one's time the phase's end), the
 * code of the events and the phase's borders. */
int chain_bx_phase(chain_inst *c, chain_event *ev, int *nev, sc_msg *msg);
/* The guard of an event of the phase (kind, block) into g, its terms in
 * the phase's buffers (valid until the next guard). */
void chain_guard_of(chain_inst *c, int kind, int block, sc_guard_long *g);
/* The derivatives of that guard at time t of the phase, t held fixed,
 * in every column (d, then the parameters) into dg (c->P values), and
 * its rate there into *gdot; overwrites the state at the event. */
void chain_guard_sens(chain_inst *c, int kind, int block, double t,
                      double *dg, double *gdot);
/* The maximal runs of the slipping set c->slip into c->runs, c->nruns,
 * with their bases (chain_phase.c). */
int chain_find_runs(chain_inst *c, sc_msg *msg);

/* Second derivatives (chain_jet.c): chain_log_start() after the onset
 * (takes the record's buffers on first use), chain_log_phase() after each
 * phase (its events ev[0 .. nev - 1], the earliest first), then
 * chain_jet_fill() at the GSP: out's H, Jp and T at the state x by
 * replaying the record in jet arithmetic with the closed-form (Coulomb)
 * flows, whichever flows found the phases (NaN where an event's guard
 * has zero slope: f is not twice differentiable there; NaN under
 * velocity weakening, which has no closed form). */
int chain_log_start(chain_inst *c, sc_msg *msg);
void chain_log_phase(chain_inst *c, const chain_event *ev, int nev);
int chain_jet_fill(chain_inst *c, const double *x, sc_mapn_value *out,
                   sc_msg *msg);
void chain_log_free(chain_inst *c);

/* The slip-event record (chain_events.c), called by the event loop only
 * when c->rec is set: after the onset, after each phase (its length t,
 * before its re-sticks are applied), at the global stick phase. */
void chain_rec_begin(chain_inst *c);
void chain_rec_phase(chain_inst *c, double t);
void chain_rec_end(chain_inst *c);
/* The model's eval_event (models.h). */
int chain_eval_event(void *inst, const double *x, unsigned flags,
                     sc_mapn_value *out, sc_slip_event *ev, sc_msg *msg);
/* The model's trajectory_n (models.h). */
int chain_trajectory(void *inst, const double *x, int iterations, double dtau,
                     int (*fn)(void *, double, const double *, int), void *ctx,
                     sc_msg *msg);

#endif
