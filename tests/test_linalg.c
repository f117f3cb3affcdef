/* The linear-solver backends (dense LAPACK, sparse KLU) through one shared
 * suite: every problem below runs through every backend.
 *
 * Tolerances: for a system with 1-norm condition number kappa, backward
 * stable LU gives a relative forward error of order n kappa eps.  The
 * random systems are diagonally dominant (kappa < 10) and n <= 60, so
 * 1e-12 relative leaves a margin of more than 5 over n kappa eps. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/linalg.h"
#include "test_util.h"

/* A deterministic generator (64-bit LCG, Knuth's MMIX constants), so the
 * systems are the same on every run and platform. */
static unsigned long long rng_state = 0x2385ULL;
static double rnd(void) { /* uniform in [-1, 1) */
  rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(rng_state >> 11) / 4503599627370496.0 - 1.0;
}

static const sc_linsolve_type *backend(int b) {
  return b ? sc_linsolve_klu : sc_linsolve_dense;
}

/* y = A x for CSC A. */
static void csc_mul(int n, const int *cp, const int *ri, const double *v,
                    const double *x, double *y) {
  for (int i = 0; i < n; i++) y[i] = 0;
  for (int j = 0; j < n; j++)
    for (int k = cp[j]; k < cp[j + 1]; k++) y[ri[k]] += v[k] * x[j];
}

static double max_rel_err(int n, const double *x, const double *xref) {
  double e = 0, s = 0;
  for (int i = 0; i < n; i++) {
    e = fmax(e, fabs(x[i] - xref[i]));
    s = fmax(s, fabs(xref[i]));
  }
  return e / s;
}

/* Random sparse pattern with a full diagonal, density about @p dens, and
 * values making it strictly diagonally dominant (kappa_1 < 10). */
static void random_system(int n, double dens, int *cp, int *ri, double *v) {
  int nz = 0;
  cp[0] = 0;
  for (int j = 0; j < n; j++) {
    for (int i = 0; i < n; i++) {
      if (i == j || fabs(rnd()) < dens) {
        ri[nz] = i;
        v[nz] = i == j ? 0 : rnd();
        nz++;
      }
    }
    cp[j + 1] = nz;
  }
  /* Diagonal 2.385 + row sum of |off-diagonal| (row dominance). */
  double *rowsum = calloc((size_t)n, sizeof *rowsum);
  for (int j = 0; j < n; j++)
    for (int k = cp[j]; k < cp[j + 1]; k++)
      if (ri[k] != j) rowsum[ri[k]] += fabs(v[k]);
  for (int j = 0; j < n; j++)
    for (int k = cp[j]; k < cp[j + 1]; k++)
      if (ri[k] == j) v[k] = (j % 2 ? -1 : 1) * (2.385 + rowsum[j]);
  free(rowsum);
}

static void test_random(int b) {
  const int sizes[] = {1, 2, 7, 33, 60};
  const double dens[] = {1.0, 0.3};
  for (size_t is = 0; is < sizeof sizes / sizeof *sizes; is++) {
    for (int id = 0; id < 2; id++) {
      int n = sizes[is];
      int *cp = malloc(sizeof(int) * (size_t)(n + 1));
      int *ri = malloc(sizeof(int) * (size_t)(n * n));
      double *v = malloc(sizeof(double) * (size_t)(n * n));
      double *x = malloc(sizeof(double) * (size_t)n);
      double *xs = malloc(sizeof(double) * (size_t)n);
      random_system(n, dens[id], cp, ri, v);
      for (int i = 0; i < n; i++) x[i] = rnd() * 10;
      csc_mul(n, cp, ri, v, x, xs);
      sc_linsolve *s;
      sc_msg msg = {""};
      int st = sc_linsolve_alloc(backend(b), n, cp, ri, &s, &msg);
      if (st == SC_OK) st = sc_linsolve_factor(s, v, &msg);
      if (st == SC_OK) st = sc_linsolve_solve(s, xs, &msg);
      char what[128];
      snprintf(what, sizeof what, "%s random n = %d density %.1f: status",
               sc_linsolve_type_name(backend(b)), n, dens[id]);
      tu_int(what, st, SC_OK);
      if (st) printf("  %s\n", msg.text);
      snprintf(what, sizeof what, "%s random n = %d density %.1f: rel err",
               sc_linsolve_type_name(backend(b)), n, dens[id]);
      tu_close(what, max_rel_err(n, xs, x), 0, 1e-12);
      sc_linsolve_free(s);
      free(cp), free(ri), free(v), free(x), free(xs);
    }
  }
}

