#!/usr/bin/python3
"""The 3D punch block (problems/punch_block_3d.yaml: a quarter block pushed in by a pressure patch
far into J2 plasticity) against CalculiX C3D20R (reference/calculix_3d/punch_block, made by
scripts/fe_reference/make_calculix_punch_3d_reference.py), on the finest mesh there, the graded
one (0.25 near the patch, 78,360 DOFs): at every increment the patch's mean displacement (the history's normal_displacement_patch, the
mean of u.n over the patch's face points) and the patch centre's displacement; at the last, the
plastic strain and von Mises stress 4 mm below the patch centre (the file's line `axis` at
(0, 4, 0)). The reference's own last change, from h = 0.5 to the graded mesh (convergence.csv:
+0.22% mean displacement, -0.33% centre, -1.6% plastic strain, -0.79% von Mises), bounds what the
comparison can tell. Asserted with `--check`: the displacements within 1% at every
increment, the plastic strain within 5% and von Mises within 2%; with `--mean-within F` the
patch's mean displacement within F at every increment (the suite: F = 0.01 over the file's
first 5 increments, elastic, on its own run in tests/cli/problems_run.sh). The problem's
increments are 50 MPa; `--increments N` runs the first N of them.

    punch_3d_vs_calculix.py MESHFREE ROOT [--increments N] [--check] [--mean-within F]
                            [--set K=V ...]
    punch_3d_vs_calculix.py MESHFREE ROOT --run-dir DIR [--increments N] [--check]
                            [--mean-within F]
"""
import argparse
import csv
import os
import sys
import tempfile

from meshfree_run import Checks, run_meshfree

parser = argparse.ArgumentParser()
parser.add_argument("meshfree")
parser.add_argument("root")
parser.add_argument("--increments", type=int, default=20)
parser.add_argument("--set", action="append", default=[])
parser.add_argument("--run-dir", help="a finished run of the problem instead of a run")
parser.add_argument("--check", action="store_true",
                    help="assert 1% on the displacements, 5% and 2% on the local values")
parser.add_argument("--mean-within", type=float, default=None,
                    help="assert the patch's mean displacement within this fraction")
args = parser.parse_args()
if args.run_dir and args.set:
    parser.error("--set changes a run this script makes; --run-dir is a finished one")
n = args.increments
folder = os.path.join(args.root, "reference", "calculix_3d", "punch_block")
with open(os.path.join(folder, "punch_graded.csv")) as f:
    reference = list(csv.DictReader(f))
if not 1 <= n < len(reference):
    sys.exit(f"--increments: 1 to {len(reference) - 1}, got {n}")


def results(out):
    """The history's rows and the line `axis`'s point (0, 4, 0) at increment n."""
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "line_axis.csv")) as f:
        below = [r for r in csv.DictReader(f)
                 if int(r["increment"]) == n and abs(float(r["y"]) - 4.0) < 1e-9]
    return rows, below[0]


if args.run_dir:
    rows, below = results(args.run_dir)
else:
    with tempfile.TemporaryDirectory() as work:
        out = os.path.join(work, "punch")
        run_meshfree(args.meshfree, os.path.join(args.root, "problems", "punch_block_3d.yaml"),
                     out, [f"steps.0.load_factor={50.0 * n!r}", f"steps.0.increments={n}"]
                     + args.set)
        rows, below = results(out)
check = Checks()
check(len(rows) == n + 1, f"{len(rows) - 1} increments of {n}")
worst_mean = worst_centre = 0.0
print("  p (MPa)   mean patch displacement: CalculiX, meshfree   patch centre: CalculiX, meshfree")
for ref, row in zip(reference[1:n + 1], rows[1:]):
    p = float(ref["p"])
    if abs(float(row["factor_patch"]) - p) > 1e-9 * p:
        sys.exit(f"FAIL: increment at p = {row['factor_patch']} where CalculiX has {p}")
    mean, centre = -float(row["normal_displacement_patch"]), -float(row["uy_centre"])
    e_mean = mean / float(ref["mean_patch_disp"]) - 1.0
    e_centre = centre / float(ref["uy_centre"]) - 1.0
    worst_mean, worst_centre = max(worst_mean, abs(e_mean)), max(worst_centre, abs(e_centre))
    print(f"  {p:7.1f}   {float(ref['mean_patch_disp']):.5e}, {mean:.5e} ({e_mean:+.2%})"
          f"   {float(ref['uy_centre']):.5e}, {centre:.5e} ({e_centre:+.2%})")
last = reference[n]
peeq, mises = float(last["peeq_0_4_0"]), float(last["mises_0_4_0"])
e_peeq = float(below["plastic_strain"]) / peeq - 1.0 if peeq > 0.0 else 0.0
e_mises = float(below["von_mises"]) / mises - 1.0
print(f"  at (0, 4, 0), p = {float(last['p']):g}: plastic strain {float(below['plastic_strain']):.5f}"
      f" against {peeq:.5f} ({e_peeq:+.1%}), von Mises {float(below['von_mises']):.2f} against"
      f" {mises:.2f} ({e_mises:+.2%})")
if args.mean_within is not None:
    check(worst_mean <= args.mean_within,
          f"the patch's mean displacement within {worst_mean:.2%} of CalculiX's at every "
          f"increment (at most {args.mean_within:.0%})")
if args.check:
    check(worst_mean <= 0.01 and worst_centre <= 0.01,
          f"the patch's mean displacement within {worst_mean:.2%} and its centre's within "
          f"{worst_centre:.2%} of CalculiX's at every increment (at most 1%)")
    check(abs(e_peeq) <= 0.05 and abs(e_mises) <= 0.02,
          "4 mm below the patch the plastic strain within 5% and von Mises within 2%")
sys.exit(1 if check.failed else 0)
