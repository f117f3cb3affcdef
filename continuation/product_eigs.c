/* Multipliers of a product of square matrices without forming it: QR
 * cycles (subspace iteration on the product, one Householder QR per
 * factor) split it into clusters of multipliers of different moduli, each
 * split further on its own blocks until it holds one or two multipliers
 * (read from the factors) or stops splitting (SLICOT's periodic
 * Hessenberg-triangular reduction and periodic QR, MB03VD and MB03WD).
 * The factors are scaled by powers of two and the multipliers read from
 * the periodic Schur form as mantissa and exponent, so that neither the
 * product nor its eigenvalues need to lie in the range of double.
 * docs/maps.md, "Multipliers". */
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

/* The QR cycles (see sc_product_eigs_compute) split the product where
 * the block of Q_0^T Q_m below the split has Frobenius norm at most
 * n eps: dropping it from the last factor changes that factor by at most
 * n eps ||A_{m-1}||, the backward error of the QR factorizations
 * themselves. */
#define PE_SPLIT_TOL(n) ((double)(n) * DBL_EPSILON)

/* QR cycles on a cluster of 3 or more multipliers before it goes to
 * MB03WD unsplit.  c cycles split multipliers whose moduli differ by more
 * than a factor of about eps^(-1/c) (90 for c = 8); what stays together
 * then lies within such ratios of its neighbours, and MB03WD, whose
 * products of diagonal entries and 2 x 2 standardization lose accuracy
 * only on strongly graded clusters, is given none. */
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
  double *r;      /* s x s x m, column-major: R_k of a cluster's cycle */
  double *q0, *q, *x, *wq; /* n x n each: Q_0, Q_k, A_k Q_k, Q_0^T Q_m */
  double *qtau;   /* n, the QR's reflectors */
  int *split;     /* n + 1: a cluster's split points */
  int *stack;     /* 2 n: clusters waiting (first index, size) */
  int nsplit;     /* clusters the last call finished */
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

/* v[0 .. len) times 2^e, exactly (as ldexp: only subnormal results
 * round): one multiplication by 2^e when that is a normal number, a
 * multiplication being several times faster than ldexp. */
static void scale_pow2(double *v, size_t len, int e) {
  if (e > DBL_MIN_EXP && e < DBL_MAX_EXP) {
    double f = ldexp(1.0, e);
    for (size_t i = 0; i < len; i++) v[i] *= f;
  } else {
    for (size_t i = 0; i < len; i++) v[i] = ldexp(v[i], e);
  }
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
  free(w->split);
  free(w->stack);
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
      m > (size_t)INT_MAX - n)
    return sc_fail(msg, SC_EINVAL,
                   "sc_product_eigs_work_alloc: n = %zu, m = %zu (n^2 m and "
                   "n + m at most %d)", n, m, INT_MAX);
  sc_product_eigs_work *w = calloc(1, sizeof *w);
  if (!w) goto fail;
  w->n = (int)n;
  w->m = (int)m;
  size_t nt = n > 1 ? n - 1 : 1;
  w->a = malloc(sizeof(double) * n * n * m);
  w->r = malloc(sizeof(double) * n * n * m);
  w->q0 = malloc(sizeof(double) * n * n);
  w->q = malloc(sizeof(double) * n * n);
  w->x = malloc(sizeof(double) * n * n);
  w->wq = malloc(sizeof(double) * n * n);
  w->qtau = malloc(sizeof(double) * n);
  w->split = malloc(sizeof(int) * (n + 1));
  w->stack = malloc(sizeof(int) * 2 * n);
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
      !w->split || !w->stack || !w->h || !w->tau || !w->dwork ||
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
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) h[i + (size_t)n * j] = a[(size_t)i * n + j];
  scale_pow2(h, (size_t)n * n, -e0); /* entries at most 1: no overflow */
  double ss = 0;
  for (int i = 0; i < n * n; i++) ss += h[i] * h[i];
  frexp(sqrt(ss), &e1);
  scale_pow2(h, (size_t)n * n, -e1);
  int e = e0 + e1;
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
    for (int q = 0; q < 4; q++) b[q] = c[q];
    scale_pow2(b, 4, -e);
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

