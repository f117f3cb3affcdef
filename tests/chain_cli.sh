# The chain through the program: two blocks give bk2's period-6 orbits of
# the fixed-point example (docs/chain.md), the same points to 1e-12 and
# multipliers to 1e-9 (the chain's f differs from bk2's by ~1e-15, which
# Newton's solutions and the product of six derivatives carry), and the
# folds and flips of the branch example; its options are listed and
# checked.
. "$(dirname "$0")/cli_common.sh"

write_scene() { # $1: file, $2: the model's lines
  printf '[model]\n%s\ndriver = frozen\nalpha = 3.3\nphi = 1.25\n' "$2" >"$1"
  cat >>"$1" <<'INI'
[task]
kind = fixed-point
period = 6
from = -0.3
to = 0.3
steps = 2001
[output]
plot = no
INI
}
write_scene "$TMP/bk2.ini" "name = bk2
beta = 2.5"
write_scene "$TMP/chain.ini" "name = chain
blocks = 2
beta2 = 2.5"
run_sc run "$TMP/bk2.ini" --out "$TMP/bk2" --quiet
expect_rc "bk2 fixed points" 0
run_sc run "$TMP/chain.ini" --out "$TMP/chain" --quiet
expect_rc "chain (blocks = 2) fixed points" 0
expect_rows "chain: orbits.csv" "$TMP/chain/orbits.csv" 2
check "two blocks: bk2's period-6 orbits (points 1e-12, multipliers 1e-9, itineraries)" \
  awk -F, '
  function abs(x) { return x < 0 ? -x : x }
  FNR == 1 { next }
  NR == FNR { m[FNR] = $2; d[FNR] = $4; it[FNR] = $5; nb++; next }
  { nc++
    if ($5 != it[FNR] || abs($2 - m[FNR]) > 1e-9 * (1 + abs(m[FNR]))) bad = 1
    k = split($4, a, ";"); split(d[FNR], b, ";")
    for (i = 1; i <= k; i++) if (abs(a[i] - b[i]) > 1e-12) bad = 1 }
  END { exit !(nb == 2 && nc == 2 && !bad) }' "$TMP/bk2/orbits.csv" "$TMP/chain/orbits.csv"

# The chapter's branch example (fig 5.8) with name = chain: two blocks
# run the one-dimensional branch, which reads the chain's borders through
# the one-dimensional interface (map.c).  Every special point bk2 locates
# (LP, PD, SW, GR, BR, CS), the chain locates by Newton too, with the same
# label and period, at the same alpha within 1e-12 relative; except two,
# which it finds by bisection (their rows say so): the GR at 3.8614, a
# re-stick's maximum met from the side where it fires (the chain has no
# such border yet: it brackets a BR there), and the period-16 SW at
# 3.2553284, whose orbit starts on the switching point where the frozen
# driver's map is singular (Newton from the chain's border fails there).
sed -e 's/^name = bk2/name = chain\nblocks = 2/' -e 's/^beta = /beta2 = /' \
  -e '/^plot-at/d' "$SRC/examples/branch-fig58.ini" >"$TMP/br-chain.ini"
sed -e '/^plot-at/d' "$SRC/examples/branch-fig58.ini" >"$TMP/br-bk2.ini"
run_within 600 run "$TMP/br-bk2.ini" --out "$TMP/brb" --quiet --set output.plot=no
expect_rc "branch fig 5.8, bk2" 0
run_within 600 run "$TMP/br-chain.ini" --out "$TMP/brc" --quiet --set output.plot=no
expect_rc "branch fig 5.8, chain (blocks = 2)" 0
special() { # located rows of points.csv: "LABEL PERIOD ALPHA METHOD"
  awk -F, 'NR > 1 && $1 ~ /^(LP|PD|SW|GR|BR|CS)$/ { print $1, $5, $3, $9 }' "$1"
}
special "$TMP/brb/points.csv" >"$TMP/pb"
special "$TMP/brc/points.csv" >"$TMP/pc"
check "fig 5.8: bk2's $(wc -l <"$TMP/pb") special points located by the chain by Newton within 1e-12, but for two known by bisection" \
  awk 'function abs(x) { return x < 0 ? -x : x }
  NR == FNR { lab[FNR] = $1; per[FNR] = $2; al[FNR] = $3; n = FNR; next }
  { cl[FNR] = $1; cp[FNR] = $2; ca[FNR] = $3; cm[FNR] = $4; m = FNR }
  END { if (n < 30) exit 1
    for (i = 1; i <= n; i++) {
      known = (lab[i] == "GR" && abs(al[i] - 3.8613904) < 1e-6) ||
              (lab[i] == "SW" && per[i] == 16 && abs(al[i] - 3.2553284) < 1e-6)
      ok = 0
      for (j = 1; j <= m; j++) {
        if (!known && cl[j] == lab[i] && cp[j] == per[i] && cm[j] == "newton" &&
            abs(ca[j] - al[i]) <= 1e-12 * (1 + abs(al[i]))) ok = 1
        if (known && cp[j] == per[i] && cm[j] == "bisection" &&
            abs(ca[j] - al[i]) <= 2e-5) ok = 1
      }
      if (!ok) { print "missing:", lab[i], per[i], al[i]; exit 1 } }
    nb = 0
    for (j = 1; j <= m; j++) nb += cm[j] == "bisection"
    if (nb > 3) { print nb, "rows by bisection"; exit 1 } }' "$TMP/pb" "$TMP/pc"

