/**
 * @file orbits.h
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
 * changes the discontinuity-induced bifurcation is located by Newton's
 * method on its defining system with the model's border functions (see
 * docs/branches.md).
 *
 * The objects here borrow the caller's map and change its parameters
 * while they run (a branch sets the continued parameter; it is restored
 * when the run returns).  One object per thread.
 */
#ifndef SLIPCONT_ORBITS_H
#define SLIPCONT_ORBITS_H

#include <stddef.h>

#include "slipcont/common.h"
#include "slipcont/linalg.h"
#include "slipcont/map.h"
#include "slipcont/shooting.h"

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
  double lo;           /**< family: the d-interval of the piece holding it
                            (the located ends of its itinerary); an
                            isolated orbit: lo = hi = d[0] */
  double hi;           /**< the other end (see lo) */
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
  double from;     /**< the d interval: from (< to) */
  double to;       /**< the d interval: to */
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
/* Periodic orbits of maps of n dimensions, without a start guess        */

/** Largest period of sc_fixed_points_n_find(). */
#define SC_FIXED_POINTS_N_MAX_PERIOD 1000

/** Most starts of one search (grid and attractor points together). */
#define SC_FIXED_POINTS_N_MAX_STARTS 10000000

/** What sc_fixed_points_n_find() searches. */
typedef struct {
  int period_lo;       /**< smallest minimal period, >= 1 */
  int period_hi;       /**< largest, period_lo <= period_hi <=
                            SC_FIXED_POINTS_N_MAX_PERIOD */
  const double *from;  /**< the box: n lower ends (NULL with start) */
  const double *to;    /**< n upper ends, to[i] > from[i] */
  size_t steps;        /**< grid points per axis, >= 2, ends included
                            (steps^n starts) */
  size_t attractor;    /**< starts on the attractor: iterates of a few
                            grid points after the transient (0: none) */
  long transient;      /**< iterates before attractor points are taken */
  const double *start; /**< NULL, or n values: the one start (no box, no
                            grid, no attractor) */
  sc_shoot_method method; /**< single or multiple shooting */
  const sc_linsolve_type *linsolve; /**< multiple shooting's backend, NULL:
                                         as sc_shootn_alloc() */
} sc_fixed_points_n_spec;

/** One orbit found by sc_fixed_points_n_find(). */
typedef struct {
  int period;           /**< minimal period m */
  const double *x;      /**< m points of n components, x[k n + c], from the
                             lexicographically smallest point, in the order
                             of the orbit */
  const double *mult_re; /**< n multipliers by decreasing modulus: real */
  const double *mult_im; /**< imaginary parts */
  double multiplier;    /**< the one of largest modulus (its modulus for a
                             complex pair), sc_shootn_result */
  int stable;           /**< every multiplier inside the unit circle */
  double residual;      /**< the shooting certificate */
  const double *start;  /**< the start (n values) Newton converged from */
  int in_box;           /**< 1 if a point of the orbit lies in the box
                             (always 1 with a start) */
} sc_orbitn_info;

/** What the starts of one searched period gave (sc_orbitn_set_stats()). */
typedef struct {
  size_t starts;       /**< Newton runs made */
  size_t found;        /**< new orbits (of this period or, over a range,
                            of a lower one in the range) */
  size_t known;        /**< converged to an orbit already found (deflation
                            did not keep Newton away) */
  size_t lower;        /**< converged to an orbit of a smaller minimal
                            period outside the range searched */
  size_t outside;      /**< a new orbit with no point in the box */
  size_t failed[SC_SHOOTN_NREASONS]; /**< failures by reason (index 0,
                                          converged, stays 0) */
} sc_orbitn_stats;

/** The result of sc_fixed_points_n_find() (opaque). */
typedef struct sc_orbitn_set sc_orbitn_set;

