/**
 * @file branch.h
 * @brief Periodic orbits of event maps at fixed parameters (all period-m
 *        orbits in an interval, without a start guess) and along one
 *        parameter (branches with folds, flips and discontinuity-induced
 *        bifurcations).
 *
 * The fixed-point search splits an interval of d into pieces on which
 * the itinerary of f^m is constant (so f^m is smooth there), brackets the
 * roots of f^m(d) - d piece by piece, never across a jump, and polishes
 * them with Newton's method.  Branches are continued with the
 * pseudo-arclength layer (continuation.h) on the fixed-point system of
 * f^m; their itinerary is watched at every accepted point, and where it
 * changes the discontinuity-induced bifurcation is located by bisection
 * in the parameter and classified from the degeneracy found there (see
 * docs/branches.md).
 *
 * The objects here borrow the caller's map and change its parameters
 * while they run (a branch sets the continued parameter; it is restored
 * when the run returns).  One object per thread.
 */
#ifndef SLIPCONT_BRANCH_H
#define SLIPCONT_BRANCH_H

#include <stddef.h>

#include "slipcont/common.h"
#include "slipcont/linalg.h"
#include "slipcont/map.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ */
/* All period-m orbits in an interval                                   */

/** One orbit (or family of neutral orbits) found by the search. */
typedef struct {
  int period;          /**< the minimal period m */
  int neutral;         /**< 1: a continuous family of neutral orbits */
  double multiplier;   /**< (f^m)' on the orbit; 1 for a family */
  int stable;          /**< |multiplier| < 1 (0 for a family) */
  double lo, hi;       /**< family: the d-interval of the piece holding it
                            (the located ends of its itinerary); an
                            isolated orbit: lo = hi = d[0] */
  double residual;     /**< |f^m(d[0]) - d[0]| */
  const double *d;     /**< the m orbit points, from the smallest one, in
                            the order of the orbit (owned by the set) */
  const char *itinerary; /**< itineraries of the m iterates, in the same
                              order, joined by ';' */
} sc_orbit_info;

/** The result of sc_fixed_points_find(). */
typedef struct sc_orbit_set sc_orbit_set;

/** What sc_fixed_points_find() scans. */
typedef struct {
  int period;      /**< m >= 1 */
  double from, to; /**< the d interval (from < to) */
  size_t steps;    /**< initial scan grid, >= 2 points, ends included */
} sc_fixed_points_spec;

/**
 * @brief Find every orbit of minimal period @p spec->period with a point
 * in [from, to], at the current parameters of @p m.
 *
 * f^m is evaluated on the grid; where the itinerary differs between two
 * neighbours the change is located by bisection until the bracket is
 * within newton_atol + newton_rtol |d| (several changes between two grid
 * points are found one after another).  On each piece of constant
 * itinerary, sign changes of f^m(d) - d between consecutive samples are
 * bracketed and refined by Newton's method safeguarded by bisection (the
 * exact derivative), to the shooting tolerances.  A root whose orbit has
 * a smaller minimal period is not reported (counted in
 * sc_orbit_set_nlower()).  Each orbit is reported once, whatever point
 * of it was found first: two orbits are the same when their point sets
 * agree to the tolerance.  A piece whose iterates are all neutral with
 * f^m(d) - d within newton_ftol of zero is a family of neutral orbits,
 * reported once with its d-interval.  Roots of even multiplicity and two
 * roots between neighbouring samples of one piece are not bracketed: the
 * grid decides what is resolved.  Points where the map is undefined are
 * skipped and counted.
 *
 * @return SC_OK; SC_EINVAL for a bad spec (message names the field);
 *         SC_ENOMEM; an error of the model other than an undefined map.
 */
SC_API int sc_fixed_points_find(sc_map *m, const sc_fixed_points_spec *spec,
                         sc_orbit_set **out, sc_msg *msg);

