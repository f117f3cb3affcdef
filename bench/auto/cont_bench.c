/* slipcont's side of the comparisons with AUTO-07p on the logistic map
 * (docs/performance.md, "Beside AUTO-07p"): the flips r_1..r_6 of the
 * period-doubling cascade (each period-2^(k-1) branch continued in r from
 * a point of the attractor to its flip) and the fold of the period-3
 * orbit at r = 1 + 2 sqrt 2.
 *
 *   cont_bench once cascade|fold   one computation in a fresh process
 *   cont_bench repeat N            N computations in this process
 *
 * A computation includes what it needs to start: the map, and the
 * attractor iterates that give each branch its first point (AUTO starts
 * from a fixed point it is given and switches branches at the flips).
 * `once` prints the located values with all their digits, their errors
 * against 50-digit references, the points and Newton iterations, and the
 * time inside the process with and without the starts; run_compare.py
 * times the whole process around it.  `repeat` prints the medians over N
 * computations in one process (warm caches). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/continuation.h"
#include "slipcont/map.h"
#include "bench_util.h" /* bench/ */

typedef struct {
  sc_map *m;
  int period;
} ctx_t;

static int fn(double x, const double *p, int order, sc_map1d_jet *j, void *u) {
  ctx_t *c = u;
  if (sc_map_get_param(c->m, 0) != p[0] && sc_map_set_param(c->m, 0, p[0], NULL))
    return 1;
  sc_map_value v;
  if (sc_map_iterate(c->m, x, c->period, order ? SC_EVAL_DERIV : 0, &v, NULL))
    return 1;
  j->g = v.f, j->gx = v.dfdd, j->gp[0] = v.dfdp[0];
  return 0;
}

/* Points and Newton iterations of the last computation. */
static unsigned long npoints, nnewton;

/* Continue the fixed points of f^period from (x0, r0) until the first
 * special point of test `want`; returns its r and adds the time spent to
 * *t. */
static double locate(sc_map *m, int period, double x0, double r0, double h0,
                     double hmax, int dir, size_t want, double *t) {
  ctx_t c = {m, period};
  sc_map1d_system sys = {.fn = fn, .user = &c, .kind = SC_MAP1D_FIXED,
                         .np = 1, .p = {r0}, .ifree = {0, 0}};
  sc_cont_problem pb;
  sc_map1d_problem(&sys, &pb, NULL);
  sc_cont_settings set;
  sc_cont_settings_default(&set);
  set.h0 = h0, set.hmax = hmax, set.direction = dir, set.pmax = 4;
  set.pmin = 3.8 * (dir < 0);
  double t0 = bench_wall();
  sc_branch *b;
  sc_branch_alloc(&pb, &set, NULL, &b, NULL);
  double u0[2] = {x0, r0};
  int st = sc_branch_set(b, u0, NULL);
  while (st == SC_OK || st == SC_CONTINUE ||
         (st == SC_SPECIAL && (size_t)sc_branch_location(b)->test != want))
    st = sc_branch_step(b, NULL);
  double r = st == SC_SPECIAL ? sc_branch_point(b)[1] : NAN;
  npoints += sc_branch_npoints(b);
  nnewton += sc_branch_nnewton(b);
  sc_branch_free(b);
  *t += bench_wall() - t0;
  return r;
}

/* A point of the attractor at r: 20000 iterates from 0.5 (enough next to
 * the flips of the cascade, where the orbit converges slowly). */
static double attractor(sc_map *m, double r) {
  sc_map_set_param(m, 0, r, NULL);
  double x = 0.5;
  sc_map_value v;
  for (int k = 0; k < 20000; k++) sc_map_eval(m, x, 0, &v, NULL), x = v.f;
  return x;
}

static const double ref[6] = {3.0, 3.44948974278317809819728407471,
                              3.5440903595519228536159659866,
                              3.56440726609543259777355758653,
                              3.56875941954382643129821028003,
                              3.5696916098013967142882687063};

/* The cascade: r_1..r_6 into rk[1..6]; *tc the continuation's time, the
 * return value the whole computation's (map, starts, continuation). */
static double cascade(double rk[7], double *tc) {
  double t0 = bench_wall();
  sc_map *m;
  sc_map_alloc("logistic", NULL, &m, NULL);
  *tc = 0;
  npoints = nnewton = 0;
  for (int k = 1; k <= 6; k++) {
    /* the window of branch k, scaled by Feigenbaum's 4.669 */
    double w = k == 1 ? 2 : k == 2 ? 0.45 : (rk[k - 1] - rk[k - 2]) / 4.669;
    double r0 = k == 1 ? 2.8 : rk[k - 1] + 0.5 * w;
    double x0 = attractor(m, r0);
    rk[k] = locate(m, 1 << (k - 1), x0, r0, w / 40, w / 8, 1, 1, tc);
  }
  sc_map_free(m);
  return bench_wall() - t0;
}

static double fold(double *r, double *tc) {
  double t0 = bench_wall();
  sc_map *m;
  sc_map_alloc("logistic", NULL, &m, NULL);
  *tc = 0;
  npoints = nnewton = 0;
  *r = locate(m, 3, attractor(m, 3.832), 3.832, 1e-3, 1e-2, -1, 0, tc);
  sc_map_free(m);
  return bench_wall() - t0;
}

int main(int argc, char **argv) {
  const double rfold = 1 + 2 * sqrt(2);
  double rk[7] = {0}, r, tc, tw;
  if (argc == 3 && !strcmp(argv[1], "once") && !strcmp(argv[2], "cascade")) {
    tw = cascade(rk, &tc);
    for (int k = 1; k <= 6; k++)
      printf("r_%d %.17g err %.3g\n", k, rk[k], fabs(rk[k] - ref[k - 1]));
    printf("points %lu newton %lu\n", npoints, nnewton);
    printf("time_with_starts %.6g time_continuation %.6g\n", tw, tc);
    return 0;
  }
  if (argc == 3 && !strcmp(argv[1], "once") && !strcmp(argv[2], "fold")) {
    tw = fold(&r, &tc);
    printf("fold %.17g err %.3g\n", r, fabs(r - rfold));
    printf("points %lu newton %lu\n", npoints, nnewton);
    printf("time_with_starts %.6g time_continuation %.6g\n", tw, tc);
    return 0;
  }
  long n = argc == 3 && !strcmp(argv[1], "repeat") ? strtol(argv[2], NULL, 10) : 0;
  if (n < 1 || n > 100000) {
    fprintf(stderr, "usage: cont_bench once cascade|fold | cont_bench repeat N (1..100000)\n");
    return 2;
  }
  double *t = malloc(4 * (size_t)n * sizeof *t);
  if (!t) return 1;
  for (long i = 0; i < n; i++) {
    t[i] = cascade(rk, &t[n + i]);
    t[2 * n + i] = fold(&r, &t[3 * n + i]);
  }
  printf("cascade median_with_starts %.6g median_continuation %.6g\n",
         bench_median(t, (int)n), bench_median(t + n, (int)n));
  printf("fold median_with_starts %.6g median_continuation %.6g\n",
         bench_median(t + 2 * n, (int)n), bench_median(t + 3 * n, (int)n));
  free(t);
  return 0;
}
