# Every bk2 curve scene of examples/ (fig 5.8, fig 5.12, fig 5.7(b))
# through the program, each held to what its opening comment promises:
# every point on its defining system to 1e-10, and the points the comment
# (or docs/curves.md, which the comment names) says the curve meets, ends
# at or carries.  curve-cubic and curve-gpd are in test_curve_cli.sh.
#
# Tolerances:
#  - LOC = 1e-8 in (alpha, beta) for a point located by Newton with exact
#    derivatives (CP, GPD, LP, PD, and a border GR, BR met by a curve):
#    such points agree with the branch task's independent locations to
#    ~1e-14 (docs/curves.md), and two curves meeting at one point agree to
#    1.1e-13; 1e-8 leaves room for changes in the steps that reach them
#    while a point on another curve or another border would be 1e-3 off.
#  - TP: the coordinate that turns (alpha max: alpha) to LOC; the other
#    moves like the square root of the error of the first (the curve is
#    a parabola there), so to TURN = 1e-5.
#  - END = 1e-2 for where a curve stops next to d* (a residual floor, not
#    a located point: where the corrector gives up depends on the step);
#    the end is promised near a border point, not at it.
#  - the box's edge: the coordinate on the edge exactly, the other to
#    EDGE = 1e-3 (docs/curves.md gives it to 4 digits).
# Usage: sh tests/curve_examples.sh PATH/TO/slipcont SOURCE_DIR CURVE_POINTS
# (CURVE_POINTS: the test program tests/curve_points.c, which recomputes
# the points of a fold or flip curve from the map layer alone.)
. "$(dirname "$0")/cli_common.sh"
CURVE_POINTS=${3:?usage: curve_examples.sh SLIPCONT SOURCE_DIR CURVE_POINTS}

LOC=1e-8
TURN=1e-5
END=1e-2
EDGE=1e-3
EX=$SRC/examples

# The scenes write to out/NAME (curve-fig57b reads the others from there).
mkdir -p "$TMP/w"
cd "$TMP/w" || exit 1

# curve NAME [ARGS...]: run examples/NAME.ini into out/NAME.
curve() {
  name=$1
  shift
  # shellcheck disable=SC2086
  $limit "$BIN" run "$EX/$name.ini" --quiet $plotset "$@" \
    >"$TMP/stdout" 2>"$TMP/stderr"
  RC=$?
  ERR=$(cat "$TMP/stderr")
  expect_rc "$name" 0
  no_temporaries "$name" "out/$name"
  D=out/$name
}

# residual NAME MAX: the summary's largest residual of the defining system
# over the curve's points is at most MAX (and the line is there).
residual() {
  r=$(sed -n 's/.*largest residual of the defining system over the points: //p' \
    "out/$1/summary.txt")
  check "$1: every point on its defining system, largest residual $r <= $2" \
    awk -v r="$r" -v m="$2" 'BEGIN { exit !(r != "" && r + 0 <= m + 0) }'
}

# recompute NAME fold|flip: every point of the curve, recomputed from the
# map layer alone, on f^m(d) = d, (f^m)' = +-1 to 1e-10 (curve_points.c).
recompute() {
  "$CURVE_POINTS" "$EX/$1.ini" "out/$1/curve.csv" "$2" >"$TMP/cp.out" 2>&1
  r=$?
  check "$1: recomputed from the map: $(tail -n 1 "$TMP/cp.out")" test $r -eq 0
  [ $r -eq 0 ] || cat "$TMP/cp.out"
}

# at NAME LABEL X Y TOLX TOLY: points.csv has a LABEL row within TOLX of
# X and TOLY of Y.
at() {
  got=$(awk -F, -v l="$2" '$1 == l { printf "(%s, %s) ", $2, $3 }' "out/$1/points.csv")
  check "$1: $2 at ($3, $4) to ($5, $6); rows: $got" \
    awk -F, -v l="$2" -v x="$3" -v y="$4" -v tx="$5" -v ty="$6" '
      function abs(v) { return v < 0 ? -v : v }
      $1 == l && abs($2 - x) <= tx + 0 && abs($3 - y) <= ty + 0 { ok = 1 }
      END { exit !ok }' "out/$1/points.csv"
}

# count NAME LABEL N: exactly N rows labelled LABEL in points.csv.
count() {
  n=$(awk -F, -v l="$2" '$1 == l' "out/$1/points.csv" | wc -l)
  check "$1: $3 $2 row(s) (got $n)" test "$n" -eq "$3"
}

