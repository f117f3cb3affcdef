# Helpers for the cli_*.sh tests, sourced by them.  Usage of a test:
#   sh tests/cli_X.sh PATH/TO/slipcont SOURCE_DIR
# Every check prints PASS/FAIL with what was observed; the script exits 1
# if any failed.
set -u
BIN=$1
SRC=$2
NPASS=0
NFAIL=0
TMP=$(mktemp -d "${TMPDIR:-/tmp}/slipcont-cli.XXXXXX")
trap 'rm -rf "$TMP"' EXIT

pass() { NPASS=$((NPASS + 1)); echo "PASS $1"; }
fail() { NFAIL=$((NFAIL + 1)); echo "FAIL $1"; }

# check WHAT CONDITION-COMMAND...
check() {
  what=$1
  shift
  if "$@"; then pass "$what"; else fail "$what"; fi
}

# run_cmd COMMAND...: runs a command, leaving $RC, $OUT (stdout), $ERR
# (stderr).
run_cmd() {
  "$@" >"$TMP/stdout" 2>"$TMP/stderr"
  RC=$?
  OUT=$(cat "$TMP/stdout")
  ERR=$(cat "$TMP/stderr")
}

# run_sc ARGS...: runs slipcont, as run_cmd.
run_sc() { run_cmd "$BIN" "$@"; }

# run_within SECONDS ARGS...: run_sc under a time limit, so that a hang
# is a failure (status 124) where `timeout` exists.
run_within() {
  secs=$1
  shift
  if command -v timeout >/dev/null 2>&1; then
    run_cmd timeout "$secs" "$BIN" "$@"
  else
    run_cmd "$BIN" "$@"
  fi
}

# expect_rc WHAT RC
expect_rc() {
  if [ "$RC" -eq "$2" ]; then pass "$1: exit status $2"
  else fail "$1: exit status $RC, expected $2 (stderr: $ERR)"; fi
}

# expect_err WHAT TEXT: stderr contains TEXT (fixed string).
expect_err() {
  case $ERR in
  *"$2"*) pass "$1: message contains '$2'" ;;
  *) fail "$1: message '$ERR' lacks '$2'" ;;
  esac
}

# expect_out WHAT TEXT: stdout contains TEXT (fixed string).
expect_out() {
  case $OUT in
  *"$2"*) pass "$1: output contains '$2'" ;;
  *) fail "$1: output lacks '$2'" ;;
  esac
}

# first_line FILE / data_rows FILE (lines after the header)
first_line() { head -n 1 "$1" 2>/dev/null; }
data_rows() { if [ -f "$1" ]; then echo $(($(wc -l <"$1") - 1)); else echo -1; fi; }

# expect_header WHAT FILE HEADER
expect_header() {
  h=$(first_line "$2")
  if [ "$h" = "$3" ]; then pass "$1: header '$3'"
  else fail "$1: header '$h', expected '$3'"; fi
}

# expect_rows WHAT FILE N
expect_rows() {
  n=$(data_rows "$2")
  if [ "$n" -eq "$3" ]; then pass "$1: $3 data rows"
  else fail "$1: $n data rows, expected $3"; fi
}

# no_temporaries WHAT DIR: no .name.XXXXXX files left behind.
no_temporaries() {
  left=$(find "$2" -name '.*' -type f 2>/dev/null)
  if [ -z "$left" ]; then pass "$1: no temporary files left"
  else fail "$1: temporary files left: $left"; fi
}

# Running example scenes (cli_examples.sh, branch_examples.sh): plots are
# checked only where gnuplot is installed; each run has a time limit.
plotset=
if ! command -v gnuplot >/dev/null 2>&1; then plotset="--set output.plot=no"; fi
limit=
if command -v timeout >/dev/null 2>&1; then limit="timeout 240"; fi

# example NAME: run examples/NAME.ini into $TMP/NAME.
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

# png NAME FILE: rendered when gnuplot is there.
png() {
  if [ -z "$plotset" ]; then check "$1: $2 rendered" test -s "$TMP/$1/$2"; fi
}

# computing PID SECONDS: waits until process PID has spent SECONDS of
# processor time, read from /proc (Linux); 0 then, 1 if the process ended
# first or /proc cannot tell.  A test that must signal a run in the middle
# of its compute step waits for this instead of a fixed time: reading the
# scene and preparing take milliseconds, so a run that has computed for
# SECONDS is inside its compute step whatever the machine's load.
computing() {
  [ -r /proc/self/stat ] || return 1
  tck=$(getconf CLK_TCK 2>/dev/null || echo 100)
  while :; do
    # fields after the command name: state, ..., utime (14), stime (15)
    st=$(sed 's/^.*) //' "/proc/$1/stat" 2>/dev/null) || return 1
    set -- "$1" "$2" $st
    [ "$3" = Z ] && return 1
    if awk -v u="${14}" -v s="${15}" -v t="$tck" -v want="$2" \
      'BEGIN { exit !((u + s) / t >= want) }'; then return 0; fi
    sleep 0.05
  done
}

finish() {
  echo "$NPASS passed, $NFAIL failed"
  [ "$NFAIL" -eq 0 ]
}
