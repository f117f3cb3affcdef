# The curve task on an n-dimensional model through the program: ghenon's
# NS, fold and flip curves (examples/curve-ghenon-*.ini) held to the
# closed forms their opening comments promise (docs/maps.md, "Curves and
# codimension two"), a start from a branch row, and the refusals.
# Tolerances: every curve point to 1e-12, every located point to 1e-10
# (the closed forms are computed here in awk, in double: a few ulps).
. "$(dirname "$0")/cli_common.sh"

mkdir -p "$TMP/w"
cd "$TMP/w" || exit 1
for ex in curve-ghenon-ns curve-ghenon-fold curve-ghenon-flip; do
  # shellcheck disable=SC2086
  $limit "$BIN" run "$SRC/examples/$ex.ini" --quiet $plotset \
    >"$TMP/stdout" 2>"$TMP/stderr"
  RC=$?
  ERR=$(cat "$TMP/stderr")
  expect_rc "$ex" 0
  no_temporaries "$ex" "out/$ex"
done
D=out/curve-ghenon-ns
expect_header "ns" "$D/curve.csv" \
  "alpha,beta,x1,x2,period,kappa,coefficient,multipliers"
expect_header "ns" "$D/points.csv" \
  "label,alpha,beta,x1,x2,period,note,coefficient,residual,kappa"
check "ns: every point on beta = 1 + R s, alpha = s^2 + 2 s, x = y = s, kappa = (R - 2) s / 2" \
  awk -F, 'function a(x) { return x < 0 ? -x : x }
  NR > 1 && NF > 1 { s = ($2 - 1) / 0.5; e = a($1 - s * s - 2 * s);
    if (a($3 - s) > e) e = a($3 - s); if (a($4 - s) > e) e = a($4 - s);
    if (a($6 + 0.75 * s) > e) e = a($6 + 0.75 * s);
    if (e > 1e-12) { print NR, e; exit 1 } }' "$D/curve.csv"
# R1..R4 at s = 2, -2, -1, 0 over (R - 2), each once, residual <= 1e-10
for p in "R1 -4/3 1" "R2 4/3 -1" "R3 2/3 -0.5" "R4 0 0"; do
  set -- $p
  check "ns: one $1 at its closed form, kappa $3" awk -F, -v l="$1" -v k="$3" \
    "function a(x) { return x < 0 ? -x : x }
    BEGIN { s = $2; n = 0 }
    \$1 == l { n++; e = a(\$2 - s * s - 2 * s); if (a(\$3 - 1 - 0.5 * s) > e) e = a(\$3 - 1 - 0.5 * s);
      if (a(\$4 - s) > e) e = a(\$4 - s); if (a(\$10 - k) > e) e = a(\$10 - k);
      if (e > 1e-10 || \$9 > 1e-10) exit 1 }
    END { exit n != 1 }" "$D/points.csv"
done
check "ns: no CH, nothing rejected" test "$(grep -c -E '^(CH|[A-Z0-9]+\?),' "$D/points.csv")" -eq 0
check "ns: the summary counts NS points and neutral saddles" \
  grep -q "Neimark-Sacker points (|kappa| < 1): [1-9]" "$D/summary.txt"

D=out/curve-ghenon-fold
check "fold: every point on (1 + beta)^2 + 4 (1 - R) alpha = 0" \
  awk -F, 'function a(x) { return x < 0 ? -x : x }
  NR > 1 && NF > 1 { s = -(1 + $2); e = a((1 + $2) ^ 2 + 2 * $1);
    if (a($3 - s) > e) e = a($3 - s); if (e > 1e-12) exit 1 }' "$D/curve.csv"
check "fold: R1 (-8/9, 1/3) and LPPD (0, -1), nothing else" awk -F, \
  'function a(x) { return x < 0 ? -x : x }
  $1 == "R1" { r1++; if (a($2 + 8 / 9) > 1e-10 || a($3 - 1 / 3) > 1e-10) exit 1 }
  $1 == "LPPD" { lp++; if (a($2) > 1e-10 || a($3 + 1) > 1e-10) exit 1 }
  NR > 1 && $1 != "R1" && $1 != "LPPD" && $1 != "EP" { exit 1 }
  END { exit !(r1 == 1 && lp == 1) }' "$D/points.csv"

