# The three-block chain's examples (docs/chain.md, "Three blocks"), each
# claim against a computation of its own: a chart point's period against
# the map iterated directly (orbit task), the branch's flips against the
# multipliers of the fixed-point task on both sides, its borders against
# the itineraries of the orbit on both sides and a closed form, and the
# sweep's periods.
. "$(dirname "$0")/cli_common.sh"

# scene NAME: the common model lines of the orbit and fixed-point runs
scene() {
  cat >"$TMP/$1.ini" <<'INI'
[model]
name = chain
blocks = 3
driver = frozen
phi = 1.25
v = 0.025
beta3 = 3
INI
}

run_within 120 run "$SRC/examples/chain3-chart.ini" --out "$TMP/chart" \
  --quiet --set output.plot=no
expect_rc "examples/chain3-chart.ini" 0
expect_rows "chain3-chart: chart.csv" "$TMP/chart/chart.csv" 2025

# The chart points to check: the three named in the example's comment
# and the first point of each period 1..8 (alpha, beta3, period, d1,
# iterations).
awk -F, 'function abs(x) { return x < 0 ? -x : x }
  NR == 1 { next }
  (abs($1 - 2.8) < 1e-9 && abs($2 - 3) < 1e-9 && $3 == 2) ||
  (abs($1 - 3.6) < 1e-9 && abs($2 - 3) < 1e-9 && $3 == 4) ||
  (abs($1 - 3.9) < 1e-9 && abs($2 - 3.5) < 1e-9 && $3 == 3) { print $1, $2, $3, $4, $5; named++ }
  $3 >= 1 && $3 <= 8 && !seen[$3]++ { print $1, $2, $3, $4, $5 }
  END { exit named != 3 }' "$TMP/chart/chart.csv" >"$TMP/points"
check "chain3-chart: period 2 at (2.8, 3), 4 at (3.6, 3), 3 at (3.9, 3.5)" \
  test $? -eq 0
check "chain3-chart: at least 8 points to check" test "$(wc -l <"$TMP/points")" -ge 8

check "chain3-chart: no invariant circle in the window" \
  grep -Eq '^ +invariant circle +0 points' "$TMP/chart/summary.txt"

# Each point iterated 1000 times from the chart's d0 = (0.1, 0.2): the
# last state repeats after p iterates (1e-9), after no fewer (1e-7 apart:
# p is minimal), and the chart's d1 is the orbit's at the chart's count
# of iterates (1e-12: the same evaluations; near a flip an orbit
# converges slowly, its two halves alternating ~1e-8 at that count).
scene orbit
printf '[task]\nkind = orbit\nd0 = 0.1 0.2\niterations = 1000\n[output]\nplot = no\n' \
  >>"$TMP/orbit.ini"
bad=0
k=0
while read -r a b p d1 it; do
  k=$((k + 1))
  run_within 60 run "$TMP/orbit.ini" --out "$TMP/o$k" --quiet \
    --set model.alpha="$a" --set model.beta3="$b"
  awk -F, -v p="$p" -v d1="$d1" -v it="$it" 'function abs(x) { return x < 0 ? -x : x }
    NR > 1 { x[$1] = $2; y[$1] = $3; n = $1 }
    END { if (abs(x[n] - x[n - p]) > 1e-9 || abs(y[n] - y[n - p]) > 1e-9) exit 1
      for (q = 1; q < p; q++)
        if (abs(x[n] - x[n - q]) + abs(y[n] - y[n - q]) < 1e-7) exit 1
      exit abs(x[it] - d1) > 1e-12 }' "$TMP/o$k/orbit.csv" ||
    { echo "period $p at alpha $a, beta3 $b: not so when iterated"; bad=1; }
done <"$TMP/points"
check "chain3-chart: $k points' periods confirmed by iterating the map" test $bad -eq 0

run_within 120 run "$SRC/examples/chain3-sweep.ini" --out "$TMP/sweep" \
  --quiet --set output.plot=no
expect_rc "examples/chain3-sweep.ini" 0
run_within 120 run "$SRC/examples/chain3-branch.ini" --out "$TMP/branch" \
  --quiet --set output.plot=no
expect_rc "examples/chain3-branch.ini" 0

