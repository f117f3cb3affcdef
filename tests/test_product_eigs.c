/* Multipliers of a product of matrices (sc_product_eigs): products built
 * with known eigenvalues, A_k = Q_{k+1} T_k Q_k^T with random orthogonal
 * Q_k (Q_m = Q_0) and (quasi-)triangular T_k, so that
 *   A_{m-1} ... A_0 = Q_0 (T_{m-1} ... T_0) Q_0^T
 * and the eigenvalues are the products of the T_k's diagonal entries (of
 * their 2 x 2 diagonal blocks for a complex pair).
 *
 * Tolerances.  The periodic Schur form is backward stable factor by
 * factor: the computed multipliers are exact for A_k + E_k with
 * ||E_k|| <= c n eps ||A_k||.  A multiplier mu = prod_k t_k (t_k the
 * diagonal entries of T_k) then moves by |mu| sum_k ||E_k|| / |t_k| times
 * the conditioning of the triangular coupling, so its relative error is
 * of order m n eps max_k ||A_k|| / |t_k|.  The graded products below keep
 * ||A_k|| / |t_k| <= 30 with n <= 4, m <= 12: m n eps 30 = 3.2e-13, and
 * 1e-11 relative leaves a margin of 30 for the conditioning of the random
 * couplings (the observed errors are printed; they are near 1e-14).
 * Forming the product first and calling dgeev gives an absolute error of
 * order eps ||P||, i.e. a relative error eps ||P|| / |mu|: 1e-4 / 1e-12
 * for a multiplier 1e-12 beside one of 1e12.  The tests assert that this
 * loss happens (so that they show why the periodic form is needed) and
 * that sc_product_eigs does not suffer it. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/linalg.h"
#include "test_util.h"

/* LAPACK's dgetrf (determinants) and dgeev (the naive route). */
extern void dgetrf_(const int *m, const int *n, double *a, const int *lda,
                    int *ipiv, int *info);
extern void dgeev_(const char *jobvl, const char *jobvr, const int *n,
                   double *a, const int *lda, double *wr, double *wi,
                   double *vl, const int *ldvl, double *vr, const int *ldvr,
                   double *work, const int *lwork, int *info, size_t l1,
                   size_t l2);

#define PI 3.14159265358979323846
#define NMAX 16

/* Relative error of the periodic route on well-graded products (see the
 * opening comment: m n eps 30 with a margin of 30). */
#define TOL_REL 1e-11

/* A deterministic generator (64-bit LCG, Knuth's MMIX constants). */
static unsigned long long rng_state = 0x2385ULL;
static double rnd(void) { /* uniform in [-1, 1) */
  rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(rng_state >> 11) / 4503599627370496.0 - 1.0;
}

/* A random orthogonal n x n matrix (row major): modified Gram-Schmidt,
 * twice, on a random matrix. */
static void random_orthogonal(int n, double *q) {
  for (int i = 0; i < n * n; i++) q[i] = rnd();
  for (int pass = 0; pass < 2; pass++)
    for (int j = 0; j < n; j++) {
      for (int k = 0; k < j; k++) {
        double d = 0;
        for (int i = 0; i < n; i++) d += q[i * n + j] * q[i * n + k];
        for (int i = 0; i < n; i++) q[i * n + j] -= d * q[i * n + k];
      }
      double s = 0;
      for (int i = 0; i < n; i++) s += q[i * n + j] * q[i * n + j];
      s = sqrt(s);
      for (int i = 0; i < n; i++) q[i * n + j] /= s;
    }
}

/* c = a b (n x n, row major). */
static void matmul(int n, const double *a, const double *b, double *c) {
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) {
      double s = 0;
      for (int k = 0; k < n; k++) s += a[i * n + k] * b[k * n + j];
      c[i * n + j] = s;
    }
}

/* A product of m factors with known multipliers: the caller fills T
 * (m x n x n, row major); this makes A_k = Q_{k+1} T_k Q_k^T. */
typedef struct {
  int n, m;
  double *T, *A, *Q;
  const double **Ap;
} product;

static product product_new(int n, int m) {
  product p = {n, m, NULL, NULL, NULL, NULL};
  p.T = calloc((size_t)(n * n * m), sizeof(double));
  p.A = calloc((size_t)(n * n * m), sizeof(double));
  p.Q = calloc((size_t)(n * n * m), sizeof(double));
  p.Ap = calloc((size_t)m, sizeof *p.Ap);
  for (int k = 0; k < m; k++) p.Ap[k] = p.A + (size_t)n * n * k;
  return p;
}

