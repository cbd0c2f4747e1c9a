#!/usr/bin/python3
"""Final length and footprint radius of the Taylor bar (problems/sph_taylor_bar.yaml) from a
run's fields.h5, against the benchmark's converged finite-element values.

The run holds the rod (or its quarter) above the wall z = 0. A particle stands
for a cube of the spacing, so the length is the highest particle centre plus half a spacing,
and the footprint radius is the largest distance from the axis in the first particle layer
plus half a spacing.

Usage: scripts/taylor_bar.py RUN_DIR [--spacing 0.0004] [--check 0.05]
"""
import argparse
import sys

import h5py
import numpy as np

L0 = 32.4e-3
REFERENCE_LENGTH = 21.45e-3  # 21.42-21.48 mm, converged FE solutions (problem file)
REFERENCE_RADIUS = 7.15e-3   # 7.11-7.23 mm


def measure(run_dir, spacing):
    with h5py.File(f"{run_dir}/fields.h5", "r") as f:
        x0 = f["geometry/coordinates"][:]
        last = sorted(k for k in f if k.startswith("step_"))[-1]
        x = x0 + f[f"{last}/displacement"][:]
        strain = f[f"{last}/plastic_strain"][:]
    rod = x0[:, 2] > 0.0
    length = x[rod, 2].max() + 0.5 * spacing
    first_layer = rod & (x0[:, 2] < spacing)
    radius = np.hypot(x[first_layer, 0], x[first_layer, 1]).max() + 0.5 * spacing
    return length, radius, strain[rod].max()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run_dir")
    ap.add_argument("--spacing", type=float, default=0.4e-3)
    ap.add_argument("--check", type=float, default=0.0,
                    help="fail unless the length is within this fraction of the reference")
    args = ap.parse_args()
    length, radius, strain = measure(args.run_dir, args.spacing)
    dl = length / REFERENCE_LENGTH - 1.0
    dr = radius / REFERENCE_RADIUS - 1.0
    print(f"final length {1e3 * length:.3f} mm (reference {1e3 * REFERENCE_LENGTH:.2f}, "
          f"{100 * dl:+.2f}%), L/L0 {length / L0:.4f}; footprint radius {1e3 * radius:.3f} mm "
          f"(reference {1e3 * REFERENCE_RADIUS:.2f}, {100 * dr:+.2f}%); largest plastic strain "
          f"{strain:.3f}")
    if args.check > 0.0 and abs(dl) > args.check:
        sys.exit(f"final length off by {100 * dl:+.2f}% (allowed {100 * args.check:g}%)")


if __name__ == "__main__":
    main()