/** Number of orbits (families included), by increasing smallest point. */
SC_API size_t sc_orbit_set_count(const sc_orbit_set *s);
/** @brief Orbit @p i; SC_EINVAL for i out of range. */
SC_API int sc_orbit_set_get(const sc_orbit_set *s, size_t i, sc_orbit_info *o);
/** Pieces of constant itinerary the interval was split into. */
SC_API size_t sc_orbit_set_npieces(const sc_orbit_set *s);
/** Roots whose orbit has a smaller minimal period (not reported). */
SC_API size_t sc_orbit_set_nlower(const sc_orbit_set *s);
/** Grid or bisection points where the map was undefined. */
SC_API size_t sc_orbit_set_nundefined(const sc_orbit_set *s);
/** @brief Release @p s; NULL is accepted. */
SC_API void sc_orbit_set_free(sc_orbit_set *s);

/* ------------------------------------------------------------------ */
/* Branches of periodic orbits in one parameter                          */

/** Kinds of special points on an orbit branch (points.csv labels). */
typedef enum {
  SC_PT_LP = 0, /**< fold: multiplier +1 */
  SC_PT_PD,     /**< flip: multiplier -1 */
  SC_PT_GR,     /**< grazing-sliding: a re-stick guard tangent */
  SC_PT_CS,     /**< crossing-sliding: a global stick phase of length 0 */
  SC_PT_SW,     /**< switching: a global stick phase at d* */
  SC_PT_DI,     /**< an itinerary change with no degeneracy found */
  SC_PT_EP,     /**< end point of a branch, with its reason */
} sc_point_label;

/** Label text: "LP", "PD", "GR", "CS", "SW", "DI", "EP". */
SC_API const char *sc_point_label_text(sc_point_label l);

/** What sc_orbit_branch_run() continues. */
typedef struct {
  size_t param;      /**< index of the continued parameter */
  double from, to;   /**< start value and the other end of the interval */
  int period;        /**< period m of the starting orbit, >= 1 */
  double d0;         /**< guess of a point of the starting orbit; polished
                          by multiple shooting at p = from */
  int switch_pd;     /**< 1: at each flip also continue the period-2m
                          branch (recursively, up to max_branches) */
  long max_points;   /**< accepted points per branch segment, >= 2 */
  int max_branches;  /**< branches (segments) at most, >= 1 */
  int max_period;    /**< no branch switching beyond this period */
  double h0, hmax;   /**< arclength steps (0: derived from |to - from|) */
  /** Backend of the bordered systems; NULL for dense. */
  const sc_linsolve_type *linsolve;
  /** Called after each accepted point with the number of points so far;
   * non-zero stops the run with SC_ECALLBACK.  May be NULL. */
  int (*progress)(void *ctx, size_t npoints);
  void *progress_ctx;
} sc_orbit_branch_spec;

/** One accepted point of a branch. */
typedef struct {
  int branch;        /**< segment number, from 0 */
  int period;
  double p;          /**< parameter value */
  double d;          /**< first orbit point (the continued unknown) */
  double multiplier; /**< (f^m)'(d) */
  int stable;        /**< |multiplier| < 1 */
  const char *itinerary; /**< of f^m from d, iterates joined by '|' */
} sc_orbit_point_info;

/** One special point. */
typedef struct {
  sc_point_label label;
  int branch;        /**< segment number */
  int period;        /**< period of the orbit at the point */
  double p, d, multiplier;
  double degeneracy; /**< GR: graze_margin, CS: gsp_gap, SW: dstar_dist;
                        LP, PD: multiplier -+ 1; EP: NaN */
  double width;      /**< DIB: final bisection bracket in p; else 0 */
  const char *note;  /**< which block and mode, what followed, reasons */
} sc_orbit_special_info;

typedef struct sc_orbit_branch sc_orbit_branch;

/**
 * @brief Prepare a run: check @p spec and take all storage (max_points x
 * max_branches points, as many special points).
 * @return SC_OK; SC_EINVAL naming the bad field; SC_ENOMEM.
 */
SC_API int sc_orbit_branch_alloc(sc_map *m, const sc_orbit_branch_spec *spec,
                          sc_orbit_branch **out, sc_msg *msg);

