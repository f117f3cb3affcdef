/* The chain's event map (docs/chain.md) in iterates per CPU second on one
 * core, on the workloads of docs/performance.md, "The chain":
 *
 *   bench_chain [repeats] [iterates] [workload: 0 all, 1, 2, 3]
 *
 *   1  two blocks: bk2 and chain (blocks = 2) on the same points, the
 *      orbits of fig 5.6 (alpha 2.9, beta 1, V 0.018, driver moving) and
 *      fig 5.8 (alpha 3.5, beta 2.5, V 0.025, frozen) from d0 = 0.02,
 *      computed with bk2; the two maps alternate within each repeat
 *   2  three blocks, open, phi 1.25, in chaos (no value repeats within
 *      1e-8 over the orbit's last 1000 iterates): driver frozen, V 0.025,
 *      beta2 1, beta3 3 (the chart of examples/chain3-chart.ini) at
 *      alpha 4.3; driver moving, alpha 2.9, V 0.019, beta2 = beta3 = 1
 *      (fig 5.6's parameters, docs/chain.md, "Speed"); from d = (0.1, 0.2)
 *   3  100 blocks, open, driver frozen, alpha 3, V 0.01, beta2..beta5
 *      1.3, 0.8, 1.1, 0.9 (the others 1), from a seeded random d (a
 *      moving driver falls into a slip cycle there)
 *
 * Every workload first collects `iterates` points (default 20000) of its
 * orbit (workload 3: 1/40 of them), then each repeat (default 5)
 * evaluates the map at those points, values only (as charts do); the
 * median rate is printed with the slip phases per iterate and a checksum
 * (the sum of f's first component) for comparing builds on the same
 * points. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/map.h"
#include "bench_util.h"

typedef struct {
  const char *model;
  int blocks;
  const char *driver;
  const char *par[6];
  double val[6];
} workload;

static sc_map *make_map(const workload *w, sc_msg *msg) {
  sc_accuracy acc;
  sc_map *m = NULL;
  sc_accuracy_preset(&acc, "default", NULL);
  if (sc_map_alloc(w->model, &acc, &m, msg)) return NULL;
  char nb[16];
  snprintf(nb, sizeof nb, "%d", w->blocks);
  if ((w->blocks && sc_map_set_option(m, "blocks", nb, msg)) ||
      sc_map_set_option(m, "driver", w->driver, msg)) {
    sc_map_free(m);
    return NULL;
  }
  for (int i = 0; i < 6 && w->par[i]; i++)
    if (sc_map_set_param_by_name(m, w->par[i], w->val[i], msg)) {
      sc_map_free(m);
      return NULL;
    }
  return m;
}

/* n points of m's orbit from x0 into pts (n * dim). */
static int orbit(sc_map *m, const double *x0, long n, double *pts,
                 sc_mapn_value *v, sc_msg *msg) {
  size_t dim = sc_map_dim(m);
  memcpy(pts, x0, dim * sizeof *pts);
  for (long k = 0; k + 1 < n; k++) {
    if (sc_map_eval_n(m, pts + k * dim, 0, v, msg)) return 1;
    memcpy(pts + (k + 1) * dim, v->f, dim * sizeof *pts);
  }
  return 0;
}

/* One timed pass of m over the n points: rate; phases and checksum out. */
static double pass(sc_map *m, const double *pts, long n, sc_mapn_value *v,
                   double *phases, double *sum, sc_msg *msg) {
  size_t dim = sc_map_dim(m);
  long ph = 0;
  double s = 0, t0 = bench_cpu();
  for (long k = 0; k < n; k++) {
    if (sc_map_eval_n(m, pts + k * dim, 0, v, msg)) return -1;
    ph += v->nphases;
    s += v->f[0];
  }
  double rate = (double)n / (bench_cpu() - t0);
  *phases = (double)ph / (double)n, *sum = s;
  return rate;
}

/* Time the maps ms[0..nm) alternately on the same n points, `repeats`
 * times; print each map's median rate (and the ratio of the first's
 * to the others', median over the repeats). */
static int run(const char *title, sc_map **ms, const char **names, int nm,
               const double *pts, long n, int repeats) {
  sc_msg msg;
  double rate[4][101], ratio[4][101], ph[4], sum[4];
  sc_mapn_value *v[4] = {0};
  for (int i = 0; i < nm; i++)
    if (sc_mapn_value_alloc(ms[i], SC_EVAL_VALUE, &v[i], &msg)) goto fail;
  for (int r = 0; r < repeats; r++)
    for (int i = 0; i < nm; i++) {
      rate[i][r] = pass(ms[i], pts, n, v[i], &ph[i], &sum[i], &msg);
      if (rate[i][r] < 0) goto fail;
      if (i) ratio[i][r] = rate[0][r] / rate[i][r];
    }
  printf("%s (%ld points, median of %d)\n", title, n, repeats);
  for (int i = 0; i < nm; i++) {
    double med = bench_median(rate[i], repeats);
    printf("  %-6s %.4g iterates/CPU-s, %.4g phases/CPU-s (%.2f phases an "
           "iterate), sum %.17g",
           names[i], med, med * ph[i], ph[i], sum[i]);
    if (i) printf("; %s/%s %.3f", names[0], names[i],
                  bench_median(ratio[i], repeats));
    printf("\n");
  }
  for (int i = 0; i < nm; i++) sc_mapn_value_free(v[i]);
  return 0;
fail:
  fprintf(stderr, "bench_chain: %s: %s\n", title, msg.text);
  for (int i = 0; i < nm; i++) sc_mapn_value_free(v[i]);
  return 1;
}

