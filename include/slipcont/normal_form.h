/**
 * @file normal_form.h
 * @brief Normal-form coefficients of a fixed point of an n-dimensional
 *        map g at a fold, a flip or a Neimark-Sacker bifurcation, and the
 *        test functions of the codimension-two points on their curves,
 *        from the exact derivatives of g (continuation/normal_form.c;
 *        docs/maps.md, "Normal forms").
 *
 * The continuation layer knows no model: g is given by its Jacobian A,
 * its second derivative tensor H and its third derivative tensor T at the
 * fixed point, with the index conventions of sc_mapn_value (models.h),
 * row-major:
 *  - A[i n + j] = d g_i / dx_j;
 *  - H[(i n + j) n + k] = d2 g_i / dx_j dx_k;
 *  - T[((i n + j) n + k) n + l] = d3 g_i / dx_j dx_k dx_l.
 * B(u, v)_i = sum_jk H_ijk u_j v_k and C(u, v, w)_i = sum_jkl T_ijkl u_j
 * v_k w_l are the multilinear forms of the Taylor expansion
 * g(x0 + x) = x0 + A x + B(x, x) / 2 + C(x, x, x) / 6 + O(|x|^4).
 *
 * Every function here is reentrant: no allocation, no global state;
 * the work is on the stack (n <= SC_NF_MAXDIM).
 */
#ifndef SLIPCONT_NORMAL_FORM_H
#define SLIPCONT_NORMAL_FORM_H

#include <stddef.h>

#include "slipcont/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest dimension handled here: the same as SC_DIM_TENSOR of
 * models.h, the largest map whose tensors H and T are kept. */
#define SC_NF_MAXDIM 16

/** The derivatives of g at a fixed point (arrays owned by the caller). */
typedef struct {
  size_t n;        /**< state dimension, 1 <= n <= SC_NF_MAXDIM */
  const double *A; /**< n x n Jacobian */
  const double *H; /**< n^3 second derivatives */
  const double *T; /**< n^4 third derivatives; NULL where only the fold
                        coefficient is asked for */
} sc_nf_jet;

/** A normal form at a fixed point. */
typedef struct {
  double coef;  /**< fold a, flip b, NS first Lyapunov coefficient d */
  double mu[2]; /**< the critical multiplier used (re, im) */
  double theta; /**< its argument in [0, pi] (fold 0, flip pi) */
  /** Right vector q (A q = mu q), real parts then imaginary parts (2 n
   * values; the imaginary parts are 0 for a fold or a flip). */
  double q[2 * SC_NF_MAXDIM];
  /** Left vector p (A^T p = conj(mu) p), same layout, with
   * <p, q> = sum conj(p_i) q_i = 1. */
  double p[2 * SC_NF_MAXDIM];
} sc_nf;

/**
 * @brief The fold coefficient a = p^T B(q, q) / 2 of g restricted to its
 * centre manifold, g: w -> w + a w^2 + O(w^3) along x = x0 + w q.
 *
 * q is the right eigenvector of the real multiplier of A nearest 1, with
 * |q| = 1, and p the left one with p^T q = 1.  q's sign, which decides
 * a's, is chosen so that q . @p qref > 0 (a curve passes its previous q
 * to keep a continuous), or, for @p qref NULL, so that q's component of
 * largest modulus is positive (q = 1 for n = 1: a = g_xx / 2).
 * @param g the jet (T not used).
 * @param qref NULL or n values.
 * @param out the coefficient, the multiplier and the vectors.
 * @return SC_OK; SC_EINVAL (n out of range, NULL arrays, no real
 *         multiplier); SC_ESING (q and p orthogonal: 1 is not a simple
 *         multiplier, a Bogdanov-Takens type point R1); SC_EINTERNAL
 *         (the eigenvalue solver failed).
 */
SC_API int sc_nf_fold(const sc_nf_jet *g, const double *qref, sc_nf *out,
                      sc_msg *msg);

/**
 * @brief The flip coefficient
 * b = p^T [C(q, q, q) + 3 B(q, (I - A)^(-1) B(q, q))] / 6: the centre
 * manifold's map is w -> -w + b w^3 + O(w^4) after the quadratic term is
 * removed, and its second iterate w -> w - 2 b w^3, so b > 0 is a
 * supercritical flip (docs/curves.md's sign).  For n = 1 it is
 * (g_xx / 2)^2 + g_xxx / 6.  q: the right eigenvector of the real
 * multiplier nearest -1, |q| = 1, p^T q = 1; b does not depend on q's
 * sign.
 * @return as sc_nf_fold(); also SC_EINVAL for T NULL and SC_ESING when
 *         I - A is singular (a multiplier 1 too: a fold-flip LPPD).
 */
SC_API int sc_nf_flip(const sc_nf_jet *g, sc_nf *out, sc_msg *msg);

