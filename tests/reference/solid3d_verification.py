#!/usr/bin/python3
"""3D meshfree elasticity against closed forms (problems/patch_test_3d.yaml and
problems/thick_cylinder_3d.yaml):

- the 3D patch test: a linear field reproduced in the energy norm to 1e-10 with the variationally
  consistent correction (VCI) on 2 x 2 x 2 Gauss points of cells not aligned with the nodes, and
  not without it (the test can fail); the L2 error is the held face's penalty compliance
  (|gap| ~ sigma / alpha), asserted at 1e-6;
- Lame's thick cylinder in plane strain at spacings 0.5, 0.25, 0.125: the linear basis's rates,
  energy >= 0.9 and L2 >= 1.8 from 0.25 to 0.125 (theory 1 and 2: Belytschko, Lu & Gu 1994), the
  bore's pressure resultant p a depth from the face points on the exact arcs (to 1e-8), CG + GAMG with the six
  rigid-body modes equal to MUMPS to 1e-8 in at most 25 iterations (15 with SOR on the finest
  level, 50 with Jacobi), and two MPI ranks equal to one to 1e-8;
- the elastic-perfectly plastic cylinder (problems/thick_cylinder_plastic_3d.yaml, spacing 0.2)
  collapses within 1% of the plane-strain limit pressure, meshfree and in 20-node bricks on their
  default (reduced) rule in plasticity, which the full rule locks past (2 / sqrt 3) sigma_y ln(b / a)
  (Hill 1950, ch. V): the limit taken as the first pressure whose increment's secant stiffness
  dp/du (u the bore's mean radial displacement) falls below 1% of the elastic one;
- the elastoplastic block (problems/block_uniaxial_3d.yaml) on two ranks equals one to 1e-8, and
  its field series (every 10th increment) hold one whole grid per time;
- the variations a user tries first on the cylinder: the quadratic basis and a refinement box at
  the bore lower the energy error, box supports run (measured 3.2%, 0.66% and 4.8% against
  5.4%);
- a refinement box given in 3D keeps the patch test to 1e-10 in energy, meshfree, in both bricks
  and in tet4;
- finite elements (the plane Q4/Q8 mesh extruded into 8- and 20-node bricks): the patch test to
  1e-10 in energy, and Lame's cylinder in 20-node bricks at its rates less a margin for the
  pre-asymptotic spread (theory: energy 2, L2 3, Strang & Fix 1973 ch. 3; measured 1.78, 3.02);
- the volumetric strain of the cell's mean (B-bar) keeps the patch test to 1e-10 in energy,
  meshfree and in both bricks, and unlocks Lame's cylinder (errors and stresses along a radius)
  and hollow sphere at nu = 0.4999;
- gmsh's tetrahedra of the same prism: the patch test to 1e-10 in energy in tet4 and tet10, Lame's
  cylinder at spacings 0.5, 0.25, 0.125 converging at the rates of its degree (tet4: energy 1, L2
  2; tet10: energy 2, L2 3), measured as least-squares slopes against h = DOFs^(-1/3) since
  Delaunay meshes of halved spacing are not nested (measured tet4 1.08, 2.15; tet10 1.79, 2.90),
  a refinement box at the bore lowering tet10's energy error to less than half, the elastic-
  perfectly plastic cylinder in tet10 collapsing within 1% of its limit pressure, and tet10 on
  two MPI ranks (each meshing the body itself) equal to one to 1e-8.

    solid3d_verification.py MESHFREE ROOT
"""
import csv
import math
import os
import subprocess
import sys
import tempfile

from meshfree_run import Checks, run_meshfree

MESHFREE, ROOT = sys.argv[1], sys.argv[2]
PROBLEMS = os.path.join(ROOT, "problems")


def run(problem, out, sets=(), ranks=1):
    return run_meshfree(MESHFREE, os.path.join(PROBLEMS, problem + ".yaml"), out, sets, ranks)


# A radius at 45 degrees at mid-depth, inside the quarter (a line on the symmetry faces samples
# the penalty-held boundary layer, where the linear basis' stress is poorest).
RADIAL_LINE = ("output.lines=[{name: radial, from: [0.7071067811865476, 0.7071067811865476, 0.25], "
               "to: [2.8284271247461903, 2.8284271247461903, 0.25], points: 31}]")


