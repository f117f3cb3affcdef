/* Private to the library: small dense square systems A x = b whose
 * matrix is row major, as the layers' Jacobians are, by LAPACK's LU with
 * partial pivoting (dgetrf/dgetrs, zgetrf/zgetrs), each caller with its
 * own named criterion for a singular matrix.  Defined in
 * continuation/linsolve_dense.c beside the dense backend of linalg.h,
 * which serves matrices given by a pattern. */
#ifndef SC_DENSE_IMPL_H
#define SC_DENSE_IMPL_H

#include <complex.h>
#include <stddef.h>

/* Solve the n x n row-major A x = b: A is destroyed (it ends as its LU
 * factors, column major), b becomes x;
 * @p ipiv is room for n pivot indices.  SC_ESING when a pivot of the
 * factorization is at or below @p sing times the largest |A_ij| (the
 * caller's named criterion: no significant digit left in that pivot),
 * A and b then undefined; SC_EINVAL for n beyond an int. */
int sc_dense_solve(size_t n, double *A, double *b, int *ipiv, double sing);

/* The same for complex A and b (zgetrf/zgetrs); LAPACK picks each pivot
 * by |re| + |im|, the test compares moduli. */
int sc_dense_zsolve(size_t n, double complex *A, double complex *b, int *ipiv,
                    double sing);

#endif
