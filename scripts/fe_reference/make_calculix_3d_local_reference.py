#!/usr/bin/python3
"""Regenerate the local values of the CalculiX C3D20R reference of the thick
perforated plate: the equivalent plastic strain and the von Mises stress at
the hole's edge on the net section, per increment, on two mesh levels.

Run from the repository root:

    /usr/bin/python3 scripts/fe_reference/make_calculix_3d_local_reference.py
    /usr/bin/python3 scripts/fe_reference/make_calculix_3d_local_reference.py --quick

The problem, meshes and decks are make_calculix_3d_reference.py's (the one
eighth of the perforated strip made 5 mm thick, C3D20R, v = 0 ... 0.1 mm in
20 fixed increments); its decks gain nodal output of S and PEEQ (CalculiX's
values extrapolated to the nodes, averaged over the elements there) at
(5, 0, 0), the hole's edge on the net section in the mid-plane, and at
(5, 0, 2.5), the same edge on the plate's face.  Full run: levels (16, 2)
and (24, 3) of that recipe; writes
reference/calculix_3d/thick_perforated_plate/local.csv (the finest level)
and local_convergence.csv (the final values of both and their change).
Nothing is written unless both runs succeeded (20 records of each value).
--quick remakes level (8, 1) in a temporary folder and compares it with the
committed local_level0.csv (exit 1 beyond 1e-6 of each column's largest
|value|); the full run writes that file too.  --out DIR writes into DIR.
"""

import csv
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_calculix_reference as elastic_recipe  # noqa: E402  (run_ccx)
import make_calculix_plastic_reference as plane_recipe  # noqa: E402  (von Mises)
import make_calculix_3d_reference as plate_recipe  # noqa: E402  (meshes, decks)
from make_calculix_punch_3d_reference import parse_frd_node, write_curve  # noqa: E402

NAME = plate_recipe.NAME
DEFAULT_OUT = os.path.join(plate_recipe.DEFAULT_OUT, NAME)
POINTS = [("5_0_0", (5.0, 0.0, 0.0)), ("5_0_25", (5.0, 0.0, plate_recipe.HALF_T))]
COLUMNS = ["increment", "v"] + [f"{q}_{p}" for p, _x in POINTS for q in ("peeq", "mises")]
LEVELS = [(16, 2), (24, 3)]
QUICK_LEVEL = (8, 1)
QUICK_TOL = 1e-6


def write_deck(path, mesh, ids):
    """The plate recipe's plastic deck with the nodal S and PEEQ of `ids`."""
    plate_recipe.write_deck(path, mesh)
    with open(path) as f:
        deck = f.read()
    nset = "*NSET, NSET=LOCAL\n" + "".join("%d,\n" % i for i in ids)
    if deck.count("*MATERIAL") != 1 or deck.count("*EL FILE\nPEEQ\n") != 1:
        raise RuntimeError("the plate recipe's deck changed: no place for the local output")
    deck = deck.replace("*MATERIAL", nset + "*MATERIAL")
    deck = deck.replace("*EL FILE\nPEEQ\n", "*EL FILE, NSET=LOCAL\nS, PEEQ\n")
    with open(path, "w") as f:
        f.write(deck)


def solve(n, nz, work):
    """Rows (increment, v, then PEEQ and von Mises at each point), row 0 unloaded."""
    mesh = plate_recipe.plate_mesh(n, nz)
    ids = [mesh.find(x) for _p, x in POINTS]
    job = "%s_local_%d_%d" % (NAME, n, nz)
    t0 = time.time()
    write_deck(os.path.join(work, job + ".inp"), mesh, ids)
    elastic_recipe.run_ccx(work, job)
    wall = time.time() - t0
    values = [parse_frd_node(os.path.join(work, job + ".frd"), i) for i in ids]
    for v in values:
        if len(v.get("STRESS", [])) != plate_recipe.N_INC or len(v.get("PE", [])) != \
                plate_recipe.N_INC or None in v["STRESS"] or None in v["PE"]:
            raise RuntimeError("%s: %d records of S and PEEQ expected" % (job, plate_recipe.N_INC))
    rows = [[0, 0.0] + [0.0] * (2 * len(POINTS))]
    for k in range(plate_recipe.N_INC):
        row = [k + 1, plate_recipe.V_END * (k + 1) / plate_recipe.N_INC]
        for v in values:
            row += [v["PE"][k][0], float(plane_recipe.von_mises(np.array(v["STRESS"][k][:6])))]
        rows.append(row)
    print("  level (%d, %d), %d nodes: ccx %.1f s; final %s"
          % (n, nz, mesh.nnodes, wall, ", ".join("%s %.6g" % (c, x)
                                                for c, x in zip(COLUMNS[2:], rows[-1][2:]))),
          flush=True)
    return rows, wall


def read_rows(path):
    with open(path) as f:
        return [[float(v) for v in r] for r in list(csv.reader(f))[1:]]


def write_convergence(path, finals):
    """Per level of LEVELS (`finals`: its last row and wall time) the final values and their
    change from the previous level."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["n", "nz", "wall_s"] + COLUMNS[2:] + ["rel_change_" + c for c in COLUMNS[2:]])
        prev = None
        for (n, nz), (last, wall) in zip(LEVELS, finals):
            values = last[2:]
            change = ([""] * len(values) if prev is None else
                      ["%.3e" % ((a - b) / a) for a, b in zip(values, prev)])
            w.writerow([n, nz, "%.1f" % wall] + ["%.7g" % x for x in values] + change)
            prev = values


def full_run(out, work):
    coarse, _ = solve(*QUICK_LEVEL, work)
    runs = [solve(n, nz, work) for n, nz in LEVELS]
    os.makedirs(out, exist_ok=True)
    write_curve(os.path.join(out, "local_level0.csv"), coarse, COLUMNS)
    write_curve(os.path.join(out, "local.csv"), runs[-1][0], COLUMNS)
    write_convergence(os.path.join(out, "local_convergence.csv"),
                      [(rows[-1], wall) for rows, wall in runs])
    a, b = runs[0][0][-1][2:], runs[1][0][-1][2:]
    print("rel. change of the final values, level (16, 2) -> (24, 3): "
          + ", ".join("%s %.2e" % (c, (y - x) / y) for c, x, y in zip(COLUMNS[2:], a, b)))


def quick_run(out, work):
    rows, _ = solve(*QUICK_LEVEL, work)
    ref = read_rows(os.path.join(out, "local_level0.csv"))
    got, ref = np.array(rows, dtype=float), np.array(ref)
    scale = np.abs(ref).max(axis=0)
    scale[scale == 0] = 1.0
    worst = float((np.abs(got - ref).max(axis=0) / scale).max())
    print("quick check: max relative difference %.3e" % worst)
    return 0 if worst <= QUICK_TOL else 1


def main():
    elastic_recipe.recipe_main(__doc__, DEFAULT_OUT, lambda out, work, args: full_run(out, work),
                               quick_run)

if __name__ == "__main__":
    main()
