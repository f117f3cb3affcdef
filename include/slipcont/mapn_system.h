/**
 * @file mapn_system.h
 * @brief Defining systems for fixed points of an n-dimensional map
 *        iterate g = f^m(x, p) (the continuation layer): the fixed-point
 *        system with its test functions (LP, PD, NS, BP), and the
 *        minimally augmented systems of the fold (LP), flip (PD),
 *        Neimark-Sacker (NS) and branch point (BP), with exact Jacobians
 *        (docs/maps.md, "Branches").
 *
 * Nothing here knows a model: g comes through a callback giving g, g_x,
 * g_p and on request g_xx, g_xp as arrays, row-major with the index
 * conventions of sc_mapn_value (models.h).  A system is a workspace
 * (its bordering vectors and scratch arrays): one per thread.
 *
 * Unknowns: u = (x (n), e (ne), p_free (nfree)), with e the extra
 * unknowns of the system (NS: kappa = cos theta; BP: the unfolding mu;
 * none otherwise) and the free parameters last, so that a system with
 * one more unknown than equations is a continuation problem whose
 * parameter u[last] is the last free parameter.  Equations:
 *  - SC_MAPN_FIXED: g - x (n); with nfree = 1, a branch of fixed points;
 *  - SC_MAPN_FOLD, SC_MAPN_FLIP: (g - x, s) (n + 1), s the last component
 *    of the solution of [[g_x -+ I, b], [c^T, 0]] (v; s) = (0; 1): zero
 *    exactly where g_x has the multiplier +1 (-1); nfree = 1: the point
 *    (square), nfree = 2: the curve;
 *  - SC_MAPN_NS (n >= 2): (g - x, G_a, G_b) (n + 2), u gains kappa:
 *    G (2 x 2) from [[g_x^2 - 2 kappa g_x + I, P], [Q^T, 0]] (V; G) =
 *    (0; I_2), G_a, G_b two of its entries (chosen by
 *    sc_mapn_system_update()); zero where g_x has a pair of multipliers
 *    mu, 1 / mu with mu + 1 / mu = 2 kappa: a Neimark-Sacker point for
 *    |kappa| < 1 (mu = e^{i theta}, kappa = cos theta), a neutral saddle
 *    for |kappa| > 1;
 *  - SC_MAPN_BP (nfree = 1 only): (g - x + mu b, s, w^T g_p) (n + 2), u
 *    gains mu: s the fold's bordered function, w its left null vector;
 *    at a branch point of the fixed-point branch mu = 0 (the unfolding
 *    term makes the point a regular solution).
 */
#ifndef SLIPCONT_MAPN_SYSTEM_H
#define SLIPCONT_MAPN_SYSTEM_H

#include <stddef.h>

#include "slipcont/common.h"
#include "slipcont/continuation.h"
#include "slipcont/curve_system.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest state dimension of a defining system (the size for which
 * models keep second derivative tensors, SC_DIM_TENSOR in models.h). */
#define SC_MAPN_MAXDIM 16
/** Most parameters of g. */
#define SC_MAPN_MAXPARAM 8

/**
 * g = f^m and its derivatives at (x, p), in arrays owned by the system,
 * row-major with sc_mapn_value's conventions (i: component of g; j, k:
 * of x; q: parameter):
 *  - g[i];
 *  - gx[i n + j] = dg_i / dx_j (order >= 1);
 *  - gp[q n + i] = dg_i / dp_q (order >= 1);
 *  - gxx[(i n + j) n + k] = d2 g_i / dx_j dx_k (order 2);
 *  - gxp[(q n + i) n + j] = d2 g_i / dx_j dp_q (order 2).
 */
typedef struct {
  double *g;   /**< n */
  double *gx;  /**< n x n */
  double *gp;  /**< np x n */
  double *gxx; /**< n^3 */
  double *gxp; /**< np n^2 */
} sc_mapn_jet;

/**
 * Evaluate g at @p x (n values) and @p p (all np parameters) up to
 * derivative order @p order (0, 1 or 2) into @p jet.  Returns 0, > 0
 * (recoverable: outside the domain) or < 0 (fatal), as the continuation
 * callbacks.
 */