static void product_free(product *p) {
  free(p->T);
  free(p->A);
  free(p->Q);
  free(p->Ap);
}

static double *factor_T(product *p, int k) {
  return p->T + (size_t)p->n * p->n * k;
}

/* Random strictly upper part (entries in [-g, g)) in every T_k, skipping
 * the (i, i + 1) entry of 2 x 2 blocks the caller marks in @p block. */
static void random_upper_g(product *p, const int *block, double g) {
  int n = p->n;
  for (int k = 0; k < p->m; k++)
    for (int i = 0; i < n; i++)
      for (int j = i + 1; j < n; j++)
        if (!(block && block[i] && j == i + 1))
          factor_T(p, k)[i * n + j] = g * rnd();
}

static void random_upper(product *p, const int *block) {
  random_upper_g(p, block, 1);
}

static void product_build(product *p) {
  int n = p->n;
  double *tmp = malloc(sizeof(double) * (size_t)(n * n));
  double *qt = malloc(sizeof(double) * (size_t)(n * n));
  for (int k = 0; k < p->m; k++) random_orthogonal(n, p->Q + (size_t)n * n * k);
  for (int k = 0; k < p->m; k++) {
    const double *qk = p->Q + (size_t)n * n * k;
    const double *qk1 = p->Q + (size_t)n * n * ((k + 1) % p->m);
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) qt[i * n + j] = qk[j * n + i];
    matmul(n, factor_T(p, k), qt, tmp);
    matmul(n, qk1, tmp, p->A + (size_t)n * n * k);
  }
  free(tmp);
  free(qt);
}

/* The naive route: form the product and call dgeev. */
static int naive_eigs(const product *p, double *re, double *im) {
  int n = p->n, info = 0, one = 1, lwork = 8 * NMAX;
  double P[NMAX * NMAX], C[NMAX * NMAX], F[NMAX * NMAX], work[8 * NMAX];
  memcpy(P, p->Ap[0], sizeof(double) * (size_t)(n * n));
  for (int k = 1; k < p->m; k++) {
    matmul(n, p->Ap[k], P, C);
    memcpy(P, C, sizeof(double) * (size_t)(n * n));
  }
  for (int i = 0; i < n; i++) /* row major to column major */
    for (int j = 0; j < n; j++) F[i + n * j] = P[i * n + j];
  dgeev_("N", "N", &n, F, &n, re, im, NULL, &one, NULL, &one, work, &lwork,
         &info, 1, 1);
  return info;
}

/* For each expected multiplier, the relative error of the nearest computed
 * one (each computed one used once): err[i]. */
static void match_errors(int n, const double *er, const double *ei,
                         const double *cr, const double *ci, double *err) {
  int used[NMAX] = {0};
  for (int i = 0; i < n; i++) {
    int best = -1;
    double bd = HUGE_VAL;
    for (int j = 0; j < n; j++) {
      if (used[j]) continue;
      double d = hypot(cr[j] - er[i], ci[j] - ei[i]);
      if (d < bd) {
        bd = d;
        best = j;
      }
    }
    used[best] = 1;
    double mod = hypot(er[i], ei[i]);
    err[i] = mod > 0 ? bd / mod : bd;
  }
}

/* sc_product_eigs_compute's order: decreasing modulus, a complex pair
 * adjacent with its positive imaginary part first. */
static int sorted_ok(int n, const double *la, const double *re,
                     const double *im) {
  for (int i = 0; i + 1 < n; i++)
    if (la[i] < la[i + 1]) return 0;
  for (int i = 0; i < n; i++)
    if (im[i] != 0) {
      if (!(im[i] > 0 && i + 1 < n && im[i + 1] == -im[i] &&
            re[i + 1] == re[i]))
        return 0;
      i++;
    }
  return 1;
}

/* Run both routes on @p p against the expected (er, ei); returns the
 * largest relative error of each in *ours and *naive, and the errors of
 * the multiplier @p watch in *ours_w, *naive_w. */
