# Every example scene runs and writes what its task promises: headers,
# row counts, plots (when gnuplot is present), no temporaries, and the
# known answer stated at the top of the scene.
. "$(dirname "$0")/cli_common.sh"


# summary_has NAME TEXT
summary_has() {
  if grep -qF "$2" "$TMP/$1/summary.txt"; then pass "$1: summary says '$2'"
  else fail "$1: summary lacks '$2'"; fi
}

for name in fig54-moving fig54-frozen; do
  example $name
  expect_header $name "$TMP/$name/orbit.csv" "k,d,itinerary"
  expect_rows $name "$TMP/$name/orbit.csv" 201
  expect_header $name "$TMP/$name/trajectory.csv" "tau,y1,y2,u1,u2,mode"
  n=$(data_rows "$TMP/$name/trajectory.csv")
  check "$name: trajectory has samples ($n)" test "$n" -gt 100
  summary_has $name "period of the last 100 iterates: 2"
  png $name orbit.png
  png $name phase.png
  png $name velocity.png
done
# The velocities the plots show (trajectory.csv, mode 0: global stick, 1
# or 2: that block slips alone, 3: both): in a global stick phase both
# blocks move with the driver, V = 0.025; during a slip of one block the
# stuck one stays at V_s: 0 with the driver frozen, V with it moving.
# These are exact (the stuck block's velocity is set, not computed).
check "fig54-frozen: stuck block at rest in a slip, both at V in a GSP" awk -F, '
  NR > 1 && $6 == 0 && ($4 != 0.025 || $5 != 0.025) { print "  " $0; bad = 1 }
  NR > 1 && $6 == 1 && $5 != 0 { print "  " $0; bad = 1 }
  NR > 1 && $6 == 2 && $4 != 0 { print "  " $0; bad = 1 }
  NR > 1 { n[$6]++ } END { exit bad || !n[0] || !n[1] || !n[2] }' \
  "$TMP/fig54-frozen/trajectory.csv"
check "fig54-moving: stuck block at V in a slip, both at V in a GSP" awk -F, '
  NR > 1 && $6 == 0 && ($4 != 0.025 || $5 != 0.025) { print "  " $0; bad = 1 }
  NR > 1 && $6 == 1 && $5 != 0.025 { print "  " $0; bad = 1 }
  NR > 1 && $6 == 2 && $4 != 0.025 { print "  " $0; bad = 1 }
  NR > 1 { n[$6]++ } END { exit bad || !n[0] || !n[1] || !n[2] }' \
  "$TMP/fig54-moving/trajectory.csv"

example fig55-map
expect_header fig55-map "$TMP/fig55-map/map.csv" "d,f,df,itinerary,status"
expect_rows fig55-map "$TMP/fig55-map/map.csv" 2001
first=$(sed -n 2p "$TMP/fig55-map/map.csv" | cut -d, -f1)
last=$(tail -n 1 "$TMP/fig55-map/map.csv" | cut -d, -f1)
check "fig55-map: grid from -0.25 ($first) to 0.25 ($last)" \
  test "$first" = -0.25 -a "$last" = 0.25
png fig55-map map.png
# f' = 1 exactly where one block slips alone (itinerary 1 or 2: the map
# is a translation there, docs/model.md).
check "fig55-map: f' = 1 exactly on the itineraries 1 and 2" awk -F, '
  NR > 1 && ($4 == "1" || $4 == "2") { n++; if ($3 != 1) { print "  " $0; bad = 1 } }
  END { exit bad || n < 100 }' "$TMP/fig55-map/map.csv"
# Continuous at d* = 0: f(0) = 0 and f(d) = O(sqrt|d|) on both sides; f'
# grows like |d|^(-1/2): f = a sqrt|d| + b |d| + ..., so the log-log
# slope of |f'| between |d| = 2.5e-4 and 1e-3 is -1/2 + O(sqrt|d|)
# (measured -0.488); 0.05 is that O(sqrt 1e-3) with a factor 1.5.
check "fig55-map: continuous at d* = 0" awk -F, '
  function abs(v) { return v < 0 ? -v : v }
  NR > 1 && $1 == 0 { z = 1; if ($2 != 0) bad = 1 }
  NR > 1 && $1 != 0 && abs($1) < 1.1e-3 { n++; if (abs($2) > 0.5 * sqrt(abs($1))) bad = 1 }
  END { exit bad || !z || n != 8 }' "$TMP/fig55-map/map.csv"
check "fig55-map: |f'| grows like |d|^(-1/2) on both sides of d*" awk -F, '
  function abs(v) { return v < 0 ? -v : v }
  function near(a, b) { return abs(a - b) < 1e-12 }
  NR > 1 { for (s = -1; s <= 1; s += 2) {
    if (near($1, s * 2.5e-4)) a[s] = abs($3); if (near($1, s * 1e-3)) b[s] = abs($3) } }
  END { for (s = -1; s <= 1; s += 2) {
    k = log(b[s] / a[s]) / log(4); printf "  side %d: slope %.4f\n", s, k
    if (!(k > -0.55 && k < -0.45)) bad = 1 } exit bad }' "$TMP/fig55-map/map.csv"