typedef int (*sc_mapn_fn)(const double *x, const double *p, int order,
                          sc_mapn_jet *jet, void *user);

/** Which defining system (see the file's description). */
typedef enum {
  SC_MAPN_FIXED = 0, /**< g = x */
  SC_MAPN_FOLD,      /**< g = x, multiplier +1 (LP) */
  SC_MAPN_FLIP,      /**< g = x, multiplier -1 (PD) */
  SC_MAPN_NS,        /**< g = x, multipliers e^{+-i theta} (NS) */
  SC_MAPN_BP,        /**< a branch point of g = x in one parameter */
} sc_mapn_kind;

/** The test functions of SC_MAPN_FIXED, in this order. */
enum {
  SC_MAPN_TEST_LP = 0, /**< det(g_x - I), scaled: multiplier +1 */
  SC_MAPN_TEST_PD,     /**< det(g_x + I), scaled: multiplier -1 */
  SC_MAPN_TEST_NS,     /**< det(g_x (.) g_x - I), scaled: a pair with
                            mu1 mu2 = 1 (NS or neutral saddle); constant 1
                            for n = 1 */
  SC_MAPN_TEST_BP,     /**< det [F_u; t^T], scaled: a branch point */
  SC_MAPN_NTEST
};

/** What a system is: filled by the caller, copied by
 * sc_mapn_system_alloc(). */
typedef struct {
  sc_mapn_fn fn;       /**< g and its derivatives */
  void *user;          /**< passed to fn */
  sc_mapn_kind kind;   /**< which system */
  size_t n;            /**< state dimension, 1..SC_MAPN_MAXDIM */
  size_t np;           /**< parameters of g, 1..SC_MAPN_MAXPARAM */
  double p[SC_MAPN_MAXPARAM]; /**< parameter values; the free ones are
                                   replaced by u's entries */
  size_t nfree;        /**< free parameters: 1 or 2 (BP: 1) */
  int ifree[2];        /**< their indices in p */
} sc_mapn_def;

/** A defining system with its workspace (opaque). */
typedef struct sc_mapn_system sc_mapn_system;

/**
 * @brief Create the system @p def (copied).  Its bordering vectors are
 * the unit vectors e_1 (e_1, e_2 for NS) until sc_mapn_system_init() or
 * sc_mapn_system_update() sets them at a point.
 * @return SC_OK; SC_EINVAL (NULL fn, n or np out of range, NS with
 *         n = 1, nfree not 1 or 2, BP with nfree = 2, bad or equal free
 *         indices, unknown kind) naming the field; SC_ENOMEM.
 */
SC_API int sc_mapn_system_alloc(const sc_mapn_def *def, sc_mapn_system **out,
                                sc_msg *msg);
/** @brief Release @p s; NULL is accepted. */
SC_API void sc_mapn_system_free(sc_mapn_system *s);

/** Number of unknowns n + ne + nfree. */
SC_API size_t sc_mapn_system_nunknowns(const sc_mapn_system *s);
/** Number of equations (n, n + 1 or n + 2). */
SC_API size_t sc_mapn_system_nequations(const sc_mapn_system *s);
/** Number of extra unknowns ne between x and the free parameters. */
SC_API size_t sc_mapn_system_nextra(const sc_mapn_system *s);

/** @brief Set parameter @p q (a fixed one; a free one is overwritten by u
 * at each evaluation).  @return SC_OK, SC_EINVAL for q >= np. */
SC_API int sc_mapn_system_set_param(sc_mapn_system *s, size_t q, double value);

/** @brief The equations at @p u into @p F (nequations values).
 * @return the callback's status (0, > 0, < 0). */
SC_API int sc_mapn_system_f(sc_mapn_system *s, const double *u, double *F);

/** @brief The exact Jacobian dF/du at @p u into @p J (row-major,
 * nequations x nunknowns).  @return the callback's status. */
SC_API int sc_mapn_system_jac(sc_mapn_system *s, const double *u, double *J);

