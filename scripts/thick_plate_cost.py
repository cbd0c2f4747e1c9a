#!/usr/bin/python3
"""meshfree's and CalculiX's wall time for the thick perforated plate at the same accuracy, on
one thread each.

meshfree runs problems/thick_perforated_plate.yaml (with any --set); its error is the largest
difference of its pull force from the converged CalculiX C3D20R curve
(reference/calculix_3d/thick_perforated_plate/curve.csv) over the increments, relative to the
reference force of the same increment (as tests/reference/solid3d_vs_calculix.py measures it).
CalculiX then runs C3D20R on the reference recipe's meshes (scripts/fe_reference/
make_calculix_3d_reference.py: its mapped mesh of n elements along each arc, extruded in nz
layers; its deck writer and parser) from the coarsest of --levels up, until one is as close to
the reference as meshfree's run; that level is the one timed. The two codes then run again in
turn (--repeats in all), so that both see the same machine. Every run has one thread
(OMP_NUM_THREADS=1, and CalculiX's CCX_NPROC_EQUATION_SOLVER=1). CalculiX's time is the deck's
writing (milliseconds) and ccx; meshfree's is its whole run. Writes table.csv and table.md.

    scripts/thick_plate_cost.py [--out DIR] [--set KEY=VALUE ...] [--increments N] [--repeats R]
    scripts/thick_plate_cost.py --set discretisation.method=fem --set discretisation.spacing=1
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts" / "fe_reference"))
import make_calculix_3d_reference as recipe  # noqa: E402  (meshes, deck, ccx run, parsing)

PROBLEM = ROOT / "problems" / "thick_perforated_plate.yaml"
REFERENCE = ROOT / "reference" / "calculix_3d" / "thick_perforated_plate" / "curve.csv"
ONE_THREAD = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")


def force_error(forces, reference):
    """Largest |F / F_ref - 1| over the increments (forces[k]: increment k + 1)."""
    return max(abs(f / r - 1.0) for f, r in zip(forces, reference[1:len(forces) + 1, 1]))


def run_meshfree(binary, sets, increments, folder):
    """One meshfree run of the first `increments` increments: wall time, DOFs, pull forces."""
    pull = recipe.V_END * increments / recipe.N_INC
    cmd = [binary, "run", str(PROBLEM), "--out", str(folder),
           "--set", f"steps.0.load_factor={pull!r}", "--set", f"steps.0.increments={increments}"]
    for s in sets:
        cmd += ["--set", s]
    start = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True, env=ONE_THREAD)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {done.returncode}: "
                 f"{(done.stderr.strip().splitlines() or ['no message'])[-1]}")
    with open(folder / "history.csv") as f:
        forces = [float(r["reaction_pull_y"]) for r in list(csv.DictReader(f))[1:]]
    dofs = json.loads((folder / "summary.json").read_text())["counts"]["dofs"]
    return dict(wall=wall, dofs=dofs, forces=forces)


def run_calculix(n, nz, work, tag):
    """One CalculiX C3D20R run on the recipe's mesh (n, nz): wall time, DOFs, pull forces."""
    mesh = recipe.plate_mesh(n, nz)
    r = recipe.solve(mesh, work, tag)
    return dict(wall=r["wall"], dofs=3 * mesh.nnodes, forces=list(r["curve"][1:, 1]))


def write_tables(out, rows):
    with open(out / "table.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    lines = ["| code | discretisation | DOFs | force error (largest, per increment) | "
             "wall times, one thread [s] | median [s] |", "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['code']} | {r['discretisation']} | {r['dofs']:,} | "
                     f"{r['force_error']:.3%} | {r['wall_s']} | {r['median_s']:.2f} |")
    (out / "table.md").write_text("\n".join(lines) + "\n")
    print("\n" + "\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--meshfree", default=str(ROOT / "build" / "meshfree"))
    ap.add_argument("--out", default=str(ROOT / "out" / "thick_plate_cost"))
    ap.add_argument("--set", action="append", default=[], help="KEY=VALUE for meshfree's run")
    ap.add_argument("--increments", type=int, default=recipe.N_INC,
                    help="the first N of the reference's 20 increments of 0.005 mm")
    ap.add_argument("--levels", type=int, nargs="+", default=[2, 3, 4, 5, 6, 8],
                    help="CalculiX meshes tried, coarse to fine: n elements along each arc")
    ap.add_argument("--layers", type=int, default=1, help="CalculiX's layers through the half "
                    "thickness (nz)")
    ap.add_argument("--repeats", type=int, default=2, help="timed runs of each code, in turn")
    args = ap.parse_args()
    if not 1 <= args.increments <= recipe.N_INC:
        print(f"--increments: 1 to {recipe.N_INC}, got {args.increments}", file=sys.stderr)
        sys.exit(2)
    if args.repeats < 1:
        print(f"--repeats: at least 1, got {args.repeats}", file=sys.stderr)
        sys.exit(2)
    # The recipe's deck and parser take the pull and its increments from these two.
    recipe.V_END = recipe.V_END * args.increments / recipe.N_INC
    recipe.N_INC = args.increments
    _, reference = recipe.read_curve(str(REFERENCE))
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="thick_plate_cost_") as tmp:
        work = Path(tmp)
        mf = [run_meshfree(args.meshfree, args.set, args.increments, work / "meshfree_0")]
        target = force_error(mf[0]["forces"], reference)
        print(f"meshfree ({', '.join(args.set) or 'the problem as it is'}): {mf[0]['dofs']} DOFs, "
              f"force error {target:.3%}, {mf[0]['wall']:.1f} s", flush=True)
        chosen = None
        for n in args.levels:
            run = run_calculix(n, args.layers, str(work), f"n{n}_0")
            error = force_error(run["forces"], reference)
            print(f"CalculiX C3D20R n = {n}, nz = {args.layers}: {run['dofs']} DOFs, force error "
                  f"{error:.3%}, {run['wall']:.2f} s", flush=True)
            if error <= target:
                chosen, ccx = n, [run]
                break
        if chosen is None:
            print(f"no CalculiX level of {args.levels} reaches meshfree's {target:.3%}",
                  file=sys.stderr)
            sys.exit(1)
        for k in range(1, args.repeats):
            mf.append(run_meshfree(args.meshfree, args.set, args.increments, work / f"meshfree_{k}"))
            ccx.append(run_calculix(chosen, args.layers, str(work), f"n{chosen}_{k}"))
            print(f"repeat {k + 1}: meshfree {mf[-1]['wall']:.1f} s, CalculiX {ccx[-1]['wall']:.2f} s",
                  flush=True)
    rows = []
    for code, label, runs in (("meshfree", ", ".join(args.set) or "problem file", mf),
                              ("CalculiX", f"C3D20R n = {chosen}, nz = {args.layers}", ccx)):
        walls = [r["wall"] for r in runs]
        rows.append(dict(code=code, discretisation=label, dofs=runs[0]["dofs"],
                         increments=args.increments,
                         force_error=force_error(runs[0]["forces"], reference),
                         wall_s=" ".join(f"{w:.2f}" for w in walls),
                         median_s=statistics.median(walls)))
    write_tables(out, rows)
    print(f"meshfree / CalculiX wall time at the same accuracy: "
          f"{rows[0]['median_s'] / rows[1]['median_s']:.1f}")


if __name__ == "__main__":
    main()
