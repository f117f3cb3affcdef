/**
 * @file branchn.h
 * @brief Branches of periodic orbits of an n-dimensional map in one
 *        parameter: fixed points of g = f^m continued by pseudo-arclength,
 *        with their folds (LP), flips (PD), Neimark-Sacker points (NS) and
 *        branch points (BP) located by Newton on their defining systems
 *        (mapn_system.h), each with its normal-form coefficient, and
 *        switching onto the period-doubled branch at a flip and onto the
 *        crossing branch at a branch point (docs/maps.md, "Branches").
 *
 * A branch borrows the caller's map and changes its parameters while it
 * runs; they are restored when sc_branchn_run() returns.  One object per
 * thread.  For a model with borders of its n-dimensional map
 * (sc_map_has_borders_n()), each segment follows the itinerary codes of
 * its first point; a border of its orbit that changes sign between two
 * points is located by Newton on {g(x, p) - x = 0, m(x, p) = 0} and the
 * branch is handed over to the orbit on the other side.  The model's n
 * may be 1 too, though the one-dimensional models keep their own branch
 * code (orbits.h) with its discontinuity-induced bifurcations.
 */
#ifndef SLIPCONT_BRANCHN_H
#define SLIPCONT_BRANCHN_H

#include <stddef.h>

#include "slipcont/common.h"
#include "slipcont/map.h"
#include "slipcont/orbits.h"

