/* Private to the bk2 model: exact second derivatives of its event map
 * (bk2_jet.c), replayed in jet arithmetic over the phases an ordinary
 * evaluation found (sc_bk2_eval_jet(), bk2_impl.h). */
#ifndef SC_MODELS_BK2_JET_H
#define SC_MODELS_BK2_JET_H

#include "models/bk2_impl.h"

/* Most slip phases one iterate may have for SC_EVAL_DERIV2 (the replay
 * keeps their modes and durations on the stack). */
#define SC_BK2_JET_MAXPHASES 256

/* The phases of one iterate, in order: their modes and durations. */
typedef struct {
  int n;
  int mode[SC_BK2_JET_MAXPHASES];
  double dur[SC_BK2_JET_MAXPHASES];
} bk2_phase_log;

/* Replay the phases L of the iterate from d (exact flows; out holds the
 * ordinary evaluation's results, `neutral` read) in jet arithmetic
 * (src/hybrid/jet.h): fills d2fdd2, d2fddp, d3fdd3 and d3fdd2p, NaN where
 * an event guard has zero slope or two re-sticks coincide (f is not twice
 * differentiable there).  grad (5 entries, may be NULL) receives the
 * jet's own first derivatives in (d, alpha, beta, phi, v), a cross-check
 * of the duals' (tests). */
void sc_bk2_jet_replay(const bk2_inst *b, double d, const bk2_phase_log *L,
                       sc_map_value *out, double *grad);

#endif
