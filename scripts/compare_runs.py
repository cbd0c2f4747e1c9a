#!/usr/bin/python3
"""Compares the fields of two meshfree runs (fields.h5) and exits non-zero if any field of the
last step differs by more than --rtol, relative to that field's largest magnitude.

    scripts/compare_runs.py OUT_A OUT_B [--rtol 1e-8]
"""
import argparse
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
    if worst > args.rtol:
        sys.exit(f"runs differ by {worst:.3e} > {args.rtol:.1e}")
    print(f"runs agree: {worst:.3e} <= {args.rtol:.1e}")


if __name__ == "__main__":
    main()