# sweeps: rows = passes x steps x keep when no value is undefined
sweep_rows() {
  n=$(data_rows "$TMP/$1/sweep.csv")
  nundef=$(grep -c ',nan,-1,' "$TMP/$1/sweep.csv")
  expect=$(( ($2 - nundef) * $3 + nundef ))
  if [ "$n" -eq "$expect" ]; then pass "$1: $n rows ($nundef undefined values)"
  else fail "$1: $n rows, expected $expect"; fi
}

# periods NAME DIRECTION LO HI: the distinct periods of the rows of
# sweep.csv with the parameter in [LO, HI] in that pass, sorted.
periods() {
  awk -F, -v d="$2" -v lo="$3" -v hi="$4" \
    'NR > 1 && $4 == d && $1 >= lo && $1 <= hi {print $3}' \
    "$TMP/$1/sweep.csv" | sort -n -u | tr '\n' ' ' | sed 's/ $//'
}

# expect_periods NAME DIRECTION LO HI EXPECTED
expect_periods() {
  got=$(periods "$1" "$2" "$3" "$4")
  if [ "$got" = "$5" ]; then pass "$1: $2 pass on [$3, $4]: period $5"
  else fail "$1: $2 pass on [$3, $4]: periods '$got', expected '$5'"; fi
}

example symmetric-chaos
expect_header symmetric-chaos "$TMP/symmetric-chaos/sweep.csv" "v,d,period,direction"
sweep_rows symmetric-chaos 400 100
summary_has symmetric-chaos "down v from 0.025 to"
summary_has symmetric-chaos "periods seen: -2 0 2 4"
# Not settled (-2) exactly where the orbit doubles: the first flip a
# little below V = 0.021, the second near 0.0195.
summary_has symmetric-chaos "down v from 0.02078947368 to 0.02068922306 (5 values): period -2"
expect_periods symmetric-chaos down 0.0236 0.025 2
expect_periods symmetric-chaos down 0.0197 0.0205 4
expect_periods symmetric-chaos down 0.015 0.0165 2
png symmetric-chaos sweep.png

example fig58-sweep
expect_header fig58-sweep "$TMP/fig58-sweep/sweep.csv" "alpha,d,period,direction"
sweep_rows fig58-sweep 400 150
# the flip cascade between 3 and 3.2, and the period-6 window after it
expect_periods fig58-sweep up 3.0 3.04 2
expect_periods fig58-sweep up 3.07 3.14 4
expect_periods fig58-sweep up 3.23 3.38 6
# the stable period-4 orbit is lost at its grazing, alpha = 3.8613904131
# (examples/branch-fig58.ini): period 4 up to it, another just after it
expect_periods fig58-sweep up 3.80 3.8613 4
check "fig58-sweep: the period-4 orbit is gone just above its grazing" awk -F, '
  NR > 1 && $1 > 3.8613904131 && !seen { seen = 1; p = $3 }
  END { exit !(seen && p != 4) }' "$TMP/fig58-sweep/sweep.csv"
png fig58-sweep sweep.png

example fig512-sweep
expect_header fig512-sweep "$TMP/fig512-sweep/sweep.csv" "alpha,d,period,direction"
sweep_rows fig512-sweep 800 150
summary_has fig512-sweep "up   alpha from 5 to"
check "fig512-sweep: both directions" grep -q ',down$' "$TMP/fig512-sweep/sweep.csv"
# period 2 at alpha = 5, period 3 at the top; between 5.66 and 5.74 the
# passes disagree (hysteresis): the period-3 orbit coexists
expect_periods fig512-sweep up 5 5.6 2
expect_periods fig512-sweep down 5 5.6 2
expect_periods fig512-sweep up 5.8 6.5 3
expect_periods fig512-sweep down 5.66 6.5 3
expect_periods fig512-sweep up 5.66 5.74 1
png fig512-sweep sweep.png

example logistic-sweep
expect_header logistic-sweep "$TMP/logistic-sweep/sweep.csv" "r,d,period,direction"
sweep_rows logistic-sweep 601 200
summary_has logistic-sweep "periods seen: -2 0 1 2 3 4"
# Not settled (-2) only at the flips r = 3, 1 + sqrt(6) = 3.4495, 3.5441,
# 3.5644 (200 iterates from 0.3 are too few there), never in chaos.
summary_has logistic-sweep "up   r from 2.99 to 3.002 (7 values): period -2"
summary_has logistic-sweep "up   r from 3.446 to 3.45 (3 values): period -2"
check "logistic-sweep: 4 runs not settled, at the 4 flips" \
  test "$(grep -c 'period -2$' "$TMP/logistic-sweep/summary.txt")" -eq 4
# exact answers: flips at r = 3 and 1 + sqrt(6) = 3.4495, the period-3
# window from 1 + sqrt(8) = 3.8284
expect_periods logistic-sweep up 2.8 2.95 1
expect_periods logistic-sweep up 3.05 3.43 2
expect_periods logistic-sweep up 3.46 3.54 4
# period 8 between the flips at 3.5441 and 3.5644 (branch-logistic.ini
# locates them), chaos past the cascade's accumulation at 3.5699 up to
# the period-6 window near 3.6275
expect_periods logistic-sweep up 3.546 3.562 8
expect_periods logistic-sweep up 3.57 3.626 0
expect_periods logistic-sweep up 3.83 3.84 3
png logistic-sweep sweep.png

finish
