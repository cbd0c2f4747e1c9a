#!/usr/bin/python3
"""Finite elements on gmsh meshes made from the problem's own geometry converge at the elements'
rates: the Kirsch plate (a quarter plate with a hole, problems/plate_hole_kirsch.yaml, exact
solution) meshed at spacing 0.125 and 0.0625 with T3, Q4 and Q8. The rate is taken from the DOF
counts, h ~ N^(-1/2), since the two meshes are not nested. Theory (Strang & Fix 1973, ch. 3):
energy error O(h^p), L2 error O(h^(p+1)) for elements of degree p, provided the curved
boundary is represented to that order (Q8's mid-side nodes lie on the arc).

    fem_meshed_from_geometry.py MESHFREE ROOT
"""
import json
import math
import os
import subprocess
import sys
import tempfile

MESHFREE, ROOT = sys.argv[1], sys.argv[2]
# Smallest rates accepted: the theoretical ones less a margin for the unstructured meshes'
# pre-asymptotic spread (measured: Q8 1.80 / 2.99, Q4 0.95 / 1.87, T3 0.92 / 1.93).
MINIMUM = {"q8": (1.7, 2.8), "q4": (0.85, 1.75), "t3": (0.85, 1.75)}


def errors(element, spacing, work):
    out = os.path.join(work, f"{element}_{spacing}")
    cmd = [MESHFREE, "run", os.path.join(ROOT, "problems", "plate_hole_kirsch.yaml"), "--out", out,
           "--set", "discretisation.method=fem", "--set", f"discretisation.fem.element={element}",
           "--set", f"discretisation.spacing={spacing}"]
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {done.returncode}:\n{done.stdout[-2000:]}")
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    if "gmsh mesh of the geometry" not in s["method"]:
        sys.exit(f"FAIL: {element} was not meshed from the geometry: {s['method']}")
    r = s["results"]
    return s["counts"]["dofs"], r["error_energy_relative"], r["error_l2_relative"]


failed = False
with tempfile.TemporaryDirectory() as work:
    for element, (min_energy, min_l2) in MINIMUM.items():
        n1, e1, l1 = errors(element, 0.125, work)
        n2, e2, l2 = errors(element, 0.0625, work)
        scale = 0.5 * math.log(n2 / n1)
        rate_e, rate_l2 = math.log(e1 / e2) / scale, math.log(l1 / l2) / scale
        ok = rate_e >= min_energy and rate_l2 >= min_l2
        failed |= not ok
        print(f"{'ok' if ok else 'FAIL'}: {element}: DOFs {n1} -> {n2}, energy error {e1:.3e} -> "
              f"{e2:.3e} (rate {rate_e:.2f}, at least {min_energy}), L2 error {l1:.3e} -> {l2:.3e} "
              f"(rate {rate_l2:.2f}, at least {min_l2})")
sys.exit(1 if failed else 0)
