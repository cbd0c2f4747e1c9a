#!/usr/bin/python3
"""Regenerate the CalculiX C3D20R reference of the thick perforated plate
(force-displacement curve of a 3-D elastoplastic plate, mesh-converged).

Run from the repository root:

    /usr/bin/python3 scripts/fe_reference/make_calculix_3d_reference.py
    /usr/bin/python3 scripts/fe_reference/make_calculix_3d_reference.py --quick

Full run: all mesh levels and checks, writes
reference/calculix_3d/thick_perforated_plate/.
--quick: remakes only the coarsest level in a temporary folder and compares
it with the committed curve_level0.csv; prints "quick check: max relative
difference ..." and exits 1 if any value differs by more than 1e-6 of the
largest |value| of its column.
--out DIR (or CALCULIX_REFERENCE_OUT=DIR) writes into DIR instead.
--checks: only the checks against the committed curve.csv that need no
rerun of the levels (the gmsh mesh, the plane-stress contrast).

Needs python3 with numpy, `ccx` (Debian calculix-ccx 2.20) and, for the
full run and --checks, the `gmsh` command line (4.8).  CalculiX
runs single-threaded (bit-reproducible); CCX_REF_THREADS=2 uses two threads.

Problem (kgf, mm, kgf/mm^2): the perforated strip of Zienkiewicz, Valliappan
& King made 5 mm thick.  One eighth is modelled: x in [0, 10], y in [0, 18],
z in [0, 2.5] (mid-plane z = 0) minus the cylinder x^2 + y^2 < 25.  E = 7000,
nu = 0.2, von Mises with sigma_y = 24.3 + 224 alpha.  u_x = 0 on x = 0,
u_y = 0 on y = 0, u_z = 0 on z = 0; the face y = 18 is moved by u_y = v
(u_x, u_z free), v = 0 ... 0.1 mm in 20 fixed increments (*STATIC, DIRECT).
Small strain.  The force is the total reaction F_y on the face y = 18 of the
modelled eighth.

Method (details and results: reference/calculix_3d/README.md)
------
* Hexahedral meshes: the mapped three-block quadrilateral mesh of the plane
  strip (make_calculix_plastic_reference.mesh_strip: n elements along each
  45-degree arc block) extruded in nz equal layers through the half
  thickness into 20-node bricks.  Midside nodes sit at the mapped parameter
  midpoints: every node of the hole surface lies on the circle.
* Levels (n, nz) = (8, 1), (16, 2), (24, 3): C3D20R (reduced 2x2x2
  integration).  The finest level is also run with C3D20 (full 3x3x3
  integration) as a check, the middle level with the increments halved,
  and the coarsest level as a thin slab against the committed plane-stress
  CalculiX curve (a check of the deck: conditions, material, force).
* An independent mesher: two unstructured gmsh meshes of the eighth
  (Frontal-Delaunay quadrangles recombined, extruded in layers, second
  order; the gmsh command line) with C3D20R against the finest level.
* The thick plate's force against the converged plane-stress force x the
  half thickness (how far the 3-D answer lies from plane stress).
* Elastic limit: a linear run at v = 1 per level; the largest von Mises
  stress over the integration points, and over the corner nodes (2x2x2
  values extrapolated trilinearly to the corners, averaged over elements).

Output (reference/calculix_3d/thick_perforated_plate/)
------
curve.csv (finest level), curve_level0.csv (coarsest), convergence.csv,
elastic_limit.csv, thick_perforated_plate.inp (deck of the finest level).
"""

import argparse
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_calculix_reference as elastic_recipe  # noqa: E402  (run_ccx, deck helpers)
import make_calculix_plastic_reference as plane_recipe  # noqa: E402  (strip mesh, parsing)

