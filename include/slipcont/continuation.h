/**
 * @file continuation.h
 * @brief Pseudo-arclength continuation of F(u) = 0, F: R^(n+1) -> R^n,
 *        with a Newton corrector on the bordered system, adaptive steps,
 *        user test functions and the location of special points; and the
 *        augmented (bordered) systems for fixed points, folds and flips of
 *        a one-dimensional map iterate g(x, p).
 *
 * This layer knows only vectors, Jacobians and callbacks.  The last
 * component u[n] is the continuation parameter: the parameter interval of
 * the settings applies to it, and the initial point is corrected with it
 * held fixed.
 *
 * Three levels of use:
 *  - the caller owns the loop: sc_branch_alloc(), sc_branch_set(), then
 *    sc_branch_step() until it returns SC_END or an error; each call
 *    returns after one accepted point (SC_CONTINUE) or at a located
 *    special point (SC_SPECIAL);
 *  - the driver sc_branch_solve() runs that loop and calls a function of
 *    the caller's at every point;
 *  - sc_cont_settings / sc_accuracy carry every tolerance and step.
 *
 * Thread safety: a branch object must not be used by two threads at once;
 * distinct branches share nothing (callbacks permitting).  All memory is
 * taken by sc_branch_alloc(): stepping never allocates (the KLU backend
 * aside, which allocates its factors inside KLU).
 */
#ifndef SLIPCONT_CONTINUATION_H
#define SLIPCONT_CONTINUATION_H

#include <stddef.h>

#include "slipcont/common.h"
#include "slipcont/linalg.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * The problem F(u) = 0, u in R^(n+1).  Callbacks return 0 on success,
 * > 0 for a recoverable failure (the point is outside the domain: the
 * step is shrunk), < 0 for a fatal one (the branch stops with
 * SC_ECALLBACK).  Their outputs are checked for finiteness; a non-finite
 * value is treated as a recoverable failure.  The structure is copied by
 * sc_branch_alloc(); what @c user points to must outlive the branch.
 */
typedef struct {
  size_t n; /**< number of equations, n >= 1; unknowns n + 1 */
  /** F(u): write n values into @p F. */
  int (*f)(const double *u, double *F, void *user);
  /** Jacobian dF/du (n x (n+1)): row-major, J[i (n+1) + j] = dF_i/du_j,
   * or, if @c jac_colptr is set, its nonzeros in that CSC pattern order. */
  int (*jac)(const double *u, double *J, void *user);
  /** Optional CSC pattern of the Jacobian (n rows, n + 1 columns, rows
   * strictly increasing in each column): NULL for a dense Jacobian.  The
   * arrays are copied.  With the KLU backend it keeps the bordered matrix
   * sparse. */
  const int *jac_colptr; /**< n + 2 column pointers */
  const int *jac_rowind; /**< jac_colptr[n + 1] row indices */
  size_t ntest;          /**< number of test functions, may be 0 */
  /** Test functions psi_k(u), k < ntest, at a point u on the branch with
   * unit tangent @p t (n + 1 entries, oriented along the branch).  A
   * special point is a zero of one of them.  May be NULL if ntest = 0.
   * Example: psi = t[n] vanishes at the folds (turning points) of the
   * branch in u[n], whatever F is. */
  int (*test)(const double *u, const double *t, double *psi, void *user);
  /** Optional names of the test functions ("fold", "flip"), ntest
   * entries, for messages; NULL for "test k". */
  const char *const *test_names;
  void *user; /**< passed to every callback */
} sc_cont_problem;

/** Step control and location settings; fill with
 * sc_cont_settings_default(), then change fields. */
