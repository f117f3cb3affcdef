# Every example scene runs and writes what its task promises: headers,
# row counts, plots (when gnuplot is present), no temporaries, and the
# known answer stated at the top of the scene.
. "$(dirname "$0")/cli_common.sh"

plotset=
if ! command -v gnuplot >/dev/null 2>&1; then plotset="--set output.plot=no"; fi
limit=
if command -v timeout >/dev/null 2>&1; then limit="timeout 240"; fi

# example NAME: run examples/NAME.ini into $TMP/NAME.
example() {
  # shellcheck disable=SC2086
  $limit "$BIN" run "$SRC/examples/$1.ini" --out "$TMP/$1" --quiet $plotset \
    >"$TMP/stdout" 2>"$TMP/stderr"
  RC=$?
  ERR=$(cat "$TMP/stderr")
  expect_rc "$1" 0
  no_temporaries "$1" "$TMP/$1"
  check "$1: summary.txt" test -s "$TMP/$1/summary.txt"
}

# png NAME FILE: rendered when gnuplot is there.
png() {
  if [ -z "$plotset" ]; then check "$1: $2 rendered" test -s "$TMP/$1/$2"; fi
}

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

example fig55-map
expect_header fig55-map "$TMP/fig55-map/map.csv" "d,f,df,itinerary,status"
expect_rows fig55-map "$TMP/fig55-map/map.csv" 2001
first=$(sed -n 2p "$TMP/fig55-map/map.csv" | cut -d, -f1)
last=$(tail -n 1 "$TMP/fig55-map/map.csv" | cut -d, -f1)
check "fig55-map: grid from -0.25 ($first) to 0.25 ($last)" \
  test "$first" = -0.25 -a "$last" = 0.25
png fig55-map map.png

# sweeps: rows = passes x steps x keep when no value is undefined
sweep_rows() {
  n=$(data_rows "$TMP/$1/sweep.csv")
  nundef=$(grep -c ',nan,-1,' "$TMP/$1/sweep.csv")
  expect=$(( ($2 - nundef) * $3 + nundef ))
  if [ "$n" -eq "$expect" ]; then pass "$1: $n rows ($nundef undefined values)"
  else fail "$1: $n rows, expected $expect"; fi
}

example symmetric-chaos
expect_header symmetric-chaos "$TMP/symmetric-chaos/sweep.csv" "v,d,period,direction"
sweep_rows symmetric-chaos 400 100
summary_has symmetric-chaos "down v from 0.025 to"
summary_has symmetric-chaos "periods seen: 0 2 4"
png symmetric-chaos sweep.png

example fig58-sweep
expect_header fig58-sweep "$TMP/fig58-sweep/sweep.csv" "alpha,d,period,direction"
sweep_rows fig58-sweep 400 150
png fig58-sweep sweep.png

example fig512-sweep
expect_header fig512-sweep "$TMP/fig512-sweep/sweep.csv" "alpha,d,period,direction"
sweep_rows fig512-sweep 800 150
summary_has fig512-sweep "up   alpha from 5 to"
check "fig512-sweep: both directions" grep -q ',down$' "$TMP/fig512-sweep/sweep.csv"
png fig512-sweep sweep.png

example logistic-sweep
expect_header logistic-sweep "$TMP/logistic-sweep/sweep.csv" "r,d,period,direction"
sweep_rows logistic-sweep 601 200
summary_has logistic-sweep "periods seen: 0 1 2 3 4"
png logistic-sweep sweep.png

finish
