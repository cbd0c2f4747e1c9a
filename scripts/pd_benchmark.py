#!/usr/bin/python3
"""Cost of the peridynamic bond loop against problem size and threads, meshfree and LAMMPS side
by side on the same n^3 simple-cubic lattices (spacing a = 0.5 mm, horizon 3.0002 a, s00 = 0.0005,
alpha = 0.25, rho = 2200, linear partial volumes - the LAMMPS rule -, dt = 1e-8 s, free body),
for the bond-based PMB against LAMMPS peri/pmb (c = 1.6863e22) and/or the state-based linear
peridynamic solid (LPS, influence 1/|xi|) against peri/lps (K = 25 GPa, G = 11.538 GPa: E = 30
GPa, nu = 0.3, the moduli of reference/lammps/lps_lattice). The runs are interleaved: for each
lattice and repeat, meshfree with k threads then LAMMPS with k MPI ranks (Debian's LAMMPS has no
OpenMP package), model after model with --model both, so that a machine shared with other jobs
slows all alike. The fastest repeat is kept. No bond may break (meshfree's max_damage and
LAMMPS's damage at the last step must be 0); the LAMMPS LPS deck runs 'run 0' first, since
peri/lps's first force evaluation leaves s0 uninitialised and would break every stretched bond
in step 1 (reference/lammps/README.md, L7).

Bond evaluations are counted as directed bonds x steps / seconds: LAMMPS's 'total # of bonds'
counts each bond at both ends, and so does meshfree's count (summary.json
results.bond_evaluations_per_second). meshfree's default (half) bond layout evaluates each pair
once and applies the force to both ends (Newton's third law), so one pair evaluation counts as
two bond evaluations, as LAMMPS's full neighbour list evaluates it twice. meshfree's rate is
over the whole step (velocity Verlet, forces, breaking); LAMMPS's is given over its loop time
(the whole step) and over its pair time (bond forces and short-range contact), both of the timed
run. Bytes per bond: meshfree's results.bond_bytes_per_bond (steady and at the peak while
building), LAMMPS's largest 'Per MPI rank memory allocation' of the log over its bonds.

    scripts/pd_benchmark.py [--model pmb|lps|both] [--sizes 22 43 65 100] [--threads 1 2]
                            [--repeats 2] [--out DIR] [--baseline OTHER/meshfree]

--baseline runs a second build of meshfree (an older one, say) right after each meshfree run,
in the same interleaving, and reports its rate beside: old and new measured in one session.

Writes benchmark.csv (PMB) and/or benchmark_lps.csv (LPS) in --out and prints the table with the
ratios, the growth exponent of the step time with the bond count (1 for a loop linear in the
bonds) and the two-thread speed-ups.
"""
import argparse
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts" / "pd_reference"))
import make_lammps_reference as lref  # noqa: E402  (the LAMMPS deck and lattice of the reference)
import make_lammps_lps_reference as lpsref  # noqa: E402  (K and G of the LAMMPS LPS reference)

SPACING = 0.0005
DT = 1e-8
# Directed bond evaluations per run: steps = EVALUATIONS / (particles x 120), at least 5.
EVALUATIONS = 2.4e8
# E with c = 12 E / (pi delta^4) (Silling & Askari 2005), for the report only: c is given.
YOUNG = 1.6863e22 * np.pi * (3.0002 * SPACING) ** 4 / 12
MODELS = ("pmb", "lps")
# What differs between the models: the names of their files (PMB's are those of the script
# before it measured LPS), meshfree's material and the LAMMPS deck's pair lines.
TAG = {"pmb": "", "lps": "lps_"}
CSV = {"pmb": "benchmark.csv", "lps": "benchmark_lps.csv"}
BOND = f"critical_stretch: {lref.S00_STR}, alpha: {lref.ALPHA_STR}"
MATERIAL = {
    "pmb": f"E: {YOUNG:.6e}, density: {lref.RHO_STR}, bond: {{micromodulus: {lref.C_STR}, {BOND}}}",
    "lps": f"bulk_modulus: {lpsref.K_STR}, shear_modulus: {lpsref.G_STR}, density: {lref.RHO_STR}, "
           f"bond: {{law: lps, {BOND}}}",
}
# make_lammps_reference.deck writes the peri/pmb benchmark deck; these edits make it peri/lps's,
# with its 'run 0' guard before the timed run (see the module's docstring).
LPS_DECK = [("PMB bond-based", "LPS state-based"), ("peri/pmb", "peri/lps"),
            ("# c [N/m^6], delta [m]", "# K [Pa], G [Pa], delta [m]"),
            (f"* * {lref.C_STR} ", f"* * {lpsref.K_STR} {lpsref.G_STR} ")]
LPS_GUARD = ("# the first force evaluation (before the bond family exists) leaves s0 uninitialised:\n"
             "# without this 'run 0' every bond with a positive stretch breaks in step 1\n"
             "run             0\n")
