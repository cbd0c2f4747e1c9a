#!/usr/bin/python3
"""Regenerate the CalculiX C3D20R reference of the elastoplastic 3D punch
block: a square patch of a block's top face pushed in by a uniform pressure,
the patch's mean displacement and the plastic state below it, per mesh.

Run from the repository root:

    /usr/bin/python3 scripts/fe_reference/make_calculix_punch_3d_reference.py
    /usr/bin/python3 scripts/fe_reference/make_calculix_punch_3d_reference.py --h 1 0.5
    /usr/bin/python3 scripts/fe_reference/make_calculix_punch_3d_reference.py --quick

Full run: one CalculiX run per mesh (uniform sizes --h, default 1 and 0.5,
plus, with --graded, the graded mesh; h = 0.5 took 15 min on the shared
2-core machine, h = 0.25 is out of reach), then writes
reference/calculix_3d/punch_block/: punch_h<h>.csv per uniform mesh,
punch_graded.csv, convergence.csv and the decks below 1 MB.  Nothing is
written unless every run succeeded (ccx's return code, no *ERROR, all 20
increments in the .dat and .frd files, the base reaction equal to the
applied load).  --quick remakes the h = 1 mesh in a temporary folder and
compares it with the committed punch_h1.csv (exit 1 beyond 1e-6 of each
column's largest |value|).  --out DIR (or CALCULIX_REFERENCE_OUT=DIR) writes
into DIR instead.

Problem (N, mm, MPa): the quarter x in [0, 8], y in [0, 8], z in [0, 8] of a
block (16 x 8 x 16 whole).  u_x = 0 on x = 0, u_z = 0 on z = 0 (symmetry);
u_y = 0 on the base y = 0 (rollers).  A uniform pressure p on the top face
y = 8 over the patch x in [0, 2], z in [0, 2] (the quarter of a 4 x 4 patch)
pushes into the body (-y); p = 0 ... 1000 in 20 fixed increments (*STATIC,
DIRECT, 0.05 of a step of length 1; the *DLOAD ramps linearly).  E = 200000,
nu = 0.3, von Mises with sigma_y = 250 + 2000 alpha (*PLASTIC (250, 0),
(20250, 10): exact, flat beyond alpha = 10).  Small strain.

Recorded per increment: p; the mean patch displacement along -y,
(integral of -u_y over the patch) / 4, from the nodal u_y of the patch's
element faces (8-node serendipity face functions, 3x3 Gauss points: exact);
-u_y at the patch centre (0, 8, 0); the equivalent plastic strain and the
von Mises stress at (0, 4, 0), from CalculiX's values extrapolated to the
nodes (*EL FILE PEEQ, S: the .frd file's nodal PE and STRESS blocks); the
total base reaction F_y (check: = 4 p).

Method: structured 20-node bricks on tensor grids (x, y, z lines), the
patch edges x = 2, z = 2 and the monitor y = 4 on element borders; uniform
meshes of size h (8/h per side) and a graded one (0.25 near the patch, see
GRADED); C3D20R (2x2x2 integration); CalculiX one thread (CCX_REF_THREADS),
Newton tolerances 1e-8 (the thick plate recipe's).
"""

import csv
import math
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_calculix_reference as elastic_recipe  # noqa: E402  (run_ccx, deck helpers)
import make_calculix_plastic_reference as plane_recipe  # noqa: E402  (parsing, tables)
import make_calculix_3d_reference as plate_recipe  # noqa: E402  (HexMesh, node order)
from make_calculix_cantilever_3d_reference import (  # noqa: E402
    largest_difference, read_curve, write_c3d20r_mesh)

