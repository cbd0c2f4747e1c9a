#!/usr/bin/env python3
"""Regenerate the CalculiX finite-element reference solutions for two
linear-elastic plane-stress plates.

Run from the repository root, without arguments:

    /usr/bin/python3 scripts/fe_reference/make_calculix_reference.py

Units: N, mm, MPa.  E = 200000 MPa, nu = 0.1, plane stress, thickness 1 mm.

Problems
--------
plate_tension     [0,1] x [0,1], bottom edge y=0 clamped (ux = uy = 0),
                  uniform traction 1000 MPa in +y on the top edge y=1.
plate_asymmetric  [0,2] x [0,1], bottom edge clamped only for 0 <= x <= 1,
                  uniform traction 1000 MPa in +y on the whole top edge.

Method
------
Structured mesh of CPS8 (8-node plane-stress quadrilateral, full 3x3
integration) elements of size h = 1/n, n in {20, 40, 80[, 160]}.  Every sample
point (x = i/40 on y = 0.7 and y = 1.0) is a mesh node (corner or midside),
so the displacements are read directly from the nodal output (*NODE PRINT,
U) in the .dat file; no interpolation is involved.  The top traction is
applied as *DLOAD with a negative pressure (-1000 MPa, i.e. tension) on face 3
(the top edge, nodes 3-7-4) of the top row of elements.  The sum of the
vertical reactions of the clamped nodes (*NODE PRINT, RF) is checked against
the applied force (traction * width * thickness).

Output (reference/calculix/<problem>/)
--------------------------------------
<problem>.inp     the CalculiX input deck of the finest mesh used (or of the
                  level below if the finest deck is larger than ~2 MB)
line_y07.csv      x,y,ux,uy on y = 0.7 at x = i/40   (finest level)
line_top.csv      x,y,ux,uy on y = 1.0 at x = i/40   (finest level)
convergence.csv   level,h,line,max_rel_diff_ux,max_rel_diff_uy
                  (difference of level k to level k-1, divided by the max |u|
                  of level k on that line)

Only the Python standard library is required; if numpy is available, an
independent plane-stress CPS8 implementation in numpy is additionally solved
on the coarsest mesh and compared with CalculiX (a cross-check that the
CalculiX CPS8 expansion really yields 2-D plane-stress results).
"""

import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

E_MOD = 200000.0      # MPa
NU = 0.1
THICKNESS = 1.0       # mm
TRACTION = 1000.0     # MPa (tension, +y) on the top edge
SAMPLE_DX_DEN = 40    # sample points x = i / 40
Y_LINE = 0.7
MAX_DECK_BYTES = 2_200_000

REPO_ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
OUT_ROOT = os.path.join(REPO_ROOT, "reference", "calculix")

PROBLEMS = [
    # name, width, clamp_xmax, list of n = 1/h
    dict(name="plate_tension", width=1, clamp_xmax=1.0, levels=[20, 40, 80, 160]),
    dict(name="plate_asymmetric", width=2, clamp_xmax=1.0, levels=[20, 40, 80]),
]