static void run_both(const product *p, const double *er, const double *ei,
                     const char *what, double *ours, double *naive, int watch,
                     double *ours_w, double *naive_w) {
  int n = p->n;
  double re[NMAX], im[NMAX], la[NMAX], arg[NMAX], err[NMAX];
  sc_product_eigs_work *w = NULL;
  sc_msg msg = {{0}};
  int st = sc_product_eigs_work_alloc((size_t)n, (size_t)p->m, &w, &msg);
  if (st == SC_OK)
    st = sc_product_eigs_compute(w, p->Ap, re, im, la, arg, &msg);
  tu_true(st == SC_OK, "%s: status %d (%s)", what, st, msg.text);
  sc_product_eigs_work_free(w);
  tu_true(sorted_ok(n, la, re, im), "%s: order (modulus, pairs)", what);
  match_errors(n, er, ei, re, im, err);
  *ours = 0;
  for (int i = 0; i < n; i++) *ours = fmax(*ours, err[i]);
  if (ours_w) *ours_w = err[watch];
  double nr[NMAX], ni[NMAX];
  tu_int("dgeev info", naive_eigs(p, nr, ni), 0);
  match_errors(n, er, ei, nr, ni, err);
  *naive = 0;
  for (int i = 0; i < n; i++) *naive = fmax(*naive, err[i]);
  if (naive_w) *naive_w = err[watch];
  printf("  %s: largest relative error periodic %.3g, naive %.3g\n", what,
         *ours, *naive);
}

/* 2 x 2 block c R(theta) at (i, i) of T. */
static void put_rotation(double *T, int n, int i, double c, double th) {
  T[i * n + i] = c * cos(th);
  T[i * n + i + 1] = -c * sin(th);
  T[(i + 1) * n + i] = c * sin(th);
  T[(i + 1) * n + i + 1] = c * cos(th);
}

/* Graded: multipliers about 7.6e11, a complex pair of modulus about 1
 * and 1.3e-12 (n = 4, m = 17).  Each factor has diagonal entries 5, a
 * rotation block of scale about 1 and 0.2 (times 1 + 0.1 r), so
 * ||A_k|| / |t_k| <= 30. */
static void test_graded(void) {
  int n = 4, m = 17, block[4] = {0, 1, 0, 0};
  product p = product_new(n, m);
  random_upper(&p, block);
  double big = 1, pc = 1, th = 0, small = 1;
  for (int k = 0; k < m; k++) {
    double *T = factor_T(&p, k);
    double a = 5 * (1 + 0.1 * rnd()), c = 1 + 0.1 * rnd(),
           t = 0.7 + 0.3 * rnd();
    double d = 0.2 * (1 + 0.1 * rnd());
    T[0] = a;
    put_rotation(T, n, 1, c, t);
    T[3 * n + 3] = d;
    big *= a;
    pc *= c;
    th += t;
    small *= d;
  }
  product_build(&p);
  double er[4] = {big, pc * cos(th), pc * cos(th), small};
  double ei[4] = {0, pc * sin(th), -pc * sin(th), 0};
  double ours, naive, ours_s, naive_s;
  run_both(&p, er, ei, "graded n = 4, m = 17", &ours, &naive, 3, &ours_s,
           &naive_s);
  tu_true(ours <= TOL_REL, "graded: periodic error %.3g <= %.3g", ours,
          TOL_REL);
  /* The naive error of the small multiplier is of order eps big / small =
   * 1e8; asserting only 1e-4 keeps the test about the loss, not its
   * exact size. */
  tu_true(naive_s >= 1e-4, "graded: naive error of %.3g is %.3g (>= 1e-4: the "
          "product loses it)", small, naive_s);
  tu_true(ours_s <= TOL_REL, "graded: periodic error of %.3g is %.3g", small,
          ours_s);
  product_free(&p);
}

/* n = 16, m = 16: diagonal entries exp(u) with u uniform in [-1.5, 1.5]
 * and three rotation blocks (scale exp(u), angle in [0.5, 1.5]), the
 * couplings uniform in [-0.1, 0.1): 16 multipliers spread over about
 * e^(+-6) with pairs among them, many splits of the QR cycles and
 * clusters of several sizes.  The couplings are small because a product
 * of many random triangular factors is far from normal: with couplings
 * of 1 and m = 64 a relative perturbation of 1e-15 of the entries moves
 * the multipliers by 1e-3 (measured), so no method can do better, and
 * this routine's error follows that sensitivity (it is backward stable).
 * Here the same perturbation moves them by 1.2e-13 (measured), and
 * 1e-11 relative leaves a margin of 80. */