NAME = "punch_block"
DEFAULT_OUT = os.path.join(elastic_recipe.REPO_ROOT, "reference", "calculix_3d", NAME)
E_MOD, NU, SIG_Y, H_LIN = 200000.0, 0.3, 250.0, 2000.0
SIDE = 8.0                     # the quarter block [0, 8]^3
PATCH = 2.0                    # loaded patch [0, 2] x [0, 2] on y = 8
P_END, N_INC = 1000.0, 20
DEFAULT_H = [1.0, 0.5]
MAX_KEEP_DECK = 1_000_000      # decks below this size are kept
QUICK_TOL = 1e-6
CENTRE = (0.0, SIDE, 0.0)      # patch centre
BELOW = (0.0, 4.0, 0.0)        # 4 mm below it
COLUMNS = ["increment", "p", "mean_patch_disp", "uy_centre", "peeq_0_4_0", "mises_0_4_0",
           "reaction_y"]


def _lines(*pieces):
    """Concatenate (start, end, size) pieces of equally spaced lines."""
    out = [pieces[0][0]]
    for a, b, h in pieces:
        n = int(round((b - a) / h))
        out += [a + (b - a) * k / n for k in range(1, n + 1)]
    return out


# The graded mesh: 0.25 over the patch and a margin around it (x, z <= 3,
# y >= 6), 0.5 on to x, z = 5 and down to y = 4 (the monitor (0, 4, 0) in
# it), 1 beyond.  Finer than or as fine as the uniform h = 0.5 mesh
# everywhere except x, z > 5 or y < 4.
GRADED = dict(x=_lines((0.0, 3.0, 0.25), (3.0, 5.0, 0.5), (5.0, 8.0, 1.0)),
              y=_lines((0.0, 4.0, 1.0), (4.0, 6.0, 0.5), (6.0, 8.0, 0.25)))


# --------------------------------------------------------------------------
# mesh
# --------------------------------------------------------------------------
def _half(lines):
    return elastic_recipe.Mesh._half(lines)


def brick_mesh(xlines, ylines, zlines, label, h):
    """20-node bricks on the tensor grid: element axes xi, eta, zeta along
    x, y, z, node order of CalculiX C3D20 (plate_recipe.HEX20_XI)."""
    xs, ys, zs = _half(xlines), _half(ylines), _half(zlines)
    ni, nj, nk = len(xs), len(ys), len(zs)
    ids, xyz = {}, []
    for k in range(nk):
        for j in range(nj):
            for i in range(ni):
                if (i % 2) + (j % 2) + (k % 2) >= 2:     # face / volume centres
                    continue
                xyz.append((xs[i], ys[j], zs[k]))
                ids[(i, j, k)] = len(xyz)
    elems = []
    offs = [tuple(int(c) + 1 for c in q) for q in plate_recipe.HEX20_XI]
    for ez in range(len(zlines) - 1):
        for ey in range(len(ylines) - 1):
            for ex in range(len(xlines) - 1):
                elems.append([ids[(2 * ex + a, 2 * ey + b, 2 * ez + c)] for a, b, c in offs])
    return plate_recipe.HexMesh(xyz, elems, label, h)


def uniform_mesh(h):
    n = int(round(SIDE / h))
    if abs(n * h - SIDE) > 1e-12 or abs(PATCH / h - round(PATCH / h)) > 1e-12:
        raise ValueError("h = %g: 8/h and 2/h must be integers" % h)
    lines = list(np.linspace(0.0, SIDE, n + 1))
    return brick_mesh(lines, lines, lines, "uniform h=%g (%d^3)" % (h, n), h)


def graded_mesh():
    g = GRADED
    return brick_mesh(g["x"], g["y"], g["x"], "graded %d x %d x %d"
                      % (len(g["x"]) - 1, len(g["y"]) - 1, len(g["x"]) - 1), 0.25)


# CalculiX C3D20 faces (corner nodes, 1-based), faces 1..6
HEX_FACES = [(1, 2, 3, 4), (5, 8, 7, 6), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 8, 4), (4, 8, 5, 1)]


