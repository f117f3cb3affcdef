# The files and auxiliary values a scene names besides its keys' own
# values (a branch's starts, auto-d and auto-at; a curve's start, overlay
# and also): each is checked by `check`, read as a bounded regular file
# (a FIFO or a device is refused, never waited on), and refused with exit
# status 2 before anything is created; control characters in values are
# refused.  A hang is a failure: every call has a time limit.
. "$(dirname "$0")/cli_common.sh"


# refuse NAME TEXT ARGS...: check and run give status 2 and TEXT, and run
# creates no output folder.
refuse() {
  name=$1
  text=$2
  shift 2
  for cmd in check run; do
    run_within 20 $cmd "$@" --out "$TMP/o-$name" --quiet
    expect_rc "$name ($cmd)" 2
    expect_err "$name ($cmd)" "$text"
    check "$name ($cmd): nothing created" test ! -e "$TMP/o-$name"
  done
}

cat >"$TMP/branch.ini" <<'INI'
[model]
name = bk2
driver = frozen
beta = 2.5
[task]
kind = branch
parameter = alpha
from = 2.8
to = 4
starts = auto
auto-at = 3.9
auto-period = 2
sweep = no
[output]
plot = no
INI
run_within 20 check "$TMP/branch.ini" --out "$TMP/o-good"
expect_rc "good branch scene" 0

mkfifo "$TMP/fifo" || fail "mkfifo"
mkdir -p "$TMP/folder"
printf 'label,parameter,value,d,period\nPD,alpha,3.1525203451104331,0.22708407773008357,4\nGR,alpha,5.5,0.19577564632151551,4\nGR,beta,3,0.19577564632151551,4\nGR,alpha,0.5,0.19577564632151551,4\n' >"$TMP/pts.csv"

# auto-d and auto-at: checked by check, before the run (they were read
# only while running: exit 1 with an empty folder, or silently ignored).
refuse auto-d-word "[task] auto-d = zz (valid: 'LO HI', two numbers with LO < HI)" \
  "$TMP/branch.ini" --set task.auto-d=zz
refuse auto-d-order "[task] auto-d = 0.5 -0.5 (valid: 'LO HI'" \
  "$TMP/branch.ini" --set "task.auto-d=0.5 -0.5"
refuse auto-d-three "[task] auto-d = -0.5 0 0.5 (valid" \
  "$TMP/branch.ini" --set "task.auto-d=-0.5 0 0.5"
refuse auto-at-word "[task] auto-at: value 1, 'zz', is not a number" \
  "$TMP/branch.ini" --set task.auto-at=zz
refuse auto-at-second "[task] auto-at: value 2, 'x', is not a number" \
  "$TMP/branch.ini" --set "task.auto-at=3.9 x"
refuse auto-at-outside "[task] auto-at: value 2, 4.5, is outside [from, to] = [2.8, 4]" \
  "$TMP/branch.ini" --set "task.auto-at=3.9 4.5"

# starts = FILE:N: a FIFO, a device, a folder, rows outside [from, to] or
# of another parameter.
refuse starts-fifo "[task] starts: $TMP/fifo: not a regular file: it is a pipe (FIFO)" \
  "$TMP/branch.ini" --set "task.starts=$TMP/fifo:1"
refuse starts-zero "[task] starts: /dev/zero: not a regular file: it is a device" \
  "$TMP/branch.ini" --set "task.starts=/dev/zero:100000000"
refuse starts-folder "[task] starts: $TMP/folder: not a regular file: it is a folder" \
  "$TMP/branch.ini" --set "task.starts=$TMP/folder:1"
refuse starts-outside "'$TMP/pts.csv:2': alpha = 5.5 (valid: inside [from, to] = [2.8, 4])" \
  "$TMP/branch.ini" --set "task.starts=$TMP/pts.csv:2"
refuse starts-param "'$TMP/pts.csv:3' is a point in beta (valid: a row of a branch continued in alpha)" \
  "$TMP/branch.ini" --set "task.starts=$TMP/pts.csv:3"