# --------------------------------------------------------------------------
# mesh / deck generation
# --------------------------------------------------------------------------
class Mesh:
    """Structured CPS8 mesh on [0,W] x [0,1], element size 1/n.

    Nodes live on a half-spacing grid (i, j), x = i/(2n), y = j/(2n),
    i = 0..2*W*n, j = 0..2n, except element centres (i odd and j odd).
    Node id = j*(2*nx+1) + i + 1.
    """

    def __init__(self, width, n):
        self.width = width
        self.n = n
        self.nx = width * n
        self.ny = n
        self.ni = 2 * self.nx + 1
        self.nj = 2 * self.ny + 1

    def nid(self, i, j):
        return j * self.ni + i + 1

    def xy(self, i, j):
        return i / (2.0 * self.n), j / (2.0 * self.n)

    def nodes(self):
        for j in range(self.nj):
            for i in range(self.ni):
                if (i % 2 == 1) and (j % 2 == 1):
                    continue
                yield self.nid(i, j), i, j

    def element_nodes(self, ex, ey):
        i0, j0 = 2 * ex, 2 * ey
        ij = [(i0, j0), (i0 + 2, j0), (i0 + 2, j0 + 2), (i0, j0 + 2),
              (i0 + 1, j0), (i0 + 2, j0 + 1), (i0 + 1, j0 + 2), (i0, j0 + 1)]
        return [self.nid(i, j) for i, j in ij], ij

    def eid(self, ex, ey):
        return ey * self.nx + ex + 1

    def elements(self):
        for ey in range(self.ny):
            for ex in range(self.nx):
                yield self.eid(ex, ey), self.element_nodes(ex, ey)[0]

    # -- sets ------------------------------------------------------------
    def clamp_nodes(self, clamp_xmax):
        # y = 0 and x <= clamp_xmax (exact integer test on the grid index)
        imax = int(round(clamp_xmax * 2 * self.n))
        return [self.nid(i, 0) for i in range(0, imax + 1)]

    def sample_indices(self, y):
        """grid indices (i, j) of the sample points x = k/40 on line y."""
        j = int(round(y * 2 * self.n))
        assert abs(j / (2.0 * self.n) - y) < 1e-12, "sample line is not a node row"
        assert (2 * self.n) % SAMPLE_DX_DEN == 0, "x = k/40 are not nodes"
        step = (2 * self.n) // SAMPLE_DX_DEN
        nk = self.width * SAMPLE_DX_DEN
        return [(k * step, j) for k in range(nk + 1)]

    def top_elements(self):
        return [self.eid(ex, self.ny - 1) for ex in range(self.nx)]


def write_list(f, ids, per_line=16):
    for k in range(0, len(ids), per_line):
        f.write(", ".join(str(v) for v in ids[k:k + per_line]) + ",\n")


def write_deck(path, prob, mesh):
    lines_sets = {
        "LINE_Y07": [mesh.nid(i, j) for i, j in mesh.sample_indices(Y_LINE)],
        "LINE_TOP": [mesh.nid(i, j) for i, j in mesh.sample_indices(1.0)],
    }
    clamp = mesh.clamp_nodes(prob["clamp_xmax"])
    with open(path, "w") as f:
        f.write("** CalculiX reference deck generated by "
                "scripts/fe_reference/make_calculix_reference.py\n")
        f.write("** problem %s: domain [0,%d] x [0,1] mm, CPS8, h = 1/%d\n"
                % (prob["name"], prob["width"], mesh.n))
        f.write("** bottom y=0 clamped for 0 <= x <= %g; top y=1 traction %g MPa (+y)\n"
                % (prob["clamp_xmax"], TRACTION))
        f.write("** E = %g MPa, nu = %g, plane stress, thickness %g mm; units N, mm, MPa\n"
                % (E_MOD, NU, THICKNESS))
        f.write("*HEADING\n%s h=1/%d\n" % (prob["name"], mesh.n))
        f.write("*NODE, NSET=NALL\n")
        for nid, i, j in mesh.nodes():
            x, y = mesh.xy(i, j)
            f.write("%d, %.17g, %.17g\n" % (nid, x, y))
        f.write("*ELEMENT, TYPE=CPS8, ELSET=EALL\n")
        for eid, conn in mesh.elements():
            f.write("%d, %s\n" % (eid, ", ".join(str(c) for c in conn)))
        f.write("*NSET, NSET=CLAMP\n")
        write_list(f, clamp)
        for name, ids in lines_sets.items():
            f.write("*NSET, NSET=%s\n" % name)
            write_list(f, ids)
        f.write("*ELSET, ELSET=TOPEL\n")
        write_list(f, mesh.top_elements())
        f.write("*MATERIAL, NAME=ELASTIC1\n*ELASTIC\n%.1f, %g\n" % (E_MOD, NU))
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=ELASTIC1\n%r\n" % float(THICKNESS))
        f.write("*BOUNDARY\nCLAMP, 1, 2\n")
        f.write("*STEP\n*STATIC\n")
        f.write("** uniform traction on the top edge: negative pressure on face 3 "
                "(nodes 3-7-4)\n")
        f.write("*DLOAD\nTOPEL, P3, %.1f\n" % (-TRACTION))
        f.write("*NODE PRINT, NSET=LINE_Y07\nU\n")
        f.write("*NODE PRINT, NSET=LINE_TOP\nU\n")
        f.write("*NODE PRINT, NSET=CLAMP, TOTALS=YES\nRF\n")
        f.write("*END STEP\n")
    return lines_sets, clamp


