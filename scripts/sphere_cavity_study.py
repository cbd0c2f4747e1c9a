#!/usr/bin/python3
"""The spherical cavity (problems/sphere_cavity_3d.yaml) at three spacings, meshfree RK and tet10:
DOFs, energy and L2 errors against Lame's closed form and their rates (meshfree: against the
spacing; tet10: least-squares slope against h = DOFs^(-1/3), Delaunay meshes of halved size
not being nested), and the wall time of each run. The suite's test
(tests/reference/sphere_cavity_verification.py) runs the two coarser spacings only.

    sphere_cavity_study.py [MESHFREE] [--spacings 0.5 0.25 0.125] [--methods rk tet10]
"""
import argparse
import json
import math
import os
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
METHODS = {"rk": [], "tet10": ["discretisation.method=fem", "discretisation.fem.element=tet10"],
           "tet4": ["discretisation.method=fem", "discretisation.fem.element=tet4"]}


def run(meshfree, out, sets):
    cmd = [meshfree, "run", os.path.join(ROOT, "problems", "sphere_cavity_3d.yaml"), "--out", out]
    for s in sets:
        cmd += ["--set", s]
    began = time.time()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    return s["counts"]["dofs"], s["results"]["error_energy_relative"], \
        s["results"]["error_l2_relative"], time.time() - began


def slope(xs, ys):
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("meshfree", nargs="?", default=os.path.join(ROOT, "build", "meshfree"))
    parser.add_argument("--spacings", type=float, nargs="+", default=[0.5, 0.25, 0.125])
    parser.add_argument("--methods", nargs="+", default=["rk", "tet10"], choices=list(METHODS))
    a = parser.parse_args()
    with tempfile.TemporaryDirectory() as work:
        for method in a.methods:
            rows = []
            for h in a.spacings:
                out = os.path.join(work, f"{method}_{h}")
                rows.append((h,) + run(a.meshfree, out,
                                       [f"discretisation.spacing={h}"] + METHODS[method]))
                h_, dofs, e, l2, t = rows[-1]
                print(f"{method:6s} spacing {h_:<6g} {dofs:>8d} DOFs  energy {e:.3e}  L2 {l2:.3e}  "
                      f"{t:6.1f} s", flush=True)
            size = [r[1] ** (-1.0 / 3.0) for r in rows] if method != "rk" else [r[0] for r in rows]
            print(f"{method:6s} rates: energy {slope(size, [r[2] for r in rows]):.2f}, "
                  f"L2 {slope(size, [r[3] for r in rows]):.2f}")


if __name__ == "__main__":
    main()
