/* Multipliers of a product of square matrices without forming it: the
 * periodic Hessenberg-triangular reduction and the periodic QR algorithm
 * of SLICOT (MB03VD, MB03WD), with the factors scaled by powers of two and
 * the eigenvalues read from the periodic Schur form as mantissa and
 * exponent, so that neither the product nor its eigenvalues need to lie
 * in the range of double.  docs/maps.md, "Multipliers". */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/linalg.h"

/* pi to the last digit of double (C11 has no M_PI), and log 2 in two
 * parts (Cody and Waite's): PE_LN2_HI has 32 significant bits, so
 * exp * PE_LN2_HI is exact for |exp| < 2^21 and log |mu| = log(mant) +
 * exp log 2 is rounded once, not with the error of log 2 times exp. */
#define PE_PI 3.14159265358979323846
#define PE_LN2_HI 6.93147180369123816490e-01
#define PE_LN2_LO 1.90821492927058770002e-10

/* Workspace of dgeqrf and dorgqr per column: LAPACK's block size for
 * them is 32 (ilaenv), 64 leaves room; a smaller one only slows them. */
#define PE_QR_BLOCK 64

/* The QR cycles (see sc_product_eigs_compute) split the product where
 * the block of Q_0^T Q_m below the split has Frobenius norm at most
 * n eps: dropping it from the last factor changes that factor by at most
 * n eps ||A_{m-1}||, the backward error of the QR factorizations
 * themselves. */
#define PE_SPLIT_TOL(n) ((double)(n) * DBL_EPSILON)

/* The QR cycles go on until every cluster's multipliers, estimated by the
 * products of the R_k's diagonal entries, span at most a factor
 * e^PE_SAFE_SPREAD (1e20).  MB03WD computes products of diagonal entries
 * over all factors; with each cluster's factors scaled to a geometric
 * mean of 1 they stay near the multipliers' own range, and it converges
 * when that range is small: on a random product of 256 factors of order
 * 16 it failed to converge on a cluster of 15 multipliers spanning 1e100
 * and converged once the clusters spanned at most 1e40 (measured).  One
 * cycle splits multipliers whose moduli differ by more than 1/eps, c
 * cycles by more than eps^(-1/c); a product whose factors' triangular
 * parts spread while its multipliers do not (strongly hyperbolic factors
 * turning a complex pair) never meets the test, so the cycles stop after
 * PE_MAX_CYCLES (splits down to a ratio eps^(-1/8) = 90). */
#define PE_SAFE_SPREAD 46.0
#define PE_MAX_CYCLES 8

/* SLICOT and LAPACK (Fortran 77 interface, 32-bit integers, every argument
 * by address, hidden string lengths last as gfortran passes them). */
extern void mb03vd_(const int *n, const int *p, const int *ilo, const int *ihi,
                    double *a, const int *lda1, const int *lda2, double *tau,
                    const int *ldtau, double *dwork, int *info);
extern void mb03wd_(const char *job, const char *compz, const int *n,
                    const int *p, const int *ilo, const int *ihi,
                    const int *iloz, const int *ihiz, double *h,
                    const int *ldh1, const int *ldh2, double *z,
                    const int *ldz1, const int *ldz2, double *wr, double *wi,
                    double *dwork, const int *ldwork, int *info,
                    size_t job_len, size_t compz_len);
extern void dgeqrf_(const int *m, const int *n, double *a, const int *lda,
                    double *tau, double *work, const int *lwork, int *info);
extern void dorgqr_(const int *m, const int *n, const int *k, double *a,
                    const int *lda, const double *tau, double *work,
                    const int *lwork, int *info);
extern void dlanv2_(double *a, double *b, double *c, double *d, double *rt1r,
                    double *rt1i, double *rt2r, double *rt2i, double *cs,
                    double *sn);

/* A nonzero number as mant 2^exp with 0.5 <= |mant| < 1 (frexp's form),
 * the exponent in a long: a product of 1e6 factors of 1e300 fits. */
typedef struct {
  double mant;
  long exp;
} xnum;

/* A unit of the sorted output: one real multiplier, or a complex pair
 * (kept adjacent). */
