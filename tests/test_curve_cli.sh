# The curve task through the program: the example scenes write what the
# task promises and their known answers, and bad input is refused before
# any work with a message naming the key.
. "$(dirname "$0")/cli_common.sh"

run_sc run "$SRC/examples/curve-cubic.ini" --out "$TMP/cubic" --quiet
expect_rc "curve-cubic" 0
expect_header "curve-cubic" "$TMP/cubic/curve.csv" \
  "mu1,mu2,x,period,multiplier,coefficient,itinerary"
expect_header "curve-cubic" "$TMP/cubic/points.csv" \
  "label,mu1,mu2,x,period,note,coefficient,residual"
# the cusp at the origin, exact to 1e-12
cp=$(grep '^CP,' "$TMP/cubic/points.csv")
check "curve-cubic: one CP row ($cp)" test "$(grep -c '^CP,' "$TMP/cubic/points.csv")" -eq 1
check "curve-cubic: CP at the origin to 1e-12" awk -F, -v l="$cp" 'BEGIN {
  split(l, f, ","); for (i = 2; i <= 4; i++) if (f[i] > 1e-12 || f[i] < -1e-12) exit 1 }'
# every curve point on 27 mu1^2 = 4 mu2^3 (relative to the terms' size)
check "curve-cubic: points on 27 mu1^2 = 4 mu2^3" awk -F, 'NR > 1 && NF > 1 {
  a = 27 * $1 * $1; b = 4 * $2 * $2 * $2; e = a - b; if (e < 0) e = -e;
  if (e > 1e-12 * (1 + a)) exit 1 }' "$TMP/cubic/curve.csv"
check "curve-cubic: summary names the cusp" grep -q "CP  mu1 = 0" "$TMP/cubic/summary.txt"

run_sc run "$SRC/examples/curve-gpd.ini" --out "$TMP/gpd" --quiet
expect_rc "curve-gpd" 0
check "curve-gpd: one GPD row" test "$(grep -c '^GPD,' "$TMP/gpd/points.csv")" -eq 1
check "curve-gpd: GPD at mu2 = 0" awk -F, '/^GPD,/ { if ($3 > 1e-12 || $3 < -1e-12) exit 1 }' "$TMP/gpd/points.csv"

# bad input: the same parameter twice, an empty box, a start outside it
run_sc check "$SRC/examples/curve-cubic.ini" --set task.y=mu1
expect_rc "curve: x = y" 2
expect_err "curve: x = y" "same parameter as x"
run_sc check "$SRC/examples/curve-cubic.ini" --set task.x-to=-2
expect_rc "curve: x-to below x-from" 2
expect_err "curve: x-to below x-from" "x-to"
run_sc check "$SRC/examples/curve-cubic.ini" --set model.mu2=1.8
expect_rc "curve: start outside the box" 2
expect_err "curve: start outside the box" "outside"
run_sc run "$SRC/examples/curve-cubic.ini" --set task.type=saddle --out "$TMP/bad"
expect_rc "curve: unknown type" 2
expect_err "curve: unknown type" "fold|flip|graze"
run_sc run "$SRC/examples/curve-cubic.ini" --set task.type=graze --out "$TMP/bad"
expect_rc "curve: border curve of a map without borders" 2
expect_err "curve: border curve of a map without borders" "declares no borders"
check "curve: nothing written on bad input" test ! -e "$TMP/bad/curve.csv"

# also: other curves drawn in the same plot; a pattern that matches no
# folder is refused before any output
run_sc run "$SRC/examples/curve-gpd.ini" --out "$TMP/gpd-also" --quiet \
  --set task.also="$TMP/cub*"
expect_rc "curve: also" 0
check "curve: also draws the other curve" grep -q "cubic/curve.csv' skip 1 using 1:2 with lines" "$TMP/gpd-also/curve.gp"
run_sc run "$SRC/examples/curve-gpd.ini" --out "$TMP/bad-also" --set task.also="$TMP/nothing-here*"
expect_rc "curve: also matches nothing" 2
expect_err "curve: also matches nothing" "matches no folder"
check "curve: also: nothing written" test ! -e "$TMP/bad-also/curve.csv"

