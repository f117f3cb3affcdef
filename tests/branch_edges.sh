# Edges of the branch and curve tasks that a new user met, each scene in
# tests/scenes/ with the answer its opening comment states:
#  - a hand-over at a switching point starts at the border orbit's own
#    points (the map is continuous at d*), and a hand-over to an orbit
#    farther than the corrector's step is refused with its reason;
#  - a border point whose defining system is degenerate says so, has an
#    error that covers every preset's answer, and lies in the interval;
#  - a point located by bisection is labelled by the border it knows
#    (beyond, or vanishing on its side), or IC when it knows none;
#  - a curve whose start is corrected says where it landed (summary and
#    plot title), and ends on the box's edge, not at the last point inside;
#  - every located row of a branch (LP, PD, GR, CS, SW, BR, TT) starts
#    the curve of its type, on its own border, at the row's point, and
#    explains a largest residual above its tolerance;
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

# curves_from OUT X Y X-FROM X-TO Y-FROM Y-TO 'KEY = VALUE'...: a curve
# of its type (3 points each way, the [model] keys given) from every row
# of $TMP/OUT/points.csv located by Newton; each must start: corrected at
# fixed y onto the row's own x (the row is on the curve's system:
# 1e-9 (1 + |x|), the two Newton solutions' tolerance with room),
# following the row's own border.
curves_from() {
  out=$1 x=$2 y=$3 xlo=$4 xhi=$5 ylo=$6 yhi=$7
  shift 7
  n=0 ok=0 bad=
  while IFS= read -r line; do
    n=$((n + 1))
    [ "$(echo "$line" | cut -d, -f9)" = newton ] || continue
    case ${line%%,*} in
    LP) t=fold ;; PD) t=flip ;; GR) t=graze ;; CS) t=cross ;;
    SW) t=switch ;; BR) t=both ;; TT) t=touch ;; *) continue ;;
    esac
    val=$(echo "$line" | cut -d, -f3)
    border=$(echo "$line" | cut -d, -f10 | tr ';' ',')
    {
      echo "[model]"
      for kv in "$@"; do echo "$kv"; done
      printf '[task]\nkind = curve\ntype = %s\nx = %s\ny = %s\n' $t $x $y
      printf 'x-from = %s\nx-to = %s\ny-from = %s\ny-to = %s\n' \
        $xlo $xhi $ylo $yhi
      printf 'max-points = 3\nstart = %s:%s\n' "$TMP/$out/points.csv" $n
    } >"$TMP/$out-c$n.ini"
    if ! "$BIN" run "$TMP/$out-c$n.ini" --quiet --out "$TMP/$out-c$n" \
      --set output.plot=no >"$TMP/stdout" 2>"$TMP/stderr"; then
      bad="$bad; row $n ($t): $(cat "$TMP/stderr")"
      continue
    fi
    x1=$(awk -F, 'NR == 2 { print $1 }' "$TMP/$out-c$n/curve.csv")
    if ! awk -v a="$x1" -v b="$val" 'BEGIN { e = a - b; if (e < 0) e = -e
        exit !(e <= 1e-9 * (1 + (b < 0 ? -b : b))) }'; then
      bad="$bad; row $n ($t): starts at $x = $x1, not $val"
      continue
    fi
    if [ -n "$border" ] &&
      ! grep -qF "border followed: ${line%%,*}, $border, iterate 1 of" \
        "$TMP/$out-c$n/summary.txt"; then
      bad="$bad; row $n ($t): $(grep 'border followed' "$TMP/$out-c$n/summary.txt")"
      continue
    fi
    # a largest residual above the tolerance is explained
    if awk '/largest residual of the defining system/ { r = $NF }
        /residual tolerance used/ { t = $NF }
        END { exit !(r + 0 > t + 0) }' "$TMP/$out-c$n/summary.txt" &&
      ! grep -q "the largest residual is above the tolerance" \
        "$TMP/$out-c$n/summary.txt"; then
      bad="$bad; row $n ($t): residual above the tolerance, not explained"
      continue
    fi
    ok=$((ok + 1))
  done <<EOT