typedef struct {
  int pos;       /* its (first) position in Schur order */
  int size;      /* 1, or 2 for a complex pair */
  double logabs; /* log |mu| (-HUGE_VAL for zero) */
  double cosarg; /* cos of its angle: the tie-break (larger real part first) */
} eig_unit;

struct sc_product_eigs_work {
  int n, m;
  int ns, lo;     /* the cluster in the periodic QR: size, first index */
  double *a;      /* n x n x m, column-major: the scaled factors A_k */
  double *r;      /* n x n x m, column-major: R_k of the QR cycles */
  double *q0, *q, *x, *wq; /* n x n each: Q_0, Q_k, A_k Q_k, Q_0^T Q_m */
  double *qtau;   /* n, dgeqrf's reflectors */
  double *qwork;  /* qlwork, dgeqrf and dorgqr */
  int qlwork;
  int *split;     /* n + 1: the clusters [split[c], split[c + 1]) */
  xnum *rdiag;    /* n: products of the R_k's diagonal entries */
  int nsplit;     /* number of clusters */
  int cycles;     /* QR cycles of the last call */
  double *h;      /* n x n x m, column-major: a cluster's factors, then its
                     periodic Schur form T_k (MB03VD, MB03WD) */
  double *tau;    /* max(1, n - 1) x m, MB03VD's reflectors */
  double *dwork;  /* n + m */
  double *wr, *wi; /* n, MB03WD's own products (unused: they overflow) */
  long *scale;    /* m: factor k was divided by 2^scale[k] */
  xnum *mod;      /* n: modulus of each multiplier in Schur order */
  double *ang;    /* n: angle of each multiplier in Schur order */
  int *zero;      /* n: 1 for a zero multiplier */
  eig_unit *unit; /* n: the output units */
};

static xnum xnum_of(double v) {
  int e;
  xnum x;
  x.mant = frexp(v, &e);
  x.exp = e;
  return x;
}

static xnum xnum_mul(xnum a, xnum b) {
  int e;
  xnum x;
  x.mant = frexp(a.mant * b.mant, &e);
  x.exp = a.exp + b.exp + e;
  return x;
}

static xnum xnum_div(xnum a, xnum b) {
  int e;
  xnum x;
  x.mant = frexp(a.mant / b.mant, &e);
  x.exp = a.exp - b.exp + e;
  return x;
}

/* mant 2^exp as a double: +-inf past DBL_MAX, 0 below the subnormals. */
static double xnum_value(xnum x) {
  /* Exponents past +-2 DBL_MAX_EXP give inf or 0 whatever the mantissa;
   * clamping them there keeps ldexp's int argument in range. */
  long lim = 2L * DBL_MAX_EXP;
  long e = x.exp > lim ? lim : x.exp < -lim ? -lim : x.exp;
  return ldexp(x.mant, (int)e);
}

static double xnum_log(xnum x) {
  double e = (double)x.exp;
  return e * PE_LN2_HI + (log(fabs(x.mant)) + e * PE_LN2_LO);
}

void sc_product_eigs_work_free(sc_product_eigs_work *w) {
  if (!w) return;
  free(w->a);
  free(w->r);
  free(w->q0);
  free(w->q);
  free(w->x);
  free(w->wq);
  free(w->qtau);
  free(w->qwork);
  free(w->split);
  free(w->rdiag);
  free(w->h);
  free(w->tau);
  free(w->dwork);
  free(w->wr);
  free(w->wi);
  free(w->scale);
  free(w->mod);
  free(w->ang);
  free(w->zero);
  free(w->unit);
  free(w);
}

