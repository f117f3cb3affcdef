/* Normal-form coefficients of a fixed point of an n-dimensional map at a
 * fold, a flip and a Neimark-Sacker bifurcation from its exact
 * derivatives (docs/maps.md, "Normal forms").  The critical eigenvectors
 * come from LAPACK's dgeev (right and left vectors of A); the resolvents
 * (I - A)^(-1) and (mu^2 I - A)^(-1) from LAPACK's LU (zgetrf), its work
 * on the stack (n <= SC_NF_MAXDIM). */
#include <complex.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "dense_impl.h"
#include "nf_impl.h"

extern void dgeev_(const char *jobvl, const char *jobvr, const int *n,
                   double *a, const int *lda, double *wr, double *wi,
                   double *vl, const int *ldvl, double *vr, const int *ldvr,
                   double *work, const int *lwork, int *info);

/* dgeev's workspace: at least 4 n with vectors; 34 n leaves room for its
 * blocked Hessenberg reduction at every n <= SC_NF_MAXDIM. */
#define NF_LWORK (34 * NF_N)

/* A pivot below this times the matrix's largest entry is zero to working
 * precision: the matrix is singular (a resonance), and the solution would
 * be rounding noise. */
static const double NF_SING = 64 * DBL_EPSILON;

int nf_check(const sc_nf_jet *g, int need_T, const char *who, sc_msg *msg) {
  if (!g || !g->A || !g->H || (need_T && !g->T))
    return sc_fail(msg, SC_EINVAL, "%s: NULL jet or derivative array (A, H%s)",
                   who, need_T ? ", T" : "");
  if (g->n < 1 || g->n > SC_NF_MAXDIM)
    return sc_fail(msg, SC_EINVAL, "%s: dimension %zu (valid: [1, %d])", who,
                   g->n, SC_NF_MAXDIM);
  return SC_OK;
}

int nf_eig(size_t n, const double *A, int vectors, nf_eig_t *e, sc_msg *msg) {
  double a[NF_N * NF_N], work[NF_LWORK];
  int nn = (int)n, lw = NF_LWORK, info = 0, one = 1;
  for (size_t i = 0; i < n; i++) /* column-major copy */
    for (size_t j = 0; j < n; j++)
      a[j * n + i] = A[i * n + j];
  for (size_t i = 0; i < n * n; i++)
    if (!isfinite(a[i]))
      return sc_fail(msg, SC_EINVAL, "normal form: non-finite Jacobian entry");
  dgeev_(vectors ? "V" : "N", vectors ? "V" : "N", &nn, a, &nn, e->wr, e->wi,
         e->vl, vectors ? &nn : &one, e->vr, vectors ? &nn : &one, work, &lw,
         &info);
  if (info != 0)
    return sc_fail(msg, SC_EINTERNAL,
                   "normal form: the eigenvalue solver failed (dgeev info %d)",
                   info);
  e->n = n;
  return SC_OK;
}

/* Column j of dgeev's V (column-major) as a complex vector: for a pair
 * (wi[j] > 0 at j, < 0 at j + 1) the vectors are V_j +- i V_(j+1). */
void nf_eig_vec(const nf_eig_t *e, const double *V, size_t j,
                double complex *v) {
  size_t n = e->n;
  for (size_t i = 0; i < n; i++) {
    if (e->wi[j] == 0)
      v[i] = V[j * n + i];
    else if (e->wi[j] > 0)
      v[i] = V[j * n + i] + I * V[(j + 1) * n + i];
    else
      v[i] = V[(j - 1) * n + i] - I * V[j * n + i];
  }
}

/* Index of the real eigenvalue nearest @p target, or -1 if none. */
static int nearest_real(const nf_eig_t *e, double target) {
  int best = -1;
  for (size_t j = 0; j < e->n; j++)
    if (e->wi[j] == 0 &&
        (best < 0 || fabs(e->wr[j] - target) < fabs(e->wr[best] - target)))
      best = (int)j;
  return best;
}

/* Index of the eigenvalue with im > 0 nearest @p mu (mu NULL: modulus
 * nearest 1), or -1 if none. */
static int nearest_pair(const nf_eig_t *e, const double *mu) {
  int best = -1;
  double bd = HUGE_VAL;
  for (size_t j = 0; j < e->n; j++) {
    if (!(e->wi[j] > 0)) continue;
    double d = mu ? hypot(e->wr[j] - mu[0], e->wi[j] - fabs(mu[1]))
                  : fabs(hypot(e->wr[j], e->wi[j]) - 1);
    if (d < bd) bd = d, best = (int)j;
  }
  return best;
}

int nf_resolvent(size_t n, const double *A, double complex z,
                 const double complex *rhs, double complex *x) {
  double complex M[NF_N * NF_N];
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      M[i * n + j] = (i == j ? z : 0) - A[i * n + j];
  memcpy(x, rhs, n * sizeof *x);
  int ipiv[NF_N];
  return sc_dense_zsolve(n, M, x, ipiv, NF_SING);
}

