/* tests/guard_scalar.c: the searches without the pair march's lanes. */
#ifndef SC_TEST_GUARD_SCALAR_H
#define SC_TEST_GUARD_SCALAR_H

#include "hybrid/hybrid_impl.h"

int guard_scalar_first_root_pair(const sc_guard *g, double tmax,
                                 const int *skip, double atol, double rtol,
                                 sc_guard_limit_fn limit, void *ctx,
                                 sc_root *out);

#endif
