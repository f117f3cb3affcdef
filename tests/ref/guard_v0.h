/* The first-root search before the grid march, kept callable for the map
 * equivalence tests (tests/ref/guard_v0.c). */
#ifndef SC_TESTS_REF_GUARD_V0_H
#define SC_TESTS_REF_GUARD_V0_H

#include "slipcont/hybrid.h"

int sc_guard_first_root_v0(const sc_guard *g, double tmax, int skip_start,
                           double atol, double rtol, sc_root *out);

#endif
