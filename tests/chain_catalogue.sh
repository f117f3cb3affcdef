# The event catalogue (docs/chain.md, "Event catalogue"): two blocks
# against bk2's orbit (the same events and itineraries, each single-block
# slip equal to |d' - d| and, driver frozen, to its closed form
# 2 T (1 - 1/phi) / (1 + alpha)), the energy balance on every event, the
# driver's work against a quadrature of bk2's trajectory, random
# thresholds reproducible from their seed whatever the threads, the
# example of 100 blocks, the refusals (exit 2, nothing created), and the
# trajectory of two blocks against bk2's.
# About 3 s of processor time.
# usage: sh tests/chain_catalogue.sh PATH/TO/slipcont SOURCE_DIR
. "$(dirname "$0")/cli_common.sh"

two_blocks() { # $1: driver
  cat >"$TMP/bk2.ini" <<INI
[model]
name = bk2
driver = $1
alpha = 3.3
beta = 1.7
phi = 1.25
v = 0.02
[task]
kind = orbit
d0 = 0.05
iterations = 60
[output]
plot = no
INI
  cat >"$TMP/cat.ini" <<INI
[model]
name = chain
blocks = 2
driver = $1
alpha = 3.3
beta2 = 1.7
phi = 1.25
v = 0.02
[task]
kind = catalogue
d0 = 0.05
events = 60
[output]
plot = no
INI
  run_sc run "$TMP/bk2.ini" --out "$TMP/bk2-$1" --quiet
  expect_rc "bk2 orbit, driver $1" 0
  run_sc run "$TMP/cat.ini" --out "$TMP/cat-$1" --quiet
  expect_rc "two-block catalogue, driver $1" 0
  expect_header "catalogue.csv" "$TMP/cat-$1/catalogue.csv" \
    "seed,event,start,first,count,lo,hi,blocks,slip,released,friction,driver,duration,itinerary"
  expect_rows "two blocks, driver $1: bk2's 60 iterates are 60 events" \
    "$TMP/cat-$1/catalogue.csv" 60
  # orbit.csv: k,d,itinerary; catalogue.csv: ...,slip $9, ..., itinerary $14
  check "driver $1: bk2's itineraries, single slips |d' - d| (1e-12), counts" \
    awk -F, -v frozen="$([ "$1" = frozen ] && echo 1 || echo 0)" '
    function abs(x) { return x < 0 ? -x : x }
    FNR == 1 { next }
    NR == FNR { d[$1] = $2; it[$1] = $3; next }
    { k = $2; n++
      if ($14 != it[k]) { print "event " k ": " $14 " vs bk2 " it[k]; bad = 1 }
      single = ($14 !~ /-/)
      if (single != ($5 == 1)) { print "event " k ": count " $5; bad = 1 }
      if (single && abs($9 - abs(d[k + 1] - d[k])) > 1e-12) {
        print "event " k ": slip " $9 " vs |dd| " abs(d[k + 1] - d[k]); bad = 1 }
      if (single && frozen) {
        T = ($14 == "2") ? 1.7 : 1
        if (abs($9 - 2 * T * (1 - 1 / 1.25) / 4.3) > 1e-12) {
          print "event " k ": slip " $9; bad = 1 }
        nsingle++
      }
      if (frozen && $12 != 0) { print "event " k ": driver " $12; bad = 1 }
    }
    END { if (frozen && nsingle < 10) { print "single slips: " nsingle; bad = 1 }
          exit bad || n != 60 }' "$TMP/bk2-$1/orbit.csv" "$TMP/cat-$1/catalogue.csv"
  # released = friction - driver, each of them computed its own way (the
  # springs' energies, K_i times the slips, the closed-form integral of
  # the springs' force): rounding of numbers of order 1
  check "driver $1: energy balance on every event (1e-13)" \
    awk -F, 'function abs(x) { return x < 0 ? -x : x }
    NR > 1 && abs($10 - ($11 - $12)) > 1e-13 * (1 + abs($11)) { bad = 1 }
    NR > 1 && !($10 > 0) { bad = 1 }
    END { exit bad }' "$TMP/cat-$1/catalogue.csv"
  check "driver $1: start times add duration and a stick phase >= 0" \
    awk -F, 'NR > 2 && $3 < prev { bad = 1 } NR > 1 { prev = $3 + $13 }
    END { exit bad }' "$TMP/cat-$1/catalogue.csv"
}
two_blocks frozen
two_blocks moving