static void test_random_large(void) {
  int n = 16, m = 16, block[16] = {0};
  block[2] = block[7] = block[12] = 1;
  product p = product_new(n, m);
  random_upper_g(&p, block, 0.1);
  long double lmod[16] = {0}, ang[16] = {0};
  int neg = 0; /* factors with the real diagonal entries negative */
  for (int k = 0; k < m; k++) {
    double *T = factor_T(&p, k);
    neg += k % 5 == 0;
    for (int i = 0; i < n; i++) {
      double u = exp(1.5 * rnd());
      if (block[i]) {
        double t = 1 + 0.5 * rnd();
        put_rotation(T, n, i, u, t);
        lmod[i] += logl(u);
        ang[i] += t;
        i++;
      } else {
        T[i * n + i] = k % 5 ? u : -u;
        lmod[i] += logl(u);
      }
    }
  }
  product_build(&p);
  double er[16], ei[16];
  for (int i = 0; i < n; i++) {
    double r = (double)expl(lmod[i]), a = (double)ang[i];
    er[i] = r * cos(a);
    ei[i] = r * sin(a);
    if (block[i]) {
      er[i + 1] = er[i];
      ei[i + 1] = -ei[i];
      i++;
    } else {
      ei[i] = 0;
      er[i] = neg % 2 ? -r : r;
    }
  }
  double ours, naive;
  run_both(&p, er, ei, "random n = 16, m = 16", &ours, &naive, 0, NULL, NULL);
  tu_true(ours <= 1e-11, "random n = 16, m = 16: error %.3g <= 1e-11", ours);
  product_free(&p);
}

/* A repeated multiplier 2^8 = 256, semisimple (no coupling between the
 * two positions: the product's block is 256 I, as well conditioned as a
 * simple one) and defective (coupling: a 2 x 2 Jordan block, whose
 * eigenvalue moves by the square root of the perturbation, so the
 * accuracy the theory allows is sqrt(m n eps) ~ 1e-7 relative; 1e-5
 * leaves a margin of 100 for the coupling's size). */
static void test_repeated(void) {
  for (int defective = 0; defective < 2; defective++) {
    int n = 3, m = 8;
    product p = product_new(n, m);
    random_upper(&p, NULL);
    double small = 1;
    for (int k = 0; k < m; k++) {
      double *T = factor_T(&p, k);
      T[0] = 2;
      T[n + 1] = 2;
      T[2 * n + 2] = 0.5 * (1 + 0.1 * rnd());
      small *= T[2 * n + 2];
      if (!defective) T[1] = 0;
    }
    product_build(&p);
    double er[3] = {256, 256, small}, ei[3] = {0, 0, 0};
    double ours, naive;
    run_both(&p, er, ei,
             defective ? "repeated, defective" : "repeated, semisimple", &ours,
             &naive, 0, NULL, NULL);
    double tol = defective ? 1e-5 : TOL_REL;
    tu_true(ours <= tol, "repeated (%s): error %.3g <= %.3g",
            defective ? "defective" : "semisimple", ours, tol);
    product_free(&p);
  }
}

/* A singular factor (one zero diagonal entry in T_2) gives a zero
 * multiplier: it comes out of the order of eps times the product of the
 * other entries (each factor's backward error is eps ||A_k||), and the
 * others keep their relative accuracy.  A zero factor makes every
 * multiplier exactly zero, with log |mu| = -inf. */
static void test_zero(void) {
  int n = 3, m = 5;
  product p = product_new(n, m);
  random_upper(&p, NULL);
  double d0 = 1, d2 = 1;
  for (int k = 0; k < m; k++) {
    double *T = factor_T(&p, k);
    T[0] = 1.3 + 0.1 * rnd();
    T[n + 1] = k == 2 ? 0 : 1.1;
    T[2 * n + 2] = -0.7 + 0.1 * rnd();
    d0 *= T[0];
    d2 *= T[2 * n + 2];
  }
  product_build(&p);
  double re[3], im[3], la[3], arg[3];
  sc_msg msg = {{0}};
  sc_product_eigs_work *w = NULL;
  int st = sc_product_eigs_work_alloc(3, 5, &w, &msg);
  if (st == SC_OK) st = sc_product_eigs_compute(w, p.Ap, re, im, la, arg, &msg);
  tu_int("singular factor: status", st, SC_OK);
  tu_rel("singular factor: mu 1", re[0], d0, TOL_REL);
  tu_rel("singular factor: mu 2", re[1], d2, TOL_REL);
  /* |mu 3| <= m n eps prod ||A_k||, ||A_k|| <= 3: 5 * 3 * eps * 3^5 = 8e-13. */
  tu_close("singular factor: mu 3 (zero)", hypot(re[2], im[2]), 0, 1e-12);
  tu_true(arg[1] == PI && im[1] == 0, "singular factor: mu 2 < 0 has angle pi "
          "(%.17g) and no imaginary part (%g)", arg[1], im[1]);
  memset(p.A + 3 * n * n, 0, sizeof(double) * (size_t)(n * n)); /* A_3 = 0 */
  st = sc_product_eigs_compute(w, p.Ap, re, im, la, arg, &msg);
  tu_int("zero factor: status", st, SC_OK);
  for (int i = 0; i < n; i++)
    tu_true(re[i] == 0 && im[i] == 0 && la[i] == -HUGE_VAL && arg[i] == 0,
            "zero factor: mu %d = %g%+gi exactly 0, log |mu| = %g (-inf)", i,
            re[i], im[i], la[i]);
  sc_product_eigs_work_free(w);
  product_free(&p);
}