D=out/curve-ghenon-flip
check "flip: every point on alpha = (3 - R) s^2, s = (1 + beta) / 2" \
  awk -F, 'function a(x) { return x < 0 ? -x : x }
  NR > 1 && NF > 1 { s = (1 + $2) / 2; e = a($1 - 2.5 * s * s);
    if (a($3 - s) > e) e = a($3 - s); if (e > 1e-12) exit 1 }' "$D/curve.csv"
check "flip: R2 (40/9, 5/3) and LPPD (0, -1), nothing else" awk -F, \
  'function a(x) { return x < 0 ? -x : x }
  $1 == "R2" { r2++; if (a($2 - 40 / 9) > 1e-10 || a($3 - 5 / 3) > 1e-10) exit 1 }
  $1 == "LPPD" { lp++; if (a($2) > 1e-10 || a($3 + 1) > 1e-10) exit 1 }
  NR > 1 && $1 != "R2" && $1 != "LPPD" && $1 != "EP" { exit 1 }
  END { exit !(r2 == 1 && lp == 1) }' "$D/points.csv"
png "w/out/curve-ghenon-flip" curve.png

# A start from a branch row: an NS row of a points.csv (its state in the
# model's columns, kappa optional), the start on the curve already.
cat >"$TMP/w/branch.csv" <<'CSV'
label,parameter,value,x1,x2,period,note,kappa
LP,alpha,-2.42,-2.2,-2.2,1,fold,1
NS,alpha,0.96,0.4,0.4,1,Neimark-Sacker,-0.3
CSV
sed -e '/^d0 =/d' -e 's/^alpha = 0.96/alpha = 0/' \
  "$SRC/examples/curve-ghenon-ns.ini" >"$TMP/w/row.ini"
run_sc run "$TMP/w/row.ini" --set "task.start=$TMP/w/branch.csv:2" \
  --out "$TMP/w/row" --quiet --set output.plot=no
expect_rc "ns from a branch row" 0
check "ns from a branch row: started at the row's alpha = 0.96 (to rounding)" \
  grep -q -E "start: alpha = 0\.9(59999999999|60000000000)[0-9]*, beta = 1\.2," "$TMP/w/row/summary.txt"
check "ns from a branch row: the same four resonances" \
  test "$(grep -c -E '^R[1-4],' "$TMP/w/row/points.csv")" -eq 4
run_sc check "$TMP/w/row.ini" --set "task.start=$TMP/w/branch.csv:1"
expect_rc "ns from an LP row" 2
expect_err "ns from an LP row" "is a LP in alpha (valid: a NS in x = alpha for type = ns)"

# From the branch task's own rows: examples/ghenon-branch.ini (beta = 0.7,
# R = -0.5) locates LP, NS, PD in alpha; the NS curve from its NS row
# meets R1..R4 at s = 2, -2, -1, 0 over (R - 2) (beta = 1 + R s,
# alpha = s^2 + 2 s): R1 (-0.96, 1.4), R2 (2.24, 0.6), R3 (0.96, 0.8),
# R4 (0, 1).
$limit "$BIN" run "$SRC/examples/ghenon-branch.ini" --out "$TMP/w/gb" --quiet \
  --set output.plot=no >/dev/null 2>&1
ns=$(awk -F, '$1 == "NS" { print NR - 1; exit }' "$TMP/w/gb/points.csv")
sed -e '/^d0 =/d' -e 's/^beta = 1.2/beta = 0.7/' -e 's/^R = 0.5/R = -0.5/' \
  "$SRC/examples/curve-ghenon-ns.ini" >"$TMP/w/gb.ini"
run_sc run "$TMP/w/gb.ini" --set "task.start=$TMP/w/gb/points.csv:$ns" \
  --out "$TMP/w/gbns" --quiet --set output.plot=no