# The driver's work on the first event, V times the integral of Y1 + Y2
# over the slip, by the trapezoid rule on bk2's trajectory sampled every
# 1e-4: its error ~ dtau^2 |Y''| duration / 12, below 1e-8.
cat >"$TMP/traj.ini" <<INI
[model]
name = bk2
alpha = 3.3
beta = 1.7
phi = 1.25
v = 0.02
[task]
kind = orbit
d0 = 0.05
iterations = 1
trajectory = yes
dtau = 1e-4
[output]
plot = no
INI
run_sc run "$TMP/traj.ini" --out "$TMP/traj" --quiet
expect_rc "bk2 trajectory of one iterate" 0
check "the driver's work against the trapezoid rule on bk2's trajectory (1e-7)" \
  awk -F, 'function abs(x) { return x < 0 ? -x : x }
  FNR == 1 { next }
  NR == FNR { if ($6 != 0) { if (have) w += 0.5 * ($1 - t) * (s + $2 + $3)
                             t = $1; s = $2 + $3; have = 1 }
              next }
  FNR == 2 { drv = $12 }
  END { w *= 0.02; printf "quadrature %.12g, catalogue %.12g\n", w, drv
        exit !(abs(w - drv) < 1e-7) }' "$TMP/traj/trajectory.csv" "$TMP/cat-moving/catalogue.csv"

# Trajectories: two blocks through the chain are bk2's, sample for
# sample (Y1, Y2, U1, U2 within 1e-12: closed forms of the same motion in
# other bases; tau within 1e-12 of 1 + tau: stick phases are gaps over V,
# which carry the gaps' rounding 1/V = 50 times), bk2's mode 1 or 2 one
# block slipping, 3 two.
for drv in frozen moving; do
  for m in bk2 chain; do
    if [ $m = bk2 ]; then model="name = bk2
beta = 1.7"; else model="name = chain
blocks = 2
beta2 = 1.7"; fi
    cat >"$TMP/tr-$m.ini" <<INI
[model]
$model
driver = $drv
alpha = 3.3
phi = 1.25
v = 0.02
[task]
kind = orbit
d0 = 0.05
iterations = 8
trajectory = yes
dtau = 0.05
[output]
plot = no
INI
    run_sc run "$TMP/tr-$m.ini" --out "$TMP/tr-$m-$drv" --quiet
    expect_rc "$m trajectory, driver $drv" 0
  done
  check "driver $drv: the chain's trajectory of two blocks is bk2's (1e-12)" \
    awk -F, 'function abs(x) { return x < 0 ? -x : x }
    FNR == 1 { next }
    NR == FNR { for (i = 1; i <= 6; i++) b[FNR, i] = $i; nb = FNR; next }
    { nc = FNR
      if (abs($1 - b[FNR, 1]) > 1e-12 * (1 + abs($1))) bad = 1
      for (i = 2; i <= 5; i++) if (abs($i - b[FNR, i]) > 1e-12) bad = 1
      m = b[FNR, 6]; if ($6 != (m == 3 ? 2 : m > 0 ? 1 : 0)) bad = 1 }
    END { exit bad || nb != nc || nb < 100 }' \
    "$TMP/tr-bk2-$drv/trajectory.csv" "$TMP/tr-chain-$drv/trajectory.csv"
done
expect_header "the chain's trajectory.csv" "$TMP/tr-chain-moving/trajectory.csv" \
  "tau,y1,y2,u1,u2,mode"