# a border curve from a GR row of a branch task's points.csv (fig 5.8)
printf 'label,parameter,value,d,period\nPD,alpha,3.1525203451104331,0.22708407773008357,4\nGR,alpha,3.8613904131033094,0.19577564632151551,4\n' > "$TMP/pts58.csv"
sed '/^d0 = /d' "$SRC/examples/curve-fig58-graze4.ini" > "$TMP/graze.ini"
run_sc run "$TMP/graze.ini" --out "$TMP/graze" --quiet \
  --set task.start="$TMP/pts58.csv:2"
expect_rc "curve: graze from a GR row" 0
check "curve: the graze curve's PD (a flip on the border)" grep -q '^PD,3.69577716' "$TMP/graze/points.csv"
check "curve: graze curve residuals within 1e-10" awk -F, 'NR > 1 && NF > 1 {
  if ($6 + 0 > 1e-10 || $6 + 0 < -1e-10) exit 1 }' "$TMP/graze/curve.csv"
run_sc check "$TMP/graze.ini" --set task.start="$TMP/pts58.csv:1"
expect_rc "curve: graze from a PD row" 2
expect_err "curve: graze from a PD row" "valid: a GR in x"

# The bk2 curve scenes of examples/ are held to their promises in
# curve_examples.sh.

# overlay: a chart of other parameters is refused; a chart of (mu1, mu2)
# is drawn under the curve
run_sc check "$SRC/examples/curve-cubic.ini" --set task.overlay="$TMP/cubic/points.csv"
expect_rc "curve: overlay not a chart" 2
expect_err "curve: overlay not a chart" "is not a chart of (mu1, mu2)"
run_sc check "$SRC/examples/curve-cubic.ini" --set task.overlay="$TMP/none.csv"
expect_rc "curve: overlay missing" 2
expect_err "curve: overlay missing" "cannot be read"
printf 'mu1,mu2,period,x,iterations\n0,0,1,0,10\n' >"$TMP/chart.csv"
run_sc run "$SRC/examples/curve-cubic.ini" --set task.overlay="$TMP/chart.csv" \
  --set output.plot=no --out "$TMP/ov" --quiet
expect_rc "curve: overlay" 0
check "curve: overlay drawn under the curve in the chart's colours" grep -q "chart.csv' skip 1 using 1:2:(int(rgb(\$3)) >> 16 & 255):.* with rgbimage" "$TMP/ov/curve.gp"

# start = a located LP of a branch task's points.csv instead of d0: the
# fold of x -> x + mu1 + 1.2 x - x^3 at x = -sqrt(0.4), mu1 = 0.8 sqrt(0.4)
grep -v '^d0' "$SRC/examples/curve-cubic.ini" >"$TMP/nod0.ini"
printf 'label,parameter,value,d,period,multiplier,note\n' >"$TMP/pts.csv"
printf 'PD,mu1,0.1377,-1.0328,1,-1,x\n' >>"$TMP/pts.csv"
printf 'LP,mu1,0.50596,-0.63246,1,1,x\n' >>"$TMP/pts.csv"
run_sc run "$TMP/nod0.ini" --set task.start="$TMP/pts.csv:2" --out "$TMP/st" --quiet
expect_rc "curve: start from points.csv" 0
check "curve: start from points.csv finds the cusp" grep -q "CP  mu1 = 0" "$TMP/st/summary.txt"
run_sc check "$TMP/nod0.ini" --set task.start="$TMP/pts.csv:1"
expect_rc "curve: start row is a PD for a fold" 2
expect_err "curve: start row is a PD for a fold" "is a PD in mu1"
run_sc check "$TMP/nod0.ini" --set task.start="$TMP/pts.csv:3"
expect_rc "curve: start row missing" 2
expect_err "curve: start row missing" "has no row 3"
run_sc check "$TMP/nod0.ini"
expect_rc "curve: neither d0 nor start" 2
expect_err "curve: neither d0 nor start" "either d0 or start"
finish
