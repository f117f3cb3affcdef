# The three-block chain under velocity weakening (docs/chain.md,
# "Velocity weakening"): examples/chain3-vw-sweep.ini's period-doubling
# cascade against what tests/test_chain_vw.c computes on its own (the
# period-1 orbit by Newton at gamma = 0.2, d1 = 0.1355455871; its flip at
# gamma = 0.21446, multiplier -1): the sweep's d1 at gamma = 0.2 is the
# orbit's, period 1 holds below the flip and never above it, then periods
# 2, 4, 8, 16 and chaos.  About 3 s of processor time.
. "$(dirname "$0")/cli_common.sh"

run_within 240 run "$SRC/examples/chain3-vw-sweep.ini" --out "$TMP/sweep" \
  --quiet --set output.plot=no
expect_rc "examples/chain3-vw-sweep.ini" 0
expect_rows "chain3-vw-sweep: sweep.csv (121 values x 100 kept)" \
  "$TMP/sweep/sweep.csv" 12100

# period_on FROM TO P: every kept point with FROM <= gamma <= TO has
# period P (the values are on a grid of 0.001: 1e-9 of slack).
period_on() {
  awk -F, -v a="$1" -v b="$2" -v p="$3" '
    NR > 1 && $1 >= a - 1e-9 && $1 <= b + 1e-9 { n++; if ($4 != p) bad++ }
    END { exit !(n > 0 && bad == 0) }' "$TMP/sweep/sweep.csv"
}
check "chain3-vw-sweep: period 1 on [0.18, 0.212]" period_on 0.18 0.212 1
check "chain3-vw-sweep: period 2 on [0.216, 0.251]" period_on 0.216 0.251 2
check "chain3-vw-sweep: period 4 on [0.253, 0.263]" period_on 0.253 0.263 4
check "chain3-vw-sweep: period 8 on [0.264, 0.266]" period_on 0.264 0.266 8
check "chain3-vw-sweep: period 16 at 0.267" period_on 0.267 0.267 16
check "chain3-vw-sweep: no period up to 16 on [0.268, 0.3]" \
  period_on 0.268 0.3 0
check "chain3-vw-sweep: no period 1 past the flip (gamma 0.21446)" \
  awk -F, 'NR > 1 && $1 > 0.21446 && $4 == 1 { exit 1 }' \
  "$TMP/sweep/sweep.csv"
# the default preset's promise is 2e-9 per iterate; the orbit attracts
check "chain3-vw-sweep: d1 at gamma 0.2 is the orbit's (1e-8)" \
  awk -F, 'function abs(x) { return x < 0 ? -x : x }
    NR > 1 && abs($1 - 0.2) < 1e-9 { n++; if (abs($2 - 0.1355455871) > 1e-8) bad++ }
    END { exit !(n == 100 && bad == 0) }' "$TMP/sweep/sweep.csv"
# The summary says what runs: velocity weakening is integrated whatever
# flows reads (its default, exact), with the model's precision.
check "chain3-vw-sweep: the summary says the flows are integrated (2.0e-09)" \
  grep -q "^  (the flows are integrated numerically here: f to about 2.0e-09" \
  "$TMP/sweep/summary.txt"
run_within 60 run "$SRC/examples/chain3-vw-sweep.ini" --out "$TMP/coul" \
  --quiet --set output.plot=no --set model.friction=coulomb \
  --set task.steps=3 --set task.iterations=20 --set task.keep=5
expect_rc "chain3-vw-sweep with Coulomb friction" 0
check "chain3-vw-sweep with Coulomb friction: exact flows, no such line" \
  sh -c '! grep -q "integrated numerically" "$1"' _ "$TMP/coul/summary.txt"

echo "$NPASS passed, $NFAIL failed"
[ "$NFAIL" -eq 0 ]
