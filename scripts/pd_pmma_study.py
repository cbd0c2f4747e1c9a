#!/usr/bin/python3
"""Paper 001's study of the PMMA beam under drop-weight impact, run with problems/
pd_pmma_beam_impact.yaml, and its findings checked one by one:

  1. delta = 2 dx: the crack arrests before the top edge;
  2. delta = 4 and 5 dx: growth starts earlier than with 3 dx;
  3. the offset alpha = 10 mm starts first (before 20 and 30 mm);
  4. a flat nose starts growth earlier than a spherical one;
  5. two symmetric cracks grow symmetrically and more vertically than a single one.

    scripts/pd_pmma_study.py [--out DIR] [--meshfree build/meshfree] [--quick]

Runs: horizon m = delta/dx in {2, 3, 4, 5} x initial crack model {crack (cut bonds), notch
(a removed particle column)} x offset in {10, 20, 30} mm with the spherical nose; the flat nose
and the two symmetric cracks with m = 4 and the notch, as paper 001. Writes study.csv (one row
per run), paths.png (the crack paths from the final damage field) and findings.md into DIR.
--quick runs a reduced matrix for a smoke test (the findings need the full one).

Crack growth: the crack tip is the damaged particle (damage >= 0.38, paper 001's threshold for
delta = 3 dx, used for every m) farthest above the initial crack tip; growth starts when the tip
has moved 1 mm (two spacings) above it.
"""

import argparse
import csv
import os
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
PROBLEM = os.path.join(ROOT, "problems", "pd_pmma_beam_impact.yaml")
DX = 0.0005
DEPTH = 0.045
MID = 0.110
CRACK = 0.006
START = 0.001   # growth has started when the tip is this far above the initial crack tip
TOP = 0.043     # a crack whose tip reaches this height has crossed the beam (top edge 0.045)


def crack_sets(model, offsets):
    """--set values for the initial cracks at the given signed offsets from mid-span."""
    if model == "crack":
        items = ", ".join(f"{{from: [{MID + a:.6f}, -0.001], to: [{MID + a:.6f}, {CRACK}]}}"
                          for a in offsets)
        return [f"cracks=[{items}]", "notches=[]"]
    # The notch: the particle column just left of the crack line (particles sit at cell centres,
    # none on the line itself) removed over the crack's 6 mm.
    items = ", ".join(f"{{box: [[{MID + a - 0.5 * DX:.6f}, 0], [{MID + a:.6f}, {CRACK}]]}}"
                      for a in offsets)
    return ["cracks=[]", f"notches=[{items}]"]


def cases(quick):
    out = []
    ms = [2, 3, 4, 5] if not quick else [3]
    models = ["crack", "notch"] if not quick else ["notch"]
    alphas = [10, 20, 30] if not quick else [10]
    for m in ms:
        for model in models:
            for a in alphas:
                out.append(dict(name=f"m{m}_{model}_a{a}_sphere", m=m, model=model, alpha=a,
                                nose="sphere", cracks=1))
    for a in alphas:
        out.append(dict(name=f"m4_notch_a{a}_flat", m=4, model="notch", alpha=a, nose="flat",
                        cracks=1))
        out.append(dict(name=f"m4_notch_a{a}_sphere_symmetric", m=4, model="notch", alpha=a,
                        nose="sphere", cracks=2))
    if quick:
        out = [c for c in out if c["alpha"] == 10][:3]
    return out


def overrides(case, end):
    a = case["alpha"] / 1000.0
    offsets = [a] if case["cracks"] == 1 else [a, -a]
    sets = [f"discretisation.horizon={case['m']}", f"time.end={end}",
            f"output.crack.origin=[{MID + a:.6f}, {CRACK}]",
            "output.fields_interval=1.0"]  # fields at the start and the end only
    sets += crack_sets(case["model"], offsets)
    if case["nose"] == "flat":
        # A rigid flat punch 16 mm wide whose leading face touches the top edge at t = 0.
        sets.append("impactors.0={name: striker, shape: flat, size: [0.016, 0.010], mass: 5.0, "
                    "position: [0.110, 0.050], velocity: [0, -2.3]}")
    return sets


def run_case(meshfree, case, out_dir, end):
    folder = os.path.join(out_dir, case["name"])
    cmd = [meshfree, "run", PROBLEM, "--out", folder]
    for s in overrides(case, end):
        cmd += ["--set", s]
    t0 = time.time()
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        sys.stdout.write(done.stdout[-3000:])
        raise SystemExit(f"{case['name']} failed")
    return folder, time.time() - t0