/* The cyclic bidiagonal matrix of multiple shooting for a period-m orbit:
 * A(i,i) = d_i, A(i, i+1 mod m) = e_i.  Expanding along the cycle,
 * det A = prod d_i - (-1)^m prod e_i (the m-cycle has sign (-1)^(m-1)).
 * Built from triplets, with one entry split in two to test duplicates. */
static void test_cyclic(int b) {
  enum { M = 40 };
  int ti[2 * M + 1], tj[2 * M + 1], cp[M + 1], ri[2 * M + 1], map[2 * M + 1];
  double tv[2 * M + 1], v[2 * M + 1], x[M], xs[M];
  double pd = 1, pe = 1;
  int nt = 0;
  for (int i = 0; i < M; i++) {
    double d = 1.3 + 0.01 * i, e = -0.9 - 0.005 * i;
    pd *= d;
    pe *= e;
    ti[nt] = i, tj[nt] = i, tv[nt] = d, nt++;
    ti[nt] = i, tj[nt] = (i + 1) % M, tv[nt] = e, nt++;
  }
  /* Split A(3,3) = tv[6] into two triplets that add up exactly. */
  tv[6] -= 0.25;
  ti[nt] = 3, tj[nt] = 3, tv[nt] = 0.25, nt++;
  int nnz = 0;
  sc_msg msg = {""};
  int st = sc_csc_from_triplets(M, nt, ti, tj, cp, ri, map, &nnz, &msg);
  tu_int("cyclic: triplets to CSC", st, SC_OK);
  tu_int("cyclic: nnz after merging the duplicate", nnz, 2 * M);
  sc_csc_scatter(nt, map, tv, nnz, v);
  for (int i = 0; i < M; i++) x[i] = sin(1.0 + i);
  csc_mul(M, cp, ri, v, x, xs);
  sc_linsolve *s;
  st = sc_linsolve_alloc(backend(b), M, cp, ri, &s, &msg);
  if (!st) st = sc_linsolve_factor(s, v, &msg);
  if (!st) st = sc_linsolve_solve(s, xs, &msg);
  char what[128];
  snprintf(what, sizeof what, "%s cyclic bidiagonal m = %d: status",
           sc_linsolve_type_name(backend(b)), M);
  tu_int(what, st, SC_OK);
  if (st) printf("  %s\n", msg.text);
  /* kappa_1 of this matrix is modest (|e/d| < 0.75 per row, so the cycle
   * product is tiny and A is close to bidiagonal with decaying inverse):
   * 1e-12 as for the random systems. */
  snprintf(what, sizeof what, "%s cyclic: rel err",
           sc_linsolve_type_name(backend(b)));
  tu_close(what, max_rel_err(M, xs, x), 0, 1e-12);
  int sign = 0;
  double logabs = 0;
  double det = pd - (M % 2 ? -1 : 1) * pe;
  st = sc_linsolve_det(s, &sign, &logabs);
  snprintf(what, sizeof what, "%s cyclic: det sign",
           sc_linsolve_type_name(backend(b)));
  tu_int(what, sign, det > 0 ? 1 : -1);
  /* log|det| from 40 pivots: each carries a relative error of a few eps,
   * so the sum is within 40 * 4 eps absolutely; 1e-13 is generous. */
  snprintf(what, sizeof what, "%s cyclic: log|det|",
           sc_linsolve_type_name(backend(b)));
  tu_close(what, logabs, log(fabs(det)), 1e-13);
  sc_linsolve_free(s);
}

