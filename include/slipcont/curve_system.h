/**
 * @file curve_system.h
 * @brief Two-parameter curves as defining systems (the continuation
 *        layer): a curve of codimension-one points F(u) = 0, u in
 *        R^(n+1), with test functions whose zeros are its
 *        codimension-two points, located by Newton on the extended
 *        system; the fold and flip systems of a one-dimensional map
 *        iterate given by callbacks, by single or multiple shooting
 *        (continuation/curve.c, continuation/curve_ms.c; docs/curves.md).
 *
 * Nothing here knows a model or an event map: any defining system can be
 * plugged in.  The curves of a model's map are traced by sc_curve_trace()
 * (curve.h), which builds these systems on f^m.
 */
#ifndef SLIPCONT_CURVE_SYSTEM_H
#define SLIPCONT_CURVE_SYSTEM_H

#include <stddef.h>

#include "slipcont/common.h"
#include "slipcont/continuation.h"

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
                            borders (sc_curve_trace() of curve.h only:
                            the borders are a model's) */
  SC_CURVE_NS = 3, /**< g = x, a pair of multipliers e^(+-i theta): the
                        Neimark-Sacker curve of an n-dimensional map
                        (n >= 2; sc_curven_trace() of curve.h only) */
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

#ifdef __cplusplus
}
#endif
#endif
