/* Time sc_curve_trace() on the cubic map's fold curve (the scene
 * examples/curve-cubic.ini): median of 201 runs, and the largest relative
 * violation of 27 mu1^2 = 4 mu2^3 and the cusp's distance from the
 * origin.  Built and run by run_curve.sh beside AUTO-07p. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

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

int main(void) {
  enum { R = 201 };
  double t[R];
  acc_t a = {0, NAN, 0};
  for (int r = 0; r < R; r++) {
    sc_map *m;
    sc_map_alloc("cubic", NULL, &m, NULL);
    sc_map_set_param(m, 0, -0.5, NULL);
    sc_map_set_param(m, 1, 1.2, NULL);
    sc_curve_settings s;
    sc_curve_settings_default(&s);
    s.xlo = -1.5, s.xhi = 1.5, s.ylo = -0.5, s.yhi = 1.5;
    s.hmax = 0.04, s.h0 = 0.004; /* the scene's defaults */
    a.worst = 0, a.n = 0;
    sc_curve_output out = {pt, sp, &a};
    sc_curve_stats st;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    sc_curve_trace(m, &s, 0.6, &out, &st, NULL);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    t[r] = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    sc_map_free(m);
  }
  qsort(t, R, sizeof t[0], bench_cmp_double);
  printf("slipcont cubic fold curve: median %.3g ms (min %.3g ms), %ld points, "
         "worst rel |27 mu1^2 - 4 mu2^3| %.3g, cusp at %.3g from the "
         "origin\n",
         1e3 * t[R / 2], 1e3 * t[0], a.n, a.worst, a.cusp);
  return 0;
}
