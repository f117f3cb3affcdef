/* The 1:n resonance of a slip of both blocks (docs/curves.md, "Why curves
 * end at alpha = 4").
 *
 * In a slip of both blocks the sum Y1 + Y2 oscillates with frequency 1
 * and the difference d = Y2 - Y1 with w2 = sqrt(1 + 2 alpha), about
 * mu d* (K2 - K1 = (beta - 1) mu over 1 + 2 alpha).  With the driver
 * frozen (Vs = 0; or V = 0) a slip that starts from a global stick phase
 * at d = d* starts both blocks at rest, so both modes start at rest: U1
 * and U2 are combinations of sin t and sin w2 t, and where w2 = n is an
 * integer (alpha = (n^2 - 1) / 2: 1.5, 4, 7.5, 12) both vanish at t = pi.
 * There both blocks re-stick at once, whatever beta, phi and V, and the
 * difference has turned n half periods:
 *
 *     f(d*) = mu d* + (-1)^n (1 - mu) d*.
 *
 * So the both-re-stick border (BR) of the iterate from d* is zero on the
 * lines alpha = (n^2 - 1) / 2, and the switching curves of the
 * (alpha, beta) plane meet it there (alpha = 4 in fig 5.8).  Checked
 * here for the cases where pi is the first event (every case below),
 * with the border changing sign across alpha = 4.  With the driver moving
 * (Vs = V > 0) the blocks start at Vs, which is not at rest for the sum
 * mode, and only the difference returns at t = pi: no resonance (checked
 * too). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "slipcont/map.h"
#include "slipcont/models.h"
#include "test_util.h"

static sc_map *map_at(double alpha, double beta, double phi, double v,
                      const char *driver) {
  sc_msg msg;
  sc_accuracy acc;
  sc_map *m = NULL;
  if (sc_accuracy_preset(&acc, "default", &msg) ||
      sc_map_alloc("bk2", &acc, &m, &msg) ||
      sc_map_set_option(m, "driver", driver, &msg) ||
      sc_map_set_param_by_name(m, "alpha", alpha, &msg) ||
      sc_map_set_param_by_name(m, "beta", beta, &msg) ||
      sc_map_set_param_by_name(m, "phi", phi, &msg) ||
      sc_map_set_param_by_name(m, "v", v, &msg)) {
    fprintf(stderr, "setup: %s\n", msg.text);
    sc_map_free(m);
    return NULL;
  }
  return m;
}

/* The BR border of the iterate from d, or NAN when it has none. */
static double both_border(sc_map *m, double d, sc_map_value *out) {
  sc_border b[32];
  sc_border_list l = {b, 32, 0};
  sc_itin_code code;
  sc_msg msg;
  memset(out, 0, sizeof *out);
  if (sc_map_eval_ex(m, d, SC_EVAL_ITINERARY | SC_EVAL_DERIV, NULL, &code,
                     &l, out, &msg)) {
    fprintf(stderr, "eval: %s\n", msg.text);
    return NAN;
  }
  for (size_t k = 0; k < l.n && k < l.cap; k++)
    if (b[k].kind == SC_BORDER_BOTH) return b[k].value;
  return NAN;
}

int main(void) {
  const double betas[] = {1.2, 2.1, 3.0, 5.0};
  const double phis[] = {1.25, 3.0};
  const struct {
    double v;
    const char *driver;
  } drives[] = {{0.025, "frozen"}, {0.5, "frozen"}, {0, "moving"}};
  int cases = 0;
  for (int n = 2; n <= 5; n++) {
    double alpha = (n * n - 1) / 2.0;
    for (size_t ib = 0; ib < sizeof betas / sizeof betas[0]; ib++)
      for (size_t ip = 0; ip < sizeof phis / sizeof phis[0]; ip++)
        for (size_t iv = 0; iv < sizeof drives / sizeof drives[0]; iv++) {
          double beta = betas[ib], phi = phis[ip], mu = 1 / phi;
          sc_map *m = map_at(alpha, beta, phi, drives[iv].v,
                             drives[iv].driver);
          if (!m) return 1;
          double ds = (beta - 1) / (1 + 2 * alpha);
          sc_map_value out;
          double br = both_border(m, ds, &out);
          char what[160];
          snprintf(what, sizeof what,
                   "n %d (alpha %g) beta %g phi %g V %g %s", n, alpha, beta,
                   phi, drives[iv].v, drives[iv].driver);
          tu_true(strcmp(out.itinerary, "12") == 0,
                  "%s: one slip of both blocks (itinerary %s)", what,
                  out.itinerary);
          tu_true(fabs(br) <= 1e-12, "%s: both re-stick at once (BR %.3g)",
                  what, br);
          double expect = mu * ds + (n % 2 ? -1 : 1) * (1 - mu) * ds;
          tu_true(fabs(out.f - expect) <= 1e-13 * (1 + fabs(ds)),
                  "%s: f(d*) = %.17g, closed form %.17g", what, out.f,
                  expect);
          sc_map_free(m);
          cases++;
        }
  }
  /* Across alpha = 4 the border changes sign: block 2 re-sticks first
   * below (12-2), block 1 above (12-1). */
  for (size_t ib = 0; ib < sizeof betas / sizeof betas[0]; ib++) {
    const char *expect[2] = {"12-2", "12-1"};
    for (int side = 0; side < 2; side++) {
      double alpha = side ? 4.001 : 3.999, beta = betas[ib];
      sc_map *m = map_at(alpha, beta, 1.25, 0.025, "frozen");
      if (!m) return 1;
      sc_map_value out;
      (void)both_border(m, (beta - 1) / (1 + 2 * alpha), &out);
      tu_true(strcmp(out.itinerary, expect[side]) == 0,
              "alpha %g beta %g from d*: itinerary %s, expected %s", alpha,
              beta, out.itinerary, expect[side]);
      sc_map_free(m);
    }
  }
  /* The driver moving: the sum mode does not return to Vs at pi. */
  for (int n = 2; n <= 5; n++) {
    double alpha = (n * n - 1) / 2.0;
    sc_map *m = map_at(alpha, 2.1, 1.25, 0.018, "moving");
    if (!m) return 1;
    sc_map_value out;
    double br = both_border(m, 1.1 / (1 + 2 * alpha), &out);
    tu_true(!(fabs(br) <= 1e-6),
            "alpha %g, driver moving: no both re-stick at once (BR %.3g, "
            "itinerary %s)",
            alpha, br, out.itinerary);
    sc_map_free(m);
  }
  printf("%d resonant cases\n", cases);
  return tu_finish();
}
