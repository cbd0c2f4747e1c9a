#!/usr/bin/python3
"""Regenerate the CalculiX CPS8 reference of the slotted plate pulled into
plasticity: a plate with an inclined slot (two straight sides, two round
ends), held in grips at both ends, one grip pulled.

Run from the repository root:

    /usr/bin/python3 scripts/fe_reference/make_calculix_slotted_plate_reference.py
    /usr/bin/python3 scripts/fe_reference/make_calculix_slotted_plate_reference.py --h 0.5 0.25
    /usr/bin/python3 scripts/fe_reference/make_calculix_slotted_plate_reference.py --quick

Full run: one gmsh mesh and one CalculiX run per element size (--h, default
0.5, 0.25, 0.125), then writes reference/calculix_plastic/slotted_plate/:
curve_h<h>.csv per mesh, curve.csv (the finest, which scripts/compare.py reads),
convergence.csv and the decks below 1 MB.  Nothing is
written unless every run succeeded (gmsh's and ccx's return codes, no *ERROR,
all 40 increments in the .dat file).  --quick remakes the mesh of h = 1 (945
nodes, about 15 s) in a temporary folder and compares it with the committed
curve_h1.csv, written by `--h 1 --out DIR` (exit 1 beyond 1e-6 of each
column's largest |value|).  --out DIR (or CALCULIX_REFERENCE_OUT=DIR)
writes into DIR instead.

Problem (N, mm, MPa; plane stress, 1 mm thick): the plate [0, 20] x [0, 10]
less the slot of width 2 whose round ends are centred at (8.4, 3.8) and
(11.6, 6.2) (its axis at atan(3/4) = 36.87 degrees to x).  u_x = u_y = 0 on
x = 0; u_x = v, u_y = 0 on x = 20 (grips).  v = 0 ... 0.08 mm recorded at 40
equal increments (automatic incrementation, *TIME POINTS at the records).  E = 200000, nu = 0.3, von Mises with
sigma_y = 250 + 2000 alpha (*PLASTIC (250, 0), (20250, 10)).  Small strain.
The same body as problems/slotted_plate.yaml, whose geometry gives the slot
in the built-in dialect (`holes: [{slot: {from, to, width}}]`).

Recorded per increment: v; the grip's reactions F_x and F_y (the sums of RF
over the nodes of x = 20; the inclined slot couples the pull to a shear, so
F_y is not zero).

Method: gmsh's command line (4.8, OpenCASCADE) meshes the plate minus the
slot (a rotated rectangle and two discs) with quadrilaterals of size h
(Frontal-Delaunay triangles recombined into quadrilaterals, second order
incomplete: 8-node quadrilaterals, the midside nodes on the round ends; the
quadrilateral algorithm, 8, crashes gmsh 4.8 on this body); CPS8, 3 x 3 Gauss
points.  CalculiX expands a CPS8 into a brick as thick as its section, so
plane stress is a thin slab, as in the plate recipes
(reference/calculix_plastic/README.md): 1e-3 of the slot's width, 0.002 mm,
the reactions divided by it.  CalculiX one thread, Newton tolerances 1e-8.
Measured: h = 0.5, 0.25, 0.125 took 54, 397 and 2,055 s (h = 1, --quick: 15 s).
"""

import csv
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_calculix_reference as elastic_recipe  # noqa: E402  (run_ccx, recipe_main)
import make_calculix_plastic_reference as plane_recipe  # noqa: E402  (QMesh, parsing, tables)
from make_calculix_cantilever_3d_reference import quick_verdict  # noqa: E402

NAME = "slotted_plate"
DEFAULT_OUT = os.path.join(elastic_recipe.REPO_ROOT, "reference", "calculix_plastic", NAME)
E_MOD, NU, SIG_Y, H_LIN = 200000.0, 0.3, 250.0, 2000.0
WIDTH, HEIGHT = 20.0, 10.0
SLOT_FROM, SLOT_TO, SLOT_WIDTH = (8.4, 3.8), (11.6, 6.2), 2.0
V_END, N_INC = 0.08, 40
SLAB = 1e-3 * SLOT_WIDTH       # the thin slab of plane stress
DEFAULT_H = [0.5, 0.25, 0.125]
QUICK_TOL = 1e-6
QUICK_H = 1.0                  # the quick check's mesh (curve_h1.csv, made by --h 1)
COLUMNS = ["increment", "v", "force_x", "force_y"]
MAX_KEEP_DECK = 1 << 20


