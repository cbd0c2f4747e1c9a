#!/usr/bin/env python3
"""A meshfree run of the staged_strip preload against this CalculiX reference.

    /usr/bin/python3 compare_meshfree.py MF_OUT [CCX_JOB]

MF_OUT: the output folder of an elastoplastic_static run with the reference's
boundary conditions, condition `pull` on the top edge and the four gauges of
extract.MONITORS (history.csv, fields.h5, gauss_points.h5).  Prints the
reaction curve and monitor differences (against reaction_curve.csv), the
nodal stresses and equivalent plastic strain at the four points (against
points.csv; CalculiX: extrapolated and averaged nodal values, meshfree: its
phi^2 w weighted nodal average, so that these differ also where the two
solutions agree), the peak plastic strain and the plastic area fraction.
With CCX_JOB (the path of a run's JOB, i.e. JOB.inp and JOB.dat, e.g. of
make_reference.py --work DIR: DIR/N64_CPE8/staged_strip) it also compares
meshfree Gauss points with the nearest CalculiX integration points.
Needs python3 with numpy, scipy and h5py.
"""
import csv
import os
import sys

import h5py
import numpy as np
from scipy.spatial import cKDTree

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import extract as ex  # noqa: E402

mf, ref = sys.argv[1], HERE
job = sys.argv[2] if len(sys.argv) > 2 else None
A, B, L = 0.05, 0.1, 0.18
MON = ex.MONITORS

# curves ---------------------------------------------------------------------
rc = list(csv.DictReader(open(ref + "/reaction_curve.csv")))
h = [m for m in csv.DictReader(open(mf + "/history.csv")) if float(m["factor_pull"]) > 0]
fmax = max(abs(float(r["force_top"])) for r in rc)
print("reaction curve: v, F_ccx, F_mf, rel diff (to F_ccx), diff / max|F|")
worst_rel, worst_max = 0.0, 0.0
for r, m in zip(rc[1:], h):
    fc, fm = float(r["force_top"]), float(m["reaction_pull_y"])
    d = (fm - fc)
    worst_rel = max(worst_rel, abs(d / fc))
    worst_max = max(worst_max, abs(d) / fmax)
    print("  %.5e %.6e %.6e %+.3e %+.3e" % (float(r["v"]), fc, fm, d / fc, d / fmax))
print("  largest |rel diff| %.3e, largest |diff|/max|F| %.3e" % (worst_rel, worst_max))
print("monitors, largest |diff| over the curve / max |value| of the CalculiX monitor:")
for name in MON:
    for c in ("ux", "uy"):
        col = "%s_%s" % (c, name)
        vc = np.array([float(r[col]) for r in rc[1:]])
        vm = np.array([float(m[col]) for m in h])
        scale = np.abs(vc).max()
        if scale < 1e-12:
            print("  %-28s zero in CalculiX; meshfree max |value| %.2e" % (col, np.abs(vm).max()))
            continue
        print("  %-28s ccx %.6e mf %.6e  end rel %+.3e  curve max %.3e"
              % (col, vc[-1], vm[-1], vm[-1] / vc[-1] - 1, np.abs(vm - vc).max() / scale))

# points -----------------------------------------------------------------------
f = h5py.File(mf + "/fields.h5")
g = h5py.File(mf + "/gauss_points.h5")
last = sorted(k for k in f.keys() if k.startswith("step_"))[-1]
X = f["geometry/coordinates"][:, :2]
fs = f[last]
G = g["geometry/coordinates"][:, :2]
gs = g[last]
pts = list(csv.DictReader(open(ref + "/points.csv")))
print("points at v = 1e-3 (nodal values: CalculiX extrapolated + averaged; meshfree phi^2 w averaged):")
print("  %-22s %-5s %14s %14s %10s" % ("point", "qty", "ccx", "meshfree", "rel diff"))
svm_scale = 240e6          # initial yield stress
for p in pts:
    x, y = float(p["x"]), float(p["y"])
    i = int(np.hypot(*(X - (x, y)).T).argmin())
    vals = {"sxx": fs["stress_xx"][i], "syy": fs["stress_yy"][i], "szz": fs["stress_zz"][i],
            "sxy": fs["stress_xy"][i], "peeq": fs["plastic_strain"][i]}
    for q in ("sxx", "syy", "szz", "sxy", "peeq"):
        c, m = float(p[q]), float(vals[q])
        rel = (m - c) / abs(c) if abs(c) > (1e6 if q != "peeq" else 1e-6) else float("nan")
        print("  %-22s %-5s %14.6e %14.6e %+10.3e%s" % (p["name"], q, c, m, rel,
              "" if q == "peeq" else "   (diff/sigma_y %+.3e)" % ((m - c) / svm_scale)))

