#!/usr/bin/env bash
# The distributed solve gives the serial answer: plate problems on 1 and 2 MPI ranks must agree
# to a relative difference below 1e-8 in every nodal displacement and stress.
set -eu
MF="$1"; ROOT="$2"
WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
for name in plate_tension plate_hole_kirsch; do
  "$MF" run "$ROOT/problems/$name.yaml" --out "$WORK/$name-1" > /dev/null
  mpirun -n 2 "$MF" run "$ROOT/problems/$name.yaml" --out "$WORK/$name-2" > /dev/null
  grep -q '"mpi_ranks": 2' "$WORK/$name-2/summary.json"
  /usr/bin/python3 "$ROOT/scripts/compare_runs.py" "$WORK/$name-1" "$WORK/$name-2" --rtol 1e-8
done