def radial_line(out):
    with open(os.path.join(out, "line_radial.csv")) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def radial_line_error(out):
    """The largest |sigma - Lame| / p of sigma_rr and sigma_tt along the line (a = 1, b = 5,
    p = 100: sigma_rr = A - B / r^2, sigma_tt = A + B / r^2, A = p a^2 / (b^2 - a^2),
    B = A b^2; Timoshenko & Goodier 1970, sec. 28). At 45 degrees sigma_rr and sigma_tt are
    (sigma_xx + sigma_yy) / 2 + sigma_xy and (sigma_xx + sigma_yy) / 2 - sigma_xy."""
    p, a, b = 100.0, 1.0, 5.0
    A = p * a * a / (b * b - a * a)
    B = A * b * b
    worst = 0.0
    for r in radial_line(out):
        rad = math.hypot(r["x"], r["y"])
        mean = 0.5 * (r["stress_xx"] + r["stress_yy"])
        worst = max(worst, abs(mean + r["stress_xy"] - (A - B / rad ** 2)) / p,
                    abs(mean - r["stress_xy"] - (A + B / rad ** 2)) / p)
    return worst


check = Checks()


def nodal_displacement(out):
    import h5py
    import numpy as np
    with h5py.File(os.path.join(out, "fields.h5"), "r") as f:
        steps = sorted(k for k in f.keys() if k.startswith("step_"))
        return np.array(f[steps[-1]]["displacement"])


LIMIT_PRESSURE = 2.0 / math.sqrt(3.0) * 240.0 * math.log(2.0)


def limit_pressure(out, sets=()):
    """Under load control past the limit pressure no state is in equilibrium: the run stops there
    (exit 3, its increments in out/stopped) with the last converged pressure at the limit, or
    runs on with increments that no longer move the bore's pressure against its displacement.
    Returns (the limit found or None, whether the run stopped)."""
    cmd = [MESHFREE, "run", os.path.join(PROBLEMS, "thick_cylinder_plastic_3d.yaml"), "--out", out]
    for a in ["discretisation.spacing=0.2"] + list(sets):
        cmd += ["--set", a]
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    stopped = done.returncode == 3 and "limit load" in done.stdout
    if done.returncode != 0 and not stopped:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {done.returncode}:\n{done.stdout[-2000:]}")
    with open(os.path.join(out, "stopped" if stopped else "", "history.csv")) as f:
        rows = list(csv.DictReader(f))
    p = [float(r["factor_bore_pressure"]) for r in rows]
    u = [-float(r["normal_displacement_bore_pressure"]) for r in rows]
    elastic = p[1] / u[1]
    # past the collapse an increment may not move the bore at all: no stiffness left
    limit = next((p[i] for i in range(1, len(p))
                  if p[i] - p[i - 1] < 0.01 * elastic * (u[i] - u[i - 1])
                  or u[i] <= u[i - 1]), p[-1] if stopped else None)
    return limit, stopped


def check_limit_pressure(out, sets=(), what="thick cylinder"):
    limit, stopped = limit_pressure(out, sets)
    exact = LIMIT_PRESSURE
    check(limit is not None and abs(limit / exact - 1.0) <= 0.01,
          f"{what} collapses at {limit} MPa against the limit pressure {exact:.3f} "
          f"({'-' if limit is None else f'{limit / exact - 1.0:+.2%}'}, within 1%"
          f"{'; the run stopped there' if stopped else ''})")


def check_bricks_collapse(work):
    """20-node bricks in plasticity take the reduced rule by default: the cylinder collapses at
    its limit pressure (measured: stiffness gone at 191.61 MPa, -0.25%, the run stopping at
    192.03); on the full 3 x 3 x 3 rule its isochoric flow locks and the body carries the whole
    schedule to 199.77 MPa, 4% past a limit that no body can carry."""
    fem = ["discretisation.method=fem", "discretisation.fem.element=hex20"]
    check_limit_pressure(os.path.join(work, "limit_hex20"), fem,
                         "thick cylinder in 20-node bricks (their default rule in plasticity)")
    _, stopped = limit_pressure(os.path.join(work, "limit_hex20_full"),
                                fem + ["discretisation.fem.order=3"])
    check(not stopped, "on the full 3 x 3 x 3 rule the bricks lock: they carry the schedule to "
                       f"199.77 MPa, 4% past the limit {LIMIT_PRESSURE:.3f}")


