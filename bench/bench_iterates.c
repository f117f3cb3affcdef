/* Long runs of the event map (docs/accuracy.md, "The extremes": 1e8
 * iterates): no NaN, no hang, no silently wrong itinerary.
 *
 *   bench_iterates [iterates per workload] [sample every] [workload]
 *
 * (defaults 1e8, 2000, all).  Workloads: the fig 5.6 chaotic orbit
 * (alpha 2.9, beta 1, phi 1.25, V 0.018, driver moving) followed from
 * d0 = 0.02, and five parameter sets at the ends of the ranges, where
 * orbit segments of SEGMENT iterates start from d* + u (1 + beta) /
 * (1 + alpha), u uniform in [-1, 1] (so that the iterates cover the
 * slips' scale rather than sit on one attracting orbit).  Each iterate is
 * value-only (the path sweeps and charts take).  Counted:
 *  - f not finite (must be 0);
 *  - refusals (a negative status with a message), by reason; the orbit
 *    restarts from a new d;
 *  - the slowest single iterate (a hang would show here; the run has no
 *    time limit of its own);
 *  - every `sample`-th iterate is evaluated again with derivatives and
 *    itinerary, in double and in quad: same status, same itinerary, f
 *    (also the value-only f) within the default preset's promise
 *    64 eps S (1 + |f'|) n (S = 1 + beta + (1 + alpha)|d|, n slip phases)
 *    against quad; where they differ, the sample is "on a border" if the
 *    double evaluation reports a border (d*, a threshold gap, a grazing)
 *    within 1024 eps (S + V) of zero, and "wrong" otherwise (must be 0).
 * The random numbers are a fixed xorshift stream: every run does the
 * same work. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "slipcont/bk2.h"
#include "slipcont/map.h"
#include "bench_util.h"

#define SEGMENT 10000
#define NREASON 16

static unsigned long long rng = 88172645463325252ULL;
static double uniform(void) { /* in [-1, 1) */
  rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
  return (double)(rng >> 11) * 0x1p-52 - 1;
}

typedef struct {
  const char *name;
  double alpha, beta, phi, v;
  const char *driver;
  int follow; /* 1: one orbit from d0 = 0.02; 0: random segments */
} workload;

static sc_map *make(const workload *w, int precision) {
  sc_accuracy acc;
  sc_msg msg = {""};
  sc_map *m = NULL;
  sc_accuracy_preset(&acc, "default", NULL);
  acc.precision = precision;
  if (sc_map_alloc("bk2", &acc, &m, &msg) ||
      sc_map_set_param_by_name(m, "alpha", w->alpha, &msg) ||
      sc_map_set_param_by_name(m, "beta", w->beta, &msg) ||
      sc_map_set_param_by_name(m, "phi", w->phi, &msg) ||
      sc_map_set_param_by_name(m, "v", w->v, &msg) ||
      sc_map_set_option(m, "driver", w->driver, &msg)) {
    fprintf(stderr, "bench_iterates: %s\n", msg.text);
    sc_map_free(m);
    return NULL;
  }
  return m;
}

/* The distance of d to the nearest border the double path reports. */
static double border_dist(sc_map *m, double d) {
  sc_border bl[256];
  sc_border_list l = {bl, 256, 0};
  sc_map_value v;
  double r = HUGE_VAL;
  if (sc_map_eval_ex(m, d, SC_EVAL_VALUE, NULL, NULL, &l, &v, NULL)) return r;
  for (size_t i = 0; i < l.n && i < l.cap; i++) {
    if (bl[i].kind == SC_BORDER_CROSSING &&
        strncmp(bl[i].name, "threshold gap", 13) != 0)
      continue;
    r = fmin(r, fabs(bl[i].value));
  }
  return r;
}

