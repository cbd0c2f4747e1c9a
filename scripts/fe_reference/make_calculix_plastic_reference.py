#!/usr/bin/python3
"""Regenerate the CalculiX finite-element references for seven elastoplastic
plane-stress problems (load-displacement curves, elastic limits).

Run from the repository root:

    /usr/bin/python3 scripts/fe_reference/make_calculix_plastic_reference.py
    /usr/bin/python3 scripts/fe_reference/make_calculix_plastic_reference.py --quick

Full run: all mesh levels and checks, writes reference/calculix_plastic/
(about 46 min on 2 cores, cook_membrane 10 min and cook_membrane_force 6 min
of it; --quick under 1 min).
--quick: remakes only the coarsest level of every problem in a temporary
folder and compares it with the committed curve_level0.csv files; prints
"quick check: max relative difference ..." and exits 1 if any value differs
by more than 1e-6 of the largest |value| of its column.
--out DIR (or CALCULIX_REFERENCE_OUT=DIR) writes the results into DIR
instead of reference/calculix_plastic (with --quick: the remade coarsest
level goes there, and the committed reference is still the one compared with).
--only NAME[,NAME] restricts the run to some problems.

Needs python3 with numpy and the CalculiX executable `ccx` (Debian package
calculix-ccx 2.20).  CalculiX runs single-threaded by default so that a rerun
gives byte-identical files; CCX_REF_THREADS=2 uses two threads.

Problems (plane stress, thickness 1 mm, small strain, von Mises plasticity
with isotropic hardening, monotonic loading from zero)
--------
plate_plastic_thesis     [0,1]^2, E=200000, nu=0.1, sigma_y=310 perfectly
                         plastic; bottom clamped; top traction q = 77, 154,
                         231, 308, 308.25 MPa (load control).
plate_plastic_limit      same plate; top edge uy = v (ux free), v to 0.01 mm.
plate_asymmetric_plastic [0,2]x[0,1], bottom clamped on 0 <= x <= 1 only;
                         top edge uy = v, v to 0.02 mm.
perforated_strip         quarter of the Zienkiewicz-Valliappan-King strip
                         (kgf, mm): [0,10]x[0,18] minus the disc r=5 at the
                         origin, E=7000, nu=0.2, sigma_y=24.3, H'=224; top
                         edge uy = v, v to 0.1 mm.
beam_voce_bending        [0,10]x[0,2], E=206900, nu=0.29, Voce + linear
                         hardening (Simo's constants); left clamped, right
                         edge uy = -v, v to 0.5 mm.
cook_membrane            Cook's membrane, the quadrilateral (0,0), (48,44),
                         (48,60), (0,44), material of beam_voce_bending;
                         left edge x = 0 clamped, right edge x = 48 uy = v,
                         v to 2 mm.
cook_membrane_force      the same panel, its right edge loaded by a uniform
                         shear traction of resultant F (consistent nodal
                         forces, *CLOAD), F to 3000 N.

Method (details and results: reference/calculix_plastic/README.md)
------
* CPS8 elements (8-node serendipity, full 3x3 integration).  CalculiX
  expands every CPS8 into one layer of C3D20 bricks of the section
  thickness, i.e. it solves a 3-D slab.  The orthotropic trick of
  make_calculix_reference.py cannot be combined with *PLASTIC (which needs
  an isotropic *ELASTIC), so the slab is made thin instead: thickness
  t_s = 1e-3 x the smallest body dimension, so that sigma_zz ~ 0 through
  it.  Tractions and prescribed displacements are unchanged (stresses and
  displacements do not depend on t_s); reaction forces are divided by t_s,
  i.e. reported per unit thickness (= the force on the 1 mm thick body).
  Checks: the coarsest mesh of every problem is rerun with t_s/10, and its
  elastic unit-load solution is compared with the orthotropic-trick
  solution of the elastic recipe.
* *STATIC with automatic incrementation: the largest increment is one record
  spacing and *TIME POINTS end an increment exactly at every record (fixed
  DIRECT increments diverge with the thin slab in the increment where a
  large region yields at once); tight Newton tolerances (*CONTROLS); output
  at the records with *NODE PRINT to the .dat file.
* Convergence: >= 3 mesh levels per problem (coarser levels compared with
  the finest at every increment), and the increments halved once on the
  middle level.
* Elastic limit: a linear run at unit load factor per level, *EL PRINT S at
  the integration points; nodal stresses computed here by extrapolating the
  3x3 Gauss-point values of each element with the biquadratic Lagrange
  polynomial through them and averaging over the elements at a node.
* cook_membrane also prints the yielded area at the last record (from the
  nodal PEEQ of the .frd) and the first-yield forces, and repeats the
  orthotropic cross-check on the finest level.

Output (reference/calculix_plastic/<problem>/)
------
curve.csv, curve_level0.csv, convergence.csv, elastic_limit.csv,
<problem>.inp; plate_plastic_thesis also line_top_308.csv and
line_top_30825.csv.  The perforated-strip mesh of one level is also
written as gmsh MSH 2.2 files problems/meshes/perforated_strip_q8.msh and
perforated_strip_q4.msh (full run only).
"""

import argparse
import csv
import math
import os
import re
import shutil
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_calculix_reference as elastic_recipe  # noqa: E402  (shared helpers)

REPO_ROOT = elastic_recipe.REPO_ROOT
DEFAULT_OUT = os.path.join(REPO_ROOT, "reference", "calculix_plastic")
MESH_DIR = os.path.join(REPO_ROOT, "problems", "meshes")
NTHREADS = elastic_recipe.NTHREADS
MAX_DECK_BYTES = 2_200_000
SLAB_FRACTION = 1e-3          # t_s = SLAB_FRACTION * smallest body dimension
QUICK_TOL = 1e-6              # --quick: allowed difference / column max
PLATEAU = 0.99                # records below this x the largest force: before the plateau
VOCE_TABLE_TOL = 8e-6         # design tolerance of the Voce table (target: < 1e-5)
# Newton tolerances (*CONTROLS, PARAMETERS=FIELD): largest residual force
# <= R_N * average force and largest correction <= C_N * largest increment
# of the solution.  Tighter than the CalculiX defaults (0.005, 0.01), so
# that the equilibrium iterations cannot limit the accuracy of a reference.
CONTROL_RN = 1e-8
CONTROL_CN = 1e-8
GAUSS = math.sqrt(0.6)
MIN_INC = 1e-5             # smallest increment / record spacing


# --------------------------------------------------------------------------
# hardening laws: (equivalent plastic strain, von Mises yield stress) tables
# --------------------------------------------------------------------------
def perfect_table(sig_y):
    """Perfect plasticity; CalculiX continues any table flat."""
    return [(sig_y, 0.0)]


def linear_table(sig_y, h, alpha_max):
    """Linear hardening is exact with two points; alpha_max lies far beyond
    any plastic strain reached (CalculiX continues the table flat)."""
    return [(sig_y, 0.0), (sig_y + h * alpha_max, alpha_max)]


def voce(alpha, s0, sinf, delta, h):
    return s0 + h * alpha + (sinf - s0) * (1.0 - math.exp(-delta * alpha))


def voce_table(s0, sinf, delta, h, alpha_max, tol=None):
    """Points of the Voce + linear law, spaced so that linear interpolation
    is accurate to `tol` (default VOCE_TABLE_TOL) relative: on [a, a + d] the
    error is at most d^2/8 max|f''| = d^2/8 (sinf - s0) delta^2 exp(-delta a)
    and f >= f(a), so d(a) = sqrt(8 tol f(a) / ((sinf - s0) delta^2))
    exp(delta a / 2).  The linear part needs no points, so the spacing grows
    without a cap once the exponential has died out; the table ends at
    alpha_max (CalculiX continues it flat beyond)."""
    tol = VOCE_TABLE_TOL if tol is None else tol
    c = (sinf - s0) * delta * delta
    pts = [0.0]
    while pts[-1] < alpha_max:
        a = pts[-1]
        d = math.sqrt(8.0 * tol * voce(a, s0, sinf, delta, h) / c) * math.exp(0.5 * delta * a)
        pts.append(min(a + d, alpha_max))
    return [(voce(a, s0, sinf, delta, h), a) for a in pts]


def table_interp_error(table, law):
    """Largest relative error of the piecewise-linear table against the
    exact law, sampled at 20 points in every interval."""
    worst = 0.0
    for (s1, a1), (s2, a2) in zip(table[:-1], table[1:]):
        for k in range(1, 20):
            a = a1 + (a2 - a1) * k / 20.0
            lin = s1 + (s2 - s1) * k / 20.0
            worst = max(worst, abs(lin - law(a)) / law(a))
    return worst