# The branch's rows: label, alpha, multiplier, residual, method,
# coefficient
awk -F, 'NR > 1 { print $1, $3, $7, $12, $15, $9 }' "$TMP/branch/points.csv" >"$TMP/rows"
pd=$(awk '$1 == "PD" && $2 > 3.1 && $2 < 3.3 { print $2 }' "$TMP/rows")
pd2=$(awk '$1 == "PD" && $2 > 4.1 { print $2 }' "$TMP/rows")
# With the map's exact second derivatives every flip and the NS are
# located by Newton on their systems and certified by their residual;
# their normal-form coefficients: the flips at 3.1955 and 3.0814
# supercritical (b = 393.66, 1154.6), the one at 4.1656 subcritical (b =
# -7.8e4), the NS subcritical (d = 5967 > 0).
check "chain3-branch: flips at 3.1955 (b > 0), 4.1656 (b < 0), 3.0814 (b > 0): Newton, multiplier -1 and residual within 1e-12" \
  awk 'function abs(x) { return x < 0 ? -x : x }
    $1 == "PD" { n++; if (abs($3 + 1) < 1e-12 && $4 <= 1e-12 && $5 == "newton" &&
                         ((abs($2 - 3.1955) < 1e-3 && $6 > 0) ||
                          (abs($2 - 4.1656) < 1e-3 && $6 < 0) ||
                          (abs($2 - 3.0814) < 1e-3 && $6 > 0))) ok++ }
    END { exit !(n == 3 && ok == 3) }' "$TMP/rows"
check "chain3-branch: the NS at 3.0430 by Newton (residual within 1e-12, |multiplier| 1 to 1e-12), d > 0" \
  awk 'function abs(x) { return x < 0 ? -x : x }
    $1 == "NS" { n++; if (abs($2 - 3.0430) < 1e-3 && abs($3 - 1) < 1e-12 &&
                         $4 <= 1e-12 && $5 == "newton" && $6 > 0) ok++ }
    END { exit !(n == 1 && ok == 1) }' "$TMP/rows"
check "chain3-branch: the flips' notes say supercritical, subcritical, supercritical" \
  sh -c 'grep -q "^PD,alpha,3.1955.*supercritical (b > 0)" "$1" &&
         grep -q "^PD,alpha,3.0813.*supercritical (b > 0)" "$1" &&
         grep -q "^PD,alpha,4.1656.*subcritical" "$1"' _ "$TMP/branch/points.csv"
# The borders, located by Newton with their residual certificates: down,
# blocks 1 and 2 re-stick at once in the fourth phase of the third
# iterate (BR, alpha 3.1362112258); the branch goes on past it with
# that slip's new end (12-2) down to the switching where the third
# iterate's blocks 1 and 3 have equal gaps (SW, alpha 3.0136089483).
check "chain3-branch: a BR at 3.1362112258 and a SW at 3.0136089483, each by Newton with residual <= 1e-12" \
  awk 'function abs(x) { return x < 0 ? -x : x }
    $1 == "BR" && abs($2 - 3.1362112258) < 1e-9 && $4 <= 1e-12 && $5 == "newton" { br++ }
    $1 == "SW" && abs($2 - 3.0136089483) < 1e-9 && $4 <= 1e-12 && $5 == "newton" { sw++ }
    END { exit !(br == 1 && sw == 1) }' "$TMP/rows"
check "chain3-branch: the BR's note: both re-stick, the branch continues on the other side" \
  grep -q "^BR,.*BR of iterate 3: U1 - W; U2 - W at once; phase 4 .*continues on the other side" \
  "$TMP/branch/points.csv"
check "chain3-branch: the upper end at alpha 4.19284 (a re-stick grazing from the side where it fires)" \
  awk 'function abs(x) { return x < 0 ? -x : x }
    $1 == "EP" && abs($2 - 4.19284) < 1e-5 { n++ } END { exit n != 1 }' "$TMP/rows"

# The BR by brute force: the period-4 orbit found by the fixed-point task
# at alpha 1e-11 above and below the located point, each iterated by the
# orbit task: its third iterate's slip ends 12-1 above, 12-2 below.
br=$(awk '$1 == "BR" { print $2 }' "$TMP/rows")
brd=$(awk -F, '$1 == "BR" { print $4, $5 }' "$TMP/branch/points.csv")
scene fpb
printf '[task]\nkind = fixed-point\nperiod = 4\n[output]\nplot = no\n' >>"$TMP/fpb.ini"
scene orbb
printf '[task]\nkind = orbit\niterations = 4\n[output]\nplot = no\n' >>"$TMP/orbb.ini"
for s in 1 -1; do
  a=$(awk -v a="${br:-0}" -v s=$s 'BEGIN { printf "%.17g", a + s * 1e-11 }')
  run_within 60 run "$TMP/fpb.ini" --out "$TMP/fpb$s" --quiet \
    --set model.alpha="$a" --set "task.d0=$brd"
  d=$(awk -F, 'NR == 2 { k = split($NF, p, ";"); print p[k - 1] }' "$TMP/fpb$s/orbits.csv")
  run_within 60 run "$TMP/orbb.ini" --out "$TMP/orbb$s" --quiet \
    --set model.alpha="$a" --set "task.d0=$d"