def patch_faces(mesh):
    """[(element id, face number, 8 node ids in Q8 order on the (x, z) face,
    corner coordinates)] for the element faces on y = 8 inside the patch."""
    out = []
    tol = 1e-9
    for e, conn in enumerate(mesh.elems):
        pts = mesh.xyz[conn - 1]
        for fnum, corners in enumerate(HEX_FACES, start=1):
            cp = pts[[c - 1 for c in corners]]
            if not np.all(np.abs(cp[:, 1] - SIDE) < tol):
                continue
            if cp[:, 0].max() > PATCH + tol or cp[:, 2].max() > PATCH + tol:
                continue
            x0, x1 = cp[:, 0].min(), cp[:, 0].max()
            z0, z1 = cp[:, 2].min(), cp[:, 2].max()
            # Q8 order in the face's own (s, t) = (x, z): corners CCW, midsides
            want = [(x0, z0), (x1, z0), (x1, z1), (x0, z1),
                    ((x0 + x1) / 2, z0), (x1, (z0 + z1) / 2), ((x0 + x1) / 2, z1),
                    (x0, (z0 + z1) / 2)]
            nodes = [mesh.find((x, SIDE, z)) for x, z in want]
            if not set(nodes) <= set(conn.tolist()):
                raise RuntimeError("face %d of element %d: node mismatch" % (fnum, e + 1))
            out.append((e + 1, fnum, nodes, (x0, x1, z0, z1)))
    area = sum((x1 - x0) * (z1 - z0) for *_r, (x0, x1, z0, z1) in out)
    if abs(area - PATCH * PATCH) > 1e-9:
        raise RuntimeError("patch faces cover %g mm^2, not %g" % (area, PATCH * PATCH))
    return out


def patch_weights(faces):
    """{node id: w} with mean(-u_y) = sum w * (-u_y): the integral over every
    face by the Q8 shape functions at 3x3 Gauss points, divided by the patch
    area (exact: u_y is quadratic on every face)."""
    g = math.sqrt(0.6)
    gp = list(zip((-g, 0.0, g), (5 / 9, 8 / 9, 5 / 9)))
    w = {}
    for _e, _f, nodes, (x0, x1, z0, z1) in faces:
        jac = (x1 - x0) * (z1 - z0) / 4.0
        for s, ws in gp:
            for t, wt in gp:
                n = plane_recipe.q8_shape(s, t)
                for a, nid in enumerate(nodes):
                    w[nid] = w.get(nid, 0.0) + n[a] * ws * wt * jac / (PATCH * PATCH)
    return w


# --------------------------------------------------------------------------
# CalculiX deck, run, parse
# --------------------------------------------------------------------------
def write_deck(path, mesh, faces, mon):
    wl = elastic_recipe.write_list
    with open(path, "w") as f:
        write_c3d20r_mesh(f, mesh, NAME, "make_calculix_punch_3d_reference.py")
        for name, axis in (("SYMX", 0), ("BASE", 1), ("SYMZ", 2)):
            f.write("*NSET, NSET=%s\n" % name)
            wl(f, mesh.nodes_where(axis, 0.0))
        f.write("*NSET, NSET=MON\n")
        wl(f, mon)
        f.write("*NSET, NSET=BELOW\n%d,\n" % mesh.find(BELOW))
        fnums = sorted({fn for _e, fn, _n, _c in faces})
        for fn in fnums:
            f.write("*ELSET, ELSET=PATCHF%d\n" % fn)
            wl(f, [e for e, fn2, _n, _c in faces if fn2 == fn])
        f.write("*MATERIAL, NAME=STEEL\n*ELASTIC\n%r, %r\n" % (E_MOD, NU))
        f.write("** von Mises yield stress vs equivalent plastic strain: linear hardening\n"
                "*PLASTIC\n")
        for s, a in plane_recipe.linear_table(SIG_Y, H_LIN, 10.0):
            f.write("%.12g, %.12g\n" % (s, a))
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n")
        f.write("*BOUNDARY\nSYMX, 1, 1\nBASE, 2, 2\nSYMZ, 3, 3\n")
        f.write("*STEP, INC=%d\n*STATIC, DIRECT\n%.12g, 1.0\n" % (N_INC + 10, 1.0 / N_INC))
        f.write("*CONTROLS, PARAMETERS=FIELD\n%g, %g\n"
                % (plate_recipe.CONTROL_RN, plate_recipe.CONTROL_CN))
        f.write("** uniform pressure on the patch (positive: into the body), ramped 0 -> %g\n"
                "*DLOAD\n" % P_END)
        for fn in fnums:
            f.write("PATCHF%d, P%d, %r\n" % (fn, fn, P_END))
        f.write("*NODE PRINT, NSET=MON\nU\n*NODE PRINT, NSET=BASE, TOTALS=ONLY\nRF\n")
        f.write("** stresses and equivalent plastic strain extrapolated to the nodes\n"
                "*EL FILE, NSET=BELOW\nS, PEEQ\n*END STEP\n")


