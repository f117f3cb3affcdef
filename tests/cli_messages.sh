# What the program tells a user: messages in user terms.  Every message
# a scene can trigger names what and where without the library's
# function names (sc_...), without text cut mid-sentence ("at )") and
# without the valid values given twice; help texts state the model's laws
# with their parameters.
. "$(dirname "$0")/cli_common.sh"

# The friction law of `slipcont models` shows gamma, the parameter that
# scales the velocity weakening.
run_sc models
expect_rc "models" 0
line=$(printf '%s\n' "$OUT" | grep '^  friction ')
case $line in
*"T_i / (1 + gamma |U_i - V_s|)"*) pass "models: the friction law shows gamma" ;;
*) fail "models: the friction law '$line' lacks gamma" ;;
esac

# clean WHAT TEXT: TEXT names no library function (sc_...: ), has no
# empty "at )" left by a cut message, and gives the valid values once.
clean() {
  if printf '%s\n' "$2" | grep -q 'sc_[a-z0-9_]*: '; then
    fail "$1: names a library function: $(printf '%s\n' "$2" | grep -o 'sc_[a-z0-9_]*: ' | head -n 1)"
  else pass "$1: no library function named"; fi
  case $2 in
  *"at )"*) fail "$1: a cut message ('at )')" ;;
  *) pass "$1: no cut message" ;;
  esac
  if printf '%s\n' "$2" | grep -q '(valid:.*(valid:'; then
    fail "$1: the valid values given twice"
  else pass "$1: the valid values given at most once"; fi
}
# clean_dir WHAT DIR: every file a run wrote, and its stderr.
clean_dir() { clean "$1" "$ERR$(cat "$2"/*.csv "$2"/*.txt 2>/dev/null)"; }


# A branch whose one start is on no orbit: the map is a shift there
# (every iterate a single-block slip), so the message must not speak of
# a family, must say where (the key d0) and what to do.
cp "$SRC/tests/scenes/branch-no-orbit.ini" "$TMP/noorbit.ini"
run_within 120 run "$TMP/noorbit.ini" --out "$TMP/noorbit"
expect_rc "start on no orbit" 1
clean "start on no orbit" "$ERR"
expect_err "start on no orbit" "noorbit.ini:16: [task] d0 = 5 at alpha = 2.8: no period-2 orbit through d = 5"
expect_err "start on no orbit" "run the fixed-point task there (kind = fixed-point, period = 1..2, [model] alpha = 2.8)"
case $ERR in
*family*) fail "start on no orbit: the message speaks of a family ($ERR)" ;;
*) pass "start on no orbit: no family where there is no orbit" ;;
esac
# Newton that cannot converge from the guess.
run_within 120 run "$TMP/noorbit.ini" --out "$TMP/noconv" --set task.d0=0.0001 --set task.period=3
expect_rc "start that does not converge" 1
clean "start that does not converge" "$ERR"
expect_err "start that does not converge" "[task] d0 = 0.0001 at alpha = 2.8: no period-3 orbit found from it (no Newton step decreases"
# The same start among others (at inside the interval): a row whose note
# says what and what to do, in points.csv and summary.txt.
run_within 120 run "$TMP/noorbit.ini" --out "$TMP/row" --quiet --set task.at=2.9 --set task.d0=3
expect_rc "added start on no orbit" 0
clean_dir "added start on no orbit" "$TMP/row"
check "added start on no orbit: the row says what to do" \
  grep -q '^EP,alpha,2.8999.*no period-2 orbit through d = 3:.*the fixed-point task at this parameter value finds the orbits there' "$TMP/row/points.csv"

# A curve whose start is not on its curve: where, why, what to do.
run_within 120 run "$SRC/examples/curve-fig58-fold1.ini" --out "$TMP/curve-d0" --quiet \
  --set task.d0=0.9 --set output.plot=no
expect_rc "curve start off the curve" 1
clean "curve start off the curve" "$ERR"
expect_err "curve start off the curve" "[task] d0 = 0.9 (period 1 at alpha = 2.99253067443, beta = 2.5): the start is not on a fold curve ("
expect_err "curve start off the curve" "start from a row labelled LP, located by the branch task in alpha"
check "curve start off the curve: no folder left" test ! -e "$TMP/curve-d0"

# A curve that ends next to d*, where the locating Newton's callback
# fails: its notes whole ("callback failed (1) at );" before).
run_within 120 run "$SRC/examples/curve-fig58-fold4.ini" --out "$TMP/fold4" --quiet \
  --set output.plot=no
expect_rc "curve-fig58-fold4" 0
clean_dir "curve-fig58-fold4" "$TMP/fold4"
check "curve-fig58-fold4: the SW note whole" grep -q \
  'the multiplier is singular on this border: callback failed (1) at iteration 1); d - d\* at the onset (block 2)$' \
  "$TMP/fold4/summary.txt"

# Library messages reached through a scene's values.
run_within 120 check "$TMP/noorbit.ini" --set accuracy.newton-ftol=1
expect_rc "accuracy out of range" 2
clean "accuracy out of range" "$ERR"
run_within 120 check "$TMP/noorbit.ini" --set "task.starts=2.9 0.2 0"
expect_rc "a start's period 0" 2
clean "a start's period 0" "$ERR"
expect_err "a start's period 0" "'2.9 0.2 0': period 0 (valid: [1, max-period = "
printf '[model]\nname = bk2\nalpha = 2.9\n[task]\nkind = map\nfrom = -1e308\nto = 1e308\nsteps = 5\n[output]\nplot = no\n' >"$TMP/map.ini"
run_within 120 run "$TMP/map.ini" --out "$TMP/map" --quiet
expect_rc "map over -1e308..1e308" 0
clean_dir "map over -1e308..1e308" "$TMP/map"

finish
