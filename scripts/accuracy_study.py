#!/usr/bin/python3
"""Accuracy for the cost: how many DOFs and how much wall time meshfree (RK Galerkin on 3 x 3
Gauss points per cell, with the variationally consistent correction on 2 x 2, and with exact
cut cells at holes), the in-code Q8
elements (on gmsh meshes of the geometry) and CalculiX (CPS8, the reference recipe's meshes) need to come within 1% and 0.1% of the converged CalculiX
load-displacement curve, on the perforated strip and Cook's membrane.

Adaptive meshfree (discretisation.adapt, the recovery estimate and Doerfler marking; on 3 x 3
points, and with the correction on 2 x 2) starts from twice the problem's spacing and runs to a
sequence of targets of the estimated error instead;
its wall time includes its pilot solves. With the correction it is also run refined during the
analysis (`adapt.every: 1`: each increment above the target solved again on a refined cloud,
the state at its start carried to it; no pilots; modified Newton, `nonlinear.keep_tangent:
0.5`, to `nonlinear.tolerance: 1e-5`), from twice the file's spacing (cells cut by a hole integrated on their exact region) and
from the file's own cloud (its spacing, refinement boxes and cut cells, as a user runs the
file); and, from either start, refined in the first increment only (`adapt.until: 1`: its
elastic solution refined until it meets the target, the rest of the schedule on that cloud;
meshfree_vci_first and meshfree_vci_first_file). Q8 is run adapted too, for fairness: on a gmsh mesh
whose size field is each adapted cloud's refinement boxes (its adapted_refinement.yaml), so that
the same estimate grades both; its wall time does not include the meshfree pilots.

Each problem's own discretisation is scaled by a factor (the spacing and every refinement box's
spacing together) over a sequence of factors; CalculiX runs the coarser levels of
scripts/fe_reference/make_calculix_plastic_reference.py (its finest level is the reference, so
it is not timed). The runs of the three codes alternate, level by level, so that they see the
same machine. Every run has one thread (OMP_NUM_THREADS=1, OPENBLAS_NUM_THREADS=1), as the
CalculiX runs have.

The error of a run is the largest difference of its first compared response (the force, or for
the force-driven cook_membrane_force the tip deflection) from the reference over the recorded
increments, divided by the reference's largest value (scripts/compare.py's measure).
The DOFs and the time at which a method first reaches a target error are interpolated
log-linearly between the two runs that bracket it; where CalculiX stays above a target over its
levels, its finest run's time bounds its time to the target from below, and a method's ratio to
it is given as a bound ("<"). CalculiX's DOFs are the 2D mesh's (2 per
node); it solves the expanded one-element-thick slab of C3D20 bricks, which its time includes.

    scripts/accuracy_study.py [--out out/accuracy_study] [--problems perforated_strip cook_membrane
                                                         cook_membrane_force] [--levels N]
                           [--methods METHOD ...]
"""
import argparse
import csv
import importlib.util
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
import compare  # noqa: E402  (the response definitions and the interpolation)

# Factors on the problem file's spacings, coarse to fine, and the CalculiX levels besides the
# finest (reference/calculix_plastic/README.md).
STUDY = {
    "perforated_strip": dict(factors=[4.0, 2.83, 2.0, 1.41, 1.0, 0.71, 0.5],
                             calculix_levels=[4, 6, 8, 16]),
    # Cook's membrane goes two levels further: its meshfree force curve, at 0.15% off at 0.71, reaches
    # 0.1% only there (the clamped corner's singularity slows every method).
    "cook_membrane": dict(factors=[4.0, 2.83, 2.0, 1.41, 1.0, 0.71, 0.5, 0.35],
                          calculix_levels=[6, 12, 24]),
    "cook_membrane_force": dict(factors=[4.0, 2.83, 2.0, 1.41, 1.0, 0.71, 0.5, 0.35],
                                calculix_levels=[6, 12, 24]),
}
TARGETS = (1e-2, 1e-3)
# Targets of the estimated relative energy error of the adaptive runs, coarse to fine.
ADAPT_TARGETS = [0.08, 0.05, 0.035, 0.025, 0.017, 0.012]
ENV = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")


def load_recipe():
    path = ROOT / "scripts" / "fe_reference" / "make_calculix_plastic_reference.py"
    spec = importlib.util.spec_from_file_location("calculix_recipe", path)
    module = importlib.util.module_from_spec(spec)
    sys.path.insert(0, str(path.parent))
    spec.loader.exec_module(module)
    return module


def response_error(problem, xs, ys):
    """Largest |ours - reference| / max |reference| over the reference's records."""
    c = compare.PROBLEMS[problem]
    ref = compare.read_csv(str(ROOT / "reference" / "calculix_plastic" / problem / "curve.csv"))
    rc = c["control"][1]
    rcol = c["responses"][0][2]
    rx = [float(r[rc]) for r in ref]
    ry = [float(r[rcol]) for r in ref]
    scale = max(abs(y) for y in ry)
    return max(abs(compare.interpolate(xs, ys, x) - y) / scale for x, y in zip(rx, ry))


