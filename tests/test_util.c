#include "test_util.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>

/* Tests are single-threaded programs: plain counters suffice. */
static int npass, nfail;

static int record(int ok) {
  if (ok) npass++;
  else nfail++;
  return ok;
}

int tu_close(const char *what, double observed, double expected, double tol) {
  int ok = fabs(observed - expected) <= tol;
  printf("%s %s: observed %.17g expected %.17g (diff %.3g, tol %.3g)\n",
         ok ? "PASS" : "FAIL", what, observed, expected,
         fabs(observed - expected), tol);
  return record(ok);
}

int tu_rel(const char *what, double observed, double expected, double rtol) {
  double tol = rtol * fabs(expected);
  int ok = fabs(observed - expected) <= tol;
  printf("%s %s: observed %.17g expected %.17g (rel diff %.3g, rtol %.3g)\n",
         ok ? "PASS" : "FAIL", what, observed, expected,
         expected != 0 ? fabs(observed - expected) / fabs(expected)
                       : fabs(observed),
         rtol);
  return record(ok);
}

int tu_true(int cond, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  printf("%s ", cond ? "PASS" : "FAIL");
  vprintf(fmt, ap);
  printf("\n");
  va_end(ap);
  return record(cond);
}

int tu_int(const char *what, long observed, long expected) {
  int ok = observed == expected;
  printf("%s %s: observed %ld expected %ld\n", ok ? "PASS" : "FAIL", what,
         observed, expected);
  return record(ok);
}

int tu_finish(void) {
  printf("%d passed, %d failed\n", npass, nfail);
  return nfail ? EXIT_FAILURE : EXIT_SUCCESS;
}

static unsigned long long tu_rng = 1;

void tu_seed(unsigned long long s) { tu_rng = s * 2654435761ULL + 1; }

double tu_uni(double lo, double hi) {
  tu_rng ^= tu_rng >> 12;
  tu_rng ^= tu_rng << 25;
  tu_rng ^= tu_rng >> 27;
  unsigned long long r = tu_rng * 2685821657736338717ULL;
  return lo + (hi - lo) * ((double)(r >> 11) / 9007199254740992.0);
}
