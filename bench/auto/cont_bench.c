/* Times slipcont on the AUTO-07p comparison tasks: the logistic flips
 * r_1..r_6 (each period-2^(k-1) branch continued in r from a point on the
 * attractor until its flip) and the period-3 fold.  Prints the located
 * values, their errors and the median time of the continuation calls
 * (attractor iteration excluded) over 200 repetitions. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "slipcont/continuation.h"
#include "slipcont/map.h"
#include "bench_util.h" /* bench/ */

typedef struct { sc_map *m; int period; } ctx_t;

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

/* Points and Newton iterations of the last repetition. */
static unsigned long npoints, nnewton;

/* Continue the fixed points of f^period from (x0, r0) until the first
 * special point of test `want`; returns its r and adds the time. */
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

static double attractor(sc_map *m, double r) {
  sc_map_set_param(m, 0, r, NULL);
  double x = 0.5;
  sc_map_value v;
  for (int k = 0; k < 20000; k++) sc_map_eval(m, x, 0, &v, NULL), x = v.f;
  return x;
}

int main(void) {
  const double ref[6] = {3.0, 3.44948974278317809819728407471,
                         3.5440903595519228536159659866,
                         3.56440726609543259777355758653,
                         3.56875941954382643129821028003,
                         3.5696916098013967142882687063};
  enum { REP = 200 };
  static double tc[REP], tf[REP];
  double rk[7] = {0}, rfold = 0;
  sc_map *m;
  sc_map_alloc("logistic", NULL, &m, NULL);
  for (int rep = 0; rep < REP; rep++) {
    tc[rep] = 0;
    npoints = nnewton = 0;
    for (int k = 1; k <= 6; k++) {
      double w = k == 1 ? 2 : k == 2 ? 0.45 : (rk[k - 1] - rk[k - 2]) / 4.669;
      double r0 = k == 1 ? 2.8 : rk[k - 1] + 0.5 * w;
      double x0 = attractor(m, r0);
      rk[k] = locate(m, 1 << (k - 1), x0, r0, w / 40, w / 8, 1, 1, &tc[rep]);
    }
    unsigned long pc = npoints, nc = nnewton;
    if (rep == REP - 1)
      printf("cascade: %lu points, %lu Newton iterations\n", pc, nc);
    tf[rep] = 0;
    npoints = nnewton = 0;
    rfold = locate(m, 3, attractor(m, 3.832), 3.832, 1e-3, 1e-2, -1, 0, &tf[rep]);
  }
  printf("fold: %lu points, %lu Newton iterations\n", npoints, nnewton);
  for (int k = 1; k <= 6; k++)
    printf("r_%d slipcont %.17g err %.3g\n", k, rk[k], fabs(rk[k] - ref[k - 1]));
  printf("fold slipcont %.17g err %.3g\n", rfold, fabs(rfold - (1 + 2 * sqrt(2))));
  qsort(tc, REP, sizeof *tc, bench_cmp_double);
  qsort(tf, REP, sizeof *tf, bench_cmp_double);
  printf("cascade (6 flips): median %.3g s, min %.3g s over %d runs\n",
         tc[REP / 2], tc[0], REP);
  printf("period-3 fold: median %.3g s, min %.3g s over %d runs\n",
         tf[REP / 2], tf[0], REP);
  printf("map evaluations (all runs): %lu\n", sc_map_nevals(m));
  sc_map_free(m);
  return 0;
}
