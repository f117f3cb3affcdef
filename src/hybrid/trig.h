/* cos and sin without a libm call, for the root search's anchors
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

#endif
