#!/bin/sh
# End-to-end tests of the chart task through the slipcont program:
# identical results for 1 and 2 threads (both seeds), resume after a
# stop (--stop-after-rows) and after SIGINT, damaged checkpoints, a changed scene invalidating the
# checkpoint, bad charts refused before any work, the examples.
# usage: chart_cli.sh SLIPCONT SOURCE_DIR WORK_DIR
set -u
BIN=$1
SRC=$2
W=$3
rm -rf "$W"
mkdir -p "$W"
cd "$W" || exit 1
fails=0
pass() { echo "PASS $*"; }
fail() { echo "FAIL $*"; fails=$((fails + 1)); }

# A small bk2 chart: driver frozen, alpha x beta, periods 1..16 and chaos.
cat > small.ini <<'INI'
[model]
name = bk2
driver = frozen
phi = 1.25
[task]
kind = chart
x = alpha
x-from = 2.5
x-to = 7.5
x-steps = 16
y = beta
y-from = 1.5
y-to = 6
y-steps = 12
d0 = 0
transient = 600
[output]
plot = no
INI

run() { # run OUT [args...]: quiet run into folder OUT
  out=$1
  shift
  "$BIN" run small.ini --quiet --out "$out" "$@"
}

# 1. Threads, both seeds.
for seed in fixed neighbour; do
  run t1-$seed --threads 1 --set task.seed=$seed &&
    run t2-$seed --threads 2 --set task.seed=$seed ||
    fail "runs with seed $seed"
  if cmp -s t1-$seed/chart.csv t2-$seed/chart.csv; then
    pass "seed $seed: 1 and 2 threads give identical chart.csv"
  else
    fail "seed $seed: chart.csv differs between 1 and 2 threads"
  fi
done
head -1 t1-fixed/chart.csv | grep -qx 'alpha,beta,period,d,iterations' &&
  pass "csv header names the parameters" || fail "csv header: $(head -1 t1-fixed/chart.csv)"
n=$(($(wc -l < t1-fixed/chart.csv) - 1))
[ "$n" -eq $((16 * 12)) ] && pass "csv has 16 x 12 rows" || fail "csv rows $n"
grep -q '^7.5,6,' t1-fixed/chart.csv && pass "last grid point is exactly (7.5, 6)" ||
  fail "last grid point"

# 2. Stop after 5 rows (the hook writes a checkpoint as a kill would
#    between blocks), then resume.
run stop --threads 2 --stop-after-rows 5 2> stop.err
rc=$?
[ $rc -eq 1 ] && pass "stopped run exits 1" || fail "stopped run exit $rc"
[ -f stop/chart.checkpoint ] && [ ! -f stop/chart.csv ] &&
  pass "stopped run leaves a checkpoint and no chart.csv" ||
  fail "after the stop: $(ls stop)"
"$BIN" run small.ini --out stop --threads 1 2> resume.err
grep -q 'resuming from .*5 of 12 rows' resume.err &&
  pass "rerun resumes after 5 rows" || fail "no resume note: $(cat resume.err)"
cmp -s stop/chart.csv t1-fixed/chart.csv &&
  pass "resumed chart identical to an uninterrupted one" ||
  fail "resumed chart differs"
[ ! -f stop/chart.checkpoint ] && pass "checkpoint removed when done" ||
  fail "checkpoint left behind"

# 2b. A damaged checkpoint is never trusted: each of these starts over
#     with a note saying why, and the chart comes out as an uninterrupted
#     one (before version 2, a period out of range overran the heap).
corrupt() { # corrupt NAME: stop after 5 rows, damage the checkpoint by NAME
  run "ck-$1" --stop-after-rows 5 2> /dev/null
  ck="ck-$1/chart.checkpoint"
  size=$(wc -c < "$ck")
  case $1 in
  period) # the last point's period set out of range (its top byte)
    printf '\177' | dd of="$ck" bs=1 seek=$((size - 5)) conv=notrunc 2> /dev/null ;;
  byte) # one byte of the last point's d changed: only the checksum tells
    printf '\001' | dd of="$ck" bs=1 seek=$((size - 13)) conv=notrunc 2> /dev/null ;;
  trunc) # the last point cut short
    head -c $((size - 3)) "$ck" > "$ck.t" && mv "$ck.t" "$ck" ;;
  rows) # a row count beyond the chart's
    sed '3s/^rows .*/rows 99999999/' "$ck" > "$ck.t" && mv "$ck.t" "$ck" ;;
  negrows)
    sed '3s/^rows .*/rows -3/' "$ck" > "$ck.t" && mv "$ck.t" "$ck" ;;
  cols) # a checkpoint of another width
    sed '4s/^columns .*/columns 17/' "$ck" > "$ck.t" && mv "$ck.t" "$ck" ;;
  version) # an old or foreign file
    sed '1s/checkpoint 2/checkpoint 1/' "$ck" > "$ck.t" && mv "$ck.t" "$ck" ;;
  esac
  "$BIN" run small.ini --out "ck-$1" 2> "ck-$1.err"
  rc=$?
  if [ $rc -eq 0 ] && grep -q "$2" "ck-$1.err" &&
     ! grep -q resuming "ck-$1.err" && cmp -s "ck-$1/chart.csv" t1-fixed/chart.csv; then
    pass "checkpoint damaged ($1): '$2', started over, same chart"
  else
    fail "checkpoint damaged ($1): exit $rc: $(cat "ck-$1.err")"
  fi
}
corrupt period 'corrupt (point 79: period 21'
corrupt byte 'corrupt (checksum or length differs): starting over'
corrupt trunc 'is truncated: starting over'
corrupt rows 'corrupt (rows 99999999 of 12'
corrupt negrows 'corrupt (rows -3 of 12'
corrupt cols 'columns 17 of 16'
corrupt version 'not a chart checkpoint of this version'

