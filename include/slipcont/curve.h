/**
 * @file curve.h
 * @brief Two-parameter curves of codimension-one points (folds and flips
 *        of a map iterate, orbits on a border), their codimension-two
 *        points (CP, GPD, TP, LP and PD on a border, the borders a curve
 *        meets), and the tracing of such curves for a model
 *        (docs/curves.md).
 *
 * Two levels:
 *  - generic (continuation/curve.c, continuation/map1d_curve.c): a curve
 *    is a defining system F(u) = 0, u in R^(n+1), given by callbacks (an
 *    sc_cont_problem), with test functions psi_k(u) whose zeros are its
 *    codimension-two points; sc_curve_locate() solves the extended system
 *    {F = 0, psi_k = 0} by Newton and returns a residual certificate.  Any
 *    defining system can be plugged in (src/analysis/curve_border.c
 *    plugs in the border systems).
 *  - for a model (src/analysis/curve.c, curve_border.c): sc_curve_trace()
 *    corrects a start onto the fold, flip or border system of f^m,
 *    continues the curve both ways by pseudo-arclength in (d, x, y),
 *    locates every codimension-two point, and reports points through
 *    callbacks.
 */
#ifndef SLIPCONT_CURVE_H
#define SLIPCONT_CURVE_H

#include <stddef.h>

#include "slipcont/common.h"
#include "slipcont/continuation.h"
#include "slipcont/map.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * A curve's defining system and its codimension-two tests.  The tests
 * are functions of the point alone (not of the tangent), so that their
 * zeros solve the square extended system {F = 0, psi_k = 0}.
 */
typedef struct {
  sc_cont_problem pb; /**< F, its dense Jacobian, n; pb.ntest is
                           ignored */
  size_t ntest;       /**< number of test functions */
  /** All test values psi_k(u), k < ntest; returns as pb's callbacks. */
  int (*test)(const double *u, double *psi, void *user);
  const char *const *labels; /**< ntest short labels ("CP", "GPD", "TP") */
  void *user;                /**< passed to test */
} sc_curve_system;

/** What sc_curve_locate() found. */
typedef struct {
  double residual; /**< max |F_i| at the point: the certificate */
  double psi;      /**< psi_k there (its zero is certified by the step) */
  double step;     /**< the last Newton step, max norm */
  int iterations;  /**< Newton iterations */
} sc_curve_cert;

/**
 * @brief Solve {F(u) = 0, psi_k(u) = 0} by Newton from @p u (n + 1
 * values, overwritten with the solution).  F's rows of the Jacobian are
 * exact (pb.jac); psi_k's row is a central difference of psi_k with
 * relative step acc->fd_step (psi_k is computed from exact derivatives,
 * so the row only sets the rate of convergence, never the point).
 * Converged when the step is within newton_atol + newton_rtol |u| and
 * max |F_i| within newton_ftol (psi_k is not scaled: its zero is
 * certified by the step; its value is returned).
 * @return SC_OK; SC_ENOCONV after newton_maxiter iterations (the
 *         certificate says how far it got); SC_ESING for a singular
 *         extended Jacobian; SC_EINVAL for k >= ntest; SC_ENOMEM;
 *         SC_ECALLBACK if a callback failed.
 */
SC_API int sc_curve_locate(const sc_curve_system *cs, size_t k, double *u,
                    const sc_accuracy *acc, sc_curve_cert *cert, sc_msg *msg);

/** Derivatives of g = f^m at (x, p) up to those a fold or flip curve and
 * their normal forms need. */
typedef struct {
  double g;                      /**< g(x, p) */
  double gx;                     /**< dg/dx */
  double gxx;                    /**< d2g/dx2 */
  double gxxx;                   /**< d3g/dx3 */
  double gp[SC_MAP1D_MAXPARAM];  /**< dg/dp_i */
  double gxp[SC_MAP1D_MAXPARAM]; /**< d2g/dx dp_i */
  double gxxp[SC_MAP1D_MAXPARAM]; /**< d3g/dx2 dp_i */
} sc_curve_jet;

/** g and its derivatives at (x, p) (all np parameters); returns 0, > 0
 * (recoverable), < 0 (fatal), as the continuation callbacks. */
typedef int (*sc_curve_jet_fn)(double x, const double *p, sc_curve_jet *jet,
                               void *user);

/** Which curve of a map iterate. */
typedef enum {
  SC_CURVE_FOLD = 0, /**< g = x, g_x = +1 */
  SC_CURVE_FLIP = 1, /**< g = x, g_x = -1 */
  SC_CURVE_BORDER = 2, /**< g = x, m_k = 0: the orbit on one of its
                            borders (sc_curve_trace() only) */
} sc_curve_type;

