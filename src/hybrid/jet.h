/* Truncated multivariate Taylor arithmetic ("jets") for exact second
 * derivatives, and third derivatives with two of the three directions
 * equal to direction 0.
 *
 * A jet carries, for a quantity a(x_0, ..., x_{nd-1}):
 *   v        a
 *   g[i]     da/dx_i
 *   h[i][j]  d2a/dx_i dx_j        (symmetric, stored in full)
 *   t[k]     d3a/dx_0 dx_0 dx_k
 * For a map f(d, p) with x_0 = d and x_1.. = the parameters this gives
 * f_d, f_p, f_dd, f_dp, f_pp, f_ddd and f_ddp: all a fold or flip curve
 * and its normal-form coefficients need.  Every operation is the exact
 * Leibniz / Faa di Bruno rule truncated at that order (docs/curves.md),
 * so the derivatives are exact up to rounding.  Like dual.h, `nd` is a
 * run-time count of live directions; entries beyond nd are never read.
 * Private to the library. */
#ifndef SC_HYBRID_JET_H
#define SC_HYBRID_JET_H

#include <math.h>

/* Directions carried: d and the four bk2 parameters. */
#define SC_JET_NDIR 5

typedef struct {
  double v;
  double g[SC_JET_NDIR];
  double h[SC_JET_NDIR][SC_JET_NDIR];
  double t[SC_JET_NDIR];
} sc_jet;

static inline sc_jet sc_jconst(double v) {
  sc_jet r = {0};
  r.v = v;
  return r;
}

/* A variable: derivative 1 in direction `dir` (dir >= nd: a constant). */
static inline sc_jet sc_jvar(double v, int dir, int nd) {
  sc_jet r = sc_jconst(v);
  if (dir < nd) r.g[dir] = 1;
  return r;
}

/* a + s b */
static inline sc_jet sc_jaxpy(sc_jet a, double s, const sc_jet *b, int nd) {
  a.v += s * b->v;
  for (int i = 0; i < nd; i++) {
    a.g[i] += s * b->g[i];
    a.t[i] += s * b->t[i];
    for (int j = 0; j < nd; j++)
      a.h[i][j] += s * b->h[i][j];
  }
  return a;
}

static inline sc_jet sc_jadd(sc_jet a, sc_jet b, int nd) {
  return sc_jaxpy(a, 1, &b, nd);
}

static inline sc_jet sc_jsub(sc_jet a, sc_jet b, int nd) {
  return sc_jaxpy(a, -1, &b, nd);
}

static inline sc_jet sc_jscale(sc_jet a, double s, int nd) {
  a.v *= s;
  for (int i = 0; i < nd; i++) {
    a.g[i] *= s;
    a.t[i] *= s;
    for (int j = 0; j < nd; j++)
      a.h[i][j] *= s;
  }
  return a;
}

static inline sc_jet sc_jaddc(sc_jet a, double c) {
  a.v += c;
  return a;
}

/* Leibniz: (ab)_ij = a_ij b + a_i b_j + a_j b_i + a b_ij and
 * (ab)_00k = a_00k b + 2 a_0k b_0 + a_k b_00 + a_00 b_k + 2 a_0 b_0k
 *            + a b_00k. */
static inline sc_jet sc_jmul(sc_jet a, sc_jet b, int nd) {
  sc_jet r = sc_jconst(a.v * b.v);
  for (int i = 0; i < nd; i++) {
    r.g[i] = a.g[i] * b.v + a.v * b.g[i];
    for (int j = 0; j < nd; j++)
      r.h[i][j] =
          a.h[i][j] * b.v + a.g[i] * b.g[j] + a.g[j] * b.g[i] + a.v * b.h[i][j];
  }
  for (int k = 0; k < nd; k++)
    r.t[k] = a.t[k] * b.v + 2 * a.h[0][k] * b.g[0] + a.g[k] * b.h[0][0] +
             a.h[0][0] * b.g[k] + 2 * a.g[0] * b.h[0][k] + a.v * b.t[k];
  return r;
}

/* phi(a) for a scalar function with phi(a.v) = f0 and derivatives f1, f2,
 * f3 there (Faa di Bruno):
 *   phi_ij  = f2 a_i a_j + f1 a_ij,
 *   phi_00k = f3 a_0^2 a_k + f2 (a_00 a_k + 2 a_0 a_0k) + f1 a_00k. */
static inline sc_jet sc_jcompose(const sc_jet *a, double f0, double f1,
                                 double f2, double f3, int nd) {
  sc_jet r = sc_jconst(f0);
  for (int i = 0; i < nd; i++) {
    r.g[i] = f1 * a->g[i];
    for (int j = 0; j < nd; j++)
      r.h[i][j] = f2 * a->g[i] * a->g[j] + f1 * a->h[i][j];
  }
  for (int k = 0; k < nd; k++)
    r.t[k] = f3 * a->g[0] * a->g[0] * a->g[k] +
             f2 * (a->h[0][0] * a->g[k] + 2 * a->g[0] * a->h[0][k]) +
             f1 * a->t[k];
  return r;
}

static inline sc_jet sc_jinv(sc_jet a, int nd) {
  double y = 1 / a.v;
  return sc_jcompose(&a, y, -y * y, 2 * y * y * y, -6 * y * y * y * y, nd);
}

static inline sc_jet sc_jdiv(sc_jet a, sc_jet b, int nd) {
  return sc_jmul(a, sc_jinv(b, nd), nd);
}

static inline sc_jet sc_jsqrt(sc_jet a, int nd) {
  double s = sqrt(a.v);
  return sc_jcompose(&a, s, 0.5 / s, -0.25 / (s * a.v), 0.375 / (s * a.v * a.v),
                     nd);
}

/* sin and cos of one argument together. */
static inline void sc_jsincos(sc_jet a, int nd, sc_jet *s, sc_jet *c) {
  double sv = sin(a.v), cv = cos(a.v);
  *s = sc_jcompose(&a, sv, cv, -sv, -cv, nd);
  *c = sc_jcompose(&a, cv, -sv, -cv, sv, nd);
}

#endif
