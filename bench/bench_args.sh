# bench/side_by_side.sh refuses bad arguments with a message naming them,
# exit status 2, and builds nothing.  Run by ctest (bench/CMakeLists.txt).
# usage: sh bench/bench_args.sh PATH/TO/slipcont SOURCE_DIR
. "$(dirname "$0")/../tests/cli_common.sh"
S="$SRC/bench/side_by_side.sh"

# expect LABEL RC PATTERN -- ARGS...: side_by_side.sh ARGS exits RC and
# says PATTERN.
expect() {
  label=$1 want=$2 pat=$3
  shift 4
  SLIPCONT_SBS_DIR="$TMP/sbs" sh "$S" "$@" >"$TMP/out" 2>&1
  RC=$?
  ERR=$(cat "$TMP/out")
  expect_rc "$label" "$want"
  expect_err "$label" "$pat"
}
expect "no arguments: the usage" 2 "usage: bench/side_by_side.sh BASE_REV" --
expect "a revision that is not a commit" 2 "nosuchrev-xyz is not a commit" -- nosuchrev-xyz
expect "rounds 0" 2 "ROUNDS = 0 (valid: 1..99)" -- HEAD 0
expect "rounds not a number" 2 "ROUNDS = x (valid: 1..99)" -- HEAD x
expect "a third argument other than big" 2 "third argument huge (valid: big" -- HEAD 1 huge
check "a refused run builds nothing ($TMP/sbs absent)" test ! -e "$TMP/sbs"

finish