/* A refusal's reason: its message with the numbers taken out. */
static void reason_of(const char *msg, char *out, size_t n) {
  size_t j = 0;
  for (size_t i = 0; msg[i] && j + 1 < n; i++) {
    char c = msg[i];
    if ((c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' ||
        c == 'e')
      if (j && out[j - 1] == '#') continue;
    if ((c >= '0' && c <= '9')) c = '#';
    out[j++] = c;
  }
  out[j] = '\0';
}

static int run(const workload *w, long n, long every) {
  sc_map *md = make(w, SC_PRECISION_DOUBLE), *mq = make(w, SC_PRECISION_QUAD);
  if (!md || !mq) return 1;
  double ds = sc_bk2_dstar(w->alpha, w->beta);
  double scale = (1 + w->beta) / (1 + w->alpha);
  char reasons[NREASON][128];
  long rcount[NREASON] = {0}, nrefused = 0, nnan = 0, nsample = 0,
       nsame = 0, nborder = 0, nwrong = 0, nvalue_off = 0, nq_refused = 0;
  int nreasons = 0;
  double worst_f = 0, slowest = 0, d_slowest = 0;
  double d = w->follow ? 0.02 : ds + uniform() * scale;
  double t0 = bench_wall();
  for (long k = 0; k < n; k++) {
    if (!w->follow && k % SEGMENT == 0) d = ds + uniform() * scale;
    sc_map_value v;
    sc_msg msg = {""};
    double t = bench_wall();
    int st = sc_map_eval(md, d, SC_EVAL_VALUE, &v, &msg);
    t = bench_wall() - t;
    if (t > slowest) slowest = t, d_slowest = d;
    if (!st && !isfinite(v.f)) {
      nnan++;
      st = -1;
      snprintf(msg.text, sizeof msg.text, "f not finite: %g", v.f);
    }
    if (every > 0 && k % every == 0) {
      /* the sample: double with derivatives and itinerary, and quad */
      sc_map_value a, q;
      sc_msg m1 = {""}, m2 = {""};
      unsigned fl = SC_EVAL_DERIV | SC_EVAL_ITINERARY;
      int s1 = sc_map_eval(md, d, fl, &a, &m1), s2 = sc_map_eval(mq, d, fl, &q, &m2);
      double S = 1 + w->beta + (1 + w->alpha) * fabs(d);
      int agree = (s1 == 0) == (s2 == 0) && (s1 != 0 || strcmp(a.itinerary, q.itinerary) == 0);
      double err = 0;
      if (agree && !s1) {
        double tol = 64 * DBL_EPSILON * S * (1 + fabs(q.dfdd)) * fmax(1, q.nphases);
        err = fmax(fabs(a.f - q.f), st ? 0 : fabs(v.f - q.f)) / tol;
        if (!st && fabs(v.f - q.f) > tol) nvalue_off++;
        worst_f = fmax(worst_f, err);
        agree = err <= 1;
      }
      nsample++;
      if (s2) nq_refused++;
      if (agree)
        nsame++;
      else if (border_dist(md, d) <= 1024 * DBL_EPSILON * (S + w->v))
        nborder++;
      else {
        nwrong++;
        printf("  WRONG d = %.17g: double status %d f %.17g itinerary %s "
               "(%s); quad status %d f %.17g itinerary %s (%s); err %.3g "
               "promise\n",
               d, s1, a.f, s1 ? "-" : a.itinerary, m1.text, s2, q.f,
               s2 ? "-" : q.itinerary, m2.text, err);
      }
    }
    if (st) {
      nrefused++;
      char r[128];
      reason_of(msg.text, r, sizeof r);
      int i = 0;
      while (i < nreasons && strcmp(reasons[i], r) != 0) i++;
      if (i == nreasons && nreasons < NREASON) strcpy(reasons[nreasons++], r);
      if (i < NREASON) rcount[i]++;
      d = ds + uniform() * scale;
      continue;
    }
    d = v.f;
  }
  double el = bench_wall() - t0;
  printf("%s: %ld iterates in %.1f s (%.3g it/s, samples included); f not "
         "finite %ld; slowest iterate %.3g s (d = %.17g); %ld refused\n",
         w->name, n, el, (double)n / el, nnan, slowest, d_slowest, nrefused);
  for (int i = 0; i < nreasons; i++)
    printf("  refused %ld times: %s\n", rcount[i], reasons[i]);
  printf("  %ld samples against quad: %ld agree (f within %.3g of the "
         "promise at worst), %ld on a border, %ld wrong; quad refused %ld; "
         "value-only f outside the promise %ld\n",
         nsample, nsame, worst_f, nborder, nwrong, nq_refused, nvalue_off);
  fflush(stdout);
  sc_map_free(md);
  sc_map_free(mq);
  return nwrong || nnan;
}

int main(int argc, char **argv) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  long n = argc > 1 ? (long)atof(argv[1]) : 100000000L;
  long every = argc > 2 ? atol(argv[2]) : 2000;
  int only = argc > 3 ? atoi(argv[3]) : -1;
  static const workload w[] = {
      {"fig 5.6 (alpha 2.9, beta 1, phi 1.25, V 0.018, moving, d0 0.02)", 2.9,
       1, 1.25, 0.018, "moving", 1},
      {"alpha 1e3, beta 1e2, phi 1e3, V 1e2, moving", 1e3, 1e2, 1e3, 1e2,
       "moving", 0},
      {"alpha 1e-3, beta 1e-2, phi 1e3, V 1e2, moving", 1e-3, 1e-2, 1e3, 1e2,
       "moving", 0},
      {"alpha 1e-3, beta 10, phi 1 + 1e-6, V 0.025, moving", 1e-3, 10,
       1 + 1e-6, 0.025, "moving", 0},
      {"alpha 1, beta 1e2, phi 1e3, V 1e-12, moving", 1, 1e2, 1e3, 1e-12,
       "moving", 0},
      {"alpha 1e-3, beta 1e-2, phi 1 + 1e-6, frozen", 1e-3, 1e-2, 1 + 1e-6, 0,
       "frozen", 0},
  };
  int nw = (int)(sizeof w / sizeof w[0]);
  if (n < 1 || every < 0 || only < -1 || only >= nw) {
    fprintf(stderr, "usage: bench_iterates [iterates >= 1] [sample every "
                    ">= 0 (0: none)] [workload 0..%d]\n",
            nw - 1);
    return 1;
  }
  int bad = 0;
  for (int i = 0; i < nw; i++)
    if (only < 0 || only == i) bad |= run(&w[i], n, every);
  return bad;
}
