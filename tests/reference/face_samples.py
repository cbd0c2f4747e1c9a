#!/usr/bin/python3
"""output.faces of 3D bodies: displacement and stress sampled on a named face or on the body's
section by a flat box, as passive material points, written as face_<name>.csv per increment and
as a ParaView point series (face_<name>.h5/.xmf: the same values, a step per state).

- the elastoplastic block in uniaxial stress (problems/block_uniaxial_3d.yaml, stretched and
  pushed back in 8 increments): the field is homogeneous, so at every increment every sample of
  the loaded end and of the section z = 1 carries sigma_zz = the end's reaction / its area (to
  1e-8 of the largest), the other stress components zero (1e-8 of it), u_z = the end's
  displacement at z = 2 and half of it at z = 1 (1e-7 of the largest: the penalty's gap), and
  the samples yield; two MPI ranks write the same files (1e-8 of each quantity's largest);
- the spherical cavity (problems/sphere_cavity_3d.yaml, spacing 0.25): the cavity's face samples
  lie on the sphere (r = 1 to 1e-12) and their mean radial displacement is within 4% of
  p a^3 / (4 G a^2) (measured -0.7%; the meshfree solution's error at the wall on the diagonal
  is -3.1%), and the end z = 0's samples keep out of the cavity; in tet10 the cavity's samples
  are found in the elements and their mean u_r is within 1% (measured -0.05%).

    face_samples.py MESHFREE ROOT
"""
import csv
import math
import os
import sys
import tempfile

from meshfree_run import Checks, run_meshfree

MESHFREE, ROOT = sys.argv[1], sys.argv[2]
check = Checks()


def run(problem, out, sets=(), ranks=1):
    run_meshfree(MESHFREE, os.path.join(ROOT, "problems", problem + ".yaml"), out, sets, ranks)


