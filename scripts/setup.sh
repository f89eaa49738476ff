#!/usr/bin/env bash
# Installs rbm's build dependencies from Debian 12 packages (idempotent, quiet when
# everything is already there), fetches OpenFOAM v1912's headers for the OpenFOAM plugin
# (scripts/fetchOpenFOAMHeaders.sh: Debian ships OpenFOAM's libraries but no headers), then
# unpacks OpenFOAM 13 when its tarball is found (scripts/unpackOpenFOAM13.sh), then configures
# and builds rbm and the plugins build/lib/librbmMotionSolver.so (OpenFOAM v1912) and
# build/lib/librbmMotionSolverOF13.so (OpenFOAM 13, when unpacked) in ./build.
#   scripts/setup.sh            install + build
#   scripts/setup.sh --deps     install only
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake pkg-config petsc-dev libsuitesparse-dev libvtk9-dev libgtest-dev zlib1g-dev libdeflate-dev openmpi-bin libopenblas0
          openfoam libopenfoam openfoam-examples xz-utils)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
scripts/fetchOpenFOAMHeaders.sh
scripts/unpackOpenFOAM13.sh
[ "${1:-}" = "--deps" ] && exit 0

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)"
