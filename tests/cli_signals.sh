# SIGINT and SIGTERM stop every task, leaving complete files or none:
# a task that polls stops with exit status 1; one inside a library call
# that cannot be stopped (the fixed-point search) is ended by the program
# a second after the signal with status 128 + signal, its temporaries
# removed.  A run that ignored the signal would finish with status 0 and
# write its results: that is what fails here (no time is asserted).
. "$(dirname "$0")/cli_common.sh"

# stop NAME SIGNAL SCENE ARGS...: start a long run, signal it after half a
# second, expect a non-zero status, no result file and no temporary.
stop() {
  name=$1
  sig=$2
  shift 2
  out="$TMP/o-$name"
  "$BIN" run "$@" --out "$out" --quiet --set output.plot=no \
    >"$TMP/$name.out" 2>"$TMP/$name.err" &
  pid=$!
  sleep 0.5
  kill -"$sig" $pid 2>/dev/null
  wait $pid
  RC=$?
  ERR=$(cat "$TMP/$name.err")
  check "$name: stopped by SIG$sig (exit $RC: $ERR)" test $RC -ne 0
  leftovers=$(ls -A "$out" 2>/dev/null | grep '^\.' | tr '\n' ' ')
  check "$name: no temporary left ($leftovers)" test -z "$leftovers"
}

stop fixed-point INT "$SRC/examples/fixed-point-fig58.ini" --set task.steps=5000000
expect_err "fixed-point" "slipcont: stopped by a signal (unfinished files removed"
check "fixed-point: no orbits.csv" test ! -e "$TMP/o-fixed-point/orbits.csv"
stop fixed-point-term TERM "$SRC/examples/fixed-point-fig58.ini" --set task.steps=5000000
stop sweep INT "$SRC/examples/logistic-sweep.ini" --set task.steps=2000000 \
  --set task.keep=1
check "sweep: no sweep.csv" test ! -e "$TMP/o-sweep/sweep.csv"
stop map TERM "$SRC/examples/fig55-map.ini" --set task.steps=100000000
check "map: no map.csv" test ! -e "$TMP/o-map/map.csv"

finish
