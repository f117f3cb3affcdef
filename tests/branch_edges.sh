# Edges of the branch and curve tasks that a new user met, each scene in
# tests/scenes/ with the answer its opening comment states:
#  - a hand-over at a switching point starts at the border orbit's own
#    points (the map is continuous at d*), and a hand-over to an orbit
#    farther than the corrector's step is refused with its reason;
# Usage: sh tests/branch_edges.sh PATH/TO/slipcont SOURCE_DIR
. "$(dirname "$0")/cli_common.sh"
SC=$SRC/tests/scenes

# run SCENE OUT ARGS...: the scene into $TMP/OUT, without plots.
run() {
  scene=$1 out=$2
  shift 2
  if "$BIN" run "$SC/$scene.ini" --quiet --out "$TMP/$out" \
    --set output.plot=no "$@" >"$TMP/stdout" 2>"$TMP/stderr"; then
    return 0
  fi
  fail "$scene ran: $(cat "$TMP/stderr")"
  return 1
}

# rows FILE AWK-CONDITION: the rows of points.csv that satisfy it.
rows() { awk -F, "NR > 1 && ($2)" "$1"; }

# --- a hand-over at SW -------------------------------------------------
# The segment handed over at the SW must be the orbit 1;1-12-2: its
# second point, (alpha, d), is checked against the fixed-point task run
# at that alpha (two Newton solutions: 1e-9).
if run branch-sw-handover sw; then
  P=$TMP/sw/points.csv
  sw=$(rows "$P" '$1 == "SW" && $3 > 3.4188485549 && $3 < 3.4188485551')
  case $sw in
  *"continues with period 2 (iterate 1: 2-12-2 -> 1-12-2)"*)
    pass "SW at 3.4188485550: handed over to the period-2 orbit 1-12-2" ;;
  *) fail "SW at 3.4188485550: $sw" ;;
  esac
  # branch.csv: alpha,d,multiplier,stable,itinerary,period,branch
  second=$(awk -F, 'NR > 1 && $6 == 2 && ($5 == "1|1-12-2" || $5 == "1-12-2|1") {
      if (!($7 in n)) { if ($1 - 3.418848555 > 1e-5) next }
      if (++n[$7] == 2) { print $1, $2; exit } }' "$TMP/sw/branch.csv")
  if [ -z "$second" ]; then
    fail "SW hand-over: no period-2 segment 1|1-12-2 starts at the SW"
  elif run fixed-point-sw-handover swfp --set model.alpha="${second% *}"; then
    orbit=$(awk -F, 'NR == 2 { print $4 }' "$TMP/swfp/orbits.csv")
    if echo "${second#* } $orbit" | awk '{ n = split($2, x, ";")
        for (i = 1; i <= n; i++) { e = $1 - x[i]; if (e < 0) e = -e
          if (e <= 1e-9) exit 0 } exit 1 }'; then
      pass "SW hand-over: (alpha, d) = ($second) is on the fixed-point task's orbit $orbit"
    else
      fail "SW hand-over: (alpha, d) = ($second) is not on the fixed-point task's orbit $orbit"
    fi
  fi
  p1=$(rows "$P" '$5 == 1')
  if [ -z "$p1" ]; then
    pass "SW hand-over: no period-1 row (the orbit near 0.3207 is unrelated)"
  else
    fail "SW hand-over: a period-1 segment: $p1"
  fi
fi

# --- a hand-over refused ------------------------------------------------
# Past the grazing of the period-2 orbit the only orbit shooting finds is
# the synchronous d = 0, 0.0086 away with hmax = 3.75e-4.
if run branch-gr-moving grm; then
  P=$TMP/grm/points.csv
  gr=$(rows "$P" '$1 == "GR" && $5 == 2')
  case $gr in
  *"hand-over refused: the period-1 orbit found beyond"*"more than the corrector's step"*)
    pass "GR of period 2: the hand-over to d = 0 is refused and said so" ;;
  *) fail "GR of period 2: $gr" ;;
  esac
  d0=$(rows "$P" '$5 == 1 && ($4 < 0 ? -$4 : $4) < 1e-12')
  if [ -z "$d0" ]; then
    pass "GR of period 2: no segment of the synchronous orbit d = 0"
  else
    fail "GR of period 2: rows of the synchronous orbit: $d0"
  fi
fi

finish
