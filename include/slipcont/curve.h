/**
 * @file curve.h
 * @brief Two-parameter curves of a model's event map (the analysis
 *        layer): sc_curve_trace() corrects a start onto the fold, flip or
 *        border system of f^m, continues the curve both ways by
 *        pseudo-arclength in (d, x, y), locates its codimension-two
 *        points (CP, GPD, TP, LP and PD on a border, the borders a curve
 *        meets) and reports points through callbacks
 *        (src/analysis/curve.c, curve_border.c; docs/curves.md).
 *
 * The defining systems it builds, and any other, are those of
 * curve_system.h (the generic continuation layer), included here.
 */
#ifndef SLIPCONT_CURVE_H
#define SLIPCONT_CURVE_H

#include <stddef.h>

#include "slipcont/common.h"
#include "slipcont/curve_system.h"
#include "slipcont/map.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Settings of sc_curve_trace(). */
typedef struct {
  sc_curve_type type; /**< fold, flip or border */
  int period;      /**< m >= 1 */
  int multiple;    /**< 1: multiple shooting in (d_0..d_{m-1}, x, y);
                        0: single shooting on f^m */
  int ix;          /**< parameter index of x */
  int iy;          /**< parameter index of y (not ix) */
  double xlo;      /**< the box, where the curve stops: x from */
  double xhi;      /**< x to */
  double ylo;      /**< y from */
  double yhi;      /**< y to */
  double h0;       /**< first arclength step (in (d, x, y)) */
  double hmax;     /**< largest arclength step */
  long max_points; /**< per direction */
  /** SC_CURVE_BORDER: the kind of border followed; the start's orbit
   * border of this kind nearest to zero is taken */
  sc_border_kind border;
  /** SC_CURVE_BORDER: "" (the nearest border of the kind), or the name
   * of the border to follow (sc_border.name; ';' and ',' alike, as a CSV
   * field writes it): the border of a branch row, met by the start's
   * first iterate (d0 is the orbit point where the border is met).  The
   * start's itinerary is then taken from the side of d0 where the orbit
   * has that border: on a grazing the natural map may take the other
   * side. */
  char border_name[SC_BORDER_NAME];
  /** User points (UZ): values of x at which the curve records its point,
   * located by Newton on the curve's system with x fixed there (d and y
   * free; its residual reported).  The array is the caller's, read until
   * sc_curve_trace() returns; NULL with nmarks = 0: none.  Every type
   * of curve. */
  const double *marks;
  size_t nmarks; /**< entries of marks */
} sc_curve_settings;

/** @brief Defaults: fold, period 1, steps 1e-3 and 2e-2, 2000 points. */
SC_API void sc_curve_settings_default(sc_curve_settings *s);

/** One point of a traced curve. */
typedef struct {
  double x;           /**< first parameter */
  double y;           /**< second parameter */
  double d;           /**< the orbit point carried */
  double multiplier;  /**< (f^m)' there: +1 or -1 up to the tolerance */
  double coefficient; /**< the normal-form coefficient (psi_0); on a
                           border curve the border's value m_k (zero up
                           to the residual) */
  int branch;         /**< 0: the first direction, 1: the other */
  const char *itinerary; /**< of f^m from d, iterates joined by '|' */
} sc_curve_point;

/** A codimension-two or end point of a traced curve. */
typedef struct {
  char label[8]; /**< "CP", "GPD", "TP", "EP" (end); on a border
                      curve "LP", "PD" (the orbit on the border has
                      (f^m)' = +1, -1); where the curve meets a border
                      of the orbit, that border's kind (sc_border_label:
                      "GR", "CS", "SW", "BR", "TT"); with a '?' ("CP?",
                      "GR?") for a sign change of the test that was not
                      located or is not a zero (note says why) */
  double x;           /**< first parameter */
  double y;           /**< second parameter */
  double d;           /**< the orbit point */
  double coefficient; /**< the normal-form coefficient there */
  double residual; /**< sc_curve_cert.residual; NaN for EP; for a
                        border point, the largest of |F| and |m_k| */
  char note[256];  /**< "beta min", "supercritical to subcritical",
                        why the curve ended, ... */
} sc_curve_special;

/** Callbacks of sc_curve_trace(); either may be NULL; non-zero stops. */
typedef struct {
  /** each accepted point */
  int (*point)(void *ctx, const sc_curve_point *p);
  /** each special or end point */
  int (*special)(void *ctx, const sc_curve_special *s);
  void *ctx; /**< passed to both */
} sc_curve_output;

/** What sc_curve_trace() did. */
typedef struct {
  long npoints;        /**< points reported */
  long nspecial;       /**< CP, GPD, TP located */
  int closed;          /**< 1 if the curve closed on itself */
  double max_residual; /**< largest |F| over the reported points */
  double ftol;         /**< the residual tolerance used: the accuracy's
                            newton_ftol, or 4 times the rounding floor of
                            the system at the start where that is larger
                            (at most 1e-9) */
  int border_iterate;  /**< border curve: the iterate of f^m whose border
                            is followed (from 0); -1 otherwise */
  char border[64];     /**< border curve: that border's name; "" */
} sc_curve_stats;

