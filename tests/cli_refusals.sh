# The corpus of bad input found by probing the program as a new user
# would: each is refused with exit status 2, its message, and
# nothing created; plus inputs that must be accepted (CR line endings).
. "$(dirname "$0")/cli_common.sh"

good="$TMP/good.ini"
cat >"$good" <<'INI'
[model]
name = bk2
alpha = 2.9
[task]
kind = map
from = -0.02
to = 0.02
steps = 11
[output]
plot = no
INI

# refuse NAME EXPECTED-TEXT ARGS...: slipcont run ARGS --out $TMP/o-NAME
# gives status 2, the text, and no output folder; `check` says the same.
refuse() {
  name=$1
  text=$2
  shift 2
  for cmd in check run; do
    run_sc $cmd "$@" --out "$TMP/o-$name"
    expect_rc "$name ($cmd)" 2
    expect_err "$name ($cmd)" "$text"
    check "$name ($cmd): nothing created" test ! -e "$TMP/o-$name"
  done
}

# scene NAME SED-EXPRESSION: a variant of the good scene in $TMP/NAME.ini
scene() { sed -e "$2" "$good" >"$TMP/$1.ini"; }

run_sc check "$good" --out "$TMP/o-good"
expect_rc "good scene" 0

# Numbers: one rule, decimal only; integers without point or exponent.
refuse int-exponent "[task] steps = 1e3 is not an integer: write integers in decimal digits only" \
  "$good" --set task.steps=1e3
refuse int-hex "[task] steps = '0x10' is not an integer: integers are decimal digits, like 1000" \
  "$good" --set task.steps=0x10
refuse int-overflow "[task] steps = 99999999999 out of range (valid: [1, 100000000])" \
  "$good" --set task.steps=99999999999
refuse real-hex "[model] alpha = '0x1.8p1' is not a number: numbers are decimal" \
  "$good" --set model.alpha=0x1.8p1
refuse real-overflow "[model] alpha = 1e400 is too large for a double" \
  "$good" --set model.alpha=1e400

# Text after a section header.
scene header-junk 's/^\[model\]/[model] junk/'
refuse header-junk "header-junk.ini:1: text after the section header: 'junk'" \
  "$TMP/header-junk.ini"
# A comment after a header is fine.
scene header-comment 's/^\[model\]/[model] ; the two blocks/'
run_sc check "$TMP/header-comment.ini" --out "$TMP/o-hc"
expect_rc "comment after a header" 0

# CR-only (old Mac) and CR LF line endings read as LF ones.
tr '\n' '\r' <"$good" >"$TMP/cr.ini"
run_sc check "$TMP/cr.ini" --out "$TMP/o-cr"
expect_rc "CR line endings" 0
sed 's/$/\r/' "$good" >"$TMP/crlf.ini"
run_sc check "$TMP/crlf.ini" --out "$TMP/o-crlf"
expect_rc "CR LF line endings" 0

# A FIFO, a folder as the scene: refused at once (a FIFO blocked forever).
if mkfifo "$TMP/fifo.ini" 2>/dev/null; then
  refuse fifo "fifo.ini: not a regular file" "$TMP/fifo.ini"
fi
refuse folder-scene "not a regular file" "$TMP"

# An output path the system cannot hold: refused before any folder is made.
long=$(printf 'a%.0s' $(seq 1 300))
for cmd in check run; do
  run_sc $cmd "$good" --out "$TMP/o-long/$long"
  expect_rc "long part ($cmd)" 2
  expect_err "long part ($cmd)" "a part of the path is too long (300 characters; at most"
done
check "long part: no parent created" test ! -e "$TMP/o-long"
deep=$TMP/o-deep
i=0
while [ $i -lt 30 ]; do deep=$deep/$(printf 'b%.0s' $(seq 1 150)); i=$((i + 1)); done
run_sc run "$good" --out "$deep"
expect_rc "long path" 2
expect_err "long path" "path too long ("
check "long path: nothing created" test ! -e "$TMP/o-deep"

# A result name taken by a folder: found before computing, by check too.
mkdir -p "$TMP/o-blocked/map.csv"
for cmd in check run; do
  run_sc $cmd "$good" --out "$TMP/o-blocked"
  expect_rc "blocked result ($cmd)" 2
  expect_err "blocked result ($cmd)" "o-blocked/map.csv exists and is not a file"
done
check "blocked result: nothing written" test ! -e "$TMP/o-blocked/summary.txt"

# A trajectory that would write gigabytes (or overflow a sample count).
refuse tiny-dtau "[task] dtau = 1e-300: the trajectory would have at least 6.28e+300 rows (limit 5000000" \
  "$SRC/examples/fig54-moving.ini" --set task.dtau=1e-300

# Numbers never silently wrong.  A map over -1e308..1e308: the grid does
# not overflow (the middle point is exactly 0) and points the model
# refuses are rows that say so, not the end of the run.
run_sc run "$good" --out "$TMP/o-huge" --quiet --set task.from=-1e308 \
  --set task.to=1e308 --set task.steps=5
expect_rc "map over -1e308..1e308" 0
check "map over -1e308..1e308: 5 rows" test "$(($(wc -l <"$TMP/o-huge/map.csv") - 1))" -eq 5
check "map over -1e308..1e308: middle point 0 defined" grep -q '^0,0,' "$TMP/o-huge/map.csv"
# d = 1e299..1e300 absorbs any shift of f: no "neutral family" there.
cat >"$TMP/fp-huge.ini" <<'INI'
[model]
name = bk2
alpha = 2.9
[task]
kind = fixed-point
period = 1
from = 1e299
to = 1e300
[output]
plot = no
INI
run_sc run "$TMP/fp-huge.ini" --out "$TMP/o-fp-huge" --quiet
expect_rc "fixed points at 1e300" 0
check "fixed points at 1e300: none reported" test "$(wc -l <"$TMP/o-fp-huge/orbits.csv")" -eq 1

# Log-spaced grids (x-scale = log): equal ratios, the ends exact; ends of
# different signs or 0 refused.
cat >"$TMP/logsweep.ini" <<'INI'
[model]
name = logistic
[task]
kind = sweep
parameter = r
from = 0.01
to = 1
steps = 3
x-scale = log
iterations = 10
keep = 1
d0 = 0.3
[output]
plot = no
INI
run_sc run "$TMP/logsweep.ini" --out "$TMP/o-logsweep" --quiet
expect_rc "log sweep" 0
p=$(awk -F, 'NR > 1 {print $1}' "$TMP/o-logsweep/sweep.csv" | sort -g | uniq | tr '\n' ' ')
check "log sweep: r = 0.01 0.1 1 (got $p)" test "$p" = "0.01 0.10000000000000001 1 "
refuse log-from-zero "[task] x-scale = log needs from and to of one sign and not 0 (from 0, to 1)" \
  "$TMP/logsweep.ini" --set task.from=0

finish
