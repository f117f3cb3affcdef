# The fixed-point and branch example scenes run through the program and
# write what their tasks promise: headers, the known answers stated at the
# top of each scene, plots (when gnuplot is present), no temporaries.
# Usage: sh tests/branch_examples.sh PATH/TO/slipcont SOURCE_DIR
. "$(dirname "$0")/cli_common.sh"

# has NAME FILE PATTERN (extended regular expression)
has() {
  if grep -qE "$3" "$TMP/$1/$2"; then pass "$1: $2 has /$3/"
  else fail "$1: $2 lacks /$3/"; fi
}

example fixed-point-logistic
expect_header fixed-point-logistic "$TMP/fixed-point-logistic/orbits.csv" \
  "period,multiplier,stable,d,itinerary"
expect_rows fixed-point-logistic "$TMP/fixed-point-logistic/orbits.csv" 2
has fixed-point-logistic orbits.csv '^3,-0\.3949718068295[0-9]*,yes,0\.152074266627'
has fixed-point-logistic orbits.csv '^3,2\.320521806829[0-9]*,no,0\.167205272650'
png fixed-point-logistic fixed-point.png

example fixed-point-fig58
expect_rows fixed-point-fig58 "$TMP/fixed-point-fig58/orbits.csv" 2
has fixed-point-fig58 orbits.csv '^6,-0\.0740754[0-9]*,yes,0\.0991157087'
has fixed-point-fig58 orbits.csv '^6,2\.99815[0-9]*,no,0\.1019741644'
check "fixed-point-fig58: both orbits on the itinerary 1;1-12-2;1;2-12-2;1;2-12-2" \
  awk -F, 'NR > 1 { n++; if ($5 != "1;1-12-2;1;2-12-2;1;2-12-2") bad = 1 }
    END { exit bad || n != 2 }' "$TMP/fixed-point-fig58/orbits.csv"
png fixed-point-fig58 fixed-point.png

example fixed-point-family
expect_rows fixed-point-family "$TMP/fixed-point-family/orbits.csv" 4
has fixed-point-family orbits.csv '^2,1,family,-0\.05882352941[0-9]*\.\.-0\.0506498017[0-9]*,1;2$'
has fixed-point-family orbits.csv '^2,3\.969800275[0-9]*,no,'

example branch-logistic
expect_header branch-logistic "$TMP/branch-logistic/points.csv" \
  "label,parameter,value,d,period,multiplier,residual,error,method,border,note"
expect_header branch-logistic "$TMP/branch-logistic/branch.csv" \
  "r,d,multiplier,stable,itinerary,period,branch"
has branch-logistic points.csv '^PD,r,(2\.99999999999[0-9]*|3\.0000000000[0-9]*|3),'
has branch-logistic points.csv '^PD,r,3\.44948974278(31[0-9]*|32[0-9]*),'
has branch-logistic points.csv '^PD,r,3\.54409035955(19|20)[0-9]*,'
has branch-logistic points.csv '^PD,r,3\.564407266095(4|5)[0-9]*,'
png branch-logistic branch.png
png branch-logistic branch-map.png

example branch-fig58
has branch-fig58 points.csv '^PD,alpha,3\.05684623005[0-9]*,[0-9.]*,2,'
has branch-fig58 points.csv '^LP,alpha,3\.21955808[0-9]*,[0-9.]*,6,'
has branch-fig58 points.csv '^LP,alpha,3\.38782004[0-9]*,[0-9.]*,6,'
has branch-fig58 points.csv '^GR,alpha,3\.86139041[0-9]*,'
has branch-fig58 points.csv 'closes on itself'
# the orbit of alpha = 2.8 joins the period-1 branch (at its flip, 2.8252),
# which ends in a fold
has branch-fig58 points.csv '^PD,alpha,2\.82522610020[0-9]*,[0-9.]*,1,'
has branch-fig58 points.csv '^LP,alpha,2\.99253067442[0-9]*,[0-9.]*,1,'
png branch-fig58 branch.png

example branch-fig512
has branch-fig512 points.csv '^CS,alpha,5\.64875392[0-9]*,[0-9.]*,2,.*continues with period 1'
has branch-fig512 points.csv '^GR,alpha,5\.74937697[0-9]*,[0-9.]*,1,'
has branch-fig512 points.csv '^LP,alpha,5\.63566640[0-9]*,[0-9.]*,3,'
png branch-fig512 branch.png