# --------------------------------------------------------------------------
# meshes
# --------------------------------------------------------------------------
def graded_lines(length, h0, singular, lg, beta, protect=()):
    """Mesh lines at multiples of h0 plus, within distance lg of every
    coordinate in `singular`, the points s +- lg (k/N)^beta, k = 2..N-1,
    N = ceil(beta lg / h0) (the grading of make_calculix_reference.py, with
    the size of the zone and the protected lines as parameters).  Protected
    lines (multiples of h0 and the coordinates in `protect`) inside a graded
    zone replace the graded point nearest to them, so no slivers appear."""
    n_base = int(round(length / h0))
    base = [length * i / n_base for i in range(n_base + 1)]
    protected = sorted(set(base) | set(protect))
    pts = set(base)
    nn = int(math.ceil(beta * lg / h0 - 1e-9))
    for s in singular:
        for sgn in (-1.0, 1.0):
            g = [s + sgn * lg * (k / nn) ** beta for k in range(2, nn)]
            g = [p for p in g if 0.0 < p < length]
            if not g:
                continue
            prot = [p for p in protected if 0.0 < sgn * (p - s) < lg]
            for p in prot:
                kk = min(range(len(g)), key=lambda q: abs(g[q] - p))
                g[kk] = p
            pts.update(g)
            pts.update(prot)
    out = []
    for p in sorted(pts):
        if out and p - out[-1] < 1e-12:
            if p in protected:
                out[-1] = p
            continue
        out.append(p)
    return out


class QMesh:
    """Unstructured-storage CPS8 mesh: node coordinates (ids 1..n) and
    elements with 8 node ids (corners counter-clockwise, then the midsides of
    edges 1-2, 2-3, 3-4, 4-1, the CalculiX / gmsh order)."""

    def __init__(self, xy, elems, label, h):
        self.xy = np.asarray(xy, dtype=float)
        self.elems = np.asarray(elems, dtype=int)
        self.label = label
        self.h = h
        self._lookup = {}
        for k, (x, y) in enumerate(self.xy):
            self._lookup[(round(x, 7), round(y, 7))] = k + 1

    @property
    def nnodes(self):
        return len(self.xy)

    @property
    def nelems(self):
        return len(self.elems)

    def find(self, x, y):
        """Id of the node at (x, y); the point must be a node."""
        nid = self._lookup.get((round(x, 7), round(y, 7)))
        if nid is None or np.hypot(*(self.xy[nid - 1] - (x, y))) > 1e-9:
            raise ValueError("(%g, %g) is not a node of mesh %s" % (x, y, self.label))
        return nid

    def nodes_where(self, pred):
        return [k + 1 for k, (x, y) in enumerate(self.xy) if pred(x, y)]

    def faces_where(self, pred):
        """[(element id, face number)] of the element edges whose three
        nodes all satisfy pred (face k = edge from corner k to corner k+1)."""
        out = []
        for e, conn in enumerate(self.elems):
            for f in range(4):
                ids = (conn[f], conn[(f + 1) % 4], conn[4 + f])
                if all(pred(*self.xy[i - 1]) for i in ids):
                    out.append((e + 1, f + 1))
        return out

    def min_edge(self):
        c = self.xy[self.elems[:, :4] - 1]
        d = np.linalg.norm(c - np.roll(c, -1, axis=1), axis=2)
        return float(d.min())

    def min_detj(self):
        """Smallest Jacobian determinant over the 3x3 Gauss points of all
        elements, divided by the element area / 4 (1 for a parallelogram)."""
        worst = np.inf
        xe = self.xy[self.elems - 1]                       # (ne, 8, 2)
        area = np.zeros(len(xe))
        dets = []
        for (xi, wx) in zip((-GAUSS, 0.0, GAUSS), (5 / 9, 8 / 9, 5 / 9)):
            for (eta, wy) in zip((-GAUSS, 0.0, GAUSS), (5 / 9, 8 / 9, 5 / 9)):
                dn = q8_dshape(xi, eta)                     # (8, 2)
                jac = np.einsum("eak,al->ekl", xe, dn)      # (ne, 2, 2)
                det = jac[:, 0, 0] * jac[:, 1, 1] - jac[:, 0, 1] * jac[:, 1, 0]
                dets.append(det)
                area += det * wx * wy
        for det in dets:
            worst = min(worst, float((det / (area / 4.0)).min()))
        return worst


def q8_shape(xi, eta):
    xin = (-1, 1, 1, -1, 0, 1, 0, -1)
    etn = (-1, -1, 1, 1, -1, 0, 1, 0)
    n = np.zeros(8)
    for a in range(8):
        xa, ea = xin[a], etn[a]
        if a < 4:
            n[a] = 0.25 * (1 + xi * xa) * (1 + eta * ea) * (xi * xa + eta * ea - 1)
        elif xa == 0:
            n[a] = 0.5 * (1 - xi * xi) * (1 + eta * ea)
        else:
            n[a] = 0.5 * (1 + xi * xa) * (1 - eta * eta)
    return n


def q8_dshape(xi, eta):
    """dN/dxi, dN/deta of the 8-node serendipity element, shape (8, 2)."""
    xin = (-1, 1, 1, -1, 0, 1, 0, -1)
    etn = (-1, -1, 1, 1, -1, 0, 1, 0)
    dn = np.zeros((8, 2))
    for a in range(8):
        xa, ea = xin[a], etn[a]
        if a < 4:
            dn[a, 0] = 0.25 * xa * (1 + eta * ea) * (2 * xi * xa + eta * ea)
            dn[a, 1] = 0.25 * ea * (1 + xi * xa) * (xi * xa + 2 * eta * ea)
        elif xa == 0:
            dn[a, 0] = -xi * (1 + eta * ea)
            dn[a, 1] = 0.5 * ea * (1 - xi * xi)
        else:
            dn[a, 0] = 0.5 * xa * (1 - eta * eta)
            dn[a, 1] = -eta * (1 + xi * xa)
    return dn


def tensor_mesh(xlines, ylines, label, h):
    """Structured CPS8 mesh on the tensor grid xlines x ylines."""
    xs = elastic_recipe.Mesh._half(xlines)
    ys = elastic_recipe.Mesh._half(ylines)
    nx, ny = len(xlines) - 1, len(ylines) - 1
    ids = {}
    xy = []
    for j in range(2 * ny + 1):
        for i in range(2 * nx + 1):
            if i % 2 and j % 2:
                continue
            xy.append((xs[i], ys[j]))
            ids[(i, j)] = len(xy)
    elems = []
    for ey in range(ny):
        for ex in range(nx):
            i0, j0 = 2 * ex, 2 * ey
            elems.append([ids[p] for p in ((i0, j0), (i0 + 2, j0), (i0 + 2, j0 + 2),
                                           (i0, j0 + 2), (i0 + 1, j0), (i0 + 2, j0 + 1),
                                           (i0 + 1, j0 + 2), (i0, j0 + 1))])
    m = QMesh(xy, elems, label, h)
    m.grid = (nx, ny)
    return m


def geometric(n, ratio):
    """n+1 parameters in [0, 1] whose intervals grow geometrically, last /
    first = ratio."""
    if n == 1 or ratio == 1.0:
        return [k / n for k in range(n + 1)]
    q = ratio ** (1.0 / (n - 1))
    w = [q ** k for k in range(n)]
    s = [0.0]
    for v in w:
        s.append(s[-1] + v)
    return [v / s[-1] for v in s[:-1]] + [1.0]


def block_mesh(blocks, label, h):
    """CPS8 mesh from mapped blocks.  Each block is (fun, s_params,
    r_params): fun(s, r) maps the unit square onto the block; s_params and
    r_params are the mesh-line parameters (the midside nodes sit at the
    mapped parameter midpoints).  Nodes shared by blocks are merged by their
    coordinates (rounded to 1e-9); the element orientation is made
    counter-clockwise."""
    xy, lookup, elems = [], {}, []

    def node(p):
        key = (round(p[0], 9), round(p[1], 9))
        if key not in lookup:
            xy.append((p[0], p[1]))
            lookup[key] = len(xy)
        return lookup[key]

    for fun, sp, rp in blocks:
        shalf = elastic_recipe.Mesh._half(sp)
        rhalf = elastic_recipe.Mesh._half(rp)
        for a in range(len(sp) - 1):
            for b in range(len(rp) - 1):
                i0, j0 = 2 * a, 2 * b
                loc = ((i0, j0), (i0 + 2, j0), (i0 + 2, j0 + 2), (i0, j0 + 2),
                       (i0 + 1, j0), (i0 + 2, j0 + 1), (i0 + 1, j0 + 2), (i0, j0 + 1))
                pts = [fun(shalf[i], rhalf[j]) for i, j in loc]
                # orientation from the signed area of the corner polygon
                area = 0.0
                for k in range(4):
                    x1, y1 = pts[k]
                    x2, y2 = pts[(k + 1) % 4]
                    area += x1 * y2 - x2 * y1
                if area < 0:   # mirror: corners 1 4 3 2, midsides 8 7 6 5
                    pts = [pts[0], pts[3], pts[2], pts[1], pts[7], pts[6], pts[5], pts[4]]
                elems.append([node(p) for p in pts])
    m = QMesh(xy, elems, label, h)
    # no two distinct nodes may coincide (a failed merge would split the mesh)
    arr = np.round(m.xy / 1e-7).astype(np.int64)
    if len({tuple(r) for r in arr}) != m.nnodes:
        raise RuntimeError("block mesh %s has coincident nodes" % label)
    return m


