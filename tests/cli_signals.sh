# SIGINT and SIGTERM stop every task, leaving complete files or none.
#  - Between steps: --interrupt-before STEP raises SIGINT at a known place
#    (every task, every step: cli_steps.sh; here a long search stopped
#    before its compute and after it).
#  - Inside a step: a task that polls stops with exit status 1 and
#    "interrupted"; one inside a library call that cannot be stopped (the
#    fixed-point search) is ended by the program SC_CLI_STOP_GRACE_S after
#    the signal with status 128 + signal, its temporaries removed.  The
#    signal is sent once the run has spent processor time that only its
#    compute step can take (computing, cli_common.sh), never after a
#    fixed wait; a signal that did not arrive inside the step fails here.
. "$(dirname "$0")/cli_common.sh"

EX=$SRC/examples

# Between steps, through the hook: a search of 5e7 points (minutes of
# work) is never started; one of the scene's size is never written.
run_sc run "$EX/fixed-point-fig58.ini" --out "$TMP/hook-compute" --quiet \
  --set output.plot=no --set task.steps=50000000 --interrupt-before compute
expect_rc "fixed-point, SIGINT before compute" 1
expect_err "fixed-point, SIGINT before compute" ": interrupted"
check "fixed-point, SIGINT before compute: nothing written" \
  test -z "$(ls -A "$TMP/hook-compute" 2>/dev/null)"
run_sc run "$EX/fixed-point-fig58.ini" --out "$TMP/hook-write" --quiet \
  --set output.plot=no --interrupt-before write
expect_rc "fixed-point, SIGINT before write" 1
expect_err "fixed-point, SIGINT before write" ": interrupted"
check "fixed-point, SIGINT before write: nothing written" \
  test -z "$(ls -A "$TMP/hook-write" 2>/dev/null)"
# the same run without the hook writes its orbits, so the hook is what
# stopped the run above
run_sc run "$EX/fixed-point-fig58.ini" --out "$TMP/hook-none" --quiet \
  --set output.plot=no
expect_rc "fixed-point without the hook" 0
check "fixed-point without the hook: orbits.csv" test -s "$TMP/hook-none/orbits.csv"

# stop NAME SIGNAL SCENE ARGS...: start a long run, send SIGNAL once it is
# computing, leave $RC and $ERR; no temporary may be left.
stop() {
  name=$1
  sig=$2
  shift 2
  out="$TMP/o-$name"
  "$BIN" run "$@" --out "$out" --quiet --set output.plot=no \
    >"$TMP/$name.out" 2>"$TMP/$name.err" &
  pid=$!
  if computing $pid 0.3; then
    kill -"$sig" $pid 2>/dev/null
    sent=yes
  else
    sent=no
  fi
  wait $pid
  RC=$?
  ERR=$(cat "$TMP/$name.err")
  check "$name: SIG$sig sent while it computes (sent: $sent)" test $sent = yes
  no_temporaries "$name" "$out"
}

if [ -r /proc/self/stat ]; then
  # The fixed-point search cannot be stopped: ended after the grace time,
  # 128 + signal, with the note, nothing written.
  stop fixed-point INT "$EX/fixed-point-fig58.ini" --set task.steps=50000000
  expect_rc "fixed-point, SIGINT inside the search" 130
  expect_err "fixed-point" "slipcont: stopped by a signal (unfinished files removed"
  check "fixed-point: no orbits.csv" test ! -e "$TMP/o-fixed-point/orbits.csv"
  stop fixed-point-term TERM "$EX/fixed-point-fig58.ini" --set task.steps=50000000
  expect_rc "fixed-point, SIGTERM inside the search" 143
  # Tasks that poll stop by themselves: status 1, "interrupted".
  stop sweep INT "$EX/logistic-sweep.ini" --set task.steps=2000000 \
    --set task.keep=1
  expect_rc "sweep, SIGINT inside the sweep" 1
  expect_err "sweep, SIGINT inside the sweep" ": interrupted"
  check "sweep: no sweep.csv" test ! -e "$TMP/o-sweep/sweep.csv"
  stop map TERM "$EX/fig55-map.ini" --set task.steps=100000000
  expect_rc "map, SIGTERM while it writes" 1
  expect_err "map, SIGTERM while it writes" ": interrupted"
  check "map: no map.csv" test ! -e "$TMP/o-map/map.csv"
else
  echo "SKIP signals inside a step: no /proc to tell when a run computes"
fi

finish
