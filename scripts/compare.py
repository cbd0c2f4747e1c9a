#!/usr/bin/python3
"""Overlays the load-displacement curves of meshfree, the in-code finite elements and CalculiX
for the elastoplastic problems, writes one PNG per problem, and prints the largest differences.

    scripts/compare.py                          # every problem below, runs both discretisations
    scripts/compare.py perforated_strip         # one problem
    scripts/compare.py --check 0.02             # exit 1 if a curve differs from CalculiX by more
    scripts/compare.py --check-first-yield 0.01 # ... or a first-yield load, where it is defined
    scripts/compare.py --meshfree-dir DIR ...   # use finished runs instead of running them
    scripts/compare.py --list                   # the problems it compares, one a line

The difference at a recorded point is |ours - CalculiX| divided by the largest |value| of the
CalculiX curve (so that points near zero do not blow it up); ours is interpolated linearly to
the reference's control values when its increments were cut. The CalculiX curves and how they
were made: reference/calculix_plastic/README.md.
"""

import argparse
import csv
import json
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

# First yield is compared only where the elastic stress is bounded: the clamped corners of the
# plates and the cantilever, and the end of the half clamp of the asymmetric plate, are stress
# singularities, and the reference's first-yield load falls with every mesh refinement there
# (reference/calculix_plastic/*/elastic_limit.csv).
#
# For each problem: the control (load factor) column of history.csv and of the reference curve,
# then the compared responses as (label, history column, reference column). Reactions on both
# sides are the force the support exerts on the body.
PROBLEMS = {
    "plate_plastic_thesis": dict(
        control=("factor_tension", "q", "edge load q [N/mm]"), driver="tension",
        responses=[("u_y at (0.5, 1) [mm]", "uy_top_centre", "uy_05_1"),
                   ("u_x at (1, 1) [mm]", "ux_top_right", "ux_1_1")],
        # [Faraji 2007] Fig. 4-26: u_x along the top edge at q = 308 and 308.25 (increments 4, 5).
        lines=[("top", 4, "line_top_308.csv"), ("top", 5, "line_top_30825.csv")]),
    "plate_plastic_limit": dict(
        control=("factor_pull", "v", "top displacement v [mm]"), driver="pull",
        responses=[("force on the top edge [N]", "reaction_pull_y", "force_top")]),
    "plate_asymmetric_plastic": dict(
        control=("factor_pull", "v", "top displacement v [mm]"), driver="pull",
        responses=[("force on the top edge [N]", "reaction_pull_y", "force_top")]),
    # The strip and Cook's membrane, the two problems whose discretisations the convergence
    # study chose, are held to 1% (check) rather than the suite's 2%.
    "perforated_strip": dict(
        control=("factor_pull", "v", "end displacement v [mm]"), driver="pull",
        elastic_limit=True, check=0.01,
        responses=[("force on the end [kgf]", "reaction_pull_y", "force_top")]),
    "cook_membrane": dict(
        control=("factor_shear", "v", "end shear displacement v [mm]"), driver="shear", check=0.01,
        responses=[("force on the end [N]", "reaction_shear_y", "force_right"),
                   ("u_x at (48, 60) [mm]", "ux_top_right", "ux_48_60")]),
    # Driven by force near its limit, where the tip's deflection amplifies the error of the force
    # balance about eight times: its file adapts the meshfree cloud to reach 1%.
    "cook_membrane_force": dict(
        control=("factor_shear", "F", "end shear force F [N]"), driver="shear", check=0.01,
        responses=[("u_y at (48, 60) [mm]", "uy_top_right", "uy_48_60"),
                   ("u_x at (48, 60) [mm]", "ux_top_right", "ux_48_60")]),
    # A hole of the built-in dialect other than a circle: the slot's round ends and straight
    # sides, at an angle to the pull, so the grips carry a shear force too.
    "slotted_plate": dict(
        control=("factor_pulled_grip", "v", "grip displacement v [mm]"), driver="pulled_grip",
        check=0.01,
        responses=[("force along x on the pulled grip [N]", "reaction_pulled_grip_x", "force_x"),
                   ("force along y on the pulled grip [N]", "reaction_pulled_grip_y", "force_y")]),
    "filleted_bar": dict(
        control=("factor_pulled_end", "v", "end displacement v [mm]"), driver="pulled_end",
        elastic_limit=True, check=0.01,
        responses=[("force along x on the pulled end [N]", "reaction_pulled_end_x", "force_x")]),
    # The same body read from a STEP file: the same reference.
    "filleted_bar_from_step": dict(
        control=("factor_pulled_end", "v", "end displacement v [mm]"), driver="pulled_end",
        elastic_limit=True, check=0.01, reference="filleted_bar",
        responses=[("force along x on the pulled end [N]", "reaction_pulled_end_x", "force_x")]),
    "beam_voce_bending": dict(
        control=("factor_push", "v", "end deflection v [mm]"), driver="push",
        responses=[("force on the end [N]", "reaction_push_y", "force_right")]),
}