# --- problem-specific meshes ------------------------------------------------
def plate_mesh(width, n, singular_x, singular_y, lg, beta, samples):
    """[0,width]x[0,1], base size 1/n, graded (the elastic recipe's grading,
    zone lg, exponent beta) towards the given x and y coordinates.  With
    `samples`, all multiples of 1/40 inside a graded zone are kept as lines,
    so that every top-edge sample point x = k/40 is a node."""
    prot_x = [k / 40.0 for k in range(int(40 * width) + 1)] if samples else []
    prot_y = [k / 40.0 for k in range(41)] if samples else []
    xl = graded_lines(width, 1.0 / n, singular_x, lg, beta, prot_x)
    yl = graded_lines(1.0, 1.0 / n, singular_y, lg, beta, prot_y)
    return tensor_mesh(xl, yl, "h0=1/%d graded" % n, 1.0 / n)


def mesh_plate_thesis(n):
    """Graded towards the clamped corners (0,0) and (1,0); nodes at x = k/40
    on the top edge."""
    return plate_mesh(1, n, [0.0, 1.0], [0.0], 0.1, 3.0, True)


def mesh_plate_limit(n):
    return plate_mesh(1, n, [0.0, 1.0], [0.0], 0.1, 3.0, False)


def mesh_plate_asym(n):
    """Graded towards the end of the clamp, (1, 0)."""
    return plate_mesh(2, n, [1.0], [0.0], 0.25, 3.0, False)


def mesh_beam(n):
    """[0,10]x[0,2], base size 1/n, graded towards the clamped edge x = 0 and
    its corners (y = 0, y = 2); graded zone 0.25 mm, exponent 3; nodes at
    the monitor points (5, 1) and (10, 2)."""
    xl = graded_lines(10.0, 1.0 / n, [0.0], 0.25, 3.0, [5.0])
    yl = graded_lines(2.0, 1.0 / n, [0.0, 2.0], 0.25, 3.0, [1.0])
    return tensor_mesh(xl, yl, "h0=1/%d graded" % n, 1.0 / n)


STRIP_A, STRIP_B, STRIP_L, STRIP_YB = 5.0, 10.0, 18.0, 10.0


def mesh_strip(n):
    """Perforated strip quarter, three mapped blocks:
    1: arc 0..45 deg -> right edge x = 10, 0 <= y <= 10,
    2: arc 45..90 deg -> line y = 10, 10 >= x >= 0,
    3: rectangle [0,10] x [10,18].
    n elements along each arc block (uniform in angle) and n radially,
    radial sizes growing geometrically by a factor 4 from the hole outwards;
    block 3 has n columns (continuing block 2) and ceil(0.8 n) rows with
    sizes growing by a factor 2 upwards from y = 10."""
    a, b, yb, length = STRIP_A, STRIP_B, STRIP_YB, STRIP_L
    rp = geometric(n, 4.0)
    sp = [k / n for k in range(n + 1)]

    def blk1(s, r):
        t = 0.25 * math.pi * s
        pin = (a * math.cos(t), a * math.sin(t))
        pout = (b, yb * s)
        return ((1 - r) * pin[0] + r * pout[0], (1 - r) * pin[1] + r * pout[1])

    def blk2(s, r):
        t = 0.25 * math.pi * (1.0 + s)
        pin = (a * math.cos(t), a * math.sin(t))
        pout = (b * (1.0 - s), yb)
        return ((1 - r) * pin[0] + r * pout[0], (1 - r) * pin[1] + r * pout[1])

    ny3 = int(math.ceil(0.8 * n))
    yp = geometric(ny3, 2.0)

    def blk3(s, r):
        # s runs from x = 10 to x = 0, exactly as block 2's outer edge
        return (b * (1.0 - s), yb + (length - yb) * r)

    m = block_mesh([(blk1, sp, rp), (blk2, sp, rp), (blk3, sp, yp)],
                   "n=%d mapped" % n, 0.25 * math.pi * a / n)
    m.grid = (n, ny3)
    return m


COOK_CORNERS = ((0.0, 0.0), (48.0, 44.0), (48.0, 60.0), (0.0, 44.0))


def mesh_cook(n):
    """Cook's membrane, the quadrilateral (0,0), (48,44), (48,60), (0,44):
    one mapped block, the bilinear map x = 48 s, y = 44 s + 44 r - 28 s r
    (s, r in [0, 1]).  Mesh lines at the parameters k/n (n even, so that the
    midpoint (24, 52) of the top edge, s = 1/2 on r = 1, is a node), graded
    with graded_lines (zone 0.1, exponent 3) towards s = 0 (the clamped edge
    x = 0) and r = 0, 1 (the bottom and top edges): the elements are
    smallest at the clamped corners (0,0) and (0,44).  All element edges are
    straight, with the midside nodes at their midpoints."""
    if n % 2:
        raise ValueError("mesh_cook: n must be even")
    (x1, y1), (x2, y2), (x3, y3), (x4, y4) = COOK_CORNERS

    def blk(s, r):
        return ((1 - s) * (1 - r) * x1 + s * (1 - r) * x2 + s * r * x3 + (1 - s) * r * x4,
                (1 - s) * (1 - r) * y1 + s * (1 - r) * y2 + s * r * y3 + (1 - s) * r * y4)

    sp = graded_lines(1.0, 1.0 / n, [0.0], 0.1, 3.0, [0.5])
    rp = graded_lines(1.0, 1.0 / n, [0.0, 1.0], 0.1, 3.0)
    m = block_mesh([(blk, sp, rp)], "n=%d graded" % n, 48.0 / n)
    m.grid = (len(sp) - 1, len(rp) - 1)
    return m


# --------------------------------------------------------------------------
# problem definitions
# --------------------------------------------------------------------------
def _on(v, w):
    return abs(v - w) < 1e-9


COOK_FORCE = 3000.0    # N per unit thickness: the end shear of cook_membrane_force


def edge_force_loads(mesh, pred, total, thickness):
    """{node id: force} of a uniform traction whose resultant over the edges selected by pred is
    `total` per unit thickness: each quadratic edge's share (its length over the whole) goes
    1/6, 1/6, 2/3 to its corners and midside, the consistent loads of a uniform traction on a
    straight 3-node edge [Zienkiewicz, Taylor & Zhu 2013]; times the slab thickness."""
    edges = []
    for e, fnum in mesh.faces_where(pred):
        conn = mesh.elems[e - 1]
        a, b, m = conn[fnum - 1], conn[fnum % 4], conn[4 + fnum - 1]
        edges.append((a, b, m, float(np.hypot(*(mesh.xy[a - 1] - mesh.xy[b - 1])))))
    length = sum(e[3] for e in edges)
    loads = {}
    for a, b, m, le in edges:
        share = total * thickness * le / length
        for nid, part in ((a, 1 / 6), (b, 1 / 6), (m, 2 / 3)):
            loads[nid] = loads.get(nid, 0.0) + share * part
    return loads


