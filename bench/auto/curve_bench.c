/* slipcont's side of the cubic map's fold curve beside AUTO-07p
 * (docs/performance.md, "Beside AUTO-07p"): sc_curve_trace() on the
 * scene examples/curve-cubic.ini, from its start guess (corrected onto
 * the fold by the trace itself), with the largest relative violation of
 * 27 mu1^2 = 4 mu2^3 over the points and the cusp's distance from the
 * origin.
 *
 *   curve_bench once       one trace in a fresh process, its time inside
 *   curve_bench repeat N   the median of N traces in this process
 *
 * The time includes the map's allocation.  Built and run by
 * run_compare.sh. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/slipcont.h"
#include "bench_util.h" /* bench/ */

typedef struct {
  double worst, cusp;
  long n;
} acc_t;

static int pt(void *c, const sc_curve_point *p) {
  acc_t *a = c;
  double l = 27 * p->x * p->x, r = 4 * p->y * p->y * p->y;
  a->worst = fmax(a->worst, fabs(l - r) / (1 + l));
  a->n++;
  return 0;
}

static int sp(void *c, const sc_curve_special *s) {
  acc_t *a = c;
  if (!strcmp(s->label, "CP"))
    a->cusp = fmax(fabs(s->x), fmax(fabs(s->y), fabs(s->d)));
  return 0;
}

static double trace(acc_t *a) {
  double t0 = bench_wall();
  sc_map *m;
  sc_map_alloc("cubic", NULL, &m, NULL);
  sc_map_set_param(m, 0, -0.5, NULL);
  sc_map_set_param(m, 1, 1.2, NULL);
  sc_curve_settings s;
  sc_curve_settings_default(&s);
  s.xlo = -1.5, s.xhi = 1.5, s.ylo = -0.5, s.yhi = 1.5;
  s.hmax = 0.04, s.h0 = 0.004; /* the scene's defaults */
  a->worst = 0, a->n = 0, a->cusp = NAN;
  sc_curve_output out = {pt, sp, a};
  sc_curve_stats st;
  sc_curve_trace(m, &s, 0.6, &out, &st, NULL);
  sc_map_free(m);
  return bench_wall() - t0;
}

int main(int argc, char **argv) {
  acc_t a;
  if (argc == 2 && !strcmp(argv[1], "once")) {
    double t = trace(&a);
    printf("points %ld worst %.3g cusp %.3g\ntime %.6g\n", a.n, a.worst,
           a.cusp, t);
    return 0;
  }
  long n = argc == 3 && !strcmp(argv[1], "repeat") ? strtol(argv[2], NULL, 10) : 0;
  if (n < 1 || n > 100000) {
    fprintf(stderr, "usage: curve_bench once | curve_bench repeat N (1..100000)\n");
    return 2;
  }
  double *t = malloc((size_t)n * sizeof *t);
  if (!t) return 1;
  for (long i = 0; i < n; i++) t[i] = trace(&a);
  printf("points %ld worst %.3g cusp %.3g\nmedian %.6g\n", a.n, a.worst,
         a.cusp, bench_median(t, (int)n));
  free(t);
  return 0;
}
