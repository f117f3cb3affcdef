#!/usr/bin/env bash
# A build for this processor (SLIPCONT_NATIVE=ON, -march=native) computes
# the same numbers as the portable build, bit for bit.  Two checks:
#   - no fused multiply-add in the native libraries' machine code: the
#     compiler was told not to fuse (-ffp-contract=off), and a fused
#     operation anywhere would round differently from the portable build
#     on some input, whether or not the scenes below meet it;
#   - both builds run the same scenes (a chart, a sweep, an orbit, a
#     branch with its special points, a fold curve) and every data file
#     they write must be byte-identical, and their summaries identical but
#     for the date, the output directory and the run time.
#
# usage: scripts/check-native.sh PORTABLE_BUILD_DIR [NATIVE_BUILD_DIR]
#   PORTABLE_BUILD_DIR  a configured and built default build (its slipcont)
#   NATIVE_BUILD_DIR    where the native build goes (default build-native)
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 1 ] || [ ! -x "$1/slipcont" ]; then
  echo "check-native: usage: $0 PORTABLE_BUILD_DIR [NATIVE_BUILD_DIR]" \
    "(the first must hold a built slipcont)" >&2
  exit 2
fi
portable=$1
native=${2:-build-native}
cmake -S . -B "$native" -DCMAKE_BUILD_TYPE=Release -DSLIPCONT_WERROR=ON \
  -DSLIPCONT_NATIVE=ON -DSLIPCONT_TESTS=OFF >/dev/null
cmake --build "$native" -j"$(nproc)" --target slipcont_cli >/dev/null
# fused multiply-add mnemonics: x86-64 (vfmadd231sd, vfmaddsub132pd,
# vfnmsub213pd, ...) and AArch64 (fmadd, fmsub, fnmadd, fnmsub, fmla, fmls)
x86='v?fn?m(add|sub|addsub|subadd)[0-9]*[ps][sdh]'
arm='fn?m(add|sub)|fml[as]'
fused="[[:space:]]($x86|$arm)[[:space:]]"
libs=$(find "$native" -maxdepth 1 -name 'libslipcont*.a')
if [ -z "$libs" ]; then
  echo "check-native: no library archive in $native" >&2
  exit 1
fi
fail=0
for lib in $libs; do
  hits=$(objdump -d "$lib" | grep -E -c "$fused" || true)
  if [ "$hits" != 0 ]; then
    echo "check-native: $(basename "$lib") holds $hits fused multiply-add" \
      "instructions; the first:" >&2
    objdump -d "$lib" | awk -v re="$fused" '/^[0-9a-f]+ <.*>:$/ { f = $2 }
      $0 ~ re { print "  " f " " $0; if (++n == 5) exit }' >&2
    fail=1
  fi
done
if [ "$fail" != 0 ]; then
  echo "check-native: the native build fuses operations the portable" \
    "build rounds one by one" >&2
  exit 1
fi
echo "check-native: no fused multiply-add in the native libraries"
work="$native/native-check"
rm -rf "$work"
mkdir -p "$work"
scenes=(
  "chart-alpha-beta --set task.x-steps=60 --set task.y-steps=60"
  "fig58-sweep"
  "fig54-moving"
  "branch-fig58"
  "curve-fig58-fold1"
)
# a summary without its date and its run times ("0.100 s")
untimed() {
  grep -v '^written ' "$1" | sed -E 's/[0-9]+\.[0-9]+ s([ ,;)]|$)/T s\1/g'
}
for s in "${scenes[@]}"; do
  set -- $s
  name=$1
  shift
  for b in portable native; do
    dir=$portable
    [ $b = native ] && dir=$native
    # the same output path for both (the summary names it), moved after
    "$dir/slipcont" run "examples/$name.ini" "$@" --set output.plot=no \
      --out "$work/out" --quiet --threads 2 >/dev/null
    mv "$work/out" "$work/$name-$b"
  done
  n=0
  for f in "$work/$name-portable"/*; do
    base=$(basename "$f")
    g="$work/$name-native/$base"
    case $base in
    summary.txt)
      if ! diff <(untimed "$f") <(untimed "$g") >/dev/null; then
        echo "check-native: $name: summary.txt differs" >&2
        fail=1
      fi
      ;;
    *.csv)
      if ! cmp -s "$f" "$g"; then
        echo "check-native: $name: $base differs between the builds" >&2
        fail=1
      fi
      n=$((n + 1))
      ;;
    esac
  done
  if [ "$n" = 0 ]; then
    echo "check-native: $name wrote no data file" >&2
    fail=1
  fi
  echo "check-native: $name: $n data files compared"
done
if [ "$fail" != 0 ]; then
  echo "check-native: the native build computes other numbers" >&2
  exit 1
fi
echo "check-native: the native and the portable builds agree bit for bit"