$(tail -n +2 "$TMP/$out/points.csv")
EOT
  if [ -z "$bad" ]; then
    pass "$out: the $ok located rows each start the curve of their type on their own border"
  else
    fail "$out: curves from rows$bad"
  fi
}

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
  curves_from sw alpha beta 2.5 4 2.5 3.5 "name = bk2" "driver = frozen" \
    "alpha = 2.5" "beta = 3"
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
  curves_from grm v alpha 0.01 0.03 2.5 3.2 "name = bk2" "driver = moving" \
    "alpha = 2.8" "beta = 1"
  d0=$(rows "$P" '$5 == 1 && ($4 < 0 ? -$4 : $4) < 1e-12')
  if [ -z "$d0" ]; then
    pass "GR of period 2: no segment of the synchronous orbit d = 0"
  else
    fail "GR of period 2: rows of the synchronous orbit: $d0"
  fi
fi

# --- a degenerate SW ----------------------------------------------------
# Every preset (and numerical flows): the SW near 1.5 is "degenerate",
# inside [1.5, 3.5], with a residual above 0 and an error that covers
# the distance between any two presets' values.
all=
for pre in fast default precise numerical; do
  set -- --set accuracy.preset=$pre
  [ $pre = numerical ] && set -- --set model.flows=numerical
  run branch-sw-degenerate deg-$pre "$@" || continue
  P=$TMP/deg-$pre/points.csv
  out=$(rows "$P" '$3 < 1.5 || $3 > 3.5')
  if [ -z "$out" ]; then
    pass "degenerate SW ($pre): every row inside [1.5, 3.5]"
  else
    fail "degenerate SW ($pre): rows outside [1.5, 3.5]: $out"
  fi
  # a bisection row names the border it knows, or says it knows none (IC)
  unk=$(rows "$P" '$9 == "bisection" && $10 == "" && $1 != "IC"')
  if [ -z "$unk" ]; then
    pass "bisection rows ($pre): each names its border or is labelled IC"
  else
    fail "bisection rows ($pre): labelled without a known border: $unk"
  fi
  sw=$(rows "$P" '$1 == "SW" && $3 < 1.51')
  case $(echo "$sw" | cut -d, -f9) in
  degenerate)
    if echo "$sw" | awk -F, '{ exit !($7 > 0 && $8 > 0) }'; then
      pass "degenerate SW ($pre): said so, residual $(echo "$sw" | cut -d, -f7) > 0, error $(echo "$sw" | cut -d, -f8)"
    else
      fail "degenerate SW ($pre): residual or error not above 0: $sw"
    fi ;;
  *) fail "degenerate SW ($pre): not said degenerate: $sw" ;;
  esac
  all="$all$(echo "$sw" | cut -d, -f3,8) "
done
if echo "$all" | awk '{ for (i = 1; i <= NF; i++) { split($i, a, ",")
      p[i] = a[1]; e[i] = a[2] }
    for (i = 1; i <= NF; i++) for (j = 1; j <= NF; j++) {
      d = p[i] - p[j]; if (d < 0) d = -d
      if (!(d <= e[i] + e[j])) exit 1 } }'; then
  pass "degenerate SW: the presets agree within their errors ($all)"
else
  fail "degenerate SW: the presets disagree beyond their errors ($all)"
fi

# A switch curve started from that degenerate row: where it cannot start,
# the message says the row is degenerate (not "start from a row labelled
# SW", which it is), exits 1 and leaves no output folder.
n=$(awk -F, '$1 == "SW" && $9 == "degenerate" { print NR - 1; exit }' \
  "$TMP/deg-default/points.csv")
if [ -n "$n" ]; then
  cat >"$TMP/curve-deg.ini" <<EOF
[model]
name = bk2
driver = frozen
beta = 3
[task]
kind = curve
type = switch
x = alpha
y = beta
x-from = 1
x-to = 4
y-from = 2
y-to = 4
start = $TMP/deg-default/points.csv:$n
EOF
  "$BIN" run "$TMP/curve-deg.ini" --quiet --out "$TMP/curve-deg" \
    >"$TMP/stdout" 2>"$TMP/stderr"
  rc=$?
  if [ $rc = 1 ] && [ ! -e "$TMP/curve-deg" ] &&
    grep -q "the row's point is degenerate" "$TMP/stderr" &&
    ! grep -q "start from a row labelled SW" "$TMP/stderr"; then
    pass "switch curve from the degenerate SW row: refused as degenerate (exit 1)"
  elif [ $rc = 0 ]; then
    pass "switch curve from the degenerate SW row: started"
  else
    fail "switch curve from the degenerate SW row: exit $rc, $(cat "$TMP/stderr")"
  fi
else
  fail "no degenerate SW row in $TMP/deg-default/points.csv"
fi

