# Starts of a branch told as they are: the summary's counts of added
# starts equal the rows that report them, and a start that was not
# continued belongs to no branch (no note says "branch -1").
# Known answer: examples/branch-symmetric.ini with starts = auto (periods
# 1 and 2) and max-branches = 4: the scene's own start and one added start
# (period 1) take the four segments; the three other added starts find no
# room.  The orbits of one fixed-point search (the three of period 2) are
# continued all or none: with max-branches = 6 two of them would fit, yet
# none is continued, so that none is treated unlike another (an orbit and
# its mirror image).
. "$2/tests/cli_common.sh"

for mb in 4 6; do
D="$TMP/starts$mb"
run_sc run "$SRC/examples/branch-symmetric.ini" --quiet --out "$D" \
  --set task.starts=auto --set task.auto-period=2 --set task.max-branches=$mb \
  --set task.sweep=no --set output.plot=no
expect_rc "branch with automatic starts, max-branches $mb" 0
S="$D/summary.txt"
P="$D/points.csv"
line=$(grep "added starts:" "$S")
count() { echo "$line" | sed -n "s/.* \([0-9][0-9]*\) $1.*/\1/p"; }
ok=$(count "continued both ways")
notfound=$(count "not found by shooting")
noroom=$(count "not continued (max-branches)")
rows_notfound=$(grep -c "added start not found" "$P")
rows_noroom=$(grep -c "added start not continued" "$P")
check "summary: '$line'" [ -n "$ok" -a -n "$notfound" -a -n "$noroom" ]
check "not found: summary ${notfound:-?}, rows $rows_notfound" \
  [ "${notfound:--1}" -eq "$rows_notfound" ]
check "not continued: summary ${noroom:--1}, rows $rows_noroom" \
  [ "${noroom:--1}" -eq "$rows_noroom" ]
check "starts continued: ${ok:-?} (expected 1)" [ "${ok:--1}" -eq 1 ]
check "starts not continued: ${noroom:-?} (expected 3)" [ "${noroom:--1}" -eq 3 ]
check "no note says 'branch -1'" [ "$(grep -c 'branch -1' "$P" "$S" | \
  awk -F: '{n += $2} END {print n}')" -eq 0 ]
done
finish
