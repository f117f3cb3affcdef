#!/bin/sh
# bench/side_by_side.sh refuses bad arguments with a message naming them,
# exit status 2, and builds nothing.
# usage: sh tests/bench_args.sh SOURCE_DIR
set -u
SRC=$1
S="$SRC/bench/side_by_side.sh"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail=0
expect() { # expect LABEL RC PATTERN -- args...
  label=$1 want=$2 pat=$3
  shift 4
  SLIPCONT_SBS_DIR="$TMP/sbs" sh "$S" "$@" > "$TMP/out" 2>&1
  rc=$?
  if [ "$rc" -ne "$want" ] || ! grep -q -- "$pat" "$TMP/out"; then
    echo "FAIL $label: exit $rc (want $want), output:"
    sed 's/^/  /' "$TMP/out"
    fail=1
  else
    echo "PASS $label"
  fi
}
expect "no arguments: the usage" 2 "usage: bench/side_by_side.sh BASE_REV" --
expect "a revision that is not a commit" 2 "nosuchrev-xyz is not a commit" -- nosuchrev-xyz
expect "rounds 0" 2 "ROUNDS = 0 (valid: 1..99)" -- HEAD 0
expect "rounds not a number" 2 "ROUNDS = x (valid: 1..99)" -- HEAD x
expect "a third argument other than big" 2 "third argument huge (valid: big" -- HEAD 1 huge
if [ -e "$TMP/sbs" ]; then
  echo "FAIL a refused run created $TMP/sbs"
  fail=1
fi
exit $fail
