#!/usr/bin/python3
"""A spherical cavity under internal pressure (problems/sphere_cavity_3d.yaml): the octant of a
cube of side 2.5 about a cavity of radius a = 1 at its corner, pressure p = 100, rollers on the
three planes through the centre and the unbounded body's exact traction on the outer faces, so
that the closed form (Lame 1852; Timoshenko & Goodier 1970, sec. 137) holds in the whole model:
u_r = p a^3 / (4 G r^2), sigma_rr = -p a^3 / r^3, sigma_tt = p a^3 / (2 r^3).

- meshfree RK (linear basis) at spacings 0.5 and 0.25: the rates of the energy and L2 errors at
  least 0.9 and 1.8 (theory 1 and 2; measured 1.68 and 2.78), the cavity's radial displacement
  within 4% at 0.25 (measured -3.1%; -0.5% at 0.125) and the hoop stress along the diagonal within
  12% of p / 2 at 0.25 (measured 10% at the wall, where a boundary point's stress is poorest),
  both errors smaller at 0.25 than at 0.5;
- the cavity's pressure resultant p pi a^2 / 4 on each axis, from the face points on the sphere,
  to 1e-4 (the sphere's Gauss points integrate the area exactly, the normal's components to
  about 2e-5);
- two MPI ranks equal one to 1e-8;
- gmsh's tet10 of the cube cut by the ball (OpenCASCADE's boolean) at sizes 0.5 and 0.25: rates
  against h = DOFs^(-1/3) of at least 1.5 (energy) and 2.5 (L2) (theory 2 and 3; measured 1.68
  and 2.89, the sphere's quadratic facets limiting the energy), the cavity's radial displacement
  within 0.5% at 0.25 (measured +0.2%).

- with --plastic, the elastic-perfectly plastic cavity (problems/sphere_cavity_plastic_3d.yaml,
  meshfree RK at spacing 0.25) pressed until Hill's plastic zone reaches c = 1.4 a: the samples
  along the diagonal yield up to r = c and no farther (the zone's edge within a spacing of c;
  measured: the last yielding sample at 1.4, the first elastic one at 1.5), sigma_rr in the
  plastic zone within 10% of p (measured 7.9%, the linear basis's stress at the wall and at the
  kink of the edge), and u_r in the elastic zone within 6% of sigma_y c^3 / (6 G r^2) (measured
  4.9%; the elastic cavity's own error along the diagonal at this spacing reaches 3.9%).

    sphere_cavity_verification.py MESHFREE ROOT [--plastic]
"""
import csv
import math
import os
import sys
import tempfile

from meshfree_run import Checks, run_meshfree

MESHFREE, ROOT = sys.argv[1], sys.argv[2]
PLASTIC = "--plastic" in sys.argv[3:]
PROBLEM = os.path.join(ROOT, "problems",
                       "sphere_cavity_plastic_3d.yaml" if PLASTIC else "sphere_cavity_3d.yaml")
E, NU, P, A = 200000.0, 0.3, 100.0, 1.0
G = E / (2.0 * (1.0 + NU))
D = 1.0 / math.sqrt(3.0)
# the diagonal from the cavity's wall (r = 1) to r = 2.4, inside the cube
DIAGONAL = ("output.lines=[{name: diagonal, from: [%r, %r, %r], to: [%r, %r, %r], points: %d}]"
            % (D, D, D, 2.4 * D, 2.4 * D, 2.4 * D, 15 if PLASTIC else 8))
check = Checks()


def run(out, sets=(), ranks=1):
    summary = run_meshfree(MESHFREE, PROBLEM, out, [DIAGONAL] + list(sets), ranks)
    with open(os.path.join(out, "line_diagonal.csv")) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    return summary, rows


def wall_displacement_error(rows):
    """u_r at the cavity's wall against p a^3 / (4 G a^2), relative."""
    r = rows[0]
    rad = math.sqrt(r["x"] ** 2 + r["y"] ** 2 + r["z"] ** 2)
    ur = (r["ux"] * r["x"] + r["uy"] * r["y"] + r["uz"] * r["z"]) / rad
    return ur / (P * A ** 3 / (4.0 * G * rad ** 2)) - 1.0


def hoop_error(rows):
    """The largest |sigma_tt - p a^3 / (2 r^3)| / (p / 2) along the diagonal; sigma_tt along
    (1, -1, 0) / sqrt 2 is (sigma_xx + sigma_yy) / 2 - sigma_xy."""
    worst = 0.0
    for r in rows:
        rad = math.sqrt(r["x"] ** 2 + r["y"] ** 2 + r["z"] ** 2)
        hoop = 0.5 * (r["stress_xx"] + r["stress_yy"]) - r["stress_xy"]
        worst = max(worst, abs(hoop - P * A ** 3 / (2.0 * rad ** 3)) / (0.5 * P))
    return worst


def errors(summary):
    return summary["results"]["error_energy_relative"], summary["results"]["error_l2_relative"]