# ends NAME X Y TOL: one end of the curve (the last point of a piece of
# curve.csv, whose pieces are separated by a blank line, or an EP row)
# within TOL of (X, Y) in both coordinates.
ends() {
  check "$1: ends at ($2, $3) to $4" awk -F, -v x="$2" -v y="$3" -v t="$4" '
    function abs(v) { return v < 0 ? -v : v }
    function near(a, b) { return abs(a - x) <= t + 0 && abs(b - y) <= t + 0 }
    FILENAME ~ /points/ && $1 == "EP" && near($2, $3) { ok = 1 }
    FILENAME ~ /curve.csv/ && FNR > 1 && NF == 0 && have && near(lx, ly) { ok = 1 }
    FILENAME ~ /curve.csv/ && FNR > 1 && NF > 1 { lx = $1; ly = $2; have = 1 }
    END { if (have && near(lx, ly)) ok = 1; exit !ok }' \
    "out/$1/points.csv" "out/$1/curve.csv"
}

# start NAME X Y: the curve's first point is the corrected start (X, Y),
# to LOC: a fold or flip located at fixed y.
start() {
  check "$1: starts on the point located at ($2, $3)" awk -F, -v x="$2" -v y="$3" -v t="$LOC" '
    function abs(v) { return v < 0 ? -v : v }
    FNR == 2 { exit !(abs($1 - x) <= t && abs($2 - y) <= t) }' "out/$1/curve.csv"
}

# multipliers NAME M: every point's multiplier (f^m)' is M, the fold's +1
# or the flip's -1, to 1e-10: the second equation of the promised system,
# read from curve.csv rather than from the summary.
multipliers() {
  check "$1: every point's multiplier is $2 to 1e-10" awk -F, -v m="$2" '
    function abs(v) { return v < 0 ? -v : v }
    NR > 1 && NF > 1 && abs($5 - m) > 1e-10 { print "  " $0; bad = 1 }
    END { exit bad }' "out/$1/curve.csv"
}

# on_border NAME: a border curve: every point's border value (the
# coefficient column of a border curve, docs/curves.md) is 0 to 1e-10.
on_border() {
  check "$1: every point on its border to 1e-10" awk -F, '
    function abs(v) { return v < 0 ? -v : v }
    NR > 1 && NF > 1 && abs($6) > 1e-10 { print "  " $0; bad = 1 }
    END { exit bad }' "out/$1/curve.csv"
}

# --- Fig 5.8 (driver frozen, beta = 2.5) --------------------------------

# The period-1 flip: f' = -1 everywhere; its cubic coefficient changes
# sign once in the box, at the GPD (3.8953, 1.1806), supercritical above.
curve curve-fig58-flip1
residual curve-fig58-flip1 1e-10
recompute curve-fig58-flip1 flip
multipliers curve-fig58-flip1 -1
count curve-fig58-flip1 GPD 1
at curve-fig58-flip1 GPD 3.8952574874430668 1.1805705417406247 $LOC $LOC
check "curve-fig58-flip1: the coefficient changes sign once along the curve" \
  awk -F, 'NR > 1 && NF > 1 { s = ($6 > 0) - ($6 < 0);
    if (s != 0 && p != 0 && s != p) n++; if (s != 0) p = s }
    END { exit !(n == 1) }' "$D/curve.csv"
check "curve-fig58-flip1: supercritical (c > 0) above the GPD, subcritical below" \
  awk -F, 'NR > 1 && NF > 1 && $2 > 1.19 && $6 <= 0 { bad = 1 }
    NR > 1 && NF > 1 && $2 < 1.17 && $6 >= 0 { bad = 1 } END { exit bad }' "$D/curve.csv"
at curve-fig58-flip1 EP 2.1475 5 $EDGE 0
at curve-fig58-flip1 EP 3.9962 1.02 $EDGE 0

# The period-2 flip: up to the box (beta = 5) one way, a grazing the
# other, next to d*.
curve curve-fig58-flip2
residual curve-fig58-flip2 1e-10
recompute curve-fig58-flip2 flip
start curve-fig58-flip2 3.056846230053055 2.5
at curve-fig58-flip2 EP 2.2941 5 $EDGE 0
at curve-fig58-flip2 GR 3.4614585876326545 1.8005991474337746 $LOC $LOC
count curve-fig58-flip2 GPD 0

