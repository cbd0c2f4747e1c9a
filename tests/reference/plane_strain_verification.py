#!/usr/bin/python3
"""Plane strain with the volumetric strain of each cell's mean (quadrature.volumetric_strain:
cell_mean, the plane-strain B-bar of implicit/volumetric_projection):

- the patch test (problems/patch_test.yaml in plane strain) holds to 1e-10 in energy with the
  cell mean: meshfree with VCI, Q4 and Q8;
- Kirsch's plate (problems/plate_hole_kirsch.yaml) in plane strain at nu = 0.4999: the cell mean
  unlocks the meshfree and Q4 solutions (their errors against the exact solution fall);
- the pressure strip (problems/strip_punch_plane_strain.yaml) against CalculiX CPE8R on its
  finest mesh (reference/calculix_plastic/strip_punch): the strip's mean displacement at every
  increment, the equivalent plastic strain and von Mises stress 4 mm below the strip's centre at
  the end, meshfree at the file's settings and Q8 on the reduced rule; the pointwise meshfree
  runs lock (the check can fail);
- two MPI ranks equal one to 1e-8;
- a staged run hands a cell-mean plane-strain preload over quietly.

Newton's quadratic rate with the cell mean is a unit test (test_elastoplastic.cpp).

    plane_strain_verification.py MESHFREE ROOT
"""
import csv
import os
import sys
import tempfile

import h5py
import numpy as np

from meshfree_run import Checks, run_meshfree

MESHFREE, ROOT = sys.argv[1], sys.argv[2]
PROBLEMS = os.path.join(ROOT, "problems")
REFERENCE = os.path.join(ROOT, "reference", "calculix_plastic", "strip_punch")
FINEST = "strip_h0.125.csv"
PLANE_STRAIN = ["model.type=plane_strain"]
CELL_MEAN = ["discretisation.quadrature.volumetric_strain=cell_mean"]
check = Checks()


def run(problem, out, sets=(), ranks=1):
    return run_meshfree(MESHFREE, os.path.join(PROBLEMS, problem + ".yaml"), out, sets, ranks)


def check_patch_test(work):
    """A stiff penalty (1e13 against E = 1, as the VCI unit test) leaves the penalty's own error
    under 1e-10 (measured: meshfree with VCI 9.2e-11, pointwise 9.8e-11; Q4 and Q8 4e-13)."""
    stiff = ["boundary.0.penalty=1e13", "discretisation.quadrature.order=3"]
    for name, sets in (("meshfree, VCI", ["discretisation.quadrature.correction=vci"]),
                       ("Q4", ["discretisation.method=fem", "discretisation.fem.element=q4"]),
                       ("Q8", ["discretisation.method=fem", "discretisation.fem.element=q8"])):
        s = run("patch_test", os.path.join(work, "patch_" + name[:2]),
                PLANE_STRAIN + CELL_MEAN + stiff + sets)
        e = s["results"]["error_energy_relative"]
        check(e <= 1e-10, f"plane-strain patch test with the cell mean, {name}: energy error "
                          f"{e:.1e} (<= 1e-10)")


def check_kirsch_incompressible(work):
    """Kirsch's plate at nu = 0.4999 in plane strain (spacing 0.125, 4 x 4 Gauss points a cell).
    Measured L2 / energy errors, pointwise -> cell mean: meshfree 1.05e-2 / 6.2e-2 -> 2.3e-3 /
    2.8e-2; Q4 7.7e-2 / 0.19 -> 6.2e-4 / 1.7e-2; Q8 1.0e-3 / 1.9e-2 -> 7.1e-4 / 1.6e-2 (at
    nu = 0.3 Q8's energy error is 1.5e-3 pointwise and 1.6e-2 with one mean pressure an element,
    which is why quadratic elements take the reduced rule instead)."""
    base = PLANE_STRAIN + ["materials[0].nu=0.4999"]
    fem = ["discretisation.method=fem"]
    for name, sets, l2_max, l2_share, energy_max, energy_share in (
            ("meshfree", [], 3e-3, 0.25, 3.5e-2, 0.5),
            ("Q4", fem + ["discretisation.fem.element=q4"], 1e-3, 0.05, 2e-2, 0.1)):
        errors = {}
        for mode in ("pointwise", "cell_mean"):
            r = run("plate_hole_kirsch", os.path.join(work, f"kirsch_{name}_{mode}"),
                    base + sets + [f"discretisation.quadrature.volumetric_strain={mode}"])
            errors[mode] = (r["results"]["error_l2_relative"],
                            r["results"]["error_energy_relative"])
        (l2_p, e_p), (l2_c, e_c) = errors["pointwise"], errors["cell_mean"]
        check(l2_c <= l2_max and l2_c < l2_share * l2_p and e_c <= energy_max and
              e_c < energy_share * e_p,
              f"Kirsch's plate at nu = 0.4999 in plane strain, {name}: pointwise L2 {l2_p:.2e}, "
              f"energy {e_p:.2e}; cell mean L2 {l2_c:.2e} (<= {l2_max}, < {l2_share} of "
              f"pointwise), energy {e_c:.2e} (<= {energy_max}, < {energy_share} of pointwise)")


