/* Private to the bk2 model: exact second derivatives of its event map
 * (bk2_jet.c). */
#ifndef SC_MODELS_BK2_JET_H
#define SC_MODELS_BK2_JET_H

#include "models/bk2_impl.h"

/* Most slip phases one iterate may have for SC_EVAL_DERIV2 (the replay
 * keeps their modes and durations on the stack). */
#define SC_BK2_JET_MAXPHASES 256

/* One iterate with SC_EVAL_DERIV2: the ordinary evaluation (value,
 * first derivatives, itinerary, borders), then a replay of its phases in
 * jet arithmetic (src/hybrid/jet.h) that fills d2fdd2, d2fddp, d3fdd3 and
 * d3fdd2p.  Exact flows only (SC_EINVAL otherwise).  The second
 * derivatives are NaN where an event guard has zero slope, or two
 * re-sticks coincide: f is not twice differentiable there.  grad (5
 * entries, may be NULL) receives the jet's own first derivatives in
 * (d, alpha, beta, phi, v), a cross-check of the duals' (tests). */
int sc_bk2_eval_jet(const bk2_inst *b, double d, unsigned flags,
                    sc_map_value *out, double *grad, sc_msg *msg);
/* As sc_bk2_eval_jet() along a forced code, with the code followed and
 * the borders (sc_bk2_iterate_ex()); a code with an event at a guard's
 * maximum is refused (SC_EINVAL). */
int sc_bk2_eval_jet_ex(const bk2_inst *b, double d, unsigned flags,
                       const sc_itin_code *force, sc_itin_code *code,
                       sc_border_list *borders, sc_map_value *out,
                       double *grad, sc_msg *msg);

#endif
