/* Event-map iterates per CPU second on one core, on the workloads of
 * docs/performance.md, "Where it stands":
 *
 *   bench_events [repeats] [iterates] [figure: 0 both, 1, 2]
 *
 *   fig 5.6  bk2, alpha 2.9, beta 1, phi 1.25, V 0.018, driver moving,
 *            the orbit from d0 = 0.02 (chaotic)
 *   fig 5.8  bk2, alpha 3.5, beta 2.5, V 0.025, driver frozen, from 0.02
 *
 * Each repeat iterates the map `iterates` times (default 200000) along
 * the orbit with values only (as sweeps and charts do); the median rate
 * over `repeats` (default 5) is printed, with the orbit's last point and
 * a checksum so that two builds can be compared on the same work.
 *
 * Both orbits are chaotic: a build whose map differs in the last bits
 * follows another orbit after a few hundred iterates, and times other
 * work.  With SLIPCONT_BENCH_POINTS=DIR each repeat instead evaluates the
 * map at the points of one stored orbit, DIR/fig56.points or
 * DIR/fig58.points (raw doubles): a build that finds the file missing
 * writes its own orbit's points there first, and every build run after
 * it evaluates the same points (the checksum is then the sum of f). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "slipcont/map.h"
#include "bench_util.h"

/* The n points of the orbit from d into p: read from the file `path`, or,
 * where it does not exist, computed with this build's map and written
 * there (through a temporary name, so that no half-written file is
 * left).  Returns 0, or 1 with a message. */
static int orbit_points(sc_map *m, const char *path, double d, long n,
                        double *p) {
  sc_msg msg;
  FILE *f = fopen(path, "rb");
  if (f) {
    size_t got = fread(p, sizeof *p, (size_t)n, f);
    fclose(f);
    if (got == (size_t)n) return 0;
    fprintf(stderr, "bench_events: %s holds %zu points, %ld needed\n", path,
            got, n);
    return 1;
  }
  for (long k = 0; k < n; k++) {
    sc_map_value r;
    p[k] = d;
    if (sc_map_eval(m, d, 0, &r, &msg)) {
      fprintf(stderr, "bench_events: %s\n", msg.text);
      return 1;
    }
    d = r.f;
  }
  char tmp[4200]; /* path is at most 4095 characters (main) */
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  f = fopen(tmp, "wb");
  int bad = !f || fwrite(p, sizeof *p, (size_t)n, f) != (size_t)n;
  if (f && fclose(f)) bad = 1;
  if (bad || rename(tmp, path)) {
    fprintf(stderr, "bench_events: cannot write %s\n", path);
    remove(tmp);
    return 1;
  }
  return 0;
}

int main(int argc, char **argv) {
  int repeats = argc > 1 ? atoi(argv[1]) : 5;
  long n = argc > 2 ? atol(argv[2]) : 200000;
  int only = argc > 3 ? atoi(argv[3]) : 0;
  if (repeats < 1 || repeats > 101 || n < 1 || only < 0 || only > 2) {
    fprintf(stderr, "usage: bench_events [repeats 1..101] [iterates >= 1] "
                    "[figure 0 (both), 1 or 2]\n");
    return 1;
  }
  const struct {
    const char *name, *file;
    double alpha, beta, v;
    const char *driver;
  } figs[] = {
      {"fig 5.6 (alpha 2.9, beta 1, V 0.018, moving, d0 0.02)", "fig56", 2.9, 1,
       0.018, "moving"},
      {"fig 5.8 (alpha 3.5, beta 2.5, V 0.025, frozen, d0 0.02)", "fig58", 3.5,
       2.5, 0.025, "frozen"},
  };
  const char *pdir = getenv("SLIPCONT_BENCH_POINTS");
  double *pts = NULL;
  if (pdir && !(pts = malloc((size_t)n * sizeof *pts))) {
    fprintf(stderr, "bench_events: no memory for %ld points\n", n);
    return 1;
  }
  for (size_t fi = 0; fi < sizeof figs / sizeof figs[0]; fi++) {
    if (only && (size_t)only != fi + 1) continue;
    sc_msg msg;
    sc_map *m;
    sc_accuracy acc;
    sc_accuracy_preset(&acc, "default", NULL);
    if (sc_map_alloc("bk2", &acc, &m, &msg) ||
        sc_map_set_param_by_name(m, "alpha", figs[fi].alpha, &msg) ||
        sc_map_set_param_by_name(m, "beta", figs[fi].beta, &msg) ||
        sc_map_set_param_by_name(m, "v", figs[fi].v, &msg) ||
        sc_map_set_option(m, "driver", figs[fi].driver, &msg)) {
      fprintf(stderr, "bench_events: %s\n", msg.text);
      return 1;
    }
    double rates[101], d = 0.02, sum = 0;
    if (pts) {
      char path[4096];
      if (snprintf(path, sizeof path, "%s/%s.points", pdir, figs[fi].file) >=
          (int)sizeof path) {
        fprintf(stderr, "bench_events: SLIPCONT_BENCH_POINTS is too long\n");
        return 1;
      }
      if (orbit_points(m, path, d, n, pts)) return 1;
    }
    for (int rep = 0; rep < repeats; rep++) {
      sc_map_value r;
      d = 0.02, sum = 0;
      double t0 = bench_cpu();
      for (long k = 0; k < n; k++) {
        if (sc_map_eval(m, pts ? pts[k] : d, 0, &r, &msg)) {
          fprintf(stderr, "bench_events: %s\n", msg.text);
          return 1;
        }
        d = r.f;
        sum += d;
      }
      rates[rep] = (double)n / (bench_cpu() - t0);
    }
    qsort(rates, (size_t)repeats, sizeof rates[0], bench_cmp_double);
    printf("%s: %.4g iterates/CPU-s (median of %d; min %.4g, max %.4g); "
           "%s%ld = %.17g, sum %.17g\n",
           figs[fi].name, rates[repeats / 2], repeats, rates[0],
           rates[repeats - 1], pts ? "stored points, f_" : "d_", n, d, sum);
    sc_map_free(m);
  }
  free(pts);
  return 0;
}
