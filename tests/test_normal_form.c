/* Normal forms of n-dimensional maps (continuation/normal_form.c): maps
 * written in normal form with known coefficients, with couplings to
 * stable directions whose centre-manifold contribution is known in
 * closed form, the same maps in random linear coordinates, Kuznetsov's
 * two-dimensional formula for the Neimark-Sacker coefficient with every
 * quadratic term, the one-dimensional formulas, and the refusals. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "slipcont/curve_system.h"
#include "slipcont/normal_form.h"
#include "test_util.h"

#define N SC_NF_MAXDIM

/* The jets below are exact polynomials evaluated by polarization, so the
 * coefficients carry rounding only: a few hundred ulps after the
 * eigenvectors (dgeev) and a coordinate change of condition ~10. */
static const double TOL = 1e-12;

/* A test map x -> A x + Q(x) + K(x): Q quadratic, K cubic, homogeneous. */
typedef struct {
  size_t n;
  double A[N * N];
  void (*Q)(const double *x, double *out, const void *c);
  void (*K)(const double *x, double *out, const void *c);
  const void *c;
} poly_map;

typedef struct {
  double A[N * N], H[N * N * N], T[N * N * N * N];
  sc_nf_jet jet;
} jet_store;

static void add3(size_t n, const double *a, const double *b, const double *c,
                 double *out) {
  for (size_t i = 0; i < n; i++) out[i] = a[i] + (b ? b[i] : 0) + (c ? c[i] : 0);
}

/* H_ijk = Q_i(e_j + e_k) - Q_i(e_j) - Q_i(e_k); T by the polarization
 * C(u, v, w) = K(u+v+w) - K(u+v) - K(u+w) - K(v+w) + K(u) + K(v) + K(w),
 * exact for homogeneous forms with Q = B(x, x) / 2, K = C(x, x, x) / 6. */
static void jet_of(const poly_map *m, jet_store *s) {
  size_t n = m->n;
  double e[3][N], x[N], r[8][N];
  memcpy(s->A, m->A, n * n * sizeof(double));
  for (size_t j = 0; j < n; j++)
    for (size_t k = 0; k < n; k++) {
      memset(e, 0, sizeof e);
      e[0][j] = 1, e[1][k] = 1;
      add3(n, e[0], e[1], NULL, x);
      m->Q(x, r[0], m->c), m->Q(e[0], r[1], m->c), m->Q(e[1], r[2], m->c);
      for (size_t i = 0; i < n; i++)
        s->H[(i * n + j) * n + k] = r[0][i] - r[1][i] - r[2][i];
      for (size_t l = 0; l < n; l++) {
        memset(e[2], 0, sizeof e[2]);
        e[2][l] = 1;
        add3(n, e[0], e[1], e[2], x), m->K(x, r[0], m->c);
        add3(n, e[0], e[1], NULL, x), m->K(x, r[1], m->c);
        add3(n, e[0], e[2], NULL, x), m->K(x, r[2], m->c);
        add3(n, e[1], e[2], NULL, x), m->K(x, r[3], m->c);
        m->K(e[0], r[4], m->c), m->K(e[1], r[5], m->c), m->K(e[2], r[6], m->c);
        for (size_t i = 0; i < n; i++)
          s->T[((i * n + j) * n + k) * n + l] = r[0][i] - r[1][i] - r[2][i] -
                                                 r[3][i] + r[4][i] + r[5][i] +
                                                 r[6][i];
      }
    }
  s->jet = (sc_nf_jet){n, s->A, s->H, s->T};
}

/* ---- random linear coordinates: g' = M g M^(-1) ----------------------- */

static unsigned long long rng = 0x2385u;
static double urand(void) { /* in [-1, 1) */
  rng = rng * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(rng >> 11) / 4503599627370496.0 - 1;
}

