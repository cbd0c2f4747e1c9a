"""A plane-stress plate meshed by gmsh and pulled into plasticity between grips
in CalculiX: the recipe the slotted plate and the filleted bar share (their
scripts give the body and the numbers, this module makes the meshes, decks,
curves and checks).

The plate lies between x = 0 and x = `length`, pulled at x = length (u_x = v)
and held as the plate says (`held`; by default grips: u_x = u_y = 0 on x = 0,
u_y = 0 on x = length), v = 0 ... v_end recorded at n_inc equal increments (automatic incrementation, *TIME POINTS at the records).
E = 200000, nu = 0.3, von Mises with sigma_y = 250 + 2000 alpha.  Small strain.
Recorded per increment: v; the grip's reactions F_x and F_y (the sums of RF
over the nodes of x = length).  Where the plate's elastic stress is bounded
(elastic_limit): per mesh a linear run at v = 1 whose largest von Mises stress,
at the integration points and extrapolated to the nodes
(make_calculix_plastic_reference.elastic_limit), gives the grip displacement
of first yield, sigma_y / max sigma_vM (elastic_limit.csv, which
scripts/compare.py reads).

Method: gmsh's command line (4.8, OpenCASCADE) meshes the body with
quadrilaterals of size h (Frontal-Delaunay triangles recombined into
quadrilaterals, second order incomplete: 8-node quadrilaterals, the midside
nodes on curved boundaries; the quadrilateral algorithm, 8, crashes gmsh 4.8
on such bodies); CPS8, 3 x 3 Gauss points.  CalculiX expands a CPS8 into a
brick as thick as its section, so plane stress is a thin slab, as in the plate
recipes (reference/calculix_plastic/README.md), the reactions divided by its
thickness.  CalculiX one thread, Newton tolerances 1e-8.

Full run: one mesh and one CalculiX run per element size (--h), then writes
curve_h<h>.csv per mesh, curve.csv (the finest, which scripts/compare.py
reads), convergence.csv and the decks below 1 MB.  Nothing is written unless
every run succeeded (gmsh's and ccx's return codes, no *ERROR, every increment
in the .dat file).  --quick remakes the mesh of the plate's quick_h in a
temporary folder and compares it with the committed curve_h<quick_h>.csv
(exit 1 beyond 1e-6 of each column's largest |value|).
"""

import csv
import os
import subprocess
import time
from dataclasses import dataclass, field
from typing import Callable, List, Tuple

import numpy as np

import make_calculix_reference as elastic_recipe  # run_ccx, write_list, recipe_main
import make_calculix_plastic_reference as plane_recipe  # QMesh, parsing, cards
from make_calculix_cantilever_3d_reference import quick_verdict

E_MOD, NU, SIG_Y, H_LIN = 200000.0, 0.3, 250.0, 2000.0
QUICK_TOL = 1e-6
COLUMNS = ["increment", "v", "force_x", "force_y"]
MAX_KEEP_DECK = 1 << 20


@dataclass
class Plate:
    name: str                      # the problem's and the reference folder's name
    script: str                    # the recipe's file name, written into the decks
    body: Callable[[], List[str]]  # the .geo lines (OpenCASCADE) that make the body
    length: float                  # x of the pulled grip
    v_end: float
    n_inc: int
    slab: float                    # the thin slab's thickness (plane stress)
    default_h: List[float] = field(default_factory=list)
    quick_h: float = 1.0
    elastic_limit: bool = False    # whether the elastic stress is bounded: first yield defined
    # Node sets beyond LEFT (x = 0) and RIGHT (x = length), as (name, predicate(x, y)), and the
    # held degrees of freedom as (set, first, last).
    more_sets: List[Tuple[str, Callable[[float, float], bool]]] = field(default_factory=list)
    held: List[Tuple[str, int, int]] = field(
        default_factory=lambda: [("LEFT", 1, 2), ("RIGHT", 2, 2)])

    def out(self):
        return os.path.join(elastic_recipe.REPO_ROOT, "reference", "calculix_plastic", self.name)


