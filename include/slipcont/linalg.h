/**
 * @file linalg.h
 * @brief Square linear systems A x = b through one interface with
 *        interchangeable backends: dense LAPACK LU and sparse KLU.
 *
 * A solver object is created for one sparsity pattern in compressed
 * sparse column (CSC) form; each factorization then takes the values in
 * pattern order.  The dense backend scatters them into a full matrix, the
 * sparse backend analyses the pattern once and refactors with the pivot
 * order of its first factorization on later calls (falling back to a
 * fresh pivoting factorization when that loses accuracy).  Matrices built
 * entry by entry convert from triplets with sc_csc_from_triplets().
 *
 * Backends are constant tables, like GSL's solver types:
 * `sc_linsolve_alloc(sc_linsolve_klu, ...)`.
 *
 * Thread safety: a solver object must not be used by two threads at once;
 * distinct objects share nothing.  All memory is taken by
 * sc_linsolve_alloc(): factor and solve never allocate beyond what the
 * backend library itself (KLU) does for its factors.
 *
 * The second section, multipliers of a product, gives the eigenvalues of
 * a product of square matrices without forming the product (the periodic
 * Schur form); docs/maps.md, "Multipliers".
 */
#ifndef SLIPCONT_LINALG_H
#define SLIPCONT_LINALG_H

#include "slipcont/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A backend: an opaque constant table. */
typedef struct sc_linsolve_type sc_linsolve_type;

/** Dense LU with partial pivoting (LAPACK dgetrf/dgetrs/dgecon). */
SC_API extern const sc_linsolve_type *const sc_linsolve_dense;
/** Sparse LU (SuiteSparse KLU): analyse once, refactor many times. */
SC_API extern const sc_linsolve_type *const sc_linsolve_klu;

/** @brief Backend by name ("dense", "klu"), or NULL. */
SC_API const sc_linsolve_type *sc_linsolve_type_find(const char *name);
/** @brief Name of a backend ("dense", "klu"). */
SC_API const char *sc_linsolve_type_name(const sc_linsolve_type *type);

/** A solver object for one pattern (opaque). */
typedef struct sc_linsolve sc_linsolve;

/**
 * @brief Create a solver for n x n matrices with the CSC pattern
 * (@p colptr, @p rowind).
 * @param type    sc_linsolve_dense or sc_linsolve_klu.
 * @param n       order, n >= 1.
 * @param colptr  n + 1 column pointers, colptr[0] = 0, nondecreasing;
 *                nnz = colptr[n].
 * @param rowind  nnz row indices in [0, n), strictly increasing within
 *                each column (sorted, no duplicates).
 * The pattern is copied; the caller keeps ownership of its arrays.
 * @return SC_OK; SC_EINVAL for a malformed pattern (the message names the
 *         first bad column); SC_ESING if the pattern is structurally
 *         singular (KLU); SC_ENOMEM.
 */
SC_API int sc_linsolve_alloc(const sc_linsolve_type *type, int n, const int *colptr,
                             const int *rowind, sc_linsolve **out, sc_msg *msg);

/**
 * @brief Create a solver for full n x n matrices: the pattern holds every
 * entry, so the values of sc_linsolve_factor() are the matrix in
 * column-major order, a[i + n j] = A(i, j).
 * @return as sc_linsolve_alloc().
 */
SC_API int sc_linsolve_alloc_full(const sc_linsolve_type *type, int n,
                                  sc_linsolve **out, sc_msg *msg);

/** @brief Release @p s; NULL is accepted. */
SC_API void sc_linsolve_free(sc_linsolve *s);

/**
 * @brief Factor the matrix whose nonzero values, in pattern order, are
 * @p val (nnz entries; read only, not kept).
 *
 * The first call makes a full factorization with pivoting; with KLU later
 * calls refactor with the same pivot sequence and fall back to a full
 * factorization when the refactored pivots are singular or their ratio
 * min |U_kk| / max |U_kk| drops to DBL_EPSILON.
 * @return SC_OK; SC_ENONFINITE if a value is NaN or infinite; SC_ESING if
 *         the matrix is numerically singular (an exact zero pivot, or a
 *         pivot ratio min |U_kk| / max |U_kk| <= DBL_EPSILON), with the
 *         pivot and the ratio in the message; SC_ENOMEM.  After a failure
 *         the object holds no factorization.
 */