/* Gauss-Jordan inverse of the n x n M (well conditioned by construction). */
static void invert(size_t n, const double *M, double *Mi) {
  double a[N * 2 * N];
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < 2 * n; j++)
      a[i * 2 * n + j] = j < n ? M[i * n + j] : (j - n == i);
  for (size_t c = 0; c < n; c++) {
    size_t p = c;
    for (size_t r = c + 1; r < n; r++)
      if (fabs(a[r * 2 * n + c]) > fabs(a[p * 2 * n + c])) p = r;
    for (size_t j = 0; j < 2 * n; j++) {
      double t = a[c * 2 * n + j];
      a[c * 2 * n + j] = a[p * 2 * n + j], a[p * 2 * n + j] = t;
    }
    double d = a[c * 2 * n + c];
    for (size_t j = 0; j < 2 * n; j++) a[c * 2 * n + j] /= d;
    for (size_t r = 0; r < n; r++) {
      if (r == c) continue;
      double f = a[r * 2 * n + c];
      for (size_t j = 0; j < 2 * n; j++) a[r * 2 * n + j] -= f * a[c * 2 * n + j];
    }
  }
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) Mi[i * n + j] = a[i * 2 * n + n + j];
}

/* M = I + 0.4 R (R uniform in [-1, 1)): condition of a few units. */
static void random_matrix(size_t n, double *M) {
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) M[i * n + j] = (i == j) + 0.4 * urand();
}

/* Orthogonal M: Gram-Schmidt on a random matrix. */
static void random_orthogonal(size_t n, double *M) {
  random_matrix(n, M);
  for (size_t i = 0; i < n; i++) {
    for (size_t k = 0; k < i; k++) {
      double s = 0;
      for (size_t j = 0; j < n; j++) s += M[i * n + j] * M[k * n + j];
      for (size_t j = 0; j < n; j++) M[i * n + j] -= s * M[k * n + j];
    }
    double s = 0;
    for (size_t j = 0; j < n; j++) s += M[i * n + j] * M[i * n + j];
    for (size_t j = 0; j < n; j++) M[i * n + j] /= sqrt(s);
  }
}

/* The jet of x' = M x: A' = M A Mi, H'_i(u, v) = M H(Mi u, Mi v), ... */
static void transform(const jet_store *s, const double *M, jet_store *t) {
  size_t n = s->jet.n;
  double Mi[N * N];
  invert(n, M, Mi);
  memset(t, 0, sizeof *t);
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      for (size_t a = 0; a < n; a++)
        for (size_t b = 0; b < n; b++)
          t->A[i * n + j] += M[i * n + a] * s->A[a * n + b] * Mi[b * n + j];
  for (size_t i = 0; i < n; i++)
    for (size_t a = 0; a < n; a++) {
      if (M[i * n + a] == 0) continue;
      for (size_t j = 0; j < n; j++)
        for (size_t k = 0; k < n; k++) {
          double h = 0;
          for (size_t b = 0; b < n; b++)
            for (size_t c = 0; c < n; c++)
              h += s->H[(a * n + b) * n + c] * Mi[b * n + j] * Mi[c * n + k];
          t->H[(i * n + j) * n + k] += M[i * n + a] * h;
          for (size_t l = 0; l < n; l++) {
            double v = 0;
            for (size_t b = 0; b < n; b++)
              for (size_t c = 0; c < n; c++)
                for (size_t d = 0; d < n; d++)
                  v += s->T[((a * n + b) * n + c) * n + d] * Mi[b * n + j] *
                       Mi[c * n + k] * Mi[d * n + l];
            t->T[((i * n + j) * n + k) * n + l] += M[i * n + a] * v;
          }
        }
    }
  t->jet = (sc_nf_jet){n, t->A, t->H, t->T};
}

/* |M q|^2 for q = (re, im) of @p nf (2 n values). */
static double image_norm2(size_t n, const double *M, const sc_nf *nf) {
  double s = 0;
  for (size_t i = 0; i < n; i++) {
    double re = 0, im = 0;
    for (size_t j = 0; j < n; j++)
      re += M[i * n + j] * nf->q[j], im += M[i * n + j] * nf->q[n + j];
    s += re * re + im * im;
  }
  return s;
}

/* ---- the maps ----------------------------------------------------------- */

/* fold, n = 3: x -> x + a x^2 + k x y, y -> 0.5 y + c x^2 + x z,
 * z -> -0.3 z + y^2: the fold coefficient is a. */
typedef struct { double a, k, c, b3, mu; } coefs;

static void fold_Q(const double *x, double *o, const void *cv) {
  const coefs *c = cv;
  o[0] = c->a * x[0] * x[0] + c->k * x[0] * x[1];
  o[1] = c->c * x[0] * x[0] + x[0] * x[2];
  o[2] = x[1] * x[1];
}
static void fold_K(const double *x, double *o, const void *cv) {
  const coefs *c = cv;
  o[0] = c->b3 * x[0] * x[0] * x[0], o[1] = x[1] * x[2] * x[0], o[2] = 0;
}

