/* Where an iterate's time goes (docs/performance.md, "The profile"): the event
 * map's root searches, recorded on a workload and replayed alone.
 *
 *   bench_searches [chart | fig56 | fig58] [N]
 *
 *   chart  fig 5.7(a): bk2 frozen, phi 1.25, alpha and beta on a 24 x 24
 *          grid over [1, 20], N = 300 iterates from d0 = 0 at each point
 *          (bench_chart's bare loop)
 *   fig56  bk2 moving, alpha 2.9, beta 1, V 0.018: N = 100000 iterates of
 *          the chaotic orbit from d0 = 0.02
 *   fig58  bk2 frozen, alpha 3.5, beta 2.5: N = 100000 from d0 = 0.02
 *
 * The workload is run three ways, each REPEAT times (env
 * SLIPCONT_BENCH_REPEAT, default 5), medians quoted:
 *   1. the map as it is (value-only evaluations of the model, without
 *      sc_map_eval's wrapper), per iterate;
 *   2. once with the model's two searches wrapped, which copy every call's
 *      input (and, for the pair search of a slip of both blocks, the
 *      limit the model returned for its later guard) into memory;
 *   3. the recorded calls replayed alone, pair searches and single-guard
 *      searches apart, each checked to return what it returned inside the
 *      map (bit for bit: the searches have no state).
 * The replays give each search's cost in its workload's own mix of
 * inputs; what the searches do not take of the iterate's time is the
 * rest of the map (flows, guards, events, ties, windows).  Rates are per
 * CPU second of the process.  The recording also counts the steps a pair
 * search takes (sc_root.steps: grid steps and adaptive intervals, the
 * larger of its two guards' counts), a measure of the march's work that
 * does not depend on the machine's speed. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "models/bk2_impl.h"

/* One call of each search, as the model made it. */
typedef struct {
  sc_guard g[2];
  double tmax, atol, rtol, lim, t[2];
  int skip[2], found[2];
} pair_call;

typedef struct {
  sc_guard g;
  double tmax, atol, rtol, t;
  int skip, found;
} single_call;

/* The recording: growing arrays (NULL until the first call). */
static pair_call *pairs;
static single_call *singles;
static long npair, nsingle, cappair, capsingle;
/* Steps the pair searches took (the larger of the two guards' counts: the
 * march's steps while both are live, and the later guard's alone). */
static long pair_steps;

static void *grow(void *p, long *cap, size_t size) {
  *cap = *cap ? 2 * *cap : 4096;
  void *q = realloc(p, (size_t)*cap * size);
  if (!q) {
    fprintf(stderr, "bench_searches: out of memory recording searches\n");
    exit(1);
  }
  return q;
}

static int record_single(const sc_guard *g, double tmax, int skip,
                         double atol, double rtol, sc_root *out) {
  int st = sc_guard_first_root(g, tmax, skip, atol, rtol, out);
  if (nsingle == capsingle)
    singles = grow(singles, &capsingle, sizeof *singles);
  singles[nsingle++] = (single_call){*g,   tmax,       atol, rtol,
                                     out->t, skip, out->found};
  return st;
}

/* The model's limit for the later guard of a pair, wrapped: the value it
 * returned is kept with the call (it depends on the earlier root only,
 * which the replay finds again). */
typedef struct {
  sc_guard_limit_fn limit;
  void *ctx;
  double value;
} limit_wrap;

static double record_limit(void *ctx, const sc_guard *g, const sc_root *r) {
  limit_wrap *w = ctx;
  w->value = w->limit(w->ctx, g, r);
  return w->value;
}

static int record_pair(const sc_guard *g, double tmax, const int *skip,
                       double atol, double rtol, sc_guard_limit_fn limit,
                       void *ctx, sc_root *out) {
  limit_wrap w = {limit, ctx, NAN};
  int st = sc_guard_first_root_pair(g, tmax, skip, atol, rtol, record_limit,
                                    &w, out);
  if (npair == cappair) pairs = grow(pairs, &cappair, sizeof *pairs);
  pair_call *c = &pairs[npair++];
  c->g[0] = g[0], c->g[1] = g[1];
  c->tmax = tmax, c->atol = atol, c->rtol = rtol, c->lim = w.value;
  for (int i = 0; i < 2; i++)
    c->skip[i] = skip[i], c->t[i] = out[i].t, c->found[i] = out[i].found;
  pair_steps += out[0].steps > out[1].steps ? out[0].steps : out[1].steps;
  return st;
}

/* The replay's limit: the recorded one. */
static double replay_limit(void *ctx, const sc_guard *g, const sc_root *r) {
  (void)g, (void)r;
  return *(const double *)ctx;
}

/* A workload: parameter sets and, for each, an orbit of n iterates. */
typedef struct {
  const char *name, *what;
  int frozen;
  double v, d0;
  long grid, n; /* grid x grid parameter sets (1: a single orbit) */
  double alpha, beta;
} workload;

static void set_params(const workload *w, long i, long j, double p[5]) {
  p[0] = w->alpha, p[1] = w->beta, p[2] = 1.25, p[3] = w->v, p[4] = 1;
  if (w->grid > 1) {
    p[0] = 1 + 19 * (double)i / (double)(w->grid - 1);
    p[1] = 1 + 19 * (double)j / (double)(w->grid - 1);
  }
}

/* The model at grid point (i, j), or exit with the model's message. */
static void setup(bk2_inst *b, const workload *w, long i, long j) {
  sc_accuracy acc;
  sc_msg msg;
  double p[5];
  int opt[3] = {w->frozen, 0, 0};
  set_params(w, i, j, p);
  sc_accuracy_preset(&acc, "default", NULL);
  if (sc_model_bk2.setup(b, p, opt, &acc, &msg)) {
    fprintf(stderr, "bench_searches: %s\n", msg.text);
    exit(1);
  }
}