SC_API int sc_linsolve_factor(sc_linsolve *s, const double *val, sc_msg *msg);

/**
 * @brief Solve A x = b with the current factorization; @p b (n entries)
 * is overwritten by x.
 * @return SC_OK; SC_EINVAL if there is no valid factorization;
 *         SC_ENONFINITE if the solution is not finite.
 */
SC_API int sc_linsolve_solve(sc_linsolve *s, double *b, sc_msg *msg);

/**
 * @brief Determinant of the factored matrix as a sign and a logarithm,
 * det A = sign exp(logabs), which neither overflows nor underflows.  From
 * the LU factors: the product of the pivots, the signs of the row and
 * column permutations and (KLU) the row scale factors.
 * @param sign   +1 or -1 (0 never occurs: singular matrices are refused).
 * @param logabs log |det A|.
 * @return SC_OK, or SC_EINVAL without a valid factorization.
 */
SC_API int sc_linsolve_det(const sc_linsolve *s, int *sign, double *logabs);

/**
 * @brief Estimate of the reciprocal condition number in the 1-norm,
 * 1 / (||A||_1 ||A^-1||_1): dense from LAPACK dgecon, KLU from
 * klu_condest.  Costs a few solves.
 * @return SC_OK, or SC_EINVAL without a valid factorization.
 */
SC_API int sc_linsolve_rcond(sc_linsolve *s, double *rcond, sc_msg *msg);

/**
 * @brief Crude reciprocal condition number min |U_kk| / max |U_kk| of the
 * current factors (free: read from the factors).
 * @return SC_OK, or SC_EINVAL without a valid factorization.
 */
SC_API int sc_linsolve_pivot_ratio(const sc_linsolve *s, double *ratio);

/** The backend of @p s. */
SC_API const sc_linsolve_type *sc_linsolve_get_type(const sc_linsolve *s);
/** Order n. */
SC_API int sc_linsolve_n(const sc_linsolve *s);
/** Number of entries of the pattern. */
SC_API int sc_linsolve_nnz(const sc_linsolve *s);
/** Full factorizations (with pivoting) made so far. */
SC_API unsigned long sc_linsolve_nfactor(const sc_linsolve *s);
/** Refactorizations reusing a pivot sequence (KLU) made so far. */
SC_API unsigned long sc_linsolve_nrefactor(const sc_linsolve *s);
/** Solves made so far. */
SC_API unsigned long sc_linsolve_nsolve(const sc_linsolve *s);

/**
 * @brief Convert a triplet pattern (ti[k], tj[k]), k < nt, of an n x n
 * matrix to CSC.  Duplicates are merged: their values add up in
 * sc_csc_scatter().
 * @param colptr out: n + 1 entries.
 * @param rowind out: up to nt entries (nnz are used).
 * @param map    out: nt entries; map[k] is the CSC slot of triplet k.
 * @param nnz    out: number of distinct entries.
 * Allocates a temporary workspace of n + 1 ints and frees it.
 * @return SC_OK; SC_EINVAL for n < 1, nt < 0 or an index outside [0, n);
 *         SC_ENOMEM.
 */
SC_API int sc_csc_from_triplets(int n, int nt, const int *ti, const int *tj,
                                int *colptr, int *rowind, int *map, int *nnz,
                                sc_msg *msg);

/**
 * @brief CSC values from triplet values: val[map[k]] += tval[k] after
 * zeroing the @p nnz entries of @p val.
 */
SC_API void sc_csc_scatter(int nt, const int *map, const double *tval, int nnz,
                           double *val);

/* Multipliers of a product -------------------------------------------- */

/**
 * Workspace of sc_product_eigs_compute() for products of m factors of
 * order n (opaque): with it, repeated calls allocate nothing.
 */
typedef struct sc_product_eigs_work sc_product_eigs_work;

/**
 * @brief Workspace for products of @p m factors of order @p n: about
 * 3 m n^2 + 6 n^2 + 2 m doubles.
 * @param n  order of the factors, n >= 1.
 * @param m  number of factors (the period of the orbit), m >= 1.
 * @return SC_OK; SC_EINVAL for n or m out of range (n, m >= 1; n^2 m and
 *         n + m must fit in an int, the index type of the Fortran library);
 *         SC_ENOMEM.
 */