refuse starts-period "'3.9 0.2 0': period 0 (valid: [1, max-period = 16])" \
  "$TMP/branch.ini" --set "task.starts=3.9 0.2 0"
case $ERR in
*"(valid:"*"(valid:"*) fail "starts: (valid: ...) given twice: $ERR" ;;
*) pass "starts: (valid: ...) given once" ;;
esac

# The curve task: start, overlay and also.
sed '/^d0 = /d' "$SRC/examples/curve-fig58-graze4.ini" >"$TMP/graze.ini"
run_within 20 check "$TMP/graze.ini" --set "task.start=$TMP/pts.csv:2" --out "$TMP/o-good"
expect_rc "good curve scene" 0
refuse start-fifo "[task] start: $TMP/fifo: not a regular file: it is a pipe (FIFO)" \
  "$TMP/graze.ini" --set "task.start=$TMP/fifo:1"
refuse start-zero "[task] start: /dev/zero: not a regular file: it is a device" \
  "$TMP/graze.ini" --set "task.start=/dev/zero:100000000"
# a row whose value lies outside the parameter's range (alpha > 0), with a
# box that reaches it: the box end is refused against the range
refuse box-range "[task] x-from = -1 out of range of alpha (valid: (0, 1000000])" \
  "$TMP/graze.ini" --set "task.start=$TMP/pts.csv:4" --set task.x-from=-1
refuse box-range-y "[task] y-to = 2e6 out of range of beta (valid: (0, 1000000])" \
  "$TMP/graze.ini" --set "task.start=$TMP/pts.csv:2" --set task.y-to=2e6
refuse start-outside "the start's alpha = 0.5 (its row of start) lies outside [1.5, 7.5]" \
  "$TMP/graze.ini" --set "task.start=$TMP/pts.csv:4"
common="$TMP/graze.ini --set task.start=$TMP/pts.csv:2"
# shellcheck disable=SC2086
refuse overlay-fifo "[task] overlay = $TMP/fifo cannot be read: $TMP/fifo: not a regular file: it is a pipe (FIFO)" \
  $common --set "task.overlay=$TMP/fifo"
# shellcheck disable=SC2086
refuse overlay-zero "cannot be read: /dev/zero: not a regular file: it is a device" \
  $common --set "task.overlay=/dev/zero"
# shellcheck disable=SC2086
refuse overlay-folder "cannot be read: $TMP/folder: not a regular file: it is a folder" \
  $common --set "task.overlay=$TMP/folder"
mkdir -p "$TMP/also-fifo"
mkfifo "$TMP/also-fifo/curve.csv"
# shellcheck disable=SC2086
refuse also-fifo "[task] also: $TMP/also-fifo/curve.csv: not a regular file: it is a pipe (FIFO)" \
  $common --set "task.also=$TMP/also-fifo"

# Control characters in a value: refused, from --set and from the file,
# and never repeated raw in the message.
esc=$(printf '\033')
refuse set-control "control character 0x1b at position 4 of the value" \
  "$TMP/branch.ini" --set "task.auto-at=3.9${esc}3.8"
case $ERR in
*"$esc"*) fail "set-control: the message repeats the control character" ;;
*) pass "set-control: the message shows it as '?'" ;;
esac
tab=$(printf '\t')
run_within 20 check "$TMP/branch.ini" --set "task.auto-at=3.9${tab}3.8" --out "$TMP/o-tab"
expect_rc "a tab between values is accepted" 0
printf '[model]\nname = bk2\n[task]\nkind = map\nfrom = 0\nto = 0.1\001\n' >"$TMP/ctl.ini"
refuse file-control "ctl.ini:6: [task] to: control character 0x01 at position 4 of the value" \
  "$TMP/ctl.ini"

# A run that fails while computing (the only start is on no orbit) leaves
# no folder it created.
cp "$SRC/tests/scenes/branch-no-orbit.ini" "$TMP/noorbit.ini"
run_within 20 run "$TMP/noorbit.ini" --out "$TMP/o-noorbit" --quiet
expect_rc "no orbit at the start" 1
check "no orbit at the start: no folder left" test ! -e "$TMP/o-noorbit"

finish
