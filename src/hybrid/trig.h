/* cos and sin, and atan2, without a libm call, for the root search
 * (src/hybrid/guard.c): private to the hybrid layer. */
#ifndef SC_HYBRID_TRIG_H
#define SC_HYBRID_TRIG_H

#include <math.h>

/* pi/2 in three parts (the first two of 33 bits, so that k times them is
 * exact for |k| < 2^20), and 2/pi. */
#define SC_PIO2_1 0x1.921fb544p+0
#define SC_PIO2_2 0x1.0b4611a6p-34
#define SC_PIO2_3 0x1.3198a2e037073p-69
#define SC_2_PI 0.63661977236758134308
/* Arguments up to this go to sc_fast_sincos's own reduction (|k| <
 * 2^17); beyond, libm. */
#define SC_FAST_TRIG_MAX 1e5
/* Its error bound, in ulps of 1 (tests/test_guard.c). */
#define SC_FAST_TRIG_ULPS 2.0

/* cos and sin of x, within 2 ulps (of 1, and of the value's binade) of
 * libm's (tests/test_guard.c checks 1e6 arguments in [-1000, 1000]),
 * with no call: x = k pi/2 + r, |r| <= pi/4 (Cody and Waite's reduction
 * with the three parts above), then Taylor polynomials in r^2 through
 * r^17 and r^18 (truncation below 1e-19) by Estrin's scheme, and the
 * quadrant.  libm beyond SC_FAST_TRIG_MAX. */
static inline void sc_fast_sincos(double x, double *s, double *c) {
  if (!(fabs(x) <= SC_FAST_TRIG_MAX)) {
    *s = sin(x), *c = cos(x);
    return;
  }
  const double shift = 0x1.8p52; /* rounds to an integer when added */
  double kf = (x * SC_2_PI + shift) - shift;
  long k = (long)kf;
  double r = ((x - kf * SC_PIO2_1) - kf * SC_PIO2_2) - kf * SC_PIO2_3;
  double z = r * r, z2 = z * z, z4 = z2 * z2, z8 = z4 * z4;
  double s01 = -1.0 / 6 + z * (1.0 / 120);
  double s23 = -1.0 / 5040 + z * (1.0 / 362880);
  double s45 = -1.0 / 39916800 + z * (1.0 / 6227020800);
  double s67 = -1.0 / 1307674368000 + z * (1.0 / 355687428096000);
  double S = (s01 + z2 * s23) + z4 * (s45 + z2 * s67);
  double c01 = -0.5 + z * (1.0 / 24), c23 = -1.0 / 720 + z * (1.0 / 40320);
  double c45 = -1.0 / 3628800 + z * (1.0 / 479001600);
  double c67 = -1.0 / 87178291200 + z * (1.0 / 20922789888000);
  double C = ((c01 + z2 * c23) + z4 * (c45 + z2 * c67)) +
             z8 * (-1.0 / 6402373705728000);
  double sr = r + r * (z * S), cr = 1 + z * C;
  switch (k & 3) {
  case 0: *s = sr, *c = cr; break;
  case 1: *s = cr, *c = -sr; break;
  case 2: *s = -sr, *c = -cr; break;
  default: *s = -cr, *c = sr; break;
  }
}

#include "atan_table.h"
_Static_assert(SC_ATAN_DEG == 9, "sc_atan2 evaluates b_1..b_9");

/* Its error bound, in ulps of the result (tests/test_guard.c). */
#define SC_ATAN2_ULPS 1.0

/* a * b = *hi + *lo exactly (Dekker's product, with Veltkamp's split
 * into 26-bit halves: no fused multiply-add, so that every build computes
 * the same bits), for |a|, |b| well inside 2^-900..2^900. */
static inline void sc_two_prod(double a, double b, double *hi, double *lo) {
  const double split = 134217729.0; /* 2^27 + 1 */
  double ca = split * a, ah = ca - (ca - a), al = a - ah;
  double cb = split * b, bh = cb - (cb - b), bl = b - bh;
  *hi = a * b;
  *lo = ((ah * bh - *hi) + ah * bl + al * bh) + al * bl;
}

/* atan2(y, x) within one ulp (tests/test_guard.c measures it against
 * long double on 4e6 arguments), with one division and no call.  r =
 * min(|x|, |y|) / max(|x|, |y|) in [0, 1], and its rounding error r_lo =
 * (num - r den) / den, from Dekker's exact product, folded in at the end
 * (without it, r's half ulp alone costs up to 0.94 ulp of the result).
 * For r < 3/64 the odd series through r^13; else c = k / 32, the nearest
 * table point, and atan(r) = atan(c) + p(r - c), p the Taylor polynomial
 * of degree 9 around c (exact coefficients rounded once; |r - c| <= 1/64
 * puts the truncation below 1e-19; r - c is exact by Sterbenz's lemma),
 * both by Estrin's scheme.  The octant's base (atan c, pi/2 - atan c,
 * pi - atan c or pi/2 + atan c) is a sum of two doubles, so that the
 * rounding that matters is the last addition's.  glibc's atan2 took 18
 * ns a call here, 29 ns on a dependent chain (docs/performance.md).
 * Zeros, infinities, NaN, and magnitudes beyond 2^-900..2^900 go to
 * libm; a ratio below 2^-1022 is subnormal and so is the result, rounded
 * as libm rounds it (tests/test_guard.c). */
static inline double sc_atan2(double y, double x) {
  double ax = fabs(x), ay = fabs(y);
  int sw = ay > ax;
  double num = sw ? ax : ay, den = sw ? ay : ax, r = num / den;
  if (!(num >= 0x1p-900 && den <= 0x1p900)) return atan2(y, x);
  double ph, pl;
  sc_two_prod(r, den, &ph, &pl);
  double r_lo = ((num - ph) - pl) / den; /* num - ph: Sterbenz, exact */
  int k = (int)(r * SC_ATAN_N + 0.5);
  int q = sw + 2 * (x < 0); /* 0: atan c, 1: pi/2 - .., 2: pi - .., 3 */
  double p;
  if (k <= 1) {
    /* r < 3/64: the odd series through r^13 around 0 (truncation below
     * 2^-61 of r), so that no base cancels against p */
    k = 0;
    double z = r * r, z2 = z * z, z4 = z2 * z2;
    double s01 = -1.0 / 3 + z * (1.0 / 5), s23 = -1.0 / 7 + z * (1.0 / 9);
    double s45 = -1.0 / 11 + z * (1.0 / 13);
    p = r + (r_lo + r * (z * ((s01 + z2 * s23) + z4 * s45)));
  } else {
    const double *b = sc_atan_coef[k];
    double e = r - (double)k * (1.0 / SC_ATAN_N), e2 = e * e, e4 = e2 * e2;
    double p01 = b[0] + e * b[1], p23 = b[2] + e * b[3];
    double p45 = b[4] + e * b[5], p67 = b[6] + e * b[7];
    p = e * (((p01 + e2 * p23) + e4 * (p45 + e2 * p67)) + (e4 * e4) * b[8]) +
        r_lo * b[0];
  }
  const double *base = sc_atan_base[q][k];
  double v = base[0] + (base[1] + ((q == 1 || q == 2) ? -p : p));
  return y < 0 ? -v : v;
}

#endif