/**
 * @brief The test functions of SC_MAPN_FIXED (SC_MAPN_NTEST values, in
 * the order of the SC_MAPN_TEST_ enum) at @p u on a branch with unit
 * tangent @p t (nunknowns values).  Each determinant is divided by the
 * product of its rows' Euclidean norms (each at least 1), which by
 * Hadamard's inequality puts it in [-1, 1] with the same zeros.
 * @return the callback's status; SC_EINVAL (as a fatal -1) for another
 *         kind.
 */
SC_API int sc_mapn_system_tests(sc_mapn_system *s, const double *u,
                                const double *t, double *psi);

/**
 * @brief Set the bordering vectors at @p u from the singular vectors of
 * the smallest singular values of g_x -+ I (FOLD, FLIP, BP) or of
 * g_x^2 - 2 kappa g_x + I (NS), and for NS choose the pair of entries of
 * G whose gradient is best conditioned.  Call it once at a point where
 * the system starts (a detected special point).
 * @return SC_OK; SC_ECALLBACK if g failed at @p u; SC_EINTERNAL if the
 *         SVD failed.  A no-op for FIXED.
 */
SC_API int sc_mapn_system_init(sc_mapn_system *s, const double *u, sc_msg *msg);

/**
 * @brief Update the bordering vectors at an accepted point @p u to the
 * (normalised) null vectors of the bordered systems there: b = w, c = v
 * (NS: P = W, Q = V, orthonormalised), as MatContM does after each step,
 * so that the bordered matrices stay far from singular along a curve.
 * @return SC_OK; SC_ECALLBACK if g failed; SC_ESING if the bordered
 *         matrix is singular (call sc_mapn_system_init() instead).
 */
SC_API int sc_mapn_system_update(sc_mapn_system *s, const double *u,
                                 sc_msg *msg);

/**
 * @brief The right and left null vectors of the bordered system at @p u:
 * FOLD, FLIP, BP: v and w (n values each) from M (v; s) = (0; 1) and
 * M^T (w; s2) = (0; 1), each normalised to length 1 (at the point they
 * span the kernels of g_x -+ I and its transpose); NS: V and W (n x 2,
 * column k at k n) as solved, spanning the kernels of
 * g_x^2 - 2 kappa g_x + I and its transpose.  Either pointer may be NULL.
 * @return SC_OK; SC_ECALLBACK if g failed; SC_ESING for a singular
 *         bordered matrix; SC_EINVAL for FIXED.
 */
SC_API int sc_mapn_system_vectors(sc_mapn_system *s, const double *u,
                                  double *v, double *w, sc_msg *msg);

/**
 * @brief The continuation problem of a system with one more unknown than
 * equations (FIXED with nfree = 1: a branch, with the SC_MAPN_NTEST tests;
 * FOLD, FLIP, NS with nfree = 2: a curve, without tests).  Its callbacks
 * write into @p s's workspace: @p s must outlive the branch and be used
 * by one thread.
 * @return SC_OK; SC_EINVAL for a square system.
 */
SC_API int sc_mapn_system_problem(sc_mapn_system *s, sc_cont_problem *pb,
                                  sc_msg *msg);

/**
 * @brief Newton on a square system (FOLD, FLIP, NS with nfree = 1; BP)
 * from @p u (overwritten with the solution), the Jacobian exact (BP: its
 * row w^T g_p differentiated in p by central differences of the exact
 * g_p, since g_pp is not given; the row only sets the rate).  Converged
 * when every step entry is within newton_atol + newton_rtol |u_i| and
 * max |F_i| <= newton_ftol.  The bordering vectors are held fixed.
 * @param cert out: residual max |F_i| (the certificate), the last step,
 *        iterations (cert->psi is unused: 0).
 * @return SC_OK; SC_ENOCONV after newton_maxiter iterations or when a
 *         step grows (the certificate says how far it got); SC_ESING for
 *         a singular Jacobian; SC_ECALLBACK if g failed; SC_EINVAL for a
 *         system that is not square.
 */
SC_API int sc_mapn_system_solve(sc_mapn_system *s, double *u,
                                const sc_accuracy *acc, sc_curve_cert *cert,
                                sc_msg *msg);

#ifdef __cplusplus
}
#endif
#endif
