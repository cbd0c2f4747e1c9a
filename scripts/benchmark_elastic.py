#!/usr/bin/python3
"""Cost of the implicit elastic solve against problem size: runs problems/plate_tension.yaml on
n x n node lattices, reads the phase times from summary.json, and writes benchmark.csv with the
times and rates (Gauss points per second for shape functions and assembly, DOFs per second for
the solve, nodes per second for the neighbour search) and the growth exponent of each phase
(slope of log time against log DOFs).

    scripts/benchmark_elastic.py [--sizes 50 100 200 316] [--ranks 1] [--out out/benchmark]
"""
import argparse
import csv
import json
import subprocess
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
PHASES = ["neighbours", "shape_functions", "assembly", "solve", "total"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshfree", default=str(ROOT / "build" / "meshfree"))
    ap.add_argument("--sizes", type=int, nargs="+", default=[50, 100, 200, 316])
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--out", default=str(ROOT / "out" / "benchmark"))
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for n in args.sizes:
        run_dir = out / f"plate_{n}x{n}"
        cmd = [args.meshfree, "run", str(ROOT / "problems" / "plate_tension.yaml"), "--out", str(run_dir),
               "--set", f"discretisation.spacing={1.0 / (n - 1)!r}"]
        if args.ranks > 1:
            cmd = ["mpirun", "-n", str(args.ranks)] + cmd
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        s = json.loads((run_dir / "summary.json").read_text())
        c, t = s["counts"], s["time_s"]
        row = {"nodes": c["nodes"], "dofs": c["dofs"], "domain_points": c["domain_points"],
               "nonzeros": c["matrix_nonzeros"], **{f"{p}_s": t[p] for p in PHASES}}
        row["neighbour_nodes_per_s"] = c["nodes"] / t["neighbours"]
        row["shape_points_per_s"] = c["domain_points"] / t["shape_functions"]
        row["assembly_points_per_s"] = c["domain_points"] / t["assembly"]
        row["solve_dofs_per_s"] = c["dofs"] / t["solve"]
        rows.append(row)
        print(f"{c['nodes']:7d} nodes: " + ", ".join(f"{p} {t[p]:.2f} s" for p in PHASES) +
              f" | assembly {row['assembly_points_per_s']:.3g} points/s, solve {row['solve_dofs_per_s']:.3g} DOFs/s")
    with open(out / "benchmark.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    if len(rows) > 1:
        dofs = np.log([r["dofs"] for r in rows])
        for p in PHASES:
            slope = np.polyfit(dofs, np.log([r[f"{p}_s"] for r in rows]), 1)[0]
            print(f"{p}: time grows as DOFs^{slope:.2f}")
    print(f"wrote {out / 'benchmark.csv'}")


if __name__ == "__main__":
    main()
