#!/usr/bin/env python3
"""Energy balance of a peridynamic fracture run with free and fixed penalty impactors.

problems/pd_pmma_beam_impact.yaml (the 5 kg striker at 2.3 m/s on the cracked PMMA beam, on two
fixed rollers) with penalty contact (LAMMPS fix indent's law, stiffness derived) on all three
impactors, at spacing 1 mm, to 2 ms: the striker slows, the rollers carry load and the crack
grows. The balance (kinetic + strain + contact energy of the target, the striker's kinetic
energy, the energy broken bonds took with them, against the work done on the system) must stay
within 1e-3 of the largest energy over the whole run, every history row; the run must have
broken bonds, a loaded roller and a striker that lost energy, so that each term is exercised.
Usage: pd_impact_energy_balance.py MESHFREE SOURCE_DIR [OUT_DIR]
"""
import csv
import os
import subprocess
import sys
import tempfile
from pathlib import Path


def main():
    meshfree, source = sys.argv[1], Path(sys.argv[2])
    out = Path(sys.argv[3]) if len(sys.argv) > 3 else Path(tempfile.mkdtemp()) / "pd_impact_energy"
    env = dict(os.environ, OMP_NUM_THREADS="1")
    settings = ["discretisation.spacing=0.001", "time.end=2e-3"]
    settings += ["impactors.%d.contact.type=penalty" % k for k in range(3)]
    command = [meshfree, "run", str(source / "problems/pd_pmma_beam_impact.yaml"), "--out", str(out)]
    for s in settings:
        command += ["--set", s]
    subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL)
    rows = list(csv.DictReader(open(out / "history.csv")))
    col = lambda name: [float(r[name]) for r in rows]
    energy = [a + b + c + d for a, b, c, d in zip(col("kinetic_energy"), col("strain_energy"),
                                                  col("contact_energy"), col("impactor_kinetic_energy"))]
    scale = max(max(energy), max(abs(w) for w in col("external_work")))
    balance = max(abs(b) for b in col("energy_balance")) / scale
    broken = int(float(rows[-1]["broken_bonds"]))
    roller = max(abs(f) for f in col("support_left_force_y") + col("support_right_force_y"))
    striker_loss = col("impactor_kinetic_energy")[0] - col("impactor_kinetic_energy")[-1]
    print("energy balance %.2e of the largest energy (%.4g J) over %d rows; %d broken bonds, "
          "largest roller force %.4g N, striker lost %.4g J" %
          (balance, scale, len(rows), broken, roller, striker_loss))
    ok = balance <= 1e-3 and broken > 0 and roller > 0.0 and striker_loss > 0.0
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