/* det and rcond on small matrices with exact answers. */
static void test_det_rcond(int b) {
  const char *name = sc_linsolve_type_name(backend(b));
  char what[128];
  /* diag(1.5, -1e-3, 10) with a pivot order that needs permuting:
   * stored as a permuted diagonal P D, det = sign(P) det D. */
  {
    int cp[] = {0, 1, 2, 3}, ri[] = {1, 2, 0};
    double v[] = {1.5, -1e-3, 10}; /* A(1,0)=1.5, A(2,1)=-1e-3, A(0,2)=10 */
    /* A = [0 0 10; 1.5 0 0; 0 -1e-3 0]: det = 10 * (1.5 * -1e-3) * sign
     * of the cycle (0->2->1->0, a 3-cycle: +1) = -0.015. */
    sc_linsolve *s;
    sc_msg msg = {""};
    int st = sc_linsolve_alloc(backend(b), 3, cp, ri, &s, &msg);
    if (!st) st = sc_linsolve_factor(s, v, &msg);
    snprintf(what, sizeof what, "%s permuted diagonal: factor", name);
    tu_int(what, st, SC_OK);
    int sign = 0;
    double la = 0, rc = 0;
    sc_linsolve_det(s, &sign, &la);
    snprintf(what, sizeof what, "%s permuted diagonal: det sign", name);
    tu_int(what, sign, -1);
    snprintf(what, sizeof what, "%s permuted diagonal: log|det|", name);
    tu_close(what, la, log(0.015), 4 * DBL_EPSILON);
    /* ||A||_1 = 10, ||A^-1||_1 = 1000: rcond = 1e-4.  Both estimators are
     * exact on a permuted diagonal (Hager's method finds the maximal
     * column at once); 1e-12 relative covers the rounding of 1/condest. */
    st = sc_linsolve_rcond(s, &rc, &msg);
    snprintf(what, sizeof what, "%s permuted diagonal: rcond", name);
    tu_int(what, st, SC_OK);
    tu_rel(what, rc, 1e-4, 1e-12);
    sc_linsolve_free(s);
  }
}

/* Singular matrices, provoked on purpose. */
static void test_singular(int b) {
  const char *name = sc_linsolve_type_name(backend(b));
  char what[128];
  sc_msg msg = {""};
  sc_linsolve *s;
  /* Exactly singular: [[1.2, 2.4], [0.6, 1.2]] (rows proportional, with
   * exactly representable ratios, so LU meets an exact zero pivot). */
  double v1[] = {1.2, 0.6, 2.4, 1.2};
  sc_linsolve_alloc_full(backend(b), 2, &s, &msg);
  int st = sc_linsolve_factor(s, v1, &msg);
  snprintf(what, sizeof what, "%s exactly singular 2x2: SC_ESING", name);
  tu_int(what, st, SC_ESING);
  tu_true(strlen(msg.text) > 0, "%s singular message: '%s'", name, msg.text);
  double rhs[2] = {1, 2};
  st = sc_linsolve_solve(s, rhs, &msg);
  snprintf(what, sizeof what, "%s solve after a failed factor: SC_EINVAL",
           name);
  tu_int(what, st, SC_EINVAL);
  sc_linsolve_free(s);

  /* Numerically singular: row 4 = 0.1 row 0 + 0.3 row 1 - 0.7 row 2 with
   * values that are not exactly representable, so rounding leaves a tiny
   * pivot rather than a zero one. */
  enum { N = 5 };
  double a[N * N];
  for (int j = 0; j < N; j++)
    for (int i = 0; i < N - 1; i++) a[i + N * j] = rnd() + (i == j ? 3 : 0);
  for (int j = 0; j < N; j++)
    a[N - 1 + N * j] =
        0.1 * a[0 + N * j] + 0.3 * a[1 + N * j] - 0.7 * a[2 + N * j];
  sc_linsolve_alloc_full(backend(b), N, &s, &msg);
  st = sc_linsolve_factor(s, a, &msg);
  snprintf(what, sizeof what, "%s rank-deficient 5x5: SC_ESING", name);
  tu_int(what, st, SC_ESING);
  printf("  message: %s\n", msg.text);
  sc_linsolve_free(s);

  /* Structurally singular: column 1 empty. */
  int cp[] = {0, 2, 2, 4}, ri[] = {0, 2, 1, 2};
  double v3[] = {1.5, 2.5, 3.5, 4.5};
  st = sc_linsolve_alloc(backend(b), 3, cp, ri, &s, &msg);
  if (!st) st = sc_linsolve_factor(s, v3, &msg);
  snprintf(what, sizeof what, "%s structurally singular: SC_ESING", name);
  tu_int(what, st, SC_ESING);
  printf("  message: %s\n", msg.text);
  sc_linsolve_free(s);
}

