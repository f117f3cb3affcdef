/**
 * @file shooting.h
 * @brief Periodic orbits of an event map by shooting: Newton's method on
 *        f^m(d) - d (single shooting) or on the cyclic system
 *        d_(i+1) - f(d_i) = 0, i = 1..m (multiple shooting), with the
 *        exact derivatives of the map (map.h).
 *
 * Single shooting is cheap but its Jacobian (f^m)' - 1 is the product of
 * m slopes: for an unstable orbit of long period (multipliers of 1e6 and
 * more) Newton's basin shrinks to nothing and the iteration wanders.
 * Multiple shooting keeps every point as an unknown; its Jacobian is
 * cyclic bidiagonal (1 on the superdiagonal, -f'(d_i) on the diagonal,
 * the corner closing the cycle) and well conditioned as long as the
 * orbit is hyperbolic.  It is solved by the linear-solver interface of
 * linalg.h: the dense backend for m <= SC_SHOOT_DENSE_MAX, KLU above,
 * unless the caller names a backend; both give the same answer.
 *
 * Neutral orbits (docs/model.md: every iterate a single-block slip, f' = 1
 * exactly, f^m(d) - d constant on the piece) have no isolated fixed
 * point: they are reported as SC_ENEUTRAL with the constant in the
 * result, never as a singular Jacobian.
 *
 * A shooting object holds its own workspace and solver: one per thread.
 * It borrows the caller's map, which must outlive it and is evaluated
 * (its counters advance) but not otherwise changed.
 */
#ifndef SLIPCONT_SHOOTING_H
#define SLIPCONT_SHOOTING_H

#include "slipcont/common.h"
#include "slipcont/linalg.h"
#include "slipcont/map.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Shooting methods. */
typedef enum {
  SC_SHOOT_SINGLE = 1,   /**< Newton on f^m(d) - d */
  SC_SHOOT_MULTIPLE = 2, /**< Newton on d_(i+1) - f(d_i), i = 1..m */
} sc_shoot_method;

/** Largest period for which multiple shooting picks the dense backend
 * when the caller leaves the choice to it. */
#define SC_SHOOT_DENSE_MAX 16

/** What a shooting solve reached.  The orbit itself is read with
 * sc_shoot_orbit(). */
typedef struct {
  double d;          /**< the first orbit point d_1 */
  double multiplier; /**< (f^m)'(d_1): product of f'(d_i) over the orbit;
                          exactly 1 for a neutral orbit */
  int stable;        /**< 1 if |multiplier| < 1 */
  int neutral;       /**< 1 if every iterate is neutral (a family) */
  double family_gap; /**< neutral only: the constant f^m(d) - d */
  int iterations;    /**< Newton iterations made */
  double residual;   /**< max-norm of the residual at the solution */
  double step;       /**< max-norm of the last Newton step */
  char itinerary[SC_ITIN_LEN]; /**< of f^m from d_1, iterates joined by '|' */
} sc_shoot_result;

/** A shooting problem and its workspace (opaque). */
typedef struct sc_shoot sc_shoot;

/**
 * @brief Prepare shooting for orbits of period @p period of @p m.
 * @param m       the map (borrowed; must outlive the object).
 * @param period  m >= 1 (at most 1000000).
 * @param method  SC_SHOOT_SINGLE or SC_SHOOT_MULTIPLE.
 * @param ls      backend for multiple shooting (sc_linsolve_dense or
 *                sc_linsolve_klu), or NULL for the automatic choice
 *                (dense up to SC_SHOOT_DENSE_MAX, KLU above); ignored by
 *                single shooting.
 * @return SC_OK; SC_EINVAL for a bad period or method; SC_ENOMEM.
 */
SC_API int sc_shoot_alloc(sc_map *m, int period, sc_shoot_method method,
                          const sc_linsolve_type *ls, sc_shoot **out, sc_msg *msg);

/** @brief Release @p s; NULL is accepted. */
SC_API void sc_shoot_free(sc_shoot *s);

