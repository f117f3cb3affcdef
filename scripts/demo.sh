#!/usr/bin/env bash
# The main job: install, build, and run the symmetric-chaos analysis (the
# chapter's fig 5.6: a period-doubling cascade to chaos as V decreases)
# with its plot, then the asymmetric flip cascade of fig 5.8, brute force
# and continued with its unstable orbits and special points (each located
# by Newton with its certificate), and the fold curve of its period-6
# window in (alpha, beta); then a two-dimensional map, the generalized
# Henon map: its fold, flip and Neimark-Sacker curves with their
# codimension-two points over its period chart (docs/maps.md).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target slipcont_cli >/dev/null
build/slipcont run examples/symmetric-chaos.ini --out out/symmetric-chaos
build/slipcont run examples/fig58-sweep.ini --out out/fig58-sweep
build/slipcont run examples/branch-fig58.ini --out out/branch-fig58
build/slipcont run examples/curve-fig58-period6.ini --out out/curve-fig58-period6
for s in ghenon-atlas-chart curve-ghenon-fold curve-ghenon-ns curve-ghenon-flip ghenon-atlas; do
  build/slipcont run "examples/$s.ini" --out "out/$s"
done
echo "plots: out/symmetric-chaos/*.png out/fig58-sweep/*.png out/branch-fig58/*.png out/curve-fig58-period6/*.png out/ghenon-atlas/curve.png"
