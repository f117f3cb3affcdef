/* The codimension-two test functions along fold, flip and Neimark-Sacker
 * curves of n-dimensional maps (normal_form.h; docs/maps.md, "Curves and
 * codimension two"): normal-form coefficients, and the other multipliers
 * as the roots of the characteristic polynomial divided by the curve's
 * critical factor. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "nf_impl.h"

typedef struct {
  const char *label;
  size_t min_n;
} test_info;

static const test_info fold_tests[] = {
    {"CP", 1}, {"R1", 2}, {"LPPD", 2}, {"LPNS", 3}};
static const test_info flip_tests[] = {
    {"GPD", 1}, {"R2", 2}, {"LPPD", 2}, {"PDNS", 3}};
static const test_info ns_tests[] = {{"R1", 2},   {"R2", 2},   {"R3", 2},
                                     {"R4", 2},   {"CH", 2},   {"LPNS", 3},
                                     {"PDNS", 3}, {"NSNS", 4}};

static const test_info *tests_of(sc_nf_curve kind, size_t *nt) {
  switch (kind) {
  case SC_NF_FOLD: *nt = 4; return fold_tests;
  case SC_NF_FLIP: *nt = 4; return flip_tests;
  case SC_NF_NS: *nt = 8; return ns_tests;
  }
  *nt = 0;
  return NULL;
}

size_t sc_nf_curve_ntest(sc_nf_curve kind) {
  size_t nt;
  tests_of(kind, &nt);
  return nt;
}

const char *sc_nf_curve_label(sc_nf_curve kind, size_t k, size_t *min_n) {
  size_t nt;
  const test_info *t = tests_of(kind, &nt);
  if (k >= nt) return NULL;
  if (min_n) *min_n = t[k].min_n;
  return t[k].label;
}

/* The monic characteristic polynomial sum_k c[k] lambda^k (c[n] = 1) from
 * the eigenvalues: its coefficients are symmetric functions of them, the
 * same for any order and smooth where the eigenvalues are not. */
static void char_poly(const nf_eig_t *e, double *c) {
  size_t n = e->n;
  double complex a[NF_N + 1] = {1};
  for (size_t j = 0; j < n; j++) { /* a *= (lambda - mu_j) */
    double complex mu = e->wr[j] + I * e->wi[j];
    for (size_t k = j + 1; k > 0; k--) a[k] = a[k - 1] - mu * a[k];
    a[0] = -mu * a[0];
  }
  for (size_t k = 0; k <= n; k++) c[k] = creal(a[k]);
}

/* r = p / (lambda - root): degree n - 1, the remainder dropped. */
static size_t deflate1(const double *c, size_t n, double root, double *r) {
  r[n - 1] = c[n];
  for (size_t k = n - 1; k >= 1; k--) r[k - 1] = c[k] + root * r[k];
  return n - 1;
}

/* r = p / (lambda^2 - 2 kappa lambda + 1): degree n - 2. */
static size_t deflate2(const double *c, size_t n, double kappa, double *r) {
  double s = 2 * kappa;
  for (size_t k = n; k >= 2; k--) {
    double r1 = k - 1 <= n - 2 ? r[k - 1] : 0, r2 = k <= n - 2 ? r[k] : 0;
    r[k - 2] = c[k] + s * r1 - r2;
  }
  return n - 2;
}

static double poly_at(const double *r, size_t m, double x) {
  double v = r[m];
  for (size_t k = m; k-- > 0;) v = v * x + r[k];
  return v;
}

/* The bialternate product of an (n - 1) x (n - 1) matrix: 105 x 105 at
 * n = 16 (88 kB on the stack). */
#define NF_KMAX ((NF_N - 1) * (NF_N - 2) / 2)

/* det(C (.) C - I) for the companion matrix C of the monic r (degree m):
 * the second compound's entries are C's 2 x 2 minors, its eigenvalues
 * the products nu_i nu_j (i < j) of r's roots. */
