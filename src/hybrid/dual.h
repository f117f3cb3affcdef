/* Forward-mode derivatives: a value with its derivatives in up to
 * SC_NDIR directions.  The number of live directions `nd` is a run-time
 * count, so one code path serves plain evaluation (nd = 0: the loops are
 * empty) and evaluation with derivatives (bk2: nd = 5, for d, alpha,
 * beta, phi, v).  Private to the library. */
#ifndef SC_HYBRID_DUAL_H
#define SC_HYBRID_DUAL_H

#include <math.h>

/* Directions carried: the map's argument and the parameters of the one
 * model that uses duals (bk2: d, alpha, beta, phi, v).  Kept small because
 * duals are passed by value in the flows' inner loops. */
#define SC_NDIR 6

typedef struct {
  double v;
  double d[SC_NDIR];
} sc_dual;

static inline sc_dual sc_dconst(double v, int nd) {
  (void)nd;
  sc_dual r = {v, {0}};
  return r;
}

/* A variable: derivative 1 in direction `dir` (dir >= nd: a constant). */
static inline sc_dual sc_dvar(double v, int dir, int nd) {
  sc_dual r = sc_dconst(v, nd);
  if (dir < nd) r.d[dir] = 1;
  return r;
}

static inline sc_dual sc_dadd(sc_dual a, sc_dual b, int nd) {
  a.v += b.v;
  for (int k = 0; k < nd; k++) a.d[k] += b.d[k];
  return a;
}

static inline sc_dual sc_dsub(sc_dual a, sc_dual b, int nd) {
  a.v -= b.v;
  for (int k = 0; k < nd; k++) a.d[k] -= b.d[k];
  return a;
}

static inline sc_dual sc_dscale(sc_dual a, double s, int nd) {
  a.v *= s;
  for (int k = 0; k < nd; k++) a.d[k] *= s;
  return a;
}

/* a + s b */
static inline sc_dual sc_daxpy(sc_dual a, double s, sc_dual b, int nd) {
  a.v += s * b.v;
  for (int k = 0; k < nd; k++) a.d[k] += s * b.d[k];
  return a;
}

static inline sc_dual sc_daddc(sc_dual a, double c) {
  a.v += c;
  return a;
}

/* Results start as a copy of an operand so that the unused directions
 * (k >= nd) are never uninitialised. */
static inline sc_dual sc_dmul(sc_dual a, sc_dual b, int nd) {
  sc_dual r = a;
  r.v = a.v * b.v;
  for (int k = 0; k < nd; k++) r.d[k] = a.d[k] * b.v + a.v * b.d[k];
  return r;
}

static inline sc_dual sc_ddiv(sc_dual a, sc_dual b, int nd) {
  sc_dual r = a;
  r.v = a.v / b.v;
  for (int k = 0; k < nd; k++) r.d[k] = (a.d[k] - r.v * b.d[k]) / b.v;
  return r;
}

static inline sc_dual sc_dsqrt(sc_dual a, int nd) {
  sc_dual r = a;
  r.v = sqrt(a.v);
  for (int k = 0; k < nd; k++) r.d[k] = a.d[k] / (2 * r.v);
  return r;
}

/* cos and sin of one argument together. */
static inline void sc_dsincos(sc_dual a, int nd, sc_dual *s, sc_dual *c) {
  double sv = sin(a.v), cv = cos(a.v);
  *s = a;
  *c = a;
  s->v = sv;
  c->v = cv;
  for (int k = 0; k < nd; k++) {
    s->d[k] = cv * a.d[k];
    c->d[k] = -sv * a.d[k];
  }
}

#endif
