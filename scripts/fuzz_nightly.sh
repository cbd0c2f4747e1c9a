#!/usr/bin/env bash
# The fuzzers with the day's seed (the UTC date as YYYYMMDD), for a nightly search beside the
# suite's fixed seed: mutated problem files against `check` and against short runs, mutated
# checkpoints of every kind, and 1,000 flipped bits in the metadata of a PD and of an SPH
# checkpoint each (refused in at most 2 CPU seconds and 100 MB beyond a clean restart's peak).
# A failure prints its seed; replay it with the fuzzer's --seed. Failing cases go to OUT.
#   scripts/fuzz_nightly.sh [OUT]          (about 15 minutes on 2 cores)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
MESHFREE="${MESHFREE:-$ROOT/build/meshfree}"
OUT="${1:-$ROOT/out/fuzz_nightly}"
[ -x "$MESHFREE" ] || { echo "fuzz_nightly.sh: no program at $MESHFREE (run scripts/setup.sh)" >&2; exit 2; }
mkdir -p "$OUT"
CLI="$ROOT/tests/cli"
status=0
run() { echo "== $*"; /usr/bin/python3 "$@" || status=1; }
run "$CLI/fuzz_inputs.py" "$MESHFREE" "$ROOT" --seed today --count 1000 --out "$OUT/inputs"
run "$CLI/fuzz_inputs.py" "$MESHFREE" "$ROOT" --seed today --run --count 1000 --out "$OUT/runs"
run "$CLI/fuzz_checkpoints.py" "$MESHFREE" "$ROOT" --seed today --count 1000 --out "$OUT/checkpoints"
run "$CLI/fuzz_checkpoints.py" "$MESHFREE" "$ROOT" --seed today --count 2000 \
    --mutations flip_metadata --out "$OUT/metadata"
exit $status