def reference_rows():
    with open(os.path.join(REFERENCE, FINEST)) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def strip_mean_displacement(out):
    """Per increment: the mean of -u_y over the strip (Simpson's rule on the 41 line points)."""
    by_increment = {}
    with open(os.path.join(out, "line_strip.csv")) as f:
        for r in csv.DictReader(f):
            by_increment.setdefault(int(r["increment"]), []).append(
                (float(r["x"]), -float(r["uy"])))
    means = {}
    for k, pts in by_increment.items():
        pts.sort()
        x = np.array([p[0] for p in pts])
        u = np.array([p[1] for p in pts])
        h = x[1] - x[0]
        simpson = h / 3.0 * (u[0] + u[-1] + 4.0 * u[1:-1:2].sum() + 2.0 * u[2:-1:2].sum())
        means[k] = simpson / (x[-1] - x[0])
    return means


def node_values_at(out, point):
    """The last field step's (the last increment's) plastic strain and von Mises stress at
    `point` on the symmetry line x = 0: the node there, or linear between the two nodes of the
    line around it (a gmsh mesh of finite elements need not have a node there)."""
    with h5py.File(os.path.join(out, "fields.h5"), "r") as f:
        x = np.array(f["geometry"]["coordinates"])[:, :2]
        steps = sorted((k for k in f.keys() if k.startswith("step_")), key=lambda k: int(k[5:]))
        last = f[steps[-1]]
        values = np.array(last["plastic_strain"]), np.array(last["von_mises"])
    on_line = np.flatnonzero(np.abs(x[:, 0] - point[0]) < 1e-9)
    y = x[on_line, 1]
    below, above = on_line[y <= point[1]], on_line[y >= point[1]]
    a = below[np.argmax(x[below, 1])]
    b = above[np.argmin(x[above, 1])]
    t = 0.0 if a == b else (point[1] - x[a, 1]) / (x[b, 1] - x[a, 1])
    return tuple(float((1 - t) * v[a] + t * v[b]) for v in values)


def compare_strip(out, ref):
    means = strip_mean_displacement(out)
    worst = max(abs(means[int(r["increment"])] - r["mean_strip_disp"]) / r["mean_strip_disp"]
                for r in ref[1:])
    final = (means[len(ref) - 1] - ref[-1]["mean_strip_disp"]) / ref[-1]["mean_strip_disp"]
    peeq, mises = node_values_at(out, (0.0, 4.0))
    return dict(worst=worst, final=final,
                peeq=(peeq - ref[-1]["peeq_0_4"]) / ref[-1]["peeq_0_4"],
                mises=(mises - ref[-1]["mises_0_4"]) / ref[-1]["mises_0_4"])


