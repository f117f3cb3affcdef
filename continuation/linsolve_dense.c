/* Dense backend: LU with partial pivoting from LAPACK.  The CSC values are
 * scattered into a full column-major matrix. */
#include <complex.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dense_impl.h"
#include "linsolve_impl.h"

/* LAPACK (Fortran 77 interface, 32-bit integers, hidden string lengths
 * last as gfortran passes them). */
extern void dgetrf_(const int *m, const int *n, double *a, const int *lda,
                    int *ipiv, int *info);
extern void dgetrs_(const char *trans, const int *n, const int *nrhs,
                    const double *a, const int *lda, const int *ipiv,
                    double *b, const int *ldb, int *info, size_t trans_len);
extern void dgecon_(const char *norm, const int *n, const double *a,
                    const int *lda, const double *anorm, double *rcond,
                    double *work, int *iwork, int *info, size_t norm_len);
extern void zgetrf_(const int *m, const int *n, double complex *a,
                    const int *lda, int *ipiv, int *info);
extern void zgetrs_(const char *trans, const int *n, const int *nrhs,
                    const double complex *a, const int *lda, const int *ipiv,
                    double complex *b, const int *ldb, int *info,
                    size_t trans_len);

typedef struct {
  int n;
  double *lu;    /* n x n, column-major: A, then its LU factors */
  int *ipiv;     /* n, 1-based row interchanges */
  double *work;  /* 4 n, dgecon */
  int *iwork;    /* n, dgecon */
  double anorm;  /* ||A||_1 of the factored matrix */
} dense_state;

static void dense_release(void *state) {
  dense_state *d = state;
  free(d->lu);
  free(d->ipiv);
  free(d->work);
  free(d->iwork);
}

static int dense_init(void *state, const sc_pattern *p, sc_msg *msg) {
  dense_state *d = state;
  size_t n = (size_t)p->n;
  d->n = p->n;
  d->lu = malloc(sizeof(double) * n * n);
  d->ipiv = malloc(sizeof(int) * n);
  d->work = malloc(sizeof(double) * 4 * n);
  d->iwork = malloc(sizeof(int) * n);
  if (!d->lu || !d->ipiv || !d->work || !d->iwork) {
    dense_release(d);
    memset(d, 0, sizeof *d);
    return sc_fail(msg, SC_ENOMEM, "sc_linsolve_alloc: dense: out of memory "
                                   "(n = %d)", p->n);
  }
  return SC_OK;
}

static double dense_pivot_ratio(const void *state) {
  const dense_state *d = state;
  double lo = HUGE_VAL, hi = 0;
  for (int k = 0; k < d->n; k++) {
    double u = fabs(d->lu[k + (size_t)d->n * k]);
    lo = fmin(lo, u);
    hi = fmax(hi, u);
  }
  return hi > 0 ? lo / hi : 0;
}

static int dense_factor(void *state, const sc_pattern *p, const double *val,
                        int *refactored, sc_msg *msg) {
  dense_state *d = state;
  int n = d->n, info = 0;
  *refactored = 0;
  memset(d->lu, 0, sizeof(double) * (size_t)n * (size_t)n);
  d->anorm = 0;
  for (int j = 0; j < n; j++) {
    double colsum = 0;
    for (int k = p->colptr[j]; k < p->colptr[j + 1]; k++) {
      d->lu[p->rowind[k] + (size_t)n * j] = val[k];
      colsum += fabs(val[k]);
    }
    d->anorm = fmax(d->anorm, colsum);
  }
  dgetrf_(&n, &n, d->lu, &n, d->ipiv, &info);
  if (info < 0)
    return sc_fail(msg, SC_EINTERNAL, "sc_linsolve_factor: dense: dgetrf "
                                      "argument %d invalid", -info);
  if (info > 0)
    return sc_fail(msg, SC_ESING,
                   "sc_linsolve_factor: dense: exact zero pivot U(%d,%d) "
                   "(n = %d)",
                   info - 1, info - 1, n);
  double ratio = dense_pivot_ratio(d);
  if (ratio <= SC_LINSOLVE_SING_RATIO)
    return sc_fail(msg, SC_ESING,
                   "sc_linsolve_factor: dense: numerically singular (pivot "
                   "ratio %.3g; valid: > %.3g)",
                   ratio, SC_LINSOLVE_SING_RATIO);
  return SC_OK;
}

