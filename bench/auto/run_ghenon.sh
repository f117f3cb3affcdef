#!/bin/sh
# slipcont and AUTO-07p side by side on the generalized Henon map ghenon
# (docs/performance.md, "Beside AUTO-07p: ghenon"): the branch of fixed
# points through LP, NS (AUTO's TR) and PD, then the fold, flip and NS
# curves in (alpha, beta) at R = 0.5 with their points of codimension
# two; AUTO at its tightest settings (EPSL = EPSU = 1e-12, EPSS = 1e-14,
# DS = DSMAX = 0.08, a hundredth of the window), both timed the same way,
# in turn, one thread.
#
#   sh bench/auto/run_ghenon.sh BUILD [ROUNDS]
#
# BUILD is a Release build folder of this checkout with `libslipcont.a`
# built (cmake --build BUILD --target slipcont_static); ROUNDS (default
# 21) the rounds of each tool in turn.  Run from the repository root.
# Needs auto-07p (Debian/Ubuntu: `apt-get install auto-07p`; AUTO_DIR
# defaults to /usr/lib/auto-07p), gfortran, gcc and python3; prints a
# Markdown summary.
set -eu
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "usage: sh bench/auto/run_ghenon.sh BUILD [ROUNDS]" >&2
  exit 2
fi
BUILD=$1 ROUNDS=${2:-21}
case $ROUNDS in
''|*[!0-9]*|0) echo "run_ghenon.sh: ROUNDS = $ROUNDS (valid: 1..1000)" >&2; exit 2 ;;
esac
[ "$ROUNDS" -le 1000 ] || { echo "run_ghenon.sh: ROUNDS = $ROUNDS (valid: 1..1000)" >&2; exit 2; }
ROOT=$(pwd)
HERE=$ROOT/bench/auto
AUTO_DIR=${AUTO_DIR:-/usr/lib/auto-07p}
for f in "$BUILD/libslipcont.a" "$AUTO_DIR/cmds/cmds.make"; do
  [ -e "$f" ] || { echo "run_ghenon.sh: $f not found" >&2; exit 2; }
done
# One thread on both sides (AUTO is built with -fopenmp).
OMP_NUM_THREADS=1
export OMP_NUM_THREADS
WORK=$(mktemp -d "${TMPDIR:-/tmp}/slipcont-ghenon.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
cp "$HERE/ghenon.f90" "$HERE/c.ghenon" "$WORK/"
(cd "$WORK" && make -s -f "$AUTO_DIR/cmds/cmds.make" AUTO_DIR="$AUTO_DIR" \
  EQUATION_NAME=ghenon ghenon.exe >build.log 2>&1) || {
  echo "run_ghenon.sh: building ghenon.exe failed:" >&2
  cat "$WORK/build.log" >&2
  exit 1
}
gcc -O2 -std=c11 -I"$ROOT/include" -I"$ROOT/bench" "$HERE/ghenon_bench.c" \
  "$BUILD/libslipcont.a" -lklu -lamd -lcolamd -lbtf -lsuitesparseconfig \
  -lslicot -llapack -lblas -lgsl -lgslcblas -linih -lquadmath -lgfortran \
  -fopenmp -lm -o "$WORK/ghenon_bench"
echo "slipcont warm, in one process (median of 50):"
"$WORK/ghenon_bench" repeat 50 | tail -1
echo
python3 "$HERE/run_ghenon.py" "$WORK" "$ROUNDS" "$WORK/ghenon_bench"
