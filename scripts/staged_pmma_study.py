#!/usr/bin/python3
"""The pre-stretched cracked PMMA plate of problems/staged_pmma_impact.yaml struck by its
projectile, against the same plate unloaded (the preload's traction factor 0): crack initiation
time and path at each crack tip.

    scripts/staged_pmma_study.py [--out DIR] [--meshfree build/meshfree] [--threads N]

Runs both cases (each one command: `meshfree run problems/staged_pmma_impact.yaml`, the second
with --set stages.0.steps.0.load_factor=0), reads each one's fields.h5, and writes
study.csv (one row per case and crack tip) and study.md into DIR.

Crack growth at a tip: the particles with damage >= 0.38 (the damage of a crack face cut by
the pre-crack is about 0.41 on its two rows, so only particles beyond the tip, |x| > a, count)
within 15 mm of the tip and farther than 12 mm from the impact point (the crushed zone under
the nose is not a crack); the grown crack's tip is the farthest of them from the initial tip.
Growth has started when damage within 3 mm of the tip lies 1 mm (two spacings) or more from it
(scripts/pd_pmma_study.py's criterion; the 3 mm keep out the crack that runs from the crushed
zone toward the right tip); the initiation time is the first field instant it does (fields every 5 microseconds;
the history's energies and broken-bond count come every microsecond). The path is the
polyline of the farthest damaged particle per 1 mm band of distance from the tip; its angle is
measured from the crack's own direction (+x at the right tip, -x at the left), positive toward
+y.
"""

import argparse
import csv
import math
import os
import re
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
PROBLEM = os.path.join(ROOT, "problems", "staged_pmma_impact.yaml")
A = 0.010                   # half crack length
IMPACT = (0.050, -0.005)    # where the nose meets the plate
THRESHOLD = 0.38
START = 0.001               # growth has started when the tip has moved this far
REACH = 0.015               # damage this close to a tip belongs to its crack
CRUSH = 0.012               # damage this close to the impact point is the crushed zone
INITIATION_REACH = 0.003    # initiation is growth within this distance of the tip


def run(meshfree, out, extra, threads):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    cmd = [meshfree, "run", PROBLEM, "--out", out] + extra
    t0 = time.time()
    with open(out + ".log", "w") as log:
        subprocess.run(cmd, check=True, stdout=log, stderr=subprocess.STDOUT, env=env)
    return time.time() - t0


def growth(fields, tip_x):
    """Per field step: time, distance of the farthest damaged particle from the tip, its
    position."""
    f = h5py.File(fields, "r")
    X = f["geometry/coordinates"][:, :2]
    with open(fields[:-2] + "xmf") as fh:
        times = [float(v) for v in re.findall(r'<Time Value="([^"]+)"', fh.read())]
    r = np.hypot(X[:, 0] - tip_x, X[:, 1])
    beyond = np.sign(tip_x) * X[:, 0] > A
    away = np.hypot(X[:, 0] - IMPACT[0], X[:, 1] - IMPACT[1]) > CRUSH
    candidates = beyond & away & (r < REACH)
    out = []
    steps = sorted(k for k in f if k.startswith("step_"))
    for k, s in enumerate(steps):
        d = f[s + "/damage"][:]
        m = candidates & (d >= THRESHOLD)
        t = times[k]
        if m.any():
            j = np.argmax(np.where(m, r, -1.0))
            near = m & (r < INITIATION_REACH)
            first = float(r[near].max()) if near.any() else 0.0
            out.append((float(t), float(r[j]), X[j].tolist(), m, first))
        else:
            out.append((float(t), 0.0, None, m, 0.0))
    return X, r, out


def path_of(X, r, m, tip_x):
    """The farthest damaged particle per 1 mm band of distance from the tip."""
    points = []
    for b in np.arange(0.0, REACH, 0.001):
        sel = m & (r >= b) & (r < b + 0.001)
        if sel.any():
            j = np.flatnonzero(sel)[np.argmax(r[sel])]
            points.append((float(X[j, 0]), float(X[j, 1])))
    return points


def angle(p, tip_x):
    dx, dy = p[0] - tip_x, p[1]
    return math.degrees(math.atan2(dy, dx * np.sign(tip_x)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "staged_pmma_study"))
    ap.add_argument("--meshfree", default=os.path.join(ROOT, "build", "meshfree"))
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--reuse", action="store_true", help="analyse the runs already in --out")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    cases = [("preloaded", []), ("unloaded", ["--set", "stages.0.steps.0.load_factor=0"])]
    rows = []
    for name, extra in cases:
        out = os.path.join(args.out, name)
        seconds = 0.0 if args.reuse else run(args.meshfree, out, extra, args.threads)
        for tip_x in (A, -A):
            X, r, g = growth(os.path.join(out, "fields.h5"), tip_x)
            start = next((t for t, _, _, _, first in g if first >= START), None)
            t_end, dist, tip, m, _ = g[-1]
            path = path_of(X, r, m, tip_x)
            rows.append({
                "case": name, "tip_x": tip_x, "seconds": round(seconds, 1),
                "initiation_us": None if start is None else round(1e6 * start, 1),
                "growth_mm": round(1e3 * dist, 2),
                "final_tip": None if tip is None else [round(1e3 * c, 2) for c in tip],
                "angle_deg": None if tip is None else round(angle(tip, tip_x), 1),
                "path_mm": [(round(1e3 * x, 2), round(1e3 * y, 2)) for x, y in path],
            })
            print(rows[-1], flush=True)
    with open(os.path.join(args.out, "study.csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(args.out, "study.md"), "w") as fh:
        fh.write("| case | tip | initiation (us) | growth (mm) | final tip (mm) | angle (deg) |\n")
        fh.write("|---|---|---|---|---|---|\n")
        for r_ in rows:
            fh.write(f"| {r_['case']} | {'right' if r_['tip_x'] > 0 else 'left'} | "
                     f"{r_['initiation_us']} | {r_['growth_mm']} | {r_['final_tip']} | "
                     f"{r_['angle_deg']} |\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
