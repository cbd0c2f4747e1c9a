#!/usr/bin/python3
"""Regenerate the CalculiX CPS8 reference of the slotted plate pulled into
plasticity: a plate with an inclined slot (two straight sides, two round
ends), held in grips at both ends, one grip pulled.

Run from the repository root:

    /usr/bin/python3 scripts/fe_reference/make_calculix_slotted_plate_reference.py
    /usr/bin/python3 scripts/fe_reference/make_calculix_slotted_plate_reference.py --h 0.5 0.25
    /usr/bin/python3 scripts/fe_reference/make_calculix_slotted_plate_reference.py --quick

Full run: one gmsh mesh and one CalculiX run per element size (--h, default
0.5, 0.25, 0.125), then writes reference/calculix_plastic/slotted_plate/:
curve_h<h>.csv per mesh, curve.csv (the finest, which scripts/compare.py reads),
convergence.csv and the decks below 1 MB.  Nothing is
written unless every run succeeded (gmsh's and ccx's return codes, no *ERROR,
all 40 increments in the .dat file).  --quick remakes the mesh of h = 1 (945
nodes, about 15 s) in a temporary folder and compares it with the committed
curve_h1.csv, written by `--h 1 --out DIR` (exit 1 beyond 1e-6 of each
column's largest |value|).  --out DIR (or CALCULIX_REFERENCE_OUT=DIR)
writes into DIR instead.

Problem (N, mm, MPa; plane stress, 1 mm thick): the plate [0, 20] x [0, 10]
less the slot of width 2 whose round ends are centred at (8.4, 3.8) and
(11.6, 6.2) (its axis at atan(3/4) = 36.87 degrees to x).  u_x = u_y = 0 on
x = 0; u_x = v, u_y = 0 on x = 20 (grips).  v = 0 ... 0.08 mm recorded at 40
equal increments (automatic incrementation, *TIME POINTS at the records).  E = 200000, nu = 0.3, von Mises with
sigma_y = 250 + 2000 alpha (*PLASTIC (250, 0), (20250, 10)).  Small strain.
The same body as problems/slotted_plate.yaml, whose geometry gives the slot
in the built-in dialect (`holes: [{slot: {from, to, width}}]`).

Recorded per increment: v; the grip's reactions F_x and F_y (the sums of RF
over the nodes of x = 20; the inclined slot couples the pull to a shear, so
F_y is not zero).

Method (scripts/fe_reference/calculix_plate_in_grips.py, which the filleted
bar's recipe shares): gmsh meshes the plate minus the slot (a rotated rectangle
and two discs) with 8-node quadrilaterals of size h, the midside nodes on the
round ends; CPS8 in a thin slab of 1e-3 of the slot's width, 0.002 mm, the
reactions divided by it.
Measured: h = 0.5, 0.25, 0.125 took 54, 397 and 2,055 s (h = 1, --quick: 15 s).
"""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import calculix_plate_in_grips as grips  # noqa: E402

SLOT_FROM, SLOT_TO, SLOT_WIDTH = (8.4, 3.8), (11.6, 6.2), 2.0
WIDTH, HEIGHT = 20.0, 10.0


def body():
    (ax, ay), (bx, by) = SLOT_FROM, SLOT_TO
    length = np.hypot(bx - ax, by - ay)
    angle = np.arctan2(by - ay, bx - ax)
    cx, cy, r = 0.5 * (ax + bx), 0.5 * (ay + by), 0.5 * SLOT_WIDTH
    return [
        "Rectangle(1) = {0, 0, 0, %r, %r};" % (WIDTH, HEIGHT),
        "Rectangle(2) = {%r, %r, 0, %r, %r};" % (cx - length / 2, cy - r, length, 2 * r),
        "Rotate {{0, 0, 1}, {%r, %r, 0}, %r} { Surface{2}; }" % (cx, cy, angle),
        "Disk(3) = {%r, %r, 0, %r, %r};" % (ax, ay, r, r),
        "Disk(4) = {%r, %r, 0, %r, %r};" % (bx, by, r, r),
        "BooleanDifference{ Surface{1}; Delete; }{ Surface{2, 3, 4}; Delete; }"]


PLATE = grips.Plate(name="slotted_plate", script="make_calculix_slotted_plate_reference.py",
                    body=body, length=WIDTH, v_end=0.08, n_inc=40, slab=1e-3 * SLOT_WIDTH,
                    default_h=[0.5, 0.25, 0.125], quick_h=1.0)

if __name__ == "__main__":
    grips.main(PLATE, __doc__, "slot")