int sc_product_eigs_work_alloc(size_t n, size_t m, sc_product_eigs_work **out,
                               sc_msg *msg) {
  if (!out)
    return sc_fail(msg, SC_EINVAL, "sc_product_eigs_work_alloc: out is NULL");
  *out = NULL;
  if (n < 1 || m < 1)
    return sc_fail(msg, SC_EINVAL,
                   "sc_product_eigs_work_alloc: n = %zu, m = %zu (both >= 1)",
                   n, m);
  /* SLICOT indexes the n x n x m array with 32-bit integers. */
  if (n > (size_t)INT_MAX / n || n * n > (size_t)INT_MAX / m ||
      m > (size_t)INT_MAX - n || n > (size_t)INT_MAX / PE_QR_BLOCK)
    return sc_fail(msg, SC_EINVAL,
                   "sc_product_eigs_work_alloc: n = %zu, m = %zu (n^2 m and "
                   "n + m at most %d)", n, m, INT_MAX);
  sc_product_eigs_work *w = calloc(1, sizeof *w);
  if (!w) goto fail;
  w->n = (int)n;
  w->m = (int)m;
  size_t nt = n > 1 ? n - 1 : 1;
  w->qlwork = (int)(PE_QR_BLOCK * n);
  w->a = malloc(sizeof(double) * n * n * m);
  w->r = malloc(sizeof(double) * n * n * m);
  w->q0 = malloc(sizeof(double) * n * n);
  w->q = malloc(sizeof(double) * n * n);
  w->x = malloc(sizeof(double) * n * n);
  w->wq = malloc(sizeof(double) * n * n);
  w->qtau = malloc(sizeof(double) * n);
  w->qwork = malloc(sizeof(double) * (size_t)w->qlwork);
  w->split = malloc(sizeof(int) * (n + 1));
  w->rdiag = malloc(sizeof(xnum) * n);
  w->h = malloc(sizeof(double) * n * n * m);
  w->tau = malloc(sizeof(double) * nt * m);
  w->dwork = malloc(sizeof(double) * (n + m));
  w->wr = malloc(sizeof(double) * n);
  w->wi = malloc(sizeof(double) * n);
  w->scale = malloc(sizeof(long) * m);
  w->mod = malloc(sizeof(xnum) * n);
  w->ang = malloc(sizeof(double) * n);
  w->zero = malloc(sizeof(int) * n);
  w->unit = malloc(sizeof(eig_unit) * n);
  if (!w->a || !w->r || !w->q0 || !w->q || !w->x || !w->wq || !w->qtau ||
      !w->qwork || !w->split || !w->rdiag || !w->h || !w->tau || !w->dwork ||
      !w->wr || !w->wi || !w->scale || !w->mod || !w->ang || !w->zero ||
      !w->unit)
    goto fail;
  *out = w;
  return SC_OK;
fail:
  sc_product_eigs_work_free(w);
  return sc_fail(msg, SC_ENOMEM,
                 "sc_product_eigs_work_alloc: out of memory (n = %zu, m = %zu)",
                 n, m);
}

/* Copy A[k] (row major) into w->a (column major), divided by 2^scale[k]
 * with the scale chosen so that the copy's Frobenius norm lies in
 * [0.5, 1) (exact: a power of two).  Returns 1 if the factor is zero. */
static int load_factor(sc_product_eigs_work *w, int k, const double *a) {
  int n = w->n;
  double amax = 0;
  for (int i = 0; i < n * n; i++) amax = fmax(amax, fabs(a[i]));
  double *h = w->a + (size_t)n * n * (size_t)k;
  if (amax == 0) {
    memset(h, 0, sizeof(double) * (size_t)n * n);
    w->scale[k] = 0;
    return 1;
  }
  int e0, e1;
  frexp(amax, &e0);
  double ss = 0;
  for (int i = 0; i < n * n; i++) {
    double v = ldexp(a[i], -e0);
    ss += v * v;
  }
  frexp(sqrt(ss), &e1);
  int e = e0 + e1;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      h[i + (size_t)n * j] = ldexp(a[(size_t)i * n + j], -e);
  w->scale[k] = e;
  return 0;
}

/* Entry (i, j) of T in SLICOT's slot p (0-based). */
static double tij(const sc_product_eigs_work *w, int p, int i, int j) {
  return w->h[i + (size_t)w->ns * j + (size_t)w->ns * w->ns * p];
}

/* The 1 x 1 block at i: the product of the diagonal entries. */
static void block_real(sc_product_eigs_work *w, int i, long scale) {
  xnum x = {1.0, scale};
  int o = w->lo + i;
  for (int p = 0; p < w->m; p++) {
    double d = tij(w, p, i, i);
    if (d == 0) {
      w->zero[o] = 1;
      return;
    }
    x = xnum_mul(x, xnum_of(d));
  }
  w->zero[o] = 0;
  w->mod[o] = (xnum){fabs(x.mant), x.exp};
  w->ang[o] = x.mant < 0 ? PE_PI : 0;
}