def check_variations(work, linear):
    """What a user changes first, at spacing 0.25 against the linear basis's energy error there:
    the quadratic basis and a refinement box at the bore each lower it; box supports run too."""
    quadratic = run("thick_cylinder_3d", os.path.join(work, "cyl_quadratic"),
                    ["discretisation.spacing=0.25", "discretisation.basis=quadratic"])
    boxes = run("thick_cylinder_3d", os.path.join(work, "cyl_boxes"),
                ["discretisation.spacing=0.25", "discretisation.support=rectangular"])
    refined = run("thick_cylinder_3d", os.path.join(work, "cyl_refined"),
                  ["discretisation.spacing=0.25",
                   "discretisation.refinement=[{box: [[0, 0], [2, 2]], spacing: 0.125}]"])
    e_q, e_b, e_r = (x["results"]["error_energy_relative"] for x in (quadratic, boxes, refined))
    check(e_q < linear and e_r < 0.5 * linear and e_b < 2.0 * linear,
          f"at spacing 0.25, energy error {linear:.2e} linear: quadratic {e_q:.2e}, box supports "
          f"{e_b:.2e}, a refinement box of 0.125 at the bore {e_r:.2e}")


def check_bricks(work):
    for element in ("hex8", "hex20", "q4"):  # q4: hex8 by the name of the plane element
        s = run("patch_test_3d", os.path.join(work, f"patch_{element}"),
                ["discretisation.method=fem", f"discretisation.fem.element={element}"])
        e = s["results"]["error_energy_relative"]
        check(e <= 1e-10, f"patch test in {element} bricks: energy error {e:.1e} "
                          f"(<= 1e-10), {s['method']}")
    errors = []
    for h in (0.25, 0.125):
        s = run("thick_cylinder_3d", os.path.join(work, f"cyl_fe_{h}"),
                ["discretisation.method=fem", f"discretisation.spacing={h}"])
        errors.append((s["results"]["error_energy_relative"], s["results"]["error_l2_relative"]))
    (e1, l1), (e2, l2) = errors
    rate_e, rate_l2 = math.log(e1 / e2) / math.log(2.0), math.log(l1 / l2) / math.log(2.0)
    check(rate_e >= 1.6 and rate_l2 >= 2.7,
          f"thick cylinder in 20-node bricks: energy {e1:.2e} -> {e2:.2e} (rate {rate_e:.2f}, "
          f">= 1.6), L2 {l1:.2e} -> {l2:.2e} (rate {rate_l2:.2f}, >= 2.7)")


def check_boxes_along_z(work):
    """A refinement box given in 3D (its own layers over a z range off the base levels) keeps the
    patch test to 1e-10 in energy: meshfree with VCI, in both bricks (the layers through the
    whole section) and in tet4 (gmsh's box field over the range)."""
    box = "discretisation.refinement=[{box: [[0.3, 0.2, 0.1], [0.7, 0.5, 0.3]], spacing: 0.0625}]"
    for element in ("meshfree", "hex8", "hex20", "tet4"):
        method = [] if element == "meshfree" else [
            "discretisation.method=fem", f"discretisation.fem.element={element}"]
        s = run("patch_test_3d", os.path.join(work, f"patch_z_{element}"), [box] + method)
        e = s["results"]["error_energy_relative"]
        check(e <= 1e-10, f"patch test, {element}, a refinement box given in 3D: energy error "
                          f"{e:.1e} (<= 1e-10), {s['method']}")