# plastic zone -------------------------------------------------------------------
pl = gs["plastic_strain"][:] > 0
pe = gs["plastic_strain"][:]
print("peak PEEQ: meshfree Gauss point %.6e at (%.5g, %.5g); meshfree nodal %.6e"
      % (pe.max(), *G[pe.argmax()], fs["plastic_strain"][:].max()))
# area fraction by nearest-point sampling on a 0.2 mm grid (the Gauss weights
# are not in the output); the same sampling of the CalculiX points follows
# with CCX_JOB, against its exact weighted value in summary.csv
hs = 2e-4
xs = np.arange(-B + hs / 2, B, hs)
ys = np.arange(hs / 2, L, hs)
XX, YY = np.meshgrid(xs, ys)
S = np.c_[XX.ravel(), YY.ravel()]
S = S[np.hypot(S[:, 0], S[:, 1]) > A]
_, idx = cKDTree(G).query(S)
print("plastic area fraction (nearest Gauss point, 0.2 mm sampling): meshfree %.6f; CalculiX "
      "(weighted integration points, summary.csv) %s" % (pl[idx].mean(), dict(
          (r["quantity"], r["value"]) for r in csv.DictReader(open(ref + "/summary.csv")))[
          "plastic_area_fraction_ip"]))
row = (G[:, 1] < 6e-4) & (np.abs(G[:, 0]) >= A)
print("net section: largest |x| of a plastic meshfree Gauss point with y < 0.6 mm: %.5g"
      % np.abs(G[row & pl, 0]).max())

if job:
    # the CalculiX integration points of the middle zeta layer (they repeat in zeta)
    nodes, elems, etype, _nsets = ex.read_inp(job + ".inp")
    dat = ex.read_dat(job + ".dat")
    pe_ip = dat[("equivalent plastic strain", "EALL")][-1][1]
    s_ip = dat[("stresses", "EALL")][-1][1]
    ips = ex.integration_points(etype)
    npl = len(ips) // (3 if etype == "CPE8" else 2)
    cx, cs, cp = [], [], []
    for e, conn in elems.items():
        xe = np.array([nodes[i] for i in conn])
        for k, (xi, eta, _w) in enumerate(ips[npl:2 * npl] if etype == "CPE8" else ips[:npl]):
            k_ip = k + 1 + (npl if etype == "CPE8" else 0)
            n, _ = ex.q8_shape(xi, eta)
            cx.append(n @ xe)
            cs.append(s_ip[(e, k_ip)][:4])
            cp.append(pe_ip[(e, k_ip)][0])
    cx, cs, cp = np.array(cx), np.array(cs), np.array(cp)
    tc = cKDTree(cx)
    _, idc = tc.query(S)
    print("plastic area fraction (same sampling of the CalculiX points): %.6f" % (cp[idc] > 0).mean())
    tm = cKDTree(G)
    print("Gauss point nearest to each point against the CalculiX integration point nearest to it:")
    for p in pts:
        _d, im = tm.query((float(p["x"]), float(p["y"])))
        dc, ic = tc.query(G[im])
        print("  %-20s meshfree (%.5f, %.5f): syy %.4e sxx %.4e szz %.4e peeq %.4e"
              % (p["name"], G[im][0], G[im][1], gs["stress_yy"][im], gs["stress_xx"][im],
                 gs["stress_zz"][im], gs["plastic_strain"][im]))
        print("  %-20s CalculiX %.2e m away:   syy %.4e sxx %.4e szz %.4e peeq %.4e"
              % ("", dc, cs[ic][1], cs[ic][0], cs[ic][2], cp[ic]))
    d, ic = tc.query(G)
    ok = d < 5e-4
    dsyy = (gs["stress_yy"][:] - cs[ic, 1])[ok] / 240e6
    dpe = (gs["plastic_strain"][:] - cp[ic])[ok]
    # nearest points, not interpolated: where the stress varies fast the distance
    # between the two points alone makes a difference
    print("all Gauss points with a CalculiX point within 0.5 mm (%d of %d): syy difference / sigma_y "
          "rms %.3e, 99th percentile of |.| %.3e; PEEQ difference rms %.3e, largest |.| %.3e "
          "(CalculiX largest PEEQ %.3e)" % (ok.sum(), len(G), np.sqrt((dsyy ** 2).mean()),
                                             np.percentile(abs(dsyy), 99), np.sqrt((dpe ** 2).mean()),
                                             abs(dpe).max(), cp.max()))