/* The 2 x 2 block at (i, i + 1).  Its determinant is the product of the
 * factors' determinants (det of T_0's 2 x 2 block times u11 u22 of the
 * others), accumulated as mantissa and exponent: |mu|^2 of a complex pair
 * and mu1 mu2 of a real one, to the relative accuracy of the entries.  The
 * angle, or the larger real multiplier, comes from the product of the
 * blocks renormalized after each factor, standardized by dlanv2. */
static void block_pair(sc_product_eigs_work *w, int i, long scale) {
  int i1 = i + 1;
  double b[4] = {tij(w, 0, i, i), tij(w, 0, i, i1), tij(w, 0, i1, i),
                 tij(w, 0, i1, i1)};
  xnum det = xnum_of(b[0] * b[3] - b[1] * b[2]);
  long bexp = 0;
  for (int p = 1; p < w->m; p++) {
    double u11 = tij(w, p, i, i), u12 = tij(w, p, i, i1);
    double u22 = tij(w, p, i1, i1);
    det = xnum_mul(det, xnum_mul(xnum_of(u11), xnum_of(u22)));
    double c[4] = {b[0] * u11, b[0] * u12 + b[1] * u22, b[2] * u11,
                   b[2] * u12 + b[3] * u22};
    double cmax =
        fmax(fmax(fabs(c[0]), fabs(c[1])), fmax(fabs(c[2]), fabs(c[3])));
    int e = 0;
    if (cmax > 0) frexp(cmax, &e);
    for (int q = 0; q < 4; q++) b[q] = ldexp(c[q], -e);
    bexp += e;
  }
  det.exp += 2 * scale;
  int o = w->lo + i, o1 = o + 1;
  double r1r, r1i, r2r, r2i, cs, sn;
  dlanv2_(&b[0], &b[1], &b[2], &b[3], &r1r, &r1i, &r2r, &r2i, &cs, &sn);
  if (r1i != 0) { /* complex pair: |mu| = sqrt(det) */
    xnum r;
    if (det.mant > 0) {
      xnum d = det;
      if (d.exp % 2) {
        d.mant *= 2;
        d.exp -= 1;
      }
      r = (xnum){sqrt(d.mant), d.exp / 2};
    } else { /* rounding made det <= 0 at a double root: from the block */
      r = xnum_of(hypot(r1r, r1i));
      r.exp += bexp + scale;
    }
    double th = atan2(fabs(r1i), r1r);
    w->mod[o] = w->mod[o1] = r;
    w->ang[o] = th;
    w->ang[o1] = -th;
    w->zero[o] = w->zero[o1] = 0;
    return;
  }
  /* Real pair: the larger from the block, the smaller as det / larger. */
  double big = fabs(r1r) >= fabs(r2r) ? r1r : r2r;
  if (big == 0) {
    w->zero[o] = w->zero[o1] = 1;
    return;
  }
  xnum xb = xnum_of(big);
  xb.exp += bexp + scale;
  w->mod[o] = (xnum){fabs(xb.mant), xb.exp};
  w->ang[o] = xb.mant < 0 ? PE_PI : 0;
  w->zero[o] = 0;
  if (det.mant == 0) {
    w->zero[o1] = 1;
    return;
  }
  xnum xs = xnum_div(det, xb);
  w->mod[o1] = (xnum){fabs(xs.mant), xs.exp};
  w->ang[o1] = xs.mant < 0 ? PE_PI : 0;
  w->zero[o1] = 0;
}

static int unit_cmp(const void *pa, const void *pb) {
  const eig_unit *a = pa, *b = pb;
  if (a->logabs != b->logabs) return a->logabs > b->logabs ? -1 : 1;
  if (a->cosarg != b->cosarg) return a->cosarg > b->cosarg ? -1 : 1;
  return (a->pos > b->pos) - (a->pos < b->pos);
}