# Random thresholds: a seed's rows are the same alone, among other seeds
# and with any number of threads.
cat >"$TMP/rand.ini" <<INI
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
[output]
plot = no
INI
run_sc run "$TMP/rand.ini" --out "$TMP/r3" --quiet --set model.threshold-seed=3
expect_rc "30 blocks, seed 3" 0
run_sc run "$TMP/rand.ini" --out "$TMP/r3b" --quiet --set model.threshold-seed=3
check "the same seed, the same catalogue" cmp -s "$TMP/r3/catalogue.csv" "$TMP/r3b/catalogue.csv"
run_sc run "$TMP/rand.ini" --out "$TMP/r35" --quiet --set "task.seeds=3 5" --threads 2
expect_rc "seeds 3 5, two threads" 0
run_sc run "$TMP/rand.ini" --out "$TMP/r35t" --quiet --set "task.seeds=3 5" --threads 1
check "seeds 3 5: one thread or two, byte for byte" cmp -s "$TMP/r35/catalogue.csv" "$TMP/r35t/catalogue.csv"
grep '^3,' "$TMP/r35/catalogue.csv" >"$TMP/s3"
tail -n +2 "$TMP/r3/catalogue.csv" >"$TMP/a3"
check "seed 3 among two seeds is seed 3 alone" cmp -s "$TMP/s3" "$TMP/a3"
check "seed 5 is another chain" sh -c "[ \$(grep -c '^5,' '$TMP/r35/catalogue.csv') -eq 300 ] && ! cmp -s '$TMP/s3' '$TMP/r35/catalogue.csv'"

# The example: 100 blocks with random thresholds.
run_within 120 run "$SRC/examples/chain100-catalogue.ini" --out "$TMP/ex" --quiet
expect_rc "examples/chain100-catalogue.ini" 0
expect_rows "the example's events" "$TMP/ex/catalogue.csv" 4000
check "the example's mf.csv counts every event" \
  awk -F, 'NR > 1 { n += $4 } NR == 2 { c = $5 } END { exit !(n == 4000 && c == 4000) }' "$TMP/ex/mf.csv"
# Its title names 100 blocks' parameters: broken into lines that fit the
# picture (each quoted piece of gnuplot's title at most 110 characters).
check "the example's plot titles are broken into lines that fit" \
  awk -v q="'" 'index($0, "set title") == 1 { n++; k = split($0, a, q)
    for (i = 2; i <= k; i += 2) if (length(a[i]) > 110) exit 1 }
    END { exit !(n == 2) }' "$TMP/ex/mf.gp" "$TMP/ex/catalogue.gp"

# Refusals: exit status 2, the message, nothing created.
refuse() { # $1: what, $2: expected text, $3...: --set overrides
  what=$1 text=$2
  shift 2
  run_sc run "$TMP/rand.ini" --out "$TMP/no" --quiet "$@"
  expect_rc "$what" 2
  expect_err "$what" "$text"
  check "$what: nothing created" test ! -e "$TMP/no"
}
refuse "betas of the wrong length" "betas holds 3 thresholds; blocks = 30 needs 29" \
  --set model.thresholds=given --set "model.betas=1 2 3"
refuse "a NaN threshold" "'nan' (word 2) is not a finite number" \
  --set model.thresholds=given --set "model.betas=1 nan 28*1"
refuse "a threshold <= 0" "-0.5 (word 3) out of range" \
  --set model.thresholds=given --set "model.betas=1 1 -0.5 27*1"
refuse "betas with a random draw" "give one of them" --set "model.betas=29*1"
refuse "seeds with given thresholds" "seeds draw the thresholds" \
  --set model.thresholds=given --set model.threshold-range= \
  --set "task.seeds=1 2"
refuse "a bad seed" "'x' is not an integer" --set "task.seeds=1 x"
refuse "v = 0" "needs v > 0" --set model.v=0
refuse "a bad range" "valid: 0 < lo <= hi" --set "model.threshold-range=1.2 0.8"
printf '[model]\nname = bk2\n[task]\nkind = catalogue\n' >"$TMP/bk2cat.ini"
run_sc run "$TMP/bk2cat.ini" --out "$TMP/no" --quiet
expect_rc "bk2 has no catalogue" 2
expect_err "bk2 has no catalogue" "model bk2 records no slip events"

finish