def problem_spacings(problem):
    import yaml
    with open(ROOT / "problems" / f"{problem}.yaml") as f:
        doc = yaml.safe_load(f)
    d = doc["discretisation"]
    return d["spacing"], [(r["box"], r["spacing"]) for r in d.get("refinement", [])]


# The in-code variants: meshfree on the problem's 3 x 3 Gauss points per cell, meshfree with the
# variationally consistent correction on 2 x 2 points, meshfree with the cells a hole cuts
# integrated on their exact region (problems with holes only), and Q8.
VARIANTS = {
    "meshfree": ["discretisation.method=meshfree", "discretisation.quadrature.order=3",
                 "discretisation.quadrature.correction=none"],
    "meshfree_vci": ["discretisation.method=meshfree", "discretisation.quadrature.order=2",
                     "discretisation.quadrature.correction=vci"],
    "meshfree_arcs": ["discretisation.method=meshfree",
                      "discretisation.quadrature.cut_cells=arcs"],
    "fem": ["discretisation.method=fem"],
}
# The scaled runs are uniform: a file's own adaptation (cook_membrane_force) is switched off.
UNIFORM = ["discretisation.adapt=off"]
WITH_HOLES = {"perforated_strip"}


def variants(problem):
    return [m for m in VARIANTS if m != "meshfree_arcs" or problem in WITH_HOLES]


def timed_run(cmd, label):
    """Runs meshfree; its wall time, or None where it did not run (too coarse a discretisation
    for a method: a point its supports do not cover), the study going on with the levels that
    run."""
    start = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV)
    wall = time.perf_counter() - start
    if p.returncode != 0:
        reason = (p.stderr.strip().splitlines() or ["no message"])[-1]
        print(f"{label}: not run (exit {p.returncode}): {reason}")
        return None
    return wall


def curve_row(problem, method, level, folder, wall):
    """The study's row of a run: its DOFs, wall time and the error of its compared response."""
    s = json.loads((folder / "summary.json").read_text())
    c = compare.PROBLEMS[problem]
    hist = compare.read_csv(str(folder / "history.csv"))
    xs = [float(h[c["control"][0]]) for h in hist]
    ys = [float(h[c["responses"][0][1]]) for h in hist]
    return dict(problem=problem, method=method, level=level, dofs=s["counts"]["dofs"],
                wall_s=wall, error=response_error(problem, xs, ys))


def run_case(binary, problem, method, level, out, sets):
    """Runs the problem file with the `--set` assignments `sets`; its study row, or None."""
    folder = out / f"{problem}_{method}_{level}"
    cmd = [str(binary), "run", str(ROOT / "problems" / f"{problem}.yaml"), "--out", str(folder)]
    for a in sets:
        cmd += ["--set", a]
    wall = timed_run(cmd, f"{problem} {method} {level}")
    return None if wall is None else curve_row(problem, method, level, folder, wall)


def run_meshfree(binary, problem, method, factor, out):
    """A uniform run of the variant `method` at `factor` times the problem's spacings."""
    spacing, boxes = problem_spacings(problem)
    refinement = "[" + ", ".join(f"{{box: {b}, spacing: {s * factor!r}}}" for b, s in boxes) + "]"
    sets = [f"discretisation.spacing={spacing * factor!r}",
            f"discretisation.refinement={refinement}"] + VARIANTS[method] + UNIFORM
    return run_case(binary, problem, method, factor, out, sets)


def run_adaptive(binary, problem, target, out, base="meshfree"):
    """Adaptive meshfree on the quadrature of the variant `base` (meshfree or meshfree_vci)."""
    spacing, _ = problem_spacings(problem)
    sets = [f"discretisation.spacing={2 * spacing!r}", "discretisation.refinement=[]",
            f"discretisation.adapt={{target: {target!r}, passes: 10}}"] + VARIANTS[base]
    return run_case(binary, problem, base + "_adaptive", target, out, sets)


def run_vci_adaptive(binary, problem, target, out):
    return run_adaptive(binary, problem, target, out, base="meshfree_vci")


# The runs refined during the analysis keep the factorised tangent while Newton contracts |R| to
# half an iteration (modified Newton: the same converged states, fewer factorisations), and stop
# at |R| <= 1e-5 |F|: a kept tangent contracts |R| linearly, so that each decade below costs
# iterations, and the study's errors are the same to four digits at 1e-8. CalculiX is run to the
# same relative tolerance (its *CONTROLS), where it takes the same time as at 1e-8.
NEWTON_TOLERANCE = 1e-5
KEPT_TANGENT = ["nonlinear.keep_tangent=0.5", f"nonlinear.tolerance={NEWTON_TOLERANCE!r}"]
CALCULIX_CONTROLS = (NEWTON_TOLERANCE, NEWTON_TOLERANCE)


