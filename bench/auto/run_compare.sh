#!/bin/sh
# slipcont and AUTO-07p side by side on the logistic cascade's flips, the
# period-3 fold and the cubic map's fold curve with its cusp
# (docs/performance.md, "Beside AUTO-07p"): AUTO at its tightest settings
# (EPSL = EPSU = 1e-12, EPSS = 1e-14, stopping at the special point
# sought, steps scaled to each window), both timed the same way, in turn.
#
#   sh bench/auto/run_compare.sh BUILD [ROUNDS]
#
# BUILD is a Release build folder of this checkout with `slipcont` and
# `libslipcont.a` built (cmake --build BUILD --target slipcont_cli
# slipcont_static); ROUNDS (default 21) the rounds of each tool in turn.
# Run from the repository root.  Needs auto-07p (Debian/Ubuntu:
# `apt-get install auto-07p`; AUTO_DIR defaults to /usr/lib/auto-07p),
# gfortran, gcc and python3; prints a Markdown summary.
set -eu
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "usage: sh bench/auto/run_compare.sh BUILD [ROUNDS]" >&2
  exit 2
fi
BUILD=$1 ROUNDS=${2:-21}
case $ROUNDS in
''|*[!0-9]*|0) echo "run_compare.sh: ROUNDS = $ROUNDS (valid: 1..1000)" >&2; exit 2 ;;
esac
[ "$ROUNDS" -le 1000 ] || { echo "run_compare.sh: ROUNDS = $ROUNDS (valid: 1..1000)" >&2; exit 2; }
ROOT=$(pwd)
HERE=$ROOT/bench/auto
AUTO_DIR=${AUTO_DIR:-/usr/lib/auto-07p}
for f in "$BUILD/slipcont" "$BUILD/libslipcont.a" "$AUTO_DIR/cmds/cmds.make"; do
  [ -e "$f" ] || { echo "run_compare.sh: $f not found" >&2; exit 2; }
done
# One thread on both sides (AUTO is built with -fopenmp).
OMP_NUM_THREADS=1
export OMP_NUM_THREADS
WORK=$(mktemp -d "${TMPDIR:-/tmp}/slipcont-compare.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
for b in cont_bench curve_bench; do
  gcc -O2 -std=c11 -I"$ROOT/include" -I"$ROOT/bench" "$HERE/$b.c" \
    "$BUILD/libslipcont.a" -lklu -lamd -lcolamd -lbtf -lsuitesparseconfig \
    -llapack -lblas -lgsl -lgslcblas -linih -lquadmath -fopenmp -lm \
    -o "$WORK/$b"
done
cp "$HERE"/cascade.f90 "$HERE"/fold.f90 "$HERE"/cusp.f90 \
   "$HERE"/c.cascade "$HERE"/c.fold "$HERE"/c.cusp "$WORK/"
for eq in cascade fold cusp; do
  (cd "$WORK" && make -s -f "$AUTO_DIR/cmds/cmds.make" AUTO_DIR="$AUTO_DIR" \
    EQUATION_NAME=$eq "$eq.exe" >build.log 2>&1) || {
    echo "run_compare.sh: building $eq.exe failed:" >&2
    cat "$WORK/build.log" >&2
    exit 1
  }
done
echo "slipcont warm, in one process (median of 200):"
"$WORK/cont_bench" repeat 200
"$WORK/curve_bench" repeat 200
echo
python3 "$HERE/run_compare.py" "$WORK" "$ROUNDS" "$BUILD/slipcont" "$ROOT"
