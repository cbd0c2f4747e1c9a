#!/usr/bin/python3
"""SPH throughput of two builds of meshfree, measured side by side (interleaved runs, ratios).

LAMMPS has no counterpart here: its SPH and SMD packages are missing from Debian's build
(reference/lammps/README.md, "Installed packages"), so the reference is an older meshfree binary
(--old), run on the same problems, alternating with the new one so that both see the same load.

Two parts:
  problems  Sod's tube (problems/sph_sod_tube.yaml) and tunnel case 1
            (problems/sph_tunnel_blast.yaml) over --fraction of their end time on one thread:
            particle-steps/s, neighbour-list builds and the neighbour search's share of the run;
            the new binary with its default sums (each pair once) and with
            discretisation.deterministic (every row summed whole in global-id order).
  blocks    2D gas blocks of 10^4 .. 10^6 particles (a blast tube in a plane: p = 1 | 0.1 at rho = 1),
            either at one spacing ("uniform") or with the right half 8 times coarser ("h 8:1",
            smoothing lengths varying 8:1), at 1 and 2 threads, and the new binary on 2 MPI
            ranks x 1 thread (--ranks): particle-steps/s and interacting pair evaluations per
            second per core (pairs within 2 h_ij counted on the initial
            lattice, two rate evaluations per step), bytes per pair of the neighbour list, and the
            growth exponent of the run time with the particle count. The old binary's search
            holds every pair within the largest reach; it is left out of blocks where that list
            would pass --old-pair-limit entries.

    scripts/sph_benchmark.py --old OLD/meshfree --new build/meshfree --out out/sph_benchmark
"""
import argparse
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

ROOT = Path(__file__).resolve().parent.parent


