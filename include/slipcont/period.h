/**
 * @file period.h
 * @brief Period detection on the orbit of an event map: a detector that
 *        the caller feeds one iterate at a time (sc_period_reset(),
 *        sc_period_push()), or that iterates a map itself
 *        (sc_period_find()).  Charts (chart.h) and sweeps (analysis.h)
 *        classify their orbits with it.
 *
 * The period rule (docs/charts.md):
 *
 * - the tolerance is tol = rtol * E + SC_PERIOD_FLOOR_ULPS * eps * A, where
 *   E = max - min and A = max |x| over every iterate seen so far (the
 *   attractor and the transient that leads to it, so E is never smaller
 *   than the attractor's extent), rtol is sc_accuracy.period_rtol and eps
 *   is DBL_EPSILON;
 * - period p is *confirmed* after the iterate x_k when
 *   |x_j - x_{j-p}| <= tol for the last `confirm * p` iterates j, i.e. the
 *   last (confirm + 1) p iterates repeat with period p (confirm full
 *   cycles after a first one);
 * - the reported period is the smallest confirmed p, except that p is not
 *   accepted while, for a proper divisor q of p, the largest lag-q
 *   differences of the window's last three cycles decay geometrically
 *   towards a limit within the tolerance of 0 (the orbit is converging to
 *   a period-q orbit whose multiplier is near -1: lag-p differences then
 *   decay faster than lag-q ones); detection goes on.  This near-flip
 *   test needs confirm >= 3;
 * - detection stops at the first accepted period (early stop);
 * - "high" (SC_PERIOD_HIGH): no period 1..max_period accepted within the
 *   iterate budget: longer periods, chaos, quasi-periodicity;
 * - "not settled" (SC_PERIOD_UNSETTLED): as "high", but at the end of the
 *   budget the lag-p differences of some p <= max_period were still
 *   decaying geometrically towards 0 (sc_period_settling()): the orbit is
 *   converging, not chaotic; a longer transient would classify it;
 * - "undefined" (SC_PERIOD_UNDEFINED): an iterate failed with SC_EUNDEF
 *   (the map is not defined there) or SC_ENONFINITE (the orbit left
 *   the range of doubles).  Any other failure of the map is an error.
 */
#ifndef SLIPCONT_PERIOD_H
#define SLIPCONT_PERIOD_H

#include "slipcont/common.h"
#include "slipcont/map.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Period class: no period up to max_period (long period, chaos,
 * quasi-periodicity, or not settled within the iterate budget). */
#define SC_PERIOD_HIGH 0
/** Period class: the map is undefined somewhere on the orbit. */
#define SC_PERIOD_UNDEFINED (-1)
/** Period class: no period accepted within the iterate budget, but the
 * orbit is still converging to an orbit of period <= max_period (the
 * lag-p differences decay geometrically towards 0: sc_period_settling()):
 * a longer transient would classify it.  Distinct from "high" (chaos,
 * long periods, quasi-periodicity). */
#define SC_PERIOD_UNSETTLED (-2)
/** Largest max_period accepted. */
#define SC_PERIOD_MAX 256
/** Default max_period of a chart (fig 5.7: periods above 16 in one
 * colour). */
#define SC_PERIOD_DEFAULT_MAX 16
/** Default number of confirmation cycles. */
#define SC_PERIOD_DEFAULT_CONFIRM 4
/** Largest number of confirmation cycles accepted. */
#define SC_PERIOD_MAX_CONFIRM 64
/** The tolerance floor in units of DBL_EPSILON times the largest |x|:
 * a few rounding errors of one iterate, so that an orbit that repeats to
 * the last bits is periodic even when its extent is zero. */
#define SC_PERIOD_FLOOR_ULPS 8
/** The largest rtol accepted: a tolerance of a tenth of the orbit's
 * extent already merges distinct points of most orbits; beyond it the
 * periods found mean nothing. */
#define SC_PERIOD_MAX_RTOL 0.1

/** A period detector: workspace for one orbit at a time. */
typedef struct sc_period sc_period;

/**
 * @brief Create a detector.
 * @param max_period largest period detected, 1..SC_PERIOD_MAX.
 * @param confirm confirmation cycles, 1..SC_PERIOD_MAX_CONFIRM.
 * @param rtol tolerance relative to the orbit's extent, in
 *        [DBL_EPSILON, SC_PERIOD_MAX_RTOL] (usually sc_accuracy.period_rtol).
 * @param out the new detector (NULL on failure); free with
 *        sc_period_free().
 * @return SC_OK, SC_EINVAL (argument out of range; the message says
 *         which), SC_ENOMEM.  All memory is taken here: reset and push
 *         never allocate.
 */
SC_API int sc_period_alloc(int max_period, int confirm, double rtol,
                           sc_period **out, sc_msg *msg);

/** @brief Release @p pd; NULL is accepted. */
SC_API void sc_period_free(sc_period *pd);

/** @brief Start a new orbit at @p x0 (the initial state, iterate 0). */
SC_API void sc_period_reset(sc_period *pd, double x0);

/**
 * @brief Feed the next iterate.
 * @return the accepted period (1..max_period) once one is accepted, and
 *         the same value for every later push; 0 while none is.
 */
SC_API int sc_period_push(sc_period *pd, double x);

/**
 * @brief Whether the orbit pushed so far is still converging to a
 * periodic orbit: the smallest p <= max_period whose largest lag-p
 * difference decreased from each block of iterates to the next (blocks
 * of at least 8 iterates, a whole number of p) over the last blocks,
 * at least 4 of them and covering at least half of the orbit, and is
 * still above the tolerance; 0 if none (or too few iterates).  Used when
 * no period was accepted.
 */
SC_API int sc_period_settling(const sc_period *pd);

/** Tolerance in use after the last push (see the rule above). */
SC_API double sc_period_tol(const sc_period *pd);
/** Extent max - min of the iterates seen since the last reset. */
SC_API double sc_period_extent(const sc_period *pd);

/** Outcome of sc_period_find(). */
typedef struct {
  int period;       /**< 1..max_period, SC_PERIOD_HIGH, SC_PERIOD_UNSETTLED or
                         SC_PERIOD_UNDEFINED */
  long iterations;  /**< map iterates made (the one that failed included) */
  double d;         /**< last state reached (before a failing iterate) */
  double tol;       /**< tolerance in use at the end */
  int map_status;   /**< SC_OK, or the status that made it undefined */
} sc_period_result;

/**
 * @brief Iterate @p m from @p d0 at most @p max_iter times and classify
 * the orbit (see the period rule above).  Evaluates values only (no
 * derivatives, no itineraries); never allocates.
 * @param max_iter iterate budget (the chart's `transient`), >= 1.
 * @return SC_OK (the class is in @p res, undefined points included);
 *         SC_EINVAL (bad max_iter or non-finite d0); or the status of a
 *         map failure other than SC_EUNDEF / SC_ENONFINITE (e.g.
 *         SC_ENOCONV), with the map's message.
 */
SC_API int sc_period_find(sc_period *pd, sc_map *m, double d0, long max_iter,
                          sc_period_result *res, sc_msg *msg);

#ifdef __cplusplus
}
#endif
#endif