# --------------------------------------------------------------------------
# running ccx and parsing the .dat file
# --------------------------------------------------------------------------
FLOAT = r"[-+]?\d*\.?\d+(?:[EeDd][-+]?\d+)?"


def parse_dat(path):
    """Return {(kind, setname): {node: (v1, v2, v3)}} and {setname: totals}."""
    blocks, totals = {}, {}
    hdr = re.compile(r"^\s*(displacements|forces|total force)\s*\(.*?\)\s*for set\s+(\S+)",
                     re.IGNORECASE)
    cur = None
    with open(path) as f:
        for line in f:
            m = hdr.match(line)
            if m:
                kind, name = m.group(1).lower(), m.group(2).upper()
                cur = (kind, name)
                if kind != "total force":
                    blocks[cur] = {}
                continue
            s = line.split()
            if not s or cur is None:
                continue
            if cur[0] == "total force" and len(s) == 3:
                totals[cur[1]] = tuple(float(v) for v in s)
                cur = None
            elif len(s) == 4 and re.fullmatch(r"\d+", s[0]):
                blocks[cur][int(s[0])] = tuple(float(v) for v in s[1:])
    return blocks, totals


def ccx_version():
    try:
        p = subprocess.run(["ccx", "-v"], capture_output=True, text=True, timeout=60)
        txt = (p.stdout + p.stderr).strip()
        m = re.search(r"Version\s+([\d.]+)", txt)
        return m.group(1) if m else txt
    except Exception as exc:  # pragma: no cover
        return "unknown (%s)" % exc


def run_ccx(workdir, jobname, nthreads):
    env = dict(os.environ)
    env["OMP_NUM_THREADS"] = str(nthreads)
    env["CCX_NPROC_EQUATION_SOLVER"] = str(nthreads)
    with open(os.path.join(workdir, jobname + ".log"), "w") as log:
        p = subprocess.run(["ccx", "-i", jobname], cwd=workdir, env=env,
                           stdout=log, stderr=subprocess.STDOUT)
    logtxt = open(os.path.join(workdir, jobname + ".log")).read()
    if p.returncode != 0 or "*ERROR" in logtxt:
        sys.stderr.write(logtxt[-4000:])
        raise RuntimeError("ccx failed for %s (rc=%d)" % (jobname, p.returncode))
    return logtxt


def solve_level(prob, n, workdir, nthreads):
    mesh = Mesh(prob["width"], n)
    job = "%s_n%d" % (prob["name"], n)
    deck = os.path.join(workdir, job + ".inp")
    t0 = time.time()
    line_sets, clamp = write_deck(deck, prob, mesh)
    run_ccx(workdir, job, nthreads)
    wall = time.time() - t0
    blocks, totals = parse_dat(os.path.join(workdir, job + ".dat"))
    res = {"n": n, "h": 1.0 / n, "deck": deck, "wall": wall, "lines": {},
           "nnodes": sum(1 for _ in mesh.nodes()), "nelem": mesh.nx * mesh.ny}
    for key, setname, y in (("y07", "LINE_Y07", Y_LINE), ("top", "LINE_TOP", 1.0)):
        disp = blocks[("displacements", setname)]
        rows = []
        for (i, j) in mesh.sample_indices(y):
            x, yy = mesh.xy(i, j)
            ux, uy, _uz = disp[mesh.nid(i, j)]
            rows.append((x, yy, ux, uy))
        res["lines"][key] = rows
    rf = blocks[("forces", "CLAMP")]
    assert len(rf) == len(clamp)
    res["rf_sum"] = (sum(v[0] for v in rf.values()), sum(v[1] for v in rf.values()))
    res["rf_total_ccx"] = totals.get("CLAMP")
    res["applied"] = TRACTION * prob["width"] * THICKNESS
    return res