done
check "chain3-branch: the BR by brute force: iterate 3 ends 12-1 at +1e-11, 12-2 at -1e-11" \
  sh -c 'grep -q "^2,.*,1-12-123-12-1\$" "$1" && grep -q "^2,.*,1-12-123-12-2\$" "$2"' _ \
  "$TMP/orbb1/orbit.csv" "$TMP/orbb-1/orbit.csv"

# The SW by brute force: the orbit task iterates the located point twice;
# there the gaps of blocks 1 and 3, in closed form, differ by
# (1 + alpha)(d1 + d2) - 2: zero within 1e-12; a step of 1e-9 along
# (1, 1) either way starts the slip at block 3 or at block 1.
sw=$(awk '$1 == "SW" { print $2 }' "$TMP/rows")
swd=$(awk -F, '$1 == "SW" { print $4, $5 }' "$TMP/branch/points.csv")
printf '[task]\nkind = orbit\niterations = 2\n[output]\nplot = no\n' >"$TMP/orbs.tail"
scene orbs
cat "$TMP/orbs.tail" >>"$TMP/orbs.ini"
run_within 60 run "$TMP/orbs.ini" --out "$TMP/orbs" --quiet \
  --set model.alpha="$sw" --set "task.d0=$swd"
x2=$(awk -F, '$1 == 2 { printf "%.17g %.17g", $2, $3 }' "$TMP/orbs/orbit.csv")
check "chain3-branch: the SW's third iterate starts where gap 1 = gap 3 (1e-12)" \
  awk -v a="${sw:-0}" -v x="$x2" 'BEGIN { split(x, d, " "); g = (1 + a) * (d[1] + d[2]) - 2
    exit !(x != "" && (g < 0 ? -g : g) < 1e-12) }'
scene orbs1
printf '[task]\nkind = orbit\niterations = 1\n[output]\nplot = no\n' >>"$TMP/orbs1.ini"
for s in 1 -1; do
  d=$(awk -v x="$x2" -v s=$s 'BEGIN { split(x, d, " "); printf "%.17g %.17g", d[1] + s * 1e-9, d[2] + s * 1e-9 }')
  run_within 60 run "$TMP/orbs1.ini" --out "$TMP/orbs1$s" --quiet \
    --set model.alpha="$sw" --set "task.d0=$d"
done
check "chain3-branch: the SW by brute force: block 3 starts on one side, block 1 on the other" \
  sh -c 'grep -q "^0,.*,3-23-" "$1" && grep -q "^0,.*,1-" "$2"' _ \
  "$TMP/orbs11/orbit.csv" "$TMP/orbs1-1/orbit.csv"

# The flip by brute force: the period-4 orbit's multiplier from the
# fixed-point task below -1 at 3.185, above at 3.205, and its linear
# interpolation at -1 within 1e-3 of the branch's PD.
scene fp
printf '[task]\nkind = fixed-point\nperiod = 4\nd0 = 0.1435 0.3552\n[output]\nplot = no\n' \
  >>"$TMP/fp.ini"
for a in 3.185 3.205; do
  run_within 60 run "$TMP/fp.ini" --out "$TMP/fp$a" --quiet --set model.alpha=$a
  expect_rc "period 4 at alpha = $a" 0
done
check "chain3-branch: the flip, multiplier -1 crossed between 3.185 and 3.205 near the PD" \
  awk -F, -v pd="${pd:-0}" 'function abs(x) { return x < 0 ? -x : x }
    FNR == 2 { m[++k] = $2; if ($1 != 4) exit 1 }
    END { if (k != 2 || !(m[1] < -1 && m[2] > -1)) exit 1
      a = 3.185 + 0.02 * (-1 - m[1]) / (m[2] - m[1])
      exit abs(a - pd) > 1e-3 }' "$TMP/fp3.185/orbits.csv" "$TMP/fp3.205/orbits.csv"