def crack_paths(folder, case):
    """Crack paths from the final damage field: for each particle row above the initial crack,
    the mean x of the damaged particles on each side of mid-span (one path per crack)."""
    with h5py.File(os.path.join(folder, "fields.h5")) as h5:
        x = h5["geometry/coordinates"][:, 0]
        y = h5["geometry/coordinates"][:, 1]
        last = sorted(k for k in h5 if k.startswith("step_"))[-1]
        phi = h5[last]["damage"][...]
    paths = {}
    sides = ["right"] if case["cracks"] == 1 else ["right", "left"]
    for side in sides:
        pts = []
        for row in np.unique(y[y > CRACK]):
            sel = (np.abs(y - row) < 1e-9) & (phi >= 0.38)
            sel &= (x > MID) if side == "right" else (x < MID)
            if sel.any():
                pts.append((float(np.mean(x[sel])), float(row)))
        paths[side] = pts
    return paths


def analyse(folder, case):
    rows = list(csv.DictReader(open(os.path.join(folder, "history.csv"))))
    t = np.array([float(r["time"]) for r in rows])
    tip_y = np.array([float(r["crack_tip_y"]) for r in rows])
    length = np.array([float(r["crack_length"]) for r in rows])
    started = np.nonzero(length >= START)[0]
    crossed = np.nonzero(tip_y >= TOP)[0]
    paths = crack_paths(folder, case)
    right = paths["right"]
    drift = right[-1][0] - right[0][0] if len(right) > 1 else 0.0
    result = dict(case=case["name"], m=case["m"], model=case["model"], alpha_mm=case["alpha"],
                  nose=case["nose"], cracks=case["cracks"],
                  initiation_us=1e6 * t[started[0]] if len(started) else float("nan"),
                  final_tip_y_mm=1e3 * tip_y[-1],
                  top_reached_us=1e6 * t[crossed[0]] if len(crossed) else float("nan"),
                  drift_toward_centre_mm=-1e3 * drift)
    if case["cracks"] == 2 and len(paths["left"]) > 1:
        # Symmetry: the left path mirrored about mid-span against the right one, row by row.
        left = {round(yy, 6): xx for xx, yy in paths["left"]}
        diffs = [abs((xx - MID) - (MID - left[round(yy, 6)])) for xx, yy in right
                 if round(yy, 6) in left]
        result["asymmetry_mm"] = 1e3 * max(diffs) if diffs else float("nan")
    return result, paths


def plot(results, all_paths, out_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ms = sorted({r["m"] for r in results if r["nose"] == "sphere" and r["cracks"] == 1})
    fig, axes = plt.subplots(1, len(ms) + 1, figsize=(4 * (len(ms) + 1), 4), squeeze=False)
    for ax, m in zip(axes[0], ms):
        for r in results:
            if r["m"] != m or r["cracks"] != 1 or r["nose"] != "sphere":
                continue
            pts = np.array(all_paths[r["case"]]["right"]) * 1e3
            if len(pts):
                ax.plot(pts[:, 0], pts[:, 1], "-" if r["model"] == "crack" else "--",
                        label=f"{r['model']}, alpha {r['alpha_mm']} mm")
        ax.set_title(f"delta = {m} dx, spherical nose")
    ax = axes[0][-1]
    for r in results:
        if r["nose"] == "flat" or r["cracks"] == 2:
            for side, pts in all_paths[r["case"]].items():
                pts = np.array(pts) * 1e3
                if len(pts):
                    ax.plot(pts[:, 0], pts[:, 1], "-" if r["cracks"] == 2 else ":",
                            label=f"{'two cracks' if r['cracks'] == 2 else 'flat nose'}, "
                                  f"alpha {r['alpha_mm']}" if side == "right" else None)
    ax.set_title("delta = 4 dx, notch: flat nose, two cracks")
    for ax in axes[0]:
        ax.set_xlim(60, 160)
        ax.set_ylim(0, 45)
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]")
        ax.axvline(110, color="0.8", lw=0.5)
        ax.legend(fontsize=6)
    axes[0][0].set_ylabel("y [mm]")
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "paths.png"), dpi=110)


