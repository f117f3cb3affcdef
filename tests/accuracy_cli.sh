#!/bin/sh
# The [accuracy] precision key through the program: the example next to
# d* in quad and in double agree within the default preset's promise
# (docs/accuracy.md), and bad values are refused before any work.
# usage: sh tests/accuracy_cli.sh PATH/TO/slipcont SOURCE_DIR
. "$(dirname "$0")/cli_common.sh"

example accuracy-dstar
png accuracy-dstar map.png
expect_rows accuracy-dstar "$TMP/accuracy-dstar/map.csv" 201
check "accuracy-dstar: summary names precision = quad" \
  grep -q "precision *= quad" "$TMP/accuracy-dstar/summary.txt"

# the same scene in double
$limit "$BIN" run "$SRC/examples/accuracy-dstar.ini" --out "$TMP/double" \
  --quiet --set accuracy.precision=double --set output.plot=no \
  >"$TMP/stdout" 2>"$TMP/stderr"
RC=$?
ERR=$(cat "$TMP/stderr")
expect_rc "precision = double" 0
# Promise of the default preset: |f - f_quad| <= 64 eps S (1 + |f'|), S =
# 1 + beta + (1 + alpha)|d| (beta = 2.5, alpha = 3.3).  Every row is
# compared; the worst ratio to the bound is printed.
worst=$(paste -d, "$TMP/accuracy-dstar/map.csv" "$TMP/double/map.csv" |
  awk -F, 'NR > 1 {
    eps = 2.220446049250313e-16
    d = $1; fq = $2; dfq = $3; fd = $7
    S = 1 + 2.5 + 4.3 * (d < 0 ? -d : d)
    g = 1 + (dfq < 0 ? -dfq : dfq)
    e = fd - fq; if (e < 0) e = -e
    r = e / (64 * eps * S * g); if (r > w) w = r
    if ($1 != $6) w = 1e9
  } END { printf "%.3g", w }')
check "double vs quad next to d*: worst |df| / promise = $worst (<= 1)" \
  awk "BEGIN { exit !($worst <= 1) }"
# f' sqrt|d - d*| is nearly constant on each side (the |d - d*|^-1/2 law):
# the ratio of its values 1e-6 and 1e-7 from d* (rows 1 and 91, below d*)
ratio=$(awk -F, 'NR == 2 || NR == 92 {
    ds = 0.19736842105263158; x = $1 - ds; if (x < 0) x = -x
    v[n++] = $3 * sqrt(x) } END { printf "%.6g", v[0] / v[1] }' \
  "$TMP/accuracy-dstar/map.csv")
check "f' sqrt|d - d*| at 1e-6 and 1e-7 below d*: ratio $ratio within 5% of 1" \
  awk "BEGIN { exit !($ratio > 0.95 && $ratio < 1.05) }"
# and above d* (rows 202 and 112: 1e-6 and 1e-7 above)
ratio=$(awk -F, 'NR == 202 || NR == 112 {
    ds = 0.19736842105263158; x = $1 - ds; if (x < 0) x = -x
    v[NR] = $3 * sqrt(x) } END { printf "%.6g", v[202] / v[112] }' \
  "$TMP/accuracy-dstar/map.csv")
check "f' sqrt|d - d*| at 1e-6 and 1e-7 above d*: ratio $ratio within 5% of 1" \
  awk "BEGIN { exit !($ratio > 0.95 && $ratio < 1.05) }"
# f continuous at d*: the values 1e-8 either side of it differ by
# O(sqrt 1e-8) = 1e-4 at most, not by a jump
jump=$(awk -F, 'NR == 101 || NR == 103 { f[NR] = $2 } END {
    j = f[103] - f[101]; if (j < 0) j = -j; printf "%.3g", j }' \
  "$TMP/accuracy-dstar/map.csv")
check "f continuous at d*: |f(d* + 1e-8) - f(d* - 1e-8)| = $jump <= 1e-3" \
  awk "BEGIN { exit !($jump <= 1e-3) }"

run_sc run "$SRC/examples/accuracy-dstar.ini" --out "$TMP/bad" \
  --set accuracy.precision=single
expect_rc "precision = single" 2
expect_err "precision = single" "double|quad"
expect_err "precision = single" "precision"
check "precision = single: no output folder" test ! -e "$TMP/bad/map.csv"

run_sc run "$SRC/examples/accuracy-dstar.ini" --out "$TMP/bad2" \
  --set model.flows=numerical
expect_rc "quad with numerical flows" 2
expect_err "quad with numerical flows" "precision = quad needs flows = exact"
finish