/* Householder QR of the n x n column-major x in place (LAPACK's dgeqr2:
 * reflectors I - tau v v^T with v_j = 1 below the diagonal, tau in
 * w->qtau), then Q explicitly into q (dorg2r's backward accumulation).
 * Written out because the factors are small: LAPACK's dgeqrf and dorgqr
 * spent more time in their set-up (ilaenv, dnrm2's scaling) than in the
 * arithmetic for n <= 16 (measured: twice the time of the whole cycle).
 * The entries are at most 1 in modulus (the factors have Frobenius norm
 * below 1, Q_k is orthogonal), so the sums of squares cannot overflow;
 * a column below 1e-154 may underflow to a zero reflector, which leaves
 * entries below 1e-154 ||A_k|| out of R: far below the backward error. */
static void householder_qr(int n, double *x, double *tau, double *q) {
  for (int j = 0; j < n; j++) {
    double alpha = x[j + n * j], sigma = 0;
    for (int i = j + 1; i < n; i++) sigma += x[i + n * j] * x[i + n * j];
    tau[j] = 0;
    if (sigma == 0) continue;
    double norm = sqrt(alpha * alpha + sigma);
    double beta = alpha <= 0 ? norm : -norm;
    double f = 1 / (alpha - beta);
    tau[j] = (beta - alpha) / beta;
    x[j + n * j] = beta;
    for (int i = j + 1; i < n; i++) x[i + n * j] *= f;
    for (int c = j + 1; c < n; c++) {
      double *xc = x + n * c;
      double sum = xc[j];
      for (int i = j + 1; i < n; i++) sum += x[i + n * j] * xc[i];
      sum *= tau[j];
      xc[j] -= sum;
      for (int i = j + 1; i < n; i++) xc[i] -= sum * x[i + n * j];
    }
  }
  memset(q, 0, sizeof(double) * (size_t)n * n);
  for (int i = 0; i < n; i++) q[i + n * i] = 1;
  for (int j = n - 1; j >= 0; j--) {
    if (tau[j] == 0) continue;
    for (int c = j; c < n; c++) {
      double *qc = q + n * c;
      double sum = qc[j];
      for (int i = j + 1; i < n; i++) sum += x[i + n * j] * qc[i];
      sum *= tau[j];
      qc[j] -= sum;
      for (int i = j + 1; i < n; i++) qc[i] -= sum * x[i + n * j];
    }
  }
}

/* One QR cycle on the cluster [lo, lo + s) of the factors in w->a (their
 * diagonal s x s blocks F_k, leading dimension n) from w->q0:
 * F_k Q_k = Q_{k+1} R_k for k = 0 .. m - 1 (R_k into w->r, s x s each),
 * then W = Q_0^T Q_m in w->wq.  The cluster's product is
 *   F_{m-1} ... F_0 = Q_0 (W R_{m-1}) R_{m-2} ... R_0 Q_0^T,
 * per factor backward stable, and W is block upper triangular to
 * rounding wherever the cycle has split the multipliers' moduli apart
 * (the cycle is one step of subspace iteration on the product). */
static void qr_cycle(sc_product_eigs_work *w, int lo, int s) {
  int n = w->n;
  size_t nn = (size_t)n * n, ss = (size_t)s * s;
  memcpy(w->q, w->q0, sizeof(double) * ss);
  for (int k = 0; k < w->m; k++) {
    const double *a = w->a + nn * k + lo + (size_t)n * lo;
    double *r = w->r + ss * k;
    memset(w->x, 0, sizeof(double) * ss);
    for (int j = 0; j < s; j++) /* x = F_k q, column by column */
      for (int l = 0; l < s; l++) {
        double qlj = w->q[l + s * j];
        for (int i = 0; i < s; i++) w->x[i + s * j] += a[i + n * l] * qlj;
      }
    householder_qr(s, w->x, w->qtau, w->q);
    for (int j = 0; j < s; j++)
      for (int i = 0; i < s; i++) r[i + s * j] = i <= j ? w->x[i + s * j] : 0;
  }
  for (int j = 0; j < s; j++)
    for (int i = 0; i < s; i++) {
      double sum = 0;
      for (int l = 0; l < s; l++) sum += w->q0[l + s * i] * w->q[l + s * j];
      w->wq[i + s * j] = sum;
    }
}

