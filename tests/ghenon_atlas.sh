# The ghenon atlas through the program (docs/maps.md, "The ghenon
# atlas"): the chart of examples/ghenon-atlas-chart.ini and the NS curve
# of examples/ghenon-atlas.ini drawn over it with the fold and flip
# curves of examples/curve-ghenon-fold.ini and curve-ghenon-flip.ini (the
# flip scene draws curve-ghenon-ns.ini's curve: run before it), held to
# the closed forms.
#
# Tolerances: a chart stops iterating at its period test (relative
# 1e-6), so its state is the fixed point only to about 1e-6 / (1 - |mu|)
# for a multiplier mu: 1e-4 covers margins 1 - |mu| down to 0.01.  Curve
# points to 1e-12 and located points to 1e-10, as tests/curve_n_cli.sh
# (the closed forms computed here in awk, in double).
. "$(dirname "$0")/cli_common.sh"

mkdir -p "$TMP/w"
cd "$TMP/w" || exit 1
for ex in ghenon-atlas-chart curve-ghenon-fold curve-ghenon-ns curve-ghenon-flip \
    ghenon-atlas; do
  # shellcheck disable=SC2086
  $limit "$BIN" run "$SRC/examples/$ex.ini" --quiet $plotset \
    >"$TMP/stdout" 2>"$TMP/stderr"
  RC=$?
  ERR=$(cat "$TMP/stderr")
  expect_rc "$ex" 0
  no_temporaries "$ex" "out/$ex"
done

C=out/ghenon-atlas-chart/chart.csv
expect_header "chart" "$C" "alpha,beta,period,x1,iterations"
# the stable root s of (1 - R) s^2 + (1 + beta) s = alpha nearest x1:
# stable where |D| < 1 and |T| < 1 + D (T = (R - 2) s, D = beta - R s)
check "chart: every period-1 point at a stable fixed point, x1 = s to 1e-4, and over 1000 of them" \
  awk -F, 'function a(x) { return x < 0 ? -x : x }
  NR > 1 && $3 == 1 { R = 0.5; d = (1 + $2) ^ 2 + 4 * (1 - R) * $1; best = 1e9
    if (d < 0) exit 1
    for (k = -1; k <= 1; k += 2) { s = (-(1 + $2) + k * sqrt(d)) / (2 * (1 - R))
      if (a($4 - s) < best) { best = a($4 - s); T = (R - 2) * s; D = $2 - R * s } }
    if (best > 1e-4 || !(a(D) < 1 && a(T) < 1 + D)) { print NR, best; exit 1 }
    n++ }
  END { exit !(n > 1000) }' "$C"
check "chart: every period-2 point past the flip curve alpha = (3 - R) (1 + beta)^2 / 4" \
  awk -F, 'NR > 1 && $3 == 2 { n++; if ($1 <= 0.625 * (1 + $2) ^ 2) exit 1 }
  END { exit !(n > 100) }' "$C"

D=out/ghenon-atlas
check "atlas: every NS-curve point on beta = 1 + R s, alpha = s^2 + 2 s, x = y = s" \
  awk -F, 'function a(x) { return x < 0 ? -x : x }
  NR > 1 && NF > 1 { s = ($2 - 1) / 0.5; e = a($1 - s * s - 2 * s);
    if (a($3 - s) > e) e = a($3 - s); if (a($4 - s) > e) e = a($4 - s);
    if (e > 1e-12) { print NR, e; exit 1 } }' "$D/curve.csv"
for p in "R1 -4/3" "R2 4/3" "R3 2/3" "R4 0"; do
  set -- $p
  check "atlas: one $1 at its closed form" awk -F, -v l="$1" \
    "function a(x) { return x < 0 ? -x : x }
    BEGIN { s = $2; n = 0 }
    \$1 == l { n++; e = a(\$2 - s * s - 2 * s); if (a(\$3 - 1 - 0.5 * s) > e) e = a(\$3 - 1 - 0.5 * s);
      if (e > 1e-10 || \$9 > 1e-10) exit 1 }
    END { exit n != 1 }" "$D/points.csv"
done
if [ -z "$plotset" ]; then check "atlas: its figure is drawn" test -s "$D/curve.png"; fi
finish
