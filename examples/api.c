/* The smallest use of the library: the two-block model of fig 5.4
 * (alpha = 3, beta = 1, phi = 1.25, V = 0.025, driver moving), iterated
 * from d0 = 0.02.  Known answer: a stable period-2 orbit, symmetric
 * because beta = 1 (f(-d) = -f(d)): d alternates between +-0.0153337753870
 * with itineraries "2-12-1" and "1-12-2" (one block slips, triggers the
 * other, re-sticks first), f' = 0.634677 on each iterate.
 *
 *   cc api.c $(pkg-config --cflags --libs slipcont) -o api && ./api
 */
#include <stdio.h>

#include "slipcont/slipcont.h"

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
  for (int k = 0; k < 200; k++) {
    sc_map_value r;
    int st = sc_map_eval(m, d, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &r, &msg);
    if (st) {
      fprintf(stderr, "iterate %d: %s: %s\n", k, sc_strerror(st), msg.text);
      sc_map_free(m);
      return 1;
    }
    if (k >= 198)
      printf("d = %.15f -> f(d) = %.15f  f' = %g  itinerary %s\n", d, r.f,
             r.dfdd, r.itinerary);
    d = r.f;
  }
  sc_map_free(m);
  return 0;
}