/* m = 1: the eigenvalues of one random 6 x 6 matrix against dgeev.  Both
 * are backward stable, so they agree to about eps ||A|| times the
 * eigenvalues' condition numbers (below 1e2 for this matrix); 1e-12
 * ||A|| leaves a margin of 40. */
static void test_single(void) {
  int n = 6;
  product p = product_new(n, 1);
  for (int i = 0; i < n * n; i++) p.A[i] = rnd();
  double re[6], im[6], nr[6], ni[6], err[6];
  sc_msg msg = {{0}};
  tu_int("m = 1: status", sc_product_eigs(6, 1, p.Ap, re, im, &msg), SC_OK);
  tu_int("m = 1: dgeev", naive_eigs(&p, nr, ni), 0);
  match_errors(n, nr, ni, re, im, err);
  double norm = 0, e = 0;
  for (int i = 0; i < n * n; i++) norm += p.A[i] * p.A[i];
  for (int i = 0; i < n; i++) e = fmax(e, err[i] * hypot(nr[i], ni[i]));
  tu_close("m = 1: largest difference from dgeev / ||A||_F", e / sqrt(norm), 0,
           1e-12);
  int pairs = 0;
  for (int i = 0; i < n; i++) pairs += im[i] > 0;
  tu_true(pairs >= 1, "m = 1: the matrix has a complex pair (%d)", pairs);
  product_free(&p);
}

/* n = 1: the plain product, to the rounding of its m multiplications
 * (m eps / 2 relative; 2e-15 for m = 7), and a product of 1000 numbers
 * near -1e3 (|mu| about 1e3000, far past DBL_MAX): log |mu| is the sum of
 * the logarithms (in long double; ours has the 1000 roundings of the
 * product, 1.1e-13 relative, and one of log |mu| = 6868: 2e-12 absolute),
 * re = -inf or +inf by the sign, the angle 0 or pi. */
static void test_scalar(void) {
  double a[1000], prod = 1;
  long double lsum = 0; /* the reference in 64-bit mantissas */
  const double *ap[1000];
  int neg = 0;
  for (int k = 0; k < 7; k++) {
    a[k] = 2.385 * (1 + 0.5 * rnd());
    if (k == 3) a[k] = -a[k];
    prod *= a[k];
    ap[k] = &a[k];
  }
  double re, im, la, arg;
  sc_msg msg = {{0}};
  tu_int("n = 1: status", sc_product_eigs(1, 7, ap, &re, &im, &msg), SC_OK);
  tu_rel("n = 1, m = 7: the product", re, prod, 2e-15);
  tu_true(im == 0, "n = 1: imaginary part %g (0)", im);
  for (int k = 0; k < 1000; k++) {
    a[k] = (k % 3 ? 1e3 : -1e3) * (1 + 0.5 * rnd());
    neg ^= a[k] < 0;
    lsum += logl(fabsl((long double)a[k]));
    ap[k] = &a[k];
  }
  sc_product_eigs_work *w = NULL;
  int st = sc_product_eigs_work_alloc(1, 1000, &w, &msg);
  if (st == SC_OK)
    st = sc_product_eigs_compute(w, ap, &re, &im, &la, &arg, &msg);
  tu_int("n = 1, m = 1000: status", st, SC_OK);
  tu_close("n = 1, m = 1000: log |mu|", la, (double)lsum, 2e-12);
  tu_true(re == (neg ? -HUGE_VAL : HUGE_VAL) && arg == (neg ? PI : 0),
          "n = 1, m = 1000: re = %g, angle %g (sign %s)", re, arg,
          neg ? "-" : "+");
  sc_product_eigs_work_free(w);
}