for a in 4.163 4.168; do
  run_within 60 run "$TMP/fp.ini" --out "$TMP/fp$a" --quiet --set model.alpha=$a \
    --set "task.d0=0.1477 0.2815"
  expect_rc "period 4 at alpha = $a" 0
done
check "chain3-branch: the upper flip, multiplier -1 crossed between 4.163 and 4.168 near its PD" \
  awk -F, -v pd="${pd2:-0}" 'function abs(x) { return x < 0 ? -x : x }
    FNR == 2 { m[++k] = $2; if ($1 != 4) exit 1 }
    END { if (k != 2 || !(m[1] > -1 && m[2] < -1)) exit 1
      a = 4.163 + 0.005 * (-1 - m[1]) / (m[2] - m[1])
      exit abs(a - pd) > 1e-3 }' "$TMP/fp4.163/orbits.csv" "$TMP/fp4.168/orbits.csv"

# Below the flip the orbit from its point settles on period 8 (1e-7
# after 3000 iterates), its two halves apart by a width that grows away
# from the flip (0.014 at 3.18, 0.038 at 3.17): a supercritical flip,
# seen by iteration, as the sign of its coefficient says.
scene orb8
printf '[task]\nkind = orbit\nd0 = 0.1435 0.3552\niterations = 3000\n[output]\nplot = no\n' \
  >>"$TMP/orb8.ini"
for a in 3.18 3.17; do
  run_within 60 run "$TMP/orb8.ini" --out "$TMP/orb8-$a" --quiet --set model.alpha=$a
done
check "chain3-branch: below the flip a stable period-8 orbit, its halves parting away from it" \
  awk -F, 'function abs(x) { return x < 0 ? -x : x }
    FNR == 1 { f++; next }
    { x[f, $1] = $2; y[f, $1] = $3; n = $1 }
    END { for (k = 1; k <= 2; k++) {
        if (abs(x[k, n] - x[k, n - 8]) + abs(y[k, n] - y[k, n - 8]) > 1e-7) exit 1
        w[k] = abs(x[k, n] - x[k, n - 4]) + abs(y[k, n] - y[k, n - 4]) }
      exit !(w[1] > 1e-3 && w[2] > 2 * w[1] && w[2] < 0.1) }' \
  "$TMP/orb8-3.18/orbit.csv" "$TMP/orb8-3.17/orbit.csv"

# The flip's coefficient b against its period-8 orbit: on the centre
# manifold f^4 is w -> -(1 + e) w + b w^3 (docs/maps.md, "Normal forms";
# |q| = 1, e = -1 - the period-4 multiplier), so the period-8 orbit's two
# halves are 2 w apart with w^2 = e / b + O(e^2).  The fixed-point task's
# period-8 orbits at alpha 3.194 and 3.1925 (the switched branch lives
# between its border at 3.1903 and the flip) and the period-4
# multipliers there give e / w^2 at the orbit's pair nearest the flip's
# point (386 and 390), extrapolated linearly to e = 0: b within 1%
# (observed 393.7 against 393.66).
sed 's/period = 4/period = 8/; s/^d0 = .*/d0 = 0.14297 0.35920/' \
  "$TMP/fp.ini" >"$TMP/fp8.ini"
for a in 3.194 3.1925; do
  run_within 60 run "$TMP/fp.ini" --out "$TMP/nf4-$a" --quiet --set model.alpha=$a
  run_within 60 run "$TMP/fp8.ini" --out "$TMP/nf8-$a" --quiet --set model.alpha=$a
  expect_rc "period 8 at alpha = $a" 0
done
pdrow=$(awk -F, '$1 == "PD" && $3 > 3.1 && $3 < 3.3 { print $4, $5, $9 }' "$TMP/branch/points.csv")
check "chain3-branch: the flip's b from its period-8 orbit's width (1%)" \
  awk -F, -v pdrow="$pdrow" 'function abs(x) { return x < 0 ? -x : x }
    FNR == 1 { f++; next }
    f % 2 == 1 { e[(f + 1) / 2] = -1 - $2; next }
    { split(pdrow, P, " "); n = split($8, Q, ";"); best = 1e9
      for (k = 1; k <= n; k++) { split(Q[k], q, " "); x[k] = q[1]; y[k] = q[2] }
      for (k = 1; k <= n / 2; k++) {
        dx = x[k] - x[k + n / 2]; dy = y[k] - y[k + n / 2]
        m = abs((x[k] + x[k + n / 2]) / 2 - P[1]) + abs((y[k] + y[k + n / 2]) / 2 - P[2])
        if (m < best) { best = m; w2 = (dx * dx + dy * dy) / 4 } }
      est[f / 2] = e[f / 2] / w2 }
    END { if (f != 4 || !(e[1] > 0 && e[2] > e[1])) exit 1
      b0 = est[1] - e[1] * (est[2] - est[1]) / (e[2] - e[1])
      printf "b %s, from the period-8 orbits %.6g, %.6g -> %.6g\n", P[3], est[1], est[2], b0
      exit abs(b0 - P[3]) > 0.01 * P[3] }' \
  "$TMP/nf4-3.194/orbits.csv" "$TMP/nf8-3.194/orbits.csv" \
  "$TMP/nf4-3.1925/orbits.csv" "$TMP/nf8-3.1925/orbits.csv"

