#!/usr/bin/env python3
"""Extract the reference values from a CalculiX run of the deck written by
mesh_and_deck.py.

    python3 extract.py JOB OUTDIR      (reads JOB.inp, JOB.dat, JOB.frd)

Writes to OUTDIR
  reaction_curve.csv  increment, v, force_top (sum of RF_y over the top edge,
                      N per m of thickness), then u_x, u_y of the four monitor
                      nodes, one row per increment (row 0 = unloaded state);
  points.csv          name, x, y, ux, uy, sxx, syy, szz, sxy, peeq at the four
                      monitor nodes at v = 1e-3: displacements from *NODE PRINT,
                      stresses and equivalent plastic strain as CalculiX writes
                      them to the .frd (*EL FILE: integration-point values
                      extrapolated to the nodes of every element and averaged
                      over the elements at the node);
  summary.csv         quantity, value: peak equivalent plastic strain (nodal and
                      at the integration points, with its place), the plastic
                      zone on the net section y = 0 and the plastic area
                      fraction (integration points with PEEQ > 0, weighted by
                      their area w_i det J_i), checks.
Needs python3 with numpy.
"""

import csv
import math
import os
import re
import sys

import numpy as np

MONITORS = ("edge_at_net_section", "hole_at_net_section", "hole_top", "side_mid_height")
A, B, V_END, N_INC = 0.05, 0.1, 1.0e-3, 20
G3 = math.sqrt(0.6)
G2 = 1.0 / math.sqrt(3.0)


def read_inp(path):
    """nodes {id: (x, y)}, elements {id: [8 ids]}, element type, nsets."""
    nodes, elems, nsets = {}, {}, {}
    etype, mode, cur = None, None, None
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s or s.startswith("**"):
                continue
            if s.startswith("*"):
                up = s.upper().replace(" ", "")
                mode = None
                if up.startswith("*NODE,") or up == "*NODE":
                    mode = "node"
                elif up.startswith("*ELEMENT"):
                    mode = "elem"
                    etype = re.search(r"TYPE=(\w+)", up).group(1)
                elif up.startswith("*NSET"):
                    mode = "nset"
                    cur = re.search(r"NSET=(\w+)", up).group(1)
                    nsets[cur] = []
                continue
            v = [t for t in s.replace(",", " ").split()]
            if mode == "node":
                nodes[int(v[0])] = (float(v[1]), float(v[2]))
            elif mode == "elem":
                elems[int(v[0])] = [int(t) for t in v[1:9]]
            elif mode == "nset":
                nsets[cur] += [int(t) for t in v]
    return nodes, elems, etype, nsets


HDR = re.compile(r"^\s*(displacements|total force|equivalent plastic strain|stresses)\s*"
                 r"\(.*?\)\s*for set\s+(\S+)\s+and time\s+(\S+)", re.IGNORECASE)


def read_dat(path):
    """{(kind, SET): [(time, {key: values})]}."""
    out, cur = {}, None
    with open(path) as f:
        for line in f:
            m = HDR.match(line)
            if m:
                cur = (m.group(1).lower(), m.group(2).upper())
                out.setdefault(cur, []).append((float(m.group(3)), {}))
                continue
            s = line.split()
            if cur is None or not s:
                continue
            blk = out[cur][-1][1]
            if cur[0] == "total force":
                blk[0] = tuple(map(float, s))
            elif cur[0] in ("equivalent plastic strain", "stresses"):
                blk[(int(s[0]), int(s[1]))] = tuple(map(float, s[2:]))
            else:
                blk[int(s[0])] = tuple(map(float, s[1:]))
    return out