# --------------------------------------------------------------------------
# optional independent cross-check (numpy): 2-D plane-stress CPS8, 3x3 Gauss
# --------------------------------------------------------------------------
def numpy_crosscheck(prob, n):
    try:
        import numpy as np
    except ImportError:
        return None
    mesh = Mesh(prob["width"], n)
    ids = {}
    for nid, i, j in mesh.nodes():
        ids[nid] = len(ids)
    ndof = 2 * len(ids)
    D = E_MOD / (1 - NU ** 2) * np.array([[1, NU, 0], [NU, 1, 0], [0, 0, (1 - NU) / 2]])
    xi_n = np.array([-1, 1, 1, -1, 0, 1, 0, -1.0])
    eta_n = np.array([-1, -1, 1, 1, -1, 0, 1, 0.0])
    g = math.sqrt(0.6)
    gp = [(-g, 5 / 9), (0.0, 8 / 9), (g, 5 / 9)]

    def dshape(xi, eta):
        dN = np.zeros((8, 2))
        for a in range(8):
            xa, ea = xi_n[a], eta_n[a]
            if a < 4:
                dN[a, 0] = 0.25 * xa * (1 + eta * ea) * (2 * xi * xa + eta * ea)
                dN[a, 1] = 0.25 * ea * (1 + xi * xa) * (xi * xa + 2 * eta * ea)
            elif xa == 0:
                dN[a, 0] = -xi * (1 + eta * ea)
                dN[a, 1] = 0.5 * ea * (1 - xi * xi)
            else:
                dN[a, 0] = 0.5 * xa * (1 - eta * eta)
                dN[a, 1] = -eta * (1 + xi * xa)
        return dN

    h = 1.0 / n
    # all elements are identical squares -> one element stiffness
    J = np.diag([h / 2, h / 2])
    Jinv = np.linalg.inv(J)
    Ke = np.zeros((16, 16))
    for xi, wx in gp:
        for eta, wy in gp:
            dN = dshape(xi, eta) @ Jinv
            B = np.zeros((3, 16))
            B[0, 0::2] = dN[:, 0]
            B[1, 1::2] = dN[:, 1]
            B[2, 0::2] = dN[:, 1]
            B[2, 1::2] = dN[:, 0]
            Ke += B.T @ D @ B * np.linalg.det(J) * wx * wy * THICKNESS
    K = np.zeros((ndof, ndof))
    for _eid, conn in mesh.elements():
        dofs = np.array([[2 * ids[c], 2 * ids[c] + 1] for c in conn]).ravel()
        K[np.ix_(dofs, dofs)] += Ke
    F = np.zeros(ndof)
    q = TRACTION * THICKNESS * h
    for ex in range(mesh.nx):
        i0, j = 2 * ex, 2 * mesh.ny
        for i, w in ((i0, 1 / 6), (i0 + 1, 4 / 6), (i0 + 2, 1 / 6)):
            F[2 * ids[mesh.nid(i, j)] + 1] += w * q
    fixed = set()
    for c in mesh.clamp_nodes(prob["clamp_xmax"]):
        fixed.update((2 * ids[c], 2 * ids[c] + 1))
    free = np.array([d for d in range(ndof) if d not in fixed])
    u = np.zeros(ndof)
    u[free] = np.linalg.solve(K[np.ix_(free, free)], F[free])
    out = {}
    for key, y in (("y07", Y_LINE), ("top", 1.0)):
        out[key] = [(u[2 * ids[mesh.nid(i, j)]], u[2 * ids[mesh.nid(i, j)] + 1])
                    for i, j in mesh.sample_indices(y)]
    return out


# --------------------------------------------------------------------------
def write_line_csv(path, rows):
    with open(path, "w") as f:
        f.write("x,y,ux,uy\n")
        for x, y, ux, uy in rows:
            f.write("%.10e,%.10e,%.10e,%.10e\n" % (x, y, ux, uy))


