/* Private to the bk2 model: its exact flows and certified event location
 * in quadruple precision (__float128, GCC's libquadmath), selected by
 * sc_accuracy.precision = SC_PRECISION_QUAD.  Slow (tens of times the
 * double path), it is the reference every other path is measured against
 * (docs/accuracy.md).  The same physics as bk2.c (docs/derivations.md), written
 * independently in one type. */
#ifndef SC_MODELS_BK2_QUAD_H
#define SC_MODELS_BK2_QUAD_H

#include "slipcont/models.h"

/* GCC's binary128; __extension__ keeps -Wpedantic quiet about the type. */
__extension__ typedef __float128 sc_quad;

/* Directions of the quad derivatives: d, alpha, beta, phi, v. */
#define SC_BK2Q_NDIR 5

/* The parameters, in quad (any value the double table allows). */
typedef struct {
  sc_quad alpha, beta, phi, v;
  int frozen;     /* driver = frozen: V_s = 0 during slips */
  int max_events; /* slip phases before f is undefined */
} sc_bk2q_params;

/* One iterate in quad. */
typedef struct {
  sc_quad f;                /* f(d) */
  sc_quad y1, y2;           /* positions at the next GSP */
  sc_quad df[SC_BK2Q_NDIR]; /* df/dd, df/dalpha, /dbeta, /dphi, /dv
                               (nd = 5); NaN where not differentiable */
  int nphases;              /* slip phases */
  int neutral;              /* single-block slip from a GSP: f' = 1 */
  int tangent;              /* a guard only touched zero */
  double graze_margin;      /* as sc_map_value (models.h) */
  int graze_block, graze_mode;
  double gsp_gap; /* as sc_map_value */
  int gap_block;
  double dstar_dist;           /* |d - d*| */
  char itinerary[SC_ITIN_LEN]; /* as sc_map_value */
} sc_bk2q_value;

/* f(d) in quad; nd = 0 (value only) or SC_BK2Q_NDIR (with derivatives).
 * Returns SC_OK, SC_EUNDEF (no return to a GSP, with the reason in msg),
 * SC_EINVAL (non-finite d, bad parameters). */
int sc_bk2q_eval(const sc_bk2q_params *p, sc_quad d, int nd, sc_bk2q_value *out,
                 sc_msg *msg);

/* The model's eval() for precision = quad: d and the parameters are
 * taken exactly as doubles, f and its derivatives rounded to double. */
int sc_bk2_quad_eval(double alpha, double beta, double phi, double v,
                     int frozen, int max_events, double d, unsigned flags,
                     sc_map_value *out, sc_msg *msg);

#endif
