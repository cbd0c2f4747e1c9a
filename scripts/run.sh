#!/usr/bin/env bash
# Set-up and a first run: installs what is missing, builds (Release), and runs the default
# problem, problems/plate_tension.yaml. Any other problem: scripts/run.sh problems/NAME.yaml
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/scripts/setup.sh"
PROBLEM="${1:-$ROOT/problems/plate_tension.yaml}"
shift || true
cd "$ROOT"
"$ROOT/build/meshfree" run "$PROBLEM" "$@"
