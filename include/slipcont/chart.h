/**
 * @file chart.h
 * @brief Two-parameter period charts (fig 5.7 of the reference chapter):
 *        a chart driver (sc_chart_rows()) that runs the period detector
 *        of period.h at every point of a grid over two model parameters,
 *        in parallel with OpenMP.  The period rule is period.h's
 *        (docs/charts.md).
 */
#ifndef SLIPCONT_CHART_H
#define SLIPCONT_CHART_H

#include <stdint.h>

#include "slipcont/common.h"
#include "slipcont/map.h"
#include "slipcont/period.h"

#ifdef __cplusplus
extern "C" {
#endif

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
  /** A map of n > 1 components: the initial state's n values (owned by
   * the caller); NULL starts every component at d0.  Unused for n = 1. */
  const double *x0;
} sc_chart_spec;

/** One grid point's result (16 bytes). */
typedef struct {
  double d;            /**< final state (last defined iterate); of a
                            map of n > 1 components its first one */
  int32_t period;      /**< 1..max_period, SC_PERIOD_HIGH,
                            SC_PERIOD_UNSETTLED, SC_PERIOD_UNDEFINED or
                            (n > 1) SC_PERIOD_CIRCLE */
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
 * own detector (sc_periodn for a map of n > 1 components, whose orbits
 * with no period are then tested for an invariant circle on their last
 * SC_CIRCLE_POINTS points: sc_orbit_on_circle()); with SC_CHART_SEED_FIXED the points are shared among
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
