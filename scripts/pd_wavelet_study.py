#!/usr/bin/python3
"""Paper 000's wavelet study: each problem is run with its load record and with the record's
Haar (db1) approximations at levels 1-5 (each level halves the samples; the run takes one step
per sample, capped by the stable step), and the paper's table is written: samples, steps, wall
time, time saved, and the largest displacement, velocity and acceleration at the reference point
with their errors against level 0.

    scripts/pd_wavelet_study.py [PROBLEM ...] [--records 1,2] [--levels 0,1,2,3,4,5]
                                [--out problems/pd_wavelet] [--meshfree build/meshfree] [--quick]

PROBLEM: pd_cantilever_random_load (example 1, linear), pd_rc_cantilever (example 2),
pd_rc_simply_supported (example 3); default all three. Each run's folder stays under
out/pd_wavelet/; the tables (<problem>_record<k>.csv and .md) go to --out, with the crack
patterns of the reinforced-concrete beams at level 0 and 4 (<problem>_record<k>_damage.png).
--quick: example 1 only, levels 0 and 3, run over the first tenth of the record (a smoke test;
its tables go to --out as well, so point --out elsewhere).
"""

import argparse
import csv
import json
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

# Record durations per problem (paper 000: example 2 1400 / 1300 us, example 3 3200 / 2900 us;
# example 1's duration is not given, see its problem file), and the reference gauge components.
PROBLEMS = {
    "pd_cantilever_random_load": dict(durations={1: 0.07, 2: 0.07 * 18000 / 19890},
                                      gauge="tip", components=["z"]),
    "pd_rc_cantilever": dict(durations={1: 1.4e-3, 2: 1.3e-3}, gauge="end", components=["x", "z"]),
    "pd_rc_simply_supported": dict(durations={1: 3.2e-3, 2: 2.9e-3}, gauge="midspan",
                                   components=["x", "z"]),
}
SAMPLES = {1: 19890, 2: 18000}


def run(meshfree, problem, record, level, duration, end, out_dir):
    folder = os.path.join(out_dir, f"{problem}_record{record}_A{level}")
    cmd = [meshfree, "run", os.path.join(ROOT, "problems", problem + ".yaml"), "--out", folder,
           "--set", f"functions.0.file=loads/random_load_{record}.csv",
           "--set", f"functions.0.duration={duration}",
           "--set", f"functions.0.haar_level={level}",
           "--set", f"time.end={end}"]
    print("running:", problem, f"record {record}", f"level {level}", flush=True)
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        sys.stdout.write(done.stdout[-3000:])
        raise SystemExit(f"{problem} record {record} level {level} failed")
    with open(os.path.join(folder, "summary.json")) as f:
        return folder, json.load(f)