/* A workload's maps, its orbit from x0 (by the first map), the run. */
static int workload_run(const char *title, const workload *w, int nm,
                        const double *x0, long n, int repeats) {
  sc_msg msg;
  sc_map *ms[4] = {0};
  const char *names[4];
  sc_mapn_value *v = NULL;
  double *pts = NULL;
  int bad = 1;
  for (int i = 0; i < nm; i++) {
    if (!(ms[i] = make_map(&w[i], &msg))) goto out;
    names[i] = w[i].model;
  }
  size_t dim = sc_map_dim(ms[0]);
  pts = malloc((size_t)n * dim * sizeof *pts);
  if (!pts || sc_mapn_value_alloc(ms[0], SC_EVAL_VALUE, &v, &msg)) goto out;
  if (orbit(ms[0], x0, n, pts, v, &msg)) goto out;
  bad = run(title, ms, names, nm, pts, n, repeats);
  if (bad) msg.text[0] = '\0';
out:
  if (bad && msg.text[0]) fprintf(stderr, "bench_chain: %s\n", msg.text);
  sc_mapn_value_free(v);
  free(pts);
  for (int i = 0; i < nm; i++) sc_map_free(ms[i]);
  return bad;
}

int main(int argc, char **argv) {
  int repeats = argc > 1 ? atoi(argv[1]) : 5;
  long n = argc > 2 ? atol(argv[2]) : 20000;
  int only = argc > 3 ? atoi(argv[3]) : 0;
  if (repeats < 1 || repeats > 101 || n < 40 || only < 0 || only > 3) {
    fprintf(stderr, "usage: bench_chain [repeats 1..101] [iterates >= 40] "
                    "[workload 0 (all), 1, 2 or 3]\n");
    return 1;
  }
  int bad = 0;
  if (!only || only == 1) {
    const workload f56[2] = {
        {"bk2", 0, "moving", {"alpha", "beta", "v"}, {2.9, 1, 0.018}},
        {"chain", 2, "moving", {"alpha", "beta2", "v"}, {2.9, 1, 0.018}}};
    const workload f58[2] = {
        {"bk2", 0, "frozen", {"alpha", "beta", "v"}, {3.5, 2.5, 0.025}},
        {"chain", 2, "frozen", {"alpha", "beta2", "v"}, {3.5, 2.5, 0.025}}};
    double x0 = 0.02;
    bad |= workload_run("two blocks, fig 5.6 (bk2's orbit)", f56, 2, &x0, n,
                        repeats);
    bad |= workload_run("two blocks, fig 5.8 (bk2's orbit)", f58, 2, &x0, n,
                        repeats);
  }
  if (!only || only == 2) {
    const workload fr = {"chain", 3, "frozen",
                         {"alpha", "beta2", "beta3", "v", "phi"},
                         {4.3, 1, 3, 0.025, 1.25}};
    const workload mv = {"chain", 3, "moving",
                         {"alpha", "beta2", "beta3", "v", "phi"},
                         {2.9, 1, 1, 0.019, 1.25}};
    double x0[2] = {0.1, 0.2};
    bad |= workload_run("three blocks, frozen, alpha 4.3, beta3 3", &fr, 1, x0,
                        n, repeats);
    bad |= workload_run("three blocks, moving, alpha 2.9, V 0.019",
                        &mv, 1, x0, n, repeats);
  }
  if (!only || only == 3) {
    const workload h = {"chain", 100, "frozen",
                        {"alpha", "v", "beta2", "beta3", "beta4", "beta5"},
                        {3, 0.01, 1.3, 0.8, 1.1, 0.9}};
    double x0[99];
    unsigned long s = 12345;
    for (int i = 0; i < 99; i++) {
      s = s * 6364136223846793005UL + 1442695040888963407UL;
      x0[i] = 0.02 * ((double)(s >> 11) / 9007199254740992.0 - 0.5);
    }
    bad |= workload_run("100 blocks, open, frozen, alpha 3", &h, 1, x0,
                        n / 40 > 1 ? n / 40 : 2, repeats);
  }
  return bad;
}
