# Bad input is refused before any work: exit status 2, one message naming
# file, line, key and valid range, and nothing created in the output
# folder.
. "$(dirname "$0")/cli_common.sh"

good="$TMP/good.ini"
cat >"$good" <<'INI'
; a good scene
[model]
name = bk2
driver = moving
alpha = 2.9
beta = 1
phi = 1.25

[task]
kind = sweep
parameter = v
from = 0.025
to = 0.015
steps = 4
iterations = 20
keep = 10
d0 = 0.02

[output]
plot = no
INI

run_sc check "$good" --out "$TMP/never"
expect_rc "check good scene" 0
expect_out "check good scene" "$good: ok (model bk2, task sweep"
check "check creates nothing" test ! -e "$TMP/never"

# bad NAME SED-EXPRESSION EXPECTED-TEXT...: edit the good scene, run it,
# expect status 2, each text in the message, and no output folder.
bad() {
  name=$1
  expr=$2
  shift 2
  scene="$TMP/$name.ini"
  sed -e "$expr" "$good" >"$scene"
  out="$TMP/out-$name"
  run_sc run "$scene" --out "$out"
  expect_rc "$name" 2
  for t in "$@"; do expect_err "$name" "$t"; done
  check "$name: no output folder" test ! -e "$out"
}

bad unknown-section 's/^\[output\]/[outputs]/' \
  "$TMP/unknown-section.ini:19: unknown section [outputs]" "valid: model, task, accuracy, output"
bad unknown-key 's/^phi = 1.25/psi = 1.25/' \
  "$TMP/unknown-key.ini:7: [model] unknown key 'psi' for model bk2" "alpha, beta, phi, v"
bad unknown-task-key 's/^keep = 10/kept = 10/' \
  "$TMP/unknown-task-key.ini:16: [task] unknown key 'kept' for kind sweep"
bad duplicate-key 's/^beta = 1$/beta = 1\nbeta = 2/' \
  "$TMP/duplicate-key.ini:7: [model] duplicate key 'beta' (first at line 6)"
bad bad-number 's/^alpha = 2.9/alpha = 2,9/' \
  "$TMP/bad-number.ini:5: [model] alpha = '2,9' is not a number: numbers are decimal, like 0.025, -3 or 1e-3 (valid: (0, 1000000])"
bad nan 's/^d0 = 0.02/d0 = NaN/' \
  "$TMP/nan.ini:17: [task] d0 = NaN is not a finite number"
bad out-of-range 's/^alpha = 2.9/alpha = -1/' \
  "$TMP/out-of-range.ini:5: [model] alpha = -1 out of range (valid: (0, 1000000])"
bad from-out-of-range 's/^from = 0.025/from = -0.1/' \
  "$TMP/from-out-of-range.ini:12: [task] from = -0.1 out of range of v (valid: [0, 1000])"
bad missing-key '/^parameter = v/d' \
  "$TMP/missing-key.ini:9: [task] missing required key 'parameter' (valid: alpha|beta|phi|v|gamma)"
bad missing-kind '/^kind = sweep/d' \
  "$TMP/missing-kind.ini:9: [task] missing required key 'kind'" "sweep"
bad steps-zero 's/^steps = 4/steps = 0/' \
  "$TMP/steps-zero.ini:14: [task] steps = 0 out of range (valid: [1, 10000000])"
bad keep-too-large 's/^keep = 10/keep = 30/' \
  "$TMP/keep-too-large.ini:16: [task] keep = 30 is more than iterations = 20"
bad bad-choice 's/^d0 = 0.02/d0 = 0.02\nseed = random/' \
  "$TMP/bad-choice.ini:18: [task] seed = 'random' is not valid (valid: fixed|previous)"
bad bad-option 's/^driver = moving/driver = stopped/' \
  "$TMP/bad-option.ini:4: [model] driver = 'stopped' is not valid (valid: moving|frozen)"
bad bad-kind 's/^kind = sweep/kind = chart-of-everything/' \
  "$TMP/bad-kind.ini:10: [task] kind = 'chart-of-everything' is not a task"
bad bad-preset 's/^\[output\]/[accuracy]\npreset = sloppy\n[output]/' \
  "$TMP/bad-preset.ini:20: [accuracy] preset = 'sloppy' is not valid (valid: fast|default|precise)"

# An override is refused like a line of the file.
run_sc run "$good" --set model.alpha=-1 --out "$TMP/out-set"
expect_rc "bad --set" 2
expect_err "bad --set" "--set model.alpha=-1: [model] alpha = -1 out of range (valid: (0, 1000000])"
check "bad --set: no output folder" test ! -e "$TMP/out-set"
run_sc run "$good" --set alpha=3 --out "$TMP/out-set"
expect_rc "--set without a section" 2
expect_err "--set without a section" "expected section.key=value"

# Trajectory needs a model with continuous motion.
cat >"$TMP/traj.ini" <<'INI'
[model]
name = logistic
[task]
kind = orbit
d0 = 0.3
trajectory = yes
INI
run_sc run "$TMP/traj.ini" --out "$TMP/out-traj"
expect_rc "trajectory with logistic" 2
expect_err "trajectory with logistic" "$TMP/traj.ini:6: [task] trajectory = yes: model logistic has no continuous motion"

# A missing scene file.
run_sc run "$TMP/nope.ini" --out "$TMP/out-nope"
expect_rc "missing file" 2
expect_err "missing file" "$TMP/nope.ini: cannot open the scene file"

# An output folder that cannot be created (under a regular file; this
# holds even for root).
echo x >"$TMP/plain"
run_sc run "$good" --out "$TMP/plain/out"
expect_rc "unwritable output folder (--out)" 2
expect_err "unwritable output folder (--out)" "--out: [output] dir = $TMP/plain/out"
run_sc check "$good" --out "$TMP/plain/out"
expect_rc "unwritable output folder (check)" 2
expect_err "unwritable output folder (check)" "is not a folder"
sed -e "s|^plot = no|plot = no\ndir = $TMP/plain/sub|" "$good" >"$TMP/dir.ini"
run_sc run "$TMP/dir.ini"
expect_rc "unwritable output folder (scene)" 2
expect_err "unwritable output folder (scene)" "$TMP/dir.ini:21: [output] dir = $TMP/plain/sub"

# Usage errors.
run_sc
expect_rc "no command" 2
run_sc frobnicate
expect_rc "unknown command" 2
expect_err "unknown command" "unknown command 'frobnicate'"
run_sc run "$good" --frob
expect_rc "unknown option" 2
run_sc run
expect_rc "run without a scene" 2
run_sc run "$good" --threads 0
expect_rc "--threads 0" 2
run_sc --help
expect_rc "--help" 0
expect_out "--help" "usage: slipcont COMMAND"
run_sc run --help
expect_rc "run --help" 0
expect_out "run --help" "[task] kind = sweep"
expect_out "run --help" "direction"
run_sc help orbit
expect_rc "help orbit" 0
expect_out "help orbit" "trajectory-iterates"
run_sc models
expect_rc "models" 0
expect_out "models" "alpha      (0, 1000000]"
expect_out "models" "driver     moving|frozen"

finish
