#!/usr/bin/python3
"""Convergence studies against exact solutions: Timoshenko's cantilever and Kirsch's plate with
a hole, over four node spacings each. Runs `meshfree run` for each spacing, collects the relative
L2 and energy-norm errors from summary.json, writes convergence.csv and convergence.png into
--out and prints the fitted rates (least-squares slope of log error against log h).

    scripts/convergence_study.py [--meshfree build/meshfree] [--out out/convergence] [--quick]
"""
import argparse
import csv
import json
import subprocess
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
STUDIES = {
    "cantilever_timoshenko": [3.0, 1.5, 0.75, 0.375, 0.1875],
    "plate_hole_kirsch": [0.5, 0.25, 0.125, 0.0625, 0.03125],
}


def run_study(meshfree, out, problem, spacings):
    """Runs the problem at each spacing; returns (h, l2, energy, rate_l2, rate_energy, rows) with
    one csv row per run."""
    h, l2, en, rows = [], [], [], []
    for s in spacings:
        run_dir = Path(out) / f"{problem}_h{s:g}"
        subprocess.run([meshfree, "run", str(ROOT / "problems" / f"{problem}.yaml"),
                        "--out", str(run_dir), "--set", f"discretisation.spacing={s}"],
                       check=True, stdout=subprocess.DEVNULL)
        summary = json.loads((run_dir / "summary.json").read_text())
        res, counts = summary["results"], summary["counts"]
        h.append(s)
        l2.append(res["error_l2_relative"])
        en.append(res["error_energy_relative"])
        rows.append([problem, s, counts["nodes"], res["error_l2_relative"], res["error_energy_relative"],
                     summary["time_s"]["total"]])
    rate_l2 = np.polyfit(np.log(h), np.log(l2), 1)[0]
    rate_en = np.polyfit(np.log(h), np.log(en), 1)[0]
    return h, l2, en, rate_l2, rate_en, rows


def plot(fig_rows, path):
    """One log-log panel per study: {problem: (h, l2, energy, rate_l2, rate_energy)}."""
    fig, axes = plt.subplots(1, len(fig_rows), figsize=(11, 4.5), squeeze=False)
    for ax, (problem, (h, l2, en, rl, re)) in zip(axes[0], fig_rows.items()):
        ax.loglog(h, l2, "o-", label=f"L2 displacement (rate {rl:.2f})")
        ax.loglog(h, en, "s-", label=f"energy norm (rate {re:.2f})")
        for p, style in ((1, "k:"), (2, "k--")):
            ax.loglog(h, en[0] * (np.array(h) / h[0]) ** p, style, lw=0.8, label=f"h^{p}")
        ax.set_xlabel("node spacing h")
        ax.set_ylabel("relative error")
        ax.set_title(problem)
        ax.legend(fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshfree", default=str(ROOT / "build" / "meshfree"))
    ap.add_argument("--out", default=str(ROOT / "out" / "convergence"))
    ap.add_argument("--quick", action="store_true", help="four spacings per study instead of five")
    ap.add_argument("--min-energy-rate", type=float, default=None,
                    help="exit non-zero if an energy-norm rate is below this")
    ap.add_argument("--min-l2-rate", type=float, default=None, help="exit non-zero if an L2 rate is below this")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows, fig_rows, failures = [], {}, []
    for problem, spacings in STUDIES.items():
        if args.quick:
            spacings = spacings[:4]
        h, l2, en, rate_l2, rate_en, study_rows = run_study(args.meshfree, out, problem, spacings)
        rows += study_rows
        print(f"{problem}: rate L2 {rate_l2:.2f}, energy {rate_en:.2f} "
              f"(finest h = {h[-1]:g}: L2 {l2[-1]:.2e}, energy {en[-1]:.2e})")
        fig_rows[problem] = (h, l2, en, rate_l2, rate_en)
        if args.min_energy_rate is not None and rate_en < args.min_energy_rate:
            failures.append(f"{problem}: energy rate {rate_en:.2f} < {args.min_energy_rate}")
        if args.min_l2_rate is not None and rate_l2 < args.min_l2_rate:
            failures.append(f"{problem}: L2 rate {rate_l2:.2f} < {args.min_l2_rate}")
    with open(out / "convergence.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["problem", "spacing", "nodes", "error_l2_relative", "error_energy_relative", "wall_time_s"])
        w.writerows(rows)
    plot(fig_rows, out / "convergence.png")
    print(f"wrote {out / 'convergence.csv'} and {out / 'convergence.png'}")
    if failures:
        raise SystemExit("; ".join(failures))


if __name__ == "__main__":
    main()
