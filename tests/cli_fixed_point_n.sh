# The fixed-point task for maps of n > 1 dimensions: the example
# examples/henon-fixed-points.ini (Henon at a = 1.4, b = 0.3, periods
# 1..12) against its closed forms and its known counts, a start alone
# (d0), the generalized Henon map's fixed points, and the refusals.
. "$(dirname "$0")/cli_common.sh"

ex="$SRC/examples/henon-fixed-points.ini"
run_sc run "$ex" --out "$TMP/ex" --quiet --set output.plot=no
expect_rc "henon-fixed-points.ini" 0
expect_header "henon: periods.csv" "$TMP/ex/periods.csv" \
  "period,orbits,stable,unstable,starts,known,lower_period,outside_box,failed"
expect_header "henon: orbits.csv" "$TMP/ex/orbits.csv" \
  "period,multiplier,multipliers,stable,residual,start_x1,start_x2,points"
# The counts of the Henon attractor's orbits by period (with the fixed
# point off it), checked independently for periods 1..6 by
# tests/test_fixed_points_n.c.
counts=$(awk -F, 'NR > 1 {printf "%s ", $2}' "$TMP/ex/periods.csv")
check "henon: orbits per period 2 1 0 1 0 2 4 7 6 10 14 19 (got $counts)" \
  test "$counts" = "2 1 0 1 0 2 4 7 6 10 14 19 "
stable=$(awk -F, 'NR > 1 {s += $3} END {print s + 0}' "$TMP/ex/periods.csv")
check "henon: no stable orbit on the chaotic attractor (got $stable)" \
  test "$stable" = 0
# Fixed points x = (-(1 - b) +- sqrt((1 - b)^2 + 4 a)) / (2 a), y = b x;
# the period-2 orbit x = ((1 - b) +- sqrt(4 a - 3 (1 - b)^2)) / (2 a),
# y1 = b x2, y2 = b x1; to 1e-12.
check "henon: fixed points and the period-2 orbit in closed form" awk -F, '
  function abs(x) { return x < 0 ? -x : x }
  BEGIN { a = 1.4; b = 0.3; r1 = sqrt((1 - b)^2 + 4 * a)
    f[0] = (-(1 - b) - r1) / (2 * a); f[1] = (-(1 - b) + r1) / (2 * a)
    r2 = sqrt(4 * a - 3 * (1 - b)^2)
    x1 = ((1 - b) - r2) / (2 * a); x2 = ((1 - b) + r2) / (2 * a); n1 = 0 }
  $1 == 1 { split($8, p, " ")
    if (abs(p[1] - f[n1]) < 1e-12 && abs(p[2] - b * f[n1]) < 1e-12) ok1++
    n1++ }
  $1 == 2 { split($8, q, ";"); split(q[1], u, " "); split(q[2], v, " ")
    if (abs(u[1] - x1) < 1e-12 && abs(u[2] - b * x2) < 1e-12 &&
        abs(v[1] - x2) < 1e-12 && abs(v[2] - b * x1) < 1e-12) ok2++ }
  END { exit !(ok1 == 2 && ok2 == 1) }' "$TMP/ex/orbits.csv"
check "henon: every row has 2 multipliers and m points" awk -F, '
  NR > 1 { if (split($3, mu, " ") != 2 || split($8, pt, ";") != $1) bad++ }
  END { exit bad > 0 }' "$TMP/ex/orbits.csv"
check "henon: residuals are certificates below 1e-12" awk -F, '
  NR > 1 && !($5 + 0 < 1e-12) { bad++ } END { exit bad > 0 }' \
  "$TMP/ex/orbits.csv"
grep -q "starts a period: 441 grid points (21 per axis)" "$TMP/ex/summary.txt"
check "henon: the summary counts the starts" test $? -eq 0
grep -q "period 12: 19 orbits (0 stable)" "$TMP/ex/summary.txt"
check "henon: the summary counts per period" test $? -eq 0
grep -q "failed [0-9]* (no" "$TMP/ex/summary.txt"
check "henon: failed starts grouped by reason" test $? -eq 0
# The plot script (written with plot = no too): the plane, coloured by
# period, stable filled (pt 7), unstable open (pt 6).
expect_header "henon: fixed-point-orbits.csv" "$TMP/ex/fixed-point-orbits.csv" \
  "x1,x2,stable,orbit,period"