def every_increment(target, until=None):
    """The adapt map of a run refined during the analysis: every increment estimated (up to
    increment `until`, where given) and, above the target, solved again on a refined cloud."""
    return (f"discretisation.adapt={{target: {target!r}, passes: 10, every: 1"
            + (f", until: {until}" if until else "") + "}")


def run_vci_every(binary, problem, target, out, until=None, name="meshfree_vci_every"):
    """Adaptive meshfree with the correction, refined during the analysis itself (every increment
    estimated, and above the target solved again on a refined cloud) instead of by pilot
    solves; a cell cut by a hole integrated on its exact region."""
    spacing, _ = problem_spacings(problem)
    sets = [f"discretisation.spacing={2 * spacing!r}", "discretisation.refinement=[]",
            every_increment(target, until)]
    arcs = ["discretisation.quadrature.cut_cells=arcs"] if problem in WITH_HOLES else []
    return run_case(binary, problem, name, target, out,
                    sets + VARIANTS["meshfree_vci"] + arcs + KEPT_TANGENT)


def run_vci_every_file(binary, problem, target, out, until=None,
                       name="meshfree_vci_every_file"):
    """The same refinement during the analysis from the problem file's own cloud (its spacing,
    refinement boxes and cut cells), as a user runs the file."""
    return run_case(binary, problem, name, target, out,
                    [every_increment(target, until)] + VARIANTS["meshfree_vci"] + KEPT_TANGENT)


def run_vci_first(binary, problem, target, out):
    """Refinement in the first increment only (`until: 1`, its elastic solution estimated and
    refined until it meets the target), the rest of the schedule on that cloud; from 2 h."""
    return run_vci_every(binary, problem, target, out, until=1, name="meshfree_vci_first")


def run_vci_first_file(binary, problem, target, out):
    """Refinement in the first increment only, from the file's own cloud."""
    return run_vci_every_file(binary, problem, target, out, until=1,
                              name="meshfree_vci_first_file")


def run_fem_adapted(binary, problem, target, out):
    """Q8 on a gmsh mesh whose size field is the adapted meshfree cloud's boxes (the same
    estimate, the same start spacing), after run_adaptive with the same target."""
    spacing, _ = problem_spacings(problem)
    boxes = out / f"{problem}_meshfree_adaptive_{target}" / "adapted_refinement.yaml"
    if not boxes.is_file():
        return None
    sets = [f"discretisation.spacing={2 * spacing!r}",
            f"discretisation.refinement={boxes.read_text()}"] + VARIANTS["fem"] + UNIFORM
    return run_case(binary, problem, "fem_adapted", target, out, sets)


def run_calculix(recipe, problem, level, work):
    prob = next(p for p in recipe.PROBLEMS if p["name"] == problem)
    mesh = prob["mesh"](level)
    start = time.perf_counter()
    res = recipe.solve(prob, mesh, str(work), f"study{level}", controls=CALCULIX_CONTROLS)
    wall = time.perf_counter() - start
    curve = res["curve"]
    # the compared response's column of the recipe's curve (load, force, monitors...)
    column = recipe.curve_columns(prob)[1:].index(compare.PROBLEMS[problem]["responses"][0][2])
    return dict(problem=problem, method="calculix", level=level, dofs=2 * mesh.nnodes,
                wall_s=wall,
                error=response_error(problem, list(curve[:, 0]), list(curve[:, column])))


def reach(runs, target):
    """DOFs and wall time where the error first falls to `target` (log-linear between the runs
    that bracket it); None when no run reaches it, the coarsest run's when it already does."""
    runs = sorted(runs, key=lambda r: r["dofs"])
    if runs and runs[0]["error"] <= target:
        return runs[0]["dofs"], runs[0]["wall_s"], "at or below"
    for a, b in zip(runs, runs[1:]):
        if a["error"] > target >= b["error"]:
            t = math.log(a["error"] / target) / math.log(a["error"] / b["error"])
            dofs = math.exp(math.log(a["dofs"]) + t * math.log(b["dofs"] / a["dofs"]))
            wall = math.exp(math.log(a["wall_s"]) + t * math.log(b["wall_s"] / a["wall_s"]))
            return dofs, wall, "about"
    return None


# The adaptive runs, in the order they run at each level (Q8 graded by the boxes of the
# meshfree_adaptive run of the same target).
ADAPTIVE = {"meshfree_adaptive": run_adaptive, "meshfree_vci_adaptive": run_vci_adaptive,
            "meshfree_vci_every": run_vci_every, "meshfree_vci_every_file": run_vci_every_file,
            "meshfree_vci_first": run_vci_first, "meshfree_vci_first_file": run_vci_first_file,
            "fem_adapted": run_fem_adapted}