def table(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


BLOCK = ["steps=[{name: stretch, load_factor: 0.02, increments: 4}, "
         "{name: compress, load_factor: -0.01, increments: 4}]",
         "output.faces=[{name: end, face: front, spacing: 0.5}, "
         "{name: middle, box: [[0, 0, 1], [1, 1, 1]], spacing: 0.25}]"]


def check_block(work):
    one, two = os.path.join(work, "block"), os.path.join(work, "block_two_ranks")
    run("block_uniaxial_3d", one, BLOCK)
    history = {int(h["increment"]): h for h in table(os.path.join(one, "history.csv"))}
    scale = max(abs(h["reaction_end_z"]) for h in history.values())
    worst_s = worst_other = worst_u = 0.0
    counts = {}
    for face, height in (("end", 2.0), ("middle", 1.0)):
        rows = table(os.path.join(one, f"face_{face}.csv"))
        counts[face] = sum(1 for r in rows if r["increment"] == 0)
        for r in rows:
            h = history[int(r["increment"])]
            worst_s = max(worst_s, abs(r["stress_zz"] - h["reaction_end_z"]) / scale)
            worst_other = max(worst_other, max(abs(r[k]) for k in (
                "stress_xx", "stress_yy", "stress_yz", "stress_xz", "stress_xy")) / scale)
            worst_u = max(worst_u, abs(r["uz"] - h["factor_end"] * height / 2.0) / 0.02)
    # u_z misses the held value by the penalty's compliance, sigma / alpha = 330 / 8e11 mm: 2e-8
    # of the stretch
    check(counts == {"end": 9, "middle": 25},
          f"samples: 3 x 3 on the end (spacing 0.5), 5 x 5 on the section (0.25): {counts}")
    check(worst_s <= 1e-8 and worst_other <= 1e-8 and worst_u <= 1e-7,
          f"block: sigma_zz = reaction / area within {worst_s:.1e}, other components "
          f"{worst_other:.1e} (<= 1e-8), u_z within {worst_u:.1e} (<= 1e-7) at every increment")
    check_point_series(one, "middle")
    plastic = max(r["plastic_strain"] for r in table(os.path.join(one, "face_middle.csv")))
    check(plastic > 0.0, f"block: the samples yield with the body (plastic strain {plastic:.3e})")
    run("block_uniaxial_3d", two, BLOCK, ranks=2)
    diff = 0.0
    for face in ("end", "middle"):
        a = table(os.path.join(one, f"face_{face}.csv"))
        b = table(os.path.join(two, f"face_{face}.csv"))
        if len(a) != len(b):
            diff = math.inf
            break
        diff = max(diff, largest_difference(a, b))
    check(diff <= 1e-8, f"two MPI ranks write the same face samples (within {diff:.1e} of each "
                        f"quantity's largest value)")


def check_point_series(out, face):
    """face_<name>.h5/.xmf, the ParaView point series, holds the CSV's values: a step per state,
    the displacement as a vector."""
    import h5py
    import numpy as np
    rows = table(os.path.join(out, f"face_{face}.csv"))
    worst, steps = 0.0, 0
    with h5py.File(os.path.join(out, f"face_{face}.h5"), "r") as f:
        xyz = np.array(f["geometry/coordinates"])
        for name in sorted(k for k in f.keys() if k.startswith("step_")):
            state = [r for r in rows if r["increment"] == steps]
            steps += 1
            u = np.array(f[name]["displacement"])
            szz = np.array(f[name]["stress_zz"])
            # the CSV carries 12 significant digits
            worst = max(worst, max(max(abs(a - b) / max(1.0, abs(b)) for a, b in (
                (u[k][2], r["uz"]), (szz[k], r["stress_zz"]), (xyz[k][0], r["x"])))
                for k, r in enumerate(state)))
    states = len({r["increment"] for r in rows})
    check(steps == states and worst <= 1e-11 and os.path.exists(os.path.join(out, f"face_{face}.xmf")),
          f"face_{face}.h5/.xmf: {steps} steps for {states} states, equal to the CSV "
          f"(largest relative difference {worst:.1e}, <= 1e-11)")


def largest_difference(a, b):
    """The largest difference of two sample tables, each quantity's (displacement, stress,
    plastic strain, position) against its largest magnitude in `a`."""
    groups = {"u": ("ux", "uy", "uz"), "x": ("increment", "x", "y", "z"),
              "stress": ("stress_xx", "stress_yy", "stress_zz", "stress_yz", "stress_xz",
                         "stress_xy", "von_mises"), "plastic": ("plastic_strain",)}
    worst = 0.0
    for keys in groups.values():
        scale = max(abs(r[k]) for r in a for k in keys) or 1.0
        worst = max(worst, max(abs(ra[k] - rb[k]) for ra, rb in zip(a, b) for k in keys) / scale)
    return worst


def check_cavity(work):
    out = os.path.join(work, "cavity")
    run("sphere_cavity_3d", out, ["output.faces=[{name: wall, face: cavity, spacing: 0.2}, "
                                  "{name: base, face: back, spacing: 0.25}]"])
    G = 200000.0 / (2.0 * 1.3)
    wall = table(os.path.join(out, "face_wall.csv"))
    off = max(abs(math.sqrt(r["x"] ** 2 + r["y"] ** 2 + r["z"] ** 2) - 1.0) for r in wall)
    ur = sum((r["ux"] * r["x"] + r["uy"] * r["y"] + r["uz"] * r["z"]) for r in wall) / len(wall)
    error = ur / (100.0 / (4.0 * G)) - 1.0
    check(len(wall) > 20 and off <= 1e-12 and abs(error) <= 0.04,
          f"cavity: {len(wall)} samples on the sphere (off it by {off:.1e}), mean u_r "
          f"{error:+.2%} from the closed form (within 4%)")
    base = table(os.path.join(out, "face_base.csv"))
    inside = min(math.sqrt(r["x"] ** 2 + r["y"] ** 2) for r in base)
    check(len(base) == 11 * 11 - 15 and inside >= 1.0 - 1e-9,
          f"cavity: {len(base)} samples on the end z = 0 (11 x 11 less the 15 inside the cavity), "
          f"none in it (nearest the centre {inside:.3f})")


def check_cavity_tet10(work):
    """Face samples on tetrahedra: the points are located in the elements (the sphere's samples
    on or just off the quadratic facets)."""
    out = os.path.join(work, "cavity_tet10")
    run("sphere_cavity_3d", out, ["discretisation.method=fem", "discretisation.fem.element=tet10",
                                  "output.faces=[{name: wall, face: cavity, spacing: 0.2}]"])
    G = 200000.0 / (2.0 * 1.3)
    wall = table(os.path.join(out, "face_wall.csv"))
    ur = sum((r["ux"] * r["x"] + r["uy"] * r["y"] + r["uz"] * r["z"]) for r in wall) / len(wall)
    error = ur / (100.0 / (4.0 * G)) - 1.0
    check(len(wall) > 20 and abs(error) <= 0.01,
          f"cavity in tet10: {len(wall)} samples on the sphere, mean u_r {error:+.2%} from the "
          f"closed form (within 1%)")


with tempfile.TemporaryDirectory() as work:
    check_block(work)
    check_cavity(work)
    check_cavity_tet10(work)
sys.exit(1 if check.failed else 0)
