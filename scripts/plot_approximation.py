#!/usr/bin/python3
"""Plots the function-approximation comparison of [Faraji 2007] section 4-1 (its Figs. 4-1 to 4-7):
plain SPH kernel sums against RK shape functions (linear and quadratic basis) for linear,
quadratic and cos(x) data in 1D and z = 2x + y, z = 2x^2 + y^2 in 2D, on 11 (11 x 11) nodes
with a cubic B-spline window. Reads the CSV files written by `approximation_study DIR` and
writes approx_*.png beside them; prints the largest errors, in the interior and on the boundary.

    build/approximation_study out/approximation && scripts/plot_approximation.py out/approximation
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

LABELS = {"sph": "SPH (no correction)", "rk_linear": "RK, linear basis", "rk_quadratic": "RK, quadratic basis"}


def load(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def report(name, d):
    x, y = d["x"], d["y"]
    on_boundary = (x == 0) | (x == 1) | (((y == 0) | (y == 1)) if y.max() > 0 else False)
    for key in LABELS:
        err = np.abs(d[key] - d["exact"])
        print(f"{name:14s} {LABELS[key]:22s} max error: interior {err[~on_boundary].max():.2e}, "
              f"boundary {err[on_boundary].max():.2e}")


def plot_1d(name, d, out):
    fig, (ax, ae) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True)
    ax.plot(d["x"], d["exact"], "k-", lw=2.5, label="exact")
    for key, style in zip(LABELS, ["r--", "b-", "g:"]):
        ax.plot(d["x"], d[key], style, label=LABELS[key])
        ae.semilogy(d["x"], np.abs(d[key] - d["exact"]) + 1e-17, style, label=LABELS[key])
    ax.set_ylabel("u(x)")
    ax.legend()
    ax.set_title(f"{name}: approximation from nodal values (11 nodes)")
    ae.set_xlabel("x")
    ae.set_ylabel("|error|")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def plot_2d(name, d, out):
    n = int(round(np.sqrt(len(d["x"]))))
    X, Y = d["x"].reshape(n, n), d["y"].reshape(n, n)
    fig = plt.figure(figsize=(13, 4))
    for i, key in enumerate(LABELS):
        ax = fig.add_subplot(1, 3, i + 1)
        err = np.abs(d[key] - d["exact"]).reshape(n, n)
        c = ax.contourf(X, Y, np.log10(err + 1e-17), levels=20, cmap="viridis")
        fig.colorbar(c, ax=ax, label="log10 |error|")
        ax.set_title(f"{LABELS[key]}\nmax |error| {err.max():.1e}")
        ax.set_aspect("equal")
    fig.suptitle(f"{name}: error of the approximation (11 x 11 nodes)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main():
    folder = Path(sys.argv[1] if len(sys.argv) > 1 else "out/approximation")
    files = sorted(folder.glob("approx_*.csv"))
    if not files:
        sys.exit(f"no approx_*.csv in {folder}; run build/approximation_study {folder} first")
    for f in files:
        d = load(f)
        name = f.stem.replace("approx_", "")
        report(name, d)
        (plot_1d if name.startswith("1d") else plot_2d)(name, d, f.with_suffix(".png"))
    print(f"plots in {folder}")


if __name__ == "__main__":
    main()
