#!/usr/bin/env bash
# Fig 5.7(b), lower part, with its curves: the chart, then every curve
# scene whose output examples/curve-fig57b.ini draws (`also`), then that
# scene (docs/curves.md, "Fig 5.7(b) with the curves").  Builds first.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target slipcont_cli >/dev/null
build/slipcont run examples/chart-fig57b-window.ini --quiet
for c in flip1 flip2 flip4 flip4b fold1 fold4 period6 switch4; do
  build/slipcont run "examples/curve-fig58-$c.ini" --quiet
done
for c in period3 cross2 graze3; do
  build/slipcont run "examples/curve-fig512-$c.ini" --quiet
done
build/slipcont run examples/curve-fig57b.ini
