#!/usr/bin/python3
"""The elastoplastic 3D cantilever (problems/cantilever_plastic_3d.yaml) against CalculiX C3D20R
on its finest mesh (reference/calculix_3d/cantilever_plastic/curve.csv, made by
scripts/fe_reference/make_calculix_cantilever_3d_reference.py): the tip force at every increment,
at each of the given spacings, and the rate at which the largest difference falls between them.

    cantilever_3d_vs_calculix.py MESHFREE ROOT [--increments N] [--spacings H ...]
                                 [--within F] [--rate R] [--set K=V ...]

It passes when the largest force difference at the finest spacing is within `--within` and,
with two spacings or more, falls at least at `--rate` between the last two. The suite runs the
4 elastic increments at spacings 2.5 and 1.25 (about a minute); the whole curve at 1.25 takes
about 3 minutes on two threads.
"""
import argparse
import csv
import math
import os
import sys
import tempfile

from meshfree_run import calculix_3d_curve, run_meshfree

parser = argparse.ArgumentParser()
parser.add_argument("meshfree")
parser.add_argument("root")
parser.add_argument("--increments", type=int, default=16)
parser.add_argument("--spacings", type=float, nargs="+", default=[1.25])
parser.add_argument("--within", type=float, default=0.015)
parser.add_argument("--rate", type=float, default=1.0)
parser.add_argument("--set", action="append", default=[])
args = parser.parse_args()
n = args.increments
reference = calculix_3d_curve(args.root, "cantilever_plastic", n)


def largest_difference(work, spacing):
    out = os.path.join(work, f"cantilever_{spacing}")
    v = float(reference[n]["v"])
    run_meshfree(args.meshfree, os.path.join(args.root, "problems", "cantilever_plastic_3d.yaml"),
                 out, [f"steps.0.load_factor={v!r}", f"steps.0.increments={n}",
                       f"discretisation.spacing={spacing!r}"] + args.set)
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    if len(rows) != n + 1:
        sys.exit(f"FAIL: {len(rows) - 1} increments, {n} expected")
    worst = 0.0
    print(f"spacing {spacing}:  v (mm)   CalculiX (N)   meshfree (N)   difference")
    for ref, row in zip(reference[1:n + 1], rows[1:]):
        expected, force = float(ref["force_y"]), float(row["reaction_push_y"])
        worst = max(worst, abs(force / expected - 1.0))
        print(f"   {float(ref['v']):.3f}   {expected:12.4f}   {force:12.4f}   "
              f"{force / expected - 1.0:+.3%}")
    return worst


with tempfile.TemporaryDirectory() as work:
    worst = [largest_difference(work, h) for h in args.spacings]
ok = worst[-1] <= args.within
text = (f"largest force difference {', '.join(f'{w:.3%}' for w in worst)} at spacings "
        f"{', '.join(str(h) for h in args.spacings)} (at most {args.within:.1%} at the finest")
if len(worst) > 1:
    rate = math.log(worst[-2] / worst[-1]) / math.log(args.spacings[-2] / args.spacings[-1])
    ok = ok and rate >= args.rate
    text += f"; rate {rate:.2f}, at least {args.rate}"
print(f"{'ok' if ok else 'FAIL'}: {n} increments, {text})")
sys.exit(0 if ok else 1)
