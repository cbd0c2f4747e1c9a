#!/usr/bin/env python3
"""Mesh and CalculiX deck of the preload of staged_strip_blast.

    python3 mesh_and_deck.py N DECK.inp [--element CPE8|CPE8R]

Half model (y >= 0) of a strip x in [-0.1, 0.1] m, y in [-0.18, 0.18] with a
central hole of radius 0.05: the rectangle [-0.1, 0.1] x [0, 0.18] minus the
half disc r <= 0.05.  Plane strain, unit thickness, SI units (N, m, Pa).
E = 70e9, nu = 0.3, J2 with linear isotropic hardening
sigma_y(alpha) = 240e6 + 2.24e9 alpha, density 2700.
Bottom y = 0, |x| >= 0.05: u_y = 0.  Top y = 0.18: u_x = 0, u_y = v, v ramped
to 1.0e-3 in 20 equal fixed increments (*STATIC, DIRECT).  Hole and sides free.

Mesh: eight mapped blocks of 8-node quadrilaterals, four per quarter, the
quarter x <= 0 the mirror image of x >= 0.  In the quarter x >= 0:
  block 1: arc 0..45 deg of the hole -> right edge x = 0.1, 0 <= y <= 0.09,
  block 2: arc 45..90 deg -> line y = 0.09, 0.1 >= x >= 0,
  block 3: rectangle [0, 0.1] x [0.09, 0.18].
N elements along each arc block (uniform in angle: hole edge size
(pi/4) 0.05 / N), ceil(0.625 N) radially with sizes growing geometrically by a
factor 4 from the hole; block 3 has N columns and N/2 rows growing by a factor
2 upwards.  Midside nodes sit at the mapped parameter midpoints, so the hole
edge is an exact quadratic arc interpolant.  The four monitor points
(0.1, 0), (0.05, 0), (0, 0.05), (0.1, 0.09) are block corners, hence nodes.
Needs only the python standard library.
"""

import argparse
import math

A, B, L, YB = 0.05, 0.1, 0.18, 0.09        # hole radius, half width, height, block split
E, NU, SIG_Y, H_LIN, RHO = 70e9, 0.3, 240e6, 2.24e9, 2700.0
V_END, N_INC = 1.0e-3, 20
ALPHA_TABLE_END = 1.0                       # linear table exact up to alpha = 1
MONITORS = (("edge_at_net_section", 0.1, 0.0), ("hole_at_net_section", 0.05, 0.0),
            ("hole_top", 0.0, 0.05), ("side_mid_height", 0.1, 0.09))
# Newton tolerances (*CONTROLS, PARAMETERS=FIELD): residual <= R_N x the
# average force, correction <= C_N x the largest increment; far tighter than
# the CalculiX defaults (0.005, 0.01) so that the iteration limits nothing.
CONTROL_RN, CONTROL_CN = 1e-8, 1e-8


def geometric(n, ratio):
    """n+1 parameters in [0, 1] whose intervals grow geometrically, last /
    first = ratio."""
    q = ratio ** (1.0 / (n - 1))
    s = [0.0]
    for k in range(n):
        s.append(s[-1] + q ** k)
    return [v / s[-1] for v in s]


def halves(p):
    """Mesh-line parameters with the midpoints inserted."""
    out = []
    for a, b in zip(p[:-1], p[1:]):
        out += [a, 0.5 * (a + b)]
    return out + [p[-1]]