static double bialt(const double *r, size_t m) {
  if (m < 2) return NAN;
  double C[NF_N * NF_N] = {0};
  for (size_t i = 1; i < m; i++) C[i * m + i - 1] = 1; /* subdiagonal */
  for (size_t i = 0; i < m; i++) C[i * m + m - 1] = -r[i];
  size_t K = m * (m - 1) / 2;
  double M[NF_KMAX * NF_KMAX];
  size_t row = 0;
  for (size_t p = 1; p < m; p++)
    for (size_t q = 0; q < p; q++, row++) {
      size_t col = 0;
      for (size_t s = 1; s < m; s++)
        for (size_t t = 0; t < s; t++, col++)
          M[row * K + col] = C[p * m + s] * C[q * m + t] -
                             C[p * m + t] * C[q * m + s] - (row == col);
    }
  /* the determinant by elimination with partial pivoting */
  double det = 1;
  for (size_t c = 0; c < K; c++) {
    size_t pv = c;
    for (size_t i = c + 1; i < K; i++)
      if (fabs(M[i * K + c]) > fabs(M[pv * K + c])) pv = i;
    if (M[pv * K + c] == 0) return 0;
    if (pv != c) {
      det = -det;
      for (size_t j = 0; j < K; j++) {
        double t = M[c * K + j];
        M[c * K + j] = M[pv * K + j], M[pv * K + j] = t;
      }
    }
    det *= M[c * K + c];
    for (size_t i = c + 1; i < K; i++) {
      double f = M[i * K + c] / M[c * K + c];
      for (size_t j = c; j < K; j++) M[i * K + j] -= f * M[c * K + j];
    }
  }
  return det;
}

/* The coefficient tests: CP, GPD, CH (NaN where it cannot be had). */
static double coef_test(sc_nf_curve kind, const sc_nf_jet *g, double kappa,
                        const double *qref, double *qout) {
  sc_nf nf;
  sc_msg m;
  if (kind == SC_NF_FOLD) {
    if (sc_nf_fold(g, qref, &nf, &m)) return NAN;
    if (qout)
      for (size_t i = 0; i < g->n; i++) qout[i] = nf.q[i];
    return nf.coef;
  }
  if (kind == SC_NF_FLIP) return sc_nf_flip(g, &nf, &m) ? NAN : nf.coef;
  if (!(fabs(kappa) < 1)) return NAN; /* a neutral saddle: no CH */
  double mu[2] = {kappa, sqrt(1 - kappa * kappa)};
  return sc_nf_ns(g, mu, &nf, &m) ? NAN : nf.coef;
}

int sc_nf_curve_tests(sc_nf_curve kind, const sc_nf_jet *g, double kappa,
                      const double *qref, double *psi, double *qout,
                      sc_msg *msg) {
  size_t nt;
  const test_info *ti = tests_of(kind, &nt);
  if (!ti)
    return sc_fail(msg, SC_EINVAL, "sc_nf_curve_tests: unknown curve %d",
                   (int)kind);
  int st = nf_check(g, kind != SC_NF_FOLD, "sc_nf_curve_tests", msg);
  if (st) return st;
  size_t n = g->n;
  nf_eig_t e;
  if ((st = nf_eig(n, g->A, 0, &e, msg))) return st;
  double c[NF_N + 1], r[NF_N + 1];
  char_poly(&e, c);
  for (size_t k = 0; k < nt; k++) psi[k] = NAN;
  if (kind == SC_NF_NS) {
    psi[0] = kappa - 1, psi[1] = kappa + 1;
    psi[2] = kappa + 0.5, psi[3] = kappa;
    psi[4] = coef_test(kind, g, kappa, NULL, NULL);
    if (n >= 3) {
      size_t m = deflate2(c, n, kappa, r);
      psi[5] = poly_at(r, m, 1), psi[6] = poly_at(r, m, -1);
      if (n >= 4) psi[7] = bialt(r, m);
    }
    return SC_OK;
  }
  psi[0] = coef_test(kind, g, kappa, qref, qout);
  if (n >= 2) {
    double root = kind == SC_NF_FOLD ? 1 : -1;
    size_t m = deflate1(c, n, root, r);
    psi[1] = poly_at(r, m, root);  /* R1 on a fold, R2 on a flip */
    psi[2] = poly_at(r, m, -root); /* LPPD */
    if (n >= 3) psi[3] = bialt(r, m);
  }
  return SC_OK;
}
