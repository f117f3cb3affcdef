/* The Neimark-Sacker curve of ghenon (R = 0.5) over its whole extent in
 * (alpha, beta), with every codimension-two point on it located: the time
 * of one sc_curven_trace() call, the median over SAMPLES calls, with the
 * points it gives and the largest error of a located point against its
 * closed form (docs/maps.md, "Curves and codimension two";
 * docs/performance.md, "Curves of n-dimensional maps").
 *
 *   bench_curven [SAMPLES]      (default 21)
 *
 * The run is the curve task's: the box alpha in [-3, 5], beta in
 * [-1.5, 2], its default steps (hmax the box's smaller side / 50, h0 a
 * tenth of it), from the NS point of the branch at beta = 1.2
 * (alpha = 0.96, x = y = 0.4), both ways to the box: through R3, R2 one
 * way and R4, R1 the other, the neutral-saddle continuations past R1
 * and R2 included. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "slipcont/curve.h"

typedef struct {
  long npoints;
  double err; /* largest distance of R1..R4 from their closed forms */
  int found;  /* R1..R4 located */
} tally;

static int on_special(void *ctx, const sc_curven_special *s) {
  tally *t = ctx;
  /* R_k at s = (2, -2, -1, 0) / (R - 2), beta = 1 + R s, alpha = s^2 + 2 s */
  static const char *const lab[4] = {"R1", "R2", "R3", "R4"};
  static const double num[4] = {2, -2, -1, 0};
  const double R = 0.5;
  for (int k = 0; k < 4; k++)
    if (strcmp(s->label, lab[k]) == 0) {
      double sk = num[k] / (R - 2), b = 1 + R * sk, a = sk * sk + 2 * sk;
      t->err = fmax(t->err, fmax(fabs(s->x - a), fabs(s->y - b)));
      t->found |= 1 << k;
    }
  return 0;
}

int main(int argc, char **argv) {
  int samples = argc > 1 ? atoi(argv[1]) : 21;
  if (samples < 1 || samples > 10000) {
    fprintf(stderr, "usage: bench_curven [SAMPLES in 1..10000]\n");
    return 2;
  }
  sc_map *m;
  sc_msg msg;
  if (sc_map_alloc("ghenon", NULL, &m, &msg) ||
      sc_map_set_param(m, 0, 0.96, &msg) || sc_map_set_param(m, 1, 1.2, &msg) ||
      sc_map_set_param(m, 2, 0.5, &msg)) {
    fprintf(stderr, "bench_curven: %s\n", msg.text);
    return 1;
  }
  sc_curve_settings set;
  sc_curve_settings_default(&set);
  set.type = SC_CURVE_NS, set.ix = 0, set.iy = 1;
  set.xlo = -3, set.xhi = 5, set.ylo = -1.5, set.yhi = 2;
  set.hmax = fmin(set.xhi - set.xlo, set.yhi - set.ylo) / 50;
  set.h0 = set.hmax / 10;
  set.max_points = 5000;
  double x0[2] = {0.4, 0.4}, *t = malloc((size_t)samples * sizeof *t);
  tally tl = {0, 0, 0};
  sc_curve_stats st;
  sc_curven_output out = {NULL, on_special, &tl};
  for (int i = 0; i < samples; i++) {
    tl = (tally){0, 0, 0};
    double t0 = bench_wall();
    int rc = sc_curven_trace(m, &set, x0, NAN, &out, &st, &msg);
    t[i] = bench_wall() - t0;
    if (rc) {
      fprintf(stderr, "bench_curven: %s\n", msg.text);
      return 1;
    }
  }
  printf("ghenon NS curve (R = 0.5) in alpha [-3, 5], beta [-1.5, 2]:\n");
  printf("  %ld points, %ld codimension-two points (R1..R4 %s), largest "
         "error of R1..R4 %.2g, largest residual %.2g\n",
         st.npoints, st.nspecial, tl.found == 15 ? "all located" : "MISSING",
         tl.err, st.max_residual);
  double med = bench_median(t, samples); /* sorts t */
  printf("  time per curve: median %.3f ms, fastest %.3f ms (%d samples)\n",
         1e3 * med, 1e3 * t[0], samples);
  free(t);
  sc_map_free(m);
  return tl.found == 15 ? 0 : 1;
}