def reference_dir(problem):
    """The problem's CalculiX reference: its own, or that of the body it shares (`reference`)."""
    return os.path.join(ROOT, "reference", "calculix_plastic",
                        PROBLEMS[problem].get("reference", problem))


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def interpolate(xs, ys, x):
    """Linear interpolation of the curve (xs increasing, then possibly decreasing) at x within
    the first monotone branch that contains it."""
    for i in range(1, len(xs)):
        lo, hi = min(xs[i - 1], xs[i]), max(xs[i - 1], xs[i])
        if lo - 1e-12 * (abs(hi) + 1e-300) <= x <= hi + 1e-12 * (abs(hi) + 1e-300):
            if hi == lo:
                return ys[i]
            t = (x - xs[i - 1]) / (xs[i] - xs[i - 1])
            return ys[i - 1] + t * (ys[i] - ys[i - 1])
    return None


def run(problem, method, out_dir, meshfree):
    """Runs the problem with the given discretisation method; returns the output folder."""
    folder = os.path.join(out_dir, f"{problem}_{method}")
    cmd = [meshfree, "run", os.path.join(ROOT, "problems", problem + ".yaml"), "--out", folder,
           "--set", f"discretisation.method={method}"]
    if method == "fem":
        cmd += ["--set", "discretisation.adapt=off"]   # a file's adapted cloud is meshfree's
    print("running:", " ".join(cmd), flush=True)
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        sys.stdout.write(done.stdout[-3000:])
        raise SystemExit(f"{problem} ({method}) failed with exit code {done.returncode}")
    return folder


def compare(problem, runs, out_dir):
    """Prints and returns the largest difference of each run's curves from CalculiX."""
    spec = PROBLEMS[problem]
    ref = read_csv(os.path.join(reference_dir(problem), "curve.csv"))
    hist_control, ref_control, control_label = spec["control"]
    worst = {}
    curves = []
    for label, hist_col, ref_col in spec["responses"]:
        rx = [float(r[ref_control]) for r in ref]
        ry = [float(r[ref_col]) for r in ref]
        scale = max(abs(y) for y in ry)
        entry = dict(label=label, reference=(rx, ry), runs={})
        for method, folder in runs.items():
            hist = read_csv(os.path.join(folder, "history.csv"))
            hx = [float(h[hist_control]) for h in hist]
            hy = [float(h[hist_col]) for h in hist]
            entry["runs"][method] = (hx, hy)
            diffs = []
            for x, y in zip(rx, ry):
                ours = interpolate(hx, hy, x)
                if ours is None:
                    raise SystemExit(f"{problem} ({method}): no result at {ref_control} = {x}; "
                                     "did the run stop early?")
                diffs.append(abs(ours - y) / scale)
            d = max(diffs)
            worst[(method, label)] = d
            print(f"{problem}: {label}: {method} vs CalculiX, largest difference "
                  f"{d:.3e} of max |CalculiX| = {scale:.6g} over {len(rx)} points")
        curves.append(entry)
    for method, folder in runs.items():
        with open(os.path.join(folder, "summary.json")) as f:
            summary = json.load(f)
        counts, times = summary["counts"], summary["time_s"]
        hist = read_csv(os.path.join(folder, "history.csv"))[1:]
        its = [int(float(h["newton_iterations"])) for h in hist]
        parts = times.get("newton_parts", {})
        print(f"{problem} ({method}): {counts['nodes']} nodes, {counts['domain_points']} "
              f"integration points, {counts['increments']} increments, Newton iterations "
              f"{sum(its)} (mean {sum(its) / max(len(its), 1):.2f}, most {max(its, default=0)}), "
              f"{counts['cutbacks']} cut-backs; wall time {times['total']:.2f} s: model "
              f"{sum(times.get(k, 0.0) for k in ('nodes', 'quadrature', 'neighbours', 'shape_functions')):.2f}, "
              f"first yield {times.get('elastic_limit', 0.0):.2f}, Newton {times.get('newton', 0.0):.2f} "
              f"(residual {parts.get('residual_and_return_mapping', 0.0):.2f}, Jacobian "
              f"{parts.get('jacobian_assembly', 0.0):.2f}, linear solves "
              f"{parts.get('linear_solves_and_other', 0.0):.2f}), output "
              f"{times.get('increment_output', 0.0) + times.get('output', 0.0):.2f}")
    if len(runs) == 2:
        for label, hist_col, ref_col in spec["responses"]:
            a = read_csv(os.path.join(runs["meshfree"], "history.csv"))
            b = read_csv(os.path.join(runs["fem"], "history.csv"))
            bx = [float(h[hist_control]) for h in b]
            by = [float(h[hist_col]) for h in b]
            scale = max(abs(y) for y in by) or 1.0
            d = 0.0
            for h in a:
                other = interpolate(bx, by, float(h[hist_control]))
                if other is not None:
                    d = max(d, abs(float(h[hist_col]) - other) / scale)
            print(f"{problem}: {label}: meshfree vs in-code FE, largest difference {d:.3e}")
    for line, increment, ref_file in spec.get("lines", []):
        ref_line = read_csv(os.path.join(reference_dir(problem), ref_file))
        for method, folder in runs.items():
            ours = [r for r in read_csv(os.path.join(folder, f"line_{line}.csv"))
                    if int(float(r["increment"])) == increment]
            if len(ours) != len(ref_line):
                raise SystemExit(f"{problem} ({method}): line {line} has {len(ours)} points at "
                                 f"increment {increment}, the reference {len(ref_line)}")
            for comp in ("ux", "uy"):
                scale = max(abs(float(r[comp])) for r in ref_line)
                d = max(abs(float(a[comp]) - float(b[comp])) for a, b in zip(ours, ref_line))
                worst[(method, f"{comp} along {line} ({ref_file})")] = d / scale
                print(f"{problem}: {comp} along the {line} line at increment {increment}: {method} "
                      f"vs CalculiX, largest difference {d / scale:.3e} of max |CalculiX| = "
                      f"{scale:.6g}")
    if spec.get("elastic_limit"):
        levels = read_csv(os.path.join(reference_dir(problem),
                                       "elastic_limit.csv"))
        expected = float(levels[-1]["first_yield_factor_node"])
        for method, folder in runs.items():
            with open(os.path.join(folder, "summary.json")) as f:
                got = json.load(f)["results"]["elastic_limit"]["factors"][spec["driver"]]
            d = abs(got - expected) / expected
            worst[(method, "first yield")] = d
            print(f"{problem}: first yield at {ref_control} = {got:.6g} ({method}) against "
                  f"{expected:.6g} (CalculiX, finest level): difference {d:.3e}")
    plot(problem, control_label, curves, out_dir)
    return worst