/* n = 2, rotations: A_k = Q_{k+1} R(theta_k) Q_k^T, a pure complex pair on
 * the unit circle, angle sum theta_k (mod 2 pi).  Each factor is
 * orthogonal to a few eps, so |mu| = 1 to m eps (16 factors: 3.6e-15);
 * 1e-14 asked.  Then rotations scaled by 2^k and 2^-k alternately, with
 * the same answer, and a pair turned by 180 degrees in total (real
 * product -I: two multipliers -1). */
static void test_rotations(void) {
  int n = 2, m = 16;
  for (int variant = 0; variant < 3; variant++) {
    product p = product_new(n, m);
    double th = 0;
    for (int k = 0; k < m; k++) {
      double t = variant == 2 ? PI / m : 0.3 + 0.2 * rnd();
      double c = variant == 1 ? ldexp(1, k % 2 ? -(k - 1) : k) : 1;
      put_rotation(factor_T(&p, k), n, 0, c, t);
      th += t;
    }
    product_build(&p);
    double re[2], im[2], la[2], arg[2];
    sc_msg msg = {{0}};
    sc_product_eigs_work *w = NULL;
    int st = sc_product_eigs_work_alloc(2, (size_t)m, &w, &msg);
    if (st == SC_OK)
      st = sc_product_eigs_compute(w, p.Ap, re, im, la, arg, &msg);
    tu_int("rotations: status", st, SC_OK);
    tu_close("rotations: log |mu 1|", la[0], 0, 1e-14);
    tu_close("rotations: log |mu 2|", la[1], 0, 1e-14);
    if (variant < 2) {
      double want = remainder(th, 2 * PI);
      tu_close("rotations: angle of mu 1", arg[0], fabs(want), 1e-14);
      tu_true(arg[1] == -arg[0] && im[0] > 0 && im[1] == -im[0],
              "rotations: conjugate pair, positive imaginary part first "
              "(%g, %g)", im[0], im[1]);
    } else {
      /* R(pi) = -I: a double multiplier -1, complex to rounding or real. */
      tu_close("rotations: -I: re 1", re[0], -1, 1e-14);
      tu_close("rotations: -I: re 2", re[1], -1, 1e-14);
      tu_close("rotations: -I: im 1", im[0], 0, 1e-7);
    }
    sc_product_eigs_work_free(w);
    product_free(&p);
  }
}

/* m = 1000, n = 4: diagonal entries about a, a rotation block of scale c
 * and d.  (2.2, 2, 1.5): |mu| about 1e342, 1e301 (a pair) and 1e176, the
 * first overflows when multiplied; (4, 3, 0.5): 1e602, 1e477 (a pair) and
 * 1e-301, a range of 1e903 that no product of diagonal entries in double
 * holds.  log |mu| is checked against the sum of the logarithms of the
 * diagonal entries (long double): the relative error of mu is of order
 * m n eps ||A_k|| / |t_k| ~ 1000 4 eps 12 = 1.1e-11, so 1e-10 absolute on
 * log |mu|. */
