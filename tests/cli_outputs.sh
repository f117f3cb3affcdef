# Outputs of the program on the logistic map (exact, fast): CSV headers
# and row counts, grid endpoints, --set, atomic writing, exit status 1 for
# a failed computation, gnuplot missing, thread-count independence.
. "$(dirname "$0")/cli_common.sh"

cat >"$TMP/sweep.ini" <<'INI'
[model]
name = logistic
[task]
kind = sweep
parameter = r
from = 2.5
to = 4
steps = 31
iterations = 300
keep = 40
d0 = 0.3
direction = both
[output]
plot = no
INI

# A sweep, then the same with overrides.
run_sc run "$TMP/sweep.ini" --out "$TMP/s1"
expect_rc "sweep" 0
check "run prints nothing on stdout" test -z "$OUT"
expect_header "sweep" "$TMP/s1/sweep.csv" "r,d,period,direction"
expect_rows "sweep: 2 passes x 31 values x 40 kept" "$TMP/s1/sweep.csv" 2480
check "sweep: summary.txt" test -s "$TMP/s1/summary.txt"
check "sweep: sweep.gp written with plot = no" test -s "$TMP/s1/sweep.gp"
check "sweep: no png with plot = no" test ! -e "$TMP/s1/sweep.png"
no_temporaries "sweep" "$TMP/s1"
row2=$(sed -n 2p "$TMP/s1/sweep.csv")
case $row2 in 2.5,*,1,up) pass "sweep: up pass starts at r = 2.5, period 1" ;;
*) fail "sweep: first row '$row2'" ;; esac
last=$(tail -n 1 "$TMP/s1/sweep.csv")
case $last in 2.5,*,down) pass "sweep: down pass ends at r = 2.5" ;;
*) fail "sweep: last row '$last'" ;; esac
mid=$(grep -c '^4,' "$TMP/s1/sweep.csv")
check "sweep: r = 4 exactly, once per pass ($mid rows)" test "$mid" -eq 80
grep -q 'periods seen: -2 0 1 2' "$TMP/s1/summary.txt" &&
  pass "sweep: summary lists the periods seen" ||
  fail "sweep: summary lacks 'periods seen: -2 0 1 2 ...'"
# r = 3 is the flip itself (multiplier -1: the orbit converges too slowly
# to settle): not settled on both passes, like r = 3.45 next to 1 + sqrt 6.
check "sweep: r = 3 not settled on both passes" \
  test "$(grep -c 'r from 3 to 3 (1 values): period -2' "$TMP/s1/summary.txt")" -eq 2

run_sc run "$TMP/sweep.ini" --out "$TMP/s2" --set task.steps=1 \
  --set task.direction=up --set task.keep=5 --quiet
expect_rc "sweep with --set" 0
check "--quiet: nothing on stderr" test -z "$ERR"
expect_rows "steps = 1 via --set: from only, 5 kept" "$TMP/s2/sweep.csv" 5
check "steps = 1: every row at r = from" test "$(grep -c '^2.5,' "$TMP/s2/sweep.csv")" -eq 5
grep -q 'steps *= 1 *; --set task.steps=1' "$TMP/s2/summary.txt" &&
  pass "summary says where steps was set" ||
  fail "summary lacks the origin of steps"

# Results do not depend on the thread count (seed = fixed).
run_sc run "$TMP/sweep.ini" --out "$TMP/t1" --threads 1 --quiet
run_sc run "$TMP/sweep.ini" --out "$TMP/t3" --threads 3 --quiet
check "sweep identical for 1 and 3 threads" cmp -s "$TMP/t1/sweep.csv" "$TMP/t3/sweep.csv"

# Undefined points: orbits from x = 1.5 leave the doubles: one row each
# with d = nan, period -1.
run_sc run "$TMP/sweep.ini" --out "$TMP/s3" --set task.d0=1.5 --set task.steps=4 --quiet
expect_rc "sweep with undefined points" 0
expect_rows "undefined: one row per value and pass" "$TMP/s3/sweep.csv" 8
check "undefined rows: nan, -1" test "$(grep -c ',nan,-1,' "$TMP/s3/sweep.csv")" -eq 8

