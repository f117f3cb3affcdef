#!/bin/sh
# The ghenon atlas (docs/maps.md, "The ghenon atlas"): the fold, flip and
# Neimark-Sacker curves of the fixed point of the generalized Henon map
# (x, y) -> (y, alpha - beta x - y^2 + R x y) in the (alpha, beta) plane
# at R = 0.5, with the points of codimension two R1, R2, R3, R4 and LPPD,
# drawn from their closed forms over a period chart of the map computed
# with the toolkit's model (sc_map_eval_n).
#
#   sh docs/img/ghenon-atlas.sh BUILD [OUT.png]
#
# BUILD is a build folder with libslipcont.a; OUT defaults to
# docs/img/ghenon-atlas.png.  Run from the repository root; needs gcc and
# gnuplot.
#
# The closed forms: the fixed points are x = y = s with
# (1 - R) s^2 + (1 + beta) s = alpha; the Jacobian there has trace
# T = (R - 2) s and determinant D = beta - R s, so
#   fold (1 - T + D = 0): alpha = (1 + beta)^2 / (4 (R - 1));
#   flip (1 + T + D = 0): alpha = (3 - R) (1 + beta)^2 / 4;
#   NS (D = 1, |T| < 2):  s = (beta - 1) / R, alpha = (1 - R) s^2 + (1 + beta) s,
#                         between R1 and R2;
#   R1 (T = 2, D = 1), R2 (T = -2), R3 (T = -1): s = 2, -2, -1 over (R - 2),
#   beta = 1 + R s; R4 (T = 0, D = 1): (0, 1); LPPD (T = 0, D = -1): (0, -1).
# The chart: each cell starts from the last state of the cell to its left
# (from (0.1, 0.1) at a row's start and after an escape) and, if that
# escapes, from each fixed point nudged by 1e-3; 2000 iterates of
# transient, then the least period p <= 12 with |f^p(x) - x| <= 1e-7
# (1 + |x|); "escape" where |x| passes 1e6, "no period" otherwise
# (quasi-periodic or chaotic).
set -eu
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "usage: sh docs/img/ghenon-atlas.sh BUILD [OUT.png]" >&2
  exit 2
