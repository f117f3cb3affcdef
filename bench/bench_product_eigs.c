/* Multipliers of a product of m random n x n factors: the time of one
 * sc_product_eigs_compute() call (workspace taken once) against forming
 * the product and calling LAPACK's dgeev (workspace taken once too), for
 * n = 2, 4, 16 and m = 1, 16, 256.  Each figure is the median over
 * SAMPLES samples of the mean time of enough calls to fill 20 ms.
 *
 *   bench_product_eigs [SAMPLES]      (default 7)
 *
 * The factors have entries uniform in [-1, 1) / sqrt(n) (norms near 1),
 * so that the formed product stays in range for the naive route; its
 * answers are then what it would give, not checked here (tests/
 * test_product_eigs.c holds the accuracy).  docs/performance.md,
 * "Multipliers". */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "slipcont/linalg.h"

extern void dgeev_(const char *jobvl, const char *jobvr, const int *n,
                   double *a, const int *lda, double *wr, double *wi,
                   double *vl, const int *ldvl, double *vr, const int *ldvr,
                   double *work, const int *lwork, int *info, size_t l1,
                   size_t l2);

#define NMAX 16
/* Calls per sample: enough for 20 ms, so the clock's resolution and the
 * loop's overhead do not count. */
#define SAMPLE_SECONDS 0.02

static unsigned long long rng_state = 0x2385ULL;
static double rnd(void) { /* uniform in [-1, 1) */
  rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(rng_state >> 11) / 4503599627370496.0 - 1.0;
}

typedef struct {
  int n, m;
  const double *const *A;
  sc_product_eigs_work *w;
  double re[NMAX], im[NMAX];
  double P[NMAX * NMAX], C[NMAX * NMAX], work[8 * NMAX];
} job;

static int run_periodic(job *j) {
  return sc_product_eigs_compute(j->w, j->A, j->re, j->im, NULL, NULL, NULL);
}

/* Form P = A[m-1] ... A[0] column major (P^T row major: the same
 * matrix read the other way), then dgeev. */
static int run_naive(job *j) {
  int n = j->n, info = 0, one = 1, lwork = 8 * NMAX;
  for (int i = 0; i < n; i++) /* P = A[0] in column major */
    for (int c = 0; c < n; c++) j->P[i + n * c] = j->A[0][i * n + c];
  for (int k = 1; k < j->m; k++) {
    const double *a = j->A[k];
    for (int c = 0; c < n; c++)
      for (int i = 0; i < n; i++) {
        double s = 0;
        for (int l = 0; l < n; l++) s += a[i * n + l] * j->P[l + n * c];
        j->C[i + n * c] = s;
      }
    memcpy(j->P, j->C, sizeof(double) * (size_t)(n * n));
  }
  dgeev_("N", "N", &n, j->P, &n, j->re, j->im, NULL, &one, NULL, &one,
         j->work, &lwork, &info, 1, 1);
  return info;
}

/* Median over @p samples of the seconds per call of @p fn. */
static double time_calls(int (*fn)(job *), job *j, int samples) {
  long calls = 1;
  double t0 = bench_cpu();
  while (1) { /* calibrate: calls that fill SAMPLE_SECONDS */
    t0 = bench_cpu();
    for (long c = 0; c < calls; c++) fn(j);
    if (bench_cpu() - t0 >= SAMPLE_SECONDS) break;
    calls *= 2;
  }
  double t[64];
  for (int s = 0; s < samples; s++) {
    t0 = bench_cpu();
    for (long c = 0; c < calls; c++) fn(j);
    t[s] = (bench_cpu() - t0) / (double)calls;
  }
  return bench_median(t, samples);
}

int main(int argc, char **argv) {
  int samples = argc > 1 ? atoi(argv[1]) : 7;
  if (samples < 1 || samples > 64) {
    fprintf(stderr, "bench_product_eigs: SAMPLES = '%s' (1 .. 64)\n", argv[1]);
    return 2;
  }
  const int ns[] = {2, 4, 16}, ms[] = {1, 16, 256};
  printf("# median of %d samples, CPU microseconds per call\n", samples);
  printf("%4s %5s %12s %12s %8s\n", "n", "m", "periodic", "naive", "ratio");
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      int n = ns[a], m = ms[b];
      double *store = malloc(sizeof(double) * (size_t)(n * n * m));
      const double **A = malloc(sizeof *A * (size_t)m);
      for (int i = 0; i < n * n * m; i++) store[i] = rnd() / sqrt(n);
      for (int k = 0; k < m; k++) A[k] = store + (size_t)n * n * k;
      job *j = calloc(1, sizeof *j);
      j->n = n;
      j->m = m;
      j->A = A;
      sc_msg msg = {{0}};
      if (sc_product_eigs_work_alloc((size_t)n, (size_t)m, &j->w, &msg) ||
          run_periodic(j) || run_naive(j)) {
        fprintf(stderr, "bench_product_eigs: n = %d, m = %d failed: %s\n", n,
                m, msg.text);
        return 1;
      }
      double tp = time_calls(run_periodic, j, samples);
      double tn = time_calls(run_naive, j, samples);
      printf("%4d %5d %12.2f %12.2f %8.2f\n", n, m, 1e6 * tp, 1e6 * tn,
             tp / tn);
      fflush(stdout);
      sc_product_eigs_work_free(j->w);
      free(j);
      free(A);
      free(store);
    }
  return 0;
}
