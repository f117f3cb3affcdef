/* Private to the hybrid layer and the models built on it. */
#ifndef SC_HYBRID_IMPL_H
#define SC_HYBRID_IMPL_H

#include "slipcont/hybrid.h"

/* C11 has no M_PI. */
#define SC_PI 3.14159265358979323846

/* Inlined into every caller, whatever the compiler's estimate of the cost
 * (the hot helpers of the event search and of bk2's phases); a plain
 * inline elsewhere. */
#if defined(__GNUC__)
#define SC_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define SC_ALWAYS_INLINE inline
#endif

/* The search limit of the later guard of a pair, from the earlier one's
 * guard and root (bk2: the root plus twice its tie tolerance). */
typedef double (*sc_guard_limit_fn)(void *ctx, const sc_guard *g,
                                    const sc_root *r);

/* The first events of two guards of one phase (docs/events.md, "Two
 * guards at once"): out[i] is what sc_guard_first_root(&g[i], ...) finds,
 * the guard whose root comes first searched up to tmax and the other only
 * up to limit() of that root (not found if its root lies beyond).  When
 * g[1] is g[0] with each term times +-1 (the same c0, c1, frequencies:
 * the two re-stick guards of a slip of both blocks), one grid march
 * decides both, each term computed once for the two; otherwise g[0] is
 * searched first and g[1] after it.  Returns SC_OK, or SC_EINVAL as
 * sc_guard_first_root(). */
int sc_guard_first_root_pair(const sc_guard *g, double tmax, const int *skip,
                             double atol, double rtol, sc_guard_limit_fn limit,
                             void *ctx, sc_root *out);

#endif
