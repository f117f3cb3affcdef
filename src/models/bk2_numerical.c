/* Numerical flows for bk2 (placeholder until the GSL path lands). */
#include "models/bk2_impl.h"
#include <stdlib.h>
int sc_bk2_num_setup(bk2_inst *b, sc_msg *msg) {
  (void)b;
  return sc_fail(msg, SC_EINVAL, "bk2: flows = numerical not yet available");
}
void sc_bk2_num_release(bk2_inst *b) { (void)b; }
int sc_bk2_num_phase(const bk2_inst *b, const bk2_dpar *P, int mode, int fresh,
                     bk2_state *x, double *duration, bk2_events *ev,
                     sc_msg *msg) {
  (void)b, (void)P, (void)mode, (void)fresh, (void)x, (void)duration, (void)ev;
  return sc_fail(msg, SC_EINTERNAL, "bk2: numerical flows unavailable");
}
int sc_bk2_num_sample(const bk2_inst *b, const bk2_dpar *P, int mode,
                      const bk2_state *x0, double duration, void *traj_ctx) {
  (void)b, (void)P, (void)mode, (void)x0, (void)duration, (void)traj_ctx;
  return SC_EINTERNAL;
}
