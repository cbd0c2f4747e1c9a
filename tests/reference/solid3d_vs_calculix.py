#!/usr/bin/python3
"""The thick perforated plate (problems/thick_perforated_plate.yaml, one eighth of a 5 mm plate,
J2 with linear hardening) against the mesh-converged CalculiX C3D20R curve of the same eighth
(reference/calculix_3d/thick_perforated_plate/curve.csv, made by
scripts/fe_reference/make_calculix_3d_reference.py): the pull force within 1% of CalculiX's at
every increment. The problem's increments are 0.005 mm of pull; `--increments N` runs the first N
of them (the suite runs 8, into the net section's yield; the whole curve is 20, about 130 s on
two threads).

    solid3d_vs_calculix.py MESHFREE ROOT [--increments N]
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

parser = argparse.ArgumentParser()
parser.add_argument("meshfree")
parser.add_argument("root")
parser.add_argument("--increments", type=int, default=20)
args = parser.parse_args()
with open(os.path.join(args.root, "reference", "calculix_3d", "thick_perforated_plate",
                       "curve.csv")) as f:
    reference = list(csv.DictReader(f))
n = args.increments
if not 1 <= n < len(reference):
    sys.exit(f"--increments: 1 to {len(reference) - 1}, got {n}")
with tempfile.TemporaryDirectory() as work:
    out = os.path.join(work, "plate")
    pull = float(reference[n]["v"])
    cmd = [args.meshfree, "run", os.path.join(args.root, "problems", "thick_perforated_plate.yaml"),
           "--out", out, "--set", f"steps.0.load_factor={pull!r}", "--set", f"steps.0.increments={n}"]
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {done.returncode}:\n{done.stdout[-2000:]}")
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
worst = 0.0
print(" pull (mm)   CalculiX (kgf)   meshfree (kgf)   difference")
for ref, row in zip(reference[1:n + 1], rows[1:]):
    v, expected, force = float(ref["v"]), float(ref["force_y"]), float(row["reaction_pull_y"])
    if abs(float(row["factor_pull"]) - v) > 1e-12:
        sys.exit(f"FAIL: increment at pull {row['factor_pull']} where CalculiX has {v}")
    worst = max(worst, abs(force / expected - 1.0))
    print(f"  {v:.3f}      {expected:10.4f}      {force:10.4f}      {force / expected - 1.0:+.3%}")
ok = len(rows) == n + 1 and worst <= 0.01
print(f"{'ok' if ok else 'FAIL'}: {len(rows) - 1} increments, largest difference {worst:.3%} "
      f"(at most 1%)")
sys.exit(0 if ok else 1)