MEMORY = r"Per MPI rank memory allocation \(min/avg/max\) = \S+ \| (\S+) \| \S+ Mbytes"

PROBLEM = """name: pd_benchmark_{tag}{n}
description: free {n}^3 {label} lattice, the LAMMPS benchmark lattice, {steps} steps
units: N, m, kg, s
analysis: peridynamics
model: {{type: solid_3d}}
materials:
  - {{name: glass, {material}}}
geometry:
  box: {{origin: [0, 0, 0], size: [{L}, {L}, {L}]}}
discretisation: {{spacing: {a}, horizon: 3.0002, volume_correction: linear}}
regions:
  - {{box: [[0, 0, 0], [{half}, {L}, {L}]], velocity: [0.01, 0, 0]}}
time: {{end: {end}, dt: {dt}}}
output: {{history_interval: {end}, fields_interval: {end}}}
"""


def write_problem(out, model, n, steps):
    L = n * SPACING
    problem = out / f"lattice_{TAG[model]}{n}.yaml"
    problem.write_text(PROBLEM.format(tag=TAG[model], n=n, label=model.upper(), steps=steps,
                                      material=MATERIAL[model], L=L, a=SPACING, half=L / 2,
                                      end=steps * DT, dt=DT))
    return problem


def lammps_deck(model, data, n, steps):
    text = lref.deck(data, lref.DT_STR, steps, lref.S00_STR, 0, steps, f"benchmark {n}^3", bench=True)
    if model == "lps":
        last = f"run             {steps}\n"
        for old, new in LPS_DECK + [(last, LPS_GUARD + last)]:
            if old not in text:
                raise SystemExit(f"make_lammps_reference.deck has changed: no {old!r} in its deck")
            text = text.replace(old, new)
    return text


def run_once(exe, problem, out_dir, threads):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMP_PROC_BIND="false")
    subprocess.run([exe, "run", str(problem), "--out", str(out_dir)], check=True, env=env,
                   stdout=subprocess.DEVNULL)
    s = json.loads((out_dir / "summary.json").read_text())
    if s["results"]["broken_bonds"] or s["results"]["max_damage"]:
        raise SystemExit(f"{problem}: {s['results']['broken_bonds']} bonds broke in {exe}")
    return s


def run_lammps(lmp, workdir, model, n, steps, ranks):
    """LAMMPS peri/pmb or peri/lps on the n^3 reference lattice: (bonds, loop s, pair s, bytes
    per bond)."""
    data = workdir / f"data.bench{n}"
    if not data.exists():
        lref.write_data(data, lref.make_lattice(n))
    deck = workdir / f"bench{TAG[model]}{n}_{steps}.in"
    deck.write_text(lammps_deck(model, data.name, n, steps))
    prefix = []
    if ranks > 1:
        prefix = [shutil.which("mpirun"), "-np", str(ranks), "--oversubscribe"]
        if os.geteuid() == 0:
            prefix.append("--allow-run-as-root")
    text, _ = lref.run_lmp(lmp, workdir, deck.name, prefix=prefix)
    timed = re.split(r"^run\s", text, flags=re.M)[-1]    # the log after the last 'run' command
    p = lref.parse_log(timed)
    bonds = lref.parse_log(text)["bonds"]                # printed at the first run's setup
    last = [line.split() for line in timed.splitlines() if re.match(rf"\s+{steps}\s", line)]
    if not last or float(last[-1][-1]) != 0:             # thermo's last column: max damage
        raise SystemExit(f"{deck.name}: LAMMPS's damage at step {steps} is not 0: {last}")
    mem = [float(m) for m in re.findall(MEMORY, text)]
    mem = max(mem) * 2 ** 20 * ranks if mem else float("nan")
    return bonds, p["loop"], p["pair"], mem / bonds


def measure(args, lmp, tmp, out, model, n, steps, threads, problem, best):
    """One repeat of one model: meshfree, the baseline, LAMMPS; the fastest kept in best."""
    s = run_once(args.meshfree, problem, out / f"run_{TAG[model]}{n}_{threads}", threads)
    rate = s["results"]["bond_evaluations_per_second"]
    if "meshfree" not in best or rate > best["meshfree"][0]:
        best["meshfree"] = (rate, s)
    if args.baseline:
        b = run_once(args.baseline, problem, out / f"baseline_{TAG[model]}{n}_{threads}", threads)
        best["baseline"] = max(best.get("baseline", 0.0), b["results"]["bond_evaluations_per_second"])
    if lmp:
        lb = run_lammps(lmp, tmp, model, n, steps, threads)
        if "lammps" not in best or lb[1] < best["lammps"][1]:
            best["lammps"] = lb


