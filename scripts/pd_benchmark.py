#!/usr/bin/python3
"""Cost of the peridynamic bond loop against problem size and threads, meshfree and LAMMPS
peri/pmb side by side on the same n^3 simple-cubic lattices (spacing a = 0.5 mm, horizon
3.0002 a, c = 1.6863e22, s00 = 0.0005, alpha = 0.25, rho = 2200, linear partial volumes - the
LAMMPS rule -, dt = 1e-8 s, free body), the runs interleaved: for each lattice and repeat,
meshfree with k threads then LAMMPS with k MPI ranks (Debian's LAMMPS has no OpenMP package),
so that a machine shared with other jobs slows both alike. The fastest repeat is kept.

Bond evaluations are counted as directed bonds x steps / seconds: LAMMPS's 'total # of bonds'
counts each bond at both ends, and so does meshfree's count (summary.json
results.bond_evaluations_per_second). meshfree's default (half) bond layout evaluates each pair
once and applies the force to both ends (Newton's third law), so one pair evaluation counts as
two bond evaluations, as LAMMPS's full neighbour list evaluates it twice. meshfree's rate is
over the whole step (velocity Verlet, forces, breaking); LAMMPS's is given over its loop time
(the whole step) and over its pair time (bond forces and short-range contact). Bytes per bond:
meshfree's results.bond_bytes_per_bond (steady and at the peak while building), LAMMPS's 'Per MPI
rank memory allocation' over its bonds.

    scripts/pd_benchmark.py [--sizes 22 43 65 100] [--threads 1 2] [--repeats 2] [--out DIR]
                            [--baseline OTHER/meshfree]

--baseline runs a second build of meshfree (an older one, say) right after each meshfree run,
in the same interleaving, and reports its rate beside: old and new measured in one session.

Writes benchmark.csv in --out and prints the table with the ratios, the growth exponent of the
step time with the bond count (1 for a loop linear in the bonds) and the two-thread speed-ups.
"""
import argparse
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts" / "pd_reference"))
import make_lammps_reference as lref  # noqa: E402  (the LAMMPS deck and lattice of the reference)

SPACING = 0.0005
DT = 1e-8
# Directed bond evaluations per run: steps = EVALUATIONS / (particles x 120), at least 5.
EVALUATIONS = 2.4e8
# E with c = 12 E / (pi delta^4) (Silling & Askari 2005), for the report only: c is given.
YOUNG = 1.6863e22 * np.pi * (3.0002 * SPACING) ** 4 / 12

PROBLEM = """name: pd_benchmark_{n}
description: free {n}^3 PMB lattice, the LAMMPS benchmark lattice, {steps} steps
units: N, m, kg, s
analysis: peridynamics
model: {{type: solid_3d}}
materials:
  - {{name: glass, E: {E:.6e}, density: 2200, bond: {{micromodulus: 1.6863e22, critical_stretch: 0.0005, alpha: 0.25}}}}
geometry:
  box: {{origin: [0, 0, 0], size: [{L}, {L}, {L}]}}
discretisation: {{spacing: {a}, horizon: 3.0002, volume_correction: linear}}
regions:
  - {{box: [[0, 0, 0], [{half}, {L}, {L}]], velocity: [0.01, 0, 0]}}
time: {{end: {end}, dt: {dt}}}
output: {{history_interval: {end}, fields_interval: {end}}}
"""


def run_once(exe, problem, out_dir, threads):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMP_PROC_BIND="false")
    subprocess.run([exe, "run", str(problem), "--out", str(out_dir)], check=True, env=env,
                   stdout=subprocess.DEVNULL)
    return json.loads((out_dir / "summary.json").read_text())


