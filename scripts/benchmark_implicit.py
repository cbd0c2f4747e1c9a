#!/usr/bin/python3
"""How the implicit solves grow with size: the elastic plate (problems/plate_tension.yaml,
meshfree RK, penalty-clamped) and the elastoplastic perforated strip (problems/perforated_strip.yaml
on a uniform node spacing, loaded to v = 0.05 mm in 10 increments, past first yield) from about
10^4 DOFs up to --max-dofs, with the direct solver (MUMPS, up to --direct-max-dofs) and the
multigrid one (CG + GAMG with the rigid-body modes), on 1 rank x 2 threads and 2 ranks x 1
thread.

For every run it records the DOFs, the wall time of each phase (summary.json's time_s: the
model's set-up, assembly and solve of the elastic plate; for the strip the Newton loop split into
residuals with return mapping, Jacobian assembly, and linear solves), the kernel CPU seconds
(kernel_time_s: paging in memory, for the most part; of the assembly alone for the plate), the
linear iterations, the peak resident memory (largest rank, all ranks), and the machine's rate of
writing fresh
memory at 1 to 12 GiB (first_touch.csv). It writes runs.csv, the growth exponents
(slope of log time against log DOFs over the sizes from --fit-from DOFs up) in exponents.csv,
those between successive sizes in local_exponents.csv,
and a PNG of time and memory against DOFs. Times are wall times of one run each; the machine is
shared with nothing else only if you make it so.

    scripts/benchmark_implicit.py                       # the full study (about 20 minutes)
    scripts/benchmark_implicit.py --quick --out DIR     # a smoke run: 2 small sizes of each
    scripts/benchmark_implicit.py --cases box hex8 hex20 --layouts 1x2 --solvers multigrid
                                                        # the 3D study (about 12 minutes)

The 3D cases (model solid_3d, on the box of problems/patch_test_3d.yaml): `box`, meshfree RK,
and `hex8`, `hex20`, the same box in bricks (discretisation.method: fem), from 10^4 to 10^6
DOFs (--box-max-dofs, --brick-max-dofs). No run starts whose peak memory, predicted from the
case's last run, exceeds --max-memory-gb, or whose memory above the program's own baseline
exceeds --max-added-memory-gb; the prediction for the largest size left out is printed instead.
The prediction is the baseline (the peak of `meshfree check` on a small 3D problem: the program,
its libraries and MPI, 34 MiB on one machine and 113 MB on another) plus the last run's bytes per
DOF above it times the size, so that it does not depend on the machine's baseline. A case that
runs at fewer than two sizes has no growth to report, and is said to. For each 3D case on multigrid it prints, and writes in
criteria.csv, whether the CG iterations at the largest size are within 30% of those at the size
nearest 10^5 and whether the assembly grows no faster than N^1.15 from there (issue 31's
acceptance for 3D); --check-criteria exits 1 if either fails.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# The spacing for about `dofs` DOFs, a whole fraction of the body's sides, as in the earlier
# measurements (the node lattice fits the body at any spacing since geometry::generate_nodes
# takes round(L / h) intervals a side; before, a spacing that did not divide the sides left a
# row a sliver from the edge, on which CG + GAMG stalled). The unit plate holds (1/h + 1)^2
# nodes; the strip's quarter (10 x 18 minus a quarter disc of radius 5) about 160 / h^2.
CASES = {
    "plate": dict(problem="plate_tension.yaml", analysis="elastic",
                  spacing=lambda dofs: 1.0 / round(math.sqrt(dofs / 2.0) - 1.0),
                  sets=[]),
    "strip": dict(problem="perforated_strip.yaml", analysis="elastoplastic",
                  spacing=lambda dofs: 1.0 / round(math.sqrt(dofs / 320.0)),
                  sets=["discretisation.refinement=[]", "steps.0.load_factor=0.05",
                        "steps.0.increments=10", "output.gauges=[]"]),
}
# A 3D body (model solid_3d), not in the default cases: the box of problems/patch_test_3d.yaml
# (1 x 0.75 x 0.5, held on one face, the linear field's tractions on the others), meshfree RK with
# 2 x 2 x 2 Gauss points on cells 0.7 of the spacing, no VCI (a symmetric system, so CG);
# 0.375 / h^3 nodes of 3 DOFs.
BOX = dict(problem="patch_test_3d.yaml", analysis="elastic",
           spacing=lambda dofs: (1.125 / dofs) ** (1.0 / 3.0),
           sets=lambda h: ["discretisation.quadrature.correction=none",
                           f"discretisation.quadrature.cell_size={0.7 * h!r}"])


def brick_spacing(dofs, nodes_per_cell):
    """The spacing for about `dofs` DOFs of bricks on the box: a whole fraction 0.25 / k of
    its sides (1, 0.75, 0.5), with `nodes_per_cell` nodes per brick's worth of volume (1 for
    hex8; 4 for hex20: a corner and three edge midpoints)."""
    raw = (3 * 0.375 * nodes_per_cell / dofs) ** (1.0 / 3.0)
    return 0.25 / max(1, round(0.25 / raw))


def bricks(element, nodes_per_cell):
    """The box of BOX in 8-node (hex8: plane q4 extruded) or 20-node (hex20) bricks on a structured mesh
    of spacing h, 2 x 2 x 2 or 3 x 3 x 3 Gauss points per brick."""
    return dict(problem="patch_test_3d.yaml", analysis="elastic",
                spacing=lambda dofs: brick_spacing(dofs, nodes_per_cell),
                sets=lambda h: ["discretisation.method=fem", f"discretisation.fem.element={element}",
                                "discretisation.quadrature.correction=none"])


EXTRA_CASES = {"box": BOX, "hex8": bricks("hex8", 1), "hex20": bricks("hex20", 4)}
SOLID_3D = set(EXTRA_CASES)
# Issue 31's acceptance for 3D on multigrid: CG iterations at the largest size within this
# fraction of those near 10^5 DOFs, and the assembly's growth exponent at most this.
ITERATIONS_WITHIN = 0.30
ASSEMBLY_EXPONENT_MAX = 1.15
LAYOUTS = {"1x2": (1, 2), "2x1": (2, 1)}
SETUP = ("nodes", "quadrature", "neighbours", "shape_functions")


def run_case(binary, case, dofs, solver, layout, out):
    c = CASES.get(case) or EXTRA_CASES[case]
    ranks, threads = LAYOUTS[layout]
    folder = out / f"{case}_{solver}_{layout}_{int(dofs)}"
    cmd = [str(binary), "run", str(ROOT / "problems" / c["problem"]), "--out", str(folder),
           "--set", f"discretisation.spacing={c['spacing'](dofs)!r}",
           "--set", f"linear_solver.type={solver}"]
    sets = c["sets"](c["spacing"](dofs)) if callable(c["sets"]) else c["sets"]
    for s in sets:
        cmd += ["--set", s]
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    if ranks > 1:
        cmd = ["mpirun", "-n", str(ranks), "--oversubscribe"] + cmd
        if os.geteuid() == 0:  # containers run as root; OpenMPI refuses that unless told
            env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    print(f"{case} {solver} {layout}: about {dofs:.3g} DOFs ...", flush=True)
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        # A size the machine's memory refuses (exit 2) or a run that fails: reported, and the
        # study goes on with the sizes that run.
        reason = (p.stderr.strip().splitlines() or ["no message"])[-1]
        print(f"  not run (exit {p.returncode}): {reason}", flush=True)
        return None
    s = json.loads((folder / "summary.json").read_text())
    t = s["time_s"]
    row = dict(case=case, solver=solver, layout=layout, dofs=s["counts"]["dofs"],
               setup_s=sum(t.get(k, 0.0) for k in SETUP), total_s=t["total"],
               peak_bytes_largest_rank=s["memory"]["peak_bytes_largest_rank"],
               peak_bytes_all_ranks=s["memory"]["peak_bytes_all_ranks"])
    kernel = s.get("kernel_time_s", {})
    row["kernel_s"] = sum(kernel.values())
    if c["analysis"] == "elastic":
        row.update(assembly_s=t["assembly"], assembly_kernel_s=kernel.get("assembly", 0.0),
                   solve_s=t["solve"],
                   linear_iterations=s["solver"]["iterations"], newton_iterations=0)
    else:
        parts = t["newton_parts"]
        row.update(assembly_s=parts["residual_and_return_mapping"] + parts["jacobian_assembly"],
                   assembly_kernel_s=float("nan"),
                   solve_s=parts["linear_solves_and_other"],
                   linear_iterations=s["solver"]["linear_iterations"],
                   newton_iterations=s["counts"]["newton_iterations"])
    row["bytes_per_dof"] = row["peak_bytes_all_ranks"] / row["dofs"]
    # Iterations per linear solve: one per Newton iteration, or the elastic plate's one.
    solves = max(row["newton_iterations"], 1)
    row["iterations_per_solve"] = row["linear_iterations"] / solves
    print(f"  {row['dofs']} DOFs: set-up {row['setup_s']:.2f} s, assembly {row['assembly_s']:.2f} s, "
          f"solve {row['solve_s']:.2f} s ({row['iterations_per_solve']:.1f} iterations per solve), "
          f"total {row['total_s']:.2f} s (kernel CPU {row['kernel_s']:.2f} s), "
          f"peak {row['peak_bytes_all_ranks'] / 2**20:.0f} MiB "
          f"({row['bytes_per_dof']:.0f} bytes per DOF)", flush=True)
    return row


def slope(points):
    """Least-squares slope of log y against log x."""
    xs = [math.log(x) for x, _ in points]
    ys = [math.log(max(y, 1e-9)) for _, y in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else float("nan")


def exponents(rows, fit_from):
    out = []
    keys = sorted({(r["case"], r["solver"], r["layout"]) for r in rows})
    for case, solver, layout in keys:
        rs = sorted((r for r in rows if (r["case"], r["solver"], r["layout"]) == (case, solver, layout)),
                    key=lambda r: r["dofs"])
        fit = [r for r in rs if r["dofs"] >= fit_from]
        if len(fit) < 2:
            fit = rs[-2:]
        if len(fit) < 2:
            continue
        e = dict(case=case, solver=solver, layout=layout, dofs_from=fit[0]["dofs"], dofs_to=fit[-1]["dofs"])
        for name, column in (("setup", "setup_s"), ("assembly", "assembly_s"), ("solve", "solve_s"),
                             ("total", "total_s"), ("memory", "peak_bytes_all_ranks")):
            e[name] = slope([(r["dofs"], r[column]) for r in fit])
        e["assembly_less_kernel"] = slope([(r["dofs"], outside_kernel(r)) for r in fit])
        e["iterations_growth"] = fit[-1]["iterations_per_solve"] / max(fit[0]["iterations_per_solve"], 1e-9)
        out.append(e)
    return out


def outside_kernel(row):
    """The assembly's wall time less its kernel CPU time (paging in fresh memory, for the most
    part): what the exponent of the work itself is read from, where the machine pages in memory
    at a rate that falls with the amount a process touches (first_touch.csv)."""
    return row["assembly_s"] - row["assembly_kernel_s"]


def local_exponents(rows):
    """The exponents between successive sizes: where the growth of a phase departs from N."""
    out = []
    keys = sorted({(r["case"], r["solver"], r["layout"]) for r in rows})
    for case, solver, layout in keys:
        rs = sorted((r for r in rows if (r["case"], r["solver"], r["layout"]) == (case, solver, layout)),
                    key=lambda r: r["dofs"])
        for a, b in zip(rs, rs[1:]):
            e = dict(case=case, solver=solver, layout=layout, dofs_from=a["dofs"], dofs_to=b["dofs"])
            for name, f in (("assembly", lambda r: r["assembly_s"]),
                            ("assembly_less_kernel", outside_kernel),
                            ("solve", lambda r: r["solve_s"])):
                e[name] = slope([(a["dofs"], f(a)), (b["dofs"], f(b))])
            out.append(e)
    return out


def program_baseline(binary):
    """The peak resident memory of the program that holds no model of size: `meshfree check` on
    the small box of problems/patch_test_3d.yaml (the program, its libraries, MPI's start)."""
    p = subprocess.Popen([str(binary), "check", str(ROOT / "problems" / "patch_test_3d.yaml")],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    if p.returncode != 0:
        sys.exit(f"{binary} check on patch_test_3d.yaml exited {p.returncode}")
    return usage.ru_maxrss * 1024


def predicted_peak(rows, case, solver, layout, dofs, baseline):
    """The peak memory of a run of `dofs` DOFs: the program's baseline plus the bytes per DOF
    above it of the same case's largest run so far (they fall with size in every case measured,
    so this over-estimates), or None before its first run."""
    done = [r for r in rows if (r["case"], r["solver"], r["layout"]) == (case, solver, layout)]
    if not done:
        return None
    return baseline + max(done, key=lambda r: r["dofs"])["added_bytes_per_dof"] * dofs


def criteria(rows, reference_dofs=1e5):
    """Issue 31's acceptance for each 3D case on multigrid: the CG iterations at the largest
    size against those at the size nearest `reference_dofs` below it, and the assembly's growth
    exponent between the two (least squares over the sizes from one to the other)."""
    out = []
    keys = sorted({(r["case"], r["layout"]) for r in rows
                   if r["case"] in SOLID_3D and r["solver"] == "multigrid"})
    for case, layout in keys:
        rs = sorted((r for r in rows if (r["case"], r["solver"], r["layout"]) ==
                     (case, "multigrid", layout)), key=lambda r: r["dofs"])
        if len(rs) < 2:
            continue
        top = rs[-1]
        ref = min(rs[:-1], key=lambda r: abs(math.log(r["dofs"] / reference_dofs)))
        ratio = top["iterations_per_solve"] / ref["iterations_per_solve"]
        exponent = slope([(r["dofs"], r["assembly_s"]) for r in rs if r["dofs"] >= ref["dofs"]])
        out.append(dict(case=case, layout=layout, dofs_from=ref["dofs"], dofs_to=top["dofs"],
                        iterations_from=ref["iterations_per_solve"],
                        iterations_to=top["iterations_per_solve"], iterations_ratio=ratio,
                        iterations_ok=abs(ratio - 1.0) <= ITERATIONS_WITHIN,
                        assembly_exponent=exponent,
                        assembly_ok=exponent <= ASSEMBLY_EXPONENT_MAX,
                        bytes_per_dof_at_largest=top["bytes_per_dof"]))
    return out


def print_criteria(checks, skipped):
    print("\n3D on multigrid: iterations at the largest size against those near 10^5, and the "
          "assembly's exponent:")
    for c in checks:
        print(f"  {'PASS' if c['iterations_ok'] else 'FAIL'}: {c['case']} {c['layout']}: "
              f"{c['iterations_to']:.0f} CG iterations at {c['dofs_to']} DOFs, "
              f"{c['iterations_from']:.0f} at {c['dofs_from']} (x{c['iterations_ratio']:.2f}; "
              f"within {ITERATIONS_WITHIN:.0%})")
        print(f"  {'PASS' if c['assembly_ok'] else 'FAIL'}: {c['case']} {c['layout']}: assembly "
              f"~ N^{c['assembly_exponent']:.2f} from {c['dofs_from']} to {c['dofs_to']} DOFs "
              f"(at most {ASSEMBLY_EXPONENT_MAX}); {c['bytes_per_dof_at_largest']:.0f} bytes "
              f"per DOF at the largest")
    for k in skipped:
        print(f"  not run: {k['case']} {k['solver']} {k['layout']} at about {k['dofs']:.3g} DOFs: "
              f"predicted peak {k['predicted_peak_bytes'] / 1e9:.1f} GB "
              f"({k['bytes_per_dof']:.0f} bytes per DOF, measured at {k['measured_at_dofs']})")


def plot(rows, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no plot")
        return
    fig, axes = plt.subplots(1, 3, figsize=(16, 5))
    keys = sorted({(r["case"], r["solver"], r["layout"]) for r in rows})
    for case, solver, layout in keys:
        rs = sorted((r for r in rows if (r["case"], r["solver"], r["layout"]) == (case, solver, layout)),
                    key=lambda r: r["dofs"])
        n = [r["dofs"] for r in rs]
        label = f"{case}, {solver}, {layout}"
        style = "-" if solver == "multigrid" else "--"
        axes[0].loglog(n, [r["solve_s"] for r in rs], style, marker="o", label=label)
        axes[1].loglog(n, [r["assembly_s"] for r in rs], style, marker="o", label=label)
        axes[2].loglog(n, [r["peak_bytes_all_ranks"] / 2**30 for r in rs], style, marker="o", label=label)
    titles = ["linear solves [s]", "assembly (elastic) / residual + Jacobian (strip) [s]",
              "peak memory, all ranks [GiB]"]
    for ax, title in zip(axes, titles):
        ax.set_xlabel("DOFs")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"plot: {path}")


def write_csv(path, rows):
    """Writes `rows` (dicts of one set of keys); none: an empty file, which says so."""
    with open(path, "w", newline="") as f:
        if not rows:
            return
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


PROBE = """
import sys, time, numpy as np
n = int(float(sys.argv[1]) * 2**30) // 8
blocks, start = [], time.perf_counter()
for _ in range(n // 2**24):  # 128 MiB blocks, as an application's vectors come
    blocks.append(np.ones(2**24))
first = time.perf_counter() - start
start = time.perf_counter()
for b in blocks:
    b.fill(2.0)
print(first, time.perf_counter() - start)
"""


def first_touch_rates(sizes_gib):
    """GB/s of writing fresh memory (page faults and zeroing included) and of writing it again,
    in one new process per size: on virtual machines the first touch can be several times slower
    and slower still beyond some total, which the large runs' times then carry."""
    rows = []
    for gib in sizes_gib:
        p = subprocess.run([sys.executable, "-c", PROBE, str(gib)], capture_output=True, text=True)
        if p.returncode != 0:
            continue
        first, again = (float(v) for v in p.stdout.split())
        gb = gib * 2**30 / 1e9
        rows.append(dict(gib=gib, first_touch_gb_per_s=gb / first, rewrite_gb_per_s=gb / again))
        print(f"  {gib:g} GiB: first touch {gb / first:.2f} GB/s, again {gb / again:.2f} GB/s",
              flush=True)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshfree", default=str(ROOT / "build" / "meshfree"))
    ap.add_argument("--out", default=str(ROOT / "out" / "benchmark_implicit"))
    ap.add_argument("--max-dofs", type=float, default=2.6e6)
    ap.add_argument("--strip-max-dofs", type=float, default=1e5,
                    help="the strip's 10 increments of Newton take about 40 linear solves")
    ap.add_argument("--direct-max-dofs", type=float, default=3.2e5)
    ap.add_argument("--box-max-dofs", type=float, default=1e6,
                    help="the largest meshfree 3D box (case box: about 21 KB a DOF with "
                         "multigrid, so --max-memory-gb stops it first)")
    ap.add_argument("--brick-max-dofs", type=float, default=1e6,
                    help="the largest box of bricks (cases hex8, hex20)")
    ap.add_argument("--max-memory-gb", type=float, default=10.0,
                    help="no run whose peak memory, predicted from its case's last run, exceeds "
                         "this (the machine is shared)")
    ap.add_argument("--max-added-memory-gb", type=float, default=float("inf"),
                    help="no run whose predicted peak memory above the program's baseline "
                         "exceeds this (a cap that does not depend on the machine's baseline)")
    ap.add_argument("--solvers", nargs="+", default=["direct", "multigrid"],
                    choices=["direct", "multigrid"])
    ap.add_argument("--check-criteria", action="store_true",
                    help="exit 1 if a 3D case on multigrid misses its iterations or assembly "
                         "criterion")
    ap.add_argument("--fit-from", type=float, default=1e5, help="smallest DOFs in the exponents' fit")
    ap.add_argument("--layouts", nargs="+", default=list(LAYOUTS), choices=list(LAYOUTS))
    ap.add_argument("--cases", nargs="+", default=list(CASES),
                    choices=list(CASES) + list(EXTRA_CASES))
    ap.add_argument("--quick", action="store_true", help="2 small sizes of each, for a smoke test")
    ap.add_argument("--first-touch", type=float, nargs="*", default=[1, 4, 8, 12],
                    help="GiB written by the memory probe (none: no probe)")
    ap.add_argument("--max-iterations-growth", type=float, default=None,
                    help="exit 1 if the multigrid's iterations per solve grow by more than this "
                         "factor from the smallest to the largest size")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    sizes = [4e3, 1e4] if args.quick else [1e4, 4e4, 1e5, 2e5, 4e5, 1e6, 2.5e6]
    rows, skipped = [], []
    baseline = program_baseline(args.meshfree)
    print(f"the program's baseline: peak {baseline / 2**20:.0f} MiB", flush=True)
    tops = {"plate": args.max_dofs, "box": args.box_max_dofs, "hex8": args.brick_max_dofs,
            "hex20": args.brick_max_dofs}
    for case in args.cases:
        top = tops.get(case, args.strip_max_dofs)
        for solver in args.solvers:
            for layout in args.layouts:
                for dofs in sizes:
                    if dofs > top or (solver == "direct" and dofs > args.direct_max_dofs):
                        continue
                    guess = predicted_peak(rows, case, solver, layout, dofs, baseline)
                    if guess is not None and (guess > args.max_memory_gb * 1e9 or
                                              guess - baseline > args.max_added_memory_gb * 1e9):
                        measured = max((r for r in rows if (r["case"], r["solver"], r["layout"])
                                        == (case, solver, layout)), key=lambda r: r["dofs"])
                        print(f"{case} {solver} {layout}: about {dofs:.3g} DOFs not run: predicted "
                              f"peak {guess / 1e9:.3f} GB, {(guess - baseline) / 1e9:.3f} GB above "
                              f"the baseline (caps: --max-memory-gb {args.max_memory_gb:g}, "
                              f"--max-added-memory-gb {args.max_added_memory_gb:g})", flush=True)
                        skipped.append(dict(case=case, solver=solver, layout=layout, dofs=dofs,
                                            predicted_peak_bytes=guess, baseline_bytes=baseline,
                                            added_bytes_per_dof=(guess - baseline) / dofs,
                                            bytes_per_dof=guess / dofs,
                                            measured_at_dofs=measured["dofs"]))
                        continue
                    row = run_case(args.meshfree, case, dofs, solver, layout, out)
                    if row:
                        row["added_bytes_per_dof"] = (row["peak_bytes_all_ranks"] -
                                                      baseline * LAYOUTS[layout][0]) / row["dofs"]
                        rows.append(row)
    write_csv(out / "runs.csv", rows)
    if skipped:
        write_csv(out / "predicted.csv", skipped)
    if not args.quick and args.first_touch:
        print("\nthis machine's memory (what the largest runs' assembly and set-up pay per byte):")
        write_csv(out / "first_touch.csv", first_touch_rates(args.first_touch))
    fits = exponents(rows, 0 if args.quick else args.fit_from)
    for key in sorted({(r["case"], r["solver"], r["layout"]) for r in rows}):
        if sum((r["case"], r["solver"], r["layout"]) == key for r in rows) < 2:
            print(f"{' '.join(key)}: ran at one size only (the others were left out or failed): "
                  "no growth exponent or criterion for it", flush=True)
    write_csv(out / "exponents.csv", fits)
    write_csv(out / "local_exponents.csv", local_exponents(rows))
    print("\ngrowth exponents (time ~ DOFs^e) and iterations per solve, largest over smallest size:")
    for e in fits:
        print(f"  {e['case']:5s} {e['solver']:9s} {e['layout']}: DOFs {e['dofs_from']}..{e['dofs_to']}: "
              f"set-up {e['setup']:.2f}, assembly {e['assembly']:.2f}"
              + ("" if math.isnan(e["assembly_less_kernel"]) else
                 f" ({e['assembly_less_kernel']:.2f} less its kernel time)")
              + f", solve {e['solve']:.2f}, "
              f"total {e['total']:.2f}, memory {e['memory']:.2f}; iterations x{e['iterations_growth']:.2f}")
    plot(rows, out / "benchmark_implicit.png")
    checks = criteria(rows)
    if checks or skipped:
        print_criteria(checks, skipped)
    write_csv(out / "criteria.csv", checks)
    if args.check_criteria and not all(c["iterations_ok"] and c["assembly_ok"] for c in checks):
        sys.exit(1)
    if args.max_iterations_growth is not None:
        grown = [e for e in fits if e["solver"] == "multigrid"
                 and not e["iterations_growth"] <= args.max_iterations_growth]
        for e in grown:
            print(f"FAIL: {e['case']} {e['layout']}: multigrid iterations per solve grew "
                  f"x{e['iterations_growth']:.2f} > {args.max_iterations_growth}")
        sys.exit(1 if grown else 0)


if __name__ == "__main__":
    main()