for w in "lc palette" "pt 7" "pt 6" "set cbrange [0.5:12.5]"; do
  grep -qF "$w" "$TMP/ex/fixed-point.gp"
  check "henon: fixed-point.gp has '$w'" test $? -eq 0
done
check "henon: one plotted point per orbit point" \
  test "$(data_rows "$TMP/ex/fixed-point-orbits.csv")" -eq "$(awk -F, 'NR > 1 {s += $1 * $2} END {print s}' "$TMP/ex/periods.csv")"

# A start alone: Newton from d0, no box.
cat >"$TMP/d0.ini" <<'INI'
[model]
name = henon
[task]
kind = fixed-point
period = 1
d0 = 0.6 0.2
[output]
plot = no
INI
run_sc run "$TMP/d0.ini" --out "$TMP/d0" --quiet
expect_rc "d0 alone" 0
expect_rows "d0 alone: one orbit" "$TMP/d0/orbits.csv" 1
check "d0 alone: the fixed point near it" awk -F, '
  NR == 2 { split($8, p, " "); d = p[1] - 0.63135447708950476
    exit !(d < 1e-12 && d > -1e-12) }' "$TMP/d0/orbits.csv"

# ghenon: x = y = s, (1 - R) s^2 + (1 + beta) s - alpha = 0, both roots;
# single shooting.
cat >"$TMP/gh.ini" <<'INI'
[model]
name = ghenon
alpha = 0.3
beta = 0.6
R = 0.4
[task]
kind = fixed-point
period = 1
from = -4 -4
to = 2 2
steps = 11
attractor = 50
shooting = single
[output]
plot = no
INI
run_sc run "$TMP/gh.ini" --out "$TMP/gh" --quiet
expect_rc "ghenon fixed points" 0
check "ghenon: both roots of (1 - R) s^2 + (1 + beta) s - alpha" awk -F, '
  function abs(x) { return x < 0 ? -x : x }
  BEGIN { A = 0.6; B = 1.6; d = sqrt(B * B + 4 * A * 0.3)
    s[0] = (-B - d) / (2 * A); s[1] = (-B + d) / (2 * A); n = 0 }
  NR > 1 { split($8, p, " ")
    if (abs(p[1] - s[n]) < 1e-12 && abs(p[2] - s[n]) < 1e-12) ok++; n++ }
  END { exit !(n == 2 && ok == 2) }' "$TMP/gh/orbits.csv"
grep -q "i " "$TMP/gh/orbits.csv"
check "ghenon: a complex pair written a+bi" test $? -eq 0

# Refusals.
grep -v '^d0' "$TMP/d0.ini" >"$TMP/nobox.ini"
run_sc run "$TMP/nobox.ini" --out "$TMP/r1" --quiet
expect_rc "n > 1 without d0 or a box" 2
expect_err "n > 1 without d0 or a box" "missing key 'from': the search needs a box"
run_sc check "$ex" --set task.period=1001
expect_rc "period beyond 1000" 2
expect_err "period beyond 1000" "valid for n > 1: m in [1, 1000]"
run_sc check "$ex" --set "task.to=1.5 -0.5"
expect_rc "to not above from in y" 2
expect_err "to not above from in y" "in component 2"
run_sc check "$ex" --set task.steps=5000
expect_rc "too many starts" 2
expect_err "too many starts" "starts (valid: steps^2 + attractor <="
run_sc check "$ex" --set "task.d0=0.1"
expect_rc "d0 with one number" 2
run_sc check "$SRC/examples/fixed-point-logistic.ini" --set task.d0=0.5
expect_rc "d0 on a one-dimensional model" 2
expect_err "d0 on a one-dimensional model" "d0 is a key of models of n > 1 dimensions"
finish
