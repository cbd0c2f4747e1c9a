#!/usr/bin/env python3
"""Crown and floor of the preloaded tunnel (problems/staged_tunnel_blast.yaml) against the
unpreloaded one (problems/sph_tunnel_blast.yaml) run to the same end time: a markdown table of
the blast's signal at each gauge.

The preloaded gauges start from the geostatic state (pressure p0, displacement u0 at t = 0), so
their signal is taken as the change from it: dp = p - p0, du = u - u0. Arrival: |dp| first
reaches 2% of its peak (the rule of scripts/tunnel_study.py, where p0 = 0).

Usage: staged_compare.py STAGED_RUN_DIR STANDALONE_RUN_DIR [--gauges crown floor ...]
"""
import argparse
import csv
import os

ARRIVAL_FRACTION = 0.02


def read_history(run_dir, event_only):
    with open(os.path.join(run_dir, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    if event_only:  # a staged run: the explicit stage's rows, t >= 0
        last_stage = max(float(r["stage"]) for r in rows)
        rows = [r for r in rows if float(r["stage"]) == last_stage]
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def gauge(h, g):
    t = h["time"]
    p0, uy0 = h[g + "_pressure"][0], h[g + "_uy"][0]
    dp = [p - p0 for p in h[g + "_pressure"]]
    peak = max(dp, key=abs)
    arrival = next(ti for ti, d in zip(t, dp) if abs(d) >= ARRIVAL_FRACTION * abs(peak))
    speed = [(vx * vx + vy * vy) ** 0.5 for vx, vy in zip(h[g + "_vx"], h[g + "_vy"])]
    duy = [u - uy0 for u in h[g + "_uy"]]
    return {
        "p0 kPa": 1e-3 * p0,
        "arrival ms": 1e3 * arrival,
        "peak dp kPa": 1e-3 * peak,
        "peak time ms": 1e3 * t[dp.index(peak)],
        "peak p kPa": 1e-3 * max(h[g + "_pressure"], key=abs),
        "min vy m/s": min(h[g + "_vy"]),
        "max |v| m/s": max(speed),
        "min duy mm": 1e3 * min(duy),
        "final duy mm": 1e3 * duy[-1],
        "max von Mises kPa": 1e-3 * max(h[g + "_von_mises"]),
        "end ms": 1e3 * t[-1],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("staged")
    ap.add_argument("standalone")
    ap.add_argument("--gauges", nargs="+", default=["crown", "floor", "sand_above_crown"])
    a = ap.parse_args()
    pre = read_history(a.staged, True)
    free = read_history(a.standalone, False)
    end = min(pre["time"][-1], free["time"][-1])
    for h in (pre, free):
        keep = [i for i, t in enumerate(h["time"]) if t <= end + 1e-12]
        for k in h:
            h[k] = [h[k][i] for i in keep]
    print(f"| gauge | quantity | preloaded | unpreloaded | change |")
    print("|---|---|---|---|---|")
    for g in a.gauges:
        s, u = gauge(pre, g), gauge(free, g)
        for key in s:
            if key == "end ms":
                continue
            change = ""
            if key not in ("p0 kPa",) and u[key] != 0.0:
                change = f"{100.0 * (s[key] / u[key] - 1.0):+.1f}%"
            print(f"| {g} | {key} | {s[key]:.4g} | {u[key]:.4g} | {change} |")
    print(f"\nEnd time of both: {1e3 * end:.1f} ms.")


if __name__ == "__main__":
    main()
