#!/usr/bin/python3
"""The buried-tunnel study of [Altafi 2018] (sources/digest-004): a concrete lining in dry sand
under a TNT surface burst, depths 10, 15, 20 m x charges 500, 1000, 5000 kg.

Each case is problems/sph_tunnel_blast.yaml with its depth and charge (the crown's extrados at
the depth, 6 m of sand below the invert) and a run time that grows with the depth. The script
runs the cases, then writes to --out:
  - results.csv: per case and gauge, arrival time, peak pressure, peak downward velocity, final
    vertical displacement, peak von Mises stress, particles, steps and wall time;
  - table.md: the arrival times next to [Altafi 2018]'s table (scaled x1000, as its model appears to
    be a 1:1000 replica; digest section 6.3), and the peaks;
  - gauges_<depth>m_<mass>kg.png: pressure, vertical velocity, vertical displacement and von
    Mises stress at the crown and the floor;
  - max_von_mises_vs_depth.png and arrival_vs_depth.png ([Altafi 2018] Figs 5-78/79 and 5-49/50).

Usage: scripts/tunnel_study.py [--meshfree build/meshfree] [--out out/tunnel_study]
       [--spacing 0.25] [--cases 10:500,20:5000] [--end-scale 1.0]
"""
import argparse
import copy
import csv
import json
import os
import re
import subprocess
import sys

import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TEMPLATE = os.path.join(ROOT, "problems", "sph_tunnel_blast.yaml")
DEPTHS = [10.0, 15.0, 20.0]
MASSES = [500.0, 1000.0, 5000.0]
# The first-arrival table of [Altafi 2018] (ms in its model units), digest section 6.1: depth ->
# (crown 500, 1000, 5000, floor 500, 1000, 5000). Scaled x1000 it reads in real ms.
THESIS_ARRIVAL = {10.0: (0.007, 0.006, 0.004, 0.010, 0.009, 0.008),
                  15.0: (0.008, 0.007, 0.006, 0.011, 0.009, 0.009),
                  20.0: (0.012, 0.009, 0.007, 0.014, 0.013, 0.011)}
# TM 5-855-1 ground shock in dry sand (backfill; UFC 3-340-01 / ConWep after Drake & Little
# 1983): peak particle velocity V0 = 48.768 f (2.5208 R / W^(1/3))^-n m/s (R in m, W in kg TNT),
# P0 = rho c V0, arrival t = R / c, with rho c = 498 kPa s/m, c = 305 m/s, n = 2.75; coupling
# f = 0.14 for a burst on the surface, 0.4 at zero depth of burial on the Bulson curve.
TM_RHO_C, TM_C, TM_N, TM_F = 498e3, 305.0, 2.75, (0.14, 0.4)


def tm5_855(depth, mass, f):
    """Free-field peak pressure [kPa] and arrival [ms] of TM 5-855-1 at range `depth`."""
    v0 = 48.768 * f * (2.5208 * depth / mass ** (1.0 / 3.0)) ** (-TM_N)
    return 1e-3 * TM_RHO_C * v0, 1e3 * depth / TM_C


OUTER_RADIUS, LINING = 3.25, 0.5
HALF_WIDTH, BELOW_INVERT = 16.0, 6.0
ARRIVAL_FRACTION = 0.02  # arrival: |p| first reaches this fraction of the gauge's peak


