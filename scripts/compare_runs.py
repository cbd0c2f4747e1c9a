#!/usr/bin/python3
"""Compares two meshfree runs and exits non-zero if they differ by more than --rtol: every field
of the last step in fields.h5 (relative to that field's largest magnitude), every column of
history.csv (relative to the column's largest magnitude; solver iteration counts and residuals
excepted) and every number under "results" in summary.json (relative to the largest magnitude of
its section, e.g. all reactions of a condition, or all monitor displacements). The components of
a vector (names ending in _x, _y, _z) are measured against the largest of them. An energy
balance residual given as a fraction of the run's energy scale (the history column energy_error,
the results energy_error_relative and energy_balance_relative) is measured against that scale,
1, not against the residual itself: the energies of a run spread over MPI ranks are summed in
another order, which moves the residual by the round-off of the energies.

    scripts/compare_runs.py OUT_A OUT_B [--rtol 1e-8] [--match-positions]

--match-positions pairs the nodes (particles) of the two runs by their coordinates when the two
runs write them in different orders (e.g. particles renumbered along a space-filling curve);
the two sets of coordinates must then be equal as sets.
"""
import argparse
import csv
import json
import re
import sys

import h5py
import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--rtol", type=float, default=1e-8)
    ap.add_argument("--match-positions", action="store_true",
                    help="pair nodes by coordinates when the runs order them differently")
    args = ap.parse_args()
    with h5py.File(f"{args.a}/fields.h5", "r") as fa, h5py.File(f"{args.b}/fields.h5", "r") as fb:
        xa, xb = fa["geometry/coordinates"][...], fb["geometry/coordinates"][...]
        order_a = order_b = slice(None)
        if not np.array_equal(xa, xb):
            if not args.match_positions or xa.shape != xb.shape:
                sys.exit("the two runs have different nodes")
            # Lexicographic order of the coordinates on both sides pairs equal positions.
            order_a = np.lexsort(xa.T[::-1])
            order_b = np.lexsort(xb.T[::-1])
            if not np.array_equal(xa[order_a], xb[order_b]):
                sys.exit("the two runs have different nodes (as sets of positions)")
            print(f"nodes paired by position ({len(xa)})")
        step = sorted(k for k in fa.keys() if k.startswith("step_"))[-1]
        worst = 0.0
        # Stress components are measured against the largest of them (szz of plane stress is
        # round-off around zero).
        stress_scale = max([np.abs(fa[step][n][...]).max() for n in fa[step]
                            if n.startswith("stress_") or n == "von_mises"] or [0.0])
        for name in fa[step]:
            x, y = fa[step][name][...][order_a], fb[step][name][...][order_b]
            own = np.abs(x).max()
            scale = max(stress_scale if name.startswith("stress_") else own, 1e-300)
            rel = np.abs(x - y).max() / scale
            worst = max(worst, rel)
            print(f"{step}/{name}: max relative difference {rel:.3e}")
    def numbers(tree, prefix=""):
        if isinstance(tree, dict):
            for k, v in tree.items():
                yield from numbers(v, f"{prefix}{k}.")
        elif isinstance(tree, list):
            for i, v in enumerate(tree):
                yield from numbers(v, f"{prefix}{i}.")
        elif isinstance(tree, (int, float)) and not isinstance(tree, bool):
            yield prefix.rstrip("."), float(tree)

    def results(run):  # a staged run's results are its stages'
        summary = json.loads(open(f"{run}/summary.json").read())
        if "results" in summary:
            return dict(numbers(summary["results"]))
        return {f"{name}.{k}": v for name, stage in summary.get("stages", {}).items()
                for k, v in numbers(stage.get("results", {}))}

    ra, rb = results(args.a), results(args.b)
    # Iteration counts, rates measured in wall time, memory use, round-off quantities, and where a maximum lies (symmetric problems
    # have ties that round-off decides).
    solver_keys = ("newton_iterations", "equilibrium_error", ".at.", "per_second", "bond_bytes")
    ra = {k: v for k, v in ra.items() if not any(s in k for s in solver_keys)}
    rb = {k: v for k, v in rb.items() if not any(s in k for s in solver_keys)}
    if ra.keys() != rb.keys():
        sys.exit("the two summaries report different results")

    def vector(name):  # a vector's components are measured against the largest of them
        return re.sub(r"_[xyz]$", "", name)

    def balance(name):  # an energy residual as a fraction of the energy scale
        return name == "energy_error" or name.endswith(("energy_error_relative",
                                                        "energy_balance_relative"))

    def section(key):
        return vector(".".join(key.split(".")[:2]))

    sections = {}
    for k, v in ra.items():
        if "violation" not in k:
            sections[section(k)] = max(sections.get(section(k), 0.0), abs(v))
    for key in ra:
        # Round-off of a quantity that is zero (a reaction component, a constraint violation of
        # 1e-9) is measured against its natural scale: the largest of its kind, the largest
        # displacement.
        if "violation" in key:
            scale = ra.get("max_displacement", 1.0)
        elif balance(key):
            scale = 1.0
        else:
            scale = max(sections[section(key)], 1e-300)
        rel = abs(ra[key] - rb[key]) / scale
        worst = max(worst, rel)
        if rel > args.rtol:
            print(f"summary {key}: {ra[key]:.12g} against {rb[key]:.12g} (relative {rel:.3e})")

    try:
        ha = list(csv.DictReader(open(f"{args.a}/history.csv")))
        hb = list(csv.DictReader(open(f"{args.b}/history.csv")))
    except FileNotFoundError:
        ha = hb = []
    if len(ha) != len(hb):
        sys.exit(f"history.csv: {len(ha)} rows against {len(hb)}")
    solver = {"newton_iterations", "cutbacks", "residual_relative", "equilibrium_error",
              "solver_iterations"}
    def kind(col):  # forces and displacements are measured against the largest of their kind
        # A gauge's motion against the largest of every gauge: a gauge the wave has not reached
        # yet moves by round-off, which its own largest value would magnify without bound.
        return ("force" if col.startswith(("reaction_", "load_")) else
                "displacement" if col.startswith(("ux_", "uy_")) else
                "gauge displacement" if col.endswith(("_ux", "_uy", "_uz")) else
                "gauge velocity" if col.endswith(("_vx", "_vy", "_vz")) else
                "gauge acceleration" if col.endswith(("_ax", "_ay", "_az")) else vector(col))

    columns = [c for c in (ha[0].keys() if ha else []) if c not in solver]
    kinds = {}
    for col in columns:
        kinds[kind(col)] = max(kinds.get(kind(col), 0.0),
                               max(abs(float(r[col])) for r in ha))
    for col in columns:
        x = np.array([float(r[col]) for r in ha])
        y = np.array([float(r[col]) for r in hb])
        scale = 1.0 if balance(col) else max(kinds[kind(col)], 1e-300)
        rel = np.abs(x - y).max() / scale
        worst = max(worst, rel)
        if rel > args.rtol:
            print(f"history.csv {col}: relative difference {rel:.3e}")
    if ha:
        print(f"history.csv: {len(ha)} rows compared")
    print(f"summary.json results: {len(ra)} numbers compared")
    if worst > args.rtol:
        sys.exit(f"runs differ by {worst:.3e} > {args.rtol:.1e}")
    print(f"runs agree: {worst:.3e} <= {args.rtol:.1e}")


if __name__ == "__main__":
    main()