# The period-4 flip from 3.1525: meets BR at (3.5165, 2.1011) and goes
# on across it, turns in beta and alpha, ends next to SW both ways.
curve curve-fig58-flip4
residual curve-fig58-flip4 1e-10
recompute curve-fig58-flip4 flip
start curve-fig58-flip4 3.1525203451104247 2.5
at curve-fig58-flip4 BR 3.5164752156918295 2.1010655490689003 $LOC $LOC
at curve-fig58-flip4 TP 3.7694004669554912 1.8719796911447033 $TURN $LOC
at curve-fig58-flip4 TP 4.0847645143435685 2.0172429775183027 $LOC $TURN
ends curve-fig58-flip4 4.0012 2.1012 $END
ends curve-fig58-flip4 2.3362 4.7701 $END
count curve-fig58-flip4 GPD 0
check "curve-fig58-flip4: continued across BR with itinerary 1|2-12-1|1|2-12-2" \
  grep -q ',1|2-12-1|1|2-12-2$' "$D/curve.csv"

# The period-4 flip from 3.6371: to the box at beta = 5; two TPs, then
# next to SW near (4.0006, 2.1013).
curve curve-fig58-flip4b
residual curve-fig58-flip4b 1e-10
recompute curve-fig58-flip4b flip
start curve-fig58-flip4b 3.6370578685629686 2.5
at curve-fig58-flip4b TP 4.0206897817725737 2.1133544094451633 $LOC $TURN
at curve-fig58-flip4b TP 4.0058590417400266 2.1008069698331129 $TURN $LOC
ends curve-fig58-flip4b 4.0006 2.1013 $END
at curve-fig58-flip4b EP 2.3878 5 $EDGE 0

# The period-1 fold: to the box at beta = 5, and to a grazing near
# (4.7949, 1.2950) that is not located (docs/curves.md).
curve curve-fig58-fold1
residual curve-fig58-fold1 1e-10
recompute curve-fig58-fold1 fold
multipliers curve-fig58-fold1 1
start curve-fig58-fold1 2.9925306744279285 2.5
at curve-fig58-fold1 EP 2.2065 5 $EDGE 0
ends curve-fig58-fold1 4.7949 1.2950 $END
count curve-fig58-fold1 CP 0

# The period-4 fold from 3.9338: meets BR at (3.9117, 2.4619) and goes on;
# both ends next to SW.
curve curve-fig58-fold4
residual curve-fig58-fold4 1e-10
recompute curve-fig58-fold4 fold
start curve-fig58-fold4 3.9337814025560522 2.5
at curve-fig58-fold4 BR 3.9117144697090729 2.4618506755426077 $LOC $LOC
ends curve-fig58-fold4 3.8930 2.4386 $END
ends curve-fig58-fold4 3.9681 2.5961 $END
check "curve-fig58-fold4: continued across BR with itinerary 2-12-1|1|2-12-2|1" \
  grep -q ',2-12-1|1|2-12-2|1$' "$D/curve.csv"

# The period-6 window: one closed fold curve, four turning points, no
# cusp, one itinerary all around.
curve curve-fig58-period6
residual curve-fig58-period6 1e-10
recompute curve-fig58-period6 fold
multipliers curve-fig58-period6 1
check "curve-fig58-period6: the curve is closed" \
  grep -q 'points, closed' "$D/summary.txt"
count curve-fig58-period6 TP 4
count curve-fig58-period6 CP 0
at curve-fig58-period6 TP 2.8390428310788667 3.2361019147514201 $LOC $TURN
at curve-fig58-period6 TP 2.8464374934759231 3.2517768278369217 $TURN $LOC
at curve-fig58-period6 TP 3.5187000576513654 2.2782305100061313 $LOC $TURN
at curve-fig58-period6 TP 3.5054429384489345 2.2646995988703944 $TURN $LOC
check "curve-fig58-period6: itinerary 1|1-12-2|1|2-12-2|1|2-12-2 all around" \
  awk -F, 'NR > 1 && NF > 1 && $7 != "1|1-12-2|1|2-12-2|1|2-12-2" { bad = 1 }
    END { exit bad }' "$D/curve.csv"

