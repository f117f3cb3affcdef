#!/bin/sh
# slipcont and AUTO-07p side by side on the logistic and cubic maps
# (docs/accuracy.md, "Branches on smooth maps"): step size and
# Newton tolerances against the error of the located flips and folds
# (known exactly) and time, one point per setting on one plot.
#
#   sh bench/auto/run_auto.sh BUILD/bench/bench_accuracy_branch OUTDIR [REPEATS]
#
# Runs `bench_accuracy_branch --smooth OUTDIR REPEATS` (slipcont: tables
# to OUTDIR/smooth.md, rows to smooth.csv), then builds the AUTO problems
# of this folder with AUTO's own makefile (cmds.make, as its @r command
# does; its compile flags are gfortran -O2 -fopenmp -std=legacy) and runs
# them at each setting (run_auto.py), appending AUTO's rows and tables,
# and redraws OUTDIR/smooth.png.  Needs auto-07p (Debian/Ubuntu:
# `apt-get install auto-07p`; AUTO_DIR defaults to /usr/lib/auto-07p),
# gfortran and python3; without them the AUTO part is skipped with a
# message and the exit status is 0 (CI does not install AUTO).
set -eu
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: sh bench/auto/run_auto.sh BUILD/bench/bench_accuracy_branch OUTDIR [REPEATS]" >&2
  exit 2
fi
BIN=$1 OUT=$2 REPEAT=${3:-11}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
"$BIN" --smooth "$OUT" "$REPEAT"

AUTO_DIR=${AUTO_DIR:-/usr/lib/auto-07p}
missing=
[ -f "$AUTO_DIR/cmds/cmds.make" ] || missing=" auto-07p (no $AUTO_DIR/cmds/cmds.make)"
command -v gfortran >/dev/null 2>&1 || missing="$missing gfortran"
command -v python3 >/dev/null 2>&1 || missing="$missing python3"
command -v make >/dev/null 2>&1 || missing="$missing make"
if [ -n "$missing" ]; then
  echo "run_auto.sh: skipping the AUTO-07p comparison; not found:$missing" >&2
  echo "run_auto.sh: install it with 'apt-get install auto-07p' (and gfortran), or set AUTO_DIR" >&2
  echo "run_auto.sh: slipcont's side is in $OUT/smooth.md and $OUT/smooth.csv" >&2
  exit 0
fi

# One thread, as slipcont's side (AUTO is built with -fopenmp).
OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
export OMP_NUM_THREADS
WORK=$(mktemp -d "${TMPDIR:-/tmp}/slipcont-auto.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
cp "$HERE"/*.f90 "$HERE"/c.* "$WORK/"
for eq in logistic logistic3 cubic; do
  (cd "$WORK" && make -s -f "$AUTO_DIR/cmds/cmds.make" AUTO_DIR="$AUTO_DIR" \
    EQUATION_NAME=$eq "$eq.exe" >build.log 2>&1) || {
    echo "run_auto.sh: building $eq.exe with $AUTO_DIR/cmds/cmds.make failed:" >&2
    cat "$WORK/build.log" >&2
    exit 1
  }
  [ -x "$WORK/$eq.exe" ] || { echo "run_auto.sh: no $eq.exe was built" >&2; exit 1; }
done
python3 "$HERE/run_auto.py" "$WORK" "$OUT" "$REPEAT"
if command -v gnuplot >/dev/null 2>&1; then
  gnuplot "$OUT/smooth.gp" 2>/dev/null || echo "run_auto.sh: gnuplot failed (smooth.gp)" >&2
fi
echo "run_auto.sh: $OUT/smooth.md, smooth.csv, smooth.png"