/* The output units in Schur order, then sorted; returns their number. */
static int sort_units(sc_product_eigs_work *w) {
  int nu = 0;
  for (int i = 0; i < w->n; i++) {
    eig_unit *u = &w->unit[nu++];
    u->pos = i;
    u->size = !w->zero[i] && i + 1 < w->n && w->ang[i] > 0 &&
                      w->ang[i] < PE_PI && w->ang[i + 1] == -w->ang[i]
                  ? 2
                  : 1;
    u->logabs = w->zero[i] ? -HUGE_VAL : xnum_log(w->mod[i]);
    u->cosarg = w->zero[i] ? 1 : cos(w->ang[i]);
    i += u->size - 1;
  }
  qsort(w->unit, (size_t)nu, sizeof *w->unit, unit_cmp);
  return nu;
}

/* Write the multipliers in the order of the sorted units. */
static void emit(const sc_product_eigs_work *w, int nu, double *re,
                 double *im, double *logabs, double *arg) {
  int out = 0;
  for (int k = 0; k < nu; k++) {
    for (int q = 0; q < w->unit[k].size; q++, out++) {
      int i = w->unit[k].pos + q;
      double r = w->zero[i] ? 0 : xnum_value(w->mod[i]);
      double th = w->zero[i] ? 0 : w->ang[i];
      /* Real multipliers exactly: no rounding of cos(pi) or sin(0). */
      double c = th == 0 ? 1 : th == PE_PI ? -1 : cos(th);
      double s = th == 0 || th == PE_PI ? 0 : sin(th);
      /* Products with exact zeros kept zero when r overflows to inf. */
      if (re) re[out] = c == 0 ? 0 : r * c;
      if (im) im[out] = s == 0 ? 0 : r * s;
      if (logabs) logabs[out] = w->zero[i] ? -HUGE_VAL : xnum_log(w->mod[i]);
      if (arg) arg[out] = th;
    }
  }
}

/* The periodic Schur form of the cluster's factors in w->h (ns >= 2). */
static int periodic_schur(sc_product_eigs_work *w, sc_msg *msg) {
  int n = w->ns, p = w->m, one = 1, info = 0;
  int ldtau = n > 1 ? n - 1 : 1, ldwork = n + p;
  mb03vd_(&n, &p, &one, &n, w->h, &n, &n, w->tau, &ldtau, w->dwork, &info);
  if (info != 0)
    return sc_fail(msg, SC_EINTERNAL,
                   "sc_product_eigs_compute: MB03VD refused argument %d",
                   -info);
  double zdummy = 0;
  mb03wd_("S", "N", &n, &p, &one, &n, &one, &n, w->h, &n, &n, &zdummy, &one,
          &one, w->wr, w->wi, w->dwork, &ldwork, &info, 1, 1);
  if (info < 0)
    return sc_fail(msg, SC_EINTERNAL,
                   "sc_product_eigs_compute: MB03WD refused argument %d",
                   -info);
  if (info > 0)
    return sc_fail(msg, SC_ENOCONV,
                   "sc_product_eigs_compute: the periodic QR iteration did not "
                   "converge for multiplier %d (n = %d, m = %d)", info, n, p);
  return SC_OK;
}

/* One QR cycle from w->q0: A_k Q_k = Q_{k+1} R_k for k = 0 .. m - 1,
 * then W = Q_0^T Q_m in w->wq.  The product is
 *   A_{m-1} ... A_0 = Q_0 (W R_{m-1}) R_{m-2} ... R_0 Q_0^T,
 * per factor backward stable, and W is block upper triangular to
 * rounding wherever the cycle has split the multipliers' moduli apart
 * (the cycle is one step of subspace iteration on the product). */