/**
 * @brief Solve from the single guess @p d0.  Multiple shooting seeds its
 * unknowns with the iterates d0, f(d0), ..., f^(m-1)(d0).
 *
 * Newton stops when the max-norm of the step is within
 * newton_atol + newton_rtol |d| for every unknown and the residual is
 * within newton_ftol (single shooting: newton_ftol max(1, |(f^m)'|),
 * since the rounding of f^m grows with its derivative), or (a stagnation
 * at rounding level) the step is within 4 DBL_EPSILON |d|, or (the
 * noise floor of an ill-conditioned Jacobian, near a fold or a flip) the
 * residual is within tolerance and the step stopped shrinking (it is not
 * below half the step before it).  Newton is damped: a step that lands where
 * the map is undefined, or that does not decrease the Euclidean norm of the
 * residual (across a jump of f a full step can land on another piece far
 * away), is halved, at most SC_SHOOT_MAX_HALVINGS times; a step already
 * within the step tolerance is always taken.
 * @return SC_OK with @p res filled; SC_ENEUTRAL if the iterates at the
 *         current point are all neutral (the orbit lies in a continuous
 *         family; @p res has neutral = 1, the constant f^m(d) - d in
 *         family_gap, and the message says whether d is on the family,
 *         |family_gap| <= newton_ftol, or not); SC_ENOCONV after
 *         newton_maxiter iterations, or when no halving of a step
 *         decreases the residual (residual and step in the message);
 *         SC_ESING for a singular Jacobian of a non-neutral orbit;
 *         SC_EUNDEF, SC_ENONFINITE from the map where halving did not
 *         help; SC_EINVAL for a non-finite guess.
 */
SC_API int sc_shoot_solve(sc_shoot *s, double d0, sc_shoot_result *res,
                          sc_msg *msg);

/**
 * @brief As sc_shoot_solve() from a guess of every orbit point
 * @p d0[0..period-1] (multiple shooting; single shooting uses d0[0]).
 */
SC_API int sc_shoot_solve_orbit(sc_shoot *s, const double *d0, sc_shoot_result *res,
                                sc_msg *msg);

/** Halvings of one Newton step at most (see sc_shoot_solve()). */
#define SC_SHOOT_MAX_HALVINGS 20

/** The orbit points d_1..d_m of the last solve (period values), valid
 * until the next solve. */
SC_API const double *sc_shoot_orbit(const sc_shoot *s);
/** The period m. */
SC_API int sc_shoot_period(const sc_shoot *s);
/** The method. */
SC_API sc_shoot_method sc_shoot_get_method(const sc_shoot *s);
/** The backend of multiple shooting (NULL for single shooting). */
SC_API const sc_linsolve_type *sc_shoot_linsolve_type(const sc_shoot *s);
/** Newton iterations made by @p s since its creation. */
SC_API unsigned long sc_shoot_nnewton(const sc_shoot *s);

/* ------------------------------------------------------------------ */
/* Shooting for maps of n dimensions                                     */

/** Why a shooting solve in n dimensions stopped (PETSc's "converged
 * reason": a failure is an outcome with its cause, not only a status). */
typedef enum {
  SC_SHOOTN_CONVERGED = 0, /**< residual and step within tolerance */
  SC_SHOOTN_MAXITER,       /**< newton_maxiter iterations made */
  SC_SHOOTN_NO_DECREASE,   /**< no halving of a step decreased the merit */
  SC_SHOOTN_SINGULAR,      /**< the Newton matrix is singular (a multiplier
                                1: a fold, or a start where f^m - id is
                                degenerate), or the deflated step is */
  SC_SHOOTN_UNDEFINED,     /**< the map is undefined or not finite along
                                every halving of a step (an escape to
                                infinity) */
} sc_shootn_reason;

/** Number of sc_shootn_reason values. */
#define SC_SHOOTN_NREASONS 5

/** Text of a reason: "converged", "no convergence in newton-maxiter
 * iterations", "no step decreases the residual", "singular Jacobian",
 * "map undefined or infinite". */
SC_API const char *sc_shootn_reason_text(sc_shootn_reason r);

/** What a solve in n dimensions reached.  The orbit and its multipliers
 * are read with sc_shootn_orbit() and sc_shootn_multipliers(). */