/**
 * A fold or flip curve of a 1-D map iterate in u = (x, p_a, p_b).
 * Tests: psi_0 the normal-form coefficient (fold: a = g_xx / 2, zero at a
 * cusp "CP"; flip: c = (g_xx / 2)^2 + g_xxx / 6, zero at a generalized
 * flip "GPD", c > 0 supercritical); psi_1, psi_2 vanish where the curve
 * turns back in p_a, p_b ("TP": the determinant of F's Jacobian without
 * that parameter's column, proportional to that tangent component).
 */
typedef struct {
  sc_curve_jet_fn fn;          /**< g and its derivatives */
  void *user;                  /**< passed to fn */
  sc_curve_type type;          /**< fold or flip */
  size_t np;                   /**< parameters of g */
  double p[SC_MAP1D_MAXPARAM]; /**< their values (free ones replaced) */
  int ifree[2];                /**< indices of p_a, p_b (p_b = u[2]) */
} sc_curve_map1d;

/**
 * @brief Fill @p cs with the defining system and tests of @p sys (which
 * must outlive @p cs and not change while it is used).
 * @return SC_OK, or SC_EINVAL (NULL fn, np or free indices out of range,
 *         equal free indices, unknown type).
 */
SC_API int sc_curve_map1d_system(const sc_curve_map1d *sys, sc_curve_system *cs,
                          sc_msg *msg);

/** Workspace of a multiple-shooting curve system (opaque). */
typedef struct sc_curve_ms_work sc_curve_ms_work;

/** @brief Workspace for a period-@p period multiple-shooting system.
 * @return SC_OK, SC_EINVAL (period 0) or SC_ENOMEM. */
SC_API int sc_curve_ms_work_alloc(size_t period, sc_curve_ms_work **out, sc_msg *msg);
/** @brief Release @p w; NULL is accepted. */
SC_API void sc_curve_ms_work_free(sc_curve_ms_work *w);

/**
 * A fold or flip curve of a period-m orbit by multiple shooting, in
 * u = (x_0, ..., x_{m-1}, p_a, p_b): F_k = f(x_k) - x_{k+1 mod m} (k < m)
 * and F_m = prod_k f'(x_k) -+ 1 (continuation/curve_ms.c).  Tests as
 * sc_curve_map1d (psi_0 from g = f^m at x_0 through @c gfn).  The
 * callbacks write into @c work: one system per thread.
 */
typedef struct {
  sc_curve_jet_fn fn;  /**< one iterate f: g, gx, gp, gxx, gxp are used */
  sc_curve_jet_fn gfn; /**< g = f^m at x_0, for the normal-form test */
  void *user;          /**< passed to fn */
  void *guser;         /**< passed to gfn */
  sc_curve_type type; /**< fold or flip */
  size_t period; /**< m >= 1 */
  size_t np;     /**< parameters of f */
  double p[SC_MAP1D_MAXPARAM]; /**< their values (free ones replaced) */
  int ifree[2];  /**< indices of p_a, p_b */
  sc_curve_ms_work *work; /**< from sc_curve_ms_work_alloc(period) */
} sc_curve_map1d_ms;

/**
 * @brief Fill @p cs with the multiple-shooting system of @p sys (n =
 * m + 1 equations; dense Jacobian).
 * @return SC_OK, or SC_EINVAL (NULL callbacks or workspace, a workspace
 *         of another period, bad indices or type).
 */
SC_API int sc_curve_map1d_ms_system(const sc_curve_map1d_ms *sys, sc_curve_system *cs,
                             sc_msg *msg);

/**
 * @brief The same system's continuation problem with its sparse CSC
 * pattern (m + 2 columns; about 5 m nonzeros), for the KLU backend: the
 * Jacobian callback writes the nonzeros in pattern order.
 * @return as sc_curve_map1d_ms_system().
 */
SC_API int sc_curve_map1d_ms_sparse(const sc_curve_map1d_ms *sys, sc_cont_problem *pb,
                             sc_msg *msg);

/** The normal-form coefficient of @p jet for @p type (psi_0 above). */
SC_API double sc_curve_coefficient(sc_curve_type type, const sc_curve_jet *jet);

/* ------------------------------------------------------------------ */

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
  char note[128];  /**< "beta min", "supercritical to subcritical",
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

#ifdef __cplusplus
}
#endif
#endif