# The map task's border in the state (sc_map_state_borders): two blocks
# mark the switching point where bk2 marks d*, within 1e-12.
for mdl in bk2 chain; do
  sed -e 's/^kind = fixed-point/kind = map/' -e '/^period = /d' \
    "$TMP/$mdl.ini" >"$TMP/map-$mdl.ini"
  run_sc run "$TMP/map-$mdl.ini" --out "$TMP/map-$mdl" --quiet
  expect_rc "map task, $mdl" 0
done
check "two blocks: the map task marks bk2's d* as the chain's switching point (1e-12)" \
  sh -c 'b=$(sed -n "s/^ *d\* = \([^:]*\): a border in the state.*/\1/p" "$1")
         c=$(sed -n "s/^ *SW = \([^:]*\): a border in the state (SW: gaps 1, 2 equal.*/\1/p" "$2")
         [ -n "$b" ] && [ -n "$c" ] &&
           awk -v b="$b" -v c="$c" "BEGIN { d = b - c; exit !(d < 1e-12 && d > -1e-12) }"' _ \
  "$TMP/map-bk2/summary.txt" "$TMP/map-chain/summary.txt"

# A curve of two blocks through the chain's exact second and third
# derivatives (the one-dimensional interface reads H, Jp, T of its n-d
# value): examples/curve-fig58-flip1.ini's flip curve of bk2 in (alpha,
# beta) run with name = chain, blocks = 2 in (alpha, beta2): the same
# ends and the same GPD (b = 0) to 1e-12 (observed ~1e-14).
sed -e 's/^name = bk2/name = chain\nblocks = 2/' -e 's/^beta = /beta2 = /' \
  -e 's/^y = beta$/y = beta2/' "$SRC/examples/curve-fig58-flip1.ini" \
  >"$TMP/curve-chain2.ini"
run_sc run "$SRC/examples/curve-fig58-flip1.ini" --out "$TMP/curve-bk2" \
  --quiet --set output.plot=no
expect_rc "curve-fig58-flip1, bk2" 0
run_sc run "$TMP/curve-chain2.ini" --out "$TMP/curve-chain2" --quiet \
  --set output.plot=no
expect_rc "curve-fig58-flip1, chain of two blocks" 0
check "two blocks: bk2's flip curve of fig 5.8, its ends and GPD, through the chain (1e-12)" \
  awk -F, 'function abs(x) { return x < 0 ? -x : x }
    FNR == 1 { f++; next }
    f == 1 { l[FNR] = $1; a[FNR] = $2; b[FNR] = $3; n1 = FNR; next }
    { n2 = FNR; if ($1 != l[FNR] || abs($2 - a[FNR]) > 1e-12 || abs($3 - b[FNR]) > 1e-12) bad++
      if ($1 == "GPD") gpd++ }
    END { exit !(n1 == n2 && n1 >= 3 && gpd == 1 && !bad) }' \
  "$TMP/curve-bk2/points.csv" "$TMP/curve-chain2/points.csv"

run_sc models
check "slipcont models lists chain with blocks 2..256 and topology open|ring" \
  sh -c "printf '%s' \"\$1\" | grep -q '^chain:' &&
         printf '%s' \"\$1\" | grep -Eq 'blocks +2\\.\\.256' &&
         printf '%s' \"\$1\" | grep -Eq 'topology +open\\|ring'" _ "$OUT"

write_scene "$TMP/bad.ini" "name = chain
blocks = 300"
run_sc check "$TMP/bad.ini"
expect_rc "blocks = 300 refused" 2
expect_err "blocks = 300: the range" "a whole number in 2..256"
write_scene "$TMP/ring2.ini" "name = chain
blocks = 2
topology = ring"
run_sc check "$TMP/ring2.ini"
expect_rc "a ring of two blocks refused" 2
expect_err "a ring of two blocks: why" "topology = ring needs blocks >= 3"
finish