def read_frd(path):
    """Last block of every nodal result in the .frd: {name: {node: values}}."""
    out, name = {}, None
    with open(path) as f:
        for line in f:
            if line.startswith(" -4"):
                name = line.split()[1]
                out[name] = {}
            elif line.startswith(" -3"):
                name = None
            elif name and line.startswith(" -1"):
                nid = int(line[3:13])
                vals = [float(line[13 + 12 * k:25 + 12 * k]) for k in range((len(line.rstrip()) - 13) // 12)]
                out[name][nid] = vals
    return out


def q8_shape(xi, eta):
    """Serendipity shape functions and derivatives, CalculiX node order."""
    xin = (-1, 1, 1, -1, 0, 1, 0, -1)
    etn = (-1, -1, 1, 1, -1, 0, 1, 0)
    n, dn = np.zeros(8), np.zeros((8, 2))
    for a in range(8):
        xa, ea = xin[a], etn[a]
        if a < 4:
            n[a] = 0.25 * (1 + xi * xa) * (1 + eta * ea) * (xi * xa + eta * ea - 1)
            dn[a] = (0.25 * xa * (1 + eta * ea) * (2 * xi * xa + eta * ea),
                     0.25 * ea * (1 + xi * xa) * (xi * xa + 2 * eta * ea))
        elif xa == 0:
            n[a] = 0.5 * (1 - xi * xi) * (1 + eta * ea)
            dn[a] = (-xi * (1 + eta * ea), 0.5 * ea * (1 - xi * xi))
        else:
            n[a] = 0.5 * (1 + xi * xa) * (1 - eta * eta)
            dn[a] = (0.5 * xa * (1 - eta * eta), -eta * (1 + xi * xa))
    return n, dn


def integration_points(etype):
    """(xi, eta, weight) of the points CalculiX prints for the C3D20 (CPE8)
    or C3D20R (CPE8R) that it expands the element into: xi fastest, then eta,
    then zeta (the zeta layers repeat the plane-strain state)."""
    if etype == "CPE8":
        g, w = (-G3, 0.0, G3), (5 / 9, 8 / 9, 5 / 9)
    else:
        g, w = (-G2, G2), (1.0, 1.0)
    pts = []
    for _z in g:
        for j, eta in enumerate(g):
            for i, xi in enumerate(g):
                pts.append((xi, eta, w[i] * w[j] / len(g)))
    return pts


def main():
    job, outdir = sys.argv[1], sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    nodes, elems, etype, nsets = read_inp(job + ".inp")
    dat = read_dat(job + ".dat")
    frd = read_frd(job + ".frd")
    mon = nsets["MON"]
    disp = dat[("displacements", "MON")]
    force = dat[("total force", "TOP")]
    if len(disp) != N_INC + 1 or len(force) != N_INC + 1:
        raise SystemExit("expected %d increments + the hold, found %d / %d"
                         % (N_INC, len(disp) - 1, len(force) - 1))
    # reaction curve (step 1) ----------------------------------------------
    cols = ["increment", "v", "force_top"]
    for name in MONITORS:
        cols += ["ux_" + name, "uy_" + name]
    rows = [[0, 0.0, 0.0] + [0.0] * 8]
    for k in range(N_INC):
        t, blk = disp[k]
        if abs(t - (k + 1) / N_INC) > 1e-6:
            raise SystemExit("increment %d at time %g" % (k + 1, t))
        row = [k + 1, V_END * (k + 1) / N_INC, force[k][1][0][1]]
        for nid in mon:
            row += [blk[nid][0], blk[nid][1]]
        rows.append(row)
    with open(os.path.join(outdir, "reaction_curve.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for r in rows:
            w.writerow([r[0]] + ["%.7e" % v for v in r[1:]])
    # the hold step reproduces the last increment
    hold_diff = max(abs(a - b) for a, b in zip(disp[-1][1][mon[0]], disp[-2][1][mon[0]]))
    hold_force = abs(force[-1][1][0][1] / force[-2][1][0][1] - 1.0)
    # points at v = V_END -----------------------------------------------------
    s_nod, pe_nod = frd["STRESS"], frd["PE"]
    with open(os.path.join(outdir, "points.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["name", "x", "y", "ux", "uy", "sxx", "syy", "szz", "sxy", "peeq"])
        for name, nid in zip(MONITORS, mon):
            x, y = nodes[nid]
            u = disp[-2][1][nid]
            s = s_nod[nid]
            w.writerow([name, "%g" % x, "%g" % y] + ["%.6e" % v for v in
                                                    (u[0], u[1], s[0], s[1], s[2], s[3], pe_nod[nid][0])])
    # plastic zone from the integration points --------------------------------
    pe_ip = dat[("equivalent plastic strain", "EALL")][-1][1]
    ips = integration_points(etype)
    xyz, peq, wts = [], [], []
    for e, conn in elems.items():
        xe = np.array([nodes[i] for i in conn])
        for k, (xi, eta, wk) in enumerate(ips):
            n, dn = q8_shape(xi, eta)
            jac = xe.T @ dn
            xyz.append(n @ xe)
            wts.append(wk * np.linalg.det(jac))
            peq.append(pe_ip[(e, k + 1)][0])
    xyz, peq, wts = np.array(xyz), np.array(peq), np.array(wts)
    plastic = peq > 0.0
    area = wts.sum()
    exact_area = 2 * B * 0.18 - 0.5 * math.pi * A * A
    # symmetry check of the located points: PEEQ at (x, y) and (-x, y)
    grid = np.round(xyz * 1e8).astype(np.int64)
    key = {(gx, gy): p for (gx, gy), p in zip(grid.tolist(), peq)}

    def mirror(gx, gy):
        for dx in (0, -1, 1):
            for dy in (0, -1, 1):
                if (-gx + dx, gy + dy) in key:
                    return key[(-gx + dx, gy + dy)]
        raise SystemExit("no mirror image of the integration point (%g, %g)" % (gx, gy))

    sym = max(abs(mirror(gx, gy) - p) for (gx, gy), p in zip(grid.tolist(), peq))
    # net section: the row of points nearest to y = 0 in the elements on it,
    # and the nodes on y = 0 (nodal values)
    net_elems = [e for e, conn in elems.items()
                 if sum(abs(nodes[i][1]) < 1e-12 for i in conn) == 3]
    npt = len(ips)
    order = {e: k for k, e in enumerate(elems)}
    row0 = []                        # (|x|, peeq, y) of the points nearest to y = 0
    for e in net_elems:
        sl = slice(order[e] * npt, (order[e] + 1) * npt)
        ye = xyz[sl, 1]
        near = ye < ye.min() + 1e-9 * B
        row0 += [(abs(x), p, y) for (x, y), p in zip(xyz[sl][near], peq[sl][near])]
    ymin = max(t[2] for t in row0)
    x_ip = max((t[0] for t in row0 if t[1] > 0.0), default=float("nan"))
    net_nodes = sorted((abs(nodes[i][0]), pe_nod[i][0]) for i in nodes
                       if abs(nodes[i][1]) < 1e-12 and abs(nodes[i][0]) >= A - 1e-12)
    x_nod = max((x for x, p in net_nodes if p > 0.0), default=float("nan"))
    imax = int(np.argmax(peq))
    nmax = max(pe_nod, key=lambda i: pe_nod[i][0])
    summary = [
        ("element", etype),
        ("elements", len(elems)),
        ("nodes", len(nodes)),
        ("force_top_at_v_end", "%.7e" % rows[-1][2]),
        ("peeq_max_node", "%.6e" % pe_nod[nmax][0]),
        ("peeq_max_node_x", "%.6g" % nodes[nmax][0]),
        ("peeq_max_node_y", "%.6g" % nodes[nmax][1]),
        ("peeq_max_ip", "%.6e" % peq[imax]),
        ("peeq_max_ip_x", "%.6g" % xyz[imax][0]),
        ("peeq_max_ip_y", "%.6g" % xyz[imax][1]),
        ("net_section_plastic_x_max_node", "%.6g" % x_nod),
        ("net_section_plastic_x_max_ip", "%.6g" % x_ip),
        ("net_section_ip_row_y_max", "%.6g" % ymin),
        ("net_section_peeq_min_node", "%.6e" % min(p for _x, p in net_nodes)),
        ("plastic_area_fraction_ip", "%.6f" % (wts[plastic].sum() / area)),
        ("check_area_rel_error", "%.3e" % (area / exact_area - 1.0)),
        ("check_ip_symmetry_max_peeq_diff", "%.3e" % sym),
        ("check_hold_step_du", "%.3e" % hold_diff),
        ("check_hold_step_dforce_rel", "%.3e" % hold_force),
    ]
    with open(os.path.join(outdir, "summary.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["quantity", "value"])
        w.writerows(summary)
    for k, v in summary:
        print("%-34s %s" % (k, v))


if __name__ == "__main__":
    main()