/* Refactorization with new values on the same pattern, including values
 * for which the first pivot order breaks down (KLU must fall back to a
 * pivoting factorization). */
static void test_refactor(int b) {
  const char *name = sc_linsolve_type_name(backend(b));
  char what[128];
  sc_msg msg = {""};
  sc_linsolve *s;
  enum { N = 4 };
  sc_linsolve_alloc_full(backend(b), N, &s, &msg);
  double a[N * N], x[N], y[N];
  for (int round = 0; round < 5; round++) {
    for (int j = 0; j < N; j++)
      for (int i = 0; i < N; i++)
        a[i + N * j] = rnd() + (i == j ? 4.0 + round : 0);
    if (round == 4) {
      /* Swap rows 0 and 1 of a dominant matrix: the pivot sequence of the
       * previous rounds now meets a small A(0,0) (set to zero). */
      for (int j = 0; j < N; j++) {
        double t = a[0 + N * j];
        a[0 + N * j] = a[1 + N * j];
        a[1 + N * j] = t;
      }
      a[0] = 0;
    }
    int cp[N + 1], ri[N * N];
    for (int j = 0; j <= N; j++) cp[j] = N * j;
    for (int k = 0; k < N * N; k++) ri[k] = k % N;
    for (int i = 0; i < N; i++) x[i] = 1.0 / (i + 1.7);
    csc_mul(N, cp, ri, a, x, y);
    int st = sc_linsolve_factor(s, a, &msg);
    if (!st) st = sc_linsolve_solve(s, y, &msg);
    snprintf(what, sizeof what, "%s refactor round %d: status", name, round);
    tu_int(what, st, SC_OK);
    snprintf(what, sizeof what, "%s refactor round %d: rel err", name, round);
    /* the swapped matrix is still well conditioned (kappa < 20): 1e-12 */
    tu_close(what, max_rel_err(N, y, x), 0, 1e-12);
  }
  /* Dense always factors afresh: 5 factorizations.  KLU: 1 factorization,
   * 3 refactorizations, then one fallback to a pivoting factorization. */
  snprintf(what, sizeof what, "%s factorizations", name);
  tu_int(what, (long)sc_linsolve_nfactor(s), b ? 2 : 5);
  snprintf(what, sizeof what, "%s refactorizations", name);
  tu_int(what, (long)sc_linsolve_nrefactor(s), b ? 3 : 0);
  snprintf(what, sizeof what, "%s solves", name);
  tu_int(what, (long)sc_linsolve_nsolve(s), 5);
  sc_linsolve_free(s);
}

