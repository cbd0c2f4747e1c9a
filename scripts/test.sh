#!/usr/bin/env bash
# Set-up and the whole test suite: installs what is missing, builds (Release), runs ctest two
# tests at a time (tests that start two MPI ranks alone).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/scripts/setup.sh"
cd "$ROOT/build"
ctest --output-on-failure --timeout 900 -j2 "$@"