# The drawing agrees: below the flip (unstable by the fixed-point task at
# 3.185) the branch is drawn dashed, above it solid, the flip in both
# (the branch's own point there, within 1e-9 of the Newton-located one).
check "chain3-branch: branch-orbits.csv stable between the two flips, unstable outside (down to the BR)" \
  awk -F, -v pd="${pd:-0}" -v pd2="${pd2:-0}" -v br="${br:-9}" 'function abs(x) { return x < 0 ? -x : x }
    NR <= 2 || NF < 5 || $1 + 0 < br { next }
    abs($1 - pd) < 1e-9 || abs($1 - pd2) < 1e-9 { if (!($2 != "nan" && $3 != "nan")) bad = 1; next }
    ($1 + 0 < pd || $1 + 0 > pd2) && !($2 == "nan" && $3 != "nan") { bad = 1 }
    $1 + 0 > pd && $1 + 0 < pd2 && !($2 != "nan" && $3 == "nan") { bad = 1 }
    { n++ } END { exit bad || n < 40 }' "$TMP/branch/branch-orbits.csv"

# Curves in (alpha, beta3) from the branch's rows (start = FILE:N; the
# examples read out/chain3-branch, here the branch run above): the flip
# curves of the PDs at 3.1955 (examples/chain3-curve-flip.ini, row 3)
# and 3.0814 (examples/chain3-curve-flip2.ini, row 5) and the NS curve
# of its NS (examples/chain3-curve-ns.ini, row 6), each ended where the
# itinerary of f^4 changes (a border the curves do not locate) or at
# the box.  Located by Newton on their extended systems: a generalized
# flip (GPD, b = 0) on the first at (3.23297, 2.89819), a 1:2 resonance
# (R2, a double multiplier -1) on the second at (3.06212, 3.28270),
# which the NS curve reaches too (its kappa -> -1 there: its R2 row
# within 2e-4 of the flip curve's; the NS system is nearly singular at
# R2, and its Newton converges (the same point to 1e-14) or stops at a
# residual of 1e-12 (R2?, 9e-5 away), as the rounding of the build
# goes).  About 1.5 s of processor time.
mkdir -p "$TMP/ex/out"
ln -s "$TMP/branch" "$TMP/ex/out/chain3-branch"
for ex in chain3-curve-ns chain3-curve-flip2 chain3-curve-flip; do
  (cd "$TMP/ex" || exit 1
    run_within 60 run "$SRC/examples/$ex.ini" --quiet --set output.plot=no
    exit "$RC")
  RC=$?
  ERR=$(cat "$TMP/stderr")
  expect_rc "examples/$ex.ini" 0
done
for c in cflip:chain3-curve-flip cflip2:chain3-curve-flip2 cns:chain3-curve-ns; do
  ln -s "$TMP/ex/out/${c#*:}" "$TMP/${c%%:*}"
done
check "chain3-curves: the first flip curve's GPD at (3.23297, 2.89819), residual <= 1e-12, b > 0 within 0.02 below it in alpha, < 0 above" \
  awk -F, 'function abs(x) { return x < 0 ? -x : x }
    FNR == 1 { f++; next }
    f == 1 && $1 == "GPD" { n++; if (abs($2 - 3.23297) < 1e-5 && abs($3 - 2.89819) < 1e-5 &&
                                   $9 <= 1e-12) ok++ }
    f == 2 && $1 > 3.21297 && $1 < 3.23297 { before++; if ($7 <= 0) bad++ }
    f == 2 && $1 > 3.23297 && $1 < 3.25297 { after++; if ($7 >= 0) bad++ }
    END { exit !(n == 1 && ok == 1 && before > 0 && after > 0 && !bad) }' \
  "$TMP/cflip/points.csv" "$TMP/cflip/curve.csv"