static void test_long(double a, double c, double d) {
  int n = 4, m = 1000, block[4] = {0, 1, 0, 0};
  product p = product_new(n, m);
  random_upper(&p, block);
  long double l0 = 0, l1 = 0, l3 = 0, th = 0;
  for (int k = 0; k < m; k++) {
    double *T = factor_T(&p, k);
    double t = 0.9 + 0.3 * rnd();
    T[0] = a * (1 + 0.01 * rnd());
    put_rotation(T, n, 1, c, t);
    T[3 * n + 3] = d * (1 + 0.01 * rnd());
    l0 += logl(T[0]);
    l1 += logl(c);
    l3 += logl(T[3 * n + 3]);
    th += t;
  }
  product_build(&p);
  double re[4], im[4], la[4], arg[4];
  sc_msg msg = {{0}};
  sc_product_eigs_work *w = NULL;
  int st = sc_product_eigs_work_alloc(4, 1000, &w, &msg);
  if (st == SC_OK) st = sc_product_eigs_compute(w, p.Ap, re, im, la, arg, &msg);
  tu_int("m = 1000: status", st, SC_OK);
  printf("  m = 1000: log10 |mu| = %.6f %.6f %.6f %.6f\n", la[0] / log(10),
         la[1] / log(10), la[2] / log(10), la[3] / log(10));
  tu_close("m = 1000: log |mu 1|", la[0], (double)l0, 1e-10);
  tu_close("m = 1000: log |mu 2| (pair)", la[1], (double)l1, 1e-10);
  tu_close("m = 1000: log |mu 3| (pair)", la[2], (double)l1, 1e-10);
  tu_close("m = 1000: log |mu 4|", la[3], (double)l3, 1e-10);
  /* The angle: a sum of 1000 angles near 1, rounded in long double to
   * 1e-16; the computed one follows from the entries to m eps. */
  tu_close("m = 1000: angle of the pair", arg[1],
           fabs(remainder((double)th, 2 * PI)), 1e-10);
  tu_true(re[0] == HUGE_VAL && im[0] == 0, "m = 1000: mu 1 overflows "
          "(%g%+gi)", re[0], im[0]);
  if (l1 > logl(DBL_MAX))
    tu_true(isinf(re[1]) && isinf(im[1]), "m = 1000: the pair overflows "
            "(%g%+gi)", re[1], im[1]);
  else
    tu_rel("m = 1000: |mu 2| itself", hypot(re[1], im[1]), (double)expl(l1),
           1e-10);
  tu_rel("m = 1000: mu 4 itself (in range)", re[3], (double)expl(l3), 1e-10);
  sc_product_eigs_work_free(w);
  product_free(&p);
}

/* Strongly hyperbolic factors turning a pair around the unit circle: every
 * factor is M = diag(a, 1/a) R(theta) conjugated, A_k = Q_{k+1} M Q_k^T,
 * so the product is Q_0 M^m Q_0^T with multipliers lambda^m, lambda =
 * e^(+-i phi), cos phi = (a + 1/a) cos(theta) / 2 (det M = 1).  With
 * a = 100 the factors' triangular parts spread by 1e4 each, 1e4000 over
 * m = 1000, while the multipliers stay on the unit circle.  phi is known
 * to a few eps, m phi to about 1000 eps: 1e-11 on the angle; each factor's
 * backward error n eps ||M|| / |lambda| = 4e-14 times m bounds |log |mu||
 * by 4e-11 (1e-10 asked). */
static void test_hyperbolic_pair(void) {
  int n = 2, m = 1000;
  double a = 100, th = 1.5707;
  product p = product_new(n, m);
  for (int k = 0; k < m; k++) {
    double *T = factor_T(&p, k);
    T[0] = a * cos(th);
    T[1] = -a * sin(th);
    T[2] = sin(th) / a;
    T[3] = cos(th) / a;
  }
  product_build(&p);
  double phi = acos((a + 1 / a) * cos(th) / 2);
  double want = fabs(remainder(m * phi, 2 * PI));
  double re[2], im[2], la[2], arg[2];
  sc_msg msg = {{0}};
  sc_product_eigs_work *w = NULL;
  int st = sc_product_eigs_work_alloc(2, (size_t)m, &w, &msg);
  if (st == SC_OK) st = sc_product_eigs_compute(w, p.Ap, re, im, la, arg, &msg);
  tu_int("hyperbolic pair: status", st, SC_OK);
  printf("  hyperbolic pair: %d QR cycles, %d clusters\n",
         sc_product_eigs_ncycles(w), sc_product_eigs_nclusters(w));
  tu_close("hyperbolic pair: log |mu 1|", la[0], 0, 1e-10);
  tu_close("hyperbolic pair: log |mu 2|", la[1], 0, 1e-10);
  tu_close("hyperbolic pair: angle", arg[0], want, 1e-11);
  tu_true(arg[1] == -arg[0], "hyperbolic pair: conjugate (%g, %g)", arg[0],
          arg[1]);
  sc_product_eigs_work_free(w);
  product_free(&p);
}

/* Random factors (entries uniform in [-1, 1), rows scaled by 1 or by
 * 0.5^i), n = 2, 3, 5, 8 and m = 2, 7, 50, 256: the multipliers are not
 * known, but their product is the product of the factors' determinants,
 * so sum log |mu| = sum_k log |det A_k| (LU, long double sum).  Each
 * factor's determinant moves by its condition number (below 1e3 here)
 * times n eps relative under the backward error, so the sums agree to
 * about m n 1e3 eps = m n 2e-13; 1e-12 m n is asked and the largest
 * observed difference is printed (4e-15 m n).  This check
 * found the multipliers of MB03WD wrong by factors of up to 1e4 on such
 * products when it was given them whole.  The naive route's sum is
 * printed beside it and asserted to miss by more than 1 (a factor e): its
 * small multipliers are lost, so its sum misses by thousands once m is
 * large. */
