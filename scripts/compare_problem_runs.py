#!/usr/bin/python3
"""Runs every problem of two builds of meshfree and compares their results: the check that a
change which must not change any result (a refactor, a new input dialect) changed none.

Each side is a meshfree binary and a folder of problem files (the two may speak different input
dialects); problems are paired by file name. Explicit problems (peridynamics, sph) run over
--explicit-fraction of their end time (set through `time.end`, a key both dialects share).
The comparison is scripts/compare_runs.py at --rtol: every number under "results" in
summary.json, every history.csv column and every field of the last output step.

    scripts/compare_problem_runs.py --old-meshfree OLD/meshfree --old-problems OLD/problems \\
        --new-meshfree build/meshfree --new-problems problems --out out/compare_runs

--match-positions pairs particles by position when the two builds order them differently.
--reuse-old keeps the old runs already in OUT/old (or --old-runs DIR).
--new-set KEY=VALUE (repeatable) passes --set to the new side's explicit runs only, for an option
the old build lacks (discretisation.deterministic=true: SPH's rows summed whole).
Runs use OMP_NUM_THREADS=1 unless --threads says otherwise, so that sums are in one order.
"""
import argparse
import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def end_time(problem: Path):
    m = re.search(r"^time:\s*\{end:\s*([^,}]+)", problem.read_text(), re.M)
    return float(m.group(1)) if m else None


def explicit(problem: Path):
    return re.search(r"^analysis:\s*(peridynamics|sph)\b", problem.read_text(), re.M) is not None


def run(binary, problem: Path, out: Path, fraction, threads, log, sets=()):
    args = [str(binary), "run", str(problem), "--out", str(out)]
    end = end_time(problem) if explicit(problem) else None
    if end is not None:
        args += ["--set", f"time.end={fraction * end:.6g}"]
        for s in sets:
            args += ["--set", s]
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    t0 = time.time()
    with open(log, "w") as f:
        rc = subprocess.run(args, stdout=f, stderr=subprocess.STDOUT, env=env).returncode
    return rc, time.time() - t0


def results_folder(run_dir: Path):
    """Where a run left its results: the folder itself when it completed, else the files it kept
    under stopped/ or failed/ (the run contract)."""
    for sub in ("", "stopped", "failed"):
        if (run_dir / sub / "summary.json").exists():
            return run_dir / sub
    return run_dir


def exit_status(log_dir: Path, stem: str, rc=None):
    """The exit status of a run, kept beside its log so that a reused run still has it."""
    f = log_dir / f"{stem}.rc"
    if rc is not None:
        f.write_text(f"{rc}\n")
    return int(f.read_text()) if f.exists() else None


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--old-meshfree", required=True)
    ap.add_argument("--old-problems", required=True)
    ap.add_argument("--new-meshfree", default=str(ROOT / "build" / "meshfree"))
    ap.add_argument("--new-problems", default=str(ROOT / "problems"))
    ap.add_argument("--out", default="out/compare_problem_runs")
    ap.add_argument("--explicit-fraction", type=float, default=0.05)
    ap.add_argument("--rtol", type=float, default=1e-10)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--reuse-old", action="store_true")
    ap.add_argument("--new-set", action="append", default=[], metavar="KEY=VALUE",
                    help="--set for the new side's explicit runs")
    ap.add_argument("--match-positions", action="store_true",
                    help="pair particles by position (compare_runs.py --match-positions)")
    ap.add_argument("--old-runs", help="folder of existing old runs (default OUT/old); implies --reuse-old")
    ap.add_argument("--only-old", action="store_true", help="run the old side only")
    ap.add_argument("problems", nargs="*", help="file names to compare (default: all)")
    args = ap.parse_args()

    out = Path(args.out)
    old_root = Path(args.old_runs) if args.old_runs else out / "old"
    args.reuse_old = args.reuse_old or bool(args.old_runs)
    old_root.mkdir(parents=True, exist_ok=True)
    (out / "new").mkdir(parents=True, exist_ok=True)
    names = args.problems or sorted(p.name for p in Path(args.old_problems).glob("*.yaml"))
    rows, failures = [], 0
    for name in names:
        stem = name.removesuffix(".yaml")
        old_dir, new_dir = old_root / stem, out / "new" / stem
        if not (args.reuse_old and (results_folder(old_dir) / "summary.json").exists()):
            rc, t = run(args.old_meshfree, Path(args.old_problems) / name, old_dir,
                        args.explicit_fraction, args.threads, old_root / f"{stem}.log")
            exit_status(old_root, stem, rc)
            print(f"old {stem}: exit {rc}, {t:.1f} s", flush=True)
        old_rc = exit_status(old_root, stem)
        if args.only_old:
            continue
        new_problem = Path(args.new_problems) / name
        if not new_problem.exists():
            print(f"FAIL {stem}: no new problem file {new_problem}")
            failures += 1
            continue
        rc, t = run(args.new_meshfree, new_problem, new_dir, args.explicit_fraction,
                    args.threads, out / "new" / f"{stem}.log", args.new_set)
        cmp = subprocess.run(["/usr/bin/python3", str(ROOT / "scripts" / "compare_runs.py"),
                              str(results_folder(old_dir)), str(results_folder(new_dir)),
                              "--rtol", str(args.rtol)]
                             + (["--match-positions"] if args.match_positions else []),
                             capture_output=True, text=True)
        last = (cmp.stdout.strip().splitlines() or [""])[-1]
        same_end = rc == old_rc if old_rc is not None else rc == 0
        verdict = "ok" if same_end and cmp.returncode == 0 else "FAIL"
        failures += verdict == "FAIL"
        detail = last if cmp.returncode == 0 else (cmp.stdout + cmp.stderr).strip().replace("\n", "; ")
        if rc != 0 or not same_end:
            detail = f"exit {rc} (old {old_rc}); {detail}"
        rows.append(f"| {stem} | {verdict} | {t:.1f} | {detail} |")
        print(f"{verdict} {stem}: {detail}", flush=True)
    if rows:
        table = ["| problem | verdict | new wall s | comparison |", "|---|---|---|---|"] + rows
        (out / "comparison.md").write_text("\n".join(table) + "\n")
        print("\n".join(table))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
