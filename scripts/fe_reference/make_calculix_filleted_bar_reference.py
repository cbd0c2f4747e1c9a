#!/usr/bin/python3
"""Regenerate the CalculiX CPS8 reference of the filleted bar pulled into
plasticity: a stepped flat bar whose shoulder is rounded by a fillet, its upper
half (the bar is symmetric about y = 0), pulled at its narrow end.

Run from the repository root:

    /usr/bin/python3 scripts/fe_reference/make_calculix_filleted_bar_reference.py
    /usr/bin/python3 scripts/fe_reference/make_calculix_filleted_bar_reference.py --h 0.5 0.25
    /usr/bin/python3 scripts/fe_reference/make_calculix_filleted_bar_reference.py --quick

Full run: one gmsh mesh and one CalculiX run per element size (--h, default
1, 0.5, 0.25, 0.125), then writes reference/calculix_plastic/filleted_bar/
(curve.csv from the finest, convergence.csv, elastic_limit.csv, the decks below
1 MB); --quick remakes h = 1 and compares it with the committed curve_h1.csv.
The recipe's steps, checks and refusals are
scripts/fe_reference/calculix_plate_in_grips.py's.

Problem (N, mm, MPa; plane stress, 1 mm thick): the bar is 10 wide over
0 <= x <= 10 and 5 wide over 10 <= x <= 20, symmetric about y = 0; here its
upper half, y >= 0, whose re-entrant shoulder corner (10, 2.5) is rounded by a
fillet of radius 1 (r / d = 0.2, D / d = 2).  u_y = 0 on y = 0 (symmetry),
u_x = 0 on x = 0, u_x = v on x = 20 (the ends free to contract: no corner of
the body is a stress singularity, so the first yield is defined).
v = 0 ... 0.08 mm recorded at 40 equal increments.  E = 200000, nu = 0.3,
von Mises with sigma_y = 250 + 2000 alpha.  Small strain.  The same body as
problems/filleted_bar.yaml, whose geometry gives the fillet in the built-in
dialect (`fillets: [{at, radius}]`).

The fillet bounds the elastic stress, so the first yield is defined: per mesh
a linear run at v = 1 gives the largest von Mises stress, at the fillet's root,
and the grip displacement of first yield (elastic_limit.csv).

Method: gmsh meshes the outline (straight edges and the quarter-circle arc)
with 8-node quadrilaterals of size h, the midside nodes on the arc; CPS8 in a
thin slab of 1e-3 of the fillet's radius, 0.001 mm, the reactions divided by
it.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import calculix_plate_in_grips as grips  # noqa: E402

WIDE, NARROW, SHOULDER, LENGTH, RADIUS = 10.0, 5.0, 10.0, 20.0, 1.0


def body():
    """The outline counter-clockwise from (0, 0); the fillet's arc from its tangent point on the
    narrow part to the one on the shoulder."""
    a, b, r, s, l = 0.5 * WIDE, 0.5 * NARROW, RADIUS, SHOULDER, LENGTH
    points = [(0, 0), (l, 0), (l, b), (s + r, b), (s + r, b + r), (s, b + r), (s, a), (0, a)]
    lines = ["Point(%d) = {%r, %r, 0};" % (k + 1, float(x), float(y))
             for k, (x, y) in enumerate(points)]
    # Point 5 is the arc's centre.
    curves = [("Line", (1, 2)), ("Line", (2, 3)), ("Line", (3, 4)), ("Circle", (4, 5, 6)),
              ("Line", (6, 7)), ("Line", (7, 8)), ("Line", (8, 1))]
    for k, (kind, ends) in enumerate(curves):
        lines.append("%s(%d) = {%s};" % (kind, k + 1, ", ".join(str(e) for e in ends)))
    lines.append("Curve Loop(1) = {%s};" % ", ".join(str(k + 1) for k in range(len(curves))))
    lines.append("Plane Surface(1) = {1};")
    return lines


PLATE = grips.Plate(name="filleted_bar", script="make_calculix_filleted_bar_reference.py",
                    body=body, length=LENGTH, v_end=0.08, n_inc=40, slab=1e-3 * RADIUS,
                    default_h=[1.0, 0.5, 0.25, 0.125], quick_h=1.0, elastic_limit=True,
                    more_sets=[("SYMMETRY", lambda x, y: abs(y) < 1e-9)],
                    held=[("LEFT", 1, 1), ("SYMMETRY", 2, 2)])

if __name__ == "__main__":
    grips.main(PLATE, __doc__, "bar")