typedef struct {
  sc_shootn_reason reason; /**< SC_SHOOTN_CONVERGED after SC_OK */
  int iterations;    /**< Newton iterations made */
  double residual;   /**< certificate: max-norm of the system's residual
                          at the returned point (single: f^m(x) - x;
                          multiple: f(x_k) - x_(k+1) over k) */
  double step;       /**< max-norm of the last Newton step */
  double multiplier; /**< the multiplier of largest modulus, the one that
                          decides stability: its value when it is real,
                          its modulus for a complex pair */
  int stable;        /**< 1 if every multiplier has modulus < 1 */
} sc_shootn_result;

/** Shooting for periodic orbits of an n-dimensional map (opaque). */
typedef struct sc_shootn sc_shootn;

/**
 * @brief Prepare shooting for orbits of period @p period of @p m, a map
 * of any dimension n (sc_map_dim(); n = 1 works too, through the
 * n-dimensional interface, without the neutral-family handling of
 * sc_shoot_alloc()).
 *
 * Single shooting is Newton on g(x) - x = 0 with g = f^m, whose Jacobian
 * J_g - I comes exactly from sc_map_iterate_n() and is solved dense
 * (LAPACK through sc_linsolve_dense).  Multiple shooting keeps the m
 * orbit points x_0 .. x_(m-1) as unknowns, F_k = f(x_k) - x_(k+1 mod m):
 * its Jacobian is block cyclic (J(x_k) on the diagonal, -I on the block
 * superdiagonal and in the corner), m n unknowns with m n (n + 1)
 * nonzeros, solved by @p ls.  As sc_shoot, the object holds its own
 * workspace (one per thread) and borrows the map, whose counters
 * advance.
 * @param m       the map (borrowed; must outlive the object).
 * @param period  1 <= period <= SC_SHOOTN_MAX_PERIOD.
 * @param method  SC_SHOOT_SINGLE or SC_SHOOT_MULTIPLE.
 * @param ls      backend of multiple shooting (sc_linsolve_dense or
 *                sc_linsolve_klu), or NULL: dense up to
 *                SC_SHOOT_DENSE_MAX points, KLU above; ignored by single
 *                shooting.
 * @return SC_OK; SC_EINVAL for a bad period or method; SC_ENOMEM.
 *         Memory: about 4 m n^2 doubles (the Jacobians of the orbit and
 *         the multipliers' workspace) besides the solver's.
 */
SC_API int sc_shootn_alloc(sc_map *m, int period, sc_shoot_method method,
                           const sc_linsolve_type *ls, sc_shootn **out,
                           sc_msg *msg);

/** Largest period of sc_shootn_alloc(). */
#define SC_SHOOTN_MAX_PERIOD 100000

/** @brief Release @p s; NULL is accepted. */
SC_API void sc_shootn_free(sc_shootn *s);

/**
 * @brief Solve from the guess @p x0 (n values).  Multiple shooting seeds
 * its unknowns with the iterates x0, f(x0), ..., f^(m-1)(x0).
 *
 * Newton's method with the tolerances of sc_map_solver_accuracy(), as
 * sc_shoot_solve(): it stops when every component of the step is within
 * newton_atol + newton_rtol |x| and the max-norm of the residual within
 * newton_ftol (single shooting: newton_ftol max(1, ||J_g||_inf), since
 * the rounding of f^m grows with its derivative), or when the residual is
 * within tolerance and the step is at rounding level (within
 * 4 DBL_EPSILON |x|) or stopped shrinking (the noise floor near a fold).
 * A step that lands where the map is undefined or does not decrease the
 * merit (the Euclidean norm of the residual, times the deflation factor)
 * is halved, at most SC_SHOOT_MAX_HALVINGS times.  With deflated orbits
 * (sc_shootn_deflate()) the residual F is replaced by M(x) F(x), see
 * there.  On SC_OK the multipliers of the orbit are computed: the
 * eigenvalues of J(x_(m-1)) ... J(x_0), by decreasing modulus, by the
 * periodic Schur decomposition (sc_product_eigs_compute(), linalg.h:
 * the product is not formed, so multipliers far smaller than the
 * largest keep their relative accuracy).
 * @return SC_OK with @p res filled; SC_ENOCONV (reason MAXITER or
 *         NO_DECREASE), SC_ESING (SINGULAR), SC_EUNDEF or SC_ENONFINITE
 *         (UNDEFINED), with the residual and the point in the message and
 *         @p res->reason set; SC_EINVAL for a non-finite guess; SC_ENOMEM.
 */