PROBLEMS = [
    dict(name="plate_plastic_thesis", units="N, mm, MPa", E=200000.0, nu=0.1, sig_y=310.0,
         hardening=("perfect",), min_dim=1.0, mesh=mesh_plate_thesis, levels=[20, 40, 80],
         fixed=[("CLAMP", lambda x, y: _on(y, 0.0), (1, 2))],
         load=dict(kind="traction", faces=lambda x, y: _on(y, 1.0),
                   steps=[(308.0, 4), (308.25, 1)]),
         force=("force_clamp", "CLAMP"), load_col="q",
         monitors=[("ux_0_1", (0.0, 1.0), 0), ("uy_0_1", (0.0, 1.0), 1),
                   ("ux_05_1", (0.5, 1.0), 0), ("uy_05_1", (0.5, 1.0), 1),
                   ("ux_1_1", (1.0, 1.0), 0), ("uy_1_1", (1.0, 1.0), 1)],
         zero_by_symmetry={"ux_05_1": "ux_0_1"}, line_top=True),
    dict(name="plate_plastic_limit", units="N, mm, MPa", E=200000.0, nu=0.1, sig_y=310.0,
         hardening=("perfect",), min_dim=1.0, mesh=mesh_plate_limit, levels=[10, 20, 40],
         fixed=[("CLAMP", lambda x, y: _on(y, 0.0), (1, 2))],
         load=dict(kind="displacement", nodes=lambda x, y: _on(y, 1.0), dof=2, sign=1.0,
                   steps=[(0.01, 40)]),
         force=("force_top", "DRIVE"), load_col="v",
         monitors=[("ux_1_1", (1.0, 1.0), 0)]),
    dict(name="plate_asymmetric_plastic", units="N, mm, MPa", E=200000.0, nu=0.1, sig_y=310.0,
         hardening=("perfect",), min_dim=1.0, mesh=mesh_plate_asym, levels=[6, 12, 24],
         fixed=[("CLAMP", lambda x, y: _on(y, 0.0) and x <= 1.0 + 1e-12, (1, 2))],
         load=dict(kind="displacement", nodes=lambda x, y: _on(y, 1.0), dof=2, sign=1.0,
                   steps=[(0.02, 40)]),
         force=("force_top", "DRIVE"), load_col="v",
         monitors=[("ux_0_1", (0.0, 1.0), 0), ("ux_2_1", (2.0, 1.0), 0),
                   ("uy_2_0", (2.0, 0.0), 1)]),
    dict(name="perforated_strip", units="kgf, mm, kgf/mm^2", E=7000.0, nu=0.2, sig_y=24.3,
         hardening=("linear", 224.0), min_dim=5.0, mesh=mesh_strip, levels=[8, 16, 32],
         fixed=[("SYMX", lambda x, y: _on(x, 0.0), (1, 1)),
                ("SYMY", lambda x, y: _on(y, 0.0), (2, 2))],
         load=dict(kind="displacement", nodes=lambda x, y: _on(y, STRIP_L), dof=2, sign=1.0,
                   steps=[(0.1, 50)]),
         force=("force_top", "DRIVE"), load_col="v",
         monitors=[("ux_10_0", (10.0, 0.0), 0), ("ux_5_0", (5.0, 0.0), 0),
                   ("uy_0_5", (0.0, 5.0), 1)]),
    dict(name="beam_voce_bending", units="N, mm, MPa", E=206900.0, nu=0.29, sig_y=450.0,
         hardening=("voce", 450.0, 715.0, 16.93, 129.24), min_dim=2.0, mesh=mesh_beam,
         levels=[2, 4, 8],
         fixed=[("CLAMP", lambda x, y: _on(x, 0.0), (1, 2))],
         load=dict(kind="displacement", nodes=lambda x, y: _on(x, 10.0), dof=2, sign=-1.0,
                   steps=[(0.5, 50)]),
         force=("force_right", "DRIVE"), load_col="v",
         monitors=[("uy_5_1", (5.0, 1.0), 1), ("ux_10_2", (10.0, 2.0), 0)]),
    dict(name="cook_membrane", units="N, mm, MPa", E=206900.0, nu=0.29, sig_y=450.0,
         hardening=("voce", 450.0, 715.0, 16.93, 129.24), alpha_max=10.0, min_dim=16.0,
         mesh=mesh_cook, levels=[6, 12, 24, 48],
         fixed=[("CLAMP", lambda x, y: _on(x, 0.0), (1, 2))],
         load=dict(kind="displacement", nodes=lambda x, y: _on(x, 48.0), dof=2, sign=1.0,
                   steps=[(2.0, 50)]),
         force=("force_right", "DRIVE"), load_col="v",
         monitors=[("ux_48_60", (48.0, 60.0), 0), ("ux_48_44", (48.0, 44.0), 0),
                   ("uy_24_52", (24.0, 52.0), 1)],
         report_yielded_area=True, ortho_check_finest=True),
    # The classic form of Cook's membrane: the free end loaded by a uniform shear traction of
    # resultant F, driven to F = 3000 N, where the tangent stiffness of the tip has fallen to a
    # tenth of its elastic value (the knee of the displacement-driven curve).
    dict(name="cook_membrane_force", units="N, mm, MPa", E=206900.0, nu=0.29, sig_y=450.0,
         hardening=("voce", 450.0, 715.0, 16.93, 129.24), alpha_max=10.0, min_dim=16.0,
         mesh=mesh_cook, levels=[6, 12, 24, 48],
         fixed=[("CLAMP", lambda x, y: _on(x, 0.0), (1, 2))],
         load=dict(kind="edge_force", faces=lambda x, y: _on(x, 48.0), dof=2,
                   steps=[(COOK_FORCE, 30)]),
         force=("force_clamp", "CLAMP"), load_col="F",
         monitors=[("uy_48_60", (48.0, 60.0), 1), ("ux_48_60", (48.0, 60.0), 0),
                   ("uy_48_44", (48.0, 44.0), 1)],
         report_yielded_area=True),
]


def hardening_table(prob):
    kind = prob["hardening"][0]
    if kind == "perfect":
        return perfect_table(prob["sig_y"])
    if kind == "linear":
        return linear_table(prob["sig_y"], prob["hardening"][1], 10.0)
    _k, s0, sinf, delta, h = prob["hardening"]
    return voce_table(s0, sinf, delta, h, prob.get("alpha_max", 2.0))


def hardening_law(prob):
    """sigma_y(alpha) of the problem, exact (for checking the table)."""
    kind = prob["hardening"][0]
    if kind == "perfect":
        return lambda a: prob["sig_y"]
    if kind == "linear":
        return lambda a: prob["sig_y"] + prob["hardening"][1] * a
    _k, s0, sinf, delta, h = prob["hardening"]
    return lambda a: voce(a, s0, sinf, delta, h)


def slab_thickness(prob):
    return SLAB_FRACTION * prob["min_dim"]


# --------------------------------------------------------------------------
# CalculiX deck
# --------------------------------------------------------------------------
fmt_coord = elastic_recipe.fmt_coord
write_list = elastic_recipe.write_list


def write_mesh_cards(f, recipe, name, mesh, element, units="N, mm, MPa"):
    """The deck's opening: who made it, *HEADING, the nodes (NSET=NALL) and the elements of type
    `element` (ELSET=EALL)."""
    f.write("** CalculiX reference deck, generated by scripts/fe_reference/%s\n" % recipe)
    f.write("** %s, mesh %s: %d %s elements, %d nodes; units %s\n"
            % (name, mesh.label, mesh.nelems, element, mesh.nnodes, units))
    f.write("*HEADING\n%s %s\n*NODE, NSET=NALL\n" % (name, mesh.label))
    for k, (x, y) in enumerate(mesh.xy):
        f.write("%d, %.15g, %.15g\n" % (k + 1, x, y))
    f.write("*ELEMENT, TYPE=%s, ELSET=EALL\n" % element)
    for k, conn in enumerate(mesh.elems):
        f.write("%d, %s\n" % (k + 1, ", ".join(str(c) for c in conn)))


def write_linear_hardening(f, e_mod, nu, sig_y, h_lin):
    """*MATERIAL STEEL: isotropic elasticity and von Mises with sigma_y + h_lin alpha (exact to
    alpha = 10, flat beyond)."""
    f.write("*MATERIAL, NAME=STEEL\n*ELASTIC\n%r, %r\n" % (e_mod, nu))
    f.write("** von Mises yield stress vs equivalent plastic strain: linear hardening\n"
            "*PLASTIC\n")
    for s, a in linear_table(sig_y, h_lin, 10.0):
        f.write("%.12g, %.12g\n" % (s, a))


def scaled_steps(prob, factor):
    """Load steps [(end value, number of increments)] with the increments
    multiplied by `factor` (1 = reference, 2 = halved increment size)."""
    return [(v, n * factor) for v, n in prob["load"]["steps"]]


