# User points (UZ): `marks` on a branch or a curve records the orbit where
# the parameter (a curve's x) takes each value, located by Newton with it
# fixed; the rows are exact on maps with closed forms, checked by
# `check`, and usable as starts.
# Usage: sh tests/user_points.sh PATH/TO/slipcont SOURCE_DIR
. "$(dirname "$0")/cli_common.sh"

# The logistic map's period-1 branch is x = 1 - 1/r; its period-2 orbit
# (r > 3) is x = (r + 1 -+ sqrt((r - 3)(r + 1))) / (2 r); its period-4
# orbit at r = 3.5 has no short closed form (only checked to exist).
run_sc run "$SRC/examples/branch-logistic.ini" --out "$TMP/b" --quiet \
  --set output.plot=no --set "task.marks=2.9 3.2 3.5"
expect_rc "logistic branch with marks" 0
P="$TMP/b/points.csv"
n=$(grep -c '^UZ,' "$P")
check "logistic: 6 user points (2.9: period 1; 3.2: 1, 2; 3.5: 1, 2, 4) - $n" \
  test "$n" -eq 6
# label,parameter,value,d,period,multiplier,residual,error,method,...
awk -F, '$1 == "UZ" {
  r = $3; d = $4; m = $5; res = $7
  if (m == 1) { e = d - (1 - 1 / r); if (e < 0) e = -e }
  else if (m == 2) {
    s = sqrt((r - 3) * (r + 1)); a = (r + 1 + s) / (2 * r); b = (r + 1 - s) / (2 * r)
    e = d - a; if (e < 0) e = -e; f = d - b; if (f < 0) f = -f; if (f < e) e = f
  } else e = 0
  # 1e-14: a few roundings of numbers below 1 (Newton at the parameter
  # fixed ends at the map evaluation'"'"'s rounding)
  ok = e <= 1e-14 && res <= 1e-14 && $9 == "newton"
  printf "%s UZ r = %s period %d: d = %s, off the closed form by %.3g, residual %s\n", ok ? "PASS" : "FAIL", r, m, d, e, res
  bad += !ok
} END { exit bad > 0 }' "$P" && NPASS=$((NPASS + 1)) || NFAIL=$((NFAIL + 1))
check "logistic: the summary lists UZ" grep -q "by label:.* UZ 6" "$TMP/b/summary.txt"

# A UZ row starts a branch like any other row: the period-2 orbit at 3.2.
row=$(awk -F, '$1 == "UZ" && $5 == 2 { print NR - 1; exit }' "$P")
run_sc run "$SRC/examples/branch-logistic.ini" --out "$TMP/b2" --quiet \
  --set output.plot=no --set task.from=3.1 --set task.to=3.3 \
  --set "task.starts=$P:$row" --set task.switch=no
expect_rc "branch started from the UZ row $row" 0
n2=$(awk -F, 'NR > 1 && $6 == 2' "$TMP/b2/branch.csv" | wc -l)
check "branch from a UZ row: the period-2 branch ($n2 points)" test "$n2" -gt 10

# The plot marks the user points by their own marker and key entry.
run_sc run "$SRC/examples/branch-logistic.ini" --out "$TMP/b3" --quiet \
  --set output.plot=no --set "task.marks=3.2" --set task.sweep=no
check "branch plot: UZ in the key" grep -q "title 'UZ user point'" "$TMP/b3/branch.gp"

# Refused by check, naming the value and the key.
for bad in "abc|is not a finite number" "3.2 inf|value 2, 'inf', is not a finite" \
           "4.5|out of range of r" "3.7|is outside [2.7999999999999998, 3.6000000000000001]"; do
  val=${bad%%|*}
  msg=${bad#*|}
  run_sc check "$SRC/examples/branch-logistic.ini" --set "task.marks=$val"
  expect_rc "branch marks = $val" 2
  expect_err "branch marks = $val" "$msg"
  expect_err "branch marks = $val: the key" "marks"
done

# The cusp normal form's fold curve: mu1 = -2 x^3, mu2 = 3 x^2 (x = d).
run_sc run "$SRC/examples/curve-cubic.ini" --out "$TMP/c" --quiet \
  --set output.plot=no --set "task.marks=-0.5 -0.25 0.3"
expect_rc "cubic fold curve with marks" 0
awk -F, '$1 == "UZ" {
  c = $2; y = $3; d = $4; res = $8
  x = (c < 0 ? 1 : -1) * exp(log((c < 0 ? -c : c) / 2) / 3)
  e = d - x; if (e < 0) e = -e; f = y - 3 * x * x; if (f < 0) f = -f; if (f > e) e = f
  ok = e <= 1e-14 && res <= 1e-14
  printf "%s UZ mu1 = %s: (d, mu2) off the closed form by %.3g, residual %s\n", ok ? "PASS" : "FAIL", c, e, res
  bad += !ok; n++
} END { if (n != 3) { print "FAIL " n " user points on the fold curve, expected 3"; exit 1 } exit bad > 0 }' \
  "$TMP/c/points.csv" && NPASS=$((NPASS + 1)) || NFAIL=$((NFAIL + 1))
check "cubic curve: user points are not counted as codimension two" \
  grep -q "codimension-two points: 1$" "$TMP/c/summary.txt"
run_sc check "$SRC/examples/curve-cubic.ini" --set "task.marks=-2"
expect_rc "curve marks outside the box in x" 2
expect_err "curve marks outside the box in x" "marks: value 1, -2, is outside"
finish
