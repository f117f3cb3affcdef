# The one run skeleton (src/cli/tasks.h): every task, interrupted by a
# SIGINT just before each of its steps (--interrupt-before STEP), stops
# with status 1 and "interrupted", leaves no temporary, and leaves exactly
# the files of the steps that ran: nothing before compute, no summary
# before the summary step, no gnuplot script before the plots step.  The
# same runs without the hook finish with status 0 and every file, so a
# hook that did nothing would fail here.
. "$(dirname "$0")/cli_common.sh"

# count DIR PATTERN: files in DIR whose names match PATTERN.
count() { find "$1" -maxdepth 1 -type f -name "$2" 2>/dev/null | wc -l; }

# steps NAME SCENE ARGS...: the task of SCENE (small settings), whole and
# interrupted before each step.
steps() {
  name=$1
  shift
  out="$TMP/$name-whole"
  run_sc run "$@" --out "$out" --quiet --set output.plot=no
  expect_rc "$name whole" 0
  check "$name whole: summary and a plot script" \
    test "$(count "$out" summary.txt)" -eq 1 -a "$(count "$out" '*.gp')" -ge 1
  for step in prepare compute write summary plots report; do
    out="$TMP/$name-$step"
    run_sc run "$@" --out "$out" --quiet --set output.plot=no \
      --interrupt-before "$step"
    expect_rc "$name before $step" 1
    expect_err "$name before $step" ": interrupted"
    no_temporaries "$name before $step" "$out"
    nsum=$(count "$out" summary.txt)
    ngp=$(count "$out" '*.gp')
    case $step in
    prepare | compute)
      check "$name before $step: no file ($(ls "$out" | tr '\n' ' '))" \
        test "$(count "$out" '*')" -eq 0 ;;
    write | summary)
      check "$name before $step: no summary, no plot script" \
        test "$nsum" -eq 0 -a "$ngp" -eq 0 ;;
    plots)
      check "$name before plots: summary, no plot script" \
        test "$nsum" -eq 1 -a "$ngp" -eq 0 ;;
    report)
      check "$name before report: summary and plot scripts" \
        test "$nsum" -eq 1 -a "$ngp" -ge 1 ;;
    esac
  done
}

EX=$SRC/examples
steps orbit "$EX/fig54-moving.ini" --set task.iterations=20
steps map "$EX/fig55-map.ini" --set task.steps=11
steps chart "$EX/chart-cubic.ini" --set task.x-steps=5 --set task.y-steps=5
steps fixed-point "$EX/fixed-point-logistic.ini"
steps branch "$EX/branch-logistic.ini" --set task.sweep-steps=20
steps sweep "$EX/logistic-sweep.ini" --set task.steps=20
steps curve "$EX/curve-cubic.ini"

# The hook names a step of the skeleton, nothing else.
run_sc run "$EX/fig55-map.ini" --out "$TMP/bad" --interrupt-before release
expect_rc "--interrupt-before release" 2
expect_err "--interrupt-before release" "--interrupt-before needs a step"

finish
