/* A tiny PASS/FAIL helper for the ctest programs.  Every check prints the
 * observed and expected values and the tolerance; tu_finish() prints
 * "N passed, N failed" and returns the exit status. */
#ifndef SC_TEST_UTIL_H
#define SC_TEST_UTIL_H

#include <stdio.h>

/* |observed - expected| <= tol. */
int tu_close(const char *what, double observed, double expected, double tol);
/* |observed - expected| <= rtol |expected|. */
int tu_rel(const char *what, double observed, double expected, double rtol);
/* A condition, with a formatted explanation printed on failure. */
int tu_true(int cond, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* Integer equality. */
int tu_int(const char *what, long observed, long expected);
/* A reproducible uniform draw in [lo, hi] (xorshift64*), restarted by
 * tu_seed(): the same numbers on every machine. */
void tu_seed(unsigned long long s);
double tu_uni(double lo, double hi);
/* Summary line and exit status (0 if all passed). */
int tu_finish(void);

#endif
