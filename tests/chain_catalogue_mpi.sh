# The catalogue task under MPI (docs/chain.md, "Event catalogue"): seed i
# runs on rank i mod size and rank 0 writes every file, so 2 ranks write
# the catalogue.csv and mf.csv of one process byte for byte (three seeds:
# rank 0 runs two of them, rank 1 one).
# usage: sh tests/chain_catalogue_mpi.sh PATH/TO/slipcont SOURCE_DIR MPIRUN
. "$(dirname "$0")/cli_common.sh"
MPIRUN=$3
cd "$TMP" || exit 1
# Open MPI refuses root without --allow-run-as-root; CI runners often are.
MPI="$MPIRUN --oversubscribe -np 2"
[ "$(id -u)" -eq 0 ] && MPI="$MPIRUN --oversubscribe --allow-run-as-root -np 2"

cat > seeds.ini <<'INI'
[model]
name = chain
blocks = 30
driver = frozen
thresholds = random
threshold-range = 0.6 1.4
[task]
kind = catalogue
events = 300
skip = 50
seeds = 3 5 7
[output]
plot = no
INI

"$BIN" run seeds.ini --quiet --out serial --threads 1 || fail "serial run"
OMP_NUM_THREADS=1 $MPI "$BIN" run seeds.ini --quiet --out mpi ||
  fail "2-rank run"
for f in catalogue.csv mf.csv; do
  cmp -s serial/$f mpi/$f &&
    pass "seeds 3 5 7: 2 ranks give the serial $f byte for byte" ||
    fail "seeds 3 5 7: the 2-rank $f differs from the serial one"
done
[ "$(grep -c '^7,' mpi/catalogue.csv)" -eq 300 ] &&
  pass "seed 7 (rank 0's second seed) has its 300 rows" ||
  fail "seed 7's rows: $(grep -c '^7,' mpi/catalogue.csv)"
[ "$(grep -c '^5,' mpi/catalogue.csv)" -eq 300 ] &&
  pass "seed 5 (rank 1's) has its 300 rows" ||
  fail "seed 5's rows: $(grep -c '^5,' mpi/catalogue.csv)"

finish