static int dense_solve(void *state, double *b, sc_msg *msg) {
  dense_state *d = state;
  int one = 1, info = 0;
  dgetrs_("N", &d->n, &one, d->lu, &d->n, d->ipiv, b, &d->n, &info, 1);
  if (info)
    return sc_fail(msg, SC_EINTERNAL, "sc_linsolve_solve: dense: dgetrs "
                                      "info = %d", info);
  return SC_OK;
}

static void dense_det(const void *state, int *sign, double *logabs) {
  const dense_state *d = state;
  int s = 1;
  double l = 0;
  for (int k = 0; k < d->n; k++) {
    double u = d->lu[k + (size_t)d->n * k];
    if (u < 0) s = -s;
    if (d->ipiv[k] != k + 1) s = -s; /* each interchange flips the sign */
    l += log(fabs(u));
  }
  *sign = s;
  *logabs = l;
}

static int dense_rcond(void *state, const sc_pattern *p, double *rcond,
                       sc_msg *msg) {
  dense_state *d = state;
  (void)p;
  int info = 0;
  dgecon_("1", &d->n, d->lu, &d->n, &d->anorm, rcond, d->work, d->iwork,
          &info, 1);
  if (info)
    return sc_fail(msg, SC_EINTERNAL, "sc_linsolve_rcond: dense: dgecon "
                                      "info = %d", info);
  return SC_OK;
}

const sc_linsolve_type sc_linsolve_dense_type = {
    .name = "dense",
    .state_size = sizeof(dense_state),
    .init = dense_init,
    .release = dense_release,
    .factor = dense_factor,
    .solve = dense_solve,
    .det = dense_det,
    .rcond = dense_rcond,
    .pivot_ratio = dense_pivot_ratio,
};

/* Row-major small systems (dense_impl.h) ----------------------------- */

/* The row-major n x n A in place as column major (its transpose). */
static void transpose(size_t n, double *A) {
  for (size_t i = 0; i < n; i++)
    for (size_t j = i + 1; j < n; j++) {
      double t = A[i * n + j];
      A[i * n + j] = A[j * n + i];
      A[j * n + i] = t;
    }
}

static void ztranspose(size_t n, double complex *A) {
  for (size_t i = 0; i < n; i++)
    for (size_t j = i + 1; j < n; j++) {
      double complex t = A[i * n + j];
      A[i * n + j] = A[j * n + i];
      A[j * n + i] = t;
    }
}

int sc_dense_solve(size_t n, double *A, double *b, int *ipiv, double sing) {
  if (n && n > (size_t)INT_MAX / n) return SC_EINVAL;
  int N = (int)n, one = 1, info = 0;
  double amax = 0;
  for (size_t i = 0; i < n * n; i++) amax = fmax(amax, fabs(A[i]));
  transpose(n, A);
  dgetrf_(&N, &N, A, &N, ipiv, &info);
  if (info) return SC_ESING;
  for (size_t k = 0; k < n; k++)
    if (!(fabs(A[k * n + k]) > sing * amax)) return SC_ESING;
  dgetrs_("N", &N, &one, A, &N, ipiv, b, &N, &info, 1);
  return info ? SC_EINTERNAL : SC_OK;
}

int sc_dense_zsolve(size_t n, double complex *A, double complex *b, int *ipiv,
                    double sing) {
  if (n && n > (size_t)INT_MAX / n) return SC_EINVAL;
  int N = (int)n, one = 1, info = 0;
  double amax = 0;
  for (size_t i = 0; i < n * n; i++) amax = fmax(amax, cabs(A[i]));
  ztranspose(n, A);
  zgetrf_(&N, &N, A, &N, ipiv, &info);
  if (info) return SC_ESING;
  for (size_t k = 0; k < n; k++)
    if (!(cabs(A[k * n + k]) > sing * amax)) return SC_ESING;
  zgetrs_("N", &N, &one, A, &N, ipiv, b, &N, &info, 1);
  return info ? SC_EINTERNAL : SC_OK;
}