def case_problem(template, depth, mass, spacing, end_scale):
    """The template with the depth, charge and spacing of one case."""
    p = copy.deepcopy(template)
    centre = -(depth + OUTER_RADIUS)
    bottom = centre - OUTER_RADIUS - BELOW_INVERT
    s = spacing
    p["name"] = f"sph_tunnel_{int(depth)}m_{int(mass)}kg"
    p["description"] = (f"Concrete tunnel lining in dry sand under a {mass:g} kg TNT surface "
                        f"burst, crown {depth:g} m deep (SPH, 2D plane strain)")
    sand, lining = p["regions"]
    sand["box"] = [[-HALF_WIDTH, bottom], [HALF_WIDTH, 0.0]]
    sand["spacing"] = s
    sand["holes"] = [{"center": [0.0, centre], "radius": OUTER_RADIUS}]
    lining["ring"] = {"center": [0.0, centre], "inner_radius": OUTER_RADIUS - LINING,
                      "outer_radius": OUTER_RADIUS}
    lining["spacing"] = s
    load, left, right, floor = p["boundary"]
    load["box"] = [[-HALF_WIDTH, -s], [HALF_WIDTH, 0.0]]
    load["blast"]["tnt_mass"] = mass
    left["box"] = [[-HALF_WIDTH, bottom], [-HALF_WIDTH + s, 0.0]]
    right["box"] = [[HALF_WIDTH - s, bottom], [HALF_WIDTH, 0.0]]
    floor["box"] = [[-HALF_WIDTH + s, bottom], [HALF_WIDTH - s, bottom + s]]
    # The ground shock in the sand travels at 0.4-0.7 km/s: 4 ms per metre down to the invert
    # lets the floor's pressure peak pass.
    p["time"]["end"] = round(end_scale * 4.0e-3 * (depth + 2 * OUTER_RADIUS), 6)
    p["output"]["gauges"] = [
        {"name": "crown", "at": [0.0, -depth - 0.5 * s]},
        {"name": "floor", "at": [0.0, centre - OUTER_RADIUS + 0.5 * s]},
        {"name": "sand_above_crown", "at": [0.0, -depth + 0.5 * s]},
        {"name": "surface", "at": [0.0, -0.5 * s]},
    ]
    return p


