#!/usr/bin/python3
"""LAMMPS reference of the shipped peridynamic disk-impact example, LPS version.

Runs LAMMPS's own example examples/peri/in.peri.lps (Debian package lammps-examples:
/usr/share/lammps/examples/peri/in.peri.lps; "small Peridynamic cylinder hit by
projectile": the target of in.peri.pmb with `pair_style peri/lps` and
`pair_coeff * * 14.9e9 14.9e9 0.0015001 0.0005 0.25` (K, G, delta, s00, alpha), the same
spherical `fix indent` indenter moving at -100 m/s) unchanged, with output commands added
before its `run`, and writes into reference/lammps/disk_impact_lps/:

  lammps.in    the deck run (the shipped example plus the added output lines, marked)
  history.csv  step,time,damaged_particles,damage_sum,indenter_force_x,_y,_z,indenter_energy
               at every step 0..1000: the number of particles with damage > 0 and the sum of
               compute damage/atom, the force on the indenter [N] and its energy [J]
               (fix indent's vector and scalar times the particle volume 1.25e-10 m^3: with
               atom_style peri they are sums of force densities and energy densities)
  log.lammps   the log up to the timing summary (the wall-clock line removed)

This is make_lammps_disk_impact.py (the peri/pmb example) with the LPS example; the files
have the same format. They are bit-for-bit reproducible (serial LAMMPS, fixed formats).
Needs the Debian packages lammps and lammps-examples.
Usage: make_lammps_disk_impact_lps.py [--out DIR]
"""
import argparse
import hashlib
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

EXAMPLE = Path("/usr/share/lammps/examples/peri/in.peri.lps")
# sha256 of the example as Debian's lammps-examples 20220106.git7586adbb6a+ds1-2 ships it.
EXAMPLE_SHA256 = "044b841b111e11f840c0c2e8104b666f3f9377ef74089a78595445bdc3f54e23"
VOLUME = 1.25e-10  # `set group all volume 1.25e-10` of the example
DT = 1.0e-7        # the example's timestep

ADDED = """\
# ---- added by scripts/pd_reference/make_lammps_disk_impact_lps.py: the histories compared ----
variable        damaged atom "c_1 > 0"
compute         ndam all reduce sum v_damaged
compute         dsum all reduce sum c_1
fix             hist all ave/time 1 1 1 c_ndam c_dsum f_2 f_2[1] f_2[2] f_2[3] &
                file history_raw.txt format " %.12e"
thermo_style    custom step time ke pe f_2 f_2[2] c_ndam
# ---- end of the added lines ----
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    here = Path(__file__).resolve().parents[2]
    ap.add_argument("--out", default=str(here / "reference" / "lammps" / "disk_impact_lps"))
    args = ap.parse_args()
    lmp = shutil.which("lmp")
    if not lmp:
        sys.exit("no LAMMPS executable 'lmp' on PATH; apt-get install lammps")
    if not EXAMPLE.exists():
        sys.exit("%s missing; apt-get install lammps-examples" % EXAMPLE)
    shipped = EXAMPLE.read_text()
    digest = hashlib.sha256(shipped.encode()).hexdigest()
    if EXAMPLE_SHA256 and digest != EXAMPLE_SHA256:
        sys.exit("%s differs from the example this reference was made from" % EXAMPLE)
    lines = shipped.splitlines()
    run = [k for k, l in enumerate(lines) if l.split()[:1] == ["run"]]
    if len(run) != 1:
        sys.exit("expected one 'run' command in %s" % EXAMPLE)
    deck = "\n".join(lines[:run[0]]) + "\n" + ADDED + "\n".join(lines[run[0]:]) + "\n"
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    with tempfile.TemporaryDirectory() as tmp:
        (Path(tmp) / "lammps.in").write_text(deck)
        res = subprocess.run([lmp, "-in", "lammps.in", "-log", "log.lammps", "-screen", "none",
                              "-nocite"], cwd=tmp, capture_output=True, text=True,
                             env=dict(os.environ, OMP_NUM_THREADS="1"))
        log = (Path(tmp) / "log.lammps").read_text()
        if res.returncode != 0 or "Loop time" not in log:
            sys.exit("LAMMPS failed:\n" + res.stdout[-2000:] + res.stderr[-2000:] + log[-2000:])
        raw = (Path(tmp) / "history_raw.txt").read_text().splitlines()
    wall = time.time() - t0
    rows = ["step,time,damaged_particles,damage_sum,indenter_force_x,indenter_force_y,"
            "indenter_force_z,indenter_energy"]
    for line in raw:
        if line.startswith("#"):
            continue
        step, ndam, dsum, energy, fx, fy, fz = line.split()
        s = int(step)
        rows.append("%d,%.7e,%d,%.12e,%.12e,%.12e,%.12e,%.12e" % (
            s, s * DT, round(float(ndam)), float(dsum), VOLUME * float(fx), VOLUME * float(fy),
            VOLUME * float(fz), VOLUME * float(energy)))
    (out / "history.csv").write_text("\n".join(rows) + "\n")
    (out / "lammps.in").write_text(deck)
    keep = log.split("Loop time of", 1)[0]
    (out / "log.lammps").write_text(
        "\n".join(l for l in keep.splitlines() if not l.startswith("Total wall time")) + "\n")

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
