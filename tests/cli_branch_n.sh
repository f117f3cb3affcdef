# The branch task for maps of n > 1 dimensions: the examples
# examples/ghenon-branch.ini (a fixed point through its fold, NS point
# and flip) and examples/henon-branch.ini (the period-doubling cascade)
# against their closed forms to 1e-10, the outputs' columns, `show`, and
# the refusals.
. "$(dirname "$0")/cli_common.sh"

ex="$SRC/examples/ghenon-branch.ini"
run_sc run "$ex" --out "$TMP/gh" --quiet --set output.plot=no
expect_rc "ghenon-branch.ini" 0
expect_header "ghenon: branch.csv" "$TMP/gh/branch.csv" \
  "alpha,x1,x2,multiplier,multipliers,stable,period,branch"
expect_header "ghenon: points.csv" "$TMP/gh/points.csv" \
  "label,parameter,value,x1,x2,period,multiplier,multipliers,coefficient,kappa,theta,residual,error,iterations,method,note"
# beta = 0.7, R = -0.5: fixed points x = y = s, alpha = 1.5 s^2 + 1.7 s;
# LP at s = -17/30 (alpha = -2.89/6), NS at s = 0.6 (alpha = 1.56,
# theta = arccos(-0.75)), PD at s = 0.85 (alpha = 2.52875).
check "ghenon: LP, NS and PD at their closed forms (1e-10), certified" awk -F, '
  function abs(x) { return x < 0 ? -x : x }
  function at(a, s) { return abs($3 - a) < 1e-10 && abs($4 - s) < 1e-10 &&
                      abs($5 - s) < 1e-10 && $12 + 0 < 1e-12 && $15 == "newton" }
  $1 == "LP" && at(-2.89 / 6, -17 / 30) { lp++ }
  $1 == "NS" && at(1.56, 0.6) && abs($10 + 0.75) < 1e-10 &&
    abs($11 - atan2(sqrt(1 - 0.5625), -0.75)) < 1e-10 &&
    $8 ~ /i/ { ns++ }
  $1 == "PD" && at(2.52875, 0.85) { pd++ }
  $1 == "LP" || $1 == "NS" || $1 == "PD" { if ($9 == "nan") nocoef++ }
  END { exit !(lp == 1 && ns == 1 && pd == 1 && nocoef == 0) }' "$TMP/gh/points.csv"
check "ghenon: every branch row has 2 multipliers" awk -F, '
  NR > 1 { if (split($5, mu, " ") != 2) bad++ } END { exit bad > 0 }' \
  "$TMP/gh/branch.csv"
grep -q "by label: LP 1 PD 1 NS 1 EP 1" "$TMP/gh/summary.txt"
check "ghenon: the summary counts by label" test $? -eq 0
grep -q "located by Newton on their defining systems with a residual certificate: 3" \
  "$TMP/gh/summary.txt"
check "ghenon: the summary counts the located points" test $? -eq 0

ex="$SRC/examples/henon-branch.ini"
run_sc run "$ex" --out "$TMP/he" --quiet --set output.plot=no
expect_rc "henon-branch.ini" 0
# b = 0.3: the fixed point flips at a1 = 3 (1 - b)^2 / 4, x = (1 - b) /
# (2 a1), y = b x; the period-2 orbit at a2 = (1 + b)^2 / 4 + (1 - b)^2,
# its points roots of z^2 - S z + P, S = (1 - b) / a2, P = S^2 - 1 / a2,
# y = b times the other point.
check "henon: the first two flips at their closed forms (1e-10)" awk -F, '
  function abs(x) { return x < 0 ? -x : x }
  BEGIN { b = 0.3; a1 = 3 * (1 - b)^2 / 4; x1 = (1 - b) / (2 * a1)
    a2 = (1 + b)^2 / 4 + (1 - b)^2; S = (1 - b) / a2; P = S * S - 1 / a2 }
  $1 == "PD" && $6 == 1 && abs($3 - a1) < 1e-10 && abs($4 - x1) < 1e-10 &&
    abs($5 - b * x1) < 1e-10 && $12 + 0 < 1e-12 { p1++ }
  $1 == "PD" && $6 == 2 && abs($3 - a2) < 1e-10 &&
    abs($4 * $4 - S * $4 + P) < 1e-10 && abs($5 - b * (S - $4)) < 1e-10 &&
    $12 + 0 < 1e-12 { p2++ }
  $1 == "PD" && $6 == 4 { p4++ }
  END { exit !(p1 == 1 && p2 == 1 && p4 == 1) }' "$TMP/he/points.csv"