# The grazing curve of the period-4 orbit: a flip and a fold on the
# border, ends where it meets BR.
curve curve-fig58-graze4
residual curve-fig58-graze4 1e-10
on_border curve-fig58-graze4
at curve-fig58-graze4 PD 3.6957771603465366 2.7149217823876062 $LOC $LOC
at curve-fig58-graze4 LP 4.6025935552295492 1.923491656600016 $LOC $LOC
at curve-fig58-graze4 BR 4.9498332771522726 1.8581086979388139 $LOC $LOC

# The switching curve of the period-4 orbit: a flip on it, ends on BR at
# alpha = 4 exactly (the 1:2 resonance, docs/curves.md).
curve curve-fig58-switch4
residual curve-fig58-switch4 1e-10
on_border curve-fig58-switch4
at curve-fig58-switch4 PD 3.7286489413004813 2.185306186215068 $LOC $LOC
at curve-fig58-switch4 BR 4 2.1014465175860817 $LOC $LOC

# --- Fig 5.12 (driver frozen, beta = 3.2) -------------------------------

# The period-3 fold: the start corrected onto the LP at 5.63567 (beta
# 3.2), a cusp, a grazing where it ends, the box at beta = 5.
curve curve-fig512-period3
residual curve-fig512-period3 1e-10
recompute curve-fig512-period3 fold
multipliers curve-fig512-period3 1
start curve-fig512-period3 5.6356664070024074 3.2
count curve-fig512-period3 CP 1
at curve-fig512-period3 CP 5.3933341625625486 2.642191003026956 $LOC $LOC
at curve-fig512-period3 GR 5.6127725636684414 3.0487872861074194 $LOC $LOC
at curve-fig512-period3 EP 6.177 5 $EDGE 0

# The crossing-sliding curve of the period-2 orbit: to the box one way,
# meets the orbit's grazing the other.
curve curve-fig512-cross2
residual curve-fig512-cross2 1e-10
on_border curve-fig512-cross2
at curve-fig512-cross2 GR 5.3472417144 2.9046195874 $LOC $LOC
at curve-fig512-cross2 EP 6.3069 5 $EDGE 0

# The grazing curve of the period-3 orbit: its fold LP is the point where
# the period-3 fold curve meets GR (two curves, one point); a flip below.
curve curve-fig512-graze3
residual curve-fig512-graze3 1e-10
on_border curve-fig512-graze3
at curve-fig512-graze3 LP 5.6127725636684414 3.0487872861074194 $LOC $LOC
at curve-fig512-graze3 PD 5.2258845991 2.0608585458 $LOC $LOC
at curve-fig512-graze3 EP 6.2275 5 $EDGE 0

# --- Fig 5.7(b): the grazing curve over the chart, with every curve -------

# The chart at 30 x 20 points instead of 150 x 100 (the curves are drawn
# over it; only its beta = 1 row is promised: period 1 everywhere).
$limit "$BIN" run "$EX/chart-fig57b-window.ini" --quiet $plotset \
  --set task.x-steps=30 --set task.y-steps=20 >"$TMP/stdout" 2>"$TMP/stderr"
RC=$?
ERR=$(cat "$TMP/stderr")
expect_rc chart-fig57b-window 0
check "chart-fig57b-window: beta = 1 is period 1 everywhere" awk -F, '
  NR > 1 && $2 == 1 { n++; if ($3 != 1) bad = 1 } END { exit bad || n != 30 }' \
  out/chart-fig57b-window/chart.csv
curve curve-fig57b
residual curve-fig57b 1e-10
on_border curve-fig57b
at curve-fig57b PD 3.6957771603465366 2.7149217823876062 $LOC $LOC
at curve-fig57b BR 4.9498332771522726 1.8581086979388139 $LOC $LOC
check "curve-fig57b: the chart drawn under the curves" \
  grep -q "out/chart-fig57b-window/chart.csv' skip 1 using" "$D/curve.gp"
for other in curve-fig58-flip1 curve-fig58-flip2 curve-fig58-flip4 \
  curve-fig58-flip4b curve-fig58-fold1 curve-fig58-fold4 curve-fig58-period6 \
  curve-fig58-switch4 curve-fig512-period3 curve-fig512-cross2 \
  curve-fig512-graze3; do
  check "curve-fig57b: draws $other" grep -q "out/$other/curve.csv'" "$D/curve.gp"
done
if [ -z "$plotset" ]; then
  check "curve-fig57b: curve.png rendered" test -s "$D/curve.png"
fi

finish
