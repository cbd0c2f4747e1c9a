#!/usr/bin/env python3
"""problems/pd_disk_impact.yaml against LAMMPS's run of the same example
(reference/lammps/disk_impact, made by scripts/pd_reference/make_lammps_disk_impact.py), or with
--model lps the state-based problems/pd_disk_impact_lps.yaml against LAMMPS's peri/lps example
(reference/lammps/disk_impact_lps, made by scripts/pd_reference/make_lammps_disk_impact_lps.py).

Every 10 steps over the whole run (1000 steps): the number of damaged particles (damage > 0, from
fields.h5) within 5% of LAMMPS's, and the force on the indenter within 5% of LAMMPS's peak force
(the force passes through zero); the peak force within 5% of LAMMPS's. The energy balance of the
run (energy_balance column: kinetic + strain + contact energy - drive work + fracture energy)
within 1e-3 of the largest energy up to step 150; after it the indenter's centre passes the top
particles, where the penalty potential K (R - r)^3 / 3 has a cusp (its force, K R^2 at r = 0,
reverses direction) that a step crosses at once (the indenter force drops from 93 N to 36 N in
one step, in LAMMPS too), which the balance reports; the whole run's value is printed.
Usage: pd_disk_impact_vs_lammps.py MESHFREE SOURCE_DIR [OUT_DIR] [--model pmb|lps]
"""
import csv
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import h5py
import numpy as np


# The problem file and the LAMMPS reference of each model.
CASES = {"pmb": ("problems/pd_disk_impact.yaml", "reference/lammps/disk_impact"),
         "lps": ("problems/pd_disk_impact_lps.yaml", "reference/lammps/disk_impact_lps")}


def run(meshfree, source, out, steps=None, model="pmb"):
    """Runs the model's problem with a history row every step (the first `steps` steps only,
    when given) into `out`."""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    extra = ["--set", "time.end=%g" % (steps * 1e-7)] if steps else []
    subprocess.run([meshfree, "run", str(Path(source) / CASES[model][0]), "--out", str(out),
                    "--set", "output.history_interval=1e-7"] + extra, check=True, env=env,
                   stdout=subprocess.DEVNULL)


def compare(source, out, verbose=True, model="pmb"):
    """The run in `out` against LAMMPS over the steps both have: a dict of the measures the test
    asserts and the curves (steps, forces, damaged-particle counts) for plots."""
    source, out = Path(source), Path(out)
    ref = {int(r["step"]): r for r in csv.DictReader(open(source / CASES[model][1] / "history.csv"))}
    rows = {int(float(r["step"])): r for r in csv.DictReader(open(out / "history.csv"))}
    steps = [s for s in sorted(ref) if s in rows]
    lammps_force = np.array([float(ref[s]["indenter_force_y"]) for s in steps])
    ours_force = np.array([float(rows[s]["indenter_force_z"]) for s in steps])
    peak = np.abs(lammps_force).max()
    force_error = np.abs(ours_force - lammps_force).max() / peak
    peak_error = abs(np.abs(ours_force).max() - peak) / peak
    worst_damage = 0.0
    damage = []  # (step, ours, LAMMPS)
    with h5py.File(out / "fields.h5", "r") as f:
        for key in sorted(k for k in f.keys() if k.startswith("step_")):
            step = int(key.split("_")[1]) * 10  # fields every 1e-6 s = 10 steps
            if step not in ref:  # a frame between the reference's rows
                continue
            n_ours = int((np.array(f[key]["damage"]) > 0).sum())
            n_lammps = int(ref[step]["damaged_particles"])
            damage.append((step, n_ours, n_lammps))
            err = abs(n_ours - n_lammps) / max(n_lammps, 1)
            worst_damage = max(worst_damage, err)
            if verbose and step % 100 == 0:
                print("step %4d: damaged particles %4d (LAMMPS %4d), indenter force %8.4f N "
                      "(LAMMPS %8.4f N)" % (step, n_ours, n_lammps, float(rows[step]["indenter_force_z"]),
                                             float(ref[step]["indenter_force_y"])))
    energy = [float(r["kinetic_energy"]) + float(r["strain_energy"]) + float(r["contact_energy"])
              for s, r in sorted(rows.items()) if s <= 150]
    balance = max(abs(float(r["energy_balance"])) for s, r in rows.items() if s <= 150)
    drive = max(abs(float(r["impactor_work"])) for s, r in rows.items() if s <= 150)
    summary = json.load(open(out / "summary.json"))
    return dict(complete=len(steps) == len(ref), steps=steps, ours_force=ours_force,
                lammps_force=lammps_force, damage=damage,
                peak=peak, ours_peak=np.abs(ours_force).max(), force_error=force_error,
                peak_error=peak_error, worst_damage=worst_damage,
                early_balance=balance / max(max(energy), drive),
                whole_balance=summary["results"]["energy_balance_relative"])


# What the suite asserts: forces and damaged-particle counts within 5% of LAMMPS's, the energy
# balance within 1e-3 before the indenter's centre reaches the target.
TOLERANCES = {"force_error": 0.05, "peak_error": 0.05, "worst_damage": 0.05, "early_balance": 1e-3}


def passes(c, whole_run=True):
    """Whether a comparison made by compare() is within the tolerances, and (with `whole_run`)
    over every step of the reference."""
    return (c["complete"] or not whole_run) and all(c[k] <= v for k, v in TOLERANCES.items())


def main():
    args = sys.argv[1:]
    model = "pmb"
    if "--model" in args:
        k = args.index("--model")
        model = args[k + 1]
        del args[k:k + 2]
    meshfree, source = args[0], Path(args[1])
    out = Path(args[2]) if len(args) > 2 else Path(tempfile.mkdtemp()) / "disk_impact"
    run(meshfree, source, out, model=model)
    c = compare(source, out, model=model)
    print("peak indenter force %.4f N (LAMMPS %.4f N), largest force difference %.2e of the peak, "
          "damaged-particle count within %.2e, energy balance %.2e up to step 150 (%.2e over the "
          "whole run)" % (c["ours_peak"], c["peak"], c["force_error"], c["worst_damage"],
                          c["early_balance"], c["whole_balance"]))
    sys.exit(0 if passes(c) else 1)


if __name__ == "__main__":
    main()