def write_deck(path, prob, mesh, mode="plastic", thickness=None, inc_factor=1,
               controls=(CONTROL_RN, CONTROL_CN)):
    """mode 'plastic': the load path of the problem, recorded at equal steps
    (inc_factor = 2 halves the record spacing and the largest increment).
    mode 'elastic': linear isotropic material (no *PLASTIC), one increment
    at unit load factor (q = 1 or v = 1), stresses at the integration points.
    mode 'ortho': as 'elastic' but with the plane-stress stiffness written
    as an orthotropic law (the elastic recipe's treatment), for the
    thin-slab cross-check.  `controls`: the Newton tolerances of a plastic
    run's *CONTROLS (R_N, C_N); the reference's own by default."""
    t = slab_thickness(prob) if thickness is None else thickness
    load = prob["load"]
    E, nu = prob["E"], prob["nu"]
    with open(path, "w") as f:
        f.write("** CalculiX reference deck, generated by "
                "scripts/fe_reference/make_calculix_plastic_reference.py\n")
        f.write("** problem %s, mesh %s: %d CPS8 elements, %d nodes; units %s\n"
                % (prob["name"], mesh.label, mesh.nelems, mesh.nnodes, prob["units"]))
        f.write("** plane stress as a thin slab: section thickness %g (forces per unit "
                "thickness = reaction forces / %g)\n" % (t, t))
        f.write("*HEADING\n%s %s %s\n" % (prob["name"], mesh.label, mode))
        f.write("*NODE, NSET=NALL\n")
        for k, (x, y) in enumerate(mesh.xy):
            f.write("%d, %s, %s\n" % (k + 1, fmt_coord(x), fmt_coord(y)))
        f.write("*ELEMENT, TYPE=CPS8, ELSET=EALL\n")
        for k, conn in enumerate(mesh.elems):
            f.write("%d, %s\n" % (k + 1, ", ".join(str(c) for c in conn)))
        for name, pred, _dofs in prob["fixed"]:
            f.write("*NSET, NSET=%s\n" % name)
            write_list(f, mesh.nodes_where(pred))
        mon = sorted({mesh.find(*p) for _c, p, _k in prob["monitors"]})
        f.write("*NSET, NSET=MON\n")
        write_list(f, mon)
        if prob.get("line_top"):
            f.write("*NSET, NSET=LINETOP\n")
            write_list(f, [mesh.find(k / 40.0, 1.0) for k in range(41)])
        if load["kind"] == "displacement":
            f.write("*NSET, NSET=DRIVE\n")
            write_list(f, mesh.nodes_where(load["nodes"]))
        elif load["kind"] == "traction":
            faces = mesh.faces_where(load["faces"])
            for fnum in sorted({fc for _e, fc in faces}):
                f.write("*ELSET, ELSET=LOADF%d\n" % fnum)
                write_list(f, [e for e, fc in faces if fc == fnum])
        f.write("*MATERIAL, NAME=MAT1\n")
        if mode == "ortho":
            a = E / (1.0 - nu * nu)
            g = E / (2.0 * (1.0 + nu))
            f.write("** plane-stress stiffness written as an orthotropic law without coupling\n"
                    "** to the thickness direction (make_calculix_reference.py)\n")
            f.write("*ELASTIC, TYPE=ORTHO\n%.17g, %.17g, %.17g, 0., 0., %.17g, %.17g, %.17g\n"
                    "%.17g, 0.\n" % (a, nu * a, a, E, g, g, g))
        else:
            f.write("*ELASTIC\n%r, %r\n" % (E, nu))
        if mode == "plastic":
            f.write("** von Mises yield stress vs equivalent plastic strain (isotropic "
                    "hardening); CalculiX continues the table flat beyond its last point\n")
            f.write("*PLASTIC\n")
            for s, a in hardening_table(prob):
                f.write("%.12g, %.12g\n" % (s, a))
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=MAT1\n%r\n" % float(t))
        f.write("*BOUNDARY\n")
        for name, _pred, (d1, d2) in prob["fixed"]:
            f.write("%s, %d, %d\n" % (name, d1, d2))
        steps = scaled_steps(prob, inc_factor) if mode == "plastic" else [(1.0, 1)]
        if mode == "plastic":
            # automatic incrementation, largest increment = the record spacing;
            # the time points (step time) force an increment end at every record
            for snum, (_value, ninc) in enumerate(steps):
                f.write("*TIME POINTS, NAME=TP%d\n" % (snum + 1))
                f.write("".join("%.12g\n" % (k / ninc) for k in range(1, ninc + 1)))
        for snum, (value, ninc) in enumerate(steps):
            dt = 1.0 / ninc
            f.write("*STEP, INC=100000\n")
            if mode == "plastic":
                f.write("*STATIC\n%.12g, 1.0, %.12g, %.12g\n" % (dt, dt * MIN_INC, dt))
                f.write("*CONTROLS, PARAMETERS=FIELD\n%g, %g\n" % controls)
            else:
                f.write("*STATIC\n")
            if load["kind"] == "displacement":
                f.write("*BOUNDARY\nDRIVE, %d, %d, %r\n"
                        % (load["dof"], load["dof"], load["sign"] * value))
            elif load["kind"] == "edge_force":
                f.write("** uniform shear traction of resultant %r per unit thickness, as "
                        "consistent nodal forces on the slab\n*CLOAD\n" % value)
                for nid, fn in sorted(edge_force_loads(mesh, load["faces"], value, t).items()):
                    f.write("%d, %d, %.12e\n" % (nid, load["dof"], fn))   # ccx reads 20 characters
            else:
                f.write("** uniform traction %r in the outward normal direction = "
                        "negative pressure\n*DLOAD\n" % value)
                for fnum in sorted({fc for _e, fc in mesh.faces_where(load["faces"])}):
                    f.write("LOADF%d, P%d, %r\n" % (fnum, fnum, -value))
            tp = ", TIME POINTS=TP%d" % (snum + 1) if mode == "plastic" else ""
            f.write("*NODE PRINT, NSET=MON%s\nU\n" % tp)
            if prob.get("line_top"):
                f.write("*NODE PRINT, NSET=LINETOP%s\nU\n" % tp)
            f.write("*NODE PRINT, NSET=%s, TOTALS=ONLY%s\nRF\n" % (prob["force"][1], tp))
            if mode != "plastic":
                f.write("*EL PRINT, ELSET=EALL\nS\n")
            else:
                # equivalent plastic strain (the largest value at the end shows
                # that the hardening table reaches far enough)
                f.write("*EL FILE%s\nPEEQ\n" % tp)
            f.write("*END STEP\n")


# --------------------------------------------------------------------------
# running ccx, parsing
# --------------------------------------------------------------------------
HDR = re.compile(r"^\s*(displacements|forces|total force|stresses)\s*\(.*?\)\s*"
                 r"for set\s+(\S+)\s+and time\s+(\S+)", re.IGNORECASE)


def parse_dat(path):
    """{(kind, SET): [ {id: values} per increment ]}; stresses are keyed by
    (element, integration point) and total forces by 0."""
    out = {}
    cur = None
    with open(path) as f:
        for line in f:
            m = HDR.match(line)
            if m:
                cur = (m.group(1).lower(), m.group(2).upper())
                out.setdefault(cur, []).append({})
                continue
            if cur is None:
                continue
            s = line.split()
            if not s:
                continue
            blk = out[cur][-1]
            if cur[0] == "total force" and len(s) == 3:
                blk[0] = tuple(float(v) for v in s)
            elif cur[0] == "stresses" and len(s) == 8:
                blk[(int(s[0]), int(s[1]))] = tuple(float(v) for v in s[2:])
            elif cur[0] in ("displacements", "forces") and len(s) == 4:
                blk[int(s[0])] = tuple(float(v) for v in s[1:])
    return out


def parse_frd_peeq(path):
    """Largest nodal equivalent plastic strain in the last PE block of the
    .frd file (extrapolated to the nodes by CalculiX), or None."""
    if not os.path.exists(path):
        return None
    best, inblock = None, False
    with open(path) as f:
        for line in f:
            if line.startswith(" -4"):
                inblock = line.split()[1] == "PE"
                if inblock:
                    best = 0.0
            elif inblock and line.startswith(" -1"):
                best = max(best, float(line[13:25]))
            elif line.startswith(" -3"):
                inblock = False
    return best


def parse_frd_peeq_nodes(path):
    """Nodal equivalent plastic strain {node id: value} of the last PE block
    of the .frd file (the last recorded increment)."""
    vals, inblock = {}, False
    with open(path) as f:
        for line in f:
            if line.startswith(" -4"):
                inblock = line.split()[1] == "PE"
                if inblock:
                    vals = {}
            elif inblock and line.startswith(" -1"):
                vals[int(line[3:13])] = float(line[13:25])
            elif line.startswith(" -3"):
                inblock = False
    return vals