static int qr_cycle(sc_product_eigs_work *w, sc_msg *msg) {
  int n = w->n, info = 0;
  size_t nn = (size_t)n * n;
  memcpy(w->q, w->q0, sizeof(double) * nn);
  for (int i = 0; i < n; i++) w->rdiag[i] = (xnum){1.0, 0};
  for (int k = 0; k < w->m; k++) {
    const double *a = w->a + nn * k;
    double *r = w->r + nn * k;
    for (int j = 0; j < n; j++)
      for (int i = 0; i < n; i++) {
        double sum = 0;
        for (int l = 0; l < n; l++) sum += a[i + n * l] * w->q[l + n * j];
        w->x[i + n * j] = sum;
      }
    dgeqrf_(&n, &n, w->x, &n, w->qtau, w->qwork, &w->qlwork, &info);
    if (info == 0) {
      for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) r[i + n * j] = i <= j ? w->x[i + n * j] : 0;
      for (int i = 0; i < n; i++)
        w->rdiag[i] = xnum_mul(w->rdiag[i], xnum_of(r[i + n * i]));
      dorgqr_(&n, &n, &n, w->x, &n, w->qtau, w->qwork, &w->qlwork, &info);
    }
    if (info != 0)
      return sc_fail(msg, SC_EINTERNAL, "sc_product_eigs_compute: dgeqrf or "
                     "dorgqr refused argument %d", -info);
    double *t = w->q;
    w->q = w->x;
    w->x = t;
  }
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      double sum = 0;
      for (int l = 0; l < n; l++) sum += w->q0[l + n * i] * w->q[l + n * j];
      w->wq[i + n * j] = sum;
    }
  return SC_OK;
}

/* The clusters of W = w->wq into split[0 .. ns]: a split at s where
 * ||W[s:, :s]||_F <= PE_SPLIT_TOL.  Returns the number of clusters. */
static int find_splits(const sc_product_eigs_work *w, int *split) {
  int n = w->n, ns = 0;
  split[ns++] = 0;
  for (int s = 1; s < n; s++) {
    double ss = 0;
    for (int j = 0; j < s; j++)
      for (int i = s; i < n; i++) ss += w->wq[i + n * j] * w->wq[i + n * j];
    if (sqrt(ss) <= PE_SPLIT_TOL(n)) split[ns++] = s;
  }
  split[ns] = n;
  return ns;
}

/* log2 |det| / s of a cluster factor, rounded, from its triangular part
 * (|det W_cc| is 1 to rounding): the scale that makes the geometric mean
 * of the factor's eigenvalue moduli about 1, so that MB03WD's products of
 * diagonal entries stay near the multipliers' own range.  A singular
 * factor is scaled by its largest entry instead. */
static int cluster_scale(const double *r, int n, int lo, int s, const double *f,
                         int ldf) {
  xnum det = {1.0, 0};
  for (int i = lo; i < lo + s; i++) det = xnum_mul(det, xnum_of(r[i + n * i]));
  if (det.mant != 0) return (int)lround(xnum_log(det) / (PE_LN2_HI * s));
  double fmax_ = 0;
  for (int j = 0; j < s; j++)
    for (int i = 0; i < s; i++) fmax_ = fmax(fmax_, fabs(f[i + ldf * j]));
  int e = 0;
  if (fmax_ > 0) frexp(fmax_, &e);
  return e;
}

/* The multipliers of the cluster [lo, lo + s), base scale 2^scale. */
static int cluster_eigs(sc_product_eigs_work *w, int lo, int s, long scale,
                        sc_msg *msg) {
  int n = w->n, m = w->m;
  size_t nn = (size_t)n * n;
  w->lo = lo;
  w->ns = s;
  for (int k = 0; k < m; k++) {
    const double *r = w->r + nn * k;
    double *f = w->h + (size_t)s * s * (size_t)(m - 1 - k); /* SLICOT slot */
    for (int j = 0; j < s; j++)
      for (int i = 0; i < s; i++) {
        double v = r[lo + i + n * (lo + j)];
        if (k == m - 1) { /* W_cc R_cc */
          v = 0;
          for (int l = 0; l <= j; l++)
            v += w->wq[lo + i + n * (lo + l)] * r[lo + l + n * (lo + j)];
        }
        f[i + s * j] = v;
      }
    int e = cluster_scale(r, n, lo, s, f, s);
    for (int q = 0; q < s * s; q++) f[q] = ldexp(f[q], -e);
    scale += e;
  }
  if (s > 1) {
    int status = periodic_schur(w, msg);
    if (status != SC_OK) return status;
  }
  for (int i = 0; i < s; i++) {
    if (i + 1 < s && tij(w, 0, i + 1, i) != 0) {
      block_pair(w, i, scale);
      i++;
    } else {
      block_real(w, i, scale);
    }
  }
  return SC_OK;
}