/**
 * @brief Periodic orbits of minimal periods period_lo .. period_hi of an
 * n-dimensional map, at its current parameters, without a start guess.
 *
 * Starts: the grid of the box (steps points per axis, ends included) and
 * @p attractor points of the attractor (the iterates, after the
 * transient, of grid points whose orbits stay finite), or the one start
 * of spec->start.  For each period m in turn (increasing), Newton's method
 * (sc_shootn) runs from every start on the fixed points of f^m, with
 * every orbit already found whose period divides m deflated
 * (sc_shootn_deflate(), scale: the box's largest side), so that a start
 * drawn to a known orbit is sent on to another one.  A converged orbit
 * is recorded once, at its minimal period (sc_orbit_minimal_period_n()),
 * if that period is in the range, it is not a rotation of one recorded
 * (sc_orbit_same_n() with sc_orbit_tol() of the map's solver accuracy)
 * and (with a box) one of its points lies in the box.  The search is
 * complete only as far as its starts reach: the statistics say what
 * each start gave.
 * @return SC_OK; SC_EINVAL for a bad spec (the message names the field);
 *         SC_ENOMEM; an error of the model other than an undefined map.
 */
SC_API int sc_fixed_points_n_find(sc_map *m, const sc_fixed_points_n_spec *spec,
                                  sc_orbitn_set **out, sc_msg *msg);

/** Orbits recorded (in the box), by period then by first point. */
SC_API size_t sc_orbitn_set_count(const sc_orbitn_set *s);
/** @brief Orbit @p i; SC_EINVAL for i out of range.  Pointers are owned by
 * the set. */
SC_API int sc_orbitn_set_get(const sc_orbitn_set *s, size_t i,
                             sc_orbitn_info *o);
/** @brief The statistics of the search of period @p period (zeros for a
 * period outside the range). */
SC_API void sc_orbitn_set_stats(const sc_orbitn_set *s, int period,
                                sc_orbitn_stats *out);
/** Grid starts, attractor starts (per period searched). */
SC_API void sc_orbitn_set_starts(const sc_orbitn_set *s, size_t *grid,
                                 size_t *attractor);
/** @brief Release @p s; NULL is accepted. */
SC_API void sc_orbitn_set_free(sc_orbitn_set *s);

/* ------------------------------------------------------------------ */
/* Branches of periodic orbits in one parameter                          */

/** Kinds of special points on an orbit branch (points.csv labels).  The
 * border labels are those of sc_border_label() (models.h). */
typedef enum {
  SC_PT_LP = 0, /**< fold: multiplier +1 */
  SC_PT_PD,     /**< flip: multiplier -1 */
  SC_PT_GR,     /**< grazing-sliding: a re-stick guard tangent */
  SC_PT_CS,     /**< crossing-sliding: a global stick phase of length 0 */
  SC_PT_SW,     /**< switching: an orbit point at a switching surface */
  SC_PT_BR,     /**< both re-stick: two ending events at once */
  SC_PT_TT,     /**< a threshold touched tangentially */
  SC_PT_IC,     /**< the itinerary changes (located by bisection) at a
                     border of unknown kind */
  SC_PT_UZ,     /**< a user point: the parameter at one of the spec's
                     marks (AUTO's UZ) */
  SC_PT_EP,     /**< end point of a branch, with its reason */
} sc_point_label;

/** Label text: "LP", "PD", "GR", "CS", "SW", "BR", "TT", "IC", "UZ",
 * "EP". */
SC_API const char *sc_point_label_text(sc_point_label l);

/** The special-point label of a border kind. */
SC_API sc_point_label sc_point_label_of_border(sc_border_kind k);

