#!/bin/sh
# The event catalogue's speed (docs/performance.md, "The event
# catalogue"): 1e5 events of examples/chain100-catalogue.ini (100 blocks,
# random thresholds, driver frozen) on one thread, no plots; the wall and
# processor seconds of the whole run, and the events per processor
# second.
# usage: bench_catalogue.sh SLIPCONT SOURCE_DIR WORK_DIR [EVENTS]
set -u
CLI=$1
SRC=$2
W=$3
EVENTS=${4:-100000}
mkdir -p "$W"
cd "$W" || exit 1
echo "== $(date -u '+%Y-%m-%dT%H:%M:%SZ') on $(nproc) cores; uptime: $(uptime)"
echo "== $EVENTS events of 100 blocks on one thread"
# processor seconds of the children (the run) from the shell's times
"$CLI" run "$SRC/examples/chain100-catalogue.ini" --out "$W/catalogue" \
  --threads 1 --quiet --set "task.events=$EVENTS" --set task.skip=0 \
  --set output.plot=no || exit 1
times >"$W/times.txt" # in this shell: a pipe's subshell has no children
awk -v n="$EVENTS" 'NR == 2 {
  split($1, m, "m"); u = m[1] * 60 + m[2]
  printf "  %.2f s of processor time: %.0f events per second\n", u, n / u }' \
  "$W/times.txt"
grep "events up to" "$W/catalogue/summary.txt"