def yielded_fraction(mesh, peeq):
    """Fraction of the body's area where the equivalent plastic strain is
    positive at the last record: the nodal values (CalculiX's extrapolation
    into the .frd) are interpolated with the Q8 shape functions to the 3 x 3
    Gauss points of every element, and the Gauss weights x det J of the
    points with a positive value are summed."""
    pe = np.array([peeq.get(k + 1, 0.0) for k in range(mesh.nnodes)])
    xe = mesh.xy[mesh.elems - 1]
    pee = pe[mesh.elems - 1]
    total = plastic = 0.0
    for (xi, wx) in zip(GP, (5 / 9, 8 / 9, 5 / 9)):
        for (eta, wy) in zip(GP, (5 / 9, 8 / 9, 5 / 9)):
            dn = q8_dshape(xi, eta)
            jac = np.einsum("eak,al->ekl", xe, dn)
            w = (jac[:, 0, 0] * jac[:, 1, 1] - jac[:, 0, 1] * jac[:, 1, 0]) * wx * wy
            total += w.sum()
            plastic += w[pee @ q8_shape(xi, eta) > 0.0].sum()
    return plastic / total


def newton_stats(path):
    """(converged increments, failed attempts (cut back), total Newton
    iterations) from the .sta file."""
    n, cut, tot = 0, 0, 0
    with open(path) as f:
        for line in f:
            s = line.split()
            if len(s) == 7 and s[0].isdigit():
                tot += int(s[3])
                if s[2].endswith("U"):
                    cut += 1
                else:
                    n += 1
    return n, cut, tot


def solve(prob, mesh, workdir, tag, mode="plastic", thickness=None, inc_factor=1,
          controls=(CONTROL_RN, CONTROL_CN)):
    """Write the deck, run ccx, return the recorded values:
    curve [(load, force per unit thickness, monitors...)] for every increment
    (mode plastic), or the unit-load state (elastic / ortho) with the
    integration-point stresses."""
    job = "%s_%s" % (prob["name"], tag)
    deck = os.path.join(workdir, job + ".inp")
    t = slab_thickness(prob) if thickness is None else thickness
    t0 = time.time()
    write_deck(deck, prob, mesh, mode, t, inc_factor, controls)
    elastic_recipe.run_ccx(workdir, job)
    wall = time.time() - t0
    dat = parse_dat(os.path.join(workdir, job + ".dat"))
    steps = scaled_steps(prob, inc_factor) if mode == "plastic" else [(1.0, 1)]
    loads = []
    start = 0.0
    for value, ninc in steps:
        loads += [start + (value - start) * k / ninc for k in range(1, ninc + 1)]
        start = value
    mon_ids = [mesh.find(*p) for _c, p, _k in prob["monitors"]]
    disp = dat[("displacements", "MON")]
    tot = dat[("total force", prob["force"][1])]
    if len(disp) != len(loads) or len(tot) != len(loads):
        raise RuntimeError("%s: %d increments expected, %d / %d found in the .dat file"
                           % (job, len(loads), len(disp), len(tot)))
    # forces per unit thickness in the ortho mode: thickness is then 1 (real)
    rows = [[0.0] * (2 + len(mon_ids))]
    for k, lam in enumerate(loads):
        row = [lam, tot[k][0][1] / t]
        row += [disp[k][nid][comp] for nid, (_c, _p, comp) in zip(mon_ids, prob["monitors"])]
        rows.append(row)
    res = dict(mesh=mesh, deck=deck, deck_bytes=os.path.getsize(deck), wall=wall,
               curve=np.array(rows), thickness=t)
    if mode == "plastic":
        res["newton"] = newton_stats(os.path.join(workdir, job + ".sta"))
        res["peeq_max"] = parse_frd_peeq(os.path.join(workdir, job + ".frd"))
        if prob.get("report_yielded_area"):
            res["yielded"] = yielded_fraction(
                mesh, parse_frd_peeq_nodes(os.path.join(workdir, job + ".frd")))
    if prob.get("line_top"):
        lt = dat[("displacements", "LINETOP")]
        ids = [mesh.find(k / 40.0, 1.0) for k in range(41)]
        res["line_top"] = [[(k / 40.0, 1.0, blk[nid][0], blk[nid][1])
                            for k, nid in enumerate(ids)] for blk in lt]
    if mode != "plastic":
        res["stress"] = dat[("stresses", "EALL")][0]
    return res


# --------------------------------------------------------------------------
# elastic limit: von Mises stress at the integration points and the nodes
# --------------------------------------------------------------------------
def von_mises(s):
    """s[..., 6] = sxx, syy, szz, sxy, sxz, syz."""
    sxx, syy, szz, sxy, sxz, syz = (s[..., k] for k in range(6))
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2)
                   + 3.0 * (sxy ** 2 + sxz ** 2 + syz ** 2))


GP = (-GAUSS, 0.0, GAUSS)
NODE_XI = ((-1, -1), (1, -1), (1, 1), (-1, 1), (0, -1), (1, 0), (0, 1), (-1, 0))


def lagrange3(x):
    """Quadratic Lagrange basis through the Gauss points -g, 0, g."""
    g = GAUSS
    return np.array([x * (x - g) / (2 * g * g), (g * g - x * x) / (g * g),
                     x * (x + g) / (2 * g * g)])


def elastic_limit(res):
    """Largest von Mises stress of a unit-load elastic run (a) over the
    integration points, (b) over the nodes, with locations.

    CalculiX prints the 27 points of the expanded C3D20 element, xi fastest,
    then eta, then zeta (the thin-slab layers zeta = -g, 0, g carry the same
    in-plane state).  Nodal values: the components are averaged over the
    three layers, extrapolated from the 3 x 3 points to the 8 nodes of every
    element with the biquadratic Lagrange polynomial through them (exact for
    a field that is quadratic in xi and eta), averaged over the elements
    sharing a node, and then turned into the von Mises stress."""
    mesh = res["mesh"]
    ne = mesh.nelems
    st = np.zeros((ne, 27, 6))
    for (e, ip), v in res["stress"].items():
        st[e - 1, ip - 1] = v
    vm = von_mises(st)                                        # (ne, 27)
    e, ip = np.unravel_index(np.argmax(vm), vm.shape)
    i_xi, i_eta = ip % 3, (ip // 3) % 3
    xy_ip = q8_shape(GP[i_xi], GP[i_eta]) @ mesh.xy[mesh.elems[e] - 1]
    layer = st.reshape(ne, 3, 9, 6).mean(axis=1)              # (ne, 9, 6), i_xi + 3 i_eta
    ex = np.array([np.outer(lagrange3(b), lagrange3(a)).ravel() for a, b in NODE_XI])
    nodal = np.einsum("ak,ekc->eac", ex, layer)               # (ne, 8, 6)
    acc = np.zeros((mesh.nnodes, 6))
    cnt = np.zeros(mesh.nnodes)
    np.add.at(acc, mesh.elems - 1, nodal)
    np.add.at(cnt, mesh.elems - 1, 1.0)
    vm_n = von_mises(acc / cnt[:, None])
    k = int(np.argmax(vm_n))
    return dict(ip=float(vm[e, ip]), xy_ip=tuple(xy_ip), node=float(vm_n[k]),
                xy_node=tuple(mesh.xy[k]))


# --------------------------------------------------------------------------
# comparisons and output
# --------------------------------------------------------------------------
def curve_columns(prob):
    return (["increment", prob["load_col"], prob["force"][0]]
            + [c for c, _p, _k in prob["monitors"]])


def rel_diff(ref, other, prob=None):
    """(force, displacement, per-column) relative differences of two curves
    recorded at the same loads: max |difference| / max |reference| per
    column; the displacement value is the largest over the monitor columns.
    A monitor that is zero by symmetry (prob["zero_by_symmetry"]: ux at
    x = 0.5 in plate_plastic_thesis) is scaled by the largest |value| of the
    monitor named there instead of its own round-off-sized values."""
    scale = np.abs(ref).max(axis=0)
    if prob is not None:
        cols = curve_columns(prob)[1:]
        for col, by in prob.get("zero_by_symmetry", {}).items():
            scale[cols.index(col)] = scale[cols.index(by)]
    scale[scale == 0] = 1.0
    d = np.abs(ref - other).max(axis=0) / scale
    return float(d[1]), float(d[2:].max()), d


def at_loads(curve, loads):
    """Rows of `curve` recorded at the given load values."""
    rows = []
    for lam in loads:
        k = int(np.argmin(np.abs(curve[:, 0] - lam)))
        if abs(curve[k, 0] - lam) > 1e-9 * max(1.0, abs(lam)):
            raise RuntimeError("load %g not recorded" % lam)
        rows.append(curve[k])
    return np.array(rows)


def write_curve(path, prob, curve):
    with open(path, "w") as f:
        f.write(",".join(curve_columns(prob)) + "\n")
        for k, row in enumerate(curve):
            f.write("%d," % k + ",".join("%.10e" % v for v in row) + "\n")


def read_curve(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(v) for v in r[1:]] for r in rows[1:]])