example branch-symmetric
has branch-symmetric points.csv '^PD,v,0\.0206852436[0-9]*,[0-9.]*,2,'
has branch-symmetric points.csv '^PD,v,0\.0195011475[0-9]*,[0-9.]*,4,'
png branch-symmetric branch.png

# Refusals of bad scenes (exit status 2), before any work: the message
# names the file, line and key.
cat >"$TMP/bad-fp.ini" <<EOS
[model]
name = logistic
[task]
kind = fixed-point
period = 2
from = 1
to = 0
EOS
run_sc run "$TMP/bad-fp.ini" --out "$TMP/bad-fp" --quiet
expect_rc "fixed-point with to < from" 2
expect_err "fixed-point with to < from" "[task] to = 0 is not above from"
cat >"$TMP/bad-br.ini" <<EOS
[model]
name = logistic
[task]
kind = branch
parameter = r
from = 3
to = 3.5
d0 = 0.6
starts = 3.2 0.5
EOS
run_sc run "$TMP/bad-br.ini" --out "$TMP/bad-br" --quiet
expect_rc "branch with a malformed start" 2
expect_err "branch with a malformed start" "[task] starts: cannot read 'P D M' in '3.2 0.5'"
check "branch refused before writing anything" test ! -e "$TMP/bad-br/points.csv"
sed 's/^starts = .*/to = 3/' "$TMP/bad-br.ini" | grep -v '^to = 3.5' >"$TMP/bad-br2.ini"
run_sc run "$TMP/bad-br2.ini" --out "$TMP/bad-br2" --quiet
expect_rc "branch with to = from" 2
expect_err "branch with to = from" "equals from"

# starts = auto: the fig 5.8 orbits of period <= 4 at alpha = 3.9, found
# by the fixed-point search and continued without a typed guess: the
# period-4 orbit that brute force shows between 3.86 and 3.94 is among
# them, with its fold at 3.9400143891 and flip at 3.8747561536.
cat >"$TMP/auto.ini" <<'EOS'
[model]
name = bk2
driver = frozen
beta = 2.5
phi = 1.25
[task]
kind = branch
parameter = alpha
from = 2.8
to = 4
starts = auto
auto-at = 3.9
auto-period = 4
max-period = 8
hmax = 0.01
sweep = no
[output]
plot = no
EOS
run_sc run "$TMP/auto.ini" --out "$TMP/auto" --quiet
expect_rc "branch with starts = auto" 0
has auto points.csv '^LP,alpha,3\.94001438911[0-9]*,[-0-9.e]*,4,'
has auto points.csv '^PD,alpha,3\.87475615359[0-9]*,[-0-9.e]*,4,'
has auto summary.txt 'starts = auto: 3 orbits found'
has auto summary.txt 'added starts: 3 continued both ways, 0 not found by shooting, 0 not continued \(max-branches\)'

# A start from a row of that points.csv (the period-4 fold), and one start
# among several that fails: reported as an EP row, not fatal.
row=$(awk -F, '$1 == "LP" && $5 == 4 { print NR - 1; exit }' "$TMP/auto/points.csv")
sed -e "s|^starts = auto|starts = $TMP/auto/points.csv:$row\\
d0 = 7.5\\
period = 4|" -e 's/^auto-.*//' -e 's/^from = 2.8/from = 3.85/' \
  "$TMP/auto.ini" >"$TMP/row.ini"
run_sc run "$TMP/row.ini" --out "$TMP/row" --quiet
expect_rc "branch from a points.csv row, with a failing d0" 0
has row points.csv '^LP,alpha,3\.94001438911[0-9]*,[-0-9.e]*,4,'
has row points.csv '^EP,alpha,3\.85[0-9]*,7\.5,4,.*start not found'
run_sc check "$TMP/row.ini" --set task.starts="$TMP/auto/points.csv:999"
expect_rc "a row past the end of points.csv" 2
expect_err "a row past the end of points.csv" "has fewer than 999 rows"
run_sc check "$TMP/row.ini" --set task.starts="3.9 0.2 99999999999"
expect_rc "a start period above max-period" 2
expect_err "a start period above max-period" "(valid: [1, max-period = 8])"

