/* Single against multiple shooting for long periods of an n-dimensional
 * map: the Henon map at a = 1.058, b = 0.3, where the attractor is a
 * stable orbit of period 128 (the doubling cascade's period-128 stage)
 * and the orbits of periods 8 and 32 born before it are saddles; and,
 * for contrast, at a = 1.4 (chaos), where the orbits of period m are
 * saddles with multipliers near e^(0.42 m) (1e23 at m = 128).  For
 * m = 8, 32, 128, from STARTS points of the attractor (transient 100000,
 * every 7th iterate; in the window moved by up to 0.01 in each
 * component, since there they lie on the period-128 orbit already), each
 * method solves f^m(x) = x:
 *
 *   bench_shooting_n [STARTS]      (default 20)
 *
 * Printed per method and m: starts converged, mean Newton iterations,
 * CPU time per solve (median over the starts of the mean of enough
 * solves to fill 20 ms), the worst certificate of the orbits returned
 * (recomputed the same way for both methods: max over k of
 * ||f(x_k) - x_(k+1 mod m)||_inf), the leading multiplier, and the
 * largest distance between the orbits the two methods return from the
 * same start (when both converge to the same orbit).  Multiple shooting
 * uses KLU for m > 16 (sc_shootn_alloc()'s choice) and, for comparison,
 * the dense backend at every m.  docs/performance.md, "Shooting in n
 * dimensions". */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "slipcont/shooting.h"

#define MAXSTARTS 1000
#define MAXM 128
#define SAMPLE_SECONDS 0.02

/* max_k ||f(x_k) - x_(k+1 mod m)||_inf of the orbit o (m points). */
static double certificate(sc_map *map, sc_mapn_value *v, const double *o,
                          int m) {
  double r = 0;
  for (int k = 0; k < m; k++) {
    sc_map_eval_n(map, o + 2 * k, SC_EVAL_VALUE, v, NULL);
    const double *nx = o + 2 * ((k + 1) % m);
    r = fmax(r, fmax(fabs(v->f[0] - nx[0]), fabs(v->f[1] - nx[1])));
  }
  return r;
}

/* Distance between orbits a and b (m points), the best rotation. */
static double orbit_dist(const double *a, const double *b, int m) {
  double best = HUGE_VAL;
  for (int r = 0; r < m; r++) {
    double d = 0;
    for (int k = 0; k < 2 * m; k++)
      d = fmax(d, fabs(a[k] - b[(2 * r + k) % (2 * m)]));
    best = fmin(best, d);
  }
  return best;
}

typedef struct {
  const char *name;
  sc_shoot_method meth;
  const sc_linsolve_type *ls;
} method;

/* One parameter value: every method at every m from the same starts. */
static int scenario(sc_map *map, sc_mapn_value *v, double a, double jitter,
                    int nstarts, const char *what) {
  sc_msg msg;
  if (sc_map_set_param_by_name(map, "a", a, &msg)) {
    fprintf(stderr, "bench_shooting_n: %s\n", msg.text);
    return 1;
  }
  static double starts[MAXSTARTS][2];
  unsigned long long rng = 0x2385ULL;
  double x[2] = {0.1, 0.1};
  for (long i = 0; i < 100000 + 7L * nstarts; i++) {
    sc_map_eval_n(map, x, SC_EVAL_VALUE, v, NULL);
    memcpy(x, v->f, sizeof x);
    long j = i - 100000;
    if (j < 0 || j % 7 != 0) continue;
    for (int c = 0; c < 2; c++) { /* uniform in [-jitter, jitter) */
      rng = rng * 6364136223846793005ULL + 1442695040888963407ULL;
      double u = (double)(rng >> 11) / 4503599627370496.0 - 1.0;
      starts[j / 7][c] = x[c] + jitter * u;
    }
  }
  const method methods[3] = {{"single", SC_SHOOT_SINGLE, NULL},
                             {"multiple (auto)", SC_SHOOT_MULTIPLE, NULL},
                             {"multiple (dense)", SC_SHOOT_MULTIPLE,
                              sc_linsolve_dense}};
  static const int ms[3] = {8, 32, 128};
  static double orbits[3][MAXSTARTS][2 * MAXM];
  static int ok[3][MAXSTARTS];
  double times[MAXSTARTS];
  printf("\nhenon a = %g, b = 0.3 (%s), %d starts\n", a, what, nstarts);
  printf("%-4s %-17s %-10s %-10s %-13s %-11s %-22s %s\n", "m", "method",
         "converged", "mean iter", "time/solve", "worst cert",
         "leading multiplier", "max dist to single");
  for (int im = 0; im < 3; im++) {
    int m = ms[im];
    for (int k = 0; k < 3; k++) {
      sc_shootn *s;
      if (sc_shootn_alloc(map, m, methods[k].meth, methods[k].ls, &s, &msg)) {
        fprintf(stderr, "bench_shooting_n: %s\n", msg.text);
        return 1;
      }
      int nok = 0;
      long iters = 0;
      double worst = 0, lead = NAN, dist = 0;
      for (int i = 0; i < nstarts; i++) {
        sc_shootn_result res;
        int calls = 0;
        double t0 = bench_cpu(), t;
        do {
          ok[k][i] = sc_shootn_solve(s, starts[i], &res, NULL) == SC_OK;
          calls++;
          t = bench_cpu() - t0;
        } while (t < SAMPLE_SECONDS);
        times[i] = t / calls;
        if (!ok[k][i]) continue;
        nok++;
        iters += res.iterations;
        memcpy(orbits[k][i], sc_shootn_orbit(s),
               2 * (size_t)m * sizeof(double));
        worst = fmax(worst, certificate(map, v, orbits[k][i], m));
        if (isnan(lead)) lead = res.multiplier;
        if (k > 0 && ok[0][i]) {
          double d = orbit_dist(orbits[0][i], orbits[k][i], m);
          if (d < 1e-6) dist = fmax(dist, d); /* the same orbit */
        }
      }
      printf("%-4d %-17s %3d/%-6d %-10.2f %-13.3g %-11.2g %-22.6g %s%.2g\n",
             m, methods[k].name, nok, nstarts,
             nok ? (double)iters / nok : 0.0, bench_median(times, nstarts),
             worst, lead, k ? "" : "-", k ? dist : 0.0);
      sc_shootn_free(s);
    }
  }
  return 0;
}

int main(int argc, char **argv) {
  int nstarts = argc > 1 ? atoi(argv[1]) : 20;
  if (nstarts < 1 || nstarts > MAXSTARTS) {
    fprintf(stderr, "bench_shooting_n: STARTS = %s (valid: 1..%d)\n",
            argv[1], MAXSTARTS);
    return 2;
  }
  sc_map *map;
  sc_msg msg;
  sc_mapn_value *v;
  if (sc_map_alloc("henon", NULL, &map, &msg) ||
      sc_map_set_param_by_name(map, "b", 0.3, &msg) ||
      sc_mapn_value_alloc(map, SC_EVAL_VALUE, &v, &msg)) {
    fprintf(stderr, "bench_shooting_n: %s\n", msg.text);
    return 1;
  }
  int st = scenario(map, v, 1.058, 0.01, nstarts,
                    "period-128 window: a stable period-128 orbit");
  if (!st) st = scenario(map, v, 1.4, 0, nstarts, "chaos, for contrast");
  sc_mapn_value_free(v);
  sc_map_free(map);
  return st;
}
