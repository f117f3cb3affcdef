# End-to-end tests of the chart task through the slipcont program:
# identical results for 1 and 2 threads (both seeds), resume after a
# stop (--stop-after-rows) and after SIGINT, damaged checkpoints, a
# changed scene invalidating the checkpoint, bad charts refused before
# any work, the examples held to their known answers.
# usage: sh tests/chart_cli.sh PATH/TO/slipcont SOURCE_DIR
. "$(dirname "$0")/cli_common.sh"
cd "$TMP" || exit 1

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
for seed in fixed previous; do
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

# 4. SIGINT in the middle of the rows (the checkpoint written on the
#    signal, not the hook's): a chart of about 40 s on one thread, signalled
#    once its first periodic checkpoint is there (so inside the rows,
#    whatever the machine's load), must stop with exit 1 and a checkpoint
#    of the rows done, which a rerun resumes.  A signal that missed (the
#    chart finished) fails here.
big="--set task.x-steps=64 --set task.y-steps=1024 --set task.transient=2000"
"$BIN" run small.ini --quiet --out sig $big --threads 1 2> sig.err &
pid=$!
while [ ! -f sig/chart.checkpoint ] && kill -0 $pid 2> /dev/null; do
  sleep 0.1
done
kill -INT $pid 2> /dev/null
wait $pid
rc=$?
done_rows=$(sed -n 's/.*interrupted after \([0-9]*\) of 1024 rows.*/\1/p' sig.err)
ck_rows=$(sed -n 's/^rows //p' sig/chart.checkpoint 2> /dev/null)
if [ $rc -eq 1 ] && [ -n "$done_rows" ] && [ "$done_rows" = "$ck_rows" ]; then
  pass "SIGINT inside the rows: exit 1, checkpoint of the $done_rows rows done"
else
  fail "SIGINT inside the rows: exit $rc, checkpoint rows '$ck_rows': $(cat sig.err)"
fi
check "SIGINT: no chart.csv" test ! -e sig/chart.csv
no_temporaries "SIGINT" sig
# the rerun reads it (and is stopped by the hook before computing)
"$BIN" run small.ini --out sig $big --threads 1 --interrupt-before compute \
  2> sig2.err
check "rerun after SIGINT resumes from its $done_rows rows" \
  grep -q "resuming from .*: $done_rows of 1024 rows done" sig2.err

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

# 7. The examples, on coarse grids that keep what their opening comments
#    promise.
# ex NAME ARGS...: run examples/NAME.ini into ex-NAME.
ex() {
  name=$1
  shift
  if "$BIN" run "$SRC/examples/$name.ini" --quiet --out "ex-$name" \
    --set output.plot=no "$@" 2> "ex-$name.err"; then
    pass "example $name runs"
  else
    fail "example $name: $(cat "ex-$name.err")"
  fi
}

# chart-cubic: at mu1 = 0 the fixed point sqrt(mu2) has multiplier
# 1 - 2 mu2: period 1 for 0 < mu2 < 1 (d = sqrt(mu2) to 1e-5: the
# detector stops at period-rtol 1e-6, and with multiplier at most 0.8
# the iterate is within 1e-6 |d| / (1 - 0.8) of the fixed point), period
# 2 just above mu2 = 1; points that diverge are undefined (-1).
ex chart-cubic --set task.x-steps=13 --set task.y-steps=23
check "chart-cubic: mu1 = 0, 0 < mu2 < 1: period 1 at d = sqrt(mu2)" awk -F, '
  function abs(v) { return v < 0 ? -v : v }
  NR > 1 && $1 == 0 && $2 > 0.05 && $2 < 0.95 {
    n++; if ($3 != 1 || abs($4 - sqrt($2)) > 1e-5) { print "  " $0; bad = 1 } }
  END { exit bad || n != 9 }' ex-chart-cubic/chart.csv
check "chart-cubic: mu1 = 0, mu2 = 1.1 and 1.2: period 2" awk -F, '
  NR > 1 && $1 == 0 && ($2 == 1.1 || $2 == 1.2) { n++; if ($3 != 2) bad = 1 }
  END { exit bad || n != 2 }' ex-chart-cubic/chart.csv
check "chart-cubic: some points diverge (undefined)" \
  awk -F, 'NR > 1 && $3 == -1 { n++ } END { exit !(n > 0) }' ex-chart-cubic/chart.csv

# The bk2 charts from d0 = 0: beta = 1 is period 1 everywhere (both blocks
# slip together forever, docs/model.md); higher periods and chaos (0) as
# beta grows: on this 20 x 20 grid at least half the points of
# beta < 5.5 have period 1 or 2 and at most 30 % above, where chaos is
# more common than below.
grows() {
  check "$1: beta = 1 is period 1 everywhere" awk -F, '
    NR > 1 && $2 == 1 { n++; if ($3 != 1) bad = 1 } END { exit bad || n != 20 }' \
    "ex-$1/chart.csv"
  check "$1: low periods at small beta, higher and chaos as beta grows" awk -F, '
    NR > 1 { lo = $2 < 5.5; n[lo]++; if ($3 == 1 || $3 == 2) low[lo]++
             if ($3 == 0) chaos[lo]++ }
    END { exit !(low[1] >= 0.5 * n[1] && low[0] <= 0.3 * n[0] &&
                 chaos[0] / n[0] > chaos[1] / n[1]) }' "ex-$1/chart.csv"
}
ex chart-alpha-beta --set task.x-steps=20 --set task.y-steps=20
grows chart-alpha-beta
ex chart-alpha-beta-zoom --set task.x-steps=20 --set task.y-steps=20
grows chart-alpha-beta-zoom
ex chart-fig57b-window --set task.x-steps=20 --set task.y-steps=5
check "chart-fig57b-window: beta = 1 is period 1 everywhere" awk -F, '
  NR > 1 && $2 == 1 { n++; if ($3 != 1) bad = 1 } END { exit bad || n != 20 }' \
  ex-chart-fig57b-window/chart.csv

# chart-alpha-v at alpha = 2.9 (V every 0.00025): period 2 from V = 0.025
# down to the flip at 0.0206852 (located by examples/branch-symmetric.ini),
# period 4 below it down to the next flip at 0.0195011, chaos (0) with
# windows below, and period 2 again (single-block slips) for V <= 0.017.
ex chart-alpha-v --set task.x-steps=11 --set task.y-steps=41
alpha_v() { # alpha_v WHAT VLO VHI CONDITION-ON-p: every row at alpha 2.9
  check "chart-alpha-v: alpha = 2.9, V in [$2, $3]: $1" awk -F, -v lo="$2" -v hi="$3" '
    function abs(v) { return v < 0 ? -v : v }
    NR > 1 && abs($1 - 2.9) < 1e-9 && $2 >= lo - 1e-12 && $2 <= hi + 1e-12 {
      n++; p = $3; if (!('"$4"')) { print "  " $0; bad = 1 } }
    END { exit bad || n == 0 }' ex-chart-alpha-v/chart.csv
}
alpha_v "period 2" 0.02075 0.025 "p == 2"
alpha_v "period 4" 0.01975 0.0205 "p == 4"
check "chart-alpha-v: alpha = 2.9: chaos below the cascade" awk -F, '
  function abs(v) { return v < 0 ? -v : v }
  NR > 1 && abs($1 - 2.9) < 1e-9 && $2 > 0.0175 && $2 < 0.0195 && $3 == 0 { n++ }
  END { exit !(n >= 3) }' ex-chart-alpha-v/chart.csv
alpha_v "period 2" 0.015 0.017 "p == 2"

finish