static void test_determinant(void) {
  const int ns[] = {2, 3, 5, 8}, ms[] = {2, 7, 50, 256};
  double worst = 0, naive_worst = 0;
  for (int g = 0; g < 2; g++)
    for (int a = 0; a < 4; a++)
      for (int b = 0; b < 4; b++) {
        int n = ns[a], m = ms[b], ipiv[NMAX], info = 0;
        product p = product_new(n, m);
        long double ldet = 0;
        double lu[NMAX * NMAX];
        for (int k = 0; k < m; k++) {
          double *A = p.A + (size_t)n * n * k;
          for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++)
              A[i * n + j] = rnd() * (g ? ldexp(1, -i) : 1);
          for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) lu[i + n * j] = A[i * n + j];
          dgetrf_(&n, &n, lu, &n, ipiv, &info);
          for (int i = 0; i < n; i++) ldet += logl(fabsl(lu[i + n * i]));
        }
        double re[NMAX], im[NMAX], la[NMAX];
        sc_msg msg = {{0}};
        sc_product_eigs_work *w = NULL;
        int st = sc_product_eigs_work_alloc((size_t)n, (size_t)m, &w, &msg);
        if (st == SC_OK)
          st = sc_product_eigs_compute(w, p.Ap, re, im, la, NULL, &msg);
        sc_product_eigs_work_free(w);
        if (!tu_true(st == SC_OK, "determinant n = %d, m = %d: status %d (%s)",
                     n, m, st, msg.text)) {
          product_free(&p);
          continue;
        }
        long double sum = 0;
        for (int i = 0; i < n; i++) sum += la[i];
        double d = fabs((double)(sum - ldet));
        worst = fmax(worst, d / (m * n));
        tu_true(d <= 1e-12 * m * n, "determinant n = %d, m = %d, rows %s: "
                "sum log |mu| %.15Lg, sum log |det| %.15Lg", n, m,
                g ? "graded" : "uniform", sum, ldet);
        if (naive_eigs(&p, re, im) == 0) {
          long double ns_ = 0;
          for (int i = 0; i < n; i++) ns_ += logl(hypotl(re[i], im[i]));
          naive_worst = fmax(naive_worst, fabs((double)(ns_ - ldet)));
        }
        product_free(&p);
      }
  printf("  determinant: largest |sum log |mu| - sum log |det|| / (m n): "
         "%.3g; the naive route's largest difference: %.3g\n", worst,
         naive_worst);
  tu_true(naive_worst > 1, "determinant: the naive route misses sum log |det| "
          "by %.3g (> 1)", naive_worst);
}

/* Bad input: NULL pointers, sizes, non-finite entries. */
static void test_errors(void) {
  double a[4] = {1, 2, 3, NAN}, re[2], im[2];
  const double *ap[2] = {a, NULL};
  sc_msg msg = {{0}};
  sc_product_eigs_work *w = NULL;
  tu_int("n = 0", sc_product_eigs_work_alloc(0, 1, &w, &msg), SC_EINVAL);
  tu_int("m = 0", sc_product_eigs_work_alloc(2, 0, &w, &msg), SC_EINVAL);
  tu_int("huge n", sc_product_eigs_work_alloc((size_t)1 << 20, 4, &w, &msg),
         SC_EINVAL);
  tu_int("NaN entry", sc_product_eigs(2, 1, ap, re, im, &msg), SC_ENONFINITE);
  tu_true(strstr(msg.text, "A[0] entry (1, 1)") != NULL, "message names the "
          "entry: %s", msg.text);
  a[3] = 1;
  tu_int("NULL factor", sc_product_eigs(2, 2, ap, re, im, &msg), SC_EINVAL);
  tu_true(strstr(msg.text, "A[1]") != NULL, "message names the factor: %s",
          msg.text);
  tu_int("NULL A", sc_product_eigs(2, 2, NULL, re, im, &msg), SC_EINVAL);
}

int main(void) {
  test_graded();
  test_random_large();
  test_repeated();
  test_zero();
  test_single();
  test_scalar();
  test_rotations();
  test_long(2.2, 2, 1.5);
  test_long(4, 3, 0.5);
  test_hyperbolic_pair();
  test_determinant();
  test_errors();
  return tu_finish();
}