/* The split points of W = w->wq (s x s) into w->split[0 .. c]: a split at
 * t where ||W[t:, :t]||_F <= PE_SPLIT_TOL(n).  Returns the number c of
 * parts. */
static int find_splits(sc_product_eigs_work *w, int s) {
  int c = 0, *split = w->split;
  split[c++] = 0;
  for (int t = 1; t < s; t++) {
    double ss = 0;
    for (int j = 0; j < t; j++)
      for (int i = t; i < s; i++) ss += w->wq[i + s * j] * w->wq[i + s * j];
    if (sqrt(ss) <= PE_SPLIT_TOL(w->n)) split[c++] = t;
  }
  split[c] = s;
  return c;
}

/* The cycle's transformation written back into the cluster's blocks of
 * w->a: F_k := R_k (k < m - 1) and, on the diagonal block d of each part,
 * F_{m-1}[d, d] := W[d, d] R_{m-1}[d, d] (W block upper triangular after
 * the split: what lies below its blocks is dropped, at most
 * PE_SPLIT_TOL ||F_{m-1}||). */
static void write_back(sc_product_eigs_work *w, int lo, int s, int parts) {
  int n = w->n, m = w->m;
  size_t nn = (size_t)n * n, ss = (size_t)s * s;
  for (int k = 0; k < m - 1; k++) {
    double *a = w->a + nn * k + lo + (size_t)n * lo;
    const double *r = w->r + ss * k;
    for (int j = 0; j < s; j++)
      for (int i = 0; i < s; i++) a[i + n * j] = r[i + s * j];
  }
  double *a = w->a + nn * (m - 1) + lo + (size_t)n * lo;
  const double *r = w->r + ss * (m - 1);
  for (int q = 0; q < parts; q++) {
    int d0 = w->split[q], d1 = w->split[q + 1];
    for (int j = d0; j < d1; j++)
      for (int i = d0; i < d1; i++) {
        double v = 0;
        for (int l = d0; l <= j; l++) v += w->wq[i + s * l] * r[l + s * j];
        a[i + n * j] = v;
      }
  }
}

/* log2 |det| / s of a triangular cluster factor, rounded: the scale that
 * makes the geometric mean of its eigenvalue moduli about 1, so that
 * MB03WD's products of diagonal entries stay near the multipliers' own
 * range.  The full factor (slot 0) and singular ones are scaled by their
 * largest entry instead. */
static int cluster_scale(const double *f, int s, int triangular) {
  xnum det = {1.0, 0};
  for (int i = 0; i < s && triangular; i++)
    det = xnum_mul(det, xnum_of(f[i + s * i]));
  if (triangular && det.mant != 0)
    return (int)lround(xnum_log(det) / (PE_LN2_HI * s));
  double fmax_ = 0;
  for (int i = 0; i < s * s; i++) fmax_ = fmax(fmax_, fabs(f[i]));
  int e = 0;
  if (fmax_ > 0) frexp(fmax_, &e);
  return e;
}

/* The periodic Schur form of the w->ns factors in w->h and the
 * multipliers read from it, base scale 2^scale.  Two factors' worth of
 * order 2 (slot 0 full, the others upper triangular) are read at once by
 * block_pair: MB03WD would only standardize the block through the
 * product of its factors (a rotation computed from the formed 2 x 2
 * product and applied to the factors), which is not backward stable when
 * the two multipliers differ much in modulus (on a random 50-factor
 * product with multipliers 4e7 and 1e-11 it returned 4e4 and 4e-6;
 * measured), while block_pair takes the larger from the product and the
 * smaller from the exact determinant. */