def main():
    t_start = time.time()
    nthreads = min(2, os.cpu_count() or 1)
    version = ccx_version()
    print("CalculiX version: %s  (ccx = %s)" % (version, shutil.which("ccx")))
    summary = []
    ok = True
    for prob in PROBLEMS:
        name = prob["name"]
        outdir = os.path.join(OUT_ROOT, name)
        os.makedirs(outdir, exist_ok=True)
        print("\n=== %s ===" % name)
        with tempfile.TemporaryDirectory(prefix="ccx_%s_" % name) as work:
            results = []
            for n in prob["levels"]:
                r = solve_level(prob, n, work, nthreads)
                fy = r["rf_sum"][1]
                rel = abs(-fy - r["applied"]) / r["applied"]
                r["rf_rel_err"] = rel
                ok &= rel < 1e-6
                print("  h=1/%-4d nodes=%7d elems=%6d  ccx %.1fs  sum RF_y=%.7e "
                      "(applied %.1f N, rel.err %.2e) sum RF_x=%.3e"
                      % (n, r["nnodes"], r["nelem"], r["wall"], fy, r["applied"],
                         rel, r["rf_sum"][0]))
                r["deck_bytes"] = os.path.getsize(r["deck"])
                results.append(r)
            # deck to keep: finest whose size is acceptable
            keep = results[-1]
            for r in reversed(results):
                if r["deck_bytes"] <= MAX_DECK_BYTES:
                    keep = r
                    break
            shutil.copyfile(keep["deck"], os.path.join(outdir, name + ".inp"))
            print("  kept deck: h=1/%d (%.2f MB); finest deck h=1/%d is %.2f MB"
                  % (keep["n"], keep["deck_bytes"] / 1e6, results[-1]["n"],
                     results[-1]["deck_bytes"] / 1e6))
        finest = results[-1]
        for key in ("y07", "top"):
            write_line_csv(os.path.join(outdir, "line_%s.csv" % key), finest["lines"][key])
        # convergence table
        conv_rows = []
        for k in range(1, len(results)):
            fine, coarse = results[k], results[k - 1]
            for key in ("y07", "top"):
                a, b = fine["lines"][key], coarse["lines"][key]
                assert all(abs(p[0] - q[0]) < 1e-12 for p, q in zip(a, b))
                mux = max(abs(p[2]) for p in a)
                muy = max(abs(p[3]) for p in a)
                dux = max(abs(p[2] - q[2]) for p, q in zip(a, b))
                duy = max(abs(p[3] - q[3]) for p, q in zip(a, b))
                conv_rows.append((k, fine["h"], key, dux / mux, duy / muy))
        with open(os.path.join(outdir, "convergence.csv"), "w") as f:
            f.write("level,h,line,max_rel_diff_ux,max_rel_diff_uy\n")
            for k, h, key, rx, ry in conv_rows:
                f.write("%d,%.10e,%s,%.4e,%.4e\n" % (k, h, key, rx, ry))
        print("  convergence (level k vs k-1, relative to max|u| on the line):")
        for k, h, key, rx, ry in conv_rows:
            print("    level %d  h=1/%-4d %-4s  ux %.3e  uy %.3e"
                  % (k, round(1 / h), key, rx, ry))
        # independent numpy cross-check on the coarsest mesh
        xc = numpy_crosscheck(prob, results[0]["n"])
        if xc is None:
            print("  numpy not available: independent cross-check skipped")
        else:
            for key in ("y07", "top"):
                a = results[0]["lines"][key]
                mux = max(abs(p[2]) for p in a)
                muy = max(abs(p[3]) for p in a)
                dx = max(abs(p[2] - q[0]) for p, q in zip(a, xc[key])) / mux
                dy = max(abs(p[3] - q[1]) for p, q in zip(a, xc[key])) / muy
                print("  numpy CPS8 plane-stress cross-check h=1/%d line %s: "
                      "max rel diff ux %.2e uy %.2e" % (results[0]["n"], key, dx, dy))
                ok &= dx < 1e-5 and dy < 1e-5
        for key in ("y07", "top"):
            rows = finest["lines"][key]
            summary.append((name, key, len(rows),
                            min(p[2] for p in rows), max(p[2] for p in rows),
                            min(p[3] for p in rows), max(p[3] for p in rows)))
    print("\n=== summary (finest level) ===")
    print("%-17s %-4s %4s %14s %14s %14s %14s"
          % ("problem", "line", "npts", "min ux", "max ux", "min uy", "max uy"))
    for s in summary:
        print("%-17s %-4s %4d %14.7e %14.7e %14.7e %14.7e" % s)
    print("total run time %.1f s; checks %s" % (time.time() - t_start,
                                                "PASSED" if ok else "FAILED"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