SC_API int sc_product_eigs_work_alloc(size_t n, size_t m,
                                      sc_product_eigs_work **out, sc_msg *msg);

/** @brief Release @p w; NULL is accepted. */
SC_API void sc_product_eigs_work_free(sc_product_eigs_work *w);

/**
 * @brief Eigenvalues (multipliers) of the product P = A[m-1] ... A[1] A[0]
 * of the m factors of @p w, computed without forming P.
 *
 * QR cycles, A_k Q_k = Q_{k+1} R_k (one step of subspace iteration on P
 * per cycle), split the product into clusters of multipliers whose
 * moduli differ; each cluster is split further by more cycles on its own
 * blocks until it has one or two multipliers, which are read from the
 * factors' diagonal (2 x 2 blocks), or stops splitting after 8 cycles
 * (multipliers of close modulus), which then goes to the periodic QR
 * algorithm (SLICOT MB03VD, MB03WD).  The result is a periodic real Schur
 * form: orthogonal Z_k with Z_{k+1}^T A[k] Z_k = T_k (Z_m = Z_0), T_k
 * triangular but one quasi-triangular, so that each multiplier is a
 * product of diagonal entries (of 2 x 2 blocks for a complex pair).
 * Every factor is scaled
 * by a power of two (exact) and the products are accumulated as mantissa
 * and exponent, so moduli far beyond the range of double (a 1000-factor
 * product with |mu| = 1e602 beside 1e-301) come out right in @p logabs;
 * re and im then overflow to +-inf or underflow to 0 as the values they
 * are.  The computed multipliers are exact for factors A[k] + E[k] with
 * ||E[k]|| of order n eps ||A[k]||, so a multiplier whose factors'
 * diagonal entries are not small against their factor's norm has a
 * relative error of order m n eps, however small it is; forming P first
 * gives only an absolute error eps ||P|| (docs/maps.md, "Multipliers").
 *
 * Order: by decreasing modulus (decreasing logabs); ties by decreasing
 * real part; a complex pair adjacent, its positive imaginary part first.
 * n = 1 is the plain product (no periodic QR).
 *
 * @param w       workspace from sc_product_eigs_work_alloc() (n, m).
 * @param A       m pointers; A[k] is the n x n factor applied k-th, row
 *                major as sc_mapn_value.J: A[k][i n + j] = d f_i / d x_j
 *                at the k-th point of the orbit.  Not modified.
 * @param re, im  out: n real and imaginary parts (either may be NULL).
 * @param logabs  out (may be NULL): n values log |mu| (natural log;
 *                -HUGE_VAL for a zero multiplier).
 * @param arg     out (may be NULL): n angles of mu in (-pi, pi] (0 for
 *                a zero multiplier, pi for a negative real one).
 * @return SC_OK; SC_EINVAL for a NULL @p w, @p A or factor;
 *         SC_ENONFINITE for a NaN or infinite entry (the message names the
 *         factor and the entry); SC_ENOCONV if the periodic QR iteration
 *         did not converge (30 n sweeps).  Not thread safe on one @p w;
 *         distinct workspaces share nothing.
 */
SC_API int sc_product_eigs_compute(sc_product_eigs_work *w,
                                   const double *const *A, double *re,
                                   double *im, double *logabs, double *arg,
                                   sc_msg *msg);

/** QR cycles made by the last sc_product_eigs_compute() on @p w, over all
 *  clusters (0 for n = 1, m = 1 or a zero factor). */
SC_API int sc_product_eigs_ncycles(const sc_product_eigs_work *w);
/** Clusters the last call finished: read as 1 x 1 or 2 x 2 blocks or
 *  handed to MB03WD (1 for n = 1 or m = 1, 0 for a zero factor). */
SC_API int sc_product_eigs_nclusters(const sc_product_eigs_work *w);

/**
 * @brief sc_product_eigs_compute() with a workspace taken and released
 * for this call: the multipliers of A[m-1] ... A[0] (n x n, row major) as
 * @p re and @p im (n each), sorted as there.
 * @return as sc_product_eigs_compute() and sc_product_eigs_work_alloc().
 */
SC_API int sc_product_eigs(size_t n, size_t m, const double *const *A,
                           double *re, double *im, sc_msg *msg);

#ifdef __cplusplus
}
#endif
#endif
