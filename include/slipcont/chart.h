/**
 * @file chart.h
 * @brief Period detection on the orbit of an event map, and two-parameter
 *        period charts (fig 5.7 of the reference chapter).
 *
 * Two levels, as in GSL's odeiv2:
 *
 * - a period detector (`sc_period`) that the caller feeds one iterate at a
 *   time (sc_period_reset(), sc_period_push()), or that iterates a map
 *   itself (sc_period_find());
 * - a chart driver (sc_chart_rows()) that runs the detector at every point
 *   of a grid over two model parameters, in parallel with OpenMP.
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
 *   (no return to a global stick phase) or SC_ENONFINITE (the orbit left
 *   the range of doubles).  Any other failure of the map is an error.
 */
#ifndef SLIPCONT_CHART_H
#define SLIPCONT_CHART_H

#include <stdint.h>

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

/** How each point of a chart row starts. */
enum {
  SC_CHART_SEED_FIXED = 0,     /**< every point from d0 */
  SC_CHART_SEED_NEIGHBOUR = 1, /**< from the final state of the previous
                                    point of the same row (d0 for the first
                                    point and after an undefined one) */
};

/** Most grid points of a chart (x_steps * y_steps). */
#define SC_CHART_MAX_POINTS 100000000L
/** Most memory a chart's results may need, in bytes (2 GiB): the whole
 * grid of sc_chart_point is held by the caller that writes the files. */
#define SC_CHART_MAX_BYTES (2048.0 * 1024 * 1024)

/**
 * A chart over two parameters of a map.  Steps count grid points with
 * both ends included: x_i = sc_grid(x_from, x_to, x_steps, i, x_scale)
 * (common.h: equal differences, or equal ratios on a log scale),
 * i = 0..x_steps-1, the last one exactly x_to (likewise for y).  A row is
 * one value of y, all values of x.
 */
typedef struct {
  const char *x;      /**< parameter name for the x axis */
  double x_from;      /**< first x value */
  double x_to;        /**< last x value, exactly a grid point */
  long x_steps;       /**< >= 2 */
  const char *y;      /**< parameter name for the y axis, not x */
  double y_from;      /**< first y value */
  double y_to;        /**< last y value, exactly a grid point */
  long y_steps;       /**< >= 2 */
  int x_scale;        /**< sc_grid_scale of x (default SC_GRID_LINEAR) */
  int y_scale;        /**< sc_grid_scale of y (default SC_GRID_LINEAR) */
  double d0;          /**< initial state */
  long transient;     /**< most map iterates per point, 1..INT32_MAX */
  int max_period;     /**< 1..SC_PERIOD_MAX (default 16) */
  int confirm;        /**< confirmation cycles (default 4) */
  int seed;           /**< SC_CHART_SEED_FIXED or SC_CHART_SEED_NEIGHBOUR */
} sc_chart_spec;

/** One grid point's result (16 bytes). */
typedef struct {
  double d;            /**< final state (last defined iterate) */
  int32_t period;      /**< 1..max_period, SC_PERIOD_HIGH,
                            SC_PERIOD_UNSETTLED or SC_PERIOD_UNDEFINED */
  int32_t iterations;  /**< map iterates made at this point */
} sc_chart_point;

/** @brief Defaults: no axes, transient 1000, max_period 16, confirm 4,
 * seed fixed, d0 = 0. */
SC_API void sc_chart_spec_default(sc_chart_spec *s);

/**
 * @brief Check a chart against the model of @p m before any work: steps
 * >= 2 (a zero or negative count is refused), known and distinct
 * parameters, both ends of each axis inside the parameter's valid range,
 * finite d0, transient, max_period, confirm and seed in range, at most
 * SC_CHART_MAX_POINTS points and SC_CHART_MAX_BYTES of results.
 * @return SC_OK or SC_EINVAL with a message naming the key
 *         (`x-steps = 0 (valid: >= 2)`, `x and y are both 'alpha'`, ...).
 */
SC_API int sc_chart_check(const sc_map *m, const sc_chart_spec *s, sc_msg *msg);

/** x value of column @p i (0 <= i < x_steps). */
SC_API double sc_chart_x(const sc_chart_spec *s, long i);
/** y value of row @p j (0 <= j < y_steps). */
SC_API double sc_chart_y(const sc_chart_spec *s, long j);

/**
 * Progress callback of sc_chart_rows(): @p done points of this call are
 * complete.  Called only from the thread that called sc_chart_rows()
 * (OpenMP thread 0), after some of its own points; return non-zero to
 * cancel (the call then returns SC_ECALLBACK).
 */
typedef int (*sc_chart_progress_fn)(void *ctx, long done);

/**
 * @brief Compute rows first, first + stride, ..., (count rows) of a chart.
 *
 * Every thread works on its own clone of @p proto (sc_map_clone()) and its
 * own detector; with SC_CHART_SEED_FIXED the points are shared among
 * threads, with SC_CHART_SEED_NEIGHBOUR whole rows are (a row is then
 * sequential), both with dynamic scheduling.  The result of a point
 * depends only on its parameters, d0 and (neighbour) its row, so the
 * output is bit-identical for any thread count and any division of rows
 * among calls or processes.
 *
 * @param proto the map with every other parameter and option set; not
 *        modified (read by the threads while they clone it).
 * @param s a chart that passed sc_chart_check() with this map.
 * @param first first row (0 <= first < y_steps).
 * @param count rows to compute, >= 0.
 * @param stride row step, >= 1; the last row must be < y_steps.
 * @param threads OpenMP threads; 0 for the OpenMP default
 *        (OMP_NUM_THREADS or omp_set_num_threads()).
 * @param progress optional callback (see sc_chart_progress_fn); NULL.
 * @param out caller-owned array of count * x_steps points, row-major
 *        (out[k * x_steps + i]: row first + k stride, column i).
 * @return SC_OK; SC_EINVAL (bad arguments or chart); SC_ENOMEM; a map
 *         failure other than SC_EUNDEF/SC_ENONFINITE, with the message of
 *         the failing point of lowest index and its parameter values;
 *         SC_ECALLBACK if the callback cancelled (rows are then partly
 *         computed).
 */
SC_API int sc_chart_rows(const sc_map *proto, const sc_chart_spec *s, long first,
                         long count, long stride, int threads,
                         sc_chart_progress_fn progress, void *ctx,
                         sc_chart_point *out, sc_msg *msg);

#ifdef __cplusplus
}
#endif
#endif
