#!/usr/bin/python3
"""Regenerate the CalculiX CPE8R reference of the elastoplastic plane-strain
strip punch: a strip of a block's top edge pushed in by a uniform pressure,
the strip's mean displacement and the plastic state below it, per mesh.

Run from the repository root:

    /usr/bin/python3 scripts/fe_reference/make_calculix_strip_punch_reference.py
    /usr/bin/python3 scripts/fe_reference/make_calculix_strip_punch_reference.py --h 0.5 0.25
    /usr/bin/python3 scripts/fe_reference/make_calculix_strip_punch_reference.py --quick

Full run: one CalculiX run per uniform mesh (--h, default 0.5, 0.25 and
0.125: 2.5, 14 and 93 s on the 2-core machine, CalculiX expanding each CPE8R
into a 20-node brick with its plane-strain constraints), then writes reference/calculix_plastic/strip_punch/: strip_h<h>.csv
per mesh, convergence.csv and the decks below 1 MB.  Nothing is written
unless every run succeeded (ccx's return code, no *ERROR, all 20 increments
in the .dat and .frd files, the base reaction equal to the applied load).
--quick remakes the h = 0.5 mesh in a temporary folder and compares it with
the committed strip_h0.5.csv (exit 1 beyond 1e-6 of each column's largest
|value|).  --out DIR (or CALCULIX_REFERENCE_OUT=DIR) writes into DIR instead.

Problem (N, mm, MPa; plane strain, 1 mm thick): the half x in [0, 8],
y in [0, 8] of a block 16 mm wide and 8 mm deep.  u_x = 0 on x = 0
(symmetry); u_y = 0 on the base y = 0 (rollers).  A uniform pressure p on the
top edge y = 8 over the strip x in [0, 2] (half of a 4 mm strip) pushes into
the body (-y); p = 0 ... 800 recorded at 20 equal increments (0.05 of
a step of length 1, the *DLOAD ramping linearly; automatic incrementation
with *TIME POINTS at the records, as fixed increments diverge past Prandtl's
limit load (2 + pi) sigma_y / sqrt(3) = 742 MPa).  E = 200000, nu = 0.3, von
Mises with sigma_y = 250 + 2000 alpha (*PLASTIC (250, 0), (20250, 10):
exact, flat beyond alpha = 10).  Small strain.  The plane-strain twin of the
3D punch block (make_calculix_punch_3d_reference.py), problem file
problems/strip_punch_plane_strain.yaml.

Recorded per increment: p; the mean strip displacement along -y, (integral
of -u_y over the strip) / 2, from the nodal u_y of the strip's element edges
(quadratic edge functions, 3 Gauss points: exact); -u_y at the strip centre
(0, 8); the equivalent plastic strain and the von Mises stress (sigma_zz
included) at (0, 4), from CalculiX's values extrapolated to the nodes (*EL
FILE PEEQ, S: the .frd file's nodal PE and STRESS blocks); the total base
reaction F_y (check: = 2 p per mm of thickness).

Method: structured 8-node quadrilaterals on a uniform grid of size h (the
strip's edge x = 2 and the monitor y = 4 on element borders); CPE8R (2 x 2
integration, which does not lock under isochoric plastic flow); CalculiX one
thread (CCX_REF_THREADS), Newton tolerances 1e-8 (the plate recipes').
"""

import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_calculix_reference as elastic_recipe  # noqa: E402  (run_ccx, deck helpers)
import make_calculix_plastic_reference as plane_recipe  # noqa: E402  (mesh, parsing, tables)
from make_calculix_cantilever_3d_reference import quick_verdict  # noqa: E402
from make_calculix_punch_3d_reference import punch_records, write_study  # noqa: E402

NAME = "strip_punch"
DEFAULT_OUT = os.path.join(elastic_recipe.REPO_ROOT, "reference", "calculix_plastic", NAME)
E_MOD, NU, SIG_Y, H_LIN = 200000.0, 0.3, 250.0, 2000.0
SIDE = 8.0                     # the half block [0, 8]^2
STRIP = 2.0                    # loaded strip [0, 2] on y = 8
P_END, N_INC = 800.0, 20
DEFAULT_H = [0.5, 0.25, 0.125]
QUICK_TOL = 1e-6
CENTRE = (0.0, SIDE)           # strip centre
BELOW = (0.0, 4.0)             # 4 mm below it
COLUMNS = ["increment", "p", "mean_strip_disp", "uy_centre", "peeq_0_4", "mises_0_4",
           "reaction_y"]


def uniform_mesh(h):
    n = int(round(SIDE / h))
    if abs(n * h - SIDE) > 1e-12 or abs(STRIP / h - round(STRIP / h)) > 1e-12:
        raise ValueError("h = %g: 8/h and 2/h must be integers" % h)
    lines = list(np.linspace(0.0, SIDE, n + 1))
    return plane_recipe.tensor_mesh(lines, lines, "uniform h=%g (%d x %d)" % (h, n, n), h)


def strip_edges(mesh):
    """[(element id, face number, (corner a, corner b, midside) node ids,
    (x0, x1))] for the element edges on y = 8 inside the strip."""
    out = []
    tol = 1e-9
    for e, conn in enumerate(mesh.elems):
        for f in range(4):
            ids = (conn[f], conn[(f + 1) % 4], conn[4 + f])
            pts = mesh.xy[[i - 1 for i in ids]]
            if np.all(np.abs(pts[:, 1] - SIDE) < tol) and pts[:, 0].max() <= STRIP + tol:
                out.append((e + 1, f + 1, ids, (pts[:, 0].min(), pts[:, 0].max())))
    length = sum(x1 - x0 for *_r, (x0, x1) in out)
    if abs(length - STRIP) > 1e-9:
        raise RuntimeError("strip edges cover %g mm, not %g" % (length, STRIP))
    return out


