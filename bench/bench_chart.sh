#!/bin/sh
# Chart benchmarks: see docs/performance.md, "How to measure".
# usage: bench_chart.sh BENCH_CHART SLIPCONT SOURCE_DIR WORK_DIR [MPIRUN]
# Environment: SLIPCONT_BENCH_REPEAT (default 5) repeats of the short
# measurements, SLIPCONT_BENCH_BIG=0 to skip fig 5.7(a) at 1000 x 1000.
set -u
B=$1
CLI=$2
SRC=$3
W=$4
MPIRUN=${5:-}
REPEAT=${SLIPCONT_BENCH_REPEAT:-5}
mkdir -p "$W"
cd "$W" || exit 1
echo "== $(date -u '+%Y-%m-%dT%H:%M:%SZ') on $(nproc) cores; uptime: $(uptime)"

echo "== map iterates per second on one core (fig 5.7(a) points)"
OMP_NUM_THREADS=1 "$B" iterates || exit 1

echo "== chart points per second, 1 vs 2 threads (fig 5.7(a) at 120 x 120)"
"$B" points 120 || exit 1

# Wall time of a whole `slipcont run` (scene, compute, CSV, summary, plot
# script; the PNG is left out: gnuplot's time is not ours).
timed() { # timed LABEL [env...] -- command...
  label=$1
  shift
  t0=$(date +%s.%N)
  "$@" > /dev/null 2>&1 || echo "  (failed: $*)"
  t1=$(date +%s.%N)
  echo "$label: $(awk "BEGIN { printf \"%.3f\", $t1 - $t0 }") s"
}

if [ -n "$MPIRUN" ]; then
  echo "== 1 rank vs 2 MPI ranks, 1 thread each (fig 5.7(a) at 200 x 200)"
  MPI="$MPIRUN --oversubscribe -np 2"
  [ "$(id -u)" -eq 0 ] && MPI="$MPIRUN --oversubscribe --allow-run-as-root -np 2"
  MPI1=$(echo "$MPI" | sed 's/-np 2/-np 1/')
  i=1
  while [ $i -le "$REPEAT" ]; do
    OMP_NUM_THREADS=1 timed "run $i, 1 rank " $MPI1 "$CLI" run \
      "$SRC/examples/chart-alpha-beta.ini" --quiet --out mpi1 \
      --set output.plot=no
    OMP_NUM_THREADS=1 timed "run $i, 2 ranks" $MPI "$CLI" run \
      "$SRC/examples/chart-alpha-beta.ini" --quiet --out mpi2 \
      --set output.plot=no
    cmp -s mpi1/chart.csv mpi2/chart.csv || echo "  2-rank chart differs!"
    i=$((i + 1))
  done
fi

echo "== fig 5.7(a) at 400 x 400, 2 threads (whole run, no PNG)"
i=1
while [ $i -le 3 ]; do
  timed "run $i" "$CLI" run "$SRC/examples/chart-alpha-beta.ini" --quiet \
    --out a400 --threads 2 --set task.x-steps=400 --set task.y-steps=400 \
    --set output.plot=no
  i=$((i + 1))
done
grep -E "points,|rank" a400/summary.txt

if [ "${SLIPCONT_BENCH_BIG:-1}" != 0 ]; then
  echo "== fig 5.7(a) at 1000 x 1000, 2 threads (whole run, no PNG)"
  timed "run 1" "$CLI" run "$SRC/examples/chart-alpha-beta.ini" --quiet \
    --out a1000 --threads 2 --set task.x-steps=1000 \
    --set task.y-steps=1000 --set output.plot=no
  grep -E "points,|rank" a1000/summary.txt
fi