/* flip, n = 2: x -> -x + a2 x^2 + b3 x^3 + k x y, y -> mu y + c x^2:
 * on the centre manifold y = c x^2 / (1 - mu), so the cubic term is
 * b3 + k c / (1 - mu), and b = a2^2 + b3 + k c / (1 - mu). */
static void flip_Q(const double *x, double *o, const void *cv) {
  const coefs *c = cv;
  o[0] = c->a * x[0] * x[0] + c->k * x[0] * x[1];
  o[1] = c->c * x[0] * x[0];
}
static void flip_K(const double *x, double *o, const void *cv) {
  const coefs *c = cv;
  o[0] = c->b3 * x[0] * x[0] * x[0], o[1] = 0;
}

/* NS, n = 4: z = x0 + i x1, w1 = x2, w2 = x3;
 * z -> lam z + lam d z |z|^2 + k1 z w1 + k2 conj(z) w2 (+ a non-resonant
 * z^3 / 3), w1 -> mu1 w1 + c1 |z|^2, w2 -> mu2 w2 + c2 Re(z^2).
 * The centre manifold is w1 = c1 |z|^2 / (1 - mu1), w2 = al z^2 + conj,
 * al = c2 / (2 (lam^2 - mu2)), so the z^2 conj(z) coefficient is
 * lam d + k1 c1 / (1 - mu1) + k2 al, and d_eff = Re(e^(-i theta) (...)). */
typedef struct { double complex lam; double d, k1, k2, c1, c2, mu1, mu2; } nsc;

static void ns_Q(const double *x, double *o, const void *cv) {
  const nsc *c = cv;
  double complex z = x[0] + I * x[1];
  double complex r = c->k1 * z * x[2] + c->k2 * conj(z) * x[3];
  o[0] = creal(r), o[1] = cimag(r);
  o[2] = c->c1 * creal(z * conj(z)), o[3] = c->c2 * creal(z * z);
}
static void ns_K(const double *x, double *o, const void *cv) {
  const nsc *c = cv;
  double complex z = x[0] + I * x[1];
  double complex r = c->lam * c->d * z * z * conj(z) + z * z * z / 3;
  o[0] = creal(r), o[1] = cimag(r), o[2] = o[3] = 0;
}

static double ns_expected(const nsc *c) {
  double complex al = c->c2 / (2 * (c->lam * c->lam - c->mu2));
  double complex g = c->lam * c->d + c->k1 * c->c1 / (1 - c->mu1) + c->k2 * al;
  return creal(conj(c->lam) * g);
}

/* ---- the tests ---------------------------------------------------------- */

static void test_fold(void) {
  coefs c = {0.731, 1.3, -0.45, 0.9, 0};
  poly_map m = {3, {1, 0, 0, 0, 0.5, 0, 0, 0, -0.3}, fold_Q, fold_K, &c};
  jet_store s, t;
  jet_of(&m, &s);
  sc_nf nf;
  sc_msg msg;
  tu_int("fold: status", sc_nf_fold(&s.jet, NULL, &nf, &msg), SC_OK);
  tu_close("fold: a of x -> x + a x^2 (+ couplings)", nf.coef, c.a, TOL);
  tu_close("fold: multiplier", nf.mu[0], 1, TOL);
  double q0[3] = {-1, 0, 0};
  sc_nf_fold(&s.jet, q0, &nf, &msg);
  tu_close("fold: q oriented by qref flips a's sign", nf.coef, -c.a, TOL);
  for (int trial = 0; trial < 3; trial++) {
    double M[9], qref[3];
    random_orthogonal(3, M);
    transform(&s, M, &t);
    for (int i = 0; i < 3; i++) qref[i] = M[i * 3];
    sc_nf_fold(&t.jet, qref, &nf, &msg);
    tu_close("fold: orthogonal coordinates", nf.coef, c.a, TOL);
    random_matrix(3, M);
    transform(&s, M, &t);
    for (int i = 0; i < 3; i++) qref[i] = M[i * 3];
    sc_nf_fold(&t.jet, qref, &nf, &msg);
    /* q' = M e1 / |M e1|: a scales as q */
    double s2 = M[0] * M[0] + M[3] * M[3] + M[6] * M[6];
    tu_close("fold: general coordinates, a |M q|", nf.coef * sqrt(s2), c.a,
             TOL);
  }
}

