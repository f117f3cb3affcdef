# Borders of n-dimensional maps through the branch task: the example
# examples/bcnf-branch.ini (the border-collision normal form's fixed
# point through its switching line) against its closed forms to 1e-12:
# the SW point at mu = 0, x = y = 0, located by Newton with its residual,
# and the branch handed over to the right side's fixed point x* = mu / 2.8.
. "$(dirname "$0")/cli_common.sh"

ex="$SRC/examples/bcnf-branch.ini"
run_sc run "$ex" --out "$TMP/bc" --quiet --set output.plot=no
expect_rc "bcnf-branch.ini" 0
check "bcnf: SW at mu = 0, x = y = 0 (1e-12), certified, handed over" awk -F, '
  function abs(x) { return x < 0 ? -x : x }
  $1 == "SW" && abs($3) < 1e-12 && abs($4) < 1e-12 && abs($5) < 1e-12 &&
    $12 + 0 < 1e-12 && $15 == "newton" && $16 ~ /L -> R/ { sw++ }
  END { exit sw != 1 }' "$TMP/bc/points.csv"
# tau_L = 0.5, delta_L = 0.3: x* = mu / 0.8 on branch 0; tau_R = -1.5,
# delta_R = 0.3: x* = mu / 2.8 on branch 1, which reaches mu = 1.
check "bcnf: both branches on their closed forms (1e-12)" awk -F, '
  function abs(x) { return x < 0 ? -x : x }
  NR > 1 && $8 == 0 { n0++; if (abs($2 - $1 / 0.8) > 1e-12 ||
    abs($3 + 0.3 * $1 / 0.8) > 1e-12 || $1 > 1e-12) bad++ }
  NR > 1 && $8 == 1 { n1++; if (abs($2 - $1 / 2.8) > 1e-12 ||
    abs($3 + 0.3 * $1 / 2.8) > 1e-12 || $1 < -1e-12) bad++; last = $1 }
  END { exit !(n0 > 2 && n1 > 2 && !bad && abs(last - 1) < 1e-12) }' \
  "$TMP/bc/branch.csv"
grep -q "by label: EP 1 SW 1" "$TMP/bc/summary.txt"
check "bcnf: the summary counts by label" test $? -eq 0
finish