def blocks(n):
    sp = [k / n for k in range(n + 1)]
    rp = geometric(int(math.ceil(0.625 * n)), 4.0)
    tp = geometric(n // 2, 2.0)

    def lerp(p, q, r):
        return ((1 - r) * p[0] + r * q[0], (1 - r) * p[1] + r * q[1])

    def b1(s, r):
        t = 0.25 * math.pi * s
        return lerp((A * math.cos(t), A * math.sin(t)), (B, YB * s), r)

    def b2(s, r):
        t = 0.25 * math.pi * (1.0 + s)
        return lerp((A * math.cos(t), A * math.sin(t)), (B * (1.0 - s), YB), r)

    def b3(s, r):
        return (B * (1.0 - s), YB + (L - YB) * r)

    quarter = [(b1, sp, rp), (b2, sp, rp), (b3, sp, tp)]
    mirrored = [((lambda s, r, f=f: (-f(s, r)[0], f(s, r)[1])), a, b) for f, a, b in quarter]
    return quarter + mirrored


def build_mesh(n):
    """(nodes [(x, y)], elements [[8 node ids]]): corners counter-clockwise,
    then the midsides of edges 1-2, 2-3, 3-4, 4-1 (CalculiX order); node ids
    from 1, nodes shared by blocks merged by their rounded coordinates."""
    xy, lookup, elems = [], {}, []

    def node(p):
        key = (round(p[0], 10) + 0.0, round(p[1], 10) + 0.0)
        if key not in lookup:
            xy.append(key)
            lookup[key] = len(xy)
        return lookup[key]

    for fun, sp, rp in blocks(n):
        sh, rh = halves(sp), halves(rp)
        for a in range(len(sp) - 1):
            for b in range(len(rp) - 1):
                i, j = 2 * a, 2 * b
                loc = ((i, j), (i + 2, j), (i + 2, j + 2), (i, j + 2),
                       (i + 1, j), (i + 2, j + 1), (i + 1, j + 2), (i, j + 1))
                pts = [fun(sh[p], rh[q]) for p, q in loc]
                area = sum(pts[k][0] * pts[(k + 1) % 4][1] - pts[(k + 1) % 4][0] * pts[k][1]
                           for k in range(4))
                if area < 0:   # clockwise: corners 1 4 3 2, midsides 8 7 6 5
                    pts = [pts[0], pts[3], pts[2], pts[1], pts[7], pts[6], pts[5], pts[4]]
                elems.append([node(p) for p in pts])
    return xy, elems


def write_list(f, ids, per_line=16):
    for k in range(0, len(ids), per_line):
        f.write(", ".join(str(v) for v in ids[k:k + per_line]) + ",\n")


def write_deck(path, n, element="CPE8"):
    xy, elems = build_mesh(n)
    on = lambda a, b: abs(a - b) < 1e-12
    bottom = [k + 1 for k, (x, y) in enumerate(xy) if on(y, 0.0) and abs(x) >= A - 1e-12]
    top = [k + 1 for k, (x, y) in enumerate(xy) if on(y, L)]
    ids = {(x, y): k + 1 for k, (x, y) in enumerate(xy)}
    mon = [ids[(x, y)] for _name, x, y in MONITORS]
    with open(path, "w") as f:
        f.write("** staged_strip_blast preload: perforated strip, half model y >= 0, plane strain,\n"
                "** unit thickness, SI units (N, m, Pa); written by mesh_and_deck.py %d --element %s\n"
                "** mesh: N = %d elements per 45-degree hole arc (hole edge size %.4g m), "
                "%d %s elements, %d nodes\n"
                % (n, element, n, 0.25 * math.pi * A / n, len(elems), element, len(xy)))
        f.write("** monitor nodes (%s): %s\n" % (", ".join(m[0] for m in MONITORS),
                                                   ", ".join(map(str, mon))))
        f.write("*HEADING\nstaged_strip preload N=%d %s\n" % (n, element))
        f.write("*NODE, NSET=NALL\n")
        for k, (x, y) in enumerate(xy):
            f.write("%d, %r, %r\n" % (k + 1, x, y))
        f.write("*ELEMENT, TYPE=%s, ELSET=EALL\n" % element)
        for k, conn in enumerate(elems):
            f.write("%d, %s\n" % (k + 1, ", ".join(map(str, conn))))
        for name, ids_ in (("BOTTOM", bottom), ("TOP", top), ("MON", mon)):
            f.write("*NSET, NSET=%s\n" % name)
            write_list(f, ids_)
        f.write("*MATERIAL, NAME=ALU\n*ELASTIC\n%r, %r\n" % (E, NU))
        f.write("** von Mises yield stress vs equivalent plastic strain: linear hardening, exact\n"
                "** with two points up to alpha = %g (CalculiX continues a table flat beyond)\n"
                % ALPHA_TABLE_END)
        f.write("*PLASTIC\n%r, 0.\n%r, %r\n" % (SIG_Y, SIG_Y + H_LIN * ALPHA_TABLE_END,
                                                ALPHA_TABLE_END))
        f.write("*DENSITY\n%r\n" % RHO)
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=ALU\n1.\n")
        f.write("*BOUNDARY\nBOTTOM, 2, 2\nTOP, 1, 1\n")
        # step 1: the preload, v = 0 -> V_END in N_INC fixed increments
        f.write("*STEP, INC=1000\n*STATIC, DIRECT\n%r, 1.\n" % (1.0 / N_INC))
        f.write("*CONTROLS, PARAMETERS=FIELD\n%g, %g\n" % (CONTROL_RN, CONTROL_CN))
        f.write("*BOUNDARY\nTOP, 2, 2, %r\n" % V_END)
        f.write("*NODE PRINT, NSET=MON\nU\n*NODE PRINT, NSET=TOP, TOTALS=ONLY\nRF\n")
        f.write("*END STEP\n")
        # step 2: v held for one increment (nothing changes); the fields of
        # the final state: nodal values to the .frd, integration points to the .dat
        f.write("*STEP, INC=1000\n*STATIC, DIRECT\n1., 1.\n")
        f.write("*CONTROLS, PARAMETERS=FIELD\n%g, %g\n" % (CONTROL_RN, CONTROL_CN))
        f.write("*BOUNDARY\nTOP, 2, 2, %r\n" % V_END)
        f.write("*NODE PRINT, NSET=MON\nU\n*NODE PRINT, NSET=TOP, TOTALS=ONLY\nRF\n")
        f.write("*NODE FILE\nU\n*EL FILE\nS, PEEQ\n")
        f.write("*EL PRINT, ELSET=EALL\nPEEQ, S\n")
        f.write("*END STEP\n")
    return len(elems), len(xy)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("n", type=int, help="elements per 45-degree hole arc (even)")
    ap.add_argument("deck")
    ap.add_argument("--element", default="CPE8", choices=("CPE8", "CPE8R"))
    args = ap.parse_args()
    ne, nn = write_deck(args.deck, args.n, args.element)
    print("%s: %d %s elements, %d nodes" % (args.deck, ne, args.element, nn))


if __name__ == "__main__":
    main()
