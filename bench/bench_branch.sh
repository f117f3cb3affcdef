#!/bin/sh
# The whole fig 5.8 branch set (examples/branch-fig58.ini, no sweep, no
# plots) under each accuracy preset and with numerical flows: median wall
# time of REPEAT runs, and what was found (points, special points by
# location method).  Usage: sh bench/bench_branch.sh BUILD/slipcont SRC [REPEAT]
set -eu
BIN=$1 SRC=$2 REPEAT=${3:-5}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/slipcont-bench.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
printf '| run | median time (s) | segments | points | special points | newton | bisection | not located |\n'
printf '|---|---|---|---|---|---|---|---|\n'
for run in fast default precise numerical; do
  preset=$run extra=
  [ "$run" = numerical ] && preset=default extra="--set model.flows=numerical"
  times=
  for k in $(seq "$REPEAT"); do
    t0=$(date +%s.%N)
    # shellcheck disable=SC2086
    "$BIN" run "$SRC/examples/branch-fig58.ini" --quiet --out "$TMP/$run" \
      --set accuracy.preset="$preset" --set task.sweep=no \
      --set output.plot=no $extra
    t1=$(date +%s.%N)
    times="$times $(echo "$t1 - $t0" | bc)"
  done
  med=$(echo "$times" | tr ' ' '\n' | sed '/^$/d' | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
  s="$TMP/$run/summary.txt"
  seg=$(sed -n 's/.*branches: \([0-9]*\), points: \([0-9]*\), special points: \([0-9]*\).*/\1 \2 \3/p' "$s")
  loc=$(sed -n 's/.*certificate: \([0-9]*\); by bisection (fallback): \([0-9]*\); detected but NOT located: \([0-9]*\).*/\1 \2 \3/p' "$s")
  set -- $seg $loc
  printf '| %s | %.2f | %s | %s | %s | %s | %s | %s |\n' "$run" "$med" "$1" "$2" "$3" "$4" "$5" "$6"
done