def check_cell_mean(work):
    """The volumetric strain of the cell's mean (quadrature.volumetric_strain: cell_mean, B-bar)
    keeps the patch test (meshfree with VCI and both bricks), and unlocks Lame's cylinder at
    nu = 0.4999 (spacing 0.25; measured meshfree L2 12.5% -> 1.07%, energy 34% -> 7.2%; 20-node
    bricks 1.09% -> 0.026%, 9.7% -> 0.67%, their nu = 0.3 errors 0.028% and 0.66%), the
    stresses along a radius too (largest error / p: meshfree 77 -> 0.45, hex20 8.1 -> 0.005)."""
    cell_mean = ["discretisation.quadrature.volumetric_strain=cell_mean"]
    fem = ["discretisation.method=fem"]
    nearly_incompressible = ["materials[0].nu=0.4999"]
    for name, sets, l2_max, energy_max, line_max in (("meshfree", [], 0.012, 0.08, 0.5),
                                                     ("hex20", fem, 3e-4, 7.5e-3, 0.01)):
        errors = {}
        for mode in ("pointwise", "cell_mean"):
            out = os.path.join(work, f"cyl_incompressible_{name}_{mode}")
            r = run("thick_cylinder_3d", out,
                    sets + nearly_incompressible + [RADIAL_LINE,
                    f"discretisation.quadrature.volumetric_strain={mode}"])["results"]
            errors[mode] = (r["error_l2_relative"], r["error_energy_relative"],
                            radial_line_error(out))
        (l2_p, e_p, line_p), (l2_c, e_c, line_c) = errors["pointwise"], errors["cell_mean"]
        check(l2_c <= l2_max and e_c <= energy_max and e_c < 0.25 * e_p,
              f"Lame's cylinder at nu = 0.4999, {name}: pointwise L2 {l2_p:.2e}, energy "
              f"{e_p:.2e}; cell mean L2 {l2_c:.2e} (<= {l2_max}), energy {e_c:.2e} "
              f"(<= {energy_max}, < a quarter of pointwise)")
        # the line's sample points take their cells' mean volumetric strain too
        check(line_c <= line_max,
              f"Lame's cylinder at nu = 0.4999, {name}: sigma_rr and sigma_tt along a radius, "
              f"largest error / p {line_p:.3g} pointwise, {line_c:.3g} cell mean (<= {line_max})")
    # hex20 also by its plane element's name q8, which reads as the same brick
    for name, sets in (("meshfree", []), ("hex8", fem + ["discretisation.fem.element=hex8"]),
                       ("hex20", fem + ["discretisation.fem.element=hex20"]),
                       ("q8", fem + ["discretisation.fem.element=q8"])):
        s = run("patch_test_3d", os.path.join(work, f"patch_cell_mean_{name}"), sets + cell_mean)
        e = s["results"]["error_energy_relative"]
        check(e <= 1e-10, f"patch test with the cell-mean volumetric strain, {s['method']}: "
                          f"energy error {e:.1e} (<= 1e-10)")


def check_cell_mean_sphere(work):
    """Cells a spherical cavity cuts take their mean too: Lame's hollow sphere at nu = 0.4999
    (problems/sphere_cavity_3d.yaml; measured L2 23.8% -> 3.8%, energy 45% -> 12.3%)."""
    errors = {}
    for mode in ("pointwise", "cell_mean"):
        r = run("sphere_cavity_3d", os.path.join(work, f"sphere_incompressible_{mode}"),
                ["materials[0].nu=0.4999",
                 f"discretisation.quadrature.volumetric_strain={mode}"])["results"]
        errors[mode] = (r["error_l2_relative"], r["error_energy_relative"])
    (l2_p, e_p), (l2_c, e_c) = errors["pointwise"], errors["cell_mean"]
    check(l2_c <= 0.045 and e_c < 0.3 * e_p,
          f"Lame's hollow sphere at nu = 0.4999: pointwise L2 {l2_p:.2e}, energy {e_p:.2e}; cell "
          f"mean L2 {l2_c:.2e} (<= 0.045), energy {e_c:.2e} (< 0.3 of pointwise)")


def slope(dofs, errors):
    """Least-squares slope of log(error) against log(h), h = DOFs^(-1/3)."""
    x = [-math.log(n) / 3.0 for n in dofs]
    y = [math.log(e) for e in errors]
    mx, my = sum(x) / len(x), sum(y) / len(y)
    return (sum((a - mx) * (b - my) for a, b in zip(x, y)) /
            sum((a - mx) ** 2 for a in x))