# --- a curve's start moved ----------------------------------------------
# The fold of fig 5.8's period-1 orbit at beta = 2.5: alpha =
# 2.9925306744279 (docs/branches.md), to the corrector's 1e-9.
if "$BIN" run "$SC/curve-fold-moved.ini" --quiet --out "$TMP/moved" \
  --set output.plot=no >"$TMP/stdout" 2>"$TMP/stderr"; then
  line=$(grep "^  start:" "$TMP/moved/summary.txt")
  if echo "$line" | awk '{ x = $4; sub(",", "", x); e = x - 2.9925306744279
      if (e < 0) e = -e; exit !(e < 1e-9) }' &&
    echo "$line" | grep -qF "corrected from the given alpha = 3.2000000000000002 (moved by -0.207)"; then
    pass "curve start moved: the summary says where ($line)"
  else
    fail "curve start moved: summary's start line: '$line'"
  fi
  title=$(grep "^set title" "$TMP/moved/curve.gp")
  case $title in
  *"alpha = 2.99253067"*"start moved -0.207 from alpha = 3.2"*)
    pass "curve start moved: the title says where ($title)" ;;
  *) fail "curve start moved: title '$title'" ;;
  esac
else
  fail "curve-fold-moved ran: $(cat "$TMP/stderr")"
fi

# --- a curve's end on the box --------------------------------------------
# The same fold in alpha over [2.5, 3.5]: both ends on the edges exactly,
# each a point of the curve (its last row in curve.csv).
if "$BIN" run "$SC/curve-fold-moved.ini" --quiet --out "$TMP/edge" \
  --set output.plot=no --set task.x-from=2.5 --set task.x-to=3.5 \
  --set task.max-points=5000 >"$TMP/stdout" 2>"$TMP/stderr"; then
  ends=$(awk -F, 'NR > 1 && $1 == "EP" { print $2 }' "$TMP/edge/points.csv" |
    sort -g | tr '\n' ' ')
  if [ "$ends" = "2.5 3.5 " ] &&
    [ "$(grep -c "the box's edge in x (located on it)" "$TMP/edge/points.csv")" = 2 ] &&
    [ "$(awk -F, '$1 == 2.5 || $1 == 3.5' "$TMP/edge/curve.csv" | wc -l)" = 2 ]; then
    pass "curve ends: on the box's edges alpha = 2.5 and 3.5, each a curve point"
  else
    fail "curve ends: EP at alpha = $ends; $(cat "$TMP/edge/points.csv")"
  fi
else
  fail "curve-fold-moved (box [2.5, 3.5]) ran: $(cat "$TMP/stderr")"
fi

# --- a multiple-shooting curve's end on the box ---------------------------
# fig 5.8's period-4 fold over alpha in [3.92, 3.95]: with multiple
# shooting too both ends lie on the edges (its own system corrected there
# with alpha fixed), at the beta that single shooting finds on its own
# system (within 1e-10; they ended at the last points inside before, 2e-4
# from the edges).
edge_ends() { # SHOOTING -> "alpha beta" of each EP located on the edge
  "$BIN" run "$SRC/examples/curve-fig58-fold4.ini" --quiet --out "$TMP/e4-$1" \
    --set output.plot=no --set task.shooting="$1" --set task.x-from=3.92 \
    --set task.x-to=3.95 >"$TMP/stdout" 2>"$TMP/stderr" || return 1
  awk -F, 'NR > 1 && $1 == "EP" && $6 ~ /located on it/ { printf "%.17g %.17g\n", $2, $3 }' \
    "$TMP/e4-$1/points.csv" | sort -g
}
if single=$(edge_ends single) && multiple=$(edge_ends multiple); then
  if [ "$(echo "$multiple" | awk '{ print $1 }' | tr '\n' ' ')" = "3.9199999999999999 3.9500000000000002 " ] &&
    [ "$(printf '%s\n%s\n' "$single" "$multiple" | awk '{ b[NR] = $2 } END { e1 = b[1] - b[3]; e2 = b[2] - b[4]; if (e1 < 0) e1 = -e1; if (e2 < 0) e2 = -e2; print (NR == 4 && e1 <= 1e-10 && e2 <= 1e-10) }')" = 1 ]; then
    pass "multiple-shooting curve ends: on the box's edges, at single shooting's beta within 1e-10 ($multiple)"
  else
    fail "multiple-shooting curve ends: '$multiple' (single shooting: '$single'); $(cat "$TMP/e4-multiple/points.csv")"
  fi
else
  fail "curve-fig58-fold4 (box [3.92, 3.95]) ran: $(cat "$TMP/stderr")"
fi

finish
