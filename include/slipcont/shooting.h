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

#ifdef __cplusplus
}
#endif
#endif