def check_tets(work):
    fem = ["discretisation.method=fem"]
    for element in ("tet4", "tet10"):
        s = run("patch_test_3d", os.path.join(work, f"patch_{element}"),
                fem + [f"discretisation.fem.element={element}"])
        e = s["results"]["error_energy_relative"]
        check(e <= 1e-10, f"patch test in {element}: energy error {e:.1e} (<= 1e-10)")
    wanted = {"tet4": (0.9, 1.8), "tet10": (1.6, 2.7)}
    for element, (want_e, want_l2) in wanted.items():
        rows = []
        for h in (0.5, 0.25, 0.125):
            s = run("thick_cylinder_3d", os.path.join(work, f"cyl_{element}_{h}"),
                    fem + [f"discretisation.fem.element={element}", f"discretisation.spacing={h}"])
            r = s["results"]
            rows.append((s["counts"]["dofs"], r["error_energy_relative"], r["error_l2_relative"]))
        dofs, energy, l2 = zip(*rows)
        rate_e, rate_l2 = slope(dofs, energy), slope(dofs, l2)
        check(rate_e >= want_e and rate_l2 >= want_l2,
              f"thick cylinder in {element} ({' -> '.join(str(n) for n in dofs)} DOFs): energy "
              f"{energy[0]:.2e} -> {energy[-1]:.2e} (rate {rate_e:.2f}, >= {want_e}), L2 "
              f"{l2[0]:.2e} -> {l2[-1]:.2e} (rate {rate_l2:.2f}, >= {want_l2})")
    tet10 = fem + ["discretisation.fem.element=tet10", "discretisation.spacing=0.25"]
    plain = run("thick_cylinder_3d", os.path.join(work, "cyl_tet10_0.25"), tet10)
    refined = run("thick_cylinder_3d", os.path.join(work, "cyl_tet10_refined"),
                  tet10 + ["discretisation.refinement=[{box: [[0, 0], [2, 2]], spacing: 0.125}]"])
    e_p, e_r = (x["results"]["error_energy_relative"] for x in (plain, refined))
    check(e_r < 0.5 * e_p, f"tet10 at spacing 0.25: a refinement box of 0.125 at the bore lowers "
                           f"the energy error from {e_p:.2e} to {e_r:.2e} (< half)")
    check_limit_pressure(os.path.join(work, "limit_tet10"),
                         fem + ["discretisation.fem.element=tet10"], "thick cylinder in tet10")
    two = run("thick_cylinder_3d", os.path.join(work, "cyl_tet10_2"), tet10, ranks=2)
    one = nodal_displacement(os.path.join(work, "cyl_tet10_0.25"))
    diff = abs(nodal_displacement(os.path.join(work, "cyl_tet10_2")) - one).max() / abs(one).max()
    check(two["mpi_ranks"] == 2 and diff <= 1e-8,
          f"tet10 on 2 MPI ranks equals 1 to {diff:.1e} (<= 1e-8)")


BLOCK_AXIS = "output.lines=[{name: axis, from: [0.5, 0.5, 0], to: [0.5, 0.5, 2], points: 5}]"