def table_row(model, n, threads, best):
    rate, s = best["meshfree"]
    bbest, lbest = best.get("baseline"), best.get("lammps")
    bonds = 2 * s["counts"]["bonds"]
    steps = s["counts"]["steps"]
    by = s["results"]["bond_bytes_per_bond"]
    row = {"particles": s["counts"]["particles"], "bonds": bonds, "steps": steps,
           "threads": threads, "step_seconds": bonds * steps / rate,
           "bond_evaluations_per_second": rate, "per_core": rate / threads,
           "bytes_steady": by["steady"], "bytes_peak": by["peak"]}
    if bbest:
        row["baseline_rate"] = bbest
        row["ratio_baseline"] = rate / bbest
    if lbest:
        if lbest[0] != bonds:
            raise SystemExit(f"{model} {n}^3: meshfree has {bonds} bonds, LAMMPS {lbest[0]}")
        row["lammps_loop_rate"] = bonds * steps / lbest[1]
        row["lammps_pair_rate"] = bonds * steps / lbest[2]
        row["lammps_bytes"] = lbest[3]
        row["ratio_loop"] = rate / row["lammps_loop_rate"]
        row["ratio_pair"] = rate / row["lammps_pair_rate"]
        if bbest:
            row["baseline_ratio_loop"] = bbest / row["lammps_loop_rate"]
    lmp_text = (f" | LAMMPS loop {row['lammps_loop_rate']:.3g}/s, pair {row['lammps_pair_rate']:.3g}/s,"
                f" {row['lammps_bytes']:.1f} B/bond -> ratio loop {row['ratio_loop']:.2f},"
                f" pair {row['ratio_pair']:.2f}") if lbest else ""
    base_text = (f" | baseline {bbest:.3g}/s (new / baseline {rate / bbest:.2f}"
                 + (f", baseline / LAMMPS loop {row['baseline_ratio_loop']:.2f}" if lbest else "")
                 + ")") if bbest else ""
    print(f"{model.upper()} {row['particles']:7d} particles, {bonds:9d} bonds, {threads} thread(s), "
          f"{steps} steps: {rate:.3g} bond evaluations/s ({rate / threads:.3g} per core), "
          f"{by['steady']:.2f} B/bond steady, {by['peak']:.2f} peak{lmp_text}{base_text}", flush=True)
    return row


def report(model, rows, threads_list, path):
    fields = ["particles", "bonds", "steps", "threads", "step_seconds", "bond_evaluations_per_second",
              "per_core", "bytes_steady", "bytes_peak", "lammps_loop_rate", "lammps_pair_rate",
              "lammps_bytes", "ratio_loop", "ratio_pair", "baseline_rate", "ratio_baseline",
              "baseline_ratio_loop"]
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)
    for threads in threads_list:
        sel = [r for r in rows if r["threads"] == threads]
        if len(sel) > 1:
            per_bond = [r["step_seconds"] / r["steps"] for r in sel]
            slope = np.polyfit(np.log([r["bonds"] for r in sel]), np.log(per_bond), 1)[0]
            print(f"{model.upper()} {threads} thread(s): step time grows as bonds^{slope:.2f}")
    one = {r["particles"]: r for r in rows if r["threads"] == 1}
    for r in rows:
        if r["threads"] > 1 and r["particles"] in one:
            print(f"{model.upper()} {r['particles']} particles: {r['threads']} threads "
                  f"{r['bond_evaluations_per_second'] / one[r['particles']]['bond_evaluations_per_second']:.2f}x one"
                  + (f" (baseline {r['baseline_rate'] / one[r['particles']]['baseline_rate']:.2f}x)"
                     if "baseline_rate" in r and "baseline_rate" in one[r["particles"]] else ""))
    print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshfree", default=str(ROOT / "build" / "meshfree"))
    ap.add_argument("--model", choices=MODELS + ("both",), default="pmb",
                    help="PMB against peri/pmb (benchmark.csv), LPS against peri/lps "
                         "(benchmark_lps.csv), or both interleaved (default pmb)")
    ap.add_argument("--sizes", type=int, nargs="+", default=[22, 43, 65, 100])
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--no-lammps", action="store_true")
    ap.add_argument("--baseline", help="a second meshfree binary run interleaved with the first")
    ap.add_argument("--out", default=str(ROOT / "out" / "pd_benchmark"))
    args = ap.parse_args()
    models = MODELS if args.model == "both" else (args.model,)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    lmp = None if args.no_lammps else lref.find_lmp()
    tmp = Path(tempfile.mkdtemp(prefix="pd_benchmark_"))
    rows = {m: [] for m in models}
    for n in args.sizes:
        steps = max(5, int(round(EVALUATIONS / (n ** 3 * 120))))
        problems = {m: write_problem(out, m, n, steps) for m in models}
        for threads in args.threads:
            best = {m: {} for m in models}
            for _ in range(args.repeats):
                for m in models:
                    measure(args, lmp, tmp, out, m, n, steps, threads, problems[m], best[m])
            for m in models:
                rows[m].append(table_row(m, n, threads, best[m]))
    for m in models:
        report(m, rows[m], args.threads, out / CSV[m])
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