fi
BUILD=$1 OUT=${2:-docs/img/ghenon-atlas.png}
[ -e "$BUILD/libslipcont.a" ] || { echo "ghenon-atlas.sh: $BUILD/libslipcont.a not found" >&2; exit 2; }
command -v gnuplot >/dev/null 2>&1 || { echo "ghenon-atlas.sh: gnuplot not found" >&2; exit 2; }
ROOT=$(pwd)
WORK=$(mktemp -d "${TMPDIR:-/tmp}/slipcont-atlas.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
cat >"$WORK/chart.c" <<'CEOF'
#include <math.h>
#include <stdio.h>
#include "slipcont/slipcont.h"
enum { NA = 480, NB = 360, TRANSIENT = 2000, PMAX = 12 };
static const double ALO = -3, AHI = 5, BLO = -1.5, BHI = 2, R = 0.5;
static const double ESCAPE = 1e6, SAME = 1e-7, NUDGE = 1e-3;
static int step(sc_map *m, sc_mapn_value *v, double *x) {
  if (sc_map_eval_n(m, x, 0, v, NULL) != SC_OK) return 1;
  x[0] = v->f[0], x[1] = v->f[1];
  return !(fabs(x[0]) < ESCAPE && fabs(x[1]) < ESCAPE);
}
static int period(sc_map *m, sc_mapn_value *v, double *x) {
  for (int k = 0; k < TRANSIENT; k++)
    if (step(m, v, x)) return -1;
  double x0[2] = {x[0], x[1]};
  for (int p = 1; p <= PMAX; p++) {
    if (step(m, v, x)) return -1;
    if (fabs(x[0] - x0[0]) + fabs(x[1] - x0[1]) <=
        SAME * (1 + fabs(x0[0]) + fabs(x0[1])))
      return p;
  }
  return 0;
}
int main(void) {
  sc_map *m;
  sc_mapn_value *v;
  if (sc_map_alloc("ghenon", NULL, &m, NULL) || sc_mapn_value_alloc(m, 0, &v, NULL))
    return 1;
  sc_map_set_param(m, 2, R, NULL);
  for (int j = 0; j < NB; j++) {
    double beta = BLO + (BHI - BLO) * (j + 0.5) / NB, x[2] = {0.1, 0.1};
    sc_map_set_param(m, 1, beta, NULL);
    for (int i = 0; i < NA; i++) {
      double alpha = ALO + (AHI - ALO) * (i + 0.5) / NA;
      sc_map_set_param(m, 0, alpha, NULL);
      int p = period(m, v, x);
      /* escaped: again from each fixed point, nudged off it */
      double disc = (1 + beta) * (1 + beta) + 4 * (1 - R) * alpha;
      for (int k = 0; p < 0 && k < 2 && disc >= 0; k++) {
        x[0] = x[1] = (-(1 + beta) + (k ? 1 : -1) * sqrt(disc)) / (2 * (1 - R)) + NUDGE;
        p = period(m, v, x);
      }
      if (p < 0) x[0] = x[1] = 0.1;
      printf("%.6g %.6g %d\n", alpha, beta, p);
    }
    printf("\n");
  }
  sc_mapn_value_free(v);
  sc_map_free(m);
  return 0;
}
CEOF
gcc -O2 -std=c11 -I"$ROOT/include" "$WORK/chart.c" "$BUILD/libslipcont.a" \
  -lklu -lamd -lcolamd -lbtf -lsuitesparseconfig -llapack -lblas -lgsl \
  -lgslcblas -linih -lquadmath -fopenmp -lm -o "$WORK/chart"
"$WORK/chart" >"$WORK/chart.dat"
cat >"$WORK/atlas.gp" <<GEOF
set terminal pngcairo size 1040,640 font "sans,11"
set output "$OUT"
R = 0.5
s(b) = (b - 1) / R
afold(b) = (1 + b)**2 / (4 * (R - 1))
aflip(b) = (3 - R) * (1 + b)**2 / 4
ans(b) = (1 - R) * s(b)**2 + (1 + b) * s(b)
sR(k) = k / (R - 2)
bR(k) = 1 + R * sR(k)
aR(k) = (1 - R) * sR(k)**2 + (1 + bR(k)) * sR(k)
set xrange [-3:5]
set yrange [-1.5:2]
set xlabel "alpha"
set ylabel "beta"
set title "ghenon at R = 0.5: fold, flip and NS curves of the fixed point (closed forms) over a period chart"
# one colour a class: escape white, no period grey, periods 1..12
col(p) = p < 0 ? 0xffffff : p == 0 ? 0x8c8c8c : p == 1 ? 0xcfe3f7 : p == 2 ? 0xf9dca8 : p == 3 ? 0xc9ebc0 : p == 4 ? 0xf4b6c2 : p == 5 ? 0xd8c8f0 : p == 6 ? 0xfff09a : p == 8 ? 0xa8e0da : 0xe0c8a8
red(p) = (col(p) >> 16) & 255
grn(p) = (col(p) >> 8) & 255
blu(p) = col(p) & 255
set key outside right top box
set parametric
set trange [-1.5:2]
set samples 400
set label 1 "R1" at aR(2), bR(2) offset -3.5,-0.6 front
set label 2 "R2" at aR(-2), bR(-2) offset 0.8,0 front
set label 3 "R3" at aR(-1), bR(-1) offset 0.8,0 front
set label 4 "R4" at 0, 1 offset 0.8,0 front
set label 5 "LPPD" at 0, -1 offset 0.8,-0.6 front
plot "$WORK/chart.dat" using 1:2:(red(\$3)):(grn(\$3)):(blu(\$3)) with rgbimage notitle, \
     1/0, 1/0 with boxes fs solid lc rgb "#cfe3f7" title "period 1", \
     1/0, 1/0 with boxes fs solid lc rgb "#f9dca8" title "period 2", \
     1/0, 1/0 with boxes fs solid lc rgb "#f4b6c2" title "period 4", \
     1/0, 1/0 with boxes fs solid lc rgb "#e0c8a8" title "other periods <= 12", \
     1/0, 1/0 with boxes fs solid lc rgb "#8c8c8c" title "no period <= 12", \
     1/0, 1/0 with boxes fs empty border lc rgb "black" lc rgb "black" title "escape", \
     afold(t), t lw 2 lc rgb "#1f5fbf" title "fold (LP)", \
     aflip(t), t lw 2 lc rgb "#c0392b" title "flip (PD)", \
     ans(bR(2) + (bR(-2) - bR(2)) * (t + 1.5) / 3.5), bR(2) + (bR(-2) - bR(2)) * (t + 1.5) / 3.5 lw 2 lc rgb "#1e8449" title "Neimark-Sacker (NS)", \
     "+" using (aR(2)):(bR(2)) every ::0::0 with points pt 7 ps 1.4 lc rgb "black" notitle, \
     "+" using (aR(-2)):(bR(-2)) every ::0::0 with points pt 7 ps 1.4 lc rgb "black" notitle, \
     "+" using (aR(-1)):(bR(-1)) every ::0::0 with points pt 7 ps 1.4 lc rgb "black" notitle, \
     "+" using (0):(1) every ::0::0 with points pt 7 ps 1.4 lc rgb "black" notitle, \
     "+" using (0):(-1) every ::0::0 with points pt 7 ps 1.4 lc rgb "black" title "codimension two"
GEOF
gnuplot "$WORK/atlas.gp"
echo "ghenon-atlas.sh: $OUT"