# 3. A changed scene invalidates the checkpoint, with a message.
run change --stop-after-rows 4 2> /dev/null
"$BIN" run small.ini --out change --set task.transient=500 2> change.err
grep -q 'another scene (task.transient = 600 -> task.transient = 500)' \
  change.err && pass "scene change noted" || fail "no note: $(cat change.err)"
grep -q resuming change.err && fail "resumed a changed scene" ||
  pass "changed scene starts over"
run ref500 --set task.transient=500
cmp -s change/chart.csv ref500/chart.csv &&
  pass "restarted chart identical to a fresh one" || fail "restarted differs"

# 4. SIGINT: a chart of about 1.5 s on one thread, interrupted after
#    1 s (exit 1, checkpoint of the rows done), then rerun.
big="--set task.x-steps=40 --set task.y-steps=60 --set task.transient=2000"
run sigref $big --threads 2
"$BIN" run small.ini --quiet --out sig $big --threads 1 2> sig.err &
pid=$!
sleep 1
kill -INT $pid 2> /dev/null
wait $pid
rc=$?
if [ $rc -eq 1 ] && grep -q interrupted sig.err && [ -f sig/chart.checkpoint ]; then
  pass "SIGINT: exit 1, checkpoint saved: $(cat sig.err)"
else
  echo "  (not interrupted in time: exit $rc; $(cat sig.err))"
fi
"$BIN" run small.ini --out sig $big --threads 2 2> sig2.err
cat sig2.err
cmp -s sig/chart.csv sigref/chart.csv &&
  pass "chart after SIGINT and rerun identical" ||
  fail "chart after SIGINT differs"

# 5. Progress: a bar on a terminal (script(1) gives one), none with
#    --quiet, none when stderr is a file.
"$BIN" run small.ini --out nobar 2> nobar.err
grep -q 'points/s' nobar.err && fail "progress bar written to a file" ||
  pass "no progress bar when stderr is not a terminal"
if command -v script > /dev/null 2>&1; then
  script -qc "'$BIN' run small.ini --out bar" /dev/null > bar.out 2>&1
  grep -q '100.0% 192/192 points, .* points/s, .* spent, 00:00 left' bar.out &&
    pass "progress bar with rate and time left on a terminal" ||
    fail "no progress bar on a terminal: $(tr '\r' '\n' < bar.out | tail -3)"
  script -qc "'$BIN' run small.ini --out bar --quiet" /dev/null > quiet.out 2>&1
  grep -q 'points/s' quiet.out && fail "progress bar despite --quiet" ||
    pass "no progress bar with --quiet"
fi

# 6. Bad charts are refused before any work (exit 2, nothing written).
bad() { # bad NEEDLE --set ...
  needle=$1
  shift
  "$BIN" run small.ini --quiet --out bad "$@" 2> bad.err
  rc=$?
  if [ $rc -eq 2 ] && grep -q -- "$needle" bad.err && [ ! -e bad/chart.csv ]; then
    pass "refused ($*): $(cat bad.err)"
  else
    fail "not refused as expected ($*): exit $rc: $(cat bad.err)"
  fi
}
bad "x-steps" --set task.x-steps=0
bad "y-steps" --set task.y-steps=-4
bad "x and y are both 'alpha'" --set task.y=alpha
bad "delta" --set task.x=delta
bad "grid points" --set task.x-steps=20000 --set task.y-steps=20000
bad "alpha" --set task.x-from=-1
bad "seed" --set task.seed=random

# 7. The examples, on a coarse grid.
for ex in "$SRC"/examples/chart-*.ini; do
  name=$(basename "$ex" .ini)
  if "$BIN" run "$ex" --quiet --out "ex-$name" --set task.x-steps=6 \
    --set task.y-steps=5 --set output.plot=no; then
    pass "example $name runs"
  else
    fail "example $name"
  fi
done

echo "$fails failed"
[ $fails -eq 0 ]
