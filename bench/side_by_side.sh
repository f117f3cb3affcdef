#!/bin/sh
# The event map's speed, this checkout against an earlier commit, measured
# side by side: both are built the same way (Release, from `git archive`
# for the base) and their benchmarks run alternately, so that the load of
# a shared machine falls on both (docs/performance.md, "How to measure").
#
# usage: bench/side_by_side.sh BASE_REV [ROUNDS] [big]
#   BASE_REV  a commit of this repository (e.g. dac61ff, HEAD~3)
#   ROUNDS    alternating rounds (default 3); each round runs
#             bench_events 5 100000 and bench_chart iterates (3 repeats)
#             for the base, then for this checkout
#   big       also fig 5.7(a) at 1000 x 1000 on 2 threads, whole runs
#             (about 35-50 s each), one a round and build
# Environment: SLIPCONT_SBS_DIR (default /tmp/slipcont-sbs) keeps the
# builds; a base build already there is reused.  SLIPCONT_SBS_NATIVE=1
# also builds this checkout with SLIPCONT_NATIVE=ON and runs it third in
# every round (the summary's third column).
#
# Prints one line per measurement and a summary of medians over the
# rounds (rates per CPU second; the 1000 x 1000 chart's wall and user s),
# then the 90th percentile of each build's rates (the 10th of its times):
# a shared machine's load only slows a run down, so this quantile moves
# less than the median (one binary against its copy, 40 rounds: within
# 0.9%, the medians 7% apart; docs/performance.md, "How to measure").
set -eu
if [ $# -lt 1 ]; then
  sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
BASE=$1
ROUNDS=${2:-3}
BIG=${3:-}
SRC=$(cd "$(dirname "$0")/.." && pwd)
DIR=${SLIPCONT_SBS_DIR:-/tmp/slipcont-sbs}
case $ROUNDS in
[1-9] | [1-9][0-9]) ;;
*) echo "side_by_side: ROUNDS = $ROUNDS (valid: 1..99)" >&2; exit 2 ;;
esac
case $BIG in
'' | big) ;;
*) echo "side_by_side: third argument $BIG (valid: big, or none)" >&2; exit 2 ;;
esac
REV=$(git -C "$SRC" rev-parse --short --verify --quiet "$BASE^{commit}") || {
  echo "side_by_side: $BASE is not a commit of $SRC" >&2
  exit 2
}
mkdir -p "$DIR"
J=$(nproc 2>/dev/null || echo 2)

build() { # build SOURCE BUILD_DIR [CMAKE_ARGS...]
  src=$1 bdir=$2
  shift 2
  cmake -S "$src" -B "$bdir" -DCMAKE_BUILD_TYPE=Release "$@" > "$bdir.log" 2>&1 &&
    cmake --build "$bdir" -j "$J" --target bench_events bench_chart \
      slipcont_cli >> "$bdir.log" 2>&1 || {
    echo "side_by_side: building $src failed (log: $bdir.log)" >&2
    exit 1
  }
}

if [ ! -x "$DIR/base-$REV/build/bench/bench_events" ]; then
  rm -rf "$DIR/base-$REV"
  mkdir -p "$DIR/base-$REV"
  git -C "$SRC" archive "$REV" | tar -x -C "$DIR/base-$REV"
  echo "building the base $REV in $DIR/base-$REV"
  build "$DIR/base-$REV" "$DIR/base-$REV/build"
fi
echo "building this checkout in $DIR/now"
build "$SRC" "$DIR/now"
NATIVE=${SLIPCONT_SBS_NATIVE:-0}
if [ "$NATIVE" = 1 ]; then
  echo "building this checkout with SLIPCONT_NATIVE=ON in $DIR/native"
  build "$SRC" "$DIR/native" -DSLIPCONT_NATIVE=ON
fi

