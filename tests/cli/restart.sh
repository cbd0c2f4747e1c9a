#!/usr/bin/env bash
# Checkpoint and restart: runs killed with SIGKILL after their second checkpoint and restarted with --restart give every CSV and XDMF file byte for byte, every dataset of every
# HDF5 file and every number of summary.json (times, rates and memory aside) equal to the run that was
# never stopped; a restart that changed the problem, or that has no checkpoint, is refused.
set -u
MF="$1"; ROOT="$2"
WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
fails=0
check() { # check "what" condition...
  local what="$1"; shift
  if "$@"; then echo "ok: $what"; else echo "FAIL: $what"; fails=$((fails+1)); fi
}
same_results() { # same_results A B: every output equal, bit for bit
  /usr/bin/python3 - "$1" "$2" <<'EOF'
import glob, json, os, sys
import h5py, numpy as np
a_dir, b_dir = sys.argv[1:3]
names = sorted(os.path.basename(f) for f in glob.glob(a_dir + "/*"))
assert names == sorted(os.path.basename(f) for f in glob.glob(b_dir + "/*")), "other files"
def timing(key):  # a time, a rate or the memory of this machine, not a result
    return (key.endswith(("_per_second", "seconds")) or
            key in ("share_of_run", "time_s", "kernel_time_s", "checkpoints", "memory"))
def same(x, y, where):
    if isinstance(x, dict):
        for k in x:
            if not timing(k):
                same(x[k], y.get(k), where + "." + k)
    else:
        assert x == y, "%s: %s then, %s now" % (where, x, y)
datasets = 0
for name in names:
    a, b = a_dir + "/" + name, b_dir + "/" + name
    if name.endswith((".csv", ".xmf")):
        assert open(a, "rb").read() == open(b, "rb").read(), name + " differs"
    elif name.endswith(".json"):
        same(json.load(open(a)), json.load(open(b)), name)
    elif name.endswith(".h5"):
        fa, fb = h5py.File(a, "r"), h5py.File(b, "r")
        sets = []
        fa.visit(lambda n: sets.append(n) if isinstance(fa[n], h5py.Dataset) else None)
        other = []
        fb.visit(lambda n: other.append(n) if isinstance(fb[n], h5py.Dataset) else None)
        assert sorted(sets) == sorted(other), name + " holds other datasets"
        differ = [n for n in sets if not np.array_equal(fa[n][()], fb[n][()])]
        assert not differ, "%s: datasets differ: %s" % (name, differ[:5])
        datasets += len(sets)
print("  %d files, %d datasets equal" % (len(names), datasets))
EOF
}
# frames_whole DIR: every .xmf of DIR has one grid per time, none empty, each matching fields.h5.
frames_whole() { /usr/bin/python3 "$ROOT/tests/cli/xdmf_frames.py" --check "$1" >/dev/null; }
source "$(dirname "${BASH_SOURCE[0]}")/checkpoint_support.sh"
# restart_case NAME PROBLEM INTERVAL [meshfree arguments...] [:: launcher...]
restart_case() {
  local name="$1" problem="$ROOT/problems/$2.yaml" interval="$3"
  [ -f "$problem" ] || problem="$ROOT/tests/data/$2.yaml"
  shift 3
  local sets=() launch=()
  while [ $# -gt 0 ] && [ "$1" != "::" ]; do sets+=("$1"); shift; done
  [ $# -gt 0 ] && shift && launch=("$@")
  # The interval goes to output.checkpoint_interval unless the case sets its own key (a stage's,
  # or an implicit run's checkpoint_every).
  [[ "${sets[*]-}" == *checkpoint_* ]] || sets+=(--set "output.checkpoint_interval=$interval")
  local whole="$WORK/$name-whole" cut="$WORK/$name-cut"
  "${launch[@]}" "$MF" run "$problem" --out "$whole" "${sets[@]}" >/dev/null 2>&1 ||
    { echo "FAIL: $name: the uninterrupted run"; fails=$((fails+1)); return; }
  check "$name: the uninterrupted run wrote checkpoints and removed them at the end" \
    grep -q '"written": [1-9]' "$whole/summary.json"
  check "$name: no checkpoint is left after a completed run" [ ! -e "$whole/checkpoint" ]
  kill_after_checkpoint "$cut" "${launch[@]}" "$MF" run "$problem" --out "$cut" "${sets[@]}"
  check "$name: the run was killed before it completed" [ ! -e "$cut/summary.json" ]
  local kept; kept="$(generation "$cut")"
  check "$name: the killed run left its checkpoint" [ "$kept" -ge 2 ]
  "${launch[@]}" "$MF" run "$problem" --restart "$cut" "${sets[@]}" >"$WORK/restart.log" 2>&1
  check "$name: the restart completes" grep -q '"status": "completed"' "$cut/summary.json"
  check "$name: the restart says where it started" grep -q "restarted " "$WORK/restart.log"
  check "$name: the restart loses at most one checkpoint interval" /usr/bin/python3 -c "
import json, sys
s = json.load(open('$cut/summary.json'))['checkpoints']
sys.exit(not s['restarted_at_time'] >= $kept * $interval * (1 - 1e-9))"
  check "$name: the restarted run equals the uninterrupted one, bit for bit" \
    same_results "$whole" "$cut"
  check "$name: the restarted run's frames have distinct times and whole grids" frames_whole "$cut"
}

# Peridynamics with a free penalty impactor (contact forces, fracture), one rank, two threads.
OMP_NUM_THREADS=2 restart_case pd_disk pd_disk_impact 1.0e-5
# The same with a state-based target, elastic-plastic (EPS: the bonds' plastic deviatoric
# extensions carried), through its first broken bonds.
OMP_NUM_THREADS=2 restart_case pd_disk_eps pd_disk_impact_lps 1.0e-5 --set time.end=2.5e-5 \
  --set materials.0.bond.law=eps --set materials.0.bond.yield_stress=3e8
# SPH of a solid (strength, plastic strain, neighbour lists), one rank, two threads.
OMP_NUM_THREADS=2 restart_case sph_taylor sph_taylor_bar 5.0e-6 --set time.end=2.5e-5
# A staged run: the implicit preload runs again on restart, its explicit stage (peridynamics with
# an impactor) goes on from the checkpoint.
OMP_NUM_THREADS=2 restart_case staged_pmma staged_pmma_impact 2.5e-5 \
  --set stages.1.output.checkpoint_interval=2.5e-5
# An implicit elastoplastic run (cyclic load steps, J2 with hardening) with a checkpoint after
# every converged increment: the Gauss points' histories, the nodal parameters, the schedule.
restart_case implicit_cyclic bar_uniaxial_cyclic 1 --set output.checkpoint_every=1
# Drucker-Prager (non-associated, with a tension cut-off): its Gauss points' histories carried
# through a checkpoint as J2's are.
restart_case implicit_drucker_prager strip_footing_prandtl 1 --set output.checkpoint_every=1 \
  --set 'discretisation.refinement=[{box: [[0, -2], [4, 0]], spacing: 0.125}]' \
  --set steps.0.increments=8 --set steps.0.load_factor=0.008 \
  --set materials.0.plasticity.dilation_angle=10 --set materials.0.plasticity.tension_cutoff=1.0e4
# An adapted cloud: the restart refines it again by the same pilots (the estimates do not depend
# on the run's history) and goes on from the checkpoint of the analysis on the last cloud.
restart_case implicit_adapted cook_membrane 1 --set output.checkpoint_every=1 \
  --set discretisation.spacing=4 --set discretisation.adapt.target=0.01 \
  --set discretisation.adapt.passes=3 --set discretisation.adapt.pilot_increments=2 \
  --set steps.0.increments=8
# Peridynamics spread over two MPI ranks (blast loads, broken bonds across the ranks' border),
# SPH over two ranks, and the implicit run over two ranks (its PETSc solves distributed).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# MUMPS's factorisation over several ranks does not repeat itself bit for bit from run to run
# (two uninterrupted runs differ), so the implicit case solves with GMRES and block Jacobi,
# which does.
OMP_NUM_THREADS=1 restart_case pd_slab_2ranks pd_slab_blast 3.0e-4 :: mpirun -n 2
# SPH over two ranks: a shear layer whose particles migrate between the ranks at every list
# build; the restart rebuilds each rank's halo and lists of loads from the state it kept.
OMP_NUM_THREADS=1 restart_case sph_2ranks sph_shear_layer 0.05 --set time.end=1.0 :: mpirun -n 2
check "sph_2ranks: particles migrated between the ranks" /usr/bin/python3 -c "
import json, sys
sys.exit(not json.load(open('$WORK/sph_2ranks-cut/summary.json'))['counts']['migrated_particles'] > 100)"
OMP_NUM_THREADS=1 restart_case implicit_2ranks bar_uniaxial_cyclic 1 \
  --set output.checkpoint_every=1 -- -ksp_type gmres -pc_type bjacobi -ksp_rtol 1e-12 \
  :: mpirun -n 2

# What a restart refuses, with one line naming the key, exit 2, and the checkpoint untouched.
D="$ROOT/problems/pd_disk_impact.yaml"
CUT="$WORK/refusals"
kill_after_checkpoint "$CUT" "$MF" run "$D" --out "$CUT" --set output.checkpoint_interval=1.0e-5
before="$(md5sum "$CUT"/checkpoint/* | sort)"
msg="$("$MF" run "$D" --restart "$CUT" --set output.checkpoint_interval=1.0e-5 \
  --set time.dt=2.0e-7 2>&1)"; rc=$?
check "a changed time step is refused (exit 2)" [ $rc -eq 2 ]
check "... naming the key" grep -qF "time.dt changed since the checkpoint" <<<"$msg"
check "... in one line" [ "$(wc -l <<<"$msg")" -eq 1 ]
msg="$("$MF" run "$D" --restart "$WORK/nowhere" 2>&1)"; rc=$?
check "a folder without a checkpoint is refused (exit 2)" [ $rc -eq 2 ]
check "... saying so" grep -qF "no checkpoint in" <<<"$msg"
msg="$("$MF" run "$ROOT/problems/plate_tension.yaml" --restart "$CUT" 2>&1)"; rc=$?
check "an implicit problem is refused (exit 2)" [ $rc -eq 2 ]
msg="$("$MF" run "$D" --restart "$CUT" --out "$WORK/elsewhere" 2>&1)"; rc=$?
check "--out elsewhere is refused (exit 2)" [ $rc -eq 2 ]
check "the refusals left the checkpoint as it was" [ "$(md5sum "$CUT"/checkpoint/* | sort)" = "$before" ]
# The end time and the output intervals may change: the run goes on to the new end.
"$MF" run "$D" --restart "$CUT" --set output.checkpoint_interval=2.0e-5 --set time.end=1.2e-4 \
  --set output.history_interval=5.0e-6 >/dev/null 2>&1; rc=$?
check "a restart with a later end time and other intervals completes" [ $rc -eq 0 ]
check "... to the new end" /usr/bin/python3 -c "
import csv, sys
rows = list(csv.reader(open('$CUT/history.csv')))
sys.exit(not abs(float(rows[-1][0]) - 1.2e-4) < 1e-12)"
check "... with distinct times and whole grids" frames_whole "$CUT"

# Two runs into one folder at once, and hostile checkpoints: tests/cli/checkpoint_refusals.sh.

echo "$fails failure(s)"
[ $fails -eq 0 ]
