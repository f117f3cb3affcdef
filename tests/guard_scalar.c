/* The root searches of src/hybrid/guard.c compiled without the pair
 * march's two lanes (SC_GUARD_NO_LANES), under names of their own, so that
 * tests/test_guard.c can check that the lanes change no number: the same
 * source, one guard at a time. */
#define SC_GUARD_NO_LANES 1
#define sc_guard_eval guard_scalar_eval
#define sc_guard_m3 guard_scalar_m3
#define sc_guard_first_root guard_scalar_first_root
#define sc_guard_first_root_pair guard_scalar_first_root_pair
#include "hybrid/guard.c"