def findings(results):
    """Each of paper 001's findings with the numbers that decide it."""
    def get(**kw):
        return [r for r in results if all(r[k] == v for k, v in kw.items())]
    lines = []
    single = [r for r in results if r["cracks"] == 1 and r["nose"] == "sphere"]
    if any(r["m"] == 2 for r in single):
        m2 = get(m=2, cracks=1, nose="sphere")
        ok = all(r["final_tip_y_mm"] < 1e3 * TOP for r in m2)
        tips = ", ".join(f"{r['model']} {r['alpha_mm']}: {r['final_tip_y_mm']:.1f} mm" for r in m2)
        lines.append(f"1. delta = 2 dx arrests before the top edge: {'yes' if ok else 'no'} "
                     f"(final tip heights {tips}; top edge 45 mm)")
    if {3, 4, 5} <= {r["m"] for r in single}:
        verdict = []
        for model in ("crack", "notch"):
            for a in (10, 20, 30):
                t = {r["m"]: r["initiation_us"] for r in get(model=model, alpha_mm=a, cracks=1,
                                                            nose="sphere")}
                if {3, 4, 5} <= set(t):
                    verdict.append((t[4] < t[3] and t[5] < t[3],
                                    f"{model} {a}: m=3 {t[3]:.0f}, 4 {t[4]:.0f}, 5 {t[5]:.0f} us"))
        ok = all(v for v, _ in verdict)
        lines.append(f"2. delta = 4 and 5 dx start earlier than 3 dx: {'yes' if ok else 'no'} in "
                     f"{sum(v for v, _ in verdict)} of {len(verdict)} cases ("
                     + "; ".join(s for _, s in verdict) + ")")
    verdict = []
    for m in sorted({r["m"] for r in single}):
        for model in ("crack", "notch"):
            t = {r["alpha_mm"]: r["initiation_us"] for r in get(m=m, model=model, cracks=1,
                                                               nose="sphere")}
            if {10, 20, 30} <= set(t):
                verdict.append((t[10] < t[20] and t[10] < t[30],
                                f"m{m} {model}: {t[10]:.0f}, {t[20]:.0f}, {t[30]:.0f} us"))
    if verdict:
        lines.append(f"3. offset 10 mm starts first: {'yes' if all(v for v, _ in verdict) else 'no'}"
                     f" in {sum(v for v, _ in verdict)} of {len(verdict)} cases (alpha 10, 20, 30: "
                     + "; ".join(s for _, s in verdict) + ")")
    verdict = []
    for a in (10, 20, 30):
        f = get(m=4, model="notch", alpha_mm=a, nose="flat")
        s = get(m=4, model="notch", alpha_mm=a, nose="sphere", cracks=1)
        if f and s:
            verdict.append((f[0]["initiation_us"] < s[0]["initiation_us"],
                            f"alpha {a}: flat {f[0]['initiation_us']:.0f}, sphere "
                            f"{s[0]['initiation_us']:.0f} us"))
    if verdict:
        lines.append(f"4. a flat nose starts earlier than a sphere: "
                     f"{'yes' if all(v for v, _ in verdict) else 'no'} in "
                     f"{sum(v for v, _ in verdict)} of {len(verdict)} ("
                     + "; ".join(s for _, s in verdict) + ")")
    verdict = []
    for a in (10, 20, 30):
        two = get(m=4, model="notch", alpha_mm=a, nose="sphere", cracks=2)
        one = get(m=4, model="notch", alpha_mm=a, nose="sphere", cracks=1)
        if two and one:
            sym = two[0].get("asymmetry_mm", float("nan"))
            verdict.append((sym <= 1.0 and abs(two[0]["drift_toward_centre_mm"]) <
                            abs(one[0]["drift_toward_centre_mm"]),
                            f"alpha {a}: asymmetry {sym:.2f} mm, drift toward the centre "
                            f"{two[0]['drift_toward_centre_mm']:.1f} mm (two cracks) against "
                            f"{one[0]['drift_toward_centre_mm']:.1f} mm (one)"))
    if verdict:
        lines.append(f"5. two symmetric cracks grow symmetrically and more vertically: "
                     f"{'yes' if all(v for v, _ in verdict) else 'no'} in "
                     f"{sum(v for v, _ in verdict)} of {len(verdict)} ("
                     + "; ".join(s for _, s in verdict) + ")")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "pd_pmma_study"))
    ap.add_argument("--meshfree", default=os.path.join(ROOT, "build", "meshfree"))
    ap.add_argument("--end", type=float, default=None, help="simulated time per run [s]")
    ap.add_argument("--quick", action="store_true", help="a reduced matrix (smoke test)")
    args = ap.parse_args()
    end = args.end or (1.0e-4 if args.quick else 8.0e-4)
    os.makedirs(args.out, exist_ok=True)
    results, all_paths = [], {}
    for case in cases(args.quick):
        folder, seconds = run_case(args.meshfree, case, args.out, end)
        r, paths = analyse(folder, case)
        r["wall_s"] = seconds
        results.append(r)
        all_paths[case["name"]] = paths
        print(f"{case['name']}: initiation {r['initiation_us']:.1f} us, final tip "
              f"{r['final_tip_y_mm']:.2f} mm, top reached {r['top_reached_us']:.1f} us, "
              f"drift toward the centre {r['drift_toward_centre_mm']:.2f} mm, {seconds:.0f} s",
              flush=True)
    keys = sorted({k for r in results for k in r}, key=lambda k: list(results[0]).index(k)
                  if k in results[0] else 99)
    with open(os.path.join(args.out, "study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(results)
    lines = findings(results)
    with open(os.path.join(args.out, "findings.md"), "w") as f:
        f.write("# Paper 001's findings against this code\n\n")
        f.write(f"Simulated time per run: {end * 1e6:.0f} us; growth starts when the tip has "
                f"moved {START * 1e3:.0f} mm; a crack has crossed when its tip reaches "
                f"{TOP * 1e3:.0f} mm.\n\n")
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    plot(results, all_paths, args.out)


if __name__ == "__main__":
    main()
