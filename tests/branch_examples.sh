# The fixed-point and branch example scenes run through the program and
# write what their tasks promise: headers, the known answers stated at the
# top of each scene, plots (when gnuplot is present), no temporaries.
# Usage: sh tests/branch_examples.sh PATH/TO/slipcont SOURCE_DIR
. "$(dirname "$0")/cli_common.sh"

plotset=
if ! command -v gnuplot >/dev/null 2>&1; then plotset="--set output.plot=no"; fi
limit=
if command -v timeout >/dev/null 2>&1; then limit="timeout 240"; fi

example() {
  # shellcheck disable=SC2086
  $limit "$BIN" run "$SRC/examples/$1.ini" --out "$TMP/$1" --quiet $plotset \
    >"$TMP/stdout" 2>"$TMP/stderr"
  RC=$?
  ERR=$(cat "$TMP/stderr")
  expect_rc "$1" 0
  no_temporaries "$1" "$TMP/$1"
  check "$1: summary.txt" test -s "$TMP/$1/summary.txt"
}

png() {
  if [ -z "$plotset" ]; then check "$1: $2 rendered" test -s "$TMP/$1/$2"; fi
}

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
png fixed-point-fig58 fixed-point.png

example branch-logistic
expect_header branch-logistic "$TMP/branch-logistic/points.csv" \
  "label,parameter,value,d,period,multiplier,note"
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

finish