def write_msh(mesh, path_q8, path_q4):
    """gmsh MSH 2.2 ASCII: type 16 (8-node quadrangle, corners
    counter-clockwise then midsides 1-2, 2-3, 3-4, 4-1, as CPS8) and type 3
    (4-node quadrangle, corners only, unused nodes dropped and renumbered);
    tags: physical 1, elementary 1."""
    def write(path, xy, elems, etype):
        with open(path, "w") as f:
            f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(xy))
            for k, (x, y) in enumerate(xy):
                f.write("%d %.17g %.17g 0\n" % (k + 1, x, y))
            f.write("$EndNodes\n$Elements\n%d\n" % len(elems))
            for k, conn in enumerate(elems):
                f.write("%d %d 2 1 1 %s\n" % (k + 1, etype, " ".join(str(c) for c in conn)))
            f.write("$EndElements\n")

    write(path_q8, mesh.xy, mesh.elems, 16)
    corners = sorted(set(mesh.elems[:, :4].ravel().tolist()))
    new = {old: k + 1 for k, old in enumerate(corners)}
    write(path_q4, mesh.xy[np.array(corners) - 1],
          [[new[c] for c in conn[:4]] for conn in mesh.elems], 3)
    return len(corners)


def fmt_xy(p):
    return "(%.4g, %.4g)" % p


# --------------------------------------------------------------------------
# driver
# --------------------------------------------------------------------------
def describe_material(prob):
    table = hardening_table(prob)
    kind = prob["hardening"][0]
    if kind == "perfect":
        return "perfectly plastic, sigma_y = %g" % prob["sig_y"]
    if kind == "linear":
        return ("linear hardening sigma_y = %g + %g alpha (table of 2 points up to alpha = %g)"
                % (prob["sig_y"], prob["hardening"][1], table[-1][1]))
    spacing = [b[1] - a[1] for a, b in zip(table[:-1], table[1:])]
    err = table_interp_error(table, hardening_law(prob))
    return ("Voce + linear: %d points up to alpha = %g, spacing %.3e at alpha = 0 growing "
            "about as exp(delta alpha / 2) (%d points below alpha = 0.5); max relative "
            "interpolation error %.2e"
            % (len(table), table[-1][1], spacing[0], sum(1 for _s, a in table if a < 0.5), err))


def check_load_balance(prob, mesh, curve):
    """A force-driven problem's support reaction balances the applied resultant (the traction
    times the loaded edges' length, or the edge force) at every record to 1e-6 of it: the loads
    reach the slab as meant. Prints the largest difference; raises beyond 1e-6."""
    load = prob["load"]
    if load["kind"] == "displacement":
        return
    length = 1.0
    if load["kind"] == "traction":
        length = sum(float(np.hypot(*(mesh.xy[mesh.elems[e - 1][f - 1] - 1]
                                      - mesh.xy[mesh.elems[e - 1][f % 4] - 1])))
                     for e, f in mesh.faces_where(load["faces"]))
    applied = curve[1:, 0] * length
    err = float((np.abs(curve[1:, 1] + applied) / np.abs(applied)).max())
    print("          support reaction vs applied resultant: max relative difference %.1e" % err)
    if err > 1e-6:
        raise RuntimeError("%s, %s: the reaction misses the applied load by %.1e"
                           % (prob["name"], mesh.label, err))