typedef struct {
  double h0;      /**< initial arclength step, > 0 (default 1e-2) */
  double hmin;    /**< smallest step before SC_ENOCONV, in (0, h0] (1e-10) */
  double hmax;    /**< largest step, >= h0 (0.1) */
  double grow;    /**< step factor after an easy step, >= 1 (1.5) */
  double shrink;  /**< step factor after a failure, in (0, 1) (0.5) */
  int fast_iter;  /**< a corrector converging in at most this many Newton
                       iterations counts as easy (3) */
  double pmin;    /**< parameter interval for u[n]: SC_END when the branch */
  double pmax;    /**< leaves it (default -inf, +inf; pmin < pmax) */
  int direction;  /**< +1 or -1: initial sign of du[n]/ds (+1) */
  long max_points; /**< SC_END after this many accepted points (1000) */
  double test_atol; /**< a located zero of a test function is reported only
                         if |psi| <= test_atol there (1e-8); test functions
                         should be scaled to be of order one */
  int max_locate_iter; /**< secant/bisection iterations per location (60) */
  /** Linear-solver backend for the bordered systems: NULL for dense. */
  const sc_linsolve_type *linsolve;
  /** 0 (default): sc_branch_set() corrects the start with the parameter
   * u[n] fixed, and fails if that Newton iteration fails.  1: if it
   * fails, correct with each other coordinate fixed in turn, so the start
   * may move in u[n] (within [pmin, pmax]).  For starts where F_x is
   * nearly singular: next to a fold, or on a period-doubled branch next
   * to the flip it was born in. */
  int start_free;
} sc_cont_settings;

/** @brief Fill @p s with the defaults listed in sc_cont_settings. */
SC_API void sc_cont_settings_default(sc_cont_settings *s);

/**
 * @brief Check every field of @p s (finite, in range, hmin <= h0 <= hmax,
 * pmin < pmax, direction = +-1).
 * @return SC_OK, or SC_EINVAL naming the first bad field, its value and
 *         the valid range.
 */
SC_API int sc_cont_settings_check(const sc_cont_settings *s, sc_msg *msg);

/** Why the last Newton corrector stopped: a reason, not an error. */
typedef enum {
  SC_CORR_NONE = 0,      /**< no corrector has run yet */
  SC_CORR_CONVERGED,     /**< step and residual within tolerance */
  SC_CORR_MAXITER,       /**< newton_maxiter iterations without converging */
  SC_CORR_DIVERGING,     /**< a Newton step longer than the one before */
  SC_CORR_SINGULAR,      /**< the bordered Jacobian is singular */
  SC_CORR_CALLBACK,      /**< a callback failed (recoverably) or returned a
                              non-finite value */
} sc_corr_reason;

/** @brief Text for a corrector reason ("converged", ...). */
SC_API const char *sc_corr_reason_text(sc_corr_reason r);

/** What the last location of a special point found. */
typedef struct {
  int test;        /**< index of the test function, -1 if none yet */
  int accepted;    /**< 1: reported as a special point (|psi| <= test_atol
                        and the location converged); 0: rejected, e.g. a
                        sign change across a jump of the test function */
  double psi;      /**< test function at the located point */
  double ds;       /**< last secant/bisection step in arclength */
  double width;    /**< final bracket width in arclength */
  int iterations;  /**< secant/bisection iterations */
} sc_cont_location;

/** A branch being continued (opaque). */
typedef struct sc_branch sc_branch;

/**
 * @brief Create a branch for problem @p pb.
 * @param pb   the problem (copied; the Jacobian pattern too).
 * @param set  settings (copied), NULL for the defaults.
 * @param acc  accuracy (copied): newton_atol/rtol for the corrector step
 *             and the location step, newton_ftol for the residual,
 *             newton_maxiter; NULL for the "default" preset.
 * @return SC_OK; SC_EINVAL for a malformed problem (n = 0, missing
 *         callback, bad pattern) or bad settings or accuracy; SC_ENOMEM.
 */
SC_API int sc_branch_alloc(const sc_cont_problem *pb, const sc_cont_settings *set,
                           const sc_accuracy *acc, sc_branch **out, sc_msg *msg);

/** @brief Release @p b; NULL is accepted. */
SC_API void sc_branch_free(sc_branch *b);

/**
 * @brief Start the branch at @p u0 (n + 1 values, copied): correct it by
 * Newton with the parameter u[n] held fixed, compute the unit tangent
 * (oriented so that du[n]/ds has the sign of settings.direction) and the
 * test functions, and reset the step to h0.  Counters are not reset.
 * @return SC_OK; SC_EINVAL if u0 is not finite or u0[n] is outside
 *         [pmin, pmax]; SC_ENOCONV if the corrector failed (the reason is
 *         in sc_branch_reason() and the message); SC_ECALLBACK for a
 *         fatal callback failure.
 */