def parse_frd_node(path, nid):
    """{block name: [values of node nid, one tuple per increment]} of the
    nodal result blocks of the .frd file (STRESS, PE)."""
    out, name = {}, None
    with open(path) as f:
        for line in f:
            if line.startswith(" -4"):
                name = line.split()[1]
                out.setdefault(name, []).append(None)
            elif name and line.startswith(" -1") and int(line[3:13]) == nid:
                body = line[13:].rstrip("\n")
                out[name][-1] = tuple(float(body[i:i + 12]) for i in range(0, len(body), 12))
            elif line.startswith(" -3"):
                name = None
    return out


def punch_records(workdir, job, weights, centre, below, p_end, n_inc, loaded):
    """The records of a finished punch run (3D patch or plane strip): rows (increment, p, mean
    displacement under the load (sum of weights[node] times -u_y), -u_y at `centre`, PEEQ and
    von Mises at `below`, the base reaction F_y), row 0 unloaded; every record checked present
    and the base reaction equal to p times the `loaded` area (CalculiX prints 7 digits)."""
    dat = plane_recipe.parse_dat(os.path.join(workdir, job + ".dat"))
    frd = parse_frd_node(os.path.join(workdir, job + ".frd"), below)
    disp, tot = dat.get(("displacements", "MON"), []), dat.get(("total force", "BASE"), [])
    stress, pe = frd.get("STRESS", []), frd.get("PE", [])
    counts = [len(disp), len(tot), len(stress), len(pe)]
    if any(c != n_inc for c in counts) or None in stress or None in pe:
        raise RuntimeError("%s: %d increments expected; U, RF, STRESS, PE records: %s"
                           % (job, n_inc, counts))
    rows = [[0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]]
    for k in range(n_inc):
        p = p_end * (k + 1) / n_inc
        mean = sum(w * -disp[k][nid][1] for nid, w in weights.items())
        s = np.array(stress[k][:6])
        rows.append([k + 1, p, mean, -disp[k][centre][1], pe[k][0],
                     float(plane_recipe.von_mises(s)), tot[k][0][1]])
        if abs(tot[k][0][1] - p * loaded) > 1e-5 * p * loaded:
            raise RuntimeError("%s, increment %d: base reaction %g, applied %g"
                               % (job, k + 1, tot[k][0][1], p * loaded))
    return rows


def solve(mesh, workdir, tag):
    """Write the deck, run ccx, parse: rows (increment, p, mean patch
    displacement, -u_y at the centre, PEEQ and von Mises at (0, 4, 0), base
    reaction F_y), row 0 unloaded."""
    job = "%s_%s" % (NAME, tag)
    deck = os.path.join(workdir, job + ".inp")
    faces = patch_faces(mesh)
    weights = patch_weights(faces)
    centre, below = mesh.find(CENTRE), mesh.find(BELOW)
    mon = sorted(set(weights) | {centre, below})
    t0 = time.time()
    write_deck(deck, mesh, faces, mon)
    elastic_recipe.run_ccx(workdir, job)
    wall = time.time() - t0
    rows = punch_records(workdir, job, weights, centre, below, P_END, N_INC, PATCH * PATCH)
    newton = plane_recipe.newton_stats(os.path.join(workdir, job + ".sta"))
    return dict(mesh=mesh, rows=rows, deck=deck, deck_bytes=os.path.getsize(deck),
                wall=wall, newton=newton, nfaces=len(faces))


