#!/usr/bin/env bash
# Explicit runs spread over MPI ranks give the one-rank answer. Each particle sums its bonds in
# increasing global id whichever rank holds it, so the particle fields of 2 ranks equal those of
# one rank bit for bit; only sums over the ranks (energies) are added in another order: 1e-12
# relative. The runs are shortened; the slab's window includes bond breaking (thousands of
# bonds), the beam's the kinematic contact of its striker, the disk's the penalty contact of
# LAMMPS's indenter and its first damage (short-range contact runs on one rank).
set -eu
MF="$1"; ROOT="$2"
WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
check() { # name, end time, more --set options
  local name="$1" end="$2"
  shift 2
  "$MF" run "$ROOT/problems/$name.yaml" --out "$WORK/$name-1" --set time.end=$end "$@" > /dev/null
  mpirun -n 2 "$MF" run "$ROOT/problems/$name.yaml" --out "$WORK/$name-2" --set time.end=$end \
    "$@" > /dev/null
  grep -q '"mpi_ranks": 2' "$WORK/$name-2/summary.json"
  test "$(ls "$WORK/$name-2" | grep -c '\.h5$')" = 1 # one field file, written by both ranks
  /usr/bin/python3 "$ROOT/scripts/compare_runs.py" "$WORK/$name-1" "$WORK/$name-2" --rtol 1e-12
}
check pd_slab_blast 1.0e-3
/usr/bin/python3 - "$WORK/pd_slab_blast-2/history.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert float(rows[-1]["broken_bonds"]) > 1000, "the window must include bond breaking"
PY
check pd_pmma_beam_impact 1.0e-4
check pd_disk_impact 2.0e-5 --set discretisation.short_range_contact=false