check "chain3-curves: each curve ends where the itinerary changes (at least at one end)" \
  sh -c 'for f; do grep -q "^EP,.*the itinerary changes between" "$f" || exit 1; done' _ \
  "$TMP/cflip/points.csv" "$TMP/cflip2/points.csv" "$TMP/cns/points.csv"
r2=$(awk -F, '$1 == "R2" { print $2, $3, $4, $5, $9 }' "$TMP/cflip2/points.csv")
check "chain3-curves: the second flip curve's R2 at (3.06212, 3.28270), residual <= 1e-12; the NS curve's R2 within 2e-4 of it" \
  awk -v r2="$r2" -F, 'function abs(x) { return x < 0 ? -x : x }
    BEGIN { split(r2, R, " ") }
    $1 ~ /^R2/ && abs($2 - R[1]) + abs($3 - R[2]) < 2e-4 { near++ }
    END { exit !(abs(R[1] - 3.06212) < 1e-5 && abs(R[2] - 3.28270) < 1e-5 &&
                 R[5] <= 1e-12 && near == 1) }' "$TMP/cns/points.csv"
# The R2 by the fixed-point task (the map's J only): the period-4 orbit
# at the R2's parameters has both multipliers -1, to the square root of
# the point's accuracy (a Jordan block splits as the root of a
# perturbation: 1e-15 gives 3e-8; within 1e-6).
set -- $r2
run_within 60 run "$TMP/fp.ini" --out "$TMP/fpr2" --quiet --set model.alpha="${1:-0}" \
  --set model.beta3="${2:-0}" --set "task.d0=${3:-0} ${4:-0}"
check "chain3-curves: at the R2 the fixed-point task's multipliers are -1, -1 (1e-6)" \
  awk -F, 'function abs(x) { return x < 0 ? -x : x }
    NR == 2 { split($3, m, " "); ok = $1 == 4 && abs(m[1] + 1) < 1e-6 && abs(m[2] + 1) < 1e-6 }
    END { exit !ok }' "$TMP/fpr2/orbits.csv"

# The period-4 orbit loses its stability at the upper flip (4.1656): the
# sweep's last period-4 value is below it, its next value above, with no
# period.
check "chain3-sweep: period 2 up to 3.03, period 4 from 3.29 to 4.16, lost at the upper flip" \
  awk -F, 'function abs(x) { return x < 0 ? -x : x }
    NR == 1 { next }
    { per[$1] = $4 }
    END { for (s in per) { a = s + 0
        if (a < 3.03 && per[s] != 2) exit 1
        if (a > 3.29 && a < 4.16 && per[s] != 4) exit 1
        if (a > 4.1656 && per[s] == 4) exit 1 }
      exit 0 }' "$TMP/sweep/sweep.csv"

# The period-8 orbits of the sweep between 3.2 and 3.26 coexist with the
# stable period-4 orbit of the branch: they are not the flip's.
check "chain3-sweep: period 8 at some alpha in (3.2, 3.26), where the branch's period 4 is stable" \
  awk -F, 'FNR == 1 { f++; next }
    f == 1 && $1 > 3.2 && $1 < 3.26 && $4 == 8 { p8++ }
    f == 2 && $1 > 3.2 && $1 < 3.26 { nb++; if ($6 != "yes") bad = 1 }
    END { exit !(p8 > 0 && nb > 0 && !bad) }' "$TMP/sweep/sweep.csv" "$TMP/branch/branch.csv"

# The period-2 orbit's branch bends at alpha = 2.936 (sweep.png): the
# second iterate's slip starts at block 1 below it, at block 3 above.
scene orb2
printf '[task]\nkind = orbit\nd0 = 0.197 0.305\niterations = 300\n[output]\nplot = no\n' \
  >>"$TMP/orb2.ini"
for a in 2.93 2.945; do
  run_within 60 run "$TMP/orb2.ini" --out "$TMP/orb$a" --quiet --set model.alpha=$a
done
check "chain3-sweep: period 2 slips 1-12-123-12-1 at 2.93, 3-23-123-23-3 at 2.945" \
  sh -c 'tail -n 3 "$1" | grep -q "^[0-9]*,.*,2\$" &&
         tail -n 3 "$1" | grep -q ",1-12-123-12-1\$" &&
         tail -n 3 "$2" | grep -q ",3-23-123-23-3\$"' _ \
  "$TMP/orb2.93/orbit.csv" "$TMP/orb2.945/orbit.csv"
finish
