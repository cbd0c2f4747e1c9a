#!/usr/bin/python3
"""Compares two meshfree runs and exits non-zero if they differ by more than --rtol: every field
of the last step in fields.h5 (relative to that field's largest magnitude) and every number under
"results" in summary.json (errors, reactions, constraint violations; relative to its magnitude).

    scripts/compare_runs.py OUT_A OUT_B [--rtol 1e-8]
"""
import argparse
import json
import sys

import h5py
import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--rtol", type=float, default=1e-8)
    args = ap.parse_args()
    with h5py.File(f"{args.a}/fields.h5", "r") as fa, h5py.File(f"{args.b}/fields.h5", "r") as fb:
        if not np.array_equal(fa["geometry/coordinates"][...], fb["geometry/coordinates"][...]):
            sys.exit("the two runs have different nodes")
        step = sorted(k for k in fa.keys() if k.startswith("step_"))[-1]
        worst = 0.0
        for name in fa[step]:
            x, y = fa[step][name][...], fb[step][name][...]
            scale = max(np.abs(x).max(), 1e-300)
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

    ra = dict(numbers(json.loads(open(f"{args.a}/summary.json").read())["results"]))
    rb = dict(numbers(json.loads(open(f"{args.b}/summary.json").read())["results"]))
    if ra.keys() != rb.keys():
        sys.exit("the two summaries report different results")
    force_scale = max([abs(v) for k, v in ra.items() if k.startswith("boundary.") and "violation" not in k] or [1.0])
    for key in ra:
        # Round-off of a quantity that is zero (a reaction component, a constraint violation of
        # 1e-9) is measured against its natural scale: the largest force, the largest displacement.
        if "violation" in key:
            scale = ra.get("max_displacement", 1.0)
        elif key.startswith("boundary."):
            scale = force_scale
        else:
            scale = max(abs(ra[key]), 1e-300)
        rel = abs(ra[key] - rb[key]) / scale
        worst = max(worst, rel)
        if rel > args.rtol:
            print(f"summary {key}: {ra[key]:.12g} against {rb[key]:.12g} (relative {rel:.3e})")
    print(f"summary.json results: {len(ra)} numbers compared")
    if worst > args.rtol:
        sys.exit(f"runs differ by {worst:.3e} > {args.rtol:.1e}")
    print(f"runs agree: {worst:.3e} <= {args.rtol:.1e}")


if __name__ == "__main__":
    main()