def damage_plot(folders, path, title):
    """Side view (x, z) of the damaged particles at the end of the run, for each level."""
    import h5py
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    fig, axes = plt.subplots(len(folders), 1, figsize=(8, 2.2 * len(folders)), squeeze=False)
    for ax, (label, folder) in zip(axes[:, 0], folders):
        with h5py.File(os.path.join(folder, "fields.h5")) as h5:
            xyz = h5["geometry/coordinates"][...]
            last = sorted(k for k in h5 if k.startswith("step_"))[-1]
            phi = h5[last]["damage"][...]
            mat = h5[last]["material"][...]
        # The largest damage through the width, per (x, z) column.
        keys = np.round(xyz[:, [0, 2]] / 1e-6).astype(np.int64)
        cols = {}
        for k, p in zip(map(tuple, keys), phi):
            cols[k] = max(cols.get(k, 0.0), p)
        pts = np.array([[k[0] * 1e-6, k[1] * 1e-6, p] for k, p in cols.items()])
        sc = ax.scatter(pts[:, 0], pts[:, 1], c=pts[:, 2], s=6, cmap="inferno_r", vmin=0, vmax=0.6,
                        marker="s")
        steel = mat > 0.5
        ax.scatter(xyz[steel, 0], xyz[steel, 2], s=1, c="tab:blue")
        ax.set_aspect("equal")
        ax.set_title(f"{title}: {label}", fontsize=9)
        fig.colorbar(sc, ax=ax, label="damage (max through the width)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def study(meshfree, problem, record, levels, work_dir, out_dir, fraction):
    spec = PROBLEMS[problem]
    duration = spec["durations"][record]
    end = duration * fraction
    rows, folders = [], {}
    for level in levels:
        folder, s = run(meshfree, problem, record, level, duration, end, work_dir)
        folders[level] = folder
        maxima = s["results"]["gauge_max_abs_every_step"]
        row = dict(level=level,
                   samples=_haar_count(SAMPLES[record], level),
                   steps=s["counts"]["steps"], dt=s["time_step"]["dt"],
                   wall_s=s["time_s"]["stepping"],
                   broken_bonds=s["results"]["broken_bonds"],
                   max_damage=s["results"]["max_damage"])
        for c in spec["components"]:
            for what in ("u", "v", "a"):
                row[f"max_{what}{c}"] = maxima[f"{spec['gauge']}_{what}{c}"]
        rows.append(row)
    base = rows[0]
    for r in rows:
        r["time_saved_pct"] = 100.0 * (1.0 - r["wall_s"] / base["wall_s"])
        for c in spec["components"]:
            for what in ("u", "v", "a"):
                k = f"max_{what}{c}"
                r[f"error_{what}{c}_pct"] = 100.0 * (r[k] - base[k]) / base[k] if base[k] else 0.0
    name = f"{problem}_record{record}"
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, name + ".csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = [f"### {problem}, record {record} ({duration * 1e6:.0f} us"
             + (f", run to {end * 1e6:.0f} us" if end < duration else "") + ")", "",
             "| wave | samples | steps | wall time (s) | time saved | "
             + " | ".join(f"max \\|{w}{c}\\| (error)" for c in spec["components"]
                          for w in ("u", "v", "a")) + " | broken bonds |",
             "|---|---|---|---|---|" + "---|" * (3 * len(spec["components"])) + "---|"]
    for r in rows:
        label = "main" if r["level"] == 0 else f"A{r['level']}"
        cells = []
        for c in spec["components"]:
            for what in ("u", "v", "a"):
                v = r[f"max_{what}{c}"]
                e = r[f"error_{what}{c}_pct"]
                cells.append(f"{v:.4g}" + ("" if r["level"] == 0 else f" ({e:+.1f}%)"))
        lines.append(f"| {label} | {r['samples']} | {r['steps']} | {r['wall_s']:.2f} | "
                     f"{r['time_saved_pct']:.1f}% | " + " | ".join(cells) +
                     f" | {r['broken_bonds']} |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out_dir, name + ".md"), "w") as f:
        f.write(text)
    print(text, flush=True)
    if problem != "pd_cantilever_random_load" and 0 in folders and 4 in folders:
        damage_plot([("main", folders[0]), ("A4", folders[4])],
                    os.path.join(out_dir, name + "_damage.png"), f"{problem}, record {record}")


def _haar_count(n, level):
    for _ in range(level):
        n = (n + 1) // 2
    return n


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("problems", nargs="*")
    ap.add_argument("--records", default="1,2")
    ap.add_argument("--levels", default="0,1,2,3,4,5")
    ap.add_argument("--out", default=os.path.join(ROOT, "problems", "pd_wavelet"))
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "pd_wavelet"))
    ap.add_argument("--meshfree", default=os.path.join(ROOT, "build", "meshfree"))
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    problems = args.problems or list(PROBLEMS)
    levels = [int(v) for v in args.levels.split(",")]
    records = [int(v) for v in args.records.split(",")]
    fraction = 1.0
    if args.quick:
        problems, levels, records, fraction = ["pd_cantilever_random_load"], [0, 3], [1], 0.1
    for p in problems:
        if p not in PROBLEMS:
            raise SystemExit(f"unknown problem {p}; known: {list(PROBLEMS)}")
        for k in records:
            study(args.meshfree, p, k, levels, args.work, args.out, fraction)


if __name__ == "__main__":
    main()