def run_lammps(lmp, workdir, n, steps, ranks):
    """LAMMPS peri/pmb on the n^3 reference lattice: (bonds, loop s, pair s, bytes per bond)."""
    data = workdir / f"data.bench{n}"
    if not data.exists():
        lref.write_data(data, lref.make_lattice(n))
    deck = workdir / f"bench{n}_{steps}.in"
    deck.write_text(lref.deck(data.name, lref.DT_STR, steps, lref.S00_STR, 0, steps,
                              f"benchmark {n}^3", bench=True))
    prefix = []
    if ranks > 1:
        prefix = [shutil.which("mpirun"), "-np", str(ranks), "--oversubscribe"]
        if os.geteuid() == 0:
            prefix.append("--allow-run-as-root")
    text, _ = lref.run_lmp(lmp, workdir, deck.name, prefix=prefix)
    p = lref.parse_log(text)
    m = re.search(r"Per MPI rank memory allocation \(min/avg/max\) = \S+ \| (\S+) \| \S+ Mbytes",
                  text)
    mem = float(m.group(1)) * 2 ** 20 * ranks if m else float("nan")
    return p["bonds"], p["loop"], p["pair"], mem / p["bonds"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshfree", default=str(ROOT / "build" / "meshfree"))
    ap.add_argument("--sizes", type=int, nargs="+", default=[22, 43, 65, 100])
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--no-lammps", action="store_true")
    ap.add_argument("--baseline", help="a second meshfree binary run interleaved with the first")
    ap.add_argument("--out", default=str(ROOT / "out" / "pd_benchmark"))
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    lmp = None if args.no_lammps else lref.find_lmp()
    tmp = Path(tempfile.mkdtemp(prefix="pd_benchmark_"))
    rows = []
    for n in args.sizes:
        L = n * SPACING
        steps = max(5, int(round(EVALUATIONS / (n ** 3 * 120))))
        problem = out / f"lattice_{n}.yaml"
        problem.write_text(PROBLEM.format(n=n, steps=steps, L=L, a=SPACING, half=L / 2, E=YOUNG,
                                          end=steps * DT, dt=DT))
        for threads in args.threads:
            best, lbest, bbest = None, None, None
            for _ in range(args.repeats):
                s = run_once(args.meshfree, problem, out / f"run_{n}_{threads}", threads)
                rate = s["results"]["bond_evaluations_per_second"]
                if best is None or rate > best[0]:
                    best = (rate, s)
                if args.baseline:
                    b = run_once(args.baseline, problem, out / f"baseline_{n}_{threads}", threads)
                    brate = b["results"]["bond_evaluations_per_second"]
                    bbest = brate if bbest is None else max(bbest, brate)
                if lmp:
                    lb = run_lammps(lmp, tmp, n, steps, threads)
                    if lbest is None or lb[1] < lbest[1]:
                        lbest = lb
            rate, s = best
            bonds = 2 * s["counts"]["bonds"]
            steps = s["counts"]["steps"]
            by = s["results"]["bond_bytes_per_bond"]
            row = {"particles": s["counts"]["particles"], "bonds": bonds, "steps": steps,
                   "threads": threads, "step_seconds": bonds * steps / rate,
                   "bond_evaluations_per_second": rate, "per_core": rate / threads,
                   "bytes_steady": by["steady"], "bytes_peak": by["peak"]}
            if bbest:
                row["baseline_rate"] = bbest
                row["ratio_baseline"] = rate / bbest
            if lbest:
                if lbest[0] != bonds:
                    raise SystemExit(f"{n}^3: meshfree has {bonds} bonds, LAMMPS {lbest[0]}")
                row["lammps_loop_rate"] = bonds * steps / lbest[1]
                row["lammps_pair_rate"] = bonds * steps / lbest[2]
                row["lammps_bytes"] = lbest[3]
                row["ratio_loop"] = rate / row["lammps_loop_rate"]
                row["ratio_pair"] = rate / row["lammps_pair_rate"]
                if bbest:
                    row["baseline_ratio_loop"] = bbest / row["lammps_loop_rate"]
            rows.append(row)
            lmp_text = (f" | LAMMPS loop {row['lammps_loop_rate']:.3g}/s, pair {row['lammps_pair_rate']:.3g}/s,"
                        f" {row['lammps_bytes']:.1f} B/bond -> ratio loop {row['ratio_loop']:.2f},"
                        f" pair {row['ratio_pair']:.2f}") if lbest else ""
            base_text = (f" | baseline {bbest:.3g}/s (new / baseline {rate / bbest:.2f}"
                         + (f", baseline / LAMMPS loop {row['baseline_ratio_loop']:.2f}" if lbest else "")
                         + ")") if bbest else ""
            print(f"{row['particles']:7d} particles, {bonds:9d} bonds, {threads} thread(s), {steps} steps: "
                  f"{rate:.3g} bond evaluations/s ({rate / threads:.3g} per core), "
                  f"{by['steady']:.2f} B/bond steady, {by['peak']:.2f} peak{lmp_text}{base_text}", flush=True)
    fields = ["particles", "bonds", "steps", "threads", "step_seconds", "bond_evaluations_per_second",
              "per_core", "bytes_steady", "bytes_peak", "lammps_loop_rate", "lammps_pair_rate",
              "lammps_bytes", "ratio_loop", "ratio_pair", "baseline_rate", "ratio_baseline",
              "baseline_ratio_loop"]
    with open(out / "benchmark.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)
    for threads in args.threads:
        sel = [r for r in rows if r["threads"] == threads]
        if len(sel) > 1:
            per_bond = [r["step_seconds"] / r["steps"] for r in sel]
            slope = np.polyfit(np.log([r["bonds"] for r in sel]), np.log(per_bond), 1)[0]
            print(f"{threads} thread(s): step time grows as bonds^{slope:.2f}")
    one = {r["particles"]: r for r in rows if r["threads"] == 1}
    for r in rows:
        if r["threads"] > 1 and r["particles"] in one:
            print(f"{r['particles']} particles: {r['threads']} threads "
                  f"{r['bond_evaluations_per_second'] / one[r['particles']]['bond_evaluations_per_second']:.2f}x one"
                  + (f" (baseline {r['baseline_rate'] / one[r['particles']]['baseline_rate']:.2f}x)"
                     if "baseline_rate" in r and "baseline_rate" in one[r["particles"]] else ""))
    shutil.rmtree(tmp, ignore_errors=True)
    print(f"wrote {out / 'benchmark.csv'}")


if __name__ == "__main__":
    main()