# --------------------------------------------------------------------------
# output
# --------------------------------------------------------------------------
def write_curve(path, rows, columns=COLUMNS):
    """A table of rows whose first entry is the increment, its other values to 11 digits."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for r in rows:
            w.writerow([r[0]] + ["%.10e" % v for v in r[1:]])


def tag_of(h):
    return "h%g" % h


def write_study(out, prefix, results, columns, dofs_per_node):
    """Writes a mesh study whose runs all succeeded: PREFIX_<tag>.csv per run (`columns`, the
    increment first), its deck where it is below MAX_KEEP_DECK, and convergence.csv (each run's
    final values of columns[2:6] and their change from the previous run); prints the changes."""
    os.makedirs(out, exist_ok=True)
    for tag, res in results:
        write_curve(os.path.join(out, "%s_%s.csv" % (prefix, tag)), res["rows"], columns)
        keep = os.path.join(out, "%s_%s.inp" % (prefix, tag))
        if res["deck_bytes"] < MAX_KEEP_DECK:
            os.replace(res["deck"], keep)
        elif os.path.exists(keep):
            os.remove(keep)
    with open(os.path.join(out, "convergence.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["mesh", "elements", "nodes", "dofs", "wall_s", "newton_iterations"]
                   + columns[2:6] + ["rel_change_" + c for c in columns[2:6]])
        prev = None
        for tag, res in results:
            last = res["rows"][-1]
            ch = ["" if prev is None else "%.3e" % ((last[c] - prev[c]) / last[c])
                  for c in (2, 3, 4, 5)]
            w.writerow([tag, res["mesh"].nelems, res["mesh"].nnodes,
                        dofs_per_node * res["mesh"].nnodes, "%.1f" % res["wall"],
                        res["newton"][2]] + ["%.7g" % last[c] for c in (2, 3, 4, 5)] + ch)
            prev = last
    print("rel. change of the final values against the previous mesh (%s):"
          % ", ".join(columns[2:6]))
    for (t0, r0), (t1, r1) in zip(results[:-1], results[1:]):
        a, b = r0["rows"][-1], r1["rows"][-1]
        print("  %s -> %s: %s" % (t0, t1, ", ".join("%.3e" % ((b[c] - a[c]) / b[c])
                                                      for c in (2, 3, 4, 5))))


def full_run(out, work, hs, graded):
    runs = [(tag_of(h), uniform_mesh(h)) for h in hs]
    if graded:
        runs.append(("graded", graded_mesh()))
    results = []
    for tag, mesh in runs:
        print("%s (%s): %d elements, %d nodes, %d DOFs ..."
              % (tag, mesh.label, mesh.nelems, mesh.nnodes, 3 * mesh.nnodes), flush=True)
        res = solve(mesh, work, tag)
        last = res["rows"][-1]
        print("  %.1f s, %d increments, %d cut back, %d Newton iterations; at p = %g: "
              "mean patch disp %.7g, centre %.7g, PEEQ(0,4,0) %.5g, von Mises %.5g"
              % ((res["wall"],) + res["newton"] + (last[1], last[2], last[3], last[4],
                                                    last[5])), flush=True)
        results.append((tag, res))
    write_study(out, "punch", results, COLUMNS, 3)  # every run succeeded: only now write


def quick_run(out, work):
    res = solve(uniform_mesh(1.0), work, "quick")
    ref = read_curve(os.path.join(out, "punch_h1.csv"))
    got = [[float(v) for v in r] for r in res["rows"]]
    worst = max(largest_difference(got, ref, c) for c in range(1, len(COLUMNS)))
    print("quick check: max relative difference %.3e" % worst)
    return 0 if worst <= QUICK_TOL else 1


def add_arguments(ap):
    ap.add_argument("--h", type=float, nargs="+", default=DEFAULT_H,
                    help="uniform element sizes (8/h and 2/h integers)")
    ap.add_argument("--graded", action="store_true",
                    help="also run the graded mesh (0.25 near the patch)")


def main():
    elastic_recipe.recipe_main(__doc__, DEFAULT_OUT,
                               lambda out, work, args: full_run(out, work, args.h, args.graded),
                               quick_run, add_arguments)

if __name__ == "__main__":
    main()