REPO_ROOT = elastic_recipe.REPO_ROOT
NAME = "thick_perforated_plate"
DEFAULT_OUT = os.path.join(REPO_ROOT, "reference", "calculix_3d")
PLANE_DIR = os.path.join(REPO_ROOT, "reference", "calculix_plastic", "perforated_strip")
PLANE_CURVE0 = os.path.join(PLANE_DIR, "curve_level0.csv")
QUICK_TOL = 1e-6
E_MOD, NU, SIG_Y, H_LIN = 7000.0, 0.2, 24.3, 224.0
HALF_T = 2.5                   # half thickness (plate 5 mm), z in [0, HALF_T]
LENGTH = plane_recipe.STRIP_L  # the driven face y = 18
V_END, N_INC = 0.1, 20
LEVELS = [(8, 1), (16, 2), (24, 3)]
THIN_T = 0.005                 # thin-slab check: 1e-3 x ligament, as the plane recipe
# Newton tolerances (*CONTROLS, PARAMETERS=FIELD): residual <= R_N x average
# force, correction <= C_N x largest increment; far tighter than CalculiX's
# defaults (0.005, 0.01), so that the iterations do not limit the accuracy.
CONTROL_RN = 1e-8
CONTROL_CN = 1e-8
# monitors: (column, point, component 0/1/2); every point is a node of every level
MONITORS = [("ux_10_0_0", (10.0, 0.0, 0.0), 0), ("ux_10_0_25", (10.0, 0.0, HALF_T), 0),
            ("ux_5_0_0", (5.0, 0.0, 0.0), 0), ("ux_5_0_25", (5.0, 0.0, HALF_T), 0),
            ("uz_5_0_25", (5.0, 0.0, HALF_T), 2), ("uy_0_5_0", (0.0, 5.0, 0.0), 1)]
COLUMNS = ["increment", "v", "force_y"] + [c for c, _p, _k in MONITORS]

