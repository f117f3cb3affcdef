/* A downstream program that uses only the numerics (libslipcont): the
 * symmetric period-2 orbit of the two-block model at alpha = 3, beta = 1,
 * phi = 1.25, V = 0.025 (driver moving), found by iterating the event map
 * from d0 = 0.02.  Known answer: d alternates between +-0.01533377538699
 * and f' = 0.634677 on each iterate; the program checks both and exits 1
 * if either is off. */
#include <math.h>
#include <stdio.h>

#include <slipcont/map.h>

int main(void) {
  sc_msg msg;
  sc_map *m;
  if (sc_map_alloc("bk2", NULL, &m, &msg) ||
      sc_map_set_param_by_name(m, "alpha", 3, &msg) ||
      sc_map_set_param_by_name(m, "v", 0.025, &msg)) {
    fprintf(stderr, "%s\n", msg.text);
    return 1;
  }
  double d = 0.02;
  sc_map_value r = {0};
  for (int k = 0; k < 200; k++) {
    int st = sc_map_eval(m, d, SC_EVAL_DERIV, &r, &msg);
    if (st) {
      fprintf(stderr, "iterate %d: %s: %s\n", k, sc_strerror(st), msg.text);
      sc_map_free(m);
      return 1;
    }
    d = r.f;
  }
  sc_map_free(m);
  printf("period-2 orbit: |d| = %.13f, f' = %.6f\n", fabs(d), r.dfdd);
  if (fabs(fabs(d) - 0.0153337753870) > 1e-12 || fabs(r.dfdd - 0.634677) > 1e-6)
    return 1;
  return 0;
}
