# The chart task under MPI: 2 ranks write the same chart.csv as 1, byte
# for byte, for both seeds, and a 2-rank run stopped after a few rows
# resumes to the same chart.
# usage: sh tests/chart_mpi.sh PATH/TO/slipcont SOURCE_DIR MPIRUN
. "$(dirname "$0")/cli_common.sh"
MPIRUN=$3
cd "$TMP" || exit 1
# Open MPI refuses root without --allow-run-as-root; CI runners often are.
MPI="$MPIRUN --oversubscribe -np 2"
[ "$(id -u)" -eq 0 ] && MPI="$MPIRUN --oversubscribe --allow-run-as-root -np 2"

cat > small.ini <<'INI'
[model]
name = bk2
driver = frozen
phi = 1.25
[task]
kind = chart
x = alpha
x-from = 2.5
x-to = 7.5
x-steps = 21
y = beta
y-from = 1.5
y-to = 6
y-steps = 19
transient = 600
[output]
plot = no
INI

for seed in fixed previous; do
  "$BIN" run small.ini --quiet --out serial-$seed --threads 1 \
    --set task.seed=$seed || fail "serial run ($seed)"
  OMP_NUM_THREADS=1 $MPI "$BIN" run small.ini --quiet --out mpi-$seed \
    --set task.seed=$seed || fail "2-rank run ($seed)"
  cmp -s serial-$seed/chart.csv mpi-$seed/chart.csv &&
    pass "seed $seed: 2 ranks give the serial chart.csv byte for byte" ||
    fail "seed $seed: 2-rank chart.csv differs from the serial one"
done

OMP_NUM_THREADS=1 $MPI "$BIN" run small.ini \
  --quiet --out resume --stop-after-rows 8 > /dev/null 2>&1
[ -f resume/chart.checkpoint ] && pass "2-rank stop leaves a checkpoint" ||
  fail "no checkpoint after a 2-rank stop"
OMP_NUM_THREADS=1 $MPI "$BIN" run small.ini --out resume 2> resume.err
grep -q 'resuming from .*8 of 19 rows' resume.err &&
  pass "2-rank rerun resumes after 8 rows" || fail "no resume: $(cat resume.err)"
cmp -s resume/chart.csv serial-fixed/chart.csv &&
  pass "resumed 2-rank chart identical to the serial one" ||
  fail "resumed 2-rank chart differs"

finish