static int schur_read(sc_product_eigs_work *w, long scale, sc_msg *msg) {
  int s = w->ns;
  if (s == 2) { /* read from the factors: MB03WD would standardize it */
    block_pair(w, 0, scale);
    return SC_OK;
  }
  if (s > 2) {
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

/* The multipliers of the finished cluster [lo, lo + s): its blocks of
 * w->a into SLICOT's slots of w->h (slot m - 1 - k for factor k), each
 * scaled by a power of two, then schur_read. */
static int cluster_eigs(sc_product_eigs_work *w, int lo, int s, long scale,
                        sc_msg *msg) {
  int n = w->n, m = w->m;
  size_t nn = (size_t)n * n;
  w->lo = lo;
  w->ns = s;
  w->nsplit++;
  for (int k = 0; k < m; k++) {
    const double *a = w->a + nn * k + lo + (size_t)n * lo;
    double *f = w->h + (size_t)s * s * (size_t)(m - 1 - k);
    for (int j = 0; j < s; j++)
      for (int i = 0; i < s; i++) f[i + s * j] = a[i + n * j];
    int e = cluster_scale(f, s, k < m - 1);
    scale_pow2(f, (size_t)s * s, -e);
    scale += e;
  }
  return schur_read(w, scale, msg);
}

/* QR cycles on the cluster [lo, lo + s) until it splits (at most
 * PE_MAX_CYCLES; a cluster of 2 gets one, to make its factors
 * triangular), the transformation written back.  Returns the number of
 * parts, in w->split. */
static int cycle_cluster(sc_product_eigs_work *w, int lo, int s) {
  int parts = 1;
  memset(w->q0, 0, sizeof(double) * (size_t)s * s);
  for (int i = 0; i < s; i++) w->q0[i + s * i] = 1;
  for (int c = 0; c < PE_MAX_CYCLES; c++) {
    if (c > 0) { /* start from Q_m: the next step of the iteration */
      double *t = w->q0;
      w->q0 = w->q;
      w->q = t;
    }
    qr_cycle(w, lo, s);
    w->cycles++;
    parts = find_splits(w, s);
    if (parts > 1 || s <= 2) break;
  }
  write_back(w, lo, s, parts);
  return parts;
}

/* n >= 2: the clusters of the QR cycles, each split further by more
 * cycles until it has 2 multipliers or stops splitting, then read
 * (1 x 1, 2 x 2) or handed to MB03WD (3 or more).  After the first cycle
 * every factor but the last is triangular on the clusters' blocks. */
static int product_schur(sc_product_eigs_work *w, long scale, sc_msg *msg) {
  int n = w->n, *stack = w->stack, top = 0;
  w->cycles = 0;
  w->nsplit = 0;
  if (w->m == 1) { /* one factor: no product to split, MB03WD at once */
    memcpy(w->h, w->a, sizeof(double) * (size_t)n * n);
    w->lo = 0;
    w->ns = n;
    w->nsplit = 1;
    return schur_read(w, scale, msg);
  }
  stack[top++] = 0;
  stack[top++] = n;
  int first = 1;
  while (top > 0) {
    int s = stack[--top], lo = stack[--top];
    if (s <= 2 && !first) {
      int status = cluster_eigs(w, lo, s, scale, msg);
      if (status != SC_OK) return status;
      continue;
    }
    first = 0;
    int parts = cycle_cluster(w, lo, s);
    if (parts == 1) {
      int status = cluster_eigs(w, lo, s, scale, msg);
      if (status != SC_OK) return status;
      continue;
    }
    for (int q = parts - 1; q >= 0; q--) { /* the first part on top */
      stack[top++] = lo + w->split[q];
      stack[top++] = w->split[q + 1] - w->split[q];
    }
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
