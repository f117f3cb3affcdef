#!/usr/bin/env bash
# The whole test suite, as CI runs it: install, build with warnings as
# errors, run ctest; check that a -march=native build computes the same
# numbers; install and build examples/downstream against the installed
# package (CMake and pkg-config, shared and static); then again under
# AddressSanitizer and UBSan; then the MPI build's distributed-chart test.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
jobs=$(nproc)
echo "== release build, -Werror =="
cmake -S . -B build-ci -DCMAKE_BUILD_TYPE=Release -DSLIPCONT_WERROR=ON >/dev/null
cmake --build build-ci -j"$jobs"
(cd build-ci && ctest --output-on-failure -j"$jobs")
echo "== a build for this processor (SLIPCONT_NATIVE) computes the same numbers =="
scripts/check-native.sh build-ci build-native
echo "== install, and a downstream project built against it =="
rm -rf build-ci/prefix
cmake --install build-ci --prefix build-ci/prefix >/dev/null
sh examples/downstream/check.sh build-ci/prefix build-ci/downstream
echo "== AddressSanitizer + UndefinedBehaviorSanitizer =="
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DSLIPCONT_WERROR=ON \
  -DSLIPCONT_SANITIZE=ON >/dev/null
cmake --build build-asan -j"$jobs"
# LeakSanitizer cannot run under ptrace-restricted containers; leaks are
# still reported where it can.
(cd build-asan && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --output-on-failure -j"$jobs")
echo "== API reference (doxygen) =="
if command -v doxygen >/dev/null 2>&1; then
  rm -rf build/doc && mkdir -p build/doc
  doxygen docs/Doxyfile
  nwarn=$(grep -c 'warning:' build/doc/warnings.txt || true)
  echo "build/doc/html: $nwarn warnings (build/doc/warnings.txt)"
  if [ "$nwarn" != 0 ]; then
    cat build/doc/warnings.txt
    echo "every public declaration is documented: fix the warnings above" >&2
    exit 1
  fi
else
  echo "doxygen not installed: skipped"
fi
echo "== fuzzing the scene parser (libFuzzer, 20 s) =="
if command -v clang >/dev/null 2>&1; then
  CC=clang cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSLIPCONT_FUZZ=ON -DSLIPCONT_TESTS=OFF -DSLIPCONT_WERROR=ON >/dev/null
  cmake --build build-fuzz -j"$jobs" --target fuzz_scene >/dev/null
  rm -rf build-fuzz/new && mkdir -p build-fuzz/new
  build-fuzz/fuzz_scene -max_total_time=20 -timeout=5 -rss_limit_mb=2048 \
    -print_final_stats=1 build-fuzz/new fuzz/corpus 2>&1 |
    grep -E 'stat::number_of_executed_units|Done|ERROR|SUMMARY' || true
  # A crash leaves a crash-* file and a non-zero status above; say so.
  if ls crash-* leak-* timeout-* >/dev/null 2>&1; then
    echo "fuzz_scene found an input that fails: $(ls crash-* leak-* timeout-* 2>/dev/null)"
    exit 1
  fi
else
  echo "clang not installed: skipped"
fi
echo "== MPI build =="
cmake -S . -B build-mpi -DCMAKE_BUILD_TYPE=Release -DSLIPCONT_WERROR=ON \
  -DSLIPCONT_MPI=ON >/dev/null
cmake --build build-mpi -j"$jobs"
(cd build-mpi && ctest --output-on-failure -R mpi)
