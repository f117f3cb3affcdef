#!/bin/sh
# The cubic map's fold curve and cusp, slipcont and AUTO-07p side by side
# (docs/performance.md).  Run from the repository root after building
# `build` (or set BUILD); needs the Debian package auto-07p and gfortran.
set -e
BUILD=${BUILD:-build}
ROOT=$(pwd)
WORK=$(mktemp -d)
gcc -O2 -std=c11 -I"$ROOT/include" -I"$ROOT/bench" bench/auto/curve_bench.c \
  "$BUILD/libslipcont.a" -lklu -lamd -lcolamd -lbtf -lsuitesparseconfig \
  -llapack -lblas -lgsl -lgslcblas -linih -lquadmath -fopenmp -lm -o "$WORK/curve_bench"
"$WORK/curve_bench"
cp bench/auto/cubic.f90 bench/auto/c.curve \
   bench/auto/curve.auto "$WORK"
cd "$WORK"
export PYTHONPATH=/usr/lib/auto-07p/python
auto-07p curve.auto > curve.log 2>&1
for i in 1 2 3 4 5; do
  auto-07p curve.auto 2>&1 | grep "Total Time" |
    awk '{s += $3} END {printf "AUTO cubic fold curve: Total Time summed %.3g s\n", s}'
done
grep -h "^AUTO" curve.log
rm -rf "$WORK"