SC_API int sc_shootn_solve(sc_shootn *s, const double *x0,
                           sc_shootn_result *res, sc_msg *msg);

/**
 * @brief As sc_shootn_solve() from a guess of every orbit point:
 * @p x0[k n + c] is component c of point k, k < period (single shooting
 * reads point 0 only).
 */
SC_API int sc_shootn_solve_orbit(sc_shootn *s, const double *x0,
                                 sc_shootn_result *res, sc_msg *msg);

/**
 * @brief Deflate a known orbit: later solves do not converge to it.
 *
 * Newton is then run on G(x) = M(x) F(x), with
 * M(x) = prod_j ((L / ||x - r_j||)^SC_SHOOTN_DEFLATE_POWER
 *                + SC_SHOOTN_DEFLATE_SHIFT),
 * the product over the roots r_j of F that the known orbits are: for
 * single shooting each of their points, for multiple shooting each of
 * their rotations (x_0 .. x_(m-1)) (q of them for an orbit of period q).
 * At a known simple root F vanishes like ||x - r|| while M grows like
 * ||x - r||^-2: G does not vanish there and Newton is repelled from it.
 * Far from every r_j, M tends to a constant and G is F again, so the
 * other roots keep their basins.  G's Newton step is F's Newton step d
 * scaled by 1 / (1 - grad(ln M) . d) (the Sherman-Morrison formula for
 * the rank-one term F grad(M)^T), so deflation costs no second solve.
 * @param orbit  q points of n components (layout of sc_shootn_orbit()),
 *               copied.
 * @param q      its period: a divisor of the period of @p s (SC_EINVAL
 *               otherwise), since only those orbits are roots of F.
 * @param scale  L > 0: the length of the state space's region searched
 *               (the size of a search box), so that M depends on
 *               distances relative to it; 1 for unit scale.
 * @return SC_OK; SC_EINVAL; SC_ENOMEM.
 */
SC_API int sc_shootn_deflate(sc_shootn *s, const double *orbit, int q,
                             double scale, sc_msg *msg);

/** @brief Forget every deflated orbit. */
SC_API void sc_shootn_deflate_clear(sc_shootn *s);

/** Power p of the deflation factor (see sc_shootn_deflate()): p = 2 is
 * the smallest integer power that repels Newton from a known simple root
 * with margin (p = 1 leaves G bounded there; the deflated step at
 * distance e from a known root is e / (p - 1) away from it, so p = 2
 * doubles the distance), and keeps M smooth (||x - r||^2 needs no root). */
#define SC_SHOOTN_DEFLATE_POWER 2
/** Shift sigma of the deflation factor: with sigma = 0, M F tends to zero
 * far away and Newton is drawn to infinity; sigma = 1 makes M = 1 + (L /
 * distance)^p, so that at distances beyond L (the search box) the known
 * orbits hardly change Newton's steps. */
#define SC_SHOOTN_DEFLATE_SHIFT 1.0

/** The m orbit points of the last solve, m n values (point k is
 * [k n, k n + n)), valid until the next solve. */
SC_API const double *sc_shootn_orbit(const sc_shootn *s);
/** The n multipliers of the last successful solve, by decreasing modulus
 * (ties by decreasing real part, a complex pair with its positive
 * imaginary part first): real parts in @p re, imaginary parts in @p im,
 * valid until the next solve. */
SC_API void sc_shootn_multipliers(const sc_shootn *s, const double **re,
                                  const double **im);
/** The period m. */
SC_API int sc_shootn_period(const sc_shootn *s);
/** The state dimension n. */
SC_API size_t sc_shootn_dim(const sc_shootn *s);
/** Newton iterations made by @p s since its creation. */
SC_API unsigned long sc_shootn_nnewton(const sc_shootn *s);

#ifdef __cplusplus
}
#endif
#endif
