#!/usr/bin/python3
"""LAMMPS reference of the shipped peridynamic disk-impact example.

Runs LAMMPS's own example examples/peri/in.peri.pmb (Debian package lammps-examples:
/usr/share/lammps/examples/peri/in.peri.pmb; "small Peridynamic cylinder hit by projectile":
peri/pmb target, spherical `fix indent` indenter moving at -100 m/s) unchanged, with output
commands added before its `run`, and writes into reference/lammps/disk_impact/:

  lammps.in    the deck run (the shipped example plus the added output lines, marked)
  history.csv  step,time,damaged_particles,damage_sum,indenter_force_x,_y,_z,indenter_energy
               at every step 0..1000: the number of particles with damage > 0 and the sum of
               compute damage/atom, the force on the indenter [N] and its energy [J]
               (fix indent's vector and scalar times the particle volume 1.25e-10 m^3: with
               atom_style peri they are sums of force densities and energy densities)
  log.lammps   the log up to the timing summary (the wall-clock lines removed)

The files are bit-for-bit reproducible (serial LAMMPS, fixed formats). Needs the Debian
packages lammps and lammps-examples. Usage: make_lammps_disk_impact.py [--out DIR]
"""
import argparse
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

EXAMPLE = Path("/usr/share/lammps/examples/peri/in.peri.pmb")
# sha256 of the example as Debian's lammps-examples 20220106.git7586adbb6a+ds1-2 ships it.
EXAMPLE_SHA256 = "299440d5b038c819c51711ada30484041b61acfcb2246413c0939e482373c8af"
# the same in this example and in.peri.lps (make_lammps_disk_impact_lps.py)
VOLUME = 1.25e-10  # `set group all volume 1.25e-10` of the example
DT = 1.0e-7        # the example's timestep

# the output lines added before the example's `run`; {script} is the recipe's file name
ADDED = """\
# ---- added by scripts/pd_reference/{script}: the histories compared ----
variable        damaged atom "c_1 > 0"
compute         ndam all reduce sum v_damaged
compute         dsum all reduce sum c_1
fix             hist all ave/time 1 1 1 c_ndam c_dsum f_2 f_2[1] f_2[2] f_2[3] &
                file history_raw.txt format " %.12e"
thermo_style    custom step time ke pe f_2 f_2[2] c_ndam
# ---- end of the added lines ----
"""


def make_reference(doc, script, case, example, example_sha256):
    """The recipe of this script and of make_lammps_disk_impact_lps.py: read --out (default
    reference/lammps/<case>), check the shipped `example` against its sha256, add the output
    lines (marked with the recipe's file name `script`) before its `run`, run it with serial
    LAMMPS and write lammps.in, history.csv and log.lammps.  Returns (out, digest, rows, log,
    wall): the output folder, the example's sha256, the lines of history.csv (the header
    first), LAMMPS' whole log and the seconds the LAMMPS run took."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    here = Path(__file__).resolve().parents[2]
    ap.add_argument("--out", default=str(here / "reference" / "lammps" / case))
    args = ap.parse_args()
    lmp = shutil.which("lmp")
    if not lmp:
        sys.exit("no LAMMPS executable 'lmp' on PATH; apt-get install lammps")
    if not example.exists():
        sys.exit("%s missing; apt-get install lammps-examples" % example)
    shipped = example.read_text()
    digest = hashlib.sha256(shipped.encode()).hexdigest()
    if example_sha256 and digest != example_sha256:
        sys.exit("%s differs from the example this reference was made from" % example)
    lines = shipped.splitlines()
    run = [k for k, l in enumerate(lines) if l.split()[:1] == ["run"]]
    if len(run) != 1:
        sys.exit("expected one 'run' command in %s" % example)
    deck = ("\n".join(lines[:run[0]]) + "\n" + ADDED.format(script=script)
            + "\n".join(lines[run[0]:]) + "\n")
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
    return out, digest, rows, log, wall


def main():
    out, digest, rows, _, _ = make_reference(__doc__, "make_lammps_disk_impact.py", "disk_impact",
                                             EXAMPLE, EXAMPLE_SHA256)
    f = [float(r.split(",")[5]) for r in rows[1:]]
    d = [int(r.split(",")[2]) for r in rows[1:]]
    peak = max(range(len(f)), key=lambda k: f[k])
    print("example sha256 %s" % digest)
    print("steps %d, peak indenter force %.6g N at step %d, damaged particles at steps 100, 150, "
          "200, 250, 1000: %s" % (len(f) - 1, f[peak], peak, [d[k] for k in (100, 150, 200, 250, 1000)]))
    print("wrote %s" % out)


if __name__ == "__main__":
    main()
