/**
 * @file hybrid.h
 * @brief Certified location of the first root of an event guard.
 *
 * Every guard of the Coulomb two-block model is, along one mode, a
 * function of time of the form
 *
 *     g(t) = c0 + c1 t + sum_k (a_k cos(w_k t) + b_k sin(w_k t))
 *
 * (a linear term plus sinusoids of known frequencies), so |g'''| is bounded
 * by M3 = sum_k w_k^3 sqrt(a_k^2 + b_k^2) everywhere.  sc_guard_first_root()
 * uses that bound to march through (0, tmax] in intervals that are each
 * proved either free of roots or to hold exactly one (g strictly monotone
 * there, with a sign change), so the first root is never missed, also when
 * g only touches zero.  See docs/events.md for the argument.
 */
#ifndef SLIPCONT_HYBRID_H
#define SLIPCONT_HYBRID_H

#include "slipcont/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most sinusoids in one guard. */
#define SC_GUARD_MAXFREQ 4

/** A guard c0 + c1 t + sum_k (a_k cos w_k t + b_k sin w_k t). */
typedef struct {
  double c0;                   /**< constant term */
  double c1;                   /**< drift (coefficient of t) */
  int n;                       /**< number of sinusoids, 0..SC_GUARD_MAXFREQ */
  double w[SC_GUARD_MAXFREQ];  /**< frequencies, > 0 */
  double a[SC_GUARD_MAXFREQ];  /**< cosine coefficients */
  double b[SC_GUARD_MAXFREQ];  /**< sine coefficients */
} sc_guard;

/** What sc_guard_first_root() found. */
typedef struct {
  int found;      /**< 1: a root in (0, tmax]; 0: none */
  int tangent;    /**< 1: g only touches zero there (|g'| within rounding
                       of 0 over an interval narrower than the tolerance) */
  double t;       /**< the root (tmax when none) */
  double bracket; /**< width of the interval known to hold the root */
  double slope;   /**< g'(t) at the root */
  double curv;    /**< g'' at the root, or at the last refinement iterate
                       (within M3 times the final step): for the grazing
                       margin */
  int steps;      /**< intervals examined (for benchmarks) */
  int ntrig;      /**< 0, or the number of terms (n) whose cos(w_k t) and
                       sin(w_k t) at the returned t are in cs[], sn[], to a
                       few ulps (roots found by the refinement or
                       the closed form) */
  double cs[SC_GUARD_MAXFREQ]; /**< cos(w_k t), when ntrig > 0 */
  double sn[SC_GUARD_MAXFREQ]; /**< sin(w_k t), when ntrig > 0 */
} sc_root;

/** @brief g(t), g'(t), g''(t); any output pointer may be NULL. */
SC_API void sc_guard_eval(const sc_guard *g, double t, double *g0, double *g1,
                   double *g2);

/** @brief An upper bound on |g'''| over all t. */
SC_API double sc_guard_m3(const sc_guard *g);

/**
 * @brief The first root of @p g in (0, tmax].
 * @param skip_start 1 if g(0) = 0 by construction (a slip that starts on
 *        its own re-stick guard): that root is skipped, its sign taken
 *        from g'(0), g''(0).  With 0, a g(0) within rounding of zero is a
 *        root at t = 0 only if g moves up through zero there (g'(0) > 0,
 *        or g'(0) = 0 < g''(0)): every event of docs/model.md is a guard
 *        reaching zero from below; otherwise it is skipped likewise.
 * @param atol, rtol tolerance on the root time: the returned root lies in
 *        an interval of width <= atol + rtol t (or g is within rounding of
 *        zero there).
 * @return SC_OK (found or not: see out->found); SC_EINVAL for a
 *         malformed guard (non-finite coefficients, or coefficients
 *         whose squares overflow, |a| > 1e154; n out of range; w <= 0),
 *         tmax not finite and > 0, atol <= 0 or rtol < 0.
 * Thread safe; no allocation.
 */
SC_API int sc_guard_first_root(const sc_guard *g, double tmax, int skip_start,
                        double atol, double rtol, sc_root *out);

/**
 * A guard with any number of sinusoids, its terms in the caller's arrays:
 * the N-block chain's (docs/chain.md), where a run of m slipping blocks
 * has m frequencies and a stuck block between two runs sees both runs'.
 * sc_guard_first_root() stays the fast path for short guards (bk2).
 */
typedef struct {
  double c0;        /**< constant term */
  double c1;        /**< drift */
  int n;            /**< number of sinusoids, >= 0 */
  const double *w;  /**< n frequencies, > 0 */
  const double *a;  /**< n cosine coefficients */
  const double *b;  /**< n sine coefficients */
} sc_guard_long;