def read_history(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def gauge_numbers(h, g):
    t, p = h["time"], h[g + "_pressure"]
    peak = max(p, key=abs)
    arrival = next(ti for ti, pi in zip(t, p) if abs(pi) >= ARRIVAL_FRACTION * abs(peak))
    return {"arrival_ms": 1e3 * arrival, "peak_pressure_kPa": 1e-3 * peak,
            "peak_time_ms": 1e3 * t[p.index(peak)],
            "min_vy": min(h[g + "_vy"]), "final_uy_mm": 1e3 * h[g + "_uy"][-1],
            "max_von_mises_kPa": 1e-3 * max(h[g + "_von_mises"])}


def trends(results):
    """The study's trends over the cases in `results` (rows of results.csv): at the crown and the
    floor, the arrival grows with depth and falls with charge, the peak pressure falls with depth
    and grows with charge; and the crown is reached before the floor. Returns (statement, holds)
    for each trend that two or more cases show."""
    def value(r, key):
        return abs(float(r[key]))

    by_case = {}
    for r in results:
        by_case.setdefault((float(r["depth_m"]), float(r["tnt_kg"])), {})[r["gauge"]] = r
    out = []
    for g in ("crown", "floor"):
        for key, label, with_depth in (("arrival_ms", "arrival", +1),
                                       ("peak_pressure_kPa", "|peak pressure|", -1)):
            for over, fixed in ((0, 1), (1, 0)):
                sign = with_depth if over == 0 else -with_depth
                series = {}
                for case, gauges in by_case.items():
                    series.setdefault(case[fixed], []).append((case[over], value(gauges[g], key)))
                pairs = [sorted(v) for v in series.values() if len(v) > 1]
                if not pairs:
                    continue
                holds = all(sign * (b[1] - a[1]) > 0 for v in pairs for a, b in zip(v, v[1:]))
                out.append((f"{g}: {label} {'grows' if sign > 0 else 'falls'} with "
                            f"{'depth' if over == 0 else 'charge'}", holds))
    out.append(("the crown is reached before the floor",
                all(value(c["crown"], "arrival_ms") < value(c["floor"], "arrival_ms")
                    for c in by_case.values())))
    return out


def plot_case(h, title, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    t = [1e3 * x for x in h["time"]]
    fig, ax = plt.subplots(2, 2, figsize=(10, 7))
    panels = [("pressure", 1e-3, "pressure [kPa]"), ("vy", 1.0, "vertical velocity [m/s]"),
              ("uy", 1e3, "vertical displacement [mm]"), ("von_mises", 1e-3, "von Mises [kPa]")]
    for a, (what, scale, label) in zip(ax.flat, panels):
        for g in ("crown", "floor"):
            a.plot(t, [scale * v for v in h[f"{g}_{what}"]], label=g)
        a.set_xlabel("time [ms]")
        a.set_ylabel(label)
        a.grid(True, alpha=0.3)
        a.legend()
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def lining_damage(case_dir):
    """The largest HJC damage and the number of failed particles in the lining over the run."""
    import h5py
    with h5py.File(os.path.join(case_dir, "fields.h5"), "r") as f:
        steps = [k for k in f if k.startswith("step_")]
        lining = f[f"{steps[0]}/material"][:] == 1
        damage = max(float(f[f"{k}/damage"][:][lining].max()) for k in steps)
        failed = max(int(f[f"{k}/failed"][:][lining].sum()) for k in steps)
    return damage, failed, int(lining.sum())


def plot_field(case_dir, depth, at_ms, title, path):
    """Pressure around the tunnel and damage in the lining at the field output nearest at_ms."""
    import h5py
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    with open(os.path.join(case_dir, "fields.xmf")) as f:  # the series' times, in step order
        times = [float(t) for t in re.findall(r'<Time Value="([^"]+)"', f.read())]
    with h5py.File(os.path.join(case_dir, "fields.h5"), "r") as f:
        steps = sorted(k for k in f if k.startswith("step_"))
        k = min(range(len(steps)), key=lambda i: abs(1e3 * times[i] - at_ms))
        x = f["geometry/coordinates"][:] + f[f"{steps[k]}/displacement"][:]
        p = f[f"{steps[k]}/pressure"][:]
        damage = f[f"{steps[k]}/damage"][:]
        material = f[f"{steps[k]}/material"][:]
    centre = -(depth + OUTER_RADIUS)
    near = (abs(x[:, 0]) < 8.0) & (abs(x[:, 1] - centre) < 8.0)
    fig, ax = plt.subplots(1, 2, figsize=(11, 5))
    sc = ax[0].scatter(x[near, 0], x[near, 1], c=1e-3 * p[near], s=4, cmap="viridis")
    fig.colorbar(sc, ax=ax[0], label="pressure [kPa]")
    ring = near & (material == 1)
    sc = ax[1].scatter(x[ring, 0], x[ring, 1], c=damage[ring], s=12, cmap="magma", vmin=0, vmax=1)
    fig.colorbar(sc, ax=ax[1], label="HJC damage")
    for a in ax:
        a.set_aspect("equal")
        a.set_xlabel("x [m]")
        a.set_ylabel("y [m]")
    ax[0].set_title(f"{title}: pressure at {1e3 * times[k]:.0f} ms")
    ax[1].set_title("lining damage")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_summary(results, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(10, 4.5))
    for k, g in enumerate(("crown", "floor")):
        for m in MASSES:
            pts = sorted((r["depth_m"], r["max_von_mises_kPa"]) for r in results
                         if r["gauge"] == g and r["tnt_kg"] == m)
            if pts:
                ax[k].plot([v for _, v in pts], [d for d, _ in pts], "o-", label=f"{m:g} kg")
        ax[k].invert_yaxis()
        ax[k].set_xlabel("maximum von Mises stress [kPa]")
        ax[k].set_ylabel("depth [m]")
        ax[k].set_title(g)
        ax[k].grid(True, alpha=0.3)
        ax[k].legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "max_von_mises_vs_depth.png"), dpi=110)
    plt.close(fig)
    fig, ax = plt.subplots(1, 2, figsize=(10, 4.5))
    for k, g in enumerate(("crown", "floor")):
        for j, m in enumerate(MASSES):
            pts = sorted((r["depth_m"], r["arrival_ms"]) for r in results
                         if r["gauge"] == g and r["tnt_kg"] == m)
            if not pts:
                continue
            line, = ax[k].plot([v for _, v in pts], [d for d, _ in pts], "o-", label=f"{m:g} kg")
            ax[k].plot([1e3 * THESIS_ARRIVAL[d][3 * k + j] for d in DEPTHS], DEPTHS, "x--",
                       color=line.get_color(), label=f"thesis x1000, {m:g} kg")
        ax[k].invert_yaxis()
        ax[k].set_xlabel("first arrival [ms]")
        ax[k].set_ylabel("depth [m]")
        ax[k].set_title(g)
        ax[k].grid(True, alpha=0.3)
        ax[k].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "arrival_vs_depth.png"), dpi=110)
    plt.close(fig)


