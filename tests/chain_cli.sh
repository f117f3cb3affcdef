# The chain through the program: two blocks give bk2's period-6 orbits of
# the fixed-point example (docs/chain.md), the same points to 1e-12 and
# multipliers to 1e-9 (the chain's f differs from bk2's by ~1e-15, which
# Newton's solutions and the product of six derivatives carry); its
# options are listed and checked.
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