# C3D20 node order (CalculiX): natural coordinates of nodes 1..20
HEX20_XI = np.array([(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
                     (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1),
                     (0, -1, -1), (1, 0, -1), (0, 1, -1), (-1, 0, -1),
                     (0, -1, 1), (1, 0, 1), (0, 1, 1), (-1, 0, 1),
                     (-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], dtype=float)
G2 = 1.0 / math.sqrt(3.0)
# 2x2x2 integration points in CalculiX's order (xi fastest, then eta, zeta)
IP8 = np.array([(a, b, c) for c in (-G2, G2) for b in (-G2, G2) for a in (-G2, G2)])


# --------------------------------------------------------------------------
# mesh
# --------------------------------------------------------------------------
def hex20_shape(p):
    """Serendipity shape functions of the 20-node brick at natural point p
    ([Zienkiewicz, Taylor & Zhu 2013], node order of CalculiX C3D20)."""
    out = np.empty(20)
    for a, q in enumerate(HEX20_XI):
        f = [1.0 + p[i] * q[i] if q[i] else 1.0 - p[i] * p[i] for i in range(3)]
        n = f[0] * f[1] * f[2]
        out[a] = n * (p @ q - 2.0) / 8.0 if a < 8 else n / 4.0
    return out


def hex20_dshape(p, eps=1e-6):
    """dN/dxi by central differences (exact to O(eps^2) for these cubics)."""
    d = np.empty((20, 3))
    for i in range(3):
        e = np.zeros(3)
        e[i] = eps
        d[:, i] = (hex20_shape(p + e) - hex20_shape(p - e)) / (2 * eps)
    return d


class HexMesh:
    """20-node bricks: node coordinates (ids 1..n), elements with 20 ids."""

    def __init__(self, xyz, elems, label, h):
        self.xyz = np.asarray(xyz, dtype=float)
        self.elems = np.asarray(elems, dtype=int)
        self.label, self.h = label, h
        self.top = float(self.xyz[:, 2].max())
        self._lookup = {tuple(np.round(p, 7)): k + 1 for k, p in enumerate(self.xyz)}

    @property
    def nnodes(self):
        return len(self.xyz)

    @property
    def nelems(self):
        return len(self.elems)

    def find(self, p):
        nid = self._lookup.get(tuple(np.round(p, 7)))
        if nid is None:
            raise ValueError("%s is not a node of mesh %s" % (p, self.label))
        return nid

    def monitor_ids(self):
        """Node ids of the monitors; their z = HALF_T means this mesh's top
        face (the thin slab of the plane-stress check is thinner)."""
        return [self.find((x, y, z * self.top / HALF_T)) for _c, (x, y, z), _k in MONITORS]

    def nodes_where(self, axis, value):
        return [k + 1 for k in np.flatnonzero(np.abs(self.xyz[:, axis] - value) < 1e-9)]

    def min_detj(self):
        """Smallest det J over the 3x3x3 Gauss points of all elements,
        divided by volume / 8 (1 for a parallelepiped)."""
        g = math.sqrt(0.6)
        pts = [np.array((a, b, c)) for a in (-g, 0, g) for b in (-g, 0, g) for c in (-g, 0, g)]
        wts = [wa * wb * wc for wa in (5 / 9, 8 / 9, 5 / 9) for wb in (5 / 9, 8 / 9, 5 / 9)
               for wc in (5 / 9, 8 / 9, 5 / 9)]
        xe = self.xyz[self.elems - 1]                          # (ne, 20, 3)
        dets = np.array([np.linalg.det(np.einsum("eak,al->ekl", xe, hex20_dshape(p)))
                         for p in pts])                        # (27, ne)
        vol = (dets * np.array(wts)[:, None]).sum(axis=0)
        return float((dets / (vol / 8.0)).min())


def extrude(qmesh, nz, thickness):
    """Extrude a CPS8 mesh (corners counter-clockwise seen from +z) in nz
    equal layers over z in [0, thickness] into C3D20 bricks."""
    nq = qmesh.nnodes
    corner = sorted(set(qmesh.elems[:, :4].ravel().tolist()))
    cid = {c: k for k, c in enumerate(corner)}
    xyz, full_id, mid_id = [], {}, {}
    for j in range(2 * nz + 1):
        z = thickness * j / (2 * nz)
        if j % 2 == 0:        # element faces: every node of the plane mesh
            for q in range(1, nq + 1):
                xyz.append((*qmesh.xy[q - 1], z))
                full_id[(j // 2, q)] = len(xyz)
        else:                 # layer mid-planes: the vertical edges' midpoints
            for q in corner:
                xyz.append((*qmesh.xy[q - 1], z))
                mid_id[(j // 2, cid[q])] = len(xyz)
    elems = []
    for layer in range(nz):
        for conn in qmesh.elems:
            bot = [full_id[(layer, q)] for q in conn]
            top = [full_id[(layer + 1, q)] for q in conn]
            mid = [mid_id[(layer, cid[q])] for q in conn[:4]]
            elems.append(bot[:4] + top[:4] + bot[4:] + top[4:] + mid)
    return elems, xyz


def plate_mesh(n, nz, thickness=HALF_T):
    q = plane_recipe.mesh_strip(n)
    elems, xyz = extrude(q, nz, thickness)
    return HexMesh(xyz, elems, "n=%d nz=%d" % (n, nz), q.h)


# gmsh: the eighth meshed without structure (Frontal-Delaunay quads,
# recombined, extruded in layers), second order without face/volume nodes
GMSH_GEO = """lh = %(lh)r; lf = %(lf)r;
Point(1) = {5, 0, 0, lh}; Point(2) = {10, 0, 0, lf}; Point(3) = {10, 18, 0, lf};
Point(4) = {0, 18, 0, lf}; Point(5) = {0, 5, 0, lh}; Point(6) = {0, 0, 0, lh};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5};
Circle(5) = {5, 6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Recombine Surface{1};
Extrude {0, 0, %(t)r} { Surface{1}; Layers{%(nz)d}; Recombine; }
Mesh.Algorithm = 6; Mesh.RecombinationAlgorithm = 1;
Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
Mesh.MshFileVersion = 2.2;
"""
# gmsh's 20-node hexahedron (MSH type 17) node for each CalculiX C3D20 node
GMSH_TO_CCX20 = [0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15]
GMSH_CHECKS = [dict(lh=0.2, lf=1.0, nz=2), dict(lh=0.12, lf=0.6, nz=3)]


def gmsh_mesh(work, lh, lf, nz):
    """The eighth meshed by the gmsh command line (sizes lh at the hole, lf
    at the far corners, nz layers); only its 20-node bricks are kept, with
    the nodes they use, renumbered."""
    geo, msh = os.path.join(work, "plate.geo"), os.path.join(work, "plate.msh")
    with open(geo, "w") as f:
        f.write(GMSH_GEO % dict(lh=lh, lf=lf, t=HALF_T, nz=nz))
    p = subprocess.run(["gmsh", geo, "-3", "-o", msh], capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("gmsh failed (rc=%d): %s" % (p.returncode, p.stderr[-2000:]))
    with open(msh) as f:
        lines = f.read().split("\n")
    i = lines.index("$Nodes")
    nodes = {int(r.split()[0]): [float(v) for v in r.split()[1:4]]
             for r in lines[i + 2:i + 2 + int(lines[i + 1])]}
    i = lines.index("$Elements")
    hexes = []
    for r in lines[i + 2:i + 2 + int(lines[i + 1])]:
        v = [int(t) for t in r.split()]
        if v[1] == 17:
            conn = v[3 + v[2]:]
            hexes.append([conn[k] for k in GMSH_TO_CCX20])
    used = sorted({n for h in hexes for n in h})
    new = {old: k + 1 for k, old in enumerate(used)}
    return HexMesh([nodes[n] for n in used], [[new[n] for n in h] for h in hexes],
                   "gmsh lh=%g lf=%g nz=%d" % (lh, lf, nz), lh)


# --------------------------------------------------------------------------
# CalculiX deck, run, parse
# --------------------------------------------------------------------------
def write_deck(path, mesh, etype="C3D20R", mode="plastic", inc_factor=1):
    """mode 'plastic': v = 0 ... V_END in N_INC x inc_factor fixed
    increments; mode 'elastic': linear material, one increment to v = 1,
    stresses at the integration points."""
    fc, wl = elastic_recipe.fmt_coord, elastic_recipe.write_list
    with open(path, "w") as f:
        f.write("** CalculiX reference deck, generated by "
                "scripts/fe_reference/make_calculix_3d_reference.py\n")
        f.write("** %s, mesh %s: %d %s elements, %d nodes; units kgf, mm, kgf/mm^2\n"
                % (NAME, mesh.label, mesh.nelems, etype, mesh.nnodes))
        f.write("*HEADING\n%s %s %s %s\n" % (NAME, mesh.label, etype, mode))
        f.write("*NODE, NSET=NALL\n")
        for k, (x, y, z) in enumerate(mesh.xyz):
            f.write("%d, %s, %s, %s\n" % (k + 1, fc(x), fc(y), fc(z)))
        f.write("*ELEMENT, TYPE=%s, ELSET=EALL\n" % etype)
        for k, conn in enumerate(mesh.elems):
            ids = [str(c) for c in conn]
            f.write("%d, %s,\n%s\n" % (k + 1, ", ".join(ids[:15]), ", ".join(ids[15:])))
        for name, axis, value in (("SYMX", 0, 0.0), ("SYMY", 1, 0.0), ("SYMZ", 2, 0.0),
                                  ("DRIVE", 1, LENGTH)):
            f.write("*NSET, NSET=%s\n" % name)
            wl(f, mesh.nodes_where(axis, value))
        f.write("*NSET, NSET=MON\n")
        wl(f, sorted(set(mesh.monitor_ids())))
        f.write("*MATERIAL, NAME=MAT1\n*ELASTIC\n%r, %r\n" % (E_MOD, NU))
        if mode == "plastic":
            f.write("** von Mises yield stress vs equivalent plastic strain: linear hardening\n"
                    "*PLASTIC\n")
            for s, a in plane_recipe.linear_table(SIG_Y, H_LIN, 10.0):
                f.write("%.12g, %.12g\n" % (s, a))
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=MAT1\n")
        f.write("*BOUNDARY\nSYMX, 1, 1\nSYMY, 2, 2\nSYMZ, 3, 3\n")
        ninc = N_INC * inc_factor
        f.write("*STEP, INC=%d\n" % (ninc + 10))
        if mode == "plastic":
            f.write("*STATIC, DIRECT\n%.12g, 1.0\n" % (1.0 / ninc))
            f.write("*CONTROLS, PARAMETERS=FIELD\n%g, %g\n" % (CONTROL_RN, CONTROL_CN))
            f.write("*BOUNDARY\nDRIVE, 2, 2, %r\n" % V_END)
        else:
            f.write("*STATIC\n*BOUNDARY\nDRIVE, 2, 2, 1.0\n")
        f.write("*NODE PRINT, NSET=MON\nU\n")
        f.write("*NODE PRINT, NSET=DRIVE, TOTALS=ONLY\nRF\n")
        if mode == "elastic":
            f.write("*EL PRINT, ELSET=EALL\nS\n")
        else:
            f.write("*EL FILE\nPEEQ\n")
        f.write("*END STEP\n")


def solve(mesh, workdir, tag, etype="C3D20R", mode="plastic", inc_factor=1):
    """Write the deck, run ccx; curve rows (v, F_y, monitors) with row 0 the
    unloaded state, the Newton statistics and, for 'elastic', the stresses."""
    job = "%s_%s" % (NAME, tag)
    deck = os.path.join(workdir, job + ".inp")
    t0 = time.time()
    write_deck(deck, mesh, etype, mode, inc_factor)
    elastic_recipe.run_ccx(workdir, job)
    wall = time.time() - t0
    dat = plane_recipe.parse_dat(os.path.join(workdir, job + ".dat"))
    ninc = N_INC * inc_factor if mode == "plastic" else 1
    vend = V_END if mode == "plastic" else 1.0
    disp, tot = dat[("displacements", "MON")], dat[("total force", "DRIVE")]
    if len(disp) != ninc or len(tot) != ninc:
        raise RuntimeError("%s: %d increments expected, %d / %d in the .dat file"
                           % (job, ninc, len(disp), len(tot)))
    ids = mesh.monitor_ids()
    rows = [[0.0] * (2 + len(ids))]
    for k in range(ninc):
        rows.append([vend * (k + 1) / ninc, tot[k][0][1]]
                    + [disp[k][i][c] for i, (_n, _p, c) in zip(ids, MONITORS)])
    res = dict(mesh=mesh, deck=deck, deck_bytes=os.path.getsize(deck), wall=wall,
               curve=np.array(rows), etype=etype)
    if mode == "plastic":
        res["newton"] = plane_recipe.newton_stats(os.path.join(workdir, job + ".sta"))
        res["peeq_max"] = plane_recipe.parse_frd_peeq(os.path.join(workdir, job + ".frd"))
    else:
        res["stress"] = dat[("stresses", "EALL")][0]
    return res


# --------------------------------------------------------------------------
# elastic limit
# --------------------------------------------------------------------------
def elastic_limit(res):
    """Largest von Mises stress of the unit-load run over the 2x2x2
    integration points, and over the corner nodes (the trilinear field
    through the 8 points, evaluated at the corners xi = +-1, averaged over
    the elements at a node), with locations."""
    mesh = res["mesh"]
    ne = mesh.nelems
    st = np.zeros((ne, 8, 6))
    for (e, ip), v in res["stress"].items():
        st[e - 1, ip - 1] = v
    vm = plane_recipe.von_mises(st)
    e, ip = np.unravel_index(np.argmax(vm), vm.shape)
    xyz_ip = hex20_shape(IP8[ip]) @ mesh.xyz[mesh.elems[e] - 1]
    # trilinear interpolation through the points at +-G2: weight of point b
    # at natural point p is prod (1 + p_i s_i / G2) / 2, s = sign of b
    ex = np.array([[np.prod((1.0 + c * np.sign(b) / G2) / 2.0) for b in IP8]
                   for c in HEX20_XI[:8]])                     # (8 corners, 8 points)
    nodal = np.einsum("ak,ekc->eac", ex, st)
    acc = np.zeros((mesh.nnodes, 6))
    cnt = np.zeros(mesh.nnodes)
    np.add.at(acc, mesh.elems[:, :8] - 1, nodal)
    np.add.at(cnt, mesh.elems[:, :8] - 1, 1.0)
    used = cnt > 0
    vm_n = np.zeros(mesh.nnodes)
    vm_n[used] = plane_recipe.von_mises(acc[used] / cnt[used, None])
    k = int(np.argmax(vm_n))
    return dict(ip=float(vm[e, ip]), xyz_ip=tuple(xyz_ip), node=float(vm_n[k]),
                xyz_node=tuple(mesh.xyz[k]), unit_force=float(res["curve"][1, 1]))


# --------------------------------------------------------------------------
# comparisons, output
# --------------------------------------------------------------------------
def differences(ref, other):
    """Per column: max |difference| / max |reference| over the records; and
    the force's largest difference relative to the force of its own record."""
    scale = np.abs(ref).max(axis=0)
    scale[scale == 0] = 1.0
    col = np.abs(ref - other).max(axis=0) / scale
    f_ref, f_oth = ref[1:, 1], other[1:, 1]
    per_inc = float(np.max(np.abs(f_oth - f_ref) / np.abs(f_ref)))
    return col, per_inc


def describe(col, per_inc):
    return ("force %.2e of max |F|, %.2e of F at its own increment; displacements %.2e [%s]"
            % (col[1], per_inc, col[2:].max(),
               ", ".join("%s %.1e" % (c, v) for c, v in zip(COLUMNS[3:], col[2:]))))


def write_curve(path, curve):
    with open(path, "w") as f:
        f.write(",".join(COLUMNS) + "\n")
        for k, row in enumerate(curve):
            f.write("%d," % k + ",".join("%.10e" % v for v in row) + "\n")


def read_curve(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(v) for v in r[1:]] for r in rows[1:]])


def run_level(lev, n, nz, work, etype="C3D20R"):
    mesh = plate_mesh(n, nz)
    detj = mesh.min_detj()
    if detj <= 0:
        raise RuntimeError("mesh %s has a non-positive Jacobian" % mesh.label)
    r = solve(mesh, work, "L%d_%s" % (lev, etype), etype)
    inc, cut, its = r["newton"]
    print("  level %d %-11s %s elems=%6d nodes=%6d dofs=%7d min detJ/(V/8)=%.3f | ccx %7.1fs, "
          "%d increments (%d failed), %d iterations, max PEEQ %.4g, F(v=%g) = %.7g"
          % (lev, mesh.label, etype, mesh.nelems, mesh.nnodes, 3 * mesh.nnodes, detj,
             r["wall"], inc, cut, its, r["peeq_max"] or 0.0, V_END, r["curve"][-1, 1]))
    sys.stdout.flush()
    return r


def thin_slab_check(work):
    """The coarsest in-plane mesh as a thin slab (C3D20, as CalculiX expands
    CPS8) against the committed plane-stress curve of the same mesh: the
    force per unit thickness at the common records v = 0.01 k."""
    mesh = plate_mesh(LEVELS[0][0], 1, THIN_T)
    r = solve(mesh, work, "L0_thin", "C3D20")
    _hdr, plane = read_curve(PLANE_CURVE0)
    worst = 0.0
    for row in r["curve"][1:]:
        k = int(np.argmin(np.abs(plane[:, 0] - row[0])))
        if abs(plane[k, 0] - row[0]) < 1e-12:
            worst = max(worst, abs(row[1] / THIN_T - plane[k, 1]) / abs(plane[:, 1]).max())
    print("  thin slab (z in [0, %g], C3D20, level 0 in-plane mesh, ccx %.1fs) vs the plane-"
          "stress curve_level0.csv of perforated_strip: force per unit thickness differs by "
          "%.2e of max |F| at the common records" % (THIN_T, r["wall"], worst))
    return worst


def plane_stress_contrast(curve):
    """The thick plate's force against the converged plane-stress force per
    unit thickness times the half thickness, at the records both curves
    hold: (v, relative excess) per common record."""
    _hdr, plane = read_curve(os.path.join(PLANE_DIR, "curve.csv"))
    out = []
    for row in curve[1:]:
        k = int(np.argmin(np.abs(plane[:, 0] - row[0])))
        if abs(plane[k, 0] - row[0]) < 1e-12:
            out.append((row[0], row[1] / (HALF_T * plane[k, 1]) - 1.0))
    print("  thick plate vs plane stress (converged perforated_strip curve x %g): force "
          "higher by %s" % (HALF_T, ", ".join("%.2f%% at v = %g" % (100 * d, v) for v, d in out)))
    return out


def gmsh_check(work, curve):
    """Unstructured gmsh meshes of the eighth (GMSH_CHECKS) with C3D20R
    against `curve` (the finest level)."""
    for k, sizes in enumerate(GMSH_CHECKS):
        mesh = gmsh_mesh(work, **sizes)
        detj = mesh.min_detj()
        if detj <= 0:
            raise RuntimeError("mesh %s has a non-positive Jacobian" % mesh.label)
        r = solve(mesh, work, "gmsh%d" % k)
        col, per_inc = differences(curve, r["curve"])
        print("  gmsh mesh (%s: %d elements, %d nodes, min detJ/(V/8)=%.3f; ccx %.1fs, %d "
              "iterations) vs the finest level: %s"
              % (mesh.label, mesh.nelems, mesh.nnodes, detj, r["wall"], r["newton"][2],
                 describe(col, per_inc)))
        sys.stdout.flush()


def full_run(out, work):
    outdir = os.path.join(out, NAME)
    os.makedirs(outdir, exist_ok=True)
    results = [run_level(lev, n, nz, work) for lev, (n, nz) in enumerate(LEVELS)]
    finest = results[-1]
    write_curve(os.path.join(outdir, "curve.csv"), finest["curve"])
    write_curve(os.path.join(outdir, "curve_level0.csv"), results[0]["curve"])
    shutil.copyfile(finest["deck"], os.path.join(outdir, NAME + ".inp"))
    print("  mesh convergence, level vs finest over all %d increments:" % N_INC)
    with open(os.path.join(outdir, "convergence.csv"), "w") as f:
        f.write("level,n,nz,h,max_rel_diff_force,max_rel_diff_force_per_increment,"
                "max_rel_diff_disp\n")
        for lev, r in enumerate(results[:-1]):
            col, per_inc = differences(finest["curve"], r["curve"])
            print("    level %d (%s): %s" % (lev, r["mesh"].label, describe(col, per_inc)))
            f.write("%d,%d,%d,%.10e,%.4e,%.4e,%.4e\n" % (lev, LEVELS[lev][0], LEVELS[lev][1],
                                                        r["mesh"].h, col[1], per_inc,
                                                        col[2:].max()))
    rf = solve(finest["mesh"], work, "L%d_C3D20" % (len(LEVELS) - 1), "C3D20")
    col, per_inc = differences(finest["curve"], rf["curve"])
    print("  C3D20 (full integration) on the finest level (ccx %.1fs, %d iterations): %s"
          % (rf["wall"], rf["newton"][2], describe(col, per_inc)))
    mid = len(LEVELS) // 2
    rh = solve(results[mid]["mesh"], work, "L%d_half" % mid, inc_factor=2)
    col, per_inc = differences(results[mid]["curve"], rh["curve"][::2])
    print("  increments halved on level %d (ccx %.1fs, %d iterations): %s"
          % (mid, rh["wall"], rh["newton"][2], describe(col, per_inc)))
    thin_slab_check(work)
    plane_stress_contrast(finest["curve"])
    gmsh_check(work, finest["curve"])
    print("  elastic limit (linear run at v = 1):")
    with open(os.path.join(outdir, "elastic_limit.csv"), "w") as f:
        f.write("level,n,nz,force_at_unit_v,max_vm_ip,x_ip,y_ip,z_ip,max_vm_node,x_node,"
                "y_node,z_node,first_yield_v_ip,first_yield_v_node\n")
        for lev, r in enumerate(results):
            lim = elastic_limit(solve(r["mesh"], work, "L%d_elastic" % lev, mode="elastic"))
            vy_ip, vy_n = SIG_Y / lim["ip"], SIG_Y / lim["node"]
            print("    level %d: F(v=1) = %.7g; max vM at integration points %.6g at (%.4g, %.4g, "
                  "%.4g) -> first yield v = %.5e (F = %.5g); at nodes %.6g at (%.4g, %.4g, %.4g) "
                  "-> v = %.5e (F = %.5g)"
                  % (lev, lim["unit_force"], lim["ip"], *lim["xyz_ip"], vy_ip,
                     vy_ip * lim["unit_force"], lim["node"], *lim["xyz_node"], vy_n,
                     vy_n * lim["unit_force"]))
            f.write("%d,%d,%d,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e\n"
                    % (lev, LEVELS[lev][0], LEVELS[lev][1], lim["unit_force"], lim["ip"],
                       *lim["xyz_ip"], lim["node"], *lim["xyz_node"], vy_ip, vy_n))
    return 0


def quick_run(out, work):
    outdir = os.path.join(out, NAME)
    os.makedirs(outdir, exist_ok=True)
    r = run_level(0, *LEVELS[0], work)
    write_curve(os.path.join(outdir, "curve_level0.csv"), r["curve"])
    ref = os.path.join(DEFAULT_OUT, NAME, "curve_level0.csv")
    if not os.path.exists(ref):
        sys.stderr.write("no committed %s\n" % os.path.relpath(ref, REPO_ROOT))
        return 1
    hdr, committed = read_curve(ref)
    if hdr != COLUMNS or committed.shape != r["curve"].shape:
        sys.stderr.write("the committed curve_level0.csv has a different layout\n")
        return 1
    col, _ = differences(committed, r["curve"])
    ok = col.max() <= QUICK_TOL
    print("quick check: max relative difference %.2e (tolerance %.0e): %s"
          % (col.max(), QUICK_TOL, "PASSED" if ok else "FAILED"))
    return 0 if ok else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true",
                    help="remake only the coarsest level and compare with the committed one")
    ap.add_argument("--out", default=None, help="output folder (default reference/calculix_3d, "
                    "or $CALCULIX_REFERENCE_OUT)")
    ap.add_argument("--checks", action="store_true",
                    help="only the checks that need no rerun of the levels: the gmsh mesh "
                    "and the plane-stress contrast against the committed curve.csv")
    args = ap.parse_args()
    out = args.out or os.environ.get("CALCULIX_REFERENCE_OUT")
    tmp_out = None
    if args.quick and not out:
        tmp_out = out = tempfile.mkdtemp(prefix="ccx_3d_quick_")
    out = out or DEFAULT_OUT
    t_start = time.time()
    print("CalculiX version %s (%s), %d thread(s); numpy %s; output %s"
          % (elastic_recipe.ccx_version(), shutil.which("ccx"), elastic_recipe.NTHREADS,
             np.__version__, out))
    print("=== %s: E = %g, nu = %g, sigma_y = %g + %g alpha; v = 0 ... %g in %d increments ==="
          % (NAME, E_MOD, NU, SIG_Y, H_LIN, V_END, N_INC))
    with tempfile.TemporaryDirectory(prefix="ccx_3d_") as work:
        if args.checks:
            _hdr, curve = read_curve(os.path.join(DEFAULT_OUT, NAME, "curve.csv"))
            plane_stress_contrast(curve)
            gmsh_check(work, curve)
            status = 0
        else:
            status = quick_run(out, work) if args.quick else full_run(out, work)
    if tmp_out:
        shutil.rmtree(tmp_out, ignore_errors=True)
    print("total run time %.1f s" % (time.time() - t_start))
    return status


if __name__ == "__main__":
    sys.exit(main())