/**
 * @brief Trace the fold or flip curve of the period-m orbit through
 * (d0, x, y) of map @p m (its parameters ix, iy hold the start's x, y):
 * correct the start at fixed y, continue both ways, locate CP / GPD /
 * TP, stop at the box, or where the curve closes.  The orbit keeps the
 * itinerary code of its start (single shooting: evaluated along it past
 * a border, sc_map_iterate_ex()); the borders of the orbit are test
 * functions, and where one changes sign the point {f^m(d) = d, (f^m)' =
 * +-1, m_k = 0} is located by Newton in (d, x, y) and reported with the
 * border's kind as label; the curve goes on across it with the orbit's
 * new itinerary where the fold or flip persists there (single shooting),
 * and ends there otherwise (the note says which).  What cannot be
 * located is a "KIND?" row with the reason.  A curve also ends where its
 * points stop meeting their system (the residual's rounding floor above
 * 10 tolerances, next to d*).
 *
 * With set->type SC_CURVE_BORDER the curve is that of the orbit on its
 * border of kind set->border nearest to the start: {f^m(d) = d, m_k = 0}
 * along the start's itinerary code (the border's own code for its
 * iterate), with LP and PD ((f^m)' = +-1) and the crossings of the
 * orbit's other borders located (docs/curves.md).
 * The map's parameters are changed during the trace and restored at the
 * end.  Needs SC_EVAL_DERIV2 of the model for fold and flip curves (bk2:
 * exact flows), and borders (sc_map_has_borders()) for border curves.
 * @return SC_OK; SC_EINVAL for bad settings, a border curve of a model
 *         without borders or of an orbit without a border of that kind;
 *         SC_ENOCONV if the start could not be corrected; SC_ECALLBACK if an output callback
 *         stopped; the map's errors at the start.
 */
SC_API int sc_curve_trace(sc_map *m, const sc_curve_settings *set, double d0,
                   const sc_curve_output *out, sc_curve_stats *stats,
                   sc_msg *msg);


/* ------------------------------------------------------------------ */
/* Curves of n-dimensional maps                                        */

/** One point of a traced curve of an n-dimensional map. */
typedef struct {
  double x;            /**< first parameter */
  double y;            /**< second parameter */
  size_t n;            /**< state dimension */
  const double *state; /**< the fixed point of f^m (n values) */
  /** NS: kappa = cos theta of the pair mu, 1/mu with mu + 1/mu =
   * 2 kappa: a Neimark-Sacker point for |kappa| < 1, a neutral saddle
   * (a real pair mu, 1/mu) for |kappa| > 1; fold +1, flip -1 */
  double kappa;
  double coefficient; /**< fold a, flip b, NS d (NaN on a neutral
                           saddle); docs/maps.md, "Normal forms" */
  int branch;         /**< 0: the first direction, 1: the other */
  const double *mre;  /**< the n multipliers of f^m there, real parts, by
                           decreasing modulus (sc_nf_multipliers()) */
  const double *mim;  /**< their imaginary parts */
} sc_curven_point;

/** A codimension-two or end point of a curve of an n-dimensional map. */
typedef struct {
  char label[8];      /**< "CP", "GPD", "CH", "R1" .. "R4", "LPPD",
                           "LPNS", "PDNS", "NSNS", "EP" (end); with a '?'
                           for a sign change that was not located or is
                           not that point (the note says why: a neutral
                           saddle, not a Neimark-Sacker pair) */
  double x;           /**< first parameter */
  double y;           /**< second parameter */
  size_t n;           /**< state dimension */
  double state[SC_DIM_TENSOR]; /**< the fixed point (n values) */
  double kappa;       /**< as sc_curven_point */
  double coefficient; /**< the curve's normal-form coefficient there */
  double residual;    /**< max |F| of the curve's system (the
                           certificate); NaN for EP */
  double test;        /**< the located test function's value there */
  char note[256];     /**< what the point is, why the curve ended */
} sc_curven_special;

/** Callbacks of sc_curven_trace(); either may be NULL; non-zero stops. */
typedef struct {
  int (*point)(void *ctx, const sc_curven_point *p);     /**< each point */
  int (*special)(void *ctx, const sc_curven_special *s); /**< each special */
  void *ctx; /**< passed to both */
} sc_curven_output;

/**
 * @brief Trace the fold, flip or Neimark-Sacker curve of the period-m
 * fixed point of an n-dimensional map (2 <= n <= SC_DIM_TENSOR) through
 * the guess (@p x0, x, y) in two parameters, on the minimally augmented
 * systems of mapn_system.h (unknowns: the state, kappa for NS, x, y):
 * correct the start at fixed y, continue both ways by pseudo-arclength
 * (the bordering vectors updated at each point), locate every
 * codimension-two point by Newton on the extended system {F = 0,
 * psi_k = 0} with the tests of sc_nf_curve_tests() (normal_form.h), and
 * stop at the box, max_points, or where the curve closes.
 * Settings used: type (SC_CURVE_FOLD, SC_CURVE_FLIP, SC_CURVE_NS),
 * period, ix, iy, the box, h0, hmax, max_points; the others are ignored.
 * The map's parameters are changed during the trace and restored.
 * @param x0 n values: a guess of the fixed point.
 * @param kappa0 NS: a guess of kappa = cos theta; NaN to take it from
 *        the multipliers at the guess (the complex pair nearest the unit
 *        circle).  Unused for fold and flip.
 * @param stats out: npoints, nspecial, closed, max_residual, ftol.
 * @return SC_OK; SC_EINVAL for bad settings, a map with n = 1 (use
 *         sc_curve_trace()) or n > SC_DIM_TENSOR, or NS without a
 *         complex pair at the guess; SC_ENOCONV if the start could not be
 *         corrected; SC_ECALLBACK if an output callback stopped;
 *         SC_ENOMEM.
 */
SC_API int sc_curven_trace(sc_map *m, const sc_curve_settings *set,
                           const double *x0, double kappa0,
                           const sc_curven_output *out, sc_curve_stats *stats,
                           sc_msg *msg);

#ifdef __cplusplus
}
#endif
#endif
