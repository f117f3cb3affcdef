/* Private to continuation/: the pieces of the normal forms
 * (continuation/normal_form.c) that the codimension-two tests of the
 * n-dimensional curves reuse.  Complex vectors are C99 double complex. */
#ifndef SC_NF_IMPL_H
#define SC_NF_IMPL_H

#include <complex.h>

#include "slipcont/normal_form.h"

#define NF_N SC_NF_MAXDIM

/* Eigenvalues (wr, wi) and, when asked, dgeev's right (vr) and left (vl)
 * vectors of an n x n matrix, column-major. */
typedef struct {
  size_t n;
  double wr[NF_N], wi[NF_N];
  double vl[NF_N * NF_N], vr[NF_N * NF_N];
} nf_eig_t;

int nf_check(const sc_nf_jet *g, int need_T, const char *who, sc_msg *msg);
int nf_eig(size_t n, const double *A, int vectors, nf_eig_t *e, sc_msg *msg);
void nf_eig_vec(const nf_eig_t *e, const double *V, size_t j,
                double complex *v);
/* x = (z I - A)^(-1) rhs; SC_ESING for a pivot of z I - A at or below
 * NF_SING times its largest entry. */
int nf_resolvent(size_t n, const double *A, double complex z,
                 const double complex *rhs, double complex *x);
void nf_B(size_t n, const double *H, const double complex *u,
          const double complex *v, double complex *out);
void nf_C(size_t n, const double *T, const double complex *u,
          const double complex *v, const double complex *w,
          double complex *out);
/* <p, x> = sum conj(p_i) x_i */
double complex nf_dot(size_t n, const double complex *p,
                      const double complex *x);
/* q (|q| = 1, oriented by qref or its largest component) and p (p^T q =
 * 1) of the real multiplier nearest target, which goes to *mu. */
int nf_real_vectors(const sc_nf_jet *g, double target, const double *qref,
                    double *mu, double complex *q, double complex *p,
                    const char *who, sc_msg *msg);
/* q (<q, q> = 1/2) and p (<p, q> = 1) of the pair nearest target (NULL:
 * modulus nearest 1). */
int nf_pair_vectors(const sc_nf_jet *g, const double *target,
                    double complex *mu, double complex *q, double complex *p,
                    const char *who, sc_msg *msg);
/* The flip and NS coefficients for given vectors; SC_ESING for a
 * singular resolvent. */
int nf_flip_coef(const sc_nf_jet *g, const double complex *q,
                 const double complex *p, double *b);
int nf_ns_coef(const sc_nf_jet *g, double complex mu, const double complex *q,
               const double complex *p, double *d);

#endif
