# The fixed-point task over a range of periods (period = m1..m2): every
# orbit once, at its minimal period, with a count per period; checked on
# the logistic map x -> r x (1 - x) at r = 3.835 against closed forms and
# against one run per period.
. "$(dirname "$0")/cli_common.sh"

cat >"$TMP/fp.ini" <<'INI'
[model]
name = logistic
r = 3.835
[task]
kind = fixed-point
period = 1..3
from = 0
to = 1
steps = 1001
[output]
plot = no
INI
run_sc run "$TMP/fp.ini" --out "$TMP/range" --quiet
expect_rc "period = 1..3" 0
expect_header "period = 1..3" "$TMP/range/periods.csv" \
  "period,orbits,stable,unstable,families,lower_period_roots"
# period 1: 0 and 1 - 1/r; period 2: one orbit, the roots of
# r^2 x^2 - r (r + 1) x + r + 1 = 0; period 3: the stable and unstable
# orbits born at r = 1 + sqrt(8) = 3.828.
counts=$(awk -F, 'NR > 1 {printf "%s:%s:%s ", $1, $2, $3}' "$TMP/range/periods.csv")
check "period = 1..3: orbits (stable) per period 1:2:0 2:1:0 3:2:1 (got $counts)" \
  test "$counts" = "1:2:0 2:1:0 3:2:1 "
expect_rows "period = 1..3: orbits.csv" "$TMP/range/orbits.csv" 5
# Closed forms to 1e-12 (the shooting tolerance is far below).
check "period 1: x = 0 and 1 - 1/r, multipliers r and 2 - r" awk -F, '
  function abs(x) { return x < 0 ? -x : x }
  BEGIN { r = 3.835; n = 0 }
  $1 == 1 { n++; x = $4 + 0; m = $2 + 0
    if (abs(x) < 1e-12 && abs(m - r) < 1e-12) z = 1
    if (abs(x - (1 - 1 / r)) < 1e-12 && abs(m - (2 - r)) < 1e-12) f = 1 }
  END { exit !(n == 2 && z && f) }' "$TMP/range/orbits.csv"
check "period 2: the closed-form pair, multiplier 4 + 2r - r^2" awk -F, '
  function abs(x) { return x < 0 ? -x : x }
  BEGIN { r = 3.835; s = sqrt((r + 1) * (r - 3))
    lo = (r + 1 - s) / (2 * r); hi = (r + 1 + s) / (2 * r) }
  $1 == 2 { split($4, d, ";"); a = d[1] + 0; b = d[2] + 0
    if (a > b) { t = a; a = b; b = t }
    ok = abs(a - lo) < 1e-12 && abs(b - hi) < 1e-12 &&
         abs($2 - (4 + 2 * r - r * r)) < 1e-10 }
  END { exit !ok }' "$TMP/range/orbits.csv"
check "summary: a count per period" grep -q "^  period 3: 2 orbits (1 stable), 0 neutral families" "$TMP/range/summary.txt"

# Over 1..6 the rows are those of six runs of one period each: no orbit
# is listed twice, none at a multiple of its period.
sed -i 's/^period = .*/period = 1..6/' "$TMP/fp.ini"
run_sc run "$TMP/fp.ini" --out "$TMP/r6" --quiet
expect_rc "period = 1..6" 0
: >"$TMP/each.csv"
for m in 1 2 3 4 5 6; do
  run_sc run "$TMP/fp.ini" --out "$TMP/p$m" --quiet --set task.period=$m
  tail -n +2 "$TMP/p$m/orbits.csv" >>"$TMP/each.csv"
done
tail -n +2 "$TMP/r6/orbits.csv" >"$TMP/range6.csv"
check "period = 1..6: the rows of six one-period runs" cmp -s "$TMP/each.csv" "$TMP/range6.csv"
n6=$(awk -F, 'NR > 1 {n += $2 + $5} END {print n}' "$TMP/r6/periods.csv")
check "period = 1..6: periods.csv counts the rows ($n6)" test "$n6" -eq "$(data_rows "$TMP/r6/orbits.csv")"

# A single period still writes the graph of f^m; a range its count file.
run_sc run "$TMP/fp.ini" --out "$TMP/one" --quiet --set task.period=3
expect_rc "period = 3" 0
check "period = 3: fixed-point-map.csv" test -s "$TMP/one/fixed-point-map.csv"
check "period = 3: periods.csv has one row" test "$(data_rows "$TMP/one/periods.csv")" -eq 1

# Bad ranges are refused by check.
for bad in 4..2 0 0..3 ..3 1.. 1..100001 1..2..3 x; do
  run_sc check "$TMP/fp.ini" --set task.period=$bad
  expect_rc "period = $bad" 2
  expect_err "period = $bad" "[task] period = $bad (valid: m in [1, 100000], or m1..m2"
done
finish