/** What sc_orbit_branch_run() continues. */
typedef struct {
  size_t param;      /**< index of the continued parameter */
  double from;       /**< start value of the parameter */
  double to;         /**< the other end of the interval */
  int period;        /**< period m of the starting orbit, >= 1 */
  double d0;         /**< guess of a point of the starting orbit; polished
                          by multiple shooting at p = from.  NaN: no start
                          at from (sc_orbit_branch_add_start() gives them);
                          a start that fails is fatal only when it is the
                          only one (else an EP row says why) */
  int switch_pd;     /**< 1: at each flip also continue the period-2m
                          branch (recursively, up to max_branches) */
  long max_points;   /**< accepted points per branch segment, >= 2 */
  int max_branches;  /**< branches (segments) at most, >= 1 */
  int max_period;    /**< no branch switching beyond this period */
  double h0;         /**< first arclength step (0: from |to - from|) */
  double hmax;       /**< largest step (0: from |to - from|) */
  /** Backend of the bordered systems; NULL for dense. */
  const sc_linsolve_type *linsolve;
  /** Called after each accepted point with the number of points so far;
   * non-zero stops the run with SC_ECALLBACK.  May be NULL. */
  int (*progress)(void *ctx, size_t npoints);
  void *progress_ctx; /**< passed to progress */
  /** User points (AUTO's UZ): parameter values at which every branch
   * that passes records its orbit, a UZ special point located by Newton
   * on f^m(d) = d with the parameter fixed there (residual |f^m(d) - d|
   * reported).  Finite values; the array is the caller's and is read
   * until sc_orbit_branch_run() returns.  NULL with nmarks = 0: none. */
  const double *marks;
  size_t nmarks; /**< entries of marks, at most 1000 */
} sc_orbit_branch_spec;

/** One accepted point of a branch. */
typedef struct {
  int branch;        /**< segment number, from 0 */
  int period;        /**< period m of the orbit */
  double p;          /**< parameter value */
  double d;          /**< first orbit point (the continued unknown) */
  double multiplier; /**< (f^m)'(d) */
  int stable;        /**< |multiplier| < 1 */
  const char *itinerary; /**< of f^m from d, iterates joined by '|' */
} sc_orbit_point_info;

/** How a special point was found. */
typedef enum {
  SC_LOC_NEWTON = 0, /**< solution of its defining system by Newton's
                          method (LP, PD: the continuation layer's
                          location; borders: {f^m(d) = d, m_k = 0}) */
  SC_LOC_BISECTION,  /**< fallback: bisection on a change of itinerary;
                          the parameter is known to `error` only */
  SC_LOC_FAILED,     /**< detected (a sign change) but not located: the
                          row gives the bracket's end and the reason */
  SC_LOC_NONE,       /**< an end point (EP) */
  SC_LOC_DEGENERATE, /**< solved by Newton, but its defining system is
                          degenerate there (its slope in the parameter
                          vanishes: a double root, or the orbit on the
                          border along an interval): known to `error`
                          only, `residual` is the system's noise, no
                          certificate */
} sc_location_method;

/** Text of a location method: "newton", "bisection", "not-located", "",
 * "degenerate". */
SC_API const char *sc_location_method_text(sc_location_method l);

/** One special point. */
typedef struct {
  sc_point_label label; /**< LP, PD, a border kind, EP, ... */
  int branch;        /**< segment number */
  int period;        /**< period of the orbit at the point */
  double p;          /**< parameter value */
  double d;          /**< LP, PD, EP: the continued orbit point; a border
                          point: the orbit point where the border is met
                          (SW: the point at d*) */
  double multiplier; /**< (f^m)' there (NaN where not differentiable) */
  double degeneracy; /**< the defining function at the point: LP, PD: the
                          multiplier -+ 1; borders: the border m_k;
                          EP: NaN */
  double residual;   /**< certificate: max norm of the whole defining
                          system at the returned point (NaN: not solved) */
  double error;      /**< estimated error in p: the last Newton step
                          (newton), the bracket (bisection, not located) */
  sc_location_method method; /**< how it was found */
  int iterations;    /**< Newton or location iterations */
  const char *border; /**< the border's name (borders only, else "") */
  const char *note;  /**< which block and mode, what followed, reasons */
} sc_orbit_special_info;

/** A computed branch diagram: its points, segments and special points
 * (sc_orbit_branch_run()). */
typedef struct sc_orbit_branch sc_orbit_branch;

/**
 * @brief Prepare a run: check @p spec and take the storage that does not
 * grow (points and special points grow as they come).
 * @return SC_OK; SC_EINVAL naming the bad field; SC_ENOMEM.
 */