/* 1 if every cluster's estimated multipliers (rdiag; zeros left out: MB03WD
 * deflates exact zeros itself) span at most e^PE_SAFE_SPREAD. */
static int clusters_safe(const sc_product_eigs_work *w) {
  for (int c = 0; c < w->nsplit; c++) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (int i = w->split[c]; i < w->split[c + 1]; i++) {
      if (w->rdiag[i].mant == 0) continue;
      double l = xnum_log(w->rdiag[i]);
      lo = fmin(lo, l);
      hi = fmax(hi, l);
    }
    if (hi - lo > PE_SAFE_SPREAD) return 0;
  }
  return 1;
}

/* n >= 2: QR cycles until the clusters are safe for MB03WD, then the
 * periodic Schur form of each cluster. */
static int product_schur(sc_product_eigs_work *w, long scale, sc_msg *msg) {
  int n = w->n, *split = w->split;
  memset(w->q0, 0, sizeof(double) * (size_t)n * n);
  for (int i = 0; i < n; i++) w->q0[i + n * i] = 1;
  for (int c = 0; c < PE_MAX_CYCLES; c++) {
    if (c > 0) { /* start from Q_m: the next step of the iteration */
      double *t = w->q0;
      w->q0 = w->q;
      w->q = t;
    }
    int status = qr_cycle(w, msg);
    if (status != SC_OK) return status;
    w->nsplit = find_splits(w, split);
    w->cycles = c + 1;
    if (clusters_safe(w)) break;
  }
  for (int c = 0; c < w->nsplit; c++) {
    int status = cluster_eigs(w, split[c], split[c + 1] - split[c], scale, msg);
    if (status != SC_OK) return status;
  }
  return SC_OK;
}

int sc_product_eigs_compute(sc_product_eigs_work *w, const double *const *A,
                            double *re, double *im, double *logabs,
                            double *arg, sc_msg *msg) {
  if (!w || !A)
    return sc_fail(msg, SC_EINVAL, "sc_product_eigs_compute: %s is NULL",
                   w ? "A" : "the workspace");
  int n = w->n, m = w->m;
  for (int k = 0; k < m; k++) {
    if (!A[k])
      return sc_fail(msg, SC_EINVAL,
                     "sc_product_eigs_compute: factor A[%d] is NULL", k);
    for (int i = 0; i < n * n; i++)
      if (!isfinite(A[k][i]))
        return sc_fail(msg, SC_ENONFINITE,
                       "sc_product_eigs_compute: A[%d] entry (%d, %d) is %g "
                       "(finite)", k, i / n, i % n, A[k][i]);
  }
  int anyzero = 0;
  long scale = 0;
  for (int k = 0; k < m; k++) {
    anyzero |= load_factor(w, k, A[k]);
    scale += w->scale[k];
  }
  if (anyzero) { /* a zero factor: the product is zero */
    w->cycles = 0;
    w->nsplit = 0;
    for (int i = 0; i < n; i++) w->zero[i] = 1;
  } else if (n == 1) { /* the plain product */
    w->cycles = 0;
    w->nsplit = 1;
    w->lo = 0;
    w->ns = 1;
    for (int k = 0; k < m; k++) w->h[k] = w->a[k];
    block_real(w, 0, scale);
  } else {
    int status = product_schur(w, scale, msg);
    if (status != SC_OK) return status;
  }
  emit(w, sort_units(w), re, im, logabs, arg);
  return SC_OK;
}

int sc_product_eigs(size_t n, size_t m, const double *const *A, double *re,
                    double *im, sc_msg *msg) {
  sc_product_eigs_work *w = NULL;
  int status = sc_product_eigs_work_alloc(n, m, &w, msg);
  if (status == SC_OK)
    status = sc_product_eigs_compute(w, A, re, im, NULL, NULL, msg);
  sc_product_eigs_work_free(w);
  return status;
}

int sc_product_eigs_ncycles(const sc_product_eigs_work *w) {
  return w ? w->cycles : 0;
}

int sc_product_eigs_nclusters(const sc_product_eigs_work *w) {
  return w ? w->nsplit : 0;
}