static void test_flip(void) {
  coefs c = {0.42, 1.7, 0.65, -0.23, 0.3};
  poly_map m = {2, {-1, 0, 0, 0.3}, flip_Q, flip_K, &c};
  jet_store s, t;
  jet_of(&m, &s);
  double b = c.a * c.a + c.b3 + c.k * c.c / (1 - c.mu);
  sc_nf nf;
  sc_msg msg;
  tu_int("flip: status", sc_nf_flip(&s.jet, &nf, &msg), SC_OK);
  tu_close("flip: b = a2^2 + b3 + k c / (1 - mu)", nf.coef, b, TOL);
  tu_close("flip: theta", nf.theta, acos(-1.0), TOL);
  for (int trial = 0; trial < 3; trial++) {
    double M[4];
    random_orthogonal(2, M);
    transform(&s, M, &t);
    sc_nf_flip(&t.jet, &nf, &msg);
    tu_close("flip: orthogonal coordinates", nf.coef, b, TOL);
    random_matrix(2, M);
    transform(&s, M, &t);
    sc_nf_flip(&t.jet, &nf, &msg);
    tu_close("flip: general coordinates, b |M q|^2", nf.coef,
             b / (M[0] * M[0] + M[2] * M[2]), TOL);
  }
  /* n = 1: the formula of docs/curves.md, sc_curve_coefficient() */
  double A1 = -1, H1 = 2.385, T1 = -0.71;
  sc_nf_jet one = {1, &A1, &H1, &T1};
  sc_curve_jet cj = {0};
  cj.gxx = H1, cj.gxxx = T1;
  sc_nf_flip(&one, &nf, &msg);
  tu_close("flip n = 1: (g_xx/2)^2 + g_xxx/6", nf.coef,
           sc_curve_coefficient(SC_CURVE_FLIP, &cj), 1e-15);
  A1 = 1;
  sc_nf_fold(&one, NULL, &nf, &msg);
  tu_close("fold n = 1: g_xx/2", nf.coef,
           sc_curve_coefficient(SC_CURVE_FOLD, &cj), 1e-15);
}

static void check_ns(const char *what, const nsc *c) {
  poly_map m = {4, {0}, ns_Q, ns_K, c};
  double cs = creal(c->lam), sn = cimag(c->lam);
  m.A[0] = cs, m.A[1] = -sn, m.A[4] = sn, m.A[5] = cs;
  m.A[10] = c->mu1, m.A[15] = c->mu2;
  jet_store s, t;
  jet_of(&m, &s);
  double d = ns_expected(c);
  sc_nf nf;
  sc_msg msg;
  char w[128];
  tu_int("ns: status", sc_nf_ns(&s.jet, NULL, &nf, &msg), SC_OK);
  snprintf(w, sizeof w, "ns %s: d", what);
  tu_close(w, nf.coef, d, TOL);
  snprintf(w, sizeof w, "ns %s: theta", what);
  tu_close(w, nf.theta, carg(c->lam), TOL);
  for (int trial = 0; trial < 3; trial++) {
    double M[16];
    random_orthogonal(4, M);
    transform(&s, M, &t);
    sc_nf_ns(&t.jet, NULL, &nf, &msg);
    snprintf(w, sizeof w, "ns %s: orthogonal coordinates", what);
    tu_close(w, nf.coef, d, TOL);
    random_matrix(4, M);
    transform(&s, M, &t);
    sc_nf_ns(&t.jet, NULL, &nf, &msg);
    /* q' = M q / |M q| sqrt(1/2) with <q, q> = 1/2 in the old frame */
    sc_nf nf0;
    sc_nf_ns(&s.jet, NULL, &nf0, &msg);
    snprintf(w, sizeof w, "ns %s: general coordinates, d 2 |M q|^2", what);
    tu_close(w, nf.coef * 2 * image_norm2(4, M, &nf0), d, TOL);
  }
}

/* Kuznetsov's planar formula: z -> lam z + g20/2 z^2 + g11 z conj(z) +
 * g02/2 conj(z)^2 + g21/2 z^2 conj(z) (+ other cubic terms) has
 * c1 = g20 g11 (conj(lam) - 3 + 2 lam) / (2 (lam^2 - lam)(conj(lam) - 1))
 *    + |g11|^2 / (1 - conj(lam)) + |g02|^2 / (2 (lam^2 - conj(lam)))
 *    + g21 / 2, and d = Re(e^(-i theta) c1). */