METHODS = list(VARIANTS) + list(ADAPTIVE) + ["calculix"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshfree", default=str(ROOT / "build" / "meshfree"))
    ap.add_argument("--out", default=str(ROOT / "out" / "accuracy_study"))
    ap.add_argument("--problems", nargs="+", default=list(STUDY), choices=list(STUDY))
    ap.add_argument("--levels", type=int, default=None,
                    help="only the first LEVELS of each sequence (a smoke run)")
    ap.add_argument("--methods", nargs="+", default=None, choices=METHODS,
                    help="only these methods (CalculiX is run whenever it is named)")
    ap.add_argument("--report-only", action="store_true",
                    help="no runs: the report of the runs.csv already in --out")
    args = ap.parse_args()
    wanted = set(args.methods or METHODS)
    out = Path(args.out)
    if args.report_only:
        with open(out / "runs.csv", newline="") as f:
            rows = [dict(r, dofs=int(r["dofs"]), wall_s=float(r["wall_s"]),
                         error=float(r["error"])) for r in csv.DictReader(f)]
        report(rows, args.problems, wanted, out)
        return
    out.mkdir(parents=True, exist_ok=True)
    recipe = load_recipe()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for problem in args.problems:
            study = STUDY[problem]
            levels = max(len(study["factors"]), len(study["calculix_levels"]), len(ADAPT_TARGETS))
            levels = min(levels, args.levels or levels)
            for k in range(levels):
                if k < len(study["factors"]):
                    for method in [m for m in variants(problem) if m in wanted]:
                        row = run_meshfree(args.meshfree, problem, method, study["factors"][k],
                                           out)
                        if row:
                            rows.append(row)
                            print(row, flush=True)
                if k < len(ADAPT_TARGETS):
                    for method, run_one in ADAPTIVE.items():
                        if method not in wanted:
                            continue
                        row = run_one(args.meshfree, problem, ADAPT_TARGETS[k], out)
                        if row:
                            rows.append(row)
                            print(row, flush=True)
                if k < len(study["calculix_levels"]) and "calculix" in wanted:
                    rows.append(run_calculix(recipe, problem, study["calculix_levels"][k], work))
                    print(rows[-1], flush=True)
    with open(out / "runs.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    report(rows, args.problems, wanted, out)


def report(rows, problems, wanted, out):
    """Prints and writes (reach.csv) the DOFs and time at which each method first reaches each
    target, and its ratio to CalculiX's time."""
    summary = []
    print("\nDOFs and wall time (1 thread) to reach the error, and the time over CalculiX's:")
    for problem in problems:
        for target in TARGETS:
            got = {m: reach([r for r in rows if r["problem"] == problem and r["method"] == m], target)
                   for m in variants(problem) + list(ADAPTIVE) + ["calculix"] if m in wanted}
            ccx, bound = got.get("calculix"), ""
            ccx_runs = [r for r in rows if r["problem"] == problem and r["method"] == "calculix"]
            if ccx is None and ccx_runs:
                # Not reached over CalculiX's levels: it needs more than its finest run's time.
                finest = max(ccx_runs, key=lambda r: r["dofs"])
                ccx, bound = (finest["dofs"], finest["wall_s"], "beyond"), "<"
            for method, g in got.items():
                entry = dict(problem=problem, target=target, method=method)
                if g is None:
                    entry.update(dofs="", wall_s="", ratio_to_calculix="", note="not reached")
                elif method == "calculix" or not ccx:
                    entry.update(dofs=round(g[0]), wall_s=round(g[1], 3), ratio_to_calculix="",
                                 note=g[2])
                else:
                    entry.update(dofs=round(g[0]), wall_s=round(g[1], 3),
                                 ratio_to_calculix=f"{bound}{g[1] / ccx[1]:.3f}", note=g[2])
                summary.append(entry)
                ratio = ("" if g is None or not ccx else
                         f", x{g[1] / ccx[1]:.2f} CalculiX's time" if not bound else
                         f", under x{g[1] / ccx[1]:.2f} CalculiX's time (its finest run, "
                         f"{ccx[1]:.1f} s, is above the target)")
                print(f"  {problem:19s} {target:6.0e} {method:23s}: "
                      + ("not reached over the runs" if g is None else
                         f"{g[2]} {g[0]:.0f} DOFs, {g[1]:.2f} s"
                         + ("" if method == "calculix" else ratio)))
    with open(out / "reach.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(summary[0].keys()))
        w.writeheader()
        w.writerows(summary)
    print(f"\n{out / 'runs.csv'}, {out / 'reach.csv'}")


if __name__ == "__main__":
    main()