OUT="$DIR/results-$REV.txt"
: > "$OUT"
echo "== $(date -u '+%Y-%m-%dT%H:%M:%SZ') on $J cores; $(uptime)"
run() { # run LABEL BUILD_DIR
  ev=$("$2/bench/bench_events" 5 100000 | sed 's/ iterates.*//; s/.*: //' |
    tr '\n' ' ')
  ch=$(OMP_NUM_THREADS=1 SLIPCONT_BENCH_REPEAT=3 "$2/bench/bench_chart" \
    iterates | tail -1 | sed 's/.*bare \([^,]*\), through the chart \([^;]*\);.*/\1 \2/')
  set -- "$1" $ev $ch
  echo "$1 fig56 $2 fig58 $3 bare $4 chart $5" | tee -a "$OUT"
}
big() { # big LABEL CLI
  o="$DIR/big-$1"
  rm -rf "$o"
  t=$( { /usr/bin/time -f '%e %U' "$2" run "$SRC/examples/chart-alpha-beta.ini" \
    --set task.x-steps=1000 --set task.y-steps=1000 --set output.plot=no \
    --out "$o" --quiet --threads 2 > /dev/null; } 2>&1 | tail -1)
  echo "$1 big $t" | tee -a "$OUT"
}
i=1
while [ $i -le "$ROUNDS" ]; do
  run base "$DIR/base-$REV/build"
  run now "$DIR/now"
  [ "$NATIVE" = 1 ] && run native "$DIR/native"
  if [ "$BIG" = big ]; then
    big base "$DIR/base-$REV/build/slipcont"
    big now "$DIR/now/slipcont"
    [ "$NATIVE" = 1 ] && big native "$DIR/native/slipcont"
  fi
  i=$((i + 1))
done

echo "== medians over $ROUNDS rounds (base $REV | this checkout [| native])"
awk '
  function sort_(a, n,   i, j, t) {
    for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++)
      if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
  }
  function med(a, n) {
    sort_(a, n)
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
  }
  # the p-quantile of a[1..n], the nearest rank below (p n rounded down,
  # at least 1: below 10 rounds the 90th percentile is the median rank
  # or one above it)
  function quant(a, n, p,   r) {
    sort_(a, n)
    r = int(p * n); if (r < 1) r = 1
    return a[r]
  }
  # the median of the values of key under label l; with q, the 90th
  # percentile of a rate (the 10th of a time)
  function summary(l, key, q,   i, c) {
    for (i = 1; i <= n[l, key]; i++) c[i] = v[l, key, i]
    if (!q) return med(c, n[l, key])
    return quant(c, n[l, key], (key == "wall" || key == "user") ? 0.1 : 0.9)
  }
  # the ratio "faster than the base" of value x against the base mb
  function ratio(key, mb, x) {
    return (key == "wall" || key == "user") ? mb / x : x / mb
  }
  $2 == "fig56" { for (k = 2; k < NF; k += 2) { n[$1, $k]++; v[$1, $k, n[$1, $k]] = $(k + 1) } }
  $2 == "big" { n[$1, "wall"]++; v[$1, "wall", n[$1, "wall"]] = $3
                n[$1, "user"]++; v[$1, "user", n[$1, "user"]] = $4 }
  END {
    split("fig56 fig58 bare chart wall user", keys, " ")
    for (q = 0; q <= 1; q++) {
      if (q) printf "== 90th percentiles of the rates, 10th of the times\n"
      for (k = 1; k <= 6; k++) {
        key = keys[k]
        if (!n["base", key] || !n["now", key]) continue
        mb = summary("base", key, q); mc = summary("now", key, q)
        printf "%-6s %12.4g | %12.4g   (%.3fx)", key, mb, mc, ratio(key, mb, mc)
        if (n["native", key]) {
          mn = summary("native", key, q)
          printf " | %12.4g   (%.3fx)", mn, ratio(key, mb, mn)
        }
        printf "\n"
      }
    }
  }' "$OUT"
echo "(rates: iterates per CPU second; wall, user: seconds; ratio > 1: faster than the base)"
