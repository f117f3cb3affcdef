# The examples' figures: no two labels overlap (the boxes the placing code
# wrote beside each label, in pixels), the keys list only the kinds
# present, narrow axes get tick formats whose labels differ, several
# curves are named by type and period in distinct colours under a title
# for all of them, and the chart under them uses the chart's colours.
# Usage: sh tests/figures.sh PATH/TO/slipcont SOURCE_DIR
. "$(dirname "$0")/cli_common.sh"

# The scripts are written with or without gnuplot; the pictures only with.
plotset="--set output.plot=no"
if command -v gnuplot >/dev/null 2>&1; then plotset=; fi

# labels_clear NAME SCRIPT W H: every "# box x0 y0 x1 y1" inside the plot
# area (the script's fixed margins) and no two boxes overlapping.
labels_clear() {
  awk -v W="$3" -v H="$4" -v what="$1: $2" '
    /^set lmargin at screen/ { L = $5 * W } /^set rmargin at screen/ { R = $5 * W }
    /^set bmargin at screen/ { B = $5 * H } /^set tmargin at screen/ { T = $5 * H }
    /^# box / { n++; x0[n] = $3; y0[n] = $4; x1[n] = $5; y1[n] = $6 }
    END {
      bad = 0
      for (i = 1; i <= n; i++) {
        if (x0[i] < L || x1[i] > R || y0[i] < B || y1[i] > T) {
          bad++; print "  outside the plot area: box " i
        }
        for (j = i + 1; j <= n; j++)
          if (x0[i] < x1[j] && x0[j] < x1[i] && y0[i] < y1[j] && y0[j] < y1[i]) {
            bad++; print "  boxes " i " and " j " overlap"
          }
      }
      if (n == 0) { print "FAIL " what ": no placed labels"; exit 1 }
      if (bad) { print "FAIL " what ": " bad " overlaps among " n " labels"; exit 1 }
      print "PASS " what ": " n " labels, none overlapping, all inside"
    }' "$TMP/$1/$2" && NPASS=$((NPASS + 1)) || NFAIL=$((NFAIL + 1))
}

# numbers_shown NAME: every special point but the ends has its number in
# a placed label of branch.gp, or the figure says how many are left out.
numbers_shown() {
  want=$(awk -F, 'NR > 1 && $1 != "EP"' "$TMP/$1/points.csv" | wc -l)
  got=$(awk '/^set label 1[0-9][0-9][0-9] / { sub(/^[^'"'"']*'"'"'/, "");
          sub(/'"'"'.*/, ""); n += split($0, a, ", ") } END { print n + 0 }' \
        "$TMP/$1/branch.gp")
  out=$(sed -n 's/.*'"'"'\([0-9]*\) numbers left out.*/\1/p' "$TMP/$1/branch.gp")
  if [ "$got" -eq "$((want - ${out:-0}))" ]; then
    pass "$1: $got of $want numbers placed (${out:-0} left out, said so)"
  else fail "$1: $got numbers placed, $want special points, ${out:-0} left out"; fi
}

# key_titles NAME SCRIPT: the key's titles, one a line.
key_titles() {
  grep -v '^set title' "$TMP/$1/$2" | sed -n "s/.* title '\([^']*\)'.*/\1/p"
}

for b in branch-fig58 branch-logistic branch-symmetric; do
  example $b
  labels_clear $b branch.gp 1200 800
  numbers_shown $b
  png $b branch.png
done

# Only the kinds present: the logistic branch has flips only.
kinds=$(key_titles branch-logistic branch.gp | grep -cE '^(LP|GR|CS|SW|BR|TT) ')
check "branch-logistic: no absent kind in the key" test "$kinds" -eq 0
check "branch-logistic: the flips in the key" \
  grep -q "title 'PD flip'" "$TMP/branch-logistic/branch.gp"
check "branch-fig58: the key under the x label (fixed bottom margin)" \
  grep -q "^set key at screen 0.44, screen 0.015 center bottom" \
  "$TMP/branch-fig58/branch.gp"

# A narrow axis: d over 2e-6 near 0.1974 needs eight digits.
example accuracy-dstar
check "accuracy-dstar: x tick labels with 8 digits" \
  grep -q "^set format x '%.8g'" "$TMP/accuracy-dstar/map.gp"
check "accuracy-dstar: only both-blocks motion in the key" \
  test "$(key_titles accuracy-dstar map.gp | tr '\n' '|')" = "both blocks slip|diagonal|"
png accuracy-dstar map.png

# Several curves over a chart (examples/curve-fig57b.ini, a smaller chart).
mkdir -p "$TMP/w/out"
for c in curve-fig58-flip1 curve-fig58-fold4 curve-fig58-period6 \
         curve-fig512-cross2; do
  "$BIN" run "$SRC/examples/$c.ini" --out "$TMP/w/out/$c" --quiet $plotset \
    >/dev/null 2>&1
  check "$c runs" test -s "$TMP/w/out/$c/curve.csv"
done
"$BIN" run "$SRC/examples/chart-fig57b-window.ini" --quiet $plotset \
  --out "$TMP/w/out/chart-fig57b-window" --set task.x-steps=31 \
  --set task.y-steps=21 --set task.transient=300 >/dev/null 2>&1
(cd "$TMP/w" && "$BIN" run "$SRC/examples/curve-fig57b.ini" --quiet $plotset \
  --out "$TMP/fig57b" --set "task.also=out/curve-fig58-* out/curve-fig512-*" \
  >"$TMP/stdout" 2>"$TMP/stderr")
RC=$?
ERR=$(cat "$TMP/stderr")
expect_rc curve-fig57b 0
gp="$TMP/fig57b/curve.gp"
check "curve-fig57b: titled for the 5 curves" \
  grep -q "^set title '5 curves in (alpha, beta): graze 4 (this run, thick)" "$gp"
check "curve-fig57b: the title lists them by type and period" \
  grep -q "'flip 1; fold 4, 6; cross 2'" "$gp"
for t in "flip, period 1" "fold, period 4" "fold, period 6" "cross, period 2"; do
  check "curve-fig57b: a curve named '$t'" grep -q "title '$t'" "$gp"
done
cols=$(sed -n "s/.*with lines lw 1.5 dt [0-9]* lc rgb '\(#[0-9a-f]*\)' title.*/\1/p" "$gp")
check "curve-fig57b: neighbouring curves in different colours" \
  test "$(echo "$cols" | uniq | wc -l)" -eq 4
# The chart's classes, and the key's: the same set.
have=$(awk -F, 'NR > 1 { print $3 }' "$TMP/w/out/chart-fig57b-window/chart.csv" |
  sort -n | uniq | awk '$1 > 0 { printf "%d ", $1 }')
keyed=$(sed -n "s/.*title 'chart: period \([0-9]*\)'.*/\1/p" "$gp" | tr '\n' ' ')
check "curve-fig57b: the key's periods are the chart's ($have)" test "$have" = "$keyed"
# The chart's own period colours, made pale: period 1 (0x1f77b4) first.
check "curve-fig57b: the chart's colours for periods" \
  grep -q "^array C\[16\] = \[0xbcd6e9," "$gp"
png fig57b curve.png
finish