typedef struct { double complex lam, g20, g11, g02, g21, g30; } kuz;

static void kz_Q(const double *x, double *o, const void *cv) {
  const kuz *c = cv;
  double complex z = x[0] + I * x[1];
  double complex r =
      c->g20 / 2 * z * z + c->g11 * z * conj(z) + c->g02 / 2 * conj(z * z);
  o[0] = creal(r), o[1] = cimag(r);
}
static void kz_K(const double *x, double *o, const void *cv) {
  const kuz *c = cv;
  double complex z = x[0] + I * x[1];
  double complex r = c->g21 / 2 * z * z * conj(z) + c->g30 / 6 * z * z * z;
  o[0] = creal(r), o[1] = cimag(r);
}

static void test_ns_planar(void) {
  kuz c = {cexp(I * 0.83), 0.7 - 0.2 * I, -0.35 + 0.6 * I, 0.25 + 0.45 * I,
           -0.8 + 0.3 * I, 1.1};
  double complex l = c.lam, lb = conj(l);
  double complex c1 = c.g20 * c.g11 * (lb - 3 + 2 * l) /
                          (2 * (l * l - l) * (lb - 1)) +
                      c.g11 * conj(c.g11) / (1 - lb) +
                      c.g02 * conj(c.g02) / (2 * (l * l - lb)) + c.g21 / 2;
  poly_map m = {2, {creal(l), -cimag(l), cimag(l), creal(l)}, kz_Q, kz_K, &c};
  jet_store s;
  jet_of(&m, &s);
  sc_nf nf;
  sc_msg msg;
  sc_nf_ns(&s.jet, NULL, &nf, &msg);
  tu_close("ns planar: Kuznetsov's formula with every quadratic term",
           nf.coef, creal(lb * c1), TOL);
  double mu[2] = {creal(l), -cimag(l)};
  sc_nf_ns(&s.jet, mu, &nf, &msg);
  tu_close("ns planar: chosen by the conjugate multiplier", nf.coef,
           creal(lb * c1), TOL);
}

static void test_multipliers(void) {
  /* block diag(rotation 1.2 by 0.7, 0.5, -2) in random coordinates */
  jet_store s = {0}, t;
  size_t n = 4;
  s.A[0] = 1.2 * cos(0.7), s.A[1] = -1.2 * sin(0.7);
  s.A[4] = 1.2 * sin(0.7), s.A[5] = 1.2 * cos(0.7);
  s.A[10] = 0.5, s.A[15] = -2;
  s.jet = (sc_nf_jet){n, s.A, s.H, s.T};
  double M[16], re[4], im[4];
  sc_msg msg;
  random_matrix(n, M);
  transform(&s, M, &t);
  tu_int("multipliers: status", sc_nf_multipliers(n, t.A, re, im, &msg), SC_OK);
  tu_close("multipliers: -2 first", re[0], -2, TOL);
  tu_close("multipliers: pair re", re[1], 1.2 * cos(0.7), TOL);
  tu_close("multipliers: pair im > 0 first", im[1], 1.2 * sin(0.7), TOL);
  tu_close("multipliers: conjugate next", im[2], -1.2 * sin(0.7), TOL);
  tu_close("multipliers: 0.5 last", re[3], 0.5, TOL);
}

static void test_refusals(void) {
  double A[4] = {1, 0, 0, -1}, H[8] = {0}, T[16] = {0};
  sc_nf_jet g = {2, A, H, T};
  sc_nf nf;
  sc_msg msg;
  tu_int("refuse: flip with a multiplier 1 (LPPD)", sc_nf_flip(&g, &nf, &msg),
         SC_ESING);
  tu_int("refuse: NS without a complex pair", sc_nf_ns(&g, NULL, &nf, &msg),
         SC_EINVAL);
  double J[4] = {1, 1, 0, 1}; /* a Jordan block: R1 */
  g.A = J;
  tu_int("refuse: fold at a double multiplier 1",
         sc_nf_fold(&g, NULL, &nf, &msg), SC_ESING);
  g.n = 0;
  tu_int("refuse: n = 0", sc_nf_fold(&g, NULL, &nf, &msg), SC_EINVAL);
  g.n = 2, g.T = NULL;
  tu_int("refuse: flip without T", sc_nf_flip(&g, &nf, &msg), SC_EINVAL);
}


