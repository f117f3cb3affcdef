# docs/guide.md lists every scene key: its generated block must equal
# `slipcont keys --markdown`.  To regenerate after changing a table:
#   sh tests/cli_guide.sh build/slipcont . --update
. "$(dirname "$0")/cli_common.sh"

guide="$SRC/docs/guide.md"
begin='<!-- BEGIN keys -->'
end='<!-- END keys -->'
"$BIN" keys --markdown >"$TMP/keys.md"
check "keys --markdown runs" test -s "$TMP/keys.md"
awk -v b="$begin" -v e="$end" '$0 == e {p = 0} p {print} $0 == b {p = 1}' \
  "$guide" >"$TMP/guide-keys.md"
if [ "${3:-}" = "--update" ]; then
  awk -v b="$begin" -v e="$end" -v f="$TMP/keys.md" '
    $0 == b {print; while ((getline l < f) > 0) print l; skip = 1; next}
    $0 == e {skip = 0}
    !skip {print}' "$guide" >"$TMP/guide.new" && cp "$TMP/guide.new" "$guide"
  echo "updated $guide"
  exit 0
fi
if cmp -s "$TMP/keys.md" "$TMP/guide-keys.md"; then
  pass "docs/guide.md key tables match the code's tables"
else
  fail "docs/guide.md key tables differ from 'slipcont keys --markdown' (regenerate: sh tests/cli_guide.sh BUILD/slipcont . --update)"
  diff "$TMP/guide-keys.md" "$TMP/keys.md" | head -40
fi
finish