SC_API int sc_branch_set(sc_branch *b, const double *u0, sc_msg *msg);

/**
 * @brief Make one step along the branch.
 *
 * Predicts u + h t, corrects on the bordered system [F(u); t.(u - u_prev)
 * - h] = 0, grows the step after an easy convergence and halves it (by
 * settings.shrink) after a failure, down to hmin.  At each accepted point
 * the test functions are evaluated; a sign change is located by a
 * secant/bisection iteration in arclength until the arclength step is
 * within newton_atol + newton_rtol |u|_inf and |psi| <= test_atol.  A
 * located point whose test function is not small (a sign change across a
 * jump) is not reported (see sc_branch_location()).
 * @return SC_CONTINUE after an accepted regular point; SC_SPECIAL when the
 *         current point is a located special point (sc_branch_location()
 *         says which test); SC_END when the branch reached the end of the
 *         parameter interval (the current point lies on it, corrected) or
 *         max_points; errors: SC_EINVAL if sc_branch_set() was not called;
 *         SC_ENOCONV when the step fell below hmin (the message has the
 *         last corrector reason); SC_ECALLBACK for a fatal callback
 *         failure.
 */
SC_API int sc_branch_step(sc_branch *b, sc_msg *msg);

/** Kind of point passed to a sc_branch_fn. */
typedef enum {
  SC_POINT_START = 0, /**< the corrected initial point */
  SC_POINT_REGULAR,   /**< an accepted point */
  SC_POINT_SPECIAL,   /**< a located special point */
  SC_POINT_END,       /**< the last point (end of interval or max_points) */
} sc_point_kind;

/** Called by sc_branch_solve() at every point; return non-zero to stop
 * (sc_branch_solve() then returns SC_ECALLBACK). */
typedef int (*sc_branch_fn)(void *ctx, const sc_branch *b,
                            sc_point_kind kind);

/**
 * @brief Driver: sc_branch_set(b, u0), then sc_branch_step() until SC_END,
 * calling @p fn (may be NULL) at the start, after each point and at the
 * end.
 * @return SC_OK at the end of the branch; otherwise the error of
 *         sc_branch_set()/sc_branch_step(), or SC_ECALLBACK if @p fn
 *         stopped.
 */
SC_API int sc_branch_solve(sc_branch *b, const double *u0, sc_branch_fn fn,
                           void *ctx, sc_msg *msg);

/** Number of unknowns n + 1. */
SC_API size_t sc_branch_dim(const sc_branch *b);
/** Current point (n + 1 values), valid until the next step. */
SC_API const double *sc_branch_point(const sc_branch *b);
/** Unit tangent at the current point (n + 1 values). */
SC_API const double *sc_branch_tangent(const sc_branch *b);
/** Test function values at the current point (ntest values). */
SC_API const double *sc_branch_test_values(const sc_branch *b);
/** Arclength step to be tried next. */
SC_API double sc_branch_step_size(const sc_branch *b);
/** Why the last corrector stopped. */
SC_API sc_corr_reason sc_branch_reason(const sc_branch *b);
/** The last location of a special point (accepted or rejected). */
SC_API const sc_cont_location *sc_branch_location(const sc_branch *b);
/**
 * @brief Determinant of the bordered Jacobian [F_u; t^T] at the current
 * point, as sign and log|det| (sc_linsolve_det()), where t is the
 * tangent of the previous point (at the initial point: the axis e_n, or
 * the axis used if that was singular).  Its sign changes at simple branch
 * points, not at folds.  @return SC_OK, or SC_EINVAL before
 * sc_branch_set().
 */
SC_API int sc_branch_bordered_det(const sc_branch *b, int *sign, double *logabs);