# The brute-force sweep needs a first orbit: with d0 at `at` inside the
# range it starts from d0, with starts only from the branch's first point
# (both failed with "d0 = nan is not finite" before).
sed -e 's/^starts = auto/at = 3.9\
d0 = 0.2\
period = 1/' -e 's/^auto-.*//' -e 's/^sweep = no/sweep = yes\
sweep-steps = 20/' "$TMP/auto.ini" >"$TMP/at-sweep.ini"
run_sc run "$TMP/at-sweep.ini" --out "$TMP/at-sweep" --quiet
expect_rc "branch at 3.9 with its sweep" 0
check "at-sweep: the sweep has 20 values" \
  awk -F, 'NR > 1 { p[$1] = 1 } END { n = 0; for (k in p) n++; exit !(n == 20) }' \
  "$TMP/at-sweep/branch-sweep.csv"
sed -e 's/^at = 3.9/starts = 3.9 0.2 1/' -e '/^d0 = /d' "$TMP/at-sweep.ini" \
  >"$TMP/starts-sweep.ini"
run_sc run "$TMP/starts-sweep.ini" --out "$TMP/starts-sweep" --quiet
expect_rc "branch from starts only, with its sweep" 0
check "starts-sweep: the sweep was drawn" test -s "$TMP/starts-sweep/branch-sweep.csv"

# The border examples: the motion at a located point of each kind
# (docs/branches.md shows their velocity.png).  Driver frozen: V_s = 0.
# GR: block 1's velocity in the two-block slip rises back to 0 and no
# further (a sampled maximum within 1e-5 below 0).
example border-gr
png border-gr velocity.png
gr=$(awk -F, 'BEGIN { m = -1e9 } NR > 1 && $6 == 3 && $4 > m { m = $4 } END { print m }' \
  "$TMP/border-gr/trajectory.csv")
check "border-gr: max U1 in the two-block slip is 0 (got $gr)" \
  awk -v m="$gr" 'BEGIN { exit !(m != "" && m <= 1e-12 && m >= -1e-5) }'
# CS: when block 1 re-sticks, block 2's spring force is at its threshold
# beta = 3.2 (no global stick phase in between): S2 = (1 + alpha) Y2 - alpha Y1.
example border-cs
cs=$(awk -F, -v a=5.6487539210982636 'NR > 1 && $6 == 1 { r = $0 }
  NR > 1 && $6 != 1 && r != "" { split(r, x, ","); printf "%.17g", (1 + a) * x[3] - a * x[2]; exit }' \
  "$TMP/border-cs/trajectory.csv")
check "border-cs: S2 at block 1's re-stick is beta = 3.2 (got $cs)" \
  awk -v s="$cs" 'BEGIN { e = s - 3.2; if (e < 0) e = -e; exit !(e <= 1e-9) }'
# SW: the orbit's first point is d* = (beta - 1)/(1 + 2 alpha) and both
# blocks start together.
example border-sw
has border-sw orbit.csv '^0,0\.1998735313134[0-9]*,12'
# BR: at the end of the two-block slip both velocities are 0 together.
example border-br
br=$(awk -F, 'NR > 1 && $6 == 3 { r = $0 } NR > 1 && $6 != 3 && r != "" { split(r, x, ","); u = x[4] < 0 ? -x[4] : x[4]; w = x[5] < 0 ? -x[5] : x[5]; m = u; if (w > m) m = w; printf "%.3g", m; exit }' \
  "$TMP/border-br/trajectory.csv")
check "border-br: both velocities 0 at the end of the two-block slip (got $br)" \
  awk -v m="$br" 'BEGIN { exit !(m != "" && m <= 1e-9) }'

# Velocity-weakening friction (numerical flows): the fig 5.6 sweep has no
# period up to 16 anywhere in V = 0.025 .. 0.015.
example vw-symmetric
has vw-symmetric summary.txt 'down v from 0\.025 to 0\.015 \(100 values\): period 0$'
# the attractor fills a band of d of about [-0.045, 0.045], symmetric
# under d -> -d: its ends within 0.04..0.05 and within 10 % of each other
check "vw-symmetric: d fills a band of about [-0.045, 0.045], symmetric" \
  awk -F, 'NR > 1 { if (!n++ || $2 < lo) lo = $2; if (n == 1 || $2 > hi) hi = $2 }
    END { printf "  d in [%.4f, %.4f]\n", lo, hi; s = lo + hi; if (s < 0) s = -s
      exit !(hi >= 0.04 && hi <= 0.05 && -lo >= 0.04 && -lo <= 0.05 && s <= 0.1 * hi) }' \
  "$TMP/vw-symmetric/sweep.csv"
png vw-symmetric sweep.png

finish
