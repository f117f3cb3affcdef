/**
 * @file analysis.h
 * @brief Brute-force analysis of event maps: one-parameter sweeps
 *        (bifurcation diagrams by iteration), parameter grids and period
 *        detection.
 *
 * A sweep iterates the map at each value of one parameter on a grid and
 * keeps the tail of each orbit.  It works on clones of the caller's map
 * (the caller's instance is never modified), takes all its memory in
 * sc_sweep_alloc(), and never allocates while it runs.
 */
#ifndef SLIPCONT_ANALYSIS_H
#define SLIPCONT_ANALYSIS_H

#include <stddef.h>

#include "slipcont/common.h"
#include "slipcont/map.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Point @p i of the linear grid of @p steps points from @p from to
 * @p to: sc_grid(from, to, steps, i, SC_GRID_LINEAR) (common.h).
 * @return the point; NaN for i >= steps or steps = 0.
 */
SC_API double sc_grid_point(double from, double to, size_t steps, size_t i);

/** Largest period a sweep tells apart (longer ones, chaos: 0). */
#define SC_SWEEP_PERIOD_MAX 16

/**
 * @brief The period of a stored tail @p x[0..n-1] of an orbit, by the one
 * period rule of slipcont (chart.h, sc_period) with one confirmation
 * cycle: the detector is reset at x[0] and fed the rest; periods up to
 * min(pmax, n/2).  A tail whose whole spread is within
 * rtol max|x| (+ SC_PERIOD_FLOOR_ULPS ulps) is at rest: period 1.  Sweeps
 * classify their points with the detector itself over every iterate (as
 * charts do), not with this function.
 * @param rtol relative tolerance (sc_accuracy.period_rtol), > 0.
 * @return the period, or 0 if none was found ("chaos or a period above
 *         pmax"); -1 for n = 0 or a non-finite value.
 */
SC_API int sc_sweep_period(const double *x, size_t n, double rtol, int pmax);

/** Order of a sweep over the parameter grid. */
typedef enum {
  SC_SWEEP_UP = 1,   /**< increasing parameter values */
  SC_SWEEP_DOWN = 2, /**< decreasing parameter values */
  SC_SWEEP_BOTH = 3, /**< increasing, then decreasing */
} sc_sweep_direction;

/** Initial state at each parameter value. */
typedef enum {
  SC_SEED_FIXED = 0,    /**< every value starts from d0 (parallel) */
  SC_SEED_PREVIOUS = 1, /**< from the final state of the previous value */
} sc_sweep_seed;

/**
 * What a sweep computes.  The grid is sc_grid(from, to, steps, ., x_scale)
 * (common.h); from > to is allowed and covers the same interval.
 */
typedef struct {
  size_t param;     /**< index of the swept parameter (models.h order) */
  double from;      /**< first grid value, inside the parameter's range */
  double to;        /**< last grid value, inside the parameter's range */
  size_t steps;     /**< grid points, >= 1, ends included */
  int x_scale;      /**< sc_grid_scale: SC_GRID_LINEAR (0) or SC_GRID_LOG */
  int iterations;   /**< iterates at each value, >= 1 */
  int keep;         /**< last iterates kept, 1 <= keep <= iterations */
  double d0;        /**< initial state */
  int direction;    /**< sc_sweep_direction */
  int seed;         /**< sc_sweep_seed */
  /** Called after each parameter value with the number done and the
   * total (from one thread at a time); non-zero stops the sweep with
   * SC_ECALLBACK.  May be NULL. */
  int (*progress)(void *ctx, size_t done, size_t total);
  void *progress_ctx; /**< passed to progress */
  /** A map of n > 1 components: the initial state's n values (copied by
   * sc_sweep_alloc()); NULL starts every component at d0.  Unused for
   * n = 1. */
  const double *x0;
} sc_sweep_spec;

/** Status of a point whose map was undefined (written as period -1). */
#define SC_SWEEP_UNDEFINED (-1)

/** The result at one parameter value of one pass. */
typedef struct {
  double p;         /**< parameter value */
  int direction;    /**< SC_SWEEP_UP or SC_SWEEP_DOWN: the pass */
  int status;       /**< SC_OK, or why the map failed (SC_EUNDEF, ...) */
  int period;       /**< the period rule of chart.h (sc_period, max
                         SC_SWEEP_PERIOD_MAX, SC_PERIOD_DEFAULT_CONFIRM
                         cycles) over every iterate of this value: the
                         class a chart with transient = iterations gives;
                         0 none (SC_PERIOD_HIGH); SC_PERIOD_UNSETTLED (-2)
                         still converging;
                         SC_SWEEP_UNDEFINED if status != SC_OK */
  const double *d;  /**< the kept iterates (keep of them, each of dim
                         components), or NULL when status != SC_OK */
  int nd;           /**< number of kept iterates (0 when undefined) */
  size_t dim;       /**< components of a state (the map's n) */
} sc_sweep_point;

/** A prepared sweep and its results (opaque; sc_sweep_alloc()). */
typedef struct sc_sweep sc_sweep;

/**
 * @brief Prepare a sweep of @p m (cloned: one instance per thread with
 * SC_SEED_FIXED, one with SC_SEED_PREVIOUS) and all result storage.
 * @return SC_OK; SC_EINVAL for a bad spec (the message names the field
 *         and its valid range); SC_ENOMEM.
 */
SC_API int sc_sweep_alloc(const sc_map *m, const sc_sweep_spec *spec,
                          sc_sweep **out, sc_msg *msg);

/**
 * @brief Run the sweep.  With SC_SEED_FIXED the parameter values are
 * shared among OpenMP threads; every value is computed the same way on
 * any thread, so the results are identical for any thread count.  With
 * SC_SEED_PREVIOUS (and SC_SWEEP_BOTH) the passes run in order and each
 * value starts from the final state of the one before; after an
 * undefined map the next value starts from d0 again.
 *
 * An undefined map (SC_EUNDEF), a numerical flow that failed (SC_ENOCONV)
 * or a non-finite value at one parameter value is recorded in that
 * point's status and the sweep goes on.
 * @return SC_OK; SC_ECALLBACK if progress stopped it; any other error of
 *         the model (SC_EINTERNAL, SC_ENOMEM, SC_EINVAL from a refused
 *         parameter value), with the message.
 */
SC_API int sc_sweep_run(sc_sweep *s, sc_msg *msg);

/** Number of points: steps, times 2 for SC_SWEEP_BOTH. */
SC_API size_t sc_sweep_npoints(const sc_sweep *s);

/**
 * @brief Point @p i (0 <= i < sc_sweep_npoints()), in the order of the
 * passes: the up pass by increasing parameter, then the down pass by
 * decreasing parameter.  The kept iterates stay owned by @p s.
 * @return SC_OK or SC_EINVAL for i out of range.
 */
SC_API int sc_sweep_get_point(const sc_sweep *s, size_t i, sc_sweep_point *pt);

/** Number of points whose map was undefined. */
SC_API size_t sc_sweep_nundefined(const sc_sweep *s);
/** The message of the first undefined point (in point order), or "". */
SC_API const char *sc_sweep_undefined_reason(const sc_sweep *s);
/** Map evaluations made by the sweep (all threads). */
SC_API unsigned long sc_sweep_nevals(const sc_sweep *s);

/** @brief Release @p s; NULL is accepted. */
SC_API void sc_sweep_free(sc_sweep *s);

#ifdef __cplusplus
}
#endif
#endif