def strip_weights(edges):
    """{node id: w} with mean(-u_y) = sum w * (-u_y): Simpson's rule on each
    edge (exact for its quadratic u_y), divided by the strip's length."""
    w = {}
    for _e, _f, (a, b, mid), (x0, x1) in edges:
        for nid, share in ((a, 1 / 6), (b, 1 / 6), (mid, 4 / 6)):
            w[nid] = w.get(nid, 0.0) + share * (x1 - x0) / STRIP
    return w


def write_deck(path, mesh, edges, mon):
    wl = elastic_recipe.write_list
    with open(path, "w") as f:
        plane_recipe.write_mesh_cards(f, "make_calculix_strip_punch_reference.py", NAME, mesh,
                                      "CPE8R")
        f.write("*NSET, NSET=SYMX\n")
        wl(f, mesh.nodes_where(lambda x, y: abs(x) < 1e-9))
        f.write("*NSET, NSET=BASE\n")
        wl(f, mesh.nodes_where(lambda x, y: abs(y) < 1e-9))
        f.write("*NSET, NSET=MON\n")
        wl(f, mon)
        f.write("*NSET, NSET=BELOW\n%d,\n" % mesh.find(*BELOW))
        fnums = sorted({fn for _e, fn, _n, _x in edges})
        for fn in fnums:
            f.write("*ELSET, ELSET=STRIPF%d\n" % fn)
            wl(f, [e for e, fn2, _n, _x in edges if fn2 == fn])
        plane_recipe.write_linear_hardening(f, E_MOD, NU, SIG_Y, H_LIN)
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n1.0\n")
        f.write("*BOUNDARY\nSYMX, 1, 1\nBASE, 2, 2\n")
        # automatic incrementation, the largest increment one record; the time points end
        # an increment at every record (fixed increments diverge past Prandtl's limit load)
        f.write("*TIME POINTS, NAME=TP\n")
        f.write("".join("%.12g\n" % (k / N_INC) for k in range(1, N_INC + 1)))
        dt = 1.0 / N_INC
        f.write("*STEP, INC=100000\n*STATIC\n%.12g, 1.0, %.12g, %.12g\n" % (dt, dt * 1e-5, dt))
        f.write("*CONTROLS, PARAMETERS=FIELD\n%g, %g\n"
                % (plane_recipe.CONTROL_RN, plane_recipe.CONTROL_CN))
        f.write("** uniform pressure on the strip (positive: into the body), ramped 0 -> %g\n"
                "*DLOAD\n" % P_END)
        for fn in fnums:
            f.write("STRIPF%d, P%d, %r\n" % (fn, fn, P_END))
        f.write("*NODE PRINT, NSET=MON, TIME POINTS=TP\nU\n"
                "*NODE PRINT, NSET=BASE, TOTALS=ONLY, TIME POINTS=TP\nRF\n")
        f.write("** stresses and equivalent plastic strain extrapolated to the nodes\n"
                "*EL FILE, NSET=BELOW, TIME POINTS=TP\nS, PEEQ\n*END STEP\n")


def solve(mesh, workdir, tag):
    """Write the deck, run ccx, parse: rows (increment, p, mean strip
    displacement, -u_y at the centre, PEEQ and von Mises at (0, 4), base
    reaction F_y), row 0 unloaded."""
    job = "%s_%s" % (NAME, tag)
    deck = os.path.join(workdir, job + ".inp")
    edges = strip_edges(mesh)
    weights = strip_weights(edges)
    centre, below = mesh.find(*CENTRE), mesh.find(*BELOW)
    mon = sorted(set(weights) | {centre, below})
    t0 = time.time()
    write_deck(deck, mesh, edges, mon)
    elastic_recipe.run_ccx(workdir, job)
    wall = time.time() - t0
    rows = punch_records(workdir, job, weights, centre, below, P_END, N_INC, STRIP)
    newton = plane_recipe.newton_stats(os.path.join(workdir, job + ".sta"))
    return dict(mesh=mesh, rows=rows, deck=deck, deck_bytes=os.path.getsize(deck),
                wall=wall, newton=newton)


def full_run(out, work, hs):
    results = []
    for h in hs:
        tag, mesh = "h%g" % h, uniform_mesh(h)
        print("%s (%s): %d elements, %d nodes, %d DOFs ..."
              % (tag, mesh.label, mesh.nelems, mesh.nnodes, 2 * mesh.nnodes), flush=True)
        res = solve(mesh, work, tag)
        last = res["rows"][-1]
        print("  %.1f s, %d increments, %d cut back, %d Newton iterations; at p = %g: "
              "mean strip disp %.7g, centre %.7g, PEEQ(0,4) %.5g, von Mises %.5g"
              % ((res["wall"],) + res["newton"] + tuple(last[1:6])), flush=True)
        results.append((tag, res))
    write_study(out, "strip", results, COLUMNS, 2)  # every run succeeded: only now write


def quick_run(out, work):
    res = solve(uniform_mesh(0.5), work, "quick")
    return quick_verdict(res["rows"], os.path.join(out, "strip_h0.5.csv"), len(COLUMNS), QUICK_TOL)


def main():
    elastic_recipe.recipe_main(
        __doc__, DEFAULT_OUT, lambda out, work, args: full_run(out, work, args.h), quick_run,
        lambda ap: ap.add_argument("--h", type=float, nargs="+", default=DEFAULT_H,
                                   help="uniform element sizes (8/h and 2/h integers)"))

if __name__ == "__main__":
    main()
