#!/usr/bin/env bash
# The whole test suite, as CI runs it: install, build with warnings as
# errors, run ctest; install and build examples/downstream against the
# installed package (CMake and pkg-config, shared and static); then again under AddressSanitizer and UBSan; then the
# MPI build's distributed-chart test.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
jobs=$(nproc)
echo "== release build, -Werror =="
cmake -S . -B build-ci -DCMAKE_BUILD_TYPE=Release -DSLIPCONT_WERROR=ON >/dev/null
cmake --build build-ci -j"$jobs"
(cd build-ci && ctest --output-on-failure -j"$jobs")
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
echo "== MPI build =="
cmake -S . -B build-mpi -DCMAKE_BUILD_TYPE=Release -DSLIPCONT_WERROR=ON \
  -DSLIPCONT_MPI=ON >/dev/null
cmake --build build-mpi -j"$jobs"
(cd build-mpi && ctest --output-on-failure -R mpi)