def run(binary, problem, out, threads, sets, ranks=1):
    args = [str(binary), "run", str(problem), "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMP_WAIT_POLICY="passive")
    if ranks > 1:
        args = ["mpirun", "-n", str(ranks), "--oversubscribe"] + args
        if os.geteuid() == 0:  # containers run as root; OpenMPI refuses that unless told
            env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run(args, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        sys.exit(f"{binary} {problem} failed:\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}")
    with open(Path(out) / "summary.json") as f:
        s = json.load(f)
    steps = s["counts"]["steps"]
    particles = s["counts"]["particles"]
    stepping = s["time_s"]["stepping"]
    nb = s.get("neighbour_search", {})
    return {"steps": steps, "particles": particles, "stepping_s": stepping,
            "rate": particles * steps / stepping, "builds": s["counts"]["neighbour_list_builds"],
            "share": nb.get("share_of_run"), "listed_pairs": nb.get("listed_pairs"),
            "list_bytes": nb.get("list_bytes")}


def best(runs):
    """The fastest of repeated runs (the one least disturbed by other work)."""
    return max(runs, key=lambda r: r["rate"])


def end_time(problem):
    text = Path(problem).read_text()
    import re
    return float(re.search(r"^time:\s*\{end:\s*([^,}]+)", text, re.M).group(1))


def block_problem(path, n, ratio):
    """A 2D gas block of about n particles: x in [-1, 1] with p = 1 on the left and 0.1 on the
    right, rho 1 on both; the right half's spacing is `ratio` times the left's."""
    # Left half at spacing s, right half at ratio s: n = (W / s)(1/s + 1/(ratio s)) for height W.
    width = 0.5
    s = math.sqrt(width * (1.0 + 1.0 / ratio ** 2) / n)
    left_n, right_n = round(1.0 / s), round(1.0 / (ratio * s))
    s, sr = 1.0 / left_n, 1.0 / right_n
    text = f"""name: sph_block
description: 2D gas block for the SPH benchmark
units: dimensionless
analysis: sph
model: {{type: plane_strain}}
discretisation: {{smoothing: 1.5}}
materials:
  - {{name: gas, eos: {{type: ideal_gas, gamma: 1.4}}}}
regions:
  - {{material: gas, box: [[-1.0, 0.0], [0.0, {width}]], spacing: {s:.10g}, density: 1.0, pressure: 1.0}}
  - {{material: gas, box: [[0.0, 0.0], [1.0, {width}]], spacing: {sr:.10g}, density: 1.0, pressure: 0.1}}
time: {{end: 1.0, courant: 0.3}}
output:
  history_interval: 1.0
  fields_interval: 100.0
"""
    Path(path).write_text(text)
    # The lattice as meshfree fills a box (cell centres), to count the interacting pairs.
    pts, hs = [], []
    for x0, x1, sp in ((-1.0, 0.0, s), (0.0, 1.0, sr)):
        nx, ny = round((x1 - x0) / sp), round(width / sp)
        gx, gy = np.meshgrid(x0 + (np.arange(nx) + 0.5) * sp, (np.arange(ny) + 0.5) * sp)
        pts.append(np.column_stack([gx.ravel(), gy.ravel()]))
        hs.append(np.full(nx * ny, 1.5 * sp))
    x, h = np.vstack(pts), np.concatenate(hs)
    return x, h, s


def pair_counts(x, h, scale):
    """Directed pairs with |x_i - x_j| < scale (h_i + h_j), and those the old binary's search
    examines: every pair within the largest such reach. Counted without listing them (dual-tree
    counts per pair of smoothing lengths; the blocks have one or two), so 10^6 points fit."""
    classes = {v: cKDTree(x[h == v]) for v in np.unique(h)}
    live = 0
    for a, ta in classes.items():
        for b, tb in classes.items():
            live += int(ta.count_neighbors(tb, scale * (a + b) * (1.0 - 1e-12)))
    live -= len(h)  # each point with itself
    whole = cKDTree(x)
    examined = int(whole.count_neighbors(whole, scale * 2.0 * h.max())) - len(h)
    return live, examined


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--old", required=True, help="the reference meshfree binary")
    ap.add_argument("--new", default=str(ROOT / "build" / "meshfree"))
    ap.add_argument("--out", default="out/sph_benchmark")
    ap.add_argument("--fraction", type=float, default=0.05, help="of the problems' end time")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--sizes", default="1e4,1e5,1e6")
    ap.add_argument("--steps", type=int, default=10, help="steps per block run")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--ranks", default="2",
                    help="MPI ranks x 1 thread for the new binary (at least 2; '' for none)")
    ap.add_argument("--old-pair-limit", type=float, default=3e8)
    ap.add_argument("--skip-problems", action="store_true")
    ap.add_argument("--skip-blocks", action="store_true")
    args = ap.parse_args()

    def counts(key, text, least, allow_empty=False):
        """A comma-separated list of whole numbers (1e4 too) of at least `least`, or exit 2."""
        try:
            values = [int(float(v)) for v in text.split(",") if v.strip()]
        except ValueError:
            values = []
        if (not values and not allow_empty) or any(v < least for v in values):
            ap.error(f"{key}: {text!r} is not a list of whole numbers of at least {least}")
        return values

    threads = counts("--threads", args.threads, 1)
    sizes = counts("--sizes", args.sizes, 100)
    rank_counts = counts("--ranks", args.ranks, 2, allow_empty=True)
    if args.repeats < 1 or not 0.0 < args.fraction <= 1.0 or args.steps < 1:
        ap.error(f"--repeats {args.repeats}, --fraction {args.fraction}, --steps {args.steps}: "
                 "need at least 1 repeat, a fraction in (0, 1] and at least 1 step")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    lines = []

    if not args.skip_problems:
        lines += ["## Problems (1 thread, best of %d interleaved runs each)" % args.repeats, "",
                  "| problem | binary | particles | steps | particle-steps/s | builds | "
                  "neighbour share | speed-up |", "|---|---|---|---|---|---|---|---|"]
        for name in ("sph_sod_tube", "sph_tunnel_blast"):
            problem = ROOT / "problems" / f"{name}.yaml"
            sets = [f"time.end={args.fraction * end_time(problem):.6g}"]
            # The new binary twice: its default (each pair once) and with the rows summed whole
            # in global-id order (discretisation.deterministic).
            sides = (("old", args.old, []), ("new", args.new, []),
                     ("new, deterministic", args.new, ["discretisation.deterministic=true"]))
            res = {side: [] for side, _, _ in sides}
            for _ in range(args.repeats):
                for k, (side, binary, more) in enumerate(sides):
                    res[side].append(run(binary, problem, out / f"{name}_{k}", 1, sets + more))
            o = best(res["old"])
            for side, _, _ in sides:
                r = best(res[side])
                share = "-" if r["share"] is None else f"{100 * r['share']:.1f}%"
                lines.append(f"| {name} | {side} | {r['particles']} | {r['steps']} | "
                             f"{r['rate']:.4g} | {r['builds']} | {share} | "
                             f"{r['rate'] / o['rate']:.2f} |")
            print("\n".join(lines[-3:]), flush=True)
        lines.append("")

    if not args.skip_blocks:
        lines += ["## 2D gas blocks (best of %d interleaved runs, %d steps)" % (args.repeats,
                                                                              args.steps), "",
                  "| case | particles | threads | binary | particle-steps/s | pair evals/s "
                  "per core | listed pairs per particle | bytes per listed pair | bytes per "
                  "interacting pair | builds | neighbour share | speed-up |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        growth = {}
        for case, ratio in (("uniform", 1.0), ("h 8:1", 8.0)):
            for n in sizes:
                problem = out / f"block_{ratio:g}_{n}.yaml"
                x, h, s = block_problem(problem, n, ratio)
                live, old_examined = pair_counts(x, h, 1.0)
                # dt = 0.3 h_min / c_max, c = sqrt(1.4 p / rho) = 1.18 on the left.
                dt = 0.3 * 1.5 * s / math.sqrt(1.4)
                sets = [f"time.end={args.steps * dt:.6g}"]
                sides = [("new", args.new)]
                if 1.5 ** 2 * old_examined <= args.old_pair_limit:
                    sides.insert(0, ("old", args.old))
                one = None  # the new binary on 1 rank x 1 thread
                for t in threads:
                    res = {side: [] for side, _ in sides}
                    for _ in range(args.repeats):
                        for side, binary in sides:
                            res[side].append(run(binary, problem, out / f"block_{side}", t, sets))
                    ref = best(res["old"])["rate"] if "old" in res else None
                    for side, _ in sides:
                        r = best(res[side])
                        evals = live * 2 * r["steps"] / r["stepping_s"] / t
                        share = "-" if r["share"] is None else f"{100 * r['share']:.1f}%"
                        per_listed = (f"{r['listed_pairs'] / r['particles']:.1f}"
                                      if r["listed_pairs"] else "-")
                        bpl = (f"{r['list_bytes'] / r['listed_pairs']:.2f}"
                               if r["listed_pairs"] else "-")
                        bpi = f"{r['list_bytes'] / live:.2f}" if r["list_bytes"] else "-"
                        up = f"{r['rate'] / ref:.2f}" if ref else "-"
                        lines.append(f"| {case} | {r['particles']} | {t} | {side} | "
                                     f"{r['rate']:.4g} | {evals:.4g} | {per_listed} | {bpl} | "
                                     f"{bpi} | {r['builds']} | {share} | {up} |")
                        print(lines[-1], flush=True)
                        growth.setdefault((case, t, side), []).append(
                            (r["particles"], r["stepping_s"] / r["steps"]))
                    if "old" not in res:
                        lines.append(f"| {case} | {len(h)} | {t} | old | left out: its search "
                                     f"would list {1.5 ** 2 * old_examined:.3g} pairs | | | | | | | |")
                    if t == 1:
                        one = best(res["new"])
                # The new binary spread over MPI ranks, one thread each; the speed-up is against
                # its own one-rank, one-thread run.
                for ranks in rank_counts:
                    r = best([run(args.new, problem, out / "block_ranks", 1, sets, ranks)
                              for _ in range(args.repeats)])
                    evals = live * 2 * r["steps"] / r["stepping_s"] / ranks
                    up = f"{r['rate'] / one['rate']:.2f} (vs 1 x 1)" if one else "-"
                    lines.append(f"| {case} | {r['particles']} | {ranks} ranks x 1 | new | "
                                 f"{r['rate']:.4g} | {evals:.4g} | | | | {r['builds']} | | {up} |")
                    print(lines[-1], flush=True)
        lines += ["", "Growth of the time per step with the particle count, t ~ N^b "
                  "(least squares over the sizes run):", ""]
        for (case, t, side), pts in growth.items():
            if len(pts) >= 2:
                ln = np.log(np.array(pts))
                b = np.polyfit(ln[:, 0], ln[:, 1], 1)[0]
                lines.append(f"- {case}, {t} thread(s), {side}: b = {b:.3f}")
    (out / "table.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