def geo_text(h):
    (ax, ay), (bx, by) = SLOT_FROM, SLOT_TO
    length = np.hypot(bx - ax, by - ay)
    angle = np.arctan2(by - ay, bx - ax)
    cx, cy, r = 0.5 * (ax + bx), 0.5 * (ay + by), 0.5 * SLOT_WIDTH
    return "\n".join([
        'SetFactory("OpenCASCADE");',
        "Rectangle(1) = {0, 0, 0, %r, %r};" % (WIDTH, HEIGHT),
        "Rectangle(2) = {%r, %r, 0, %r, %r};" % (cx - length / 2, cy - r, length, 2 * r),
        "Rotate {{0, 0, 1}, {%r, %r, 0}, %r} { Surface{2}; }" % (cx, cy, angle),
        "Disk(3) = {%r, %r, 0, %r, %r};" % (ax, ay, r, r),
        "Disk(4) = {%r, %r, 0, %r, %r};" % (bx, by, r, r),
        "BooleanDifference{ Surface{1}; Delete; }{ Surface{2, 3, 4}; Delete; }",
        "Mesh.CharacteristicLengthMin = %r;" % h,
        "Mesh.CharacteristicLengthMax = %r;" % h,
        "Mesh.Algorithm = 6;",
        "Mesh.RecombineAll = 1;",
        "Mesh.RecombinationAlgorithm = 1;",
        "Mesh.ElementOrder = 2;",
        "Mesh.SecondOrderIncomplete = 1;",
        "Mesh.MshFileVersion = 2.2;",
        ""])


def read_msh_q8(path, label, h):
    """The 8-node quadrilaterals (type 16) of a gmsh MSH 2.2 file as a QMesh,
    nodes renumbered 1..n in order of first use, every element counter-clockwise."""
    with open(path) as f:
        lines = f.read().split("\n")
    at = lines.index("$Nodes")
    n = int(lines[at + 1])
    xyz = {}
    for line in lines[at + 2:at + 2 + n]:
        s = line.split()
        xyz[int(s[0])] = (float(s[1]), float(s[2]))
    at = lines.index("$Elements")
    m = int(lines[at + 1])
    quads = []
    for line in lines[at + 2:at + 2 + m]:
        s = [int(v) for v in line.split()]
        if s[1] == 16:
            quads.append(s[3 + s[2]:])
        elif s[1] in (2, 9):
            raise RuntimeError("%s: gmsh left triangles in the mesh" % path)
    ids, xy, elems = {}, [], []
    for q in quads:
        c = np.array([xyz[t] for t in q[:4]])
        area = 0.5 * sum(c[i, 0] * c[(i + 1) % 4, 1] - c[(i + 1) % 4, 0] * c[i, 1]
                         for i in range(4))
        if area < 0.0:
            q = [q[0], q[3], q[2], q[1], q[7], q[6], q[5], q[4]]
        for t in q:
            if t not in ids:
                ids[t] = len(xy) + 1
                xy.append(xyz[t])
        elems.append([ids[t] for t in q])
    return plane_recipe.QMesh(xy, elems, label, h)