def plot(problem, control_label, curves, out_dir):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is missing: no plot")
        return
    fig, axes = plt.subplots(1, len(curves), figsize=(6.4 * len(curves), 4.8), squeeze=False)
    styles = {"meshfree": ("C0", "-", "meshfree (RK Galerkin)"), "fem": ("C2", "--", "in-code FE")}
    for ax, c in zip(axes[0], curves):
        rx, ry = c["reference"]
        ax.plot(rx, ry, "ko", ms=4, mfc="none", label="CalculiX (converged)")
        for method, (hx, hy) in c["runs"].items():
            color, line, name = styles[method]
            ax.plot(hx, hy, color=color, ls=line, label=name)
        ax.set_xlabel(control_label)
        ax.set_ylabel(c["label"])
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.suptitle(problem)
    fig.tight_layout()
    path = os.path.join(out_dir, problem + ".png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print("plot:", path)


def tolerance(problem, label, check, check_first_yield):
    """The largest difference allowed for one compared quantity: `check_first_yield` for the
    first-yield load, else `check`, tightened to the problem's own check where it has one; None
    where nothing is checked."""
    if label == "first yield":
        return check_first_yield
    if check is not None and "check" in PROBLEMS[problem]:
        return min(check, PROBLEMS[problem]["check"])
    return check


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("problems", nargs="*", help="problem names (default: all)")
    ap.add_argument("--meshfree", default=os.path.join(ROOT, "build", "meshfree"),
                    help="the meshfree executable")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "compare"), help="output folder")
    ap.add_argument("--meshfree-dir", help="a finished meshfree run (one problem only)")
    ap.add_argument("--fem-dir", help="a finished finite-element run (one problem only)")
    ap.add_argument("--methods", default="meshfree,fem", help="which discretisations to run")
    ap.add_argument("--check", type=float, default=None,
                    help="fail if any curve differs from CalculiX by more than this fraction")
    ap.add_argument("--check-first-yield", type=float, default=None,
                    help="fail if a first-yield load differs from CalculiX by more than this")
    ap.add_argument("--list", action="store_true", help="print the problems it compares and stop")
    args = ap.parse_args()
    if args.list:
        print("\n".join(PROBLEMS))
        return
    problems = args.problems or list(PROBLEMS)
    unknown = [p for p in problems if p not in PROBLEMS]
    if unknown:
        raise SystemExit(f"unknown problem(s) {unknown}; known: {list(PROBLEMS)}")
    if (args.meshfree_dir or args.fem_dir) and len(problems) != 1:
        raise SystemExit("--meshfree-dir and --fem-dir need exactly one problem")
    os.makedirs(args.out, exist_ok=True)
    failed = []
    for p in problems:
        runs = {}
        for method in args.methods.split(","):
            given = args.meshfree_dir if method == "meshfree" else args.fem_dir
            runs[method] = given or run(p, method, args.out, args.meshfree)
        for (method, label), d in compare(p, runs, args.out).items():
            limit = tolerance(p, label, args.check, args.check_first_yield)
            if limit is not None and not d <= limit:
                failed.append(f"{p} {method} {label}: {d:.3e} > {limit}")
    if failed:
        print("FAILED:\n  " + "\n  ".join(failed))
        sys.exit(1)


if __name__ == "__main__":
    main()