/**
 * @brief Add a starting orbit besides (d0, from): the period-@p period
 * orbit through a guess @p d at parameter @p p, polished by multiple
 * shooting and continued in both directions within [from, to].  Call
 * before sc_orbit_branch_run(); each start takes one or two of the
 * max_branches segments.
 * @return SC_OK; SC_EINVAL for p outside the interval, a non-finite d or
 *         a period outside [1, max_period]; SC_ENOMEM when more than
 *         max_branches starts were added.
 */
SC_API int sc_orbit_branch_add_start(sc_orbit_branch *b, double p, double d,
                              int period, sc_msg *msg);

/**
 * @brief Continue the branch from (d0, from) towards @p to, then from
 * each added start in both directions.
 *
 * Labels: LP and PD are the zeros of the fold and flip test functions of
 * the continuation layer, located until both the arclength step and the
 * test function are within tolerance.  A change of the itinerary of f^m
 * between two accepted points, or a corrector that can go no further,
 * starts a bisection in the parameter between the last point on the
 * known side (the orbit followed there by shooting) and the other side,
 * until the bracket is within newton_atol + newton_rtol |p|; the
 * located point is classified GR, CS or SW by the smallest of its
 * margins (graze_margin, gsp_gap, dstar_dist) when that is below
 * SC_DIB_MARGIN_TOL, DI otherwise.  The branch then continues on the
 * other side with the new itinerary when shooting finds an orbit there
 * (period m, or m -+ 1 after a crossing-sliding), and ends with a note
 * otherwise.  EP marks every end (interval end, max_points, a failure),
 * with the reason in its note.
 * @return SC_OK (the branches ended; see the EP notes); SC_EINVAL,
 *         SC_ENOCONV or SC_ENEUTRAL when the starting orbit cannot be
 *         found; SC_ECALLBACK if progress stopped it; SC_ENOMEM.
 */
SC_API int sc_orbit_branch_run(sc_orbit_branch *b, sc_msg *msg);

/** Accepted points, in the order they were computed. */
SC_API size_t sc_orbit_branch_npoints(const sc_orbit_branch *b);
/** @brief Point @p i; SC_EINVAL for i out of range. */
SC_API int sc_orbit_branch_point(const sc_orbit_branch *b, size_t i,
                          sc_orbit_point_info *pt);
/** Special points, in the order they were found. */
SC_API size_t sc_orbit_branch_nspecial(const sc_orbit_branch *b);
/** @brief Special point @p i; SC_EINVAL for i out of range. */
SC_API int sc_orbit_branch_special(const sc_orbit_branch *b, size_t i,
                            sc_orbit_special_info *sp);
/** Branch segments computed. */
SC_API int sc_orbit_branch_nbranches(const sc_orbit_branch *b);
/** @brief Release @p b; NULL is accepted. */
SC_API void sc_orbit_branch_free(sc_orbit_branch *b);

/**
 * A margin below this counts as the degeneracy of a located
 * discontinuity-induced bifurcation.  The location brackets the
 * parameter to about 1e-13.  Grazing and crossing margins vary linearly
 * with the parameter there; |d - d*| at a switching varies like the
 * square root of the distance in the parameter (f' grows like
 * |d - d*|^(-1/2), MODEL.md), so it is left at up to ~1e-7 (slope
 * factors included).  1e-6 is above both, and far below the margins of a
 * regular orbit (1e-3 and more).
 */
#define SC_DIB_MARGIN_TOL 1e-6

/**
 * @brief Classify a located itinerary change from the margins of f^m at
 * the orbit on either side (@p a, @p b: sc_map_iterate() values with
 * their margins): the smallest of graze_margin, gsp_gap and dstar_dist
 * over both, GR, CS or SW, when below SC_DIB_MARGIN_TOL; DI otherwise.
 * @p note receives which block and mode ("block 2 re-sticks ending slip
 * mode 12"), @p degeneracy the margin.
 * @return the label.
 */
SC_API sc_point_label sc_dib_classify(const sc_map_value *a, const sc_map_value *b,
                               double *degeneracy, char *note, size_t len);

#ifdef __cplusplus
}
#endif
#endif