/* The codimension-two tests: the other multipliers nu enter as
 * prod (1 - nu), prod (-1 - nu) and prod_{i<j} (nu_i nu_j - 1), whatever
 * the coordinates. */
static void test_curve_tests(void) {
  jet_store s = {0}, t;
  double M[16], psi[SC_NF_MAXTEST];
  sc_msg msg;
  const double n1 = 0.37, n2 = -1.6, th = 0.9, kap = cos(th);
  /* fold, n = 3: multipliers 1, n1, n2 */
  s.A[0] = 1, s.A[4] = n1, s.A[8] = n2;
  s.jet = (sc_nf_jet){3, s.A, s.H, s.T};
  random_matrix(3, M);
  transform(&s, M, &t);
  tu_int("fold tests: status",
         sc_nf_curve_tests(SC_NF_FOLD, &t.jet, 0, NULL, psi, NULL, &msg), SC_OK);
  tu_close("fold R1: (1 - n1)(1 - n2)", psi[1], (1 - n1) * (1 - n2), TOL);
  tu_close("fold LPPD: (-1 - n1)(-1 - n2)", psi[2], (1 + n1) * (1 + n2), TOL);
  tu_close("fold LPNS: n1 n2 - 1", psi[3], n1 * n2 - 1, TOL);
  /* flip, n = 3: multipliers -1, n1, n2 */
  s.A[0] = -1;
  transform(&s, M, &t);
  sc_nf_curve_tests(SC_NF_FLIP, &t.jet, 0, NULL, psi, NULL, &msg);
  tu_close("flip R2: (-1 - n1)(-1 - n2)", psi[1], (1 + n1) * (1 + n2), TOL);
  tu_close("flip LPPD: (1 - n1)(1 - n2)", psi[2], (1 - n1) * (1 - n2), TOL);
  tu_close("flip PDNS: n1 n2 - 1", psi[3], n1 * n2 - 1, TOL);
  /* NS, n = 4: e^(+-i theta), n1, n2 */
  memset(&s, 0, sizeof s);
  s.A[0] = s.A[5] = kap, s.A[1] = -sin(th), s.A[4] = sin(th);
  s.A[10] = n1, s.A[15] = n2;
  s.jet = (sc_nf_jet){4, s.A, s.H, s.T};
  random_matrix(4, M);
  transform(&s, M, &t);
  sc_nf_curve_tests(SC_NF_NS, &t.jet, kap, NULL, psi, NULL, &msg);
  double want[8] = {kap - 1, kap + 1, kap + 0.5, kap, 0,
                    (1 - n1) * (1 - n2), (1 + n1) * (1 + n2), n1 * n2 - 1};
  const char *nm[8] = {"R1", "R2", "R3", "R4", "CH (no H, T: d = 0)",
                       "LPNS", "PDNS", "NSNS"};
  for (int k = 0; k < 8; k++) {
    char w[64];
    snprintf(w, sizeof w, "ns %s (label %s)", nm[k],
             sc_nf_curve_label(SC_NF_NS, (size_t)k, NULL));
    tu_close(w, psi[k], want[k], TOL);
  }
  /* tests that need more dimensions are NaN: never a sign change */
  memset(&s, 0, sizeof s);
  s.A[0] = 1, s.A[3] = 0.5;
  s.jet = (sc_nf_jet){2, s.A, s.H, s.T};
  sc_nf_curve_tests(SC_NF_FOLD, &s.jet, 0, NULL, psi, NULL, &msg);
  tu_true(isnan(psi[3]), "fold LPNS at n = 2 is NaN (%g)", psi[3]);
  tu_close("fold R1 at n = 2: 1 - 0.5", psi[1], 0.5, TOL);
}

int main(void) {
  test_fold();
  test_flip();
  nsc a = {cexp(I * 1.1), -0.37, 0, 0, 0, 0, 0.2, -0.4};
  check_ns("z -> e^(i theta) z (1 + d |z|^2)", &a);
  nsc b = {cexp(I * 2.3), 0.58, 0.9, -1.4, 0.75, 0.6, 0.35, -0.55};
  check_ns("with couplings through (I - A)^-1 and (mu^2 I - A)^-1", &b);
  test_ns_planar();
  test_multipliers();
  test_curve_tests();
  test_refusals();
  return tu_finish();
}