void nf_B(size_t n, const double *H, const double complex *u,
          const double complex *v, double complex *out) {
  for (size_t i = 0; i < n; i++) {
    double complex s = 0;
    for (size_t j = 0; j < n; j++) {
      const double *h = H + (i * n + j) * n;
      double complex t = 0;
      for (size_t k = 0; k < n; k++) t += h[k] * v[k];
      s += u[j] * t;
    }
    out[i] = s;
  }
}

void nf_C(size_t n, const double *T, const double complex *u,
          const double complex *v, const double complex *w,
          double complex *out) {
  for (size_t i = 0; i < n; i++) {
    double complex s = 0;
    for (size_t j = 0; j < n; j++)
      for (size_t k = 0; k < n; k++) {
        const double *t = T + ((i * n + j) * n + k) * n;
        double complex r = 0;
        for (size_t l = 0; l < n; l++) r += t[l] * w[l];
        s += u[j] * v[k] * r;
      }
    out[i] = s;
  }
}

double complex nf_dot(size_t n, const double complex *p,
                      const double complex *x) {
  double complex s = 0;
  for (size_t i = 0; i < n; i++) s += conj(p[i]) * x[i];
  return s;
}

/* Write the multiplier and the vectors into @p out. */
static void store(size_t n, double complex mu, const double complex *q,
                  const double complex *p, sc_nf *out) {
  out->mu[0] = creal(mu), out->mu[1] = cimag(mu);
  out->theta = fabs(carg(mu));
  memset(out->q, 0, sizeof out->q);
  memset(out->p, 0, sizeof out->p);
  for (size_t i = 0; i < n; i++) {
    out->q[i] = creal(q[i]), out->q[n + i] = cimag(q[i]);
    out->p[i] = creal(p[i]), out->p[n + i] = cimag(p[i]);
  }
}

int nf_real_vectors(const sc_nf_jet *g, double target, const double *qref,
                    double *mu, double complex *q, double complex *p,
                    const char *who, sc_msg *msg) {
  size_t n = g->n;
  nf_eig_t e;
  int st = nf_eig(n, g->A, 1, &e, msg);
  if (st) return st;
  int j = nearest_real(&e, target);
  if (j < 0)
    return sc_fail(msg, SC_EINVAL, "%s: no real multiplier near %g", who,
                   target);
  nf_eig_vec(&e, e.vr, (size_t)j, q);
  nf_eig_vec(&e, e.vl, (size_t)j, p);
  double nq = 0, big = 0, ref = 0;
  size_t ib = 0;
  for (size_t i = 0; i < n; i++) {
    nq += creal(q[i]) * creal(q[i]);
    if (fabs(creal(q[i])) > big) big = fabs(creal(q[i])), ib = i;
    if (qref) ref += qref[i] * creal(q[i]);
  }
  double sgn = (qref ? ref < 0 : creal(q[ib]) < 0) ? -1 : 1;
  double complex s = 0, pn = 0;
  for (size_t i = 0; i < n; i++) {
    q[i] = sgn * creal(q[i]) / sqrt(nq);
    s += creal(p[i]) * creal(q[i]);
    pn += creal(p[i]) * creal(p[i]);
  }
  /* p^T q = 0 for unit p and q: 1 is not a simple multiplier (R1, or R2
   * for a flip) and the centre manifold is not one-dimensional. */
  if (!(fabs(creal(s)) > NF_SING * sqrt(creal(pn))))
    return sc_fail(msg, SC_ESING,
                   "%s: left and right eigenvectors orthogonal (a double "
                   "multiplier %g)",
                   who, e.wr[j]);
  for (size_t i = 0; i < n; i++) p[i] = creal(p[i]) / creal(s);
  *mu = e.wr[j];
  return SC_OK;
}

int sc_nf_fold(const sc_nf_jet *g, const double *qref, sc_nf *out,
               sc_msg *msg) {
  int st = nf_check(g, 0, "sc_nf_fold", msg);
  if (st) return st;
  size_t n = g->n;
  double complex q[NF_N], p[NF_N], b[NF_N];
  double mu;
  st = nf_real_vectors(g, 1, qref, &mu, q, p, "sc_nf_fold", msg);
  if (st) return st;
  nf_B(n, g->H, q, q, b);
  out->coef = 0.5 * creal(nf_dot(n, p, b));
  store(n, mu, q, p, out);
  return SC_OK;
}

int nf_flip_coef(const sc_nf_jet *g, const double complex *q,
                 const double complex *p, double *b) {
  size_t n = g->n;
  double complex h2[NF_N], r[NF_N], c3[NF_N], br[NF_N];
  nf_B(n, g->H, q, q, h2);
  int st = nf_resolvent(n, g->A, 1, h2, r);
  if (st) return st;
  nf_C(n, g->T, q, q, q, c3);
  nf_B(n, g->H, q, r, br);
  for (size_t i = 0; i < n; i++) c3[i] += 3 * br[i];
  *b = creal(nf_dot(n, p, c3)) / 6;
  return SC_OK;
}

