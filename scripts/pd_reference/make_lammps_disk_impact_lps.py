#!/usr/bin/python3
"""LAMMPS reference of the shipped peridynamic disk-impact example, LPS version.

Runs LAMMPS's own example examples/peri/in.peri.lps (Debian package lammps-examples:
/usr/share/lammps/examples/peri/in.peri.lps; "small Peridynamic cylinder hit by
projectile": the target of in.peri.pmb with `pair_style peri/lps` and
`pair_coeff * * 14.9e9 14.9e9 0.0015001 0.0005 0.25` (K, G, delta, s00, alpha), the same
spherical `fix indent` indenter moving at -100 m/s) unchanged, with output commands added
before its `run`.  The recipe is make_lammps_disk_impact.py's (for the peri/pmb example),
imported from beside this file: it writes the same three files in the same format,
lammps.in, history.csv and log.lammps, into reference/lammps/disk_impact_lps/.  They are
bit-for-bit reproducible (serial LAMMPS, fixed formats).
Needs the Debian packages lammps and lammps-examples.
Usage: make_lammps_disk_impact_lps.py [--out DIR]
"""
import re
import sys
from pathlib import Path

sys.dont_write_bytecode = True     # no __pycache__ beside the scripts
sys.path.insert(0, str(Path(__file__).resolve().parent))
import make_lammps_disk_impact as pmbimpact  # noqa: E402  (the recipe, shared with peri/pmb's)

EXAMPLE = Path("/usr/share/lammps/examples/peri/in.peri.lps")
# sha256 of the example as Debian's lammps-examples 20220106.git7586adbb6a+ds1-2 ships it.
EXAMPLE_SHA256 = "044b841b111e11f840c0c2e8104b666f3f9377ef74089a78595445bdc3f54e23"


def main():
    out, digest, rows, log, wall = pmbimpact.make_reference(
        __doc__, "make_lammps_disk_impact_lps.py", "disk_impact_lps", EXAMPLE, EXAMPLE_SHA256)
    cols = [r.split(",") for r in rows[1:]]
    f = [float(c[5]) for c in cols]
    d = [int(c[2]) for c in cols]
    en = [float(c[7]) for c in cols]
    m = re.search(r"Created (\d+) atoms", log)
    natoms = int(m.group(1)) if m else -1
    bonds = log.split("total # of bonds = ", 1)[1].split()[0] if "total # of bonds" in log else "?"
    peak = max(range(len(f)), key=lambda k: f[k])
    low = min(range(len(f)), key=lambda k: f[k])
    contact = [k for k in range(len(f)) if f[k] != 0.0]
    first_dmg = next((k for k in range(len(d)) if d[k] > 0), None)
    print("example %s sha256 %s" % (EXAMPLE, digest))
    print("LAMMPS run %.1f s; %d particles, total # of bonds = %s" % (wall, natoms, bonds))
    print("steps %d; contact (indenter force != 0) from step %d to step %d"
          % (len(f) - 1, contact[0], contact[-1]))
    print("peak indenter force %.6g N at step %d; the force at steps %d..%d: %s N; most negative %.6g N "
          "at step %d" % (f[peak], peak, peak - 2, peak + 12,
                          " ".join("%.4g" % f[k] for k in range(peak - 2, peak + 13)), f[low], low))
    print("largest indenter energy %.4g J at step %d" % (max(en), max(range(len(en)), key=lambda k: en[k])))
    print("first damaged particle at step %s; damaged particles at steps 100, 150, 200, 250, 1000: %s (of %d)"
          % (first_dmg, [d[k] for k in (100, 150, 200, 250, 1000)], natoms))
    print("damage sum at step 1000: %.6f" % float(cols[1000][3]))
    print("wrote %s" % out)


if __name__ == "__main__":
    main()
