# The map, orbit, sweep and chart tasks on maps of n > 1 components
# (docs/maps.md, "Tasks for n-dimensional maps"): the examples
# henon-sweep and ghenon-chart with their known answers, closed forms of
# henon's fixed point and flip, the classes of known chart points, the
# show key, and a state of the wrong size refused by every task.
. "$(dirname "$0")/cli_common.sh"

EX="$SRC/examples"

# summary_has NAME TEXT
summary_has() {
  if grep -qF "$2" "$TMP/$1/summary.txt"; then pass "$1: summary says '$2'"
  else fail "$1: summary lacks '$2'"; fi
}

# scene NAME TEXT: a scene file $TMP/NAME.ini
scene() { printf '%s\n' "$2" >"$TMP/$1.ini"; }

# --- sweep: henon's period doublings ----------------------------------
example henon-sweep
expect_header henon-sweep "$TMP/henon-sweep/sweep.csv" "a,x1,x2,period,direction"
expect_rows henon-sweep "$TMP/henon-sweep/sweep.csv" 70100
summary_has henon-sweep "a from 0 to 0.36 (181 values): period 1"
summary_has henon-sweep "a from 0.37 to 0.91 (271 values): period 2"
summary_has henon-sweep "a from 0.914 to 1.024 (56 values): period 4"
png henon-sweep sweep.png
# y' = b x: every kept point is the image of the one before it (the rows
# of one value of a), its second component 0.3 times the first component
# of that one, exactly (one product, printed to 17 digits).
check "henon-sweep: y = b x of the point before, exactly" awk -F, '
  NR > 2 && $1 == pa { n++; if ($3 != 0.3 * px) { print "  " $0; bad = 1 } }
  NR > 1 { pa = $1; px = $2 }
  END { exit bad || n < 60000 }' "$TMP/henon-sweep/sweep.csv"

# The flip of the fixed point at a = 3 (1 - b)^2 / 4 = 0.3675: within a
# step of 0.001 the attractor splits from one point (spread 2e-6 after
# 20000 iterates at 0.367, where the multiplier -1 + 8e-4 still shrinks
# the transient slowly: below 1e-4) into two (0.13 apart at 0.368: the
# split grows like the square root of the distance to the flip).
run_within 120 run "$EX/henon-sweep.ini" --out "$TMP/flip" --quiet \
  --set output.plot=no --set task.from=0.36 --set task.to=0.375 \
  --set task.steps=16 --set task.iterations=20000 --set task.keep=64
expect_rc "flip sweep" 0
spread() {
  awk -F, -v a="$1" 'NR > 1 && ($1 - a) ^ 2 < 1e-12 {
    if (n++ == 0 || $2 < lo) lo = $2; if (n == 1 || $2 > hi) hi = $2 }
    END { printf "%.3g", hi - lo }' "$TMP/flip/sweep.csv"
}
below=$(spread 0.367)
above=$(spread 0.368)
check "flip: one point at a = 0.367 (spread $below)" \
  awk -v s="$below" 'BEGIN { exit !(s < 1e-4) }'
check "flip: two points at a = 0.368 (spread $above)" \
  awk -v s="$above" 'BEGIN { exit !(s > 0.05) }'
check "flip: 3 (1 - b)^2 / 4 lies between them" \
  awk 'BEGIN { f = 3 * 0.7 ^ 2 / 4; exit !(f > 0.367 && f < 0.368) }'
summary_has flip "a from 0.36 to 0.366 (7 values): period 1"

# show: the component or the norm the plot draws; a bad one refused.
run_sc run "$EX/henon-sweep.ini" --out "$TMP/show2" --quiet \
  --set output.plot=no --set task.steps=3 --set task.show=y
expect_rc "show = y" 0
check "show = y: the plot draws column 3" grep -qF "shown(c) = column(3)" \
  "$TMP/show2/sweep.gp"
run_sc run "$EX/henon-sweep.ini" --out "$TMP/shown" --quiet \
  --set output.plot=no --set task.steps=3 --set task.show=norm
check "show = norm: the plot draws the norm" \
  grep -qF 'shown(c) = (sqrt($2**2 + $3**2))' "$TMP/shown/sweep.gp"
run_sc run "$EX/henon-sweep.ini" --out "$TMP/show3" --quiet \
  --set output.plot=no --set task.show=3
expect_rc "show = 3" 2
expect_err "show = 3" "show = 3: model henon has 2 state components (valid: 1..2, a name (x, y), or norm)"

# --- chart: invariant circles, periods and chaos ------------------------
example ghenon-chart
expect_header ghenon-chart "$TMP/ghenon-chart/chart.csv" "alpha,beta,period,x1,iterations"
expect_rows ghenon-chart "$TMP/ghenon-chart/chart.csv" 13431
png ghenon-chart chart.png
# chart_class X Y: the period class at alpha = X, beta = Y
chart_class() {
  awk -F, -v x="$1" -v y="$2" 'NR > 1 && ($1 - x) ^ 2 < 1e-16 && ($2 - y) ^ 2 < 1e-16 { print $3 }' \
    "$TMP/ghenon-chart/chart.csv"
}
c=$(chart_class 0.3 0.9)
check "ghenon-chart: alpha = 0.3, beta = 0.9 on an invariant circle (class $c)" test "$c" = -3
c=$(chart_class 0.1 0.7)
check "ghenon-chart: alpha = 0.1, beta = 0.7 below the NS curve: period 1 ($c)" test "$c" = 1
check "ghenon-chart: gold in the key" grep -qF "title 'invariant circle'" \
  "$TMP/ghenon-chart/chart.gp"