/** What sc_guard_long_first_root() found. */
typedef struct {
  int found;    /**< 1: a root in [0, tmax]; 0: none */
  int tangent;  /**< 1: g' at the root is no more than a touch's within
                     rounding of zero can have (sqrt(2 rounding M2)) */
  double t;     /**< the root (tmax when none) */
  double slope; /**< g'(t) */
  long steps;   /**< steps taken (for benchmarks) */
} sc_root_long;

/** @brief g(t), g'(t), g''(t) of a long guard; any output may be NULL. */
SC_API void sc_guard_long_eval(const sc_guard_long *g, double t, double *g0,
                               double *g1, double *g2);

/**
 * @brief The first root of the long guard @p g in [0, tmax], approached
 * from below in steps that are each proved root-free: at t with g(t) < 0
 * and M2 = sum w_k^2 sqrt(a_k^2 + b_k^2) >= |g''|, the next root is no
 * earlier than the first zero of g(t) + g'(t) s + M2 s^2 / 2 (docs/chain.md,
 * "Events").  Near a simple root the steps are Newton's, shortened; at a
 * touch they shrink geometrically until g passes its maximum or comes
 * within rounding of zero, which is reported as a root (tangent set when
 * g' is within rounding of zero too).
 * @param skip_start 1: g(0) = 0 by construction (a slip starting on its
 *        re-stick guard) and that root is skipped; 0: a g(0) within
 *        rounding of zero is a root only where g rises through it (g'(0)
 *        > 0, or g'(0) = 0 < g''(0)).  A guard that starts above zero
 *        (past its event) has its root at 0.
 * @return SC_OK (found or not: out->found); SC_EINVAL for a malformed
 *         guard (non-finite coefficients or ones whose squares overflow,
 *         |a| > 1e154; n < 0, w <= 0) or tmax not
 *         finite and >= 0; SC_ENOCONV for a start on zero that neither
 *         rises nor falls (g' and g'' within rounding of zero) or more
 *         steps than a march can take (SC_GUARD_LONG_MAXSTEPS).
 * Thread safe; no allocation.
 */
SC_API int sc_guard_long_first_root(const sc_guard_long *g, double tmax,
                                    int skip_start, sc_root_long *out);

/** Where a resumable march stands (sc_guard_long_march.stage). */
enum {
  SC_MARCH_NEW = 0, /**< not started: set this before the first call */
  SC_MARCH_TO,      /**< g still to be evaluated at t */
  SC_MARCH_AT,      /**< g0, g1 are g, g' at t */
  SC_MARCH_DONE,    /**< over: the root in root */
  SC_MARCH_KNOWN    /**< the root (t = HUGE_VAL: none) is known, in root,
                         and past every tmax so far */
};

/**
 * A march of sc_guard_long_first_root() that can be stopped at one tmax
 * and resumed to a later one with the same guard: the state between two
 * sc_guard_long_advance() calls.  Several guards marched side by side,
 * each only as far as the earliest root found so far, take the same
 * steps as each marched alone.
 */
typedef struct {
  int stage;        /**< SC_MARCH_NEW before the first call */
  double t;         /**< the march's point */
  double tsafe;     /**< g < 0 on [0, tsafe) up to rounding */
  double g0;        /**< g at t (stage SC_MARCH_AT) */
  double g1;        /**< g' at t (stage SC_MARCH_AT) */
  long steps;       /**< steps so far */
  sc_root_long root;/**< the root (stage SC_MARCH_DONE) */
  double bounds[6]; /**< the guard's bounds, from the first call */
} sc_guard_long_march;

/**
 * @brief sc_guard_long_first_root() in stages: march @p g from where @p m
 * stands up to @p tmax (the guard must be the same at every call; its
 * arrays may be rebuilt; tmax no smaller than at the call before).
 * Found or not, the result is what
 * sc_guard_long_first_root(g, tmax, skip_start) would give, steps
 * included; a root once found is returned again by later calls.
 * @return as sc_guard_long_first_root().
 */
SC_API int sc_guard_long_advance(const sc_guard_long *g, double tmax,
                                 int skip_start, sc_guard_long_march *m,
                                 sc_root_long *out);

/** Most steps of one sc_guard_long_first_root() search: a guard of
 * period 2 pi needs tens per period far from its roots, so this covers
 * horizons of tens of thousands of periods; beyond, the search stops with
 * SC_ENOCONV rather than run without end. */
#define SC_GUARD_LONG_MAXSTEPS 10000000L

#ifdef __cplusplus
}
#endif
#endif