check "henon: the cascade's segments have periods 1, 2, 4, 8" awk -F, '
  NR > 1 { seen[$7] = 1 } END { exit !(seen[1] && seen[2] && seen[4] && seen[8]) }' \
  "$TMP/he/branch.csv"

# A start inside the interval (at) is continued both ways: AUTO-07p's
# ghenon branch (bench/auto/c.ghenon: beta = 1.2, R = 0.5, x = y = -3 at
# alpha = -2.1): LP at s = -2.2 (alpha = -2.42), NS at s = 0.4 (alpha =
# 0.96, kappa = -0.3), PD at s = 1.1 (alpha = 3.025).
run_sc run "$SRC/examples/ghenon-branch.ini" --out "$TMP/at" --quiet \
  --set output.plot=no --set model.beta=1.2 --set model.R=0.5 \
  --set task.from=-3 --set task.at=-2.1 --set task.to=3.5 --set "task.d0=-3 -3"
expect_rc "at inside the interval" 0
check "at: both ways, LP, NS and PD of AUTO's branch (1e-10)" awk -F, '
  function abs(x) { return x < 0 ? -x : x }
  function at(a, s) { return abs($3 - a) < 1e-10 && abs($4 - s) < 1e-10 &&
                      $12 + 0 < 1e-12 }
  $1 == "LP" && at(-2.42, -2.2) { lp++ }
  $1 == "NS" && at(0.96, 0.4) && abs($10 + 0.3) < 1e-10 { ns++ }
  $1 == "PD" && at(3.025, 1.1) { pd++ }
  $1 == "EP" { ep++ }
  END { exit !(lp == 1 && ns == 1 && pd == 1 && ep == 2) }' "$TMP/at/points.csv"
run_sc check "$SRC/examples/ghenon-branch.ini" --set task.at=5
expect_rc "at outside [from, to]" 2
expect_err "at outside [from, to]" "at = 5 outside [from, to]"

# show = norm draws |x|; show = 2 the second component.
run_sc run "$SRC/examples/ghenon-branch.ini" --out "$TMP/nm" --quiet --set task.show=norm
expect_rc "show = norm" 0
check "show = norm: the plot's y label" grep -q "|x|" "$TMP/nm/branch.gp"
run_sc check "$SRC/examples/ghenon-branch.ini" --set task.show=3
expect_rc "show = 3 on a 2-d model" 2
expect_err "show = 3 on a 2-d model" "show = 3: model ghenon has 2 state components"
run_sc run "$SRC/examples/henon-branch.ini" --out "$TMP/y" --quiet --set task.show=y
expect_rc "show = y (a component's name)" 0
check "show = y: the plot's y label" grep -q "'y'" "$TMP/y/branch.gp"
run_sc check "$SRC/examples/ghenon-branch.ini" --set "task.starts=auto"
expect_rc "starts on a 2-d model" 2
expect_err "starts on a 2-d model" "starts is a key of one-dimensional branches"
run_sc run "$SRC/examples/ghenon-branch.ini" --out "$TMP/no" --quiet \
  --set model.alpha=-3 --set task.from=-3 --set task.to=-2
expect_rc "a start on no orbit" 1
expect_err "a start on no orbit" "[task] d0 = -2.1 -2.1 at alpha = -3: no period-1 orbit found from it (initial point not corrected"
finish