/* Both backends agree on the determinant of the same random matrix. */
static void test_det_agree(void) {
  enum { N = 25 };
  int cp[N + 1], ri[N * N];
  double v[N * N];
  random_system(N, 0.4, cp, ri, v);
  int sign[2];
  double la[2];
  for (int b = 0; b < 2; b++) {
    sc_linsolve *s;
    sc_msg msg = {""};
    sc_linsolve_alloc(backend(b), N, cp, ri, &s, &msg);
    sc_linsolve_factor(s, v, &msg);
    sc_linsolve_det(s, &sign[b], &la[b]);
    sc_linsolve_free(s);
  }
  tu_int("dense and klu det sign agree", sign[1], sign[0]);
  /* two backward-stable LUs of a kappa < 10 matrix: pivots agree to a few
   * eps each, log|det| to 25 * 8 eps; 1e-12 is generous. */
  tu_close("dense and klu log|det| agree", la[1], la[0], 1e-12);
}

static void test_errors(int b) {
  const char *name = sc_linsolve_type_name(backend(b));
  char what[128];
  sc_msg msg = {""};
  sc_linsolve *s = NULL;
  int cp[] = {0, 2, 3}, ri_bad[] = {1, 0, 1};
  int st = sc_linsolve_alloc(backend(b), 2, cp, ri_bad, &s, &msg);
  snprintf(what, sizeof what, "%s unsorted rows: SC_EINVAL", name);
  tu_int(what, st, SC_EINVAL);
  printf("  message: %s\n", msg.text);
  tu_true(s == NULL, "%s no object on failure", name);
  int ri_out[] = {0, 2, 1};
  st = sc_linsolve_alloc(backend(b), 2, cp, ri_out, &s, &msg);
  snprintf(what, sizeof what, "%s row index out of range: SC_EINVAL", name);
  tu_int(what, st, SC_EINVAL);
  st = sc_linsolve_alloc(backend(b), 0, cp, ri_out, &s, &msg);
  snprintf(what, sizeof what, "%s n = 0: SC_EINVAL", name);
  tu_int(what, st, SC_EINVAL);
  sc_linsolve_alloc_full(backend(b), 2, &s, &msg);
  double v[] = {1, NAN, 0, 1};
  st = sc_linsolve_factor(s, v, &msg);
  snprintf(what, sizeof what, "%s NaN value: SC_ENONFINITE", name);
  tu_int(what, st, SC_ENONFINITE);
  double rhs[2] = {1, 1};
  st = sc_linsolve_solve(s, rhs, &msg);
  snprintf(what, sizeof what, "%s solve without factor: SC_EINVAL", name);
  tu_int(what, st, SC_EINVAL);
  sc_linsolve_free(s);
}

int main(void) {
  tu_true(sc_linsolve_type_find("dense") == sc_linsolve_dense &&
              sc_linsolve_type_find("klu") == sc_linsolve_klu &&
              sc_linsolve_type_find("umfpack") == NULL,
          "backends found by name");
  int ti[] = {2, 0, 2, 1}, tj[] = {0, 0, 0, 2}, cp[4], ri[4], map[4], nnz;
  int st = sc_csc_from_triplets(3, 4, ti, tj, cp, ri, map, &nnz, NULL);
  tu_true(st == SC_OK && nnz == 3 && cp[0] == 0 && cp[1] == 2 &&
              cp[2] == 2 && cp[3] == 3 && ri[0] == 0 && ri[1] == 2 &&
              ri[2] == 1 && map[0] == 1 && map[1] == 0 && map[2] == 1 &&
              map[3] == 2,
          "triplets to CSC: sorted, merged, mapped");
  for (int b = 0; b < 2; b++) {
    printf("--- backend %s\n", sc_linsolve_type_name(backend(b)));
    test_random(b);
    test_cyclic(b);
    test_det_rcond(b);
    test_singular(b);
    test_refactor(b);
    test_errors(b);
  }
  test_det_agree();
  sc_linsolve_free(NULL);
  return tu_finish();
}
