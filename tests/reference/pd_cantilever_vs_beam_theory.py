#!/usr/bin/python3
"""Paper 000's linear verification: the peridynamic 3D cantilever (problems/pd_cantilever_3d.yaml)
against the Timoshenko beam's modal solution (reference/beam_theory, deflection at x = 47.5 m,
the model's last particle column). The tip deflection history over 1 s (0.5 s forced near
resonance, then free) must stay within 5% of the largest beam deflection at every millisecond.

    tests/reference/pd_cantilever_vs_beam_theory.py MESHFREE ROOT"""
import csv
import subprocess
import sys
import tempfile

import numpy as np

meshfree, root = sys.argv[1], sys.argv[2]
with tempfile.TemporaryDirectory() as out:
    subprocess.run([meshfree, "run", f"{root}/problems/pd_cantilever_3d.yaml", "--out", out],
                   check=True, stdout=subprocess.DEVNULL)
    h = list(csv.DictReader(open(f"{out}/history.csv")))
t = np.array([float(r["time"]) for r in h])
w = np.array([float(r["tip_uz"]) for r in h])
ref = list(csv.DictReader(open(f"{root}/reference/beam_theory/cantilever_stations.csv")))
tr = np.array([float(r["t"]) for r in ref])
timoshenko = np.array([float(r["w_timoshenko_x47.5"]) for r in ref])
euler = np.array([float(r["w_eb_x47.5"]) for r in ref])
ours = np.interp(tr, t, w)
scale = np.abs(timoshenko).max()
d_t = np.abs(ours - timoshenko).max() / scale
d_e = np.abs(ours - euler).max() / np.abs(euler).max()
print(f"largest |w| peridynamics {np.abs(ours).max():.6e} m, Timoshenko {scale:.6e} m, "
      f"Euler-Bernoulli {np.abs(euler).max():.6e} m")
print(f"largest difference over the history: {d_t:.3e} of the Timoshenko maximum "
      f"({d_e:.3e} against Euler-Bernoulli, which misses the shear deformation of this deep beam)")
sys.exit(0 if d_t < 0.05 else 1)