def geo_text(plate, h):
    return "\n".join(['SetFactory("OpenCASCADE");'] + plate.body() + [
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


def mesh_of(plate, h, work, stem):
    geo, msh = os.path.join(work, "%s_h%g.geo" % (stem, h)), os.path.join(work, "%s_h%g.msh" % (stem, h))
    with open(geo, "w") as f:
        f.write(geo_text(plate, h))
    p = subprocess.run(["gmsh", geo, "-2", "-o", msh], capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("gmsh failed (rc=%d): %s" % (p.returncode, p.stderr[-2000:]))
    return read_msh_q8(msh, "gmsh quads h=%g" % h, h)


def write_deck(plate, path, mesh, elastic=False):
    """The pull to v_end over n_inc recorded increments, or with `elastic` one linear step to
    v = 1 that prints the stresses at every integration point."""
    wl = elastic_recipe.write_list
    with open(path, "w") as f:
        plane_recipe.write_mesh_cards(f, plate.script, plate.name, mesh, "CPS8")
        f.write("*NSET, NSET=LEFT\n")
        wl(f, mesh.nodes_where(lambda x, y: abs(x) < 1e-9))
        f.write("*NSET, NSET=RIGHT\n")
        wl(f, mesh.nodes_where(lambda x, y: abs(x - plate.length) < 1e-9))
        for name, where in plate.more_sets:
            f.write("*NSET, NSET=%s\n" % name)
            wl(f, mesh.nodes_where(where))
        if elastic:
            f.write("*MATERIAL, NAME=STEEL\n*ELASTIC\n%r, %r\n" % (E_MOD, NU))
        else:
            plane_recipe.write_linear_hardening(f, E_MOD, NU, SIG_Y, H_LIN)
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n%r\n" % plate.slab)
        f.write("*BOUNDARY\n" + "".join("%s, %d, %d, 0.0\n" % h for h in plate.held))
        if elastic:
            f.write("*STEP\n*STATIC\n*BOUNDARY\nRIGHT, 1, 1, 1.0\n")
            f.write("*NODE PRINT, NSET=RIGHT, TOTALS=ONLY\nRF\n*EL PRINT, ELSET=EALL\nS\n"
                    "*END STEP\n")
            return
        f.write("*TIME POINTS, NAME=TP\n")
        f.write("".join("%.12g\n" % (k / plate.n_inc) for k in range(1, plate.n_inc + 1)))
        dt = 1.0 / plate.n_inc
        f.write("*STEP, INC=100000\n*STATIC\n%.12g, 1.0, %.12g, %.12g\n" % (dt, dt * 1e-5, dt))
        f.write("*CONTROLS, PARAMETERS=FIELD\n%g, %g\n"
                % (plane_recipe.CONTROL_RN, plane_recipe.CONTROL_CN))
        f.write("*BOUNDARY\nRIGHT, 1, 1, %r\n" % plate.v_end)
        f.write("*NODE PRINT, NSET=RIGHT, TOTALS=ONLY, TIME POINTS=TP\nRF\n*END STEP\n")


def first_yield(plate, mesh, work, tag):
    """The linear run at v = 1: the largest von Mises stress and where, at the integration points
    and at the nodes (make_calculix_plastic_reference.elastic_limit), and the first-yield v."""
    job = "%s_%s_elastic" % (plate.name, tag)
    write_deck(plate, os.path.join(work, job + ".inp"), mesh, elastic=True)
    elastic_recipe.run_ccx(work, job)
    blocks = plane_recipe.parse_dat(os.path.join(work, job + ".dat"))
    lim = plane_recipe.elastic_limit(dict(mesh=mesh, stress=blocks[("stresses", "EALL")][0]))
    return (mesh.h, lim["ip"], lim["xy_ip"][0], lim["xy_ip"][1], lim["node"], lim["xy_node"][0],
            lim["xy_node"][1], SIG_Y / lim["ip"], SIG_Y / lim["node"])


def solve(plate, mesh, work, tag):
    """Rows (increment, v, F_x, F_y), row 0 unloaded."""
    job = "%s_%s" % (plate.name, tag)
    deck = os.path.join(work, job + ".inp")
    t0 = time.time()
    write_deck(plate, deck, mesh)
    elastic_recipe.run_ccx(work, job)
    wall = time.time() - t0
    blocks = plane_recipe.parse_dat(os.path.join(work, job + ".dat"))
    totals = blocks[("total force", "RIGHT")]
    if len(totals) != plate.n_inc:
        raise RuntimeError("%s: %d increments in the .dat file, not %d"
                           % (job, len(totals), plate.n_inc))
    rows = [[0, 0.0, 0.0, 0.0]]
    for k, blk in enumerate(totals, start=1):
        fx, fy, _fz = blk[0]
        rows.append([k, plate.v_end * k / plate.n_inc, fx / plate.slab, fy / plate.slab])
    newton = plane_recipe.newton_stats(os.path.join(work, job + ".sta"))
    return dict(mesh=mesh, rows=rows, deck=deck, deck_bytes=os.path.getsize(deck), wall=wall,
                newton=newton)


def write_curve(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([r[0]] + ["%.10e" % v for v in r[1:]])


def full_run(plate, stem, out, work, hs):
    results = []
    for h in hs:
        mesh = mesh_of(plate, h, work, stem)
        print("h = %g (%s): %d elements, %d nodes ..." % (h, mesh.label, mesh.nelems, mesh.nnodes),
              flush=True)
        res = solve(plate, mesh, work, "h%g" % h)
        last = res["rows"][-1]
        print("  %.1f s, %d Newton iterations; at v = %g: F_x %.7g, F_y %.7g"
              % (res["wall"], res["newton"][2], last[1], last[2], last[3]), flush=True)
        if plate.elastic_limit:
            res["limit"] = first_yield(plate, mesh, work, "h%g" % h)
            print("  first yield at v = %.6g (integration points) / %.6g (nodes), the largest "
                  "von Mises stress at (%.4g, %.4g)" % (res["limit"][7], res["limit"][8],
                                                        res["limit"][5], res["limit"][6]))
        results.append((h, res))
    os.makedirs(out, exist_ok=True)  # every run succeeded: only now write
    if plate.elastic_limit:
        with open(os.path.join(out, "elastic_limit.csv"), "w") as f:
            f.write("level,h,max_vm_ip,x_ip,y_ip,max_vm_node,x_node,y_node,"
                    "first_yield_factor_ip,first_yield_factor_node\n")
            for level, (_h, res) in enumerate(results):
                f.write("%d,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e\n"
                        % ((level,) + res["limit"]))
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
            keep = os.path.join(out, "%s_h%g.inp" % (plate.name, h))
            if res["deck_bytes"] < MAX_KEEP_DECK:
                os.replace(res["deck"], keep)
            diff = max(abs(a[2] - b[2]) for a, b in zip(res["rows"], finest)) / scale
            last = res["rows"][-1]
            w.writerow(["%g" % h, res["mesh"].nelems, res["mesh"].nnodes, "%.1f" % res["wall"],
                        res["newton"][2], "%.7g" % last[2], "%.7g" % last[3], "%.3e" % diff])
            print("  h = %g: largest force difference from the finest mesh %.3e" % (h, diff))


def quick_run(plate, stem, out, work):
    res = solve(plate, mesh_of(plate, plate.quick_h, work, stem), work, "quick")
    return quick_verdict(res["rows"], os.path.join(out, "curve_h%g.csv" % plate.quick_h),
                         len(COLUMNS), QUICK_TOL)


def main(plate, doc, stem):
    """The recipe's command line (elastic_recipe.recipe_main): --h, --quick, --out."""
    elastic_recipe.recipe_main(
        doc, plate.out(), lambda out, work, args: full_run(plate, stem, out, work, args.h),
        lambda out, work: quick_run(plate, stem, out, work),
        lambda ap: ap.add_argument("--h", type=float, nargs="+", default=plate.default_h,
                                   help="element sizes of the gmsh meshes"))