def check_plastic_ranks(work):
    """The cyclic uniaxial block (elastoplastic, 40 increments) on 2 ranks equals 1 rank."""
    curves = []
    for ranks in (1, 2):
        out = os.path.join(work, f"block_{ranks}")
        run("block_uniaxial_3d", out, ["discretisation.spacing=0.5", "output.fields_every=10",
                                       BLOCK_AXIS], ranks=ranks)
        with open(os.path.join(out, "history.csv")) as f:
            curves.append([float(r["reaction_end_z"]) for r in csv.DictReader(f)])
    # The axis of the homogeneous block: its sample points carried through the 40 increments of
    # the cycle (Voce and kinematic hardening) carry the stress the end's reaction gives,
    # sigma_zz = R_z / (1 mm x 1 mm).
    with open(os.path.join(work, "block_1", "line_axis.csv")) as f:
        axis = list(csv.DictReader(f))
    worst = max(abs(float(r["stress_zz"]) - curves[0][int(float(r["increment"]))])
                for r in axis) / max(abs(v) for v in curves[0])
    check(len(axis) == 41 * 5 and worst <= 1e-6,
          f"output.lines along the block's axis, 41 states x 5 points: sigma_zz equals the "
          f"reaction per area to {worst:.1e} of the largest (<= 1e-6)")
    frames = subprocess.run(
        [sys.executable, os.path.join(ROOT, "tests", "cli", "xdmf_frames.py"), "--check",
         os.path.join(work, "block_1")], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    check(frames.returncode == 0, "the block's field and Gauss-point series: one grid per time, "
                                  "none empty (xdmf_frames.py --check)" + frames.stdout[-500:])
    largest = max(abs(v) for v in curves[0])
    diff = max(abs(a - b) for a, b in zip(*curves)) / largest
    check(len(curves[0]) == len(curves[1]) == 41 and diff <= 1e-8,
          f"elastoplastic block on 2 ranks equals 1 rank to {diff:.1e} of its largest force "
          f"(<= 1e-8)")


with tempfile.TemporaryDirectory() as work:
    s = run("patch_test_3d", os.path.join(work, "patch"))["results"]
    check(s["error_energy_relative"] <= 1e-10 and s["error_l2_relative"] <= 1e-6,
          f"patch test with VCI: energy error {s['error_energy_relative']:.2e} (<= 1e-10), "
          f"L2 error {s['error_l2_relative']:.2e} (<= 1e-6)")
    s = run("patch_test_3d", os.path.join(work, "patch_plain"),
            ["discretisation.quadrature.correction=none"])["results"]
    check(s["error_energy_relative"] >= 1e-4,
          f"patch test without VCI fails it: energy error {s['error_energy_relative']:.2e} (>= 1e-4)")

    errors, line_errors = [], []
    for h in (0.5, 0.25, 0.125):
        summary = run("thick_cylinder_3d", os.path.join(work, f"cyl_{h}"),
                      [f"discretisation.spacing={h}", RADIAL_LINE])
        line_errors.append(radial_line_error(os.path.join(work, f"cyl_{h}")))
        r = summary["results"]
        errors.append((h, summary["counts"]["dofs"], r["error_energy_relative"],
                       r["error_l2_relative"]))
        force = r["boundary"]["bore_pressure"]["applied_force"]
        # 3 Gauss points on each arc part integrate cos(theta) to about 2e-9 at spacing 0.5
        check(abs(force[0] - 50.0) <= 1e-8 * 50.0 and abs(force[1] - 50.0) <= 1e-8 * 50.0,
              f"spacing {h}: the bore's pressure resultant {force[0]:.12g}, {force[1]:.12g} "
              f"(p a depth = 50)")
    for (h1, n1, e1, l1), (h2, n2, e2, l2) in zip(errors, errors[1:]):
        rate_e = math.log(e1 / e2) / math.log(h1 / h2)
        rate_l2 = math.log(l1 / l2) / math.log(h1 / h2)
        print(f"     spacing {h1} -> {h2} ({n1} -> {n2} DOFs): energy {e1:.3e} -> {e2:.3e} "
              f"(rate {rate_e:.2f}), L2 {l1:.3e} -> {l2:.3e} (rate {rate_l2:.2f})")
    rate_line = math.log(line_errors[1] / line_errors[2]) / math.log(2.0)
    check(line_errors[2] <= 0.03 and rate_line >= 1.5,
          f"output.lines: sigma_rr and sigma_tt along a radius against Lame, largest error / p "
          f"{line_errors[0]:.2e}, {line_errors[1]:.2e}, {line_errors[2]:.2e} (<= 0.03 at 0.125, "
          f"at the bore; rate {rate_line:.2f} >= 1.5)")
    check(rate_e >= 0.9 and rate_l2 >= 1.8,
          f"thick cylinder rates at the finest pair: energy {rate_e:.2f} (>= 0.9), "
          f"L2 {rate_l2:.2f} (>= 1.8)")

    direct = nodal_displacement(os.path.join(work, "cyl_0.25"))
    mg = run("thick_cylinder_3d", os.path.join(work, "cyl_mg"),
             ["discretisation.spacing=0.25", "linear_solver.type=multigrid"])
    diff = abs(nodal_displacement(os.path.join(work, "cyl_mg")) - direct).max() / abs(direct).max()
    # The finest level's SOR smoother of meshfree bodies: 15 iterations, 50 with Jacobi.
    check(mg["solver"]["type"].startswith("cg/gamg") and diff <= 1e-8
          and mg["solver"]["iterations"] <= 25,
          f"CG + GAMG ({mg['solver']['iterations']} iterations, at most 25) equals MUMPS to "
          f"{diff:.1e} (<= 1e-8)")
    two = run("thick_cylinder_3d", os.path.join(work, "cyl_2"),
              ["discretisation.spacing=0.25", RADIAL_LINE], ranks=2)
    one_line, two_line = (radial_line(os.path.join(work, d)) for d in ("cyl_0.25", "cyl_2"))
    check(len(one_line) == len(two_line) == 31 and
          max(abs(a[k] - b[k]) for a, b in zip(one_line, two_line) for k in a) <= 1e-6,
          "output.lines on 2 ranks equals 1 rank (31 points, 1e-6 MPa)")
    check_limit_pressure(os.path.join(work, "limit"))
    check_bricks(work)
    check_boxes_along_z(work)
    check_bricks_collapse(work)
    check_cell_mean(work)
    check_cell_mean_sphere(work)
    check_tets(work)
    check_variations(work, errors[1][2])
    check_plastic_ranks(work)
    diff = abs(nodal_displacement(os.path.join(work, "cyl_2")) - direct).max() / abs(direct).max()
    check(two["mpi_ranks"] == 2 and diff <= 1e-8, f"2 MPI ranks equal 1 to {diff:.1e} (<= 1e-8)")
sys.exit(1 if check.failed else 0)
