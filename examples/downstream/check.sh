#!/bin/sh
# Builds and runs the downstream programs against an installed slipcont,
# four ways: CMake (find_package) and pkg-config, each shared and static.
#   sh examples/downstream/check.sh PREFIX WORKDIR
# PREFIX is what `cmake --install BUILD --prefix PREFIX` was given.
set -eu
prefix=$(cd "$1" && pwd)
work=$2
here=$(cd "$(dirname "$0")" && pwd)
cc=${CC:-cc}
rm -rf "$work"
mkdir -p "$work"
libdir=$(dirname "$(find "$prefix" -name slipcont.pc | head -n 1)")
libdir=$(dirname "$libdir")

for kind in shared static; do
  st=OFF; [ "$kind" = static ] && st=ON
  cmake -S "$here" -B "$work/cmake-$kind" -DCMAKE_PREFIX_PATH="$prefix" \
    -DSTATIC=$st >/dev/null
  cmake --build "$work/cmake-$kind" >/dev/null
  (cd "$work/cmake-$kind" && ctest --output-on-failure >/dev/null)
  echo "downstream: cmake $kind: ok"
done

export PKG_CONFIG_PATH="$libdir/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
out=$work/pkgconfig
mkdir -p "$out"
# Shared: the usual flags; the run finds the libraries through rpath,
# the folder taken from pkg-config as the README shows.
pclibdir=$(pkg-config --variable=libdir slipcont)
$cc "$here/orbit.c" -o "$out/orbit-shared" $(pkg-config --cflags --libs slipcont) \
  -Wl,-rpath,"$pclibdir" -lm
$cc "$here/scene.c" -o "$out/scene-shared" $(pkg-config --cflags --libs slipcont-io) \
  -Wl,-rpath,"$pclibdir" -lm
# Without rpath (the README's other way): the program runs with
# LD_LIBRARY_PATH naming pkg-config's libdir; without it, it does not
# start unless the prefix is on the loader's own path.
$cc "$here/orbit.c" -o "$out/orbit-norpath" $(pkg-config --cflags --libs slipcont) -lm
LD_LIBRARY_PATH="$pclibdir" "$out/orbit-norpath" >/dev/null
if ! ldconfig -p 2>/dev/null | grep -q "$pclibdir/libslipcont" &&
  env -u LD_LIBRARY_PATH "$out/orbit-norpath" >/dev/null 2>&1; then
  echo "downstream: orbit-norpath ran without its library's folder" >&2
  exit 1
fi
# Static: slipcont's archives, then every private dependency
# (pkg-config --static), the system's own libraries shared.
static_libs() {
  pkg-config --static --libs "$1" |
    sed -e 's/-lslipcont_io\b/-Wl,-Bstatic -lslipcont_io -Wl,-Bdynamic/' \
        -e 's/-lslipcont\( \|$\)/-Wl,-Bstatic -lslipcont -Wl,-Bdynamic /'
}
$cc "$here/orbit.c" -o "$out/orbit-static" $(pkg-config --cflags slipcont) \
  $(static_libs slipcont)
$cc "$here/scene.c" -o "$out/scene-static" $(pkg-config --cflags slipcont-io) \
  $(static_libs slipcont-io)
for p in orbit scene; do
  for kind in shared static; do
    "$out/$p-$kind" >/dev/null
  done
done
# The static programs carry no reference to libslipcont*.so.
for p in orbit scene; do
  if ldd "$out/$p-static" | grep -q 'libslipcont'; then
    echo "downstream: $p-static still needs a shared libslipcont" >&2
    exit 1
  fi
done
echo "downstream: pkg-config shared and static: ok"

# The numerics library needs no inih; both export only what the installed
# headers declare (hidden visibility, SC_API).
if readelf -d "$libdir/libslipcont.so" | grep NEEDED | grep -q inih; then
  echo "downstream: libslipcont.so needs inih" >&2
  exit 1
fi
for lib in libslipcont.so libslipcont_io.so; do
  nm -D --defined-only "$libdir/$lib" | awk '{print $3}' |
    while read -r sym; do
      grep -q "\b$sym\b" "$prefix"/include/slipcont/*.h || {
        echo "downstream: $lib exports $sym, declared in no header" >&2
        exit 1
      }
    done
done
echo "downstream: exports match the headers: ok"