def check_strip(work):
    """The problem file's settings (spacing 0.25, 0.125 under the strip), meshfree with the
    cell mean and Q8 on the reduced rule: every increment's mean strip displacement within 1%,
    the plastic strain 4 mm below within 5% and von Mises there within 2% (measured: 0.51%,
    +0.07%, +0.01% meshfree; 0.41%, -0.21%, -0.10% Q8). The same cloud pointwise misses the 1%
    (measured 1.67%); at spacing 0.5 without the box the lock shows plainly (the final increment
    -3.2% pointwise, -0.38% with the cell mean)."""
    ref = reference_rows()
    pointwise = ["discretisation.quadrature.volumetric_strain=pointwise"]
    q8_reduced = ["discretisation.method=fem", "discretisation.fem.element=q8",
                  "discretisation.fem.order=2"] + pointwise
    coarse = ["discretisation.spacing=0.5", "discretisation.refinement=[]"]
    results = {}
    for name, sets in (("meshfree, cell mean", []), ("meshfree, pointwise", pointwise),
                       ("Q8, reduced rule", q8_reduced),
                       ("meshfree at 0.5, cell mean", coarse),
                       ("meshfree at 0.5, pointwise", coarse + pointwise)):
        out = os.path.join(work, "strip_" + "".join(c for c in name if c.isalnum()))
        run("strip_punch_plane_strain", out, sets)
        c = results[name] = compare_strip(out, ref)
        text = (f"strip punch, {name}: mean strip displacement worst increment "
                f"{c['worst']:.2%}, final {c['final']:+.2%}; at (0, 4) plastic strain "
                f"{c['peeq']:+.2%}, von Mises {c['mises']:+.2%}")
        if name in ("meshfree, cell mean", "Q8, reduced rule"):
            check(c["worst"] <= 0.01 and abs(c["peeq"]) <= 0.05 and abs(c["mises"]) <= 0.02,
                  text + " (<= 1%, 5%, 2%)")
        else:
            print(text)
    check(results["meshfree, pointwise"]["worst"] > 0.01,
          "the same cloud pointwise misses the 1% (the check can fail)")
    coarse_cm, coarse_pw = results["meshfree at 0.5, cell mean"], results["meshfree at 0.5, pointwise"]
    check(abs(coarse_cm["final"]) <= 0.01 and coarse_pw["final"] < -0.02,
          f"at spacing 0.5 the final mean strip displacement is {coarse_pw['final']:+.2%} "
          f"pointwise (locked, < -2%) and {coarse_cm['final']:+.2%} with the cell mean (<= 1%)")
    return ref


def check_two_ranks(work):
    """Two MPI ranks equal one: displacements to 1e-8 of the largest |u|, reactions and loads to
    1e-8 of the largest force, the plastic strain to 1e-8 of its largest, the counts of plastic
    points exactly (the residuals are round-off and not compared)."""
    histories = []
    for ranks in (1, 2):
        out = os.path.join(work, f"strip_ranks_{ranks}")
        run("strip_punch_plane_strain", out, ranks=ranks)
        with open(os.path.join(out, "history.csv")) as f:
            histories.append(list(csv.DictReader(f)))
    one, two = histories
    groups = {"displacement": [c for c in one[0] if c[:3] in ("ux_", "uy_")],
              "force": [c for c in one[0] if c.startswith(("reaction_", "load_"))],
              "plastic strain": ["max_plastic_strain"]}
    worst = {}
    for group, columns in groups.items():
        scale = max(abs(float(r[c])) for r in one for c in columns)
        worst[group] = max(abs(float(a[c]) - float(b[c])) / scale
                           for a, b in zip(one, two) for c in columns)
    same_counts = all(a["plastic_points"] == b["plastic_points"] for a, b in zip(one, two))
    check(len(one) == len(two) and max(worst.values()) <= 1e-8 and same_counts,
          "strip punch on two MPI ranks against one: " +
          ", ".join(f"{g} {w:.1e}" for g, w in worst.items()) +
          f" of the largest (<= 1e-8); plastic points {'equal' if same_counts else 'differ'}")


def check_staged_handover(work):
    """A staged run whose plane-strain preload takes the cell mean (problems/staged_strip_blast.yaml
    in 5 increments, its SPH stage 1 us): the particles carried through the preload as passive
    points take their cells' means too, so the handover is as quiet as the project's criterion
    asks (out-of-balance <= 1e-3; measured 4e-18 to 8e-18, as pointwise) with no particle over its
    yield surface."""
    s = run("staged_strip_blast", os.path.join(work, "staged_cell_mean"),
            ["stages.0.discretisation.quadrature.volumetric_strain=cell_mean",
             "stages.0.steps.0.increments=5", "stages.1.time.end=1e-6"])
    t = s["transfer"]
    check(t["initial_out_of_balance"] <= 1e-3 and t["particles_over_yield_surface"] == 0 and
          t["plastic_particles"] > 1000,
          f"staged strip from a cell-mean preload: {t['plastic_particles']} plastic particles, "
          f"out-of-balance {t['initial_out_of_balance']:.1e} (<= 1e-3), "
          f"{t['particles_over_yield_surface']} over their yield surface")


def main():
    with tempfile.TemporaryDirectory() as work:
        check_patch_test(work)
        check_kirsch_incompressible(work)
        check_strip(work)
        check_two_ranks(work)
        check_staged_handover(work)
    sys.exit(1 if check.failed else 0)


if __name__ == "__main__":
    main()