SC_API int sc_orbit_branch_alloc(sc_map *m, const sc_orbit_branch_spec *spec,
                          sc_orbit_branch **out, sc_msg *msg);

/**
 * @brief Add a starting orbit besides (d0, from): the period-@p period
 * orbit through a guess @p d at parameter @p p, polished by multiple
 * shooting and continued in both directions within [from, to].  Call
 * before sc_orbit_branch_run(); each start continued takes two of the
 * max_branches segments, and one that finds fewer than two left is not
 * continued (a row says so: sc_orbit_branch_start_counts()).
 * @return SC_OK; SC_EINVAL for p outside the interval, a non-finite d or
 *         a period outside [1, max_period]; SC_ENOMEM when out of memory.
 */
SC_API int sc_orbit_branch_add_start(sc_orbit_branch *b, double p, double d,
                              int period, sc_msg *msg);

/**
 * @brief Make the last @p n added starts one group: the ones found by
 * shooting are continued all (both ways each) or none, when the
 * max_branches segments left cannot take them all.  Orbits that must be
 * treated alike (an orbit and its mirror image in a symmetric model, all
 * found by one fixed-point search) go in one group.  Without it each
 * start is a group of its own.
 * @return SC_OK; SC_EINVAL for n outside [1, starts added].
 */
SC_API int sc_orbit_branch_group_starts(sc_orbit_branch *b, int n,
                                        sc_msg *msg);

/**
 * @brief Continue the branch from (d0, from) towards @p to, then from
 * each added start in both directions.
 *
 * Labels: LP and PD are the zeros of the fold and flip test functions of
 * the continuation layer, located until both the arclength step and the
 * test function are within tolerance.  For a model with borders
 * (sc_map_has_borders()), each segment follows the itinerary code of its
 * first point (sc_map_iterate_ex()), so f^m is smooth along it, and every
 * border of the orbit is watched as a test function: where one changes
 * sign between two accepted points, the point is located by Newton's
 * method on {f^m(d) - d = 0, m_k(d, p) = 0} in (d, p) with exact
 * derivatives (a border in the state itself, such as d = d*, by Newton
 * in p with the orbit started on it), labelled by the border's kind
 * (sc_point_label_of_border()) and certified by its residual.  Points
 * beyond it on the segment are not real orbits and are dropped, and
 * special points found there are not reported.  A corrector that can go
 * no further (a forced event that disappears: a grazing met from the side
 * where the guard fires) falls back to a bisection in the parameter on a
 * change of the itinerary code, after which the border that vanishes
 * there is located by Newton from the other side.  The branch then
 * continues on the other side when shooting finds an orbit there
 * (period m, or m -+ 1 after a crossing-sliding), and ends with a note
 * otherwise.  A sign change that could not be located, a rejected fold
 * or flip test, a failed start: each is a special point with its reason.
 * EP marks every end (interval end, max_points, a failure), with the
 * reason in its note.
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
/** Special points met again by another segment (a flip reached from the
 * doubled branch, a closed curve from two starts): reported once, and
 * counted here. */
SC_API size_t sc_orbit_branch_nduplicate(const sc_orbit_branch *b);

/**
 * @brief How the starts added with sc_orbit_branch_add_start() fared in
 * the last run: continued both ways (@p started), not found by shooting
 * (@p not_found) and not continued for want of segments (@p no_room,
 * max_branches).  Each of the last two has a row among the special
 * points (label EP, branch -1, its reason in the note), so the counts
 * equal those rows.
 */
SC_API void sc_orbit_branch_start_counts(const sc_orbit_branch *b,
                                         size_t *started, size_t *not_found,
                                         size_t *no_room);
/** Branch segments computed. */
SC_API int sc_orbit_branch_nbranches(const sc_orbit_branch *b);
/** @brief Release @p b; NULL is accepted. */
SC_API void sc_orbit_branch_free(sc_orbit_branch *b);

#ifdef __cplusplus
}
#endif
#endif