expect_rc "ns from ghenon-branch's NS row ($ns)" 0
for p in "R1 -0.96 1.4" "R2 2.24 0.6" "R3 0.96 0.8" "R4 0 1"; do
  set -- $p
  check "ns from the branch row: $1 at ($2, $3)" awk -F, -v l="$1" -v a="$2" -v b="$3" \
    'function d(x) { return x < 0 ? -x : x }
    $1 == l { n++; if (d($2 - a) > 1e-10 || d($3 - b) > 1e-10) exit 1 }
    END { exit n != 1 }' "$TMP/w/gbns/points.csv"
done

# The NS curve over ghenon's period chart (examples/ghenon-chart.ini
# first): the chart's invariant circles drawn in the chart's colour.
for ex in ghenon-chart curve-ghenon-chart; do
  # shellcheck disable=SC2086
  $limit "$BIN" run "$SRC/examples/$ex.ini" --quiet $plotset \
    >"$TMP/stdout" 2>"$TMP/stderr"
  RC=$?
  ERR=$(cat "$TMP/stderr")
  expect_rc "$ex" 0
done
D=out/curve-ghenon-chart
check "curve-ghenon-chart: R4 at (0, 1), R3 at (7/9, 2/3), d < 0" awk -F, \
  'function a(x) { return x < 0 ? -x : x }
  $1 == "R4" { n++; if (a($2) > 1e-10 || a($3 - 1) > 1e-10 || !($8 < 0)) exit 1 }
  $1 == "R3" { n++; if (a($2 - 7 / 9) > 1e-10 || a($3 - 2 / 3) > 1e-10) exit 1 }
  END { exit n != 2 }' "$D/points.csv"
check "curve-ghenon-chart: every point on s = 1 - beta, alpha = s^2 + 2 s" \
  awk -F, 'function a(x) { return x < 0 ? -x : x }
  NR > 1 && NF > 1 { s = 1 - $2; if (a($1 - s * s - 2 * s) > 1e-12 || a($3 - s) > 1e-12) exit 1 }' \
  "$D/curve.csv"
check "curve-ghenon-chart: the overlay's invariant circles in the chart's colour" \
  grep -q "p == -3 ? " "$D/curve.gp"
check "curve-ghenon-chart: and in its key" grep -q "title 'chart: invariant circle'" "$D/curve.gp"
# past R1 and R2 the NS curve is that of neutral saddles: dashed, and in
# the key only where the curve has such points; a start that moved by
# rounding only is not news in the title
if [ -z "$plotset" ]; then
  check "curve-ghenon-ns: the neutral saddles dashed, in the key" \
    grep -q "title 'neutral saddle (not NS)'" out/curve-ghenon-ns/curve.gp
  check "curve-ghenon-chart: no neutral saddles, none in the key" \
    test "$(grep -c 'neutral saddle' "$D/curve.gp")" -eq 0
  check "curve-ghenon-chart: a start moved by rounding is not in the title" \
    test "$(grep -c 'start moved' "$D/curve.gp")" -eq 0
fi

# refusals: borders, multiple shooting, marks, ns of a one-dimensional map
run_sc check "$SRC/examples/curve-ghenon-ns.ini" --set task.type=graze
expect_rc "ghenon: type = graze" 2
expect_err "ghenon: type = graze" "declares no borders (valid: fold, flip or ns)"
run_sc check "$SRC/examples/curve-ghenon-ns.ini" --set task.shooting=multiple
expect_rc "ghenon: multiple shooting" 2
expect_err "ghenon: multiple shooting" "valid: single"
run_sc check "$SRC/examples/curve-ghenon-ns.ini" --set "task.marks=0.5"
expect_rc "ghenon: marks" 2
expect_err "ghenon: marks" "marks"
run_sc check "$SRC/examples/curve-cubic.ini" --set task.type=ns
expect_rc "cubic: type = ns" 2
expect_err "cubic: type = ns" "one-dimensional"
run_sc run "$SRC/examples/curve-ghenon-ns.ini" --set "task.d0=3 3" --out "$TMP/w/far" --quiet
expect_rc "ns: a start with no complex pair" 1
expect_err "ns: a start with no complex pair" "no complex pair"
finish