/* Runs the workload once; returns the iterates evaluated. */
static long run(bk2_inst *b, const workload *w, int recording) {
  long n = 0;
  for (long j = 0; j < w->grid; j++)
    for (long i = 0; i < w->grid; i++) {
      setup(b, w, i, j);
      if (recording) b->search = record_single, b->search_pair = record_pair;
      double d = w->d0;
      for (long k = 0; k < w->n; k++, n++) {
        sc_map_value v;
        sc_msg msg;
        v.itinerary[0] = '\0';
        if (sc_model_bk2.eval(b, d, SC_EVAL_VALUE, &v, &msg)) break;
        d = v.f;
      }
    }
  return n;
}

/* Replays the pair calls; returns the number that did not give back what
 * they gave inside the map. */
static long replay_pairs(void) {
  long bad = 0;
  for (long k = 0; k < npair; k++) {
    const pair_call *c = &pairs[k];
    sc_root out[2];
    double lim = c->lim;
    sc_guard_first_root_pair(c->g, c->tmax, c->skip, c->atol, c->rtol,
                             replay_limit, &lim, out);
    for (int i = 0; i < 2; i++)
      bad += out[i].found != c->found[i] || out[i].t != c->t[i];
  }
  return bad;
}

static long replay_singles(void) {
  long bad = 0;
  for (long k = 0; k < nsingle; k++) {
    const single_call *c = &singles[k];
    sc_root out;
    sc_guard_first_root(&c->g, c->tmax, c->skip, c->atol, c->rtol, &out);
    bad += out.found != c->found || out.t != c->t;
  }
  return bad;
}

static int repeats(void) {
  const char *r = getenv("SLIPCONT_BENCH_REPEAT");
  int n = r ? atoi(r) : 5;
  return n < 1 ? 1 : n > 50 ? 50 : n;
}

int main(int argc, char **argv) {
  static const workload ws[] = {
      {"chart", "fig 5.7(a), 24 x 24 points, iterates from d0 = 0 each", 1,
       0.025, 0, 24, 300, 0, 0},
      {"fig56", "fig 5.6, driver moving, the orbit from d0 = 0.02", 0, 0.018,
       0.02, 1, 100000, 2.9, 1},
      {"fig58", "fig 5.8, driver frozen, the orbit from d0 = 0.02", 1, 0.025,
       0.02, 1, 100000, 3.5, 2.5},
  };
  const char *name = argc > 1 ? argv[1] : "chart";
  const workload *w = NULL;
  for (size_t k = 0; k < sizeof ws / sizeof ws[0]; k++)
    if (strcmp(name, ws[k].name) == 0) w = &ws[k];
  if (!w || argc > 3) {
    fprintf(stderr, "usage: bench_searches [chart | fig56 | fig58] [N]\n");
    return 2;
  }
  workload wl = *w;
  if (argc > 2) {
    char *end;
    long n = strtol(argv[2], &end, 10);
    if (*end || n < 1 || n > 100000000) {
      fprintf(stderr,
              "bench_searches: N = '%s': want a count of iterates, 1 .. "
              "1e8\n",
              argv[2]);
      return 2;
    }
    wl.n = n;
  }
  const int R = repeats();
  bk2_inst *b = calloc(1, sizeof *b);
  if (!b) return 1;
  double map[50], tp[50], ts[50];
  long iters = 0;
  for (int r = 0; r < R; r++) {
    double c = bench_cpu();
    iters = run(b, &wl, 0);
    map[r] = (bench_cpu() - c) / (double)iters * 1e9;
  }
  run(b, &wl, 1);
  long badp = 0, bads = 0;
  for (int r = 0; r < R; r++) {
    double c = bench_cpu();
    badp += replay_pairs();
    tp[r] = (bench_cpu() - c) / (double)(npair ? npair : 1) * 1e9;
    c = bench_cpu();
    bads += replay_singles();
    ts[r] = (bench_cpu() - c) / (double)(nsingle ? nsingle : 1) * 1e9;
  }
  if (b->flows) b->flows->release(b);
  free(b);
  double it = bench_median(map, R), p = bench_median(tp, R);
  double s = bench_median(ts, R);
  double pp = (double)npair / (double)iters, sp = (double)nsingle / (double)iters;
  printf("bench_searches %s: %s; %ld iterates, medians of %d runs, CPU "
         "time\n",
         wl.name, wl.what, iters, R);
  printf("  the map:                      %7.1f ns an iterate (%.3g "
         "iterates/s)\n",
         it, 1e9 / it);
  printf("  pair searches (both blocks):  %5.3f an iterate x %6.1f ns = "
         "%6.1f ns (%4.1f%%)\n",
         pp, p, pp * p, 100 * pp * p / it);
  printf("  (steps a pair search:         %5.2f)\n",
         (double)pair_steps / (double)(npair ? npair : 1));
  printf("  single-guard searches:        %5.3f an iterate x %6.1f ns = "
         "%6.1f ns (%4.1f%%)\n",
         sp, s, sp * s, 100 * sp * s / it);
  printf("  the rest of the map:                                  %6.1f ns "
         "(%4.1f%%)\n",
         it - pp * p - sp * s, 100 * (it - pp * p - sp * s) / it);
  free(pairs);
  free(singles);
  if (badp || bads) {
    fprintf(stderr,
            "bench_searches: %ld pair and %ld single replays returned "
            "other roots than inside the map\n",
            badp, bads);
    return 1;
  }
  return 0;
}