/** Accepted points (the initial point included). */
SC_API unsigned long sc_branch_npoints(const sc_branch *b);
/** Special points reported. */
SC_API unsigned long sc_branch_nspecial(const sc_branch *b);
/** Sign changes of test functions rejected after location. */
SC_API unsigned long sc_branch_nrejected_special(const sc_branch *b);
/** Steps rejected because the corrector failed. */
SC_API unsigned long sc_branch_nrejected(const sc_branch *b);
/** Newton iterations, all correctors included. */
SC_API unsigned long sc_branch_nnewton(const sc_branch *b);
/** Evaluations of F. */
SC_API unsigned long sc_branch_nfeval(const sc_branch *b);
/** Evaluations of the Jacobian. */
SC_API unsigned long sc_branch_njac(const sc_branch *b);
/** Secant/bisection iterations spent locating special points. */
SC_API unsigned long sc_branch_nlocate(const sc_branch *b);
/** The linear solver of the bordered systems (for its counters). */
SC_API const sc_linsolve *sc_branch_linsolve(const sc_branch *b);

/* ---------------------------------------------------------------------
 * Augmented systems for a fixed point of a 1-D map iterate g = f^m(x, p)
 * ------------------------------------------------------------------- */

/** Most parameters of g. */
#define SC_MAP1D_MAXPARAM 8

/** g and its derivatives at (x, p). */
typedef struct {
  double g;                      /**< g(x, p) */
  double gx;                     /**< dg/dx (order >= 1) */
  double gp[SC_MAP1D_MAXPARAM];  /**< dg/dp_i (order >= 1) */
  double gxx;                    /**< d2g/dx2 (order >= 2) */
  double gxp[SC_MAP1D_MAXPARAM]; /**< d2g/dx dp_i (order >= 2) */
} sc_map1d_jet;

/**
 * Evaluate g at (x, p) up to derivative order @p order (0, 1 or 2): p
 * holds all np parameters.  Returns 0, > 0 (recoverable: outside the
 * domain) or < 0 (fatal), as the continuation callbacks.
 */
typedef int (*sc_map1d_fn)(double x, const double *p, int order,
                           sc_map1d_jet *jet, void *user);

/** Which augmented system. */
typedef enum {
  /** u = (x, p_a): F = g - x (n = 1).  Tests: psi_0 = g_x - 1 ("fold",
   * multiplier +1), psi_1 = g_x + 1 ("flip", multiplier -1). */
  SC_MAP1D_FIXED = 0,
  /** u = (x, p_a, p_b): F = (g - x, g_x - 1) (n = 2), the fold curve.
   * Test: psi_0 = g_xx ("cusp": the fold's quadratic coefficient). */
  SC_MAP1D_FOLD,
  /** u = (x, p_a, p_b): F = (g - x, g_x + 1) (n = 2), the flip curve.
   * No test functions. */
  SC_MAP1D_FLIP,
} sc_map1d_kind;

/**
 * A 1-D map system: fill it, then sc_map1d_problem() turns it into a
 * continuation problem whose callbacks read it (it must outlive the
 * branch, and not change while one is being continued).
 */
typedef struct {
  sc_map1d_fn fn;                /**< the map iterate and its derivatives */
  void *user;                    /**< passed to fn */
  sc_map1d_kind kind;            /**< what is continued (sc_map1d_kind) */
  size_t np;                     /**< parameters of g, 1..SC_MAP1D_MAXPARAM */
  double p[SC_MAP1D_MAXPARAM];   /**< parameter values; the free ones are
                                      replaced by u's entries at each call */
  int ifree[2];                  /**< index of p_a (and p_b: fold, flip) */
} sc_map1d_system;

/**
 * @brief Fill @p pb with the callbacks of system @p sys (n = 1 for FIXED,
 * 2 for FOLD and FLIP; test functions as listed in sc_map1d_kind).
 * @return SC_OK, or SC_EINVAL for a NULL fn, np out of range, a free
 *         index outside [0, np) or equal free indices.
 * Thread safe: the callbacks write nothing into @p sys.
 */
SC_API int sc_map1d_problem(const sc_map1d_system *sys, sc_cont_problem *pb,
                            sc_msg *msg);

#ifdef __cplusplus
}
#endif
#endif
