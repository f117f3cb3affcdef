#!/bin/sh
# Side-by-side timing of slipcont and AUTO-07p on the logistic flips and
# the period-3 fold (docs/performance.md).  Run from the repository root
# after building `build` (or set BUILD); needs the Debian package
# auto-07p and gfortran.
set -e
BUILD=${BUILD:-build}
ROOT=$(pwd)
WORK=$(mktemp -d)
gcc -O2 -std=c11 -I"$ROOT/include" -I"$ROOT/bench" bench/auto/cont_bench.c \
  "$BUILD/libslipcont.a" -lklu -lamd -lcolamd -lbtf -lsuitesparseconfig \
  -llapack -lblas -lgsl -lgslcblas -linih -lquadmath -fopenmp -lm -o "$WORK/cont_bench"
"$WORK/cont_bench"
cp bench/auto/logistic.f90 bench/auto/logistic3.f90 bench/auto/c.cascade \
   bench/auto/c.fold bench/auto/cascade.auto bench/auto/fold.auto "$WORK"
cd "$WORK"
export PYTHONPATH=/usr/lib/auto-07p/python
auto-07p cascade.auto > cascade.log 2>&1
auto-07p fold.auto > fold.log 2>&1
for i in 1 2 3 4 5; do
  auto-07p cascade.auto 2>&1 | grep "Total Time" |
    awk '{s += $3} END {printf "AUTO cascade: Total Time summed %.3g s\n", s}'
  auto-07p fold.auto 2>&1 | grep "Total Time" |
    awk '{s += $3} END {printf "AUTO fold: Total Time %.3g s\n", s}'
done
grep -h -E "^r_|^fold" cascade.log fold.log
rm -rf "$WORK"
