#!/usr/bin/env bash
# Installs the Debian packages meshfree needs (only those missing), then configures and builds a
# Release build in build/. Sourced by scripts/run.sh and scripts/test.sh.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

# libopenblas0-pthread replaces the reference BLAS under MUMPS (5x faster factorisations).
PACKAGES=(build-essential cmake pkg-config petsc-dev libhdf5-openmpi-dev libeigen3-dev
          libsuitesparse-dev libopenblas0-pthread catch2 libyaml-cpp-dev openmpi-bin
          libgmsh-dev gmsh calculix-ccx python3 python3-numpy python3-matplotlib python3-h5py python3-meshio
          python3-yaml)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "[setup] installing: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}"
else
  echo "[setup] all Debian packages present"
fi

BUILD="${MESHFREE_BUILD_DIR:-$ROOT/build}"
mkdir -p "$BUILD"
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release > "$BUILD/configure.log" 2>&1 ||
  { cat "$BUILD/configure.log"; exit 1; }
cmake --build "$BUILD" --parallel "$(nproc)"