#ifdef __cplusplus
extern "C" {
#endif

/** What sc_branchn_run() continues. */
typedef struct {
  size_t param;     /**< index of the continued parameter */
  double from;      /**< start value of the parameter */
  double to;        /**< the other end of the interval (!= from) */
  int period;       /**< period m of the starting orbit, >= 1 */
  const double *x0; /**< n values: a guess of a point of the starting
                         orbit at p = at, polished by Newton (copied) */
  int has_at;       /**< 0: x0 lies at from (the start continued towards
                         to); 1: at at */
  double at;        /**< has_at: where x0 lies, in [from, to]; inside, the
                         start is continued both ways */
  int switch_pd;    /**< 1: at each flip continue the period-2m branch */
  int switch_bp;    /**< 1: at each branch point continue the crossing
                         branch both ways */
  long max_points;  /**< accepted points per segment, >= 2 */
  int max_branches; /**< segments at most, >= 1 */
  int max_period;   /**< no switching beyond this period */
  double h0;        /**< first arclength step (0: hmax / 10) */
  double hmax;      /**< largest step (0: |to - from| / 40) */
  /** Called after each accepted point with the points so far; non-zero
   * stops the run with SC_ECALLBACK.  May be NULL. */
  int (*progress)(void *ctx, size_t npoints);
  void *progress_ctx; /**< passed to progress */
} sc_branchn_spec;

/** Labels of special points. */
typedef enum {
  SC_PTN_LP = 0, /**< fold: a multiplier +1 */
  SC_PTN_PD,     /**< flip: a multiplier -1 */
  SC_PTN_NS,     /**< Neimark-Sacker: multipliers e^{+-i theta} */
  SC_PTN_NN,     /**< neutral saddle: real multipliers mu, 1 / mu (a zero
                      of the NS test, not a bifurcation) */
  SC_PTN_BP,     /**< branch point: two branches cross */
  SC_PTN_EP,     /**< end of a segment, with its reason */
  SC_PTN_GR,     /**< a border of kind SC_BORDER_GRAZING: SC_PTN_GR + the
                      kind labels a border point (docs/maps.md, "Borders
                      in n dimensions") */
  SC_PTN_CS,     /**< border: crossing */
  SC_PTN_SW,     /**< border: switching (bcnf: an orbit point on x = 0) */
  SC_PTN_BR,     /**< border: both */
  SC_PTN_TT,     /**< border: touch */
} sc_branchn_label;

/** Number of labels. */
#define SC_PTN_NLABELS (SC_PTN_TT + 1)

/** "LP", "PD", "NS", "NN", "BP", "EP", and the border kinds' labels
 * (sc_border_label()). */
SC_API const char *sc_branchn_label_text(sc_branchn_label l);

/** One accepted point. */
typedef struct {
  int branch;        /**< segment, from 0 */
  int period;        /**< m */
  double p;          /**< parameter */
  const double *x;   /**< n values: the orbit point continued */
  const double *re;  /**< n multipliers by decreasing modulus: real */
  const double *im;  /**< and imaginary parts */
  double multiplier; /**< the one of largest modulus: its value if real,
                          its modulus if complex */
  int stable;        /**< every |mu| < 1 */
} sc_branchn_point;

/** One special point. */
typedef struct {
  sc_branchn_label label; /**< LP, PD, NS, NN, BP, EP */
  int branch;        /**< segment */
  int period;        /**< m */
  double p;          /**< parameter */
  const double *x;   /**< n values */
  const double *re;  /**< n multipliers (as sc_branchn_point) */
  const double *im;  /**< their imaginary parts */
  const char *border; /**< a border point: the border's name (models.h),
                            else "" */
  double coef;       /**< LP: a; PD: b; NS: the first Lyapunov
                          coefficient d (docs/maps.md, "Normal forms");
                          NaN for NN, BP, EP or where it failed */
  double theta;      /**< NS, NN: kappa's angle arccos kappa (NaN for a
                          neutral saddle, whose kappa is in kappa); else
                          NaN */
  double kappa;      /**< NS, NN: (mu + 1 / mu) / 2; else NaN */
  double residual;   /**< max |F| of the defining system at the point:
                          the certificate (NaN: not solved) */
  double error;      /**< the last Newton step (max norm) */
  int iterations;    /**< Newton iterations */
  sc_location_method method; /**< newton, not-located, or none (EP) */
  const char *note;  /**< what followed, or why not */
} sc_branchn_special;

/** A branch diagram being computed (opaque). */
typedef struct sc_branchn sc_branchn;

/**
 * @brief Check @p spec against @p m and prepare a run.
 * @return SC_OK; SC_EINVAL naming the field (a parameter index, an equal
 *         from and to, at outside [from, to], a period outside
 *         [1, max_period], a non-finite x0,
 *         a model of more than 16 components, a one-dimensional
 *         model with borders (bk2: orbits.h));
 *         SC_ENOMEM.
 */
SC_API int sc_branchn_alloc(sc_map *m, const sc_branchn_spec *spec,
                            sc_branchn **out, sc_msg *msg);

/**
 * @brief Continue from (x0, at) towards to (and from at back to from when
 * at is inside the interval), and every switched branch.
 *
 * The start is corrected by Newton with the parameter fixed.  Along each
 * segment the four tests of the fixed-point system are watched
 * (mapn_system.h); at a zero of one, located in arclength, Newton on the
 * special point's own system gives the point, certified by its residual:
 * the fold's where the tangent's parameter component vanishes (a zero of
 * det(g_x - I) where it does not is the branch point's, which its own test
 * reports), the flip's, the NS system's (|kappa| < 1: NS with its angle,
 * else a neutral saddle NN), the branch point's.  Coefficients from
 * sc_nf_fold(), sc_nf_flip(), sc_nf_ns() on g's exact jet.  Multipliers
 * from the m Jacobians along the orbit (sc_product_eigs()).  On an event
 * map (an evaluation with slip phases) a segment ends, with an EP row
 * that says so, where the itinerary of f^m changes: the map is not
 * smooth there, and n-dimensional borders are not located.
 * @return SC_OK (every segment ended: see the EP notes); SC_ENOCONV or
 *         SC_EINVAL when the start is on no orbit; SC_ECALLBACK if
 *         progress stopped the run; SC_ENOMEM.
 */
SC_API int sc_branchn_run(sc_branchn *b, sc_msg *msg);

/** State dimension n. */
SC_API size_t sc_branchn_dim(const sc_branchn *b);
/** Accepted points, in the order computed. */
SC_API size_t sc_branchn_npoints(const sc_branchn *b);
/** @brief Point @p i; SC_EINVAL out of range. */
SC_API int sc_branchn_point_get(const sc_branchn *b, size_t i,
                                sc_branchn_point *pt);
/** Special points, in the order found. */
SC_API size_t sc_branchn_nspecial(const sc_branchn *b);
/** @brief Special point @p i; SC_EINVAL out of range. */
SC_API int sc_branchn_special_get(const sc_branchn *b, size_t i,
                                  sc_branchn_special *sp);
/** Segments computed. */
SC_API int sc_branchn_nbranches(const sc_branchn *b);
/** Special points met again by another segment (reported once). */
SC_API size_t sc_branchn_nduplicate(const sc_branchn *b);
/** @brief Release @p b; NULL is accepted. */
SC_API void sc_branchn_free(sc_branchn *b);

#ifdef __cplusplus
}
#endif
#endif
