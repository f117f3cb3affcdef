/* Map iterates per second on one core, for the fig 5.6 and fig 5.8
 * parameters, with exact flows and with numerical flows at two ODE
 * tolerances, and the one-step error of each against the exact map.
 *
 *   build/bench_map [repeats]
 *
 * Each figure: iterate the exact map ("precise" preset) from d0 = 0.02
 * past its transient,
 * keep 2000 attractor points; time f on those points (the same inputs for
 * every variant), `repeats` times, and print the median rate.  The error
 * is max |f_variant(d) - f_exact(d)| over the points whose itineraries
 * agree (a point within the integration error of a jump of f is not an
 * error of the flow). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "slipcont/map.h"
#include "bench_util.h"

#define NPTS 2000

typedef struct {
  const char *name;
  double alpha, beta, v;
  const char *driver;
} figure;

int main(int argc, char **argv) {
  int repeats = argc > 1 ? atoi(argv[1]) : 5;
  if (repeats < 1 || repeats > 101) repeats = 5;
  const figure figs[] = {
      {"fig 5.6 (alpha 2.9, beta 1, V 0.019, moving; chaotic)", 2.9, 1, 0.019,
       "moving"},
      {"fig 5.8 (alpha 3.5, beta 2.5, frozen; chaotic)", 3.5, 2.5, 0.025,
       "frozen"},
  };
  /* Exact flows under each accuracy preset, then numerical flows at two
   * ODE tolerances.  The reference is exact flows, "precise" preset. */
  const struct {
    const char *label;
    const char *flows;
    const char *preset;
    double tol;
  } variants[] = {{"exact, precise", "exact", "precise", 0},
                  {"exact, default", "exact", "default", 0},
                  {"exact, fast", "exact", "fast", 0},
                  {"numerical 1e-8", "numerical", "default", 1e-8},
                  {"numerical 1e-12", "numerical", "default", 1e-12}};
  static double pts[NPTS], fex[NPTS];
  static char itex[NPTS][SC_ITIN_LEN];
  printf("| parameters | flows | iterates/s (median of %d) | max one-step "
         "error vs exact (precise) |\n|---|---|---|---|\n",
         repeats);
  for (size_t fi = 0; fi < sizeof figs / sizeof figs[0]; fi++) {
    sc_msg msg;
    sc_map *ex;
    sc_accuracy precise;
    sc_accuracy_preset(&precise, "precise", NULL);
    sc_map_alloc("bk2", &precise, &ex, &msg);
    sc_map_set_param_by_name(ex, "alpha", figs[fi].alpha, &msg);
    sc_map_set_param_by_name(ex, "beta", figs[fi].beta, &msg);
    sc_map_set_param_by_name(ex, "v", figs[fi].v, &msg);
    sc_map_set_option(ex, "driver", figs[fi].driver, &msg);
    double d = 0.02;
    sc_map_value r;
    for (int k = 0; k < 500 + NPTS; k++) {
      if (sc_map_eval(ex, d, SC_EVAL_ITINERARY, &r, &msg)) {
        fprintf(stderr, "%s\n", msg.text);
        return 1;
      }
      if (k >= 500) {
        pts[k - 500] = d;
        fex[k - 500] = r.f;
        strcpy(itex[k - 500], r.itinerary);
      }
      d = r.f;
    }
    for (size_t vi = 0; vi < sizeof variants / sizeof variants[0]; vi++) {
      sc_map *m;
      sc_map_clone(ex, &m, &msg);
      sc_accuracy acc;
      sc_accuracy_preset(&acc, variants[vi].preset, NULL);
      if (variants[vi].tol > 0) acc.ode_atol = acc.ode_rtol = variants[vi].tol;
      sc_map_set_accuracy(m, &acc, &msg);
      sc_map_set_option(m, "flows", variants[vi].flows, &msg);
      double rates[101], err = 0, sink = 0;
      /* one untimed pass: caches and clock frequency settle */
      for (int i = 0; i < NPTS; i++) sc_map_eval(m, pts[i], 0, &r, &msg);
      for (int rep = 0; rep < repeats; rep++) {
        double t0 = bench_wall();
        for (int i = 0; i < NPTS; i++) {
          sc_map_eval(m, pts[i], 0, &r, &msg);
          sink += r.f;
        }
        rates[rep] = NPTS / (bench_wall() - t0);
      }
      for (int i = 0; i < NPTS; i++) {
        sc_map_eval(m, pts[i], SC_EVAL_ITINERARY, &r, &msg);
        if (strcmp(r.itinerary, itex[i]) == 0)
          err = fmax(err, fabs(r.f - fex[i]));
      }
      qsort(rates, (size_t)repeats, sizeof rates[0], bench_cmp_double);
      printf("| %s | %s | %.4g | %.3g |%s\n", figs[fi].name,
             variants[vi].label, rates[repeats / 2], err,
             sink == 42 ? " " : "");
      sc_map_free(m);
    }
    sc_map_free(ex);
  }
  return 0;
}