# The map task: grid endpoints exactly, header, status.
cat >"$TMP/map.ini" <<'INI'
[model]
name = logistic
r = 3.7
[task]
kind = map
iterate = 2
from = 0
to = 1
steps = 7
[output]
plot = no
INI
run_sc run "$TMP/map.ini" --out "$TMP/m"
expect_rc "map" 0
expect_header "map" "$TMP/m/map.csv" "d,f,df,itinerary,status"
expect_rows "map: 7 points" "$TMP/m/map.csv" 7
first=$(sed -n 2p "$TMP/m/map.csv")
case $first in 0,0,*,ok) pass "map: first point d = 0, f = 0, ok" ;;
*) fail "map: first row '$first'" ;; esac
last=$(tail -n 1 "$TMP/m/map.csv")
case $last in 1,0,*,ok) pass "map: last point exactly d = 1" ;;
*) fail "map: last row '$last'" ;; esac
third=$(sed -n 4p "$TMP/m/map.csv" | cut -d, -f1)
check "map: d = 2/6 as from + 2 (to - from)/6 ($third)" test "$third" = 0.33333333333333331
run_sc run "$TMP/map.ini" --out "$TMP/m1" --set task.steps=1
expect_rows "map: steps = 1" "$TMP/m1/map.csv" 1

# The orbit task, and a failed computation: exit status 1 after writing.
cat >"$TMP/orbit.ini" <<'INI'
[model]
name = logistic
r = 3.2
[task]
kind = orbit
d0 = 0.3
iterations = 100
[output]
plot = no
INI
run_sc run "$TMP/orbit.ini" --out "$TMP/o"
expect_rc "orbit" 0
expect_header "orbit" "$TMP/o/orbit.csv" "k,d,itinerary"
expect_rows "orbit: iterations + 1 rows" "$TMP/o/orbit.csv" 101
grep -q 'period of the last 50 iterates: 2' "$TMP/o/summary.txt" &&
  pass "orbit: period 2 at r = 3.2" || fail "orbit: summary lacks period 2"
run_sc run "$TMP/orbit.ini" --out "$TMP/o2" --set task.d0=1.5 --set task.iterations=2000
expect_rc "orbit leaving the doubles" 1
expect_err "orbit leaving the doubles" "is not finite"
check "orbit.csv written before failing" test -s "$TMP/o2/orbit.csv"
check "undefined row marked" grep -q ',undefined$' "$TMP/o2/orbit.csv"
no_temporaries "failed orbit" "$TMP/o2"

# gnuplot missing: data written, a clear message, exit status 1.
run_sc run "$TMP/orbit.ini" --out "$TMP/np" --set output.plot=yes
if command -v gnuplot >/dev/null 2>&1; then
  expect_rc "orbit with gnuplot" 0
  check "orbit.png rendered" test -s "$TMP/np/orbit.png"
  no_temporaries "rendered plot" "$TMP/np"
  check "no gnuplot log left" test ! -e "$TMP/np/orbit.gp.log"
fi
env PATH=/nonexistent "$BIN" run "$TMP/orbit.ini" --out "$TMP/np2" \
  --set output.plot=yes >"$TMP/stdout" 2>"$TMP/stderr"
RC=$?
ERR=$(cat "$TMP/stderr")
expect_rc "gnuplot missing" 1
expect_err "gnuplot missing" "gnuplot not found"
check "gnuplot missing: data still written" test -s "$TMP/np2/orbit.csv"
check "gnuplot missing: script still written" test -s "$TMP/np2/orbit.gp"

# An interrupted run stops cleanly: exit status 1, no temporaries, no
# half-written result.  The SIGINT comes from --interrupt-before write,
# after the sweep is computed and before sweep.csv is opened (signals
# inside a step: cli_signals.sh).
run_sc run "$TMP/sweep.ini" --out "$TMP/int" --set task.direction=up \
  --interrupt-before write
expect_rc "interrupted sweep" 1
expect_err "interrupted sweep" ": interrupted"
no_temporaries "interrupted sweep" "$TMP/int"
check "interrupted sweep: no sweep.csv" test ! -e "$TMP/int/sweep.csv"
run_sc run "$TMP/sweep.ini" --out "$TMP/int" --set task.direction=up
expect_rc "the same sweep, not interrupted" 0
check "the same sweep, not interrupted: sweep.csv" test -s "$TMP/int/sweep.csv"

finish