# Every point below the Neimark-Sacker curve alpha = 2 (1 - beta)^2 + 1 -
# beta^2 by more than 0.02 and left of the escape's edge (alpha < 0.55)
# is period 1, or not settled (-2: a slow spiral into the fixed point,
# its multipliers' modulus near 1 close to the curve); every circle lies
# above the curve.
check "ghenon-chart: period 1 below the NS curve, circles above it" awk -F, '
  NR > 1 { ns = 2 * (1 - $2) ^ 2 + 1 - $2 ^ 2
    if ($1 < ns - 0.02 && $1 < 0.55 && $3 != 1 && $3 != -2) { print "  " $0; bad = 1 }
    if ($3 == -3) { n++; if ($1 < ns) { print "  " $0; bad = 1 } } }
  END { exit bad || n < 1000 }' "$TMP/ghenon-chart/chart.csv"
# henon at a = 1.4, b = 0.3: chaos, "high" (class 0), not a circle.
scene hchart "[model]
name = henon
[task]
kind = chart
x = a
x-from = 1.4
x-to = 1.41
x-steps = 2
y = b
y-from = 0.3
y-to = 0.31
y-steps = 2
[output]
plot = no"
run_sc run "$TMP/hchart.ini" --out "$TMP/hchart" --quiet
expect_rc "henon chart" 0
c=$(awk -F, 'NR == 2 { print $3 }' "$TMP/hchart/chart.csv")
check "henon chart: a = 1.4, b = 0.3 is chaos (class $c)" test "$c" = 0

# --- orbit: the fixed point's multipliers, an invariant circle ----------
scene horbit "[model]
name = henon
a = 0.2
b = 0.3
[task]
kind = orbit
d0 = 1 0.3
iterations = 400
[output]
plot = yes"
run_sc run "$TMP/horbit.ini" --out "$TMP/horbit" --quiet $plotset
expect_rc "henon orbit" 0
expect_header "henon orbit" "$TMP/horbit/orbit.csv" "k,x1,x2,itinerary"
expect_rows "henon orbit" "$TMP/horbit/orbit.csv" 401
summary_has horbit "period of the last 128 iterates: 1"
png horbit orbit.png
png horbit phase.png
# x = (-(1 - b) + sqrt((1 - b)^2 + 4 a)) / (2 a); multipliers -a x +-
# sqrt(a^2 x^2 + b), here 0.37160 and -0.80742: to 1e-12 (the Jacobian at
# the converged point, exact to the period rule's tolerance 1e-6 x its
# spread, here 0: the orbit is at rest to the last bits)
mults=$(sed -n 's/.*by decreasing modulus): \([^ ]*\) \([^ ]*\) (stable)$/\1 \2/p' \
  "$TMP/horbit/summary.txt")
check "henon orbit: multipliers $mults against the closed form" awk -v m="$mults" 'BEGIN {
  split(m, v, " "); a = 0.2; b = 0.3
  x = (-(1 - b) + sqrt((1 - b) ^ 2 + 4 * a)) / (2 * a)
  l1 = -a * x - sqrt(a * a * x * x + b); l2 = -a * x + sqrt(a * a * x * x + b)
  exit !((v[1] - l1) ^ 2 < 1e-24 && (v[2] - l2) ^ 2 < 1e-24) }'
scene gorbit "[model]
name = ghenon
R = -1
alpha = 0.3
beta = 0.9
[task]
kind = orbit
d0 = 0.1 0.1
iterations = 5000
[output]
plot = no"
run_sc run "$TMP/gorbit.ini" --out "$TMP/gorbit" --quiet
summary_has gorbit "an invariant circle (quasi-periodic)"

# --- map: a segment of states -------------------------------------------
scene hmap "[model]
name = henon
[task]
kind = map
from = -1 0
to = 1 0.2
steps = 11
[output]
plot = no"
run_sc run "$TMP/hmap.ini" --out "$TMP/hmap" --quiet
expect_rc "henon map" 0
expect_header "henon map" "$TMP/hmap/map.csv" "t,x1,x2,f_x1,f_x2,itinerary,status"
expect_rows "henon map" "$TMP/hmap/map.csv" 11
check "henon map: f = (1 - 1.4 x^2 + y, 0.3 x) on every row" awk -F, '
  NR > 1 { e1 = $4 - (1 - 1.4 * $2 * $2 + $3); e2 = $5 - 0.3 * $2
    if (e1 * e1 > 1e-30 || e2 * e2 > 1e-30) { print "  " $0; bad = 1 } n++ }
  END { exit bad || n != 11 }' "$TMP/hmap/map.csv"

# --- a state of the wrong size, refused by every task -------------------
for t in map orbit sweep chart; do
  case $t in
  map) keys="from = 0.1
to = 1 0.2" ;;
  orbit) keys="d0 = 0.1" ;;
  sweep) keys="parameter = a
from = 1
to = 1.4
d0 = 0.1" ;;
  chart) keys="x = a
x-from = 1
x-to = 1.4
y = b
y-from = 0.2
y-to = 0.3
d0 = 0.1" ;;
  esac
  scene "bad$t" "[model]
name = henon
[task]
kind = $t
$keys"
  run_sc run "$TMP/bad$t.ini" --out "$TMP/bad$t" --quiet
  expect_rc "$t with a 1-number state" 2
  expect_err "$t with a 1-number state" "holds 1 number; model henon has 2 state components: write 2 numbers (x y) separated by spaces"
  check "$t with a 1-number state: nothing written" test ! -e "$TMP/bad$t"
done

finish
