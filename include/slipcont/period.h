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
/** Period class of an n-dimensional map's orbit (n >= 2): no period up
 * to max_period, not settling, and its last points on a closed curve
 * (sc_orbit_on_circle()): an invariant circle, quasi-periodic (or of a
 * period above the tail's half).  One-dimensional maps never get it. */
#define SC_PERIOD_CIRCLE (-3)
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

/* ------------------------------------------------------------------ */
/* n-dimensional orbits                                                 */

/** A period detector for states of n components (opaque). */
typedef struct sc_periodn sc_periodn;

/**
 * @brief Create a detector for states of @p dim components: the period
 * rule above with |x_j - x_{j-p}| and the extent taken in the max norm,
 * tol = rtol * max_i (max x_i - min x_i) + SC_PERIOD_FLOOR_ULPS eps
 * max_{i,k} |x_{k,i}|.  With dim = 1 it gives sc_period's answers at the
 * same iterates (the same rule, without its lazy bookkeeping).
 * @param dim 1..SC_MAXDIM; the other arguments as sc_period_alloc().
 * @return SC_OK, SC_EINVAL (the message names the argument), SC_ENOMEM.
 *         Reset and push never allocate.
 */
SC_API int sc_periodn_alloc(size_t dim, int max_period, int confirm,
                            double rtol, sc_periodn **out, sc_msg *msg);
/** @brief Release @p pd; NULL is accepted. */
SC_API void sc_periodn_free(sc_periodn *pd);
/** @brief Start a new orbit at the state @p x0 (dim values). */
SC_API void sc_periodn_reset(sc_periodn *pd, const double *x0);
/** @brief Feed the next state (dim values); returns as sc_period_push(). */
SC_API int sc_periodn_push(sc_periodn *pd, const double *x);
/** @brief As sc_period_settling(), on the max-norm differences. */
SC_API int sc_periodn_settling(const sc_periodn *pd);
/** @brief Tolerance in use after the last push. */
SC_API double sc_periodn_tol(const sc_periodn *pd);

/** Points of an orbit's tail the invariant-circle test looks at by
 * default (charts): enough that the inscribed polygons of a smooth curve
 * differ by a fraction of a percent, few enough that sorting them costs
 * little next to the iterates that led there. */
#define SC_CIRCLE_POINTS 512
/** The invariant-circle test's bound on L_m / L_{m/2} (see
 * sc_orbit_on_circle()): the polygons' lengths of points on a curve
 * converge (the ratio tends to 1), those of a scattered set grow with the
 * number of points (the ratio tends to 2); the test splits at sqrt(2),
 * the geometric middle. */
#define SC_CIRCLE_RATIO 1.4142135623730951

/** The invariant-circle test's allowance for points out of order: one
 * in this many (4 of 512) beyond the one wrap, for the pairs of points
 * whose angles differ by rounding alone; a chaotic attractor folds, and
 * puts a third of its images or more out of order (docs/charts.md). */
#define SC_CIRCLE_TIES 128

/**
 * @brief Whether the states @p pts[0..m-1] (m >= 16, @p dim >= 2
 * components each, in the order of the orbit) lie on a closed curve.  The
 * points are seen in the plane of their first two components, by their
 * angle about their centroid.  Sorted by that angle, points on a closed
 * curve that is star-shaped about the centroid are in the curve's order,
 * so the closed polygon through them is inscribed in the curve: its
 * length stays below the curve's and grows towards it as points are added
 * (triangle inequality), and the ratio of the lengths through all m
 * points and through half of them tends to 1, whichever half.  Points
 * scattered over an area or a fractal (a chaotic attractor) are joined
 * across its width, and the length grows with their number: the ratio
 * tends to 2.  The halves are the even and the odd iterates (a chaotic
 * attractor in bands visited in turn has one band in each) and the older
 * and the newer half; the orbit is on a circle when the largest of the
 * four ratios is below SC_CIRCLE_RATIO, the map keeps the points' cyclic
 * order and the orbit is not periodic.  Order: on an invariant circle the
 * map is a homeomorphism of the circle, so the images of the points taken
 * by angle come by angle in the same cyclic order (or the reverse one):
 * their ranks have one descent, the wrap (or one ascent); a chaotic
 * attractor folds, and a curve-like one (henon at a = 1.36, b = 0.26)
 * passes the length test but not this one.  At most 1 + m /
 * SC_CIRCLE_TIES points may be out of order.  Not periodic: at least half
 * of the gaps between angle neighbours exceed @p tol (an orbit of at most
 * m/2 distinct points has gaps 0).  A curve that is not
 * star-shaped about its centroid reads as scattered (the test is
 * conservative).  docs/charts.md gives the evidence on ghenon and henon.
 * @param tol distance (max norm of the two components) under which two
 *        points are one (the period detector's tolerance).
 * @param work 3 m doubles of workspace.
 * @param ratio out (may be NULL): the largest of the four ratios.
 * @return 1 on a closed curve, 0 not (also for m < 16 or dim < 2).
 */
SC_API int sc_orbit_on_circle(const double *pts, size_t m, size_t dim,
                              double tol, double *work, double *ratio);

#ifdef __cplusplus
}
#endif
#endif