/**
 * @brief The Neimark-Sacker angle theta and first Lyapunov coefficient
 * d = Re{ e^(-i theta) <p, C(q, q, conj q) + 2 B(q, (I - A)^(-1)
 *     B(q, conj q)) + B(conj q, (e^(2 i theta) I - A)^(-1) B(q, q))> } / 2
 * with A q = e^(i theta) q, A^T p = e^(-i theta) p, <p, q> = 1: the
 * centre manifold's map is z -> e^(i theta) z (1 + d |z|^2) + O(|z|^4)
 * in the coordinate z of x = x0 + z q + conj(z q) (d < 0 supercritical).
 *
 * q is normalised to <q, q> = 1/2, so that z is the amplitude of the
 * real orbit (|x - x0| = |z| for a rotation): the map z -> e^(i theta) z
 * (1 + d |z|^2) written in R^2 as (Re z, Im z) gives d.  MatContM
 * normalises <q, q> = 1, which gives 2 d (the same sign).
 * @param mu NULL: the complex pair (im > 0) whose modulus is nearest 1;
 *        else (re, im) of a multiplier: the eigenvalue nearest it (its
 *        conjugate if im < 0).  Off the NS curve the chosen eigenvalue mu
 *        stands for e^(i theta) in the formula (theta = arg mu), so the
 *        coefficient is smooth across the curve.
 * @return as sc_nf_flip(); SC_EINVAL also when A has no complex
 *         multiplier; SC_ESING when I - A or mu^2 I - A is singular
 *         (strong resonances R1, R2) or <p, q> = 0.
 */
SC_API int sc_nf_ns(const sc_nf_jet *g, const double *mu, sc_nf *out,
                    sc_msg *msg);

/**
 * @brief The multipliers of A (n x n, row-major): @p re, @p im (n values
 * each), sorted by decreasing modulus, a complex pair with its positive
 * imaginary part first.
 * @return SC_OK, SC_EINVAL (n out of range), SC_EINTERNAL (the
 *         eigenvalue solver failed).
 */
SC_API int sc_nf_multipliers(size_t n, const double *A, double *re, double *im,
                             sc_msg *msg);


/* ------------------------------------------------------------------ */
/* Codimension-two tests along fold, flip and NS curves                */

/** The curve a point lies on. */
typedef enum {
  SC_NF_FOLD = 0, /**< a multiplier +1 */
  SC_NF_FLIP = 1, /**< a multiplier -1 */
  SC_NF_NS = 2    /**< a pair mu, 1/mu with mu + 1/mu = 2 kappa */
} sc_nf_curve;

/** Most tests of a curve (sc_nf_curve_ntest()). */
#define SC_NF_MAXTEST 8

/** Number of tests of @p kind: fold 4, flip 4, NS 8 (a test that needs
 * a larger n than the map's is NaN, so it never changes sign). */
SC_API size_t sc_nf_curve_ntest(sc_nf_curve kind);

/** Label of test @p k of @p kind ("CP", "R1", ...), NULL past the last;
 * and the least dimension @p min_n where it can vanish. */
SC_API const char *sc_nf_curve_label(sc_nf_curve kind, size_t k,
                                     size_t *min_n);

/**
 * @brief The codimension-two test functions at a point of a fold, flip
 * or NS curve, from the jet of g there (docs/maps.md, "Curves and
 * codimension two").  With p(lambda) = det(lambda I - A) and its
 * quotient r(lambda) by the curve's critical factor (lambda - 1,
 * lambda + 1, lambda^2 - 2 kappa lambda + 1; the remainder, zero on the
 * curve, dropped), whose roots are the other multipliers, and
 * bialt(r) = prod_{i<j} (nu_i nu_j - 1) over r's roots nu (the
 * determinant of the bialternate product of r's companion matrix minus
 * I: a pair with nu_i nu_j = 1):
 *  - fold: CP a (sc_nf_fold(), q oriented by @p qref); R1 r(1) (a second
 *    multiplier 1: the fold's p and q orthogonal); LPPD r(-1); LPNS
 *    bialt(r) (n >= 3);
 *  - flip: GPD b; R2 r(-1) (a second -1); LPPD r(1); PDNS bialt(r)
 *    (n >= 3);
 *  - NS: R1 kappa - 1; R2 kappa + 1; R3 kappa + 1/2; R4 kappa; CH d
 *    (sc_nf_ns() for the pair kappa +- i sqrt(1 - kappa^2); NaN where
 *    |kappa| >= 1, the neutral-saddle part of the curve); LPNS r(1)
 *    (n >= 3); PDNS r(-1) (n >= 3); NSNS bialt(r) (n >= 4).
 * Each is a smooth function of the point where the critical multipliers
 * are apart from the others (r's coefficients are polynomials in those
 * of p), so Newton on {F = 0, psi_k = 0} converges to its zeros.  A zero
 * of bialt(r) with a real pair nu_i nu_j = 1 is a neutral saddle, not a
 * Neimark-Sacker point: the caller tells them apart at the located point
 * (sc_nf_multipliers()).
 * @param kind the curve.
 * @param g the jet (T needed for flip and NS; H for every kind).
 * @param kappa NS: the curve's kappa = cos theta; else unused.
 * @param qref fold: NULL or n values orienting q (see sc_nf_fold()).
 * @param psi out: sc_nf_curve_ntest(kind) values (NaN: not applicable,
 *        or a coefficient that cannot be computed there).
 * @param qout fold: NULL or n values, the q used (the next call's qref).
 * @return SC_OK; SC_EINVAL (bad kind or jet); SC_EINTERNAL (the
 *         eigenvalue solver failed).
 */
SC_API int sc_nf_curve_tests(sc_nf_curve kind, const sc_nf_jet *g,
                             double kappa, const double *qref, double *psi,
                             double *qout, sc_msg *msg);

#ifdef __cplusplus
}
#endif
#endif
