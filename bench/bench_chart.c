/* Chart benchmarks (docs/performance.md, "How to measure"):
 *
 *   bench_chart iterates   map iterates per second on one core, on the
 *                          points of fig 5.7(a): bare sc_map_eval loops,
 *                          and the same work through the period detector
 *   bench_chart points N   chart points per second of fig 5.7(a) at N x N
 *                          with 1 and with 2 threads, side by side
 *
 * Each figure is the median of REPEAT runs (default 5, env
 * SLIPCONT_BENCH_REPEAT); every run prints one line so the spread shows.
 * Rates per core are per CPU second of the process (the machine is
 * shared); wall-clock rates are printed beside them. */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "slipcont/chart.h"
#include "bench_util.h"

/* CPU seconds of the whole process (all threads): on a shared machine a
 * rate per CPU second is the rate per core, whatever the load. */
/* Fig 5.7(a): bk2, driver frozen, phi = 1.25, alpha and beta over
 * [1, 20], d0 = 0, transient 1000. */
static sc_chart_spec fig57a(long n) {
  sc_chart_spec s;
  sc_chart_spec_default(&s);
  s.x = "alpha";
  s.x_from = 1;
  s.x_to = 20;
  s.x_steps = n;
  s.y = "beta";
  s.y_from = 1;
  s.y_to = 20;
  s.y_steps = n;
  s.d0 = 0;
  s.transient = 1000;
  return s;
}

static sc_map *fig57a_map(void) {
  sc_msg msg;
  sc_map *m = NULL;
  if (sc_map_alloc("bk2", NULL, &m, &msg) ||
      sc_map_set_option(m, "driver", "frozen", &msg) ||
      sc_map_set_param_by_name(m, "phi", 1.25, &msg)) {
    fprintf(stderr, "bench_chart: %s\n", msg.text);
    exit(1);
  }
  return m;
}

static int repeats(void) {
  const char *r = getenv("SLIPCONT_BENCH_REPEAT");
  int n = r ? atoi(r) : 5;
  return n < 1 ? 1 : n > 50 ? 50 : n;
}

/* Map iterates per second on one core over a G x G sample of fig 5.7(a):
 * (a) 300 bare evaluations from d0 = 0 at each point, (b) the chart's
 * own work at the same points (detector, early stop, parameter setting). */
static int bench_iterates(void) {
  const long G = 24;
  const int R = repeats();
  sc_map *m = fig57a_map();
  sc_chart_spec s = fig57a(G);
  int ia = sc_map_param_index(m, "alpha"), ib = sc_map_param_index(m, "beta");
  double bare[50], chart[50], bare_w[50], chart_w[50];
  sc_chart_point *pt = malloc((size_t)(G * G) * sizeof *pt);
  sc_msg msg;
  for (int r = 0; r < R; r++) {
    long n = 0, undef = 0;
    double t = bench_wall(), c = bench_cpu();
    for (long j = 0; j < G; j++)
      for (long i = 0; i < G; i++) {
        sc_map_set_param(m, (size_t)ib, sc_chart_y(&s, j), NULL);
        sc_map_set_param(m, (size_t)ia, sc_chart_x(&s, i), NULL);
        double d = 0;
        sc_map_value v;
        for (int k = 0; k < 300; k++, n++) {
          if (sc_map_eval(m, d, SC_EVAL_VALUE, &v, &msg)) {
            undef++;
            break;
          }
          d = v.f;
        }
      }
    bare[r] = (double)n / (bench_cpu() - c);
    bare_w[r] = (double)n / (bench_wall() - t);
    t = bench_wall();
    c = bench_cpu();
    if (sc_chart_rows(m, &s, 0, G, 1, 1, NULL, NULL, pt, &msg)) {
      fprintf(stderr, "bench_chart: %s\n", msg.text);
      return 1;
    }
    double el = bench_wall() - t, ec = bench_cpu() - c, it = 0;
    for (long k = 0; k < G * G; k++) it += pt[k].iterations;
    chart[r] = it / ec;
    chart_w[r] = it / el;
    printf("run %d: bare eval %.4g iterates/CPU-s (%.4g /s wall; %ld "
           "iterates, %ld undefined); chart %.4g iterates/CPU-s (%.4g /s "
           "wall; %.0f iterates, %.1f a point)\n",
           r + 1, bare[r], bare_w[r], n, undef, chart[r], chart_w[r], it,
           it / (double)(G * G));
  }
  printf("median map iterates per CPU second (one core): bare %.4g, "
         "through the chart %.4g; wall: %.4g, %.4g (%d runs, %ld x %ld "
         "points of fig 5.7(a))\n",
         bench_median(bare, R), bench_median(chart, R), bench_median(bare_w, R),
         bench_median(chart_w, R), R, G, G);
  free(pt);
  sc_map_free(m);
  return 0;
}

/* Points per second of fig 5.7(a) at N x N, 1 and 2 threads alternating
 * within each repeat so that both see the same load. */
static int bench_points(long N) {
  const int R = repeats();
  sc_map *m = fig57a_map();
  sc_chart_spec s = fig57a(N);
  sc_chart_point *pt = malloc((size_t)(N * N) * sizeof *pt);
  double rate[2][50], ratio[50], cpurate[2][50];
  sc_msg msg;
  for (int r = 0; r < R; r++) {
    double t1 = 0;
    for (int th = 1; th <= 2; th++) {
      double t = bench_wall(), c = bench_cpu();
      if (sc_chart_rows(m, &s, 0, N, 1, th, NULL, NULL, pt, &msg)) {
        fprintf(stderr, "bench_chart: %s\n", msg.text);
        return 1;
      }
      double el = bench_wall() - t, ec = bench_cpu() - c, it = 0;
      for (long k = 0; k < N * N; k++) it += pt[k].iterations;
      rate[th - 1][r] = (double)(N * N) / el;
      cpurate[th - 1][r] = (double)(N * N) / ec;
      if (th == 1) t1 = el;
      else ratio[r] = t1 / el;
      printf("run %d, %d thread(s): %.3f s wall, %.3f CPU-s, %.4g points/s, "
             "%.4g iterates/s, %.4g points/CPU-s\n",
             r + 1, th, el, ec, (double)(N * N) / el, it / el,
             (double)(N * N) / ec);
    }
  }
  printf("median chart points per second, fig 5.7(a) %ld x %ld: 1 thread "
         "%.4g, 2 threads %.4g, speed-up %.3f (%d runs); per CPU second: "
         "%.4g and %.4g\n",
         N, N, bench_median(rate[0], R), bench_median(rate[1], R), bench_median(ratio, R), R,
         bench_median(cpurate[0], R), bench_median(cpurate[1], R));
  free(pt);
  sc_map_free(m);
  return 0;
}

int main(int argc, char **argv) {
  if (argc >= 2 && strcmp(argv[1], "iterates") == 0) return bench_iterates();
  if (argc >= 3 && strcmp(argv[1], "points") == 0)
    return bench_points(atol(argv[2]));
  fprintf(stderr, "usage: bench_chart iterates | bench_chart points N\n");
  return 2;
}