def mesh_of(h, work):
    geo, msh = os.path.join(work, "slot_h%g.geo" % h), os.path.join(work, "slot_h%g.msh" % h)
    with open(geo, "w") as f:
        f.write(geo_text(h))
    p = subprocess.run(["gmsh", geo, "-2", "-o", msh], capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("gmsh failed (rc=%d): %s" % (p.returncode, p.stderr[-2000:]))
    return read_msh_q8(msh, "gmsh quads h=%g" % h, h)


def write_deck(path, mesh):
    wl = elastic_recipe.write_list
    with open(path, "w") as f:
        plane_recipe.write_mesh_cards(f, "make_calculix_slotted_plate_reference.py", NAME, mesh,
                                      "CPS8")
        f.write("*NSET, NSET=LEFT\n")
        wl(f, mesh.nodes_where(lambda x, y: abs(x) < 1e-9))
        f.write("*NSET, NSET=RIGHT\n")
        wl(f, mesh.nodes_where(lambda x, y: abs(x - WIDTH) < 1e-9))
        plane_recipe.write_linear_hardening(f, E_MOD, NU, SIG_Y, H_LIN)
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n%r\n" % SLAB)
        f.write("*BOUNDARY\nLEFT, 1, 2, 0.0\nRIGHT, 2, 2, 0.0\n")
        f.write("*TIME POINTS, NAME=TP\n")
        f.write("".join("%.12g\n" % (k / N_INC) for k in range(1, N_INC + 1)))
        dt = 1.0 / N_INC
        f.write("*STEP, INC=100000\n*STATIC\n%.12g, 1.0, %.12g, %.12g\n" % (dt, dt * 1e-5, dt))
        f.write("*CONTROLS, PARAMETERS=FIELD\n%g, %g\n"
                % (plane_recipe.CONTROL_RN, plane_recipe.CONTROL_CN))
        f.write("*BOUNDARY\nRIGHT, 1, 1, %r\n" % V_END)
        f.write("*NODE PRINT, NSET=RIGHT, TOTALS=ONLY, TIME POINTS=TP\nRF\n*END STEP\n")


def solve(mesh, work, tag):
    """Rows (increment, v, F_x, F_y), row 0 unloaded."""
    job = "%s_%s" % (NAME, tag)
    deck = os.path.join(work, job + ".inp")
    t0 = time.time()
    write_deck(deck, mesh)
    elastic_recipe.run_ccx(work, job)
    wall = time.time() - t0
    blocks = plane_recipe.parse_dat(os.path.join(work, job + ".dat"))
    totals = blocks[("total force", "RIGHT")]
    if len(totals) != N_INC:
        raise RuntimeError("%s: %d increments in the .dat file, not %d" % (job, len(totals), N_INC))
    rows = [[0, 0.0, 0.0, 0.0]]
    for k, blk in enumerate(totals, start=1):
        fx, fy, _fz = blk[0]
        rows.append([k, V_END * k / N_INC, fx / SLAB, fy / SLAB])
    newton = plane_recipe.newton_stats(os.path.join(work, job + ".sta"))
    return dict(mesh=mesh, rows=rows, deck=deck, deck_bytes=os.path.getsize(deck), wall=wall,
                newton=newton)


def write_curve(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([r[0]] + ["%.10e" % v for v in r[1:]])


def full_run(out, work, hs):
    results = []
    for h in hs:
        mesh = mesh_of(h, work)
        print("h = %g (%s): %d elements, %d nodes ..." % (h, mesh.label, mesh.nelems, mesh.nnodes),
              flush=True)
        res = solve(mesh, work, "h%g" % h)
        last = res["rows"][-1]
        print("  %.1f s, %d Newton iterations; at v = %g: F_x %.7g, F_y %.7g"
              % (res["wall"], res["newton"][2], last[1], last[2], last[3]), flush=True)
        results.append((h, res))
    os.makedirs(out, exist_ok=True)  # every run succeeded: only now write
    with open(os.path.join(out, "convergence.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["h", "elements", "nodes", "wall_s", "newton_iterations", "force_x_end",
                    "force_y_end", "max_rel_diff_force_x_to_finest"])
        finest = results[-1][1]["rows"]
        scale = max(abs(r[2]) for r in finest)
        for h, res in results:
            write_curve(os.path.join(out, "curve_h%g.csv" % h), res["rows"])
            if res is results[-1][1]:  # the finest: the curve scripts/compare.py reads
                write_curve(os.path.join(out, "curve.csv"), res["rows"])
            keep = os.path.join(out, "%s_h%g.inp" % (NAME, h))
            if res["deck_bytes"] < MAX_KEEP_DECK:
                os.replace(res["deck"], keep)
            diff = max(abs(a[2] - b[2]) for a, b in zip(res["rows"], finest)) / scale
            last = res["rows"][-1]
            w.writerow(["%g" % h, res["mesh"].nelems, res["mesh"].nnodes, "%.1f" % res["wall"],
                        res["newton"][2], "%.7g" % last[2], "%.7g" % last[3], "%.3e" % diff])
            print("  h = %g: largest force difference from the finest mesh %.3e" % (h, diff))


def quick_run(out, work):
    res = solve(mesh_of(QUICK_H, work), work, "quick")
    return quick_verdict(res["rows"], os.path.join(out, "curve_h%g.csv" % QUICK_H), len(COLUMNS),
                         QUICK_TOL)


def main():
    elastic_recipe.recipe_main(
        __doc__, DEFAULT_OUT, lambda out, work, args: full_run(out, work, args.h), quick_run,
        lambda ap: ap.add_argument("--h", type=float, nargs="+", default=DEFAULT_H,
                                   help="element sizes of the gmsh meshes"))


if __name__ == "__main__":
    main()
