# Every scene and program in examples/ is run by a test that holds it to
# the known answer of its opening comment (docs/contributing.md): each one's
# name appears in a test of tests/ that runs it.  A new example without a
# test fails here, with its name.
. "$(dirname "$0")/cli_common.sh"

for f in "$SRC"/examples/*.ini "$SRC"/examples/*.c; do
  name=$(basename "$f")
  name=${name%.*}
  # a run of it: a path to it, a run helper (example, curve, ex) or a
  # loop of them naming it, or the test example_NAME
  if grep -l -E "(examples/$name\.(ini|c)|^(example|curve|ex) $name( |\$)|^for [a-z]+ in (.* )?$name(;| |\$)|example_$name)" \
    "$SRC"/tests/*.sh "$SRC"/tests/*.c "$SRC"/tests/*.cmake >/dev/null 2>&1; then
    pass "$name is run by a test"
  else
    fail "$name is run by no test in tests/"
  fi
done

finish
