#!/usr/bin/env bash
# Install what slipcont needs to build, test and plot (Debian/Ubuntu).
# Skips apt when everything is already there, so reruns are quick.
set -euo pipefail
pkgs=(build-essential binutils cmake pkg-config libgsl-dev liblapack-dev
      libblas-dev libsuitesparse-dev libslicot-dev libinih-dev gnuplot-nox libopenmpi-dev
      openmpi-bin)
missing=()
for p in "${pkgs[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -q
  $sudo apt-get install -y -q "${missing[@]}"
fi
# Optional: clang with libFuzzer (the fuzz stage of scripts/test.sh) and
# doxygen (the API reference).  Their absence skips those stages only.
optional=(clang libclang-rt-dev doxygen)
omissing=()
for p in "${optional[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || omissing+=("$p")
done
if ((${#omissing[@]})); then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  { $sudo apt-get update -q && $sudo apt-get install -y -q "${omissing[@]}"; } ||
    echo "deps.sh: could not install ${omissing[*]}: their stages are skipped"
fi