int sc_nf_flip(const sc_nf_jet *g, sc_nf *out, sc_msg *msg) {
  int st = nf_check(g, 1, "sc_nf_flip", msg);
  if (st) return st;
  double complex q[NF_N], p[NF_N];
  double mu;
  st = nf_real_vectors(g, -1, NULL, &mu, q, p, "sc_nf_flip", msg);
  if (st) return st;
  if (nf_flip_coef(g, q, p, &out->coef))
    return sc_fail(msg, SC_ESING,
                   "sc_nf_flip: I - A singular (a multiplier 1 beside -1: "
                   "fold-flip)");
  store(g->n, mu, q, p, out);
  return SC_OK;
}

int nf_ns_coef(const sc_nf_jet *g, double complex mu, const double complex *q,
               const double complex *p, double *d) {
  size_t n = g->n;
  double complex qb[NF_N], h20[NF_N], h11[NF_N], r20[NF_N], r11[NF_N];
  double complex c[NF_N], t[NF_N];
  for (size_t i = 0; i < n; i++) qb[i] = conj(q[i]);
  nf_B(n, g->H, q, q, h20);
  nf_B(n, g->H, q, qb, h11);
  int st = nf_resolvent(n, g->A, 1, h11, r11);
  if (!st) st = nf_resolvent(n, g->A, mu * mu, h20, r20);
  if (st) return st;
  nf_C(n, g->T, q, q, qb, c);
  nf_B(n, g->H, q, r11, t);
  for (size_t i = 0; i < n; i++) c[i] += 2 * t[i];
  nf_B(n, g->H, qb, r20, t);
  for (size_t i = 0; i < n; i++) c[i] += t[i];
  /* e^(-i theta) = conj(mu) / |mu|: the same on the curve, smooth off it */
  *d = 0.5 * creal(conj(mu) / cabs(mu) * nf_dot(n, p, c));
  return SC_OK;
}

int nf_pair_vectors(const sc_nf_jet *g, const double *target,
                    double complex *mu, double complex *q, double complex *p,
                    const char *who, sc_msg *msg) {
  size_t n = g->n;
  nf_eig_t e;
  int st = nf_eig(n, g->A, 1, &e, msg);
  if (st) return st;
  int j = nearest_pair(&e, target);
  if (j < 0)
    return sc_fail(msg, SC_EINVAL, "%s: no complex multiplier", who);
  nf_eig_vec(&e, e.vr, (size_t)j, q);
  nf_eig_vec(&e, e.vl, (size_t)j, p);
  *mu = e.wr[j] + I * e.wi[j];
  /* <q, q> = 1/2: z is the amplitude of the real orbit x0 + 2 Re(z q) */
  double nq = sqrt(2 * creal(nf_dot(n, q, q)));
  for (size_t i = 0; i < n; i++) q[i] /= nq;
  double complex s = nf_dot(n, p, q);
  double pn = sqrt(creal(nf_dot(n, p, p)));
  if (!(cabs(s) > NF_SING * pn * sqrt(0.5)))
    return sc_fail(msg, SC_ESING,
                   "%s: left and right eigenvectors orthogonal (a double "
                   "multiplier %g%+gi)",
                   who, e.wr[j], e.wi[j]);
  for (size_t i = 0; i < n; i++) p[i] /= conj(s); /* <p, q> = 1 */
  return SC_OK;
}

int sc_nf_ns(const sc_nf_jet *g, const double *mu, sc_nf *out, sc_msg *msg) {
  int st = nf_check(g, 1, "sc_nf_ns", msg);
  if (st) return st;
  double complex q[NF_N], p[NF_N], m;
  st = nf_pair_vectors(g, mu, &m, q, p, "sc_nf_ns", msg);
  if (st) return st;
  if (nf_ns_coef(g, m, q, p, &out->coef))
    return sc_fail(msg, SC_ESING,
                   "sc_nf_ns: I - A or mu^2 I - A singular (a strong "
                   "resonance: mu = %g%+gi)",
                   creal(m), cimag(m));
  store(g->n, m, q, p, out);
  return SC_OK;
}

/* Order of the multipliers: decreasing modulus, a pair together (larger
 * |im| first among equal moduli), its im > 0 member first. */
static int before(double ra, double ia, double rb, double ib) {
  double ma = hypot(ra, ia), mb = hypot(rb, ib);
  if (ma != mb) return ma > mb;
  if (fabs(ia) != fabs(ib)) return fabs(ia) > fabs(ib);
  return ia > ib;
}

int sc_nf_multipliers(size_t n, const double *A, double *re, double *im,
                      sc_msg *msg) {
  if (n < 1 || n > SC_NF_MAXDIM || !A)
    return sc_fail(msg, SC_EINVAL,
                   "sc_nf_multipliers: dimension %zu (valid: [1, %d]) or "
                   "NULL matrix",
                   n, SC_NF_MAXDIM);
  nf_eig_t e;
  int st = nf_eig(n, A, 0, &e, msg);
  if (st) return st;
  for (size_t i = 0; i < n; i++) { /* insertion sort: n <= 16 */
    double r = e.wr[i], m = e.wi[i];
    size_t k = i;
    for (; k > 0 && before(r, m, re[k - 1], im[k - 1]); k--)
      re[k] = re[k - 1], im[k] = im[k - 1];
    re[k] = r, im[k] = m;
  }
  return SC_OK;
}