def write_table(results, runs, out, spacing):
    def get(d, m, g, key):
        for r in results:
            if r["depth_m"] == d and r["tnt_kg"] == m and r["gauge"] == g:
                return r[key]
        return None

    lines = [f"# Buried-tunnel study: results (spacing {spacing:g} m)", "",
             "First arrival at the gauge (|p| reaches "
             f"{100 * ARRIVAL_FRACTION:g}% of its peak), ms; the thesis' values x1000 in "
             "brackets.", "",
             "| depth | crown 500 kg | crown 1000 kg | crown 5000 kg | floor 500 kg | "
             "floor 1000 kg | floor 5000 kg |", "|---|---|---|---|---|---|---|"]
    for d in DEPTHS:
        cells = []
        for k, g in enumerate(("crown", "floor")):
            for j, m in enumerate(MASSES):
                a = get(d, m, g, "arrival_ms")
                ref = 1e3 * THESIS_ARRIVAL[d][3 * k + j]
                cells.append("-" if a is None else f"{a:.1f} ({ref:g})")
        lines.append(f"| {d:g} m | " + " | ".join(cells) + " |")
    lines += ["", "Free-field sand just above the crown against TM 5-855-1 (dry sand; f = 0.14 and "
              "0.4; the 2D model's line of charges decays more slowly than a point charge):", "",
              "| depth | charge | arrival ms | TM arrival ms | peak kPa | TM peak kPa (f 0.14 / 0.4) |",
              "|---|---|---|---|---|---|"]
    for d in DEPTHS:
        for m in MASSES:
            a = get(d, m, "sand_above_crown", "arrival_ms")
            if a is None:
                continue
            p = get(d, m, "sand_above_crown", "peak_pressure_kPa")
            lo, t_tm = tm5_855(d, m, TM_F[0])
            hi, _ = tm5_855(d, m, TM_F[1])
            lines.append(f"| {d:g} m | {m:g} kg | {a:.1f} | {t_tm:.1f} | {p:.4g} | "
                         f"{lo:.3g} / {hi:.3g} |")
    for key, label in (("peak_pressure_kPa", "Peak pressure, kPa"),
                       ("max_von_mises_kPa", "Maximum von Mises stress, kPa"),
                       ("min_vy", "Largest downward velocity, m/s"),
                       ("final_uy_mm", "Vertical displacement at the end of the run, mm")):
        lines += ["", label + ":", "",
                  "| depth | crown 500 kg | crown 1000 kg | crown 5000 kg | floor 500 kg | "
                  "floor 1000 kg | floor 5000 kg |", "|---|---|---|---|---|---|---|"]
        for d in DEPTHS:
            cells = []
            for g in ("crown", "floor"):
                for m in MASSES:
                    v = get(d, m, g, key)
                    cells.append("-" if v is None else f"{v:.4g}")
            lines.append(f"| {d:g} m | " + " | ".join(cells) + " |")
    lines += ["", "Runs (lining damage: the largest HJC damage and the failed particles in the "
              f"lining, of {runs[0]['lining']}):", "",
              "| case | particles | steps | end [ms] | wall [s] | energy error | lining damage | "
              "failed |", "|---|---|---|---|---|---|---|---|"]
    for r in runs:
        lines.append(f"| {r['case']} | {r['particles']} | {r['steps']} | {r['end_ms']:g} | "
                     f"{r['wall_s']:.1f} | {r['energy_error']:.2e} | {r['damage']:.3f} | "
                     f"{r['failed']} |")
    with open(os.path.join(out, "table.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--meshfree", default=os.path.join(ROOT, "build", "meshfree"))
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "tunnel_study"))
    ap.add_argument("--spacing", type=float, default=0.25)
    ap.add_argument("--cases", default="", help="depth:mass pairs, e.g. 10:500,20:5000")
    ap.add_argument("--end-scale", type=float, default=1.0,
                    help="multiplies every run's end time (a smoke test uses less)")
    ap.add_argument("--report-only", action="store_true",
                    help="write the table and plots from the runs already in --out")
    args = ap.parse_args()
    with open(TEMPLATE) as f:
        template = yaml.safe_load(f)
    cases = [(d, m) for d in DEPTHS for m in MASSES]
    if args.cases:
        cases = [tuple(float(v) for v in c.split(":")) for c in args.cases.split(",")]
        for d, m in cases:
            if d not in DEPTHS or m not in MASSES:
                sys.exit(f"--cases: {d:g}:{m:g} is not one of the thesis' cases "
                         f"(depths {DEPTHS}, masses {MASSES})")
    os.makedirs(args.out, exist_ok=True)
    results, runs = [], []
    for d, m in cases:
        name = f"{int(d)}m_{int(m)}kg"
        case_dir = os.path.join(args.out, name)
        os.makedirs(case_dir, exist_ok=True)
        problem = case_problem(template, d, m, args.spacing, args.end_scale)
        problem_path = os.path.join(case_dir, "problem.yaml")
        if not args.report_only:
            with open(problem_path, "w") as f:
                yaml.safe_dump(problem, f, sort_keys=False)
        if args.report_only:
            with open(problem_path) as f:
                problem = yaml.safe_load(f)
        else:
            run = subprocess.run([args.meshfree, "run", problem_path, "--out", case_dir],
                                 capture_output=True, text=True)
            if run.returncode != 0:
                sys.exit(f"case {name} failed:\n{run.stdout}\n{run.stderr}")
        with open(os.path.join(case_dir, "summary.json")) as f:
            summary = json.load(f)
        wall = summary["time_s"]["total"]  # not the sum: the phases beside it make up the total
        h = read_history(os.path.join(case_dir, "history.csv"))
        damage, failed, lining = lining_damage(case_dir)
        runs.append({"case": name, "particles": summary["counts"]["particles"],
                     "damage": damage, "failed": failed, "lining": lining,
                     "steps": summary["counts"]["steps"], "end_ms": 1e3 * problem["time"]["end"],
                     "wall_s": wall,
                     "energy_error": summary["results"]["energy_error_relative"]})
        for g in ("crown", "floor", "sand_above_crown", "surface"):
            row = {"depth_m": d, "tnt_kg": m, "gauge": g}
            row.update(gauge_numbers(h, g))
            results.append(row)
        plot_case(h, f"crown {d:g} m, {m:g} kg TNT", os.path.join(args.out, f"gauges_{name}.png"))
        crown = results[-4]
        plot_field(case_dir, d, crown["peak_time_ms"], f"crown {d:g} m, {m:g} kg",
                   os.path.join(args.out, f"field_{name}.png"))
        print(f"{name}: {runs[-1]['particles']} particles, {runs[-1]['steps']} steps, "
              f"{wall:.1f} s; crown arrival {crown['arrival_ms']:.2f} ms, peak "
              f"{crown['peak_pressure_kPa']:.0f} kPa", flush=True)
    with open(os.path.join(args.out, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(results[0].keys()))
        w.writeheader()
        w.writerows(results)
    write_table(results, runs, args.out, args.spacing)
    plot_summary(results, args.out)
    print(f"wrote {args.out}/table.md, results.csv and the plots")


if __name__ == "__main__":
    main()