def check_meshfree(work):
    runs = {h: run(os.path.join(work, f"rk_{h}"), [f"discretisation.spacing={h}"])
            for h in (0.5, 0.25)}
    (e0, l0), (e1, l1) = errors(runs[0.5][0]), errors(runs[0.25][0])
    re, rl = math.log(e0 / e1, 2.0), math.log(l0 / l1, 2.0)
    check(re >= 0.9 and rl >= 1.8,
          f"meshfree RK: energy error {e0:.3e} -> {e1:.3e} (rate {re:.2f} >= 0.9), L2 {l0:.3e} "
          f"-> {l1:.3e} (rate {rl:.2f} >= 1.8)")
    u0, u1 = wall_displacement_error(runs[0.5][1]), wall_displacement_error(runs[0.25][1])
    check(abs(u1) <= 0.04 and abs(u1) < abs(u0),
          f"meshfree RK: the cavity's radial displacement {u0:+.2%} at 0.5, {u1:+.2%} at 0.25 "
          f"(within 4%)")
    s0, s1 = hoop_error(runs[0.5][1]), hoop_error(runs[0.25][1])
    check(s1 <= 0.12 and s1 < s0,
          f"meshfree RK: hoop stress along the diagonal within {s0:.2%} of p/2 at 0.5, {s1:.2%} "
          f"at 0.25 (within 12%)")
    force = runs[0.25][0]["results"]["boundary"]["cavity_pressure"]["applied_force"]
    exact = P * math.pi * A * A / 4.0
    worst = max(abs(f / exact - 1.0) for f in force)
    check(worst <= 1e-4, f"the cavity's pressure resultant {force} against p pi a^2 / 4 = "
                         f"{exact:.6f} on each axis (worst {worst:.1e}, within 1e-4)")
    return runs[0.25]


def check_ranks(work, one):
    import numpy as np
    two = run(os.path.join(work, "rk_two_ranks"), ["discretisation.spacing=0.25"], ranks=2)
    a = np.array([[r["ux"], r["uy"], r["uz"]] for r in one[1]])
    b = np.array([[r["ux"], r["uy"], r["uz"]] for r in two[1]])
    diff = np.abs(a - b).max() / np.abs(a).max()
    check(two[0]["mpi_ranks"] == 2 and diff <= 1e-8, f"two MPI ranks equal one: displacement along the diagonal within "
                        f"{diff:.1e} (<= 1e-8)")


def check_tet10(work):
    runs = {h: run(os.path.join(work, f"tet10_{h}"),
                   [f"discretisation.spacing={h}", "discretisation.method=fem",
                    "discretisation.fem.element=tet10"]) for h in (0.5, 0.25)}
    h = {k: v[0]["counts"]["dofs"] ** (-1.0 / 3.0) for k, v in runs.items()}
    (e0, l0), (e1, l1) = errors(runs[0.5][0]), errors(runs[0.25][0])
    ratio = math.log(h[0.5] / h[0.25])
    re, rl = math.log(e0 / e1) / ratio, math.log(l0 / l1) / ratio
    check(re >= 1.5 and rl >= 2.5,
          f"tet10: energy error {e0:.3e} -> {e1:.3e} (rate {re:.2f} >= 1.5), L2 {l0:.3e} -> "
          f"{l1:.3e} (rate {rl:.2f} >= 2.5)")
    u1 = wall_displacement_error(runs[0.25][1])
    check(abs(u1) <= 0.005, f"tet10: the cavity's radial displacement {u1:+.2%} at 0.25 "
                            f"(within 0.5%)")


def check_plastic(work):
    sy, c = 240.0, 1.4
    p = 2.0 * sy / 3.0 + 2.0 * sy * math.log(c / A)
    _, rows = run(os.path.join(work, "plastic"))
    last = max(r["increment"] for r in rows)
    radial = []
    for r in (r for r in rows if r["increment"] == last):
        x = (r["x"], r["y"], r["z"])
        rad = math.sqrt(sum(q * q for q in x))
        n = [q / rad for q in x]
        s = [[r["stress_xx"], r["stress_xy"], r["stress_xz"]],
             [r["stress_xy"], r["stress_yy"], r["stress_yz"]],
             [r["stress_xz"], r["stress_yz"], r["stress_zz"]]]
        srr = sum(n[i] * s[i][j] * n[j] for i in range(3) for j in range(3))
        ur = sum(r[k] * q for k, q in zip(("ux", "uy", "uz"), x)) / rad
        radial.append((rad, srr, ur, r["plastic_strain"]))
    plastic = [r for r in radial if r[3] > 0.0]
    elastic = [r for r in radial if r[3] == 0.0]
    edge_in, edge_out = max(r[0] for r in plastic), min(r[0] for r in elastic)
    check(edge_in < edge_out and edge_in >= c - 0.25 and edge_out <= c + 0.25,
          f"plastic cavity: the samples yield up to r = {edge_in:.2f}, not from {edge_out:.2f} "
          f"(Hill's edge c = {c})")
    s_err = max(abs(srr - (-p + 2.0 * sy * math.log(rad / A))) / p
                for rad, srr, _, _ in radial if rad <= edge_in)
    u_err = max(abs(ur / (sy * c ** 3 / (6.0 * G * rad ** 2)) - 1.0)
                for rad, _, ur, _ in radial if rad >= edge_out)
    check(s_err <= 0.10 and u_err <= 0.06,
          f"plastic cavity: sigma_rr in the plastic zone within {s_err:.1%} of p = {p:.1f} "
          f"(<= 10%), u_r in the elastic zone within {u_err:.1%} (<= 6%)")


with tempfile.TemporaryDirectory() as work:
    if PLASTIC:
        check_plastic(work)
    else:
        one = check_meshfree(work)
        check_ranks(work, one)
        check_tet10(work)
sys.exit(1 if check.failed else 0)