def run_problem(prob, out_root, work, quick):
    """All runs of one problem; returns a summary dict."""
    name = prob["name"]
    outdir = os.path.join(out_root, name)
    os.makedirs(outdir, exist_ok=True)
    ts = slab_thickness(prob)
    print("\n=== %s (%s) ===" % (name, prob["units"]))
    print("  E = %g, nu = %g, %s" % (prob["E"], prob["nu"], describe_material(prob)))
    print("  thin slab: section thickness t_s = %g; forces = reaction / t_s" % ts)
    levels = prob["levels"][:1] if quick else prob["levels"]
    results, meshes = [], []
    for lev, n in enumerate(levels):
        mesh = prob["mesh"](n)
        detj = mesh.min_detj()
        if detj <= 0:
            raise RuntimeError("mesh %s has a non-positive Jacobian" % mesh.label)
        r = solve(prob, mesh, work, "L%d" % lev)
        inc, cut, its = r["newton"]
        print("  level %d %-16s elems=%6d nodes=%6d min edge=%.2e min detJ/(A/4)=%.3f | "
              "ccx %6.1fs, %d increments (%d cut back), %d iterations, max PEEQ %.4g"
              % (lev, mesh.label, mesh.nelems, mesh.nnodes, mesh.min_edge(), detj,
                 r["wall"], inc, cut, its, r["peeq_max"] or 0.0))
        if "yielded" in r:
            print("          yielded area at the last record (interpolated nodal PEEQ > 0 at "
                  "the Gauss points): %.1f%% of the body" % (100.0 * r["yielded"]))
        check_load_balance(prob, mesh, r["curve"])
        results.append(r)
        meshes.append(mesh)
    cols = curve_columns(prob)
    finest = results[-1]
    summary = dict(name=name, levels=[], last=finest["curve"][-1], cols=cols)
    if quick:
        return dict(name=name, curve=finest["curve"])
    write_curve(os.path.join(outdir, "curve.csv"), prob, finest["curve"])
    write_curve(os.path.join(outdir, "curve_level0.csv"), prob, results[0]["curve"])
    keep = finest
    for r in reversed(results):
        if r["deck_bytes"] <= MAX_DECK_BYTES:
            keep = r
            break
    shutil.copyfile(keep["deck"], os.path.join(outdir, name + ".inp"))
    print("  committed deck: %s (%.2f MB); finest deck %.2f MB"
          % (keep["mesh"].label, keep["deck_bytes"] / 1e6, finest["deck_bytes"] / 1e6))

    # ---- mesh convergence --------------------------------------------------
    print("  mesh convergence: level vs finest, max over all %d increments "
          "(force / max|force|, monitors / max|monitor|):" % (len(finest["curve"]) - 1))
    conv = []
    for lev in range(len(results) - 1):
        df, dd, dcol = rel_diff(finest["curve"], results[lev]["curve"], prob)
        conv.append((lev, meshes[lev].h, df, dd))
        print("    level %d (%s): force %.2e, displacements %.2e  [%s]"
              % (lev, meshes[lev].label, df, dd,
                 ", ".join("%s %.1e" % (c, v) for c, v in zip(cols[3:], dcol[2:]))))
    with open(os.path.join(outdir, "convergence.csv"), "w") as f:
        f.write("level,h,max_rel_diff_force,max_rel_diff_disp\n")
        for row in conv:
            f.write("%d,%.10e,%.4e,%.4e\n" % row)
    if len(results) >= 3:
        df, dd, _ = rel_diff(results[-2]["curve"], results[-3]["curve"], prob)
        print("    (level %d vs level %d: force %.2e, displacements %.2e)"
              % (len(results) - 2, len(results) - 3, df, dd))
    # with perfect plasticity the displacement field is not unique once the
    # limit load is reached (the plastic flow may concentrate anywhere), so
    # the records before the load plateau are also compared separately
    fabs = np.abs(finest["curve"][:, 1])
    pre = fabs < PLATEAU * fabs.max()
    if not pre.all():
        print("  same, only the %d records with |force| < %g x max |force| (before the "
              "plateau, %s <= %.4g):" % (pre.sum() - 1, PLATEAU, prob["load_col"],
                                         finest["curve"][pre, 0].max()))
        for lev in range(len(results) - 1):
            df, dd, dcol = rel_diff(finest["curve"][pre], results[lev]["curve"][pre], prob)
            print("    level %d: force %.2e, displacements %.2e  [%s]"
                  % (lev, df, dd, ", ".join("%s %.1e" % (c, v)
                                            for c, v in zip(cols[3:], dcol[2:]))))

    # ---- increment convergence (middle level, increments halved) ----------
    mid = len(results) // 2
    rh = solve(prob, meshes[mid], work, "L%d_half" % mid, inc_factor=2)
    half = at_loads(rh["curve"], results[mid]["curve"][:, 0])
    df, dd, dcol = rel_diff(half, results[mid]["curve"], prob)
    print("  increments halved on level %d (ccx %.1fs, %d increments, %d cut back): "
          "max change force %.2e, displacements %.2e  [%s]"
          % (mid, rh["wall"], rh["newton"][0], rh["newton"][1], df, dd,
             ", ".join("%s %.1e" % (c, v) for c, v in zip(cols[3:], dcol[2:]))))
    summary["halved"] = (mid, df, dd)

    # ---- slab thickness: t_s / 10 on the coarsest level --------------------
    rt = solve(prob, meshes[0], work, "L0_thin", thickness=ts / 10)
    df, dd, dcol = rel_diff(results[0]["curve"], rt["curve"], prob)
    print("  slab thickness t_s/10 = %g on level 0 (ccx %.1fs): max difference force %.2e, "
          "displacements %.2e  [%s]" % (ts / 10, rt["wall"], df, dd, ", ".join(
              "%s %.1e" % (c, v) for c, v in zip(cols[3:], dcol[2:]))))
    summary["thin"] = max(df, dd)

    # ---- elastic limit (unit load) per level -------------------------------
    print("  elastic limit (linear run at unit load factor, %s = 1):" % prob["load_col"])
    lim_rows, elastic0 = [], None
    for lev, mesh in enumerate(meshes):
        re_ = solve(prob, mesh, work, "L%d_elastic" % lev, mode="elastic")
        if lev == 0:
            elastic0 = re_
        lim = elastic_limit(re_)
        fy_ip, fy_n = prob["sig_y"] / lim["ip"], prob["sig_y"] / lim["node"]
        lim_rows.append((lev, mesh.h, lim["ip"], lim["xy_ip"][0], lim["xy_ip"][1],
                         lim["node"], lim["xy_node"][0], lim["xy_node"][1], fy_ip, fy_n))
        print("    level %d (%s): max vM at integration points %.6e at %s -> first yield "
              "%s = %.6e; at nodes %.6e at %s -> %.6e"
              % (lev, mesh.label, lim["ip"], fmt_xy(lim["xy_ip"]), prob["load_col"], fy_ip,
                 lim["node"], fmt_xy(lim["xy_node"]), fy_n))
    if prob.get("report_yielded_area"):
        # the unit-load force of the finest level scales the first-yield
        # factors to forces, for comparison with the plastic curve
        f1 = re_["curve"][1, 1]
        flast = finest["curve"][-1, 1]
        print("    finest level: force at unit load %.7g; first yield at force %.6g (IP) / "
              "%.6g (node); force at the last record %s = %g: %.7g = %.2f x / %.2f x these"
              % (f1, f1 * lim_rows[-1][8], f1 * lim_rows[-1][9], prob["load_col"],
                 finest["curve"][-1, 0], flast, flast / (f1 * lim_rows[-1][8]),
                 flast / (f1 * lim_rows[-1][9])))
        summary["unit_force"] = f1
    with open(os.path.join(outdir, "elastic_limit.csv"), "w") as f:
        f.write("level,h,max_vm_ip,x_ip,y_ip,max_vm_node,x_node,y_node,"
                "first_yield_factor_ip,first_yield_factor_node\n")
        for row in lim_rows:
            f.write("%d,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e\n" % row)
    summary["limits"] = lim_rows

    # ---- thin slab vs the orthotropic plane-stress law (elastic, level 0) --
    ro = solve(prob, meshes[0], work, "L0_ortho", mode="ortho", thickness=1.0)
    _df, _dd, d = rel_diff(ro["curve"], elastic0["curve"], prob)
    print("  cross-check, elastic unit load on level 0: thin slab (isotropic, t_s) vs "
          "orthotropic plane-stress law (t = 1): max relative difference %.2e [%s]"
          % (d[1:].max(), ", ".join("%s %.1e" % (c, v) for c, v in zip(cols[2:], d[1:]))))
    summary["ortho"] = float(d[1:].max())
    if prob.get("ortho_check_finest"):
        last = len(meshes) - 1
        ro = solve(prob, meshes[last], work, "L%d_ortho" % last, mode="ortho", thickness=1.0)
        _df, _dd, d = rel_diff(ro["curve"], re_["curve"], prob)
        print("  the same on level %d: max relative difference %.2e [%s]"
              % (last, d[1:].max(),
                 ", ".join("%s %.1e" % (c, v) for c, v in zip(cols[2:], d[1:]))))
    # the first record is elastic when it lies below first yield: it must be
    # the unit-load solution scaled
    lam1 = results[0]["curve"][1, 0]
    if lam1 < lim_rows[0][8]:
        scaled = elastic0["curve"] * lam1
        _df, _dd, d = rel_diff(scaled, results[0]["curve"][:2], prob)
        dd = d[1:]
        print("  first record %s = %g is below first yield (%.4g): plastic run vs scaled "
              "elastic run, max difference %.1e" % (prob["load_col"], lam1, lim_rows[0][8],
                                                    dd.max()))
    else:
        print("  first record %s = %g is above first yield (%.4g) on level 0"
              % (prob["load_col"], lam1, lim_rows[0][8]))

    # ---- problem-specific output -------------------------------------------
    if prob.get("line_top"):
        for k, fname in ((-2, "line_top_308.csv"), (-1, "line_top_30825.csv")):
            with open(os.path.join(outdir, fname), "w") as f:
                f.write("x,y,ux,uy\n")
                for row in finest["line_top"][k]:
                    f.write("%.10e,%.10e,%.10e,%.10e\n" % row)
    if name == "perforated_strip":
        m = meshes[-1]
        os.makedirs(MESH_DIR, exist_ok=True)
        nq4 = write_msh(m, os.path.join(MESH_DIR, "perforated_strip_q8.msh"),
                        os.path.join(MESH_DIR, "perforated_strip_q4.msh"))
        print("  wrote problems/meshes/perforated_strip_q8.msh (%s, %d elements, %d nodes) "
              "and perforated_strip_q4.msh (%d nodes)" % (m.label, m.nelems, m.nnodes, nq4))
    summary["levels"] = [(lev, meshes[lev].label, meshes[lev].nelems, meshes[lev].nnodes,
                          results[lev]["wall"]) for lev in range(len(results))]
    summary["conv"] = conv
    return summary


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true",
                    help="remake only the coarsest level and compare with the committed one")
    ap.add_argument("--out", default=None, help="output folder (default reference/"
                    "calculix_plastic, or $CALCULIX_REFERENCE_OUT)")
    ap.add_argument("--only", default=None, help="comma-separated problem names")
    args = ap.parse_args()
    out = args.out or os.environ.get("CALCULIX_REFERENCE_OUT")
    tmp_out = None
    if args.quick and not out:
        tmp_out = tempfile.mkdtemp(prefix="ccx_plastic_quick_")
        out = tmp_out
    out = out or DEFAULT_OUT
    probs = PROBLEMS
    if args.only:
        names = args.only.split(",")
        probs = [p for p in PROBLEMS if p["name"] in names]
    t_start = time.time()
    print("CalculiX version %s (%s), %d thread(s); numpy %s; output %s"
          % (elastic_recipe.ccx_version(), shutil.which("ccx"), NTHREADS, np.__version__, out))
    summaries = []
    worst, status = 0.0, 0
    for prob in probs:
        with tempfile.TemporaryDirectory(prefix="ccx_%s_" % prob["name"]) as work:
            s = run_problem(prob, out, work, args.quick)
        if args.quick:
            ref = os.path.join(DEFAULT_OUT, prob["name"], "curve_level0.csv")
            write_curve(os.path.join(out, prob["name"], "curve_level0.csv"), prob, s["curve"])
            if not os.path.exists(ref):
                print("  %s: no committed %s" % (prob["name"], os.path.relpath(ref, REPO_ROOT)))
                status = 1
                continue
            hdr, committed = read_curve(ref)
            if hdr != curve_columns(prob) or committed.shape != s["curve"].shape:
                print("  %s: committed curve_level0.csv has a different layout" % prob["name"])
                status = 1
                continue
            _df, _dd, dcol = rel_diff(committed, s["curve"], prob)
            print("  %s: max relative difference to the committed curve_level0.csv %.2e"
                  % (prob["name"], dcol.max()))
            worst = max(worst, float(dcol.max()))
        summaries.append(s)
    if args.quick:
        ok = worst <= QUICK_TOL and status == 0
        print("\nquick check: max relative difference %.2e (tolerance %.0e): %s; %.1f s"
              % (worst, QUICK_TOL, "PASSED" if ok else "FAILED", time.time() - t_start))
        if tmp_out:
            shutil.rmtree(tmp_out, ignore_errors=True)
        return 0 if ok else 1

    print("\n=== summary: finest level, last increment ===")
    for s in summaries:
        print("  %-25s %s" % (s["name"], ", ".join("%s = %.7e" % (c, v)
                                                    for c, v in zip(s["cols"][1:], s["last"]))))
    print("total run time %.1f s" % (time.time() - t_start))
    return 0


if __name__ == "__main__":
    sys.exit(main())
