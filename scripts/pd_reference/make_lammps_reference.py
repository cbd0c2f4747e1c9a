#!/usr/bin/python3
"""Regenerate the LAMMPS reference for the PMB bond-based peridynamic model.

Run from anywhere, without arguments (``--out DIR`` writes into DIR instead of
reference/lammps):

    /usr/bin/python3 scripts/pd_reference/make_lammps_reference.py

Needs the LAMMPS executable ``lmp`` (Debian package ``lammps``, with the PERI
package) and numpy (Debian ``python3-numpy``).  All LAMMPS runs happen in a
temporary directory; the files listed below are overwritten.  Every number in
reference/lammps/README.md is taken from this script's printout.

Problem ``pmb_lattice``
-----------------------
* 10 x 10 x 10 simple-cubic lattice, spacing a = 0.0005 m, positions
  (i a, j a, k a), i, j, k = 0..9; id = 1 + i + 10 j + 100 k (x fastest).
  Volume per particle a^3 = 1.25e-10 m^3, density 2200 kg/m^3.
* Material as the LAMMPS example examples/peri/in.peri.pmb:
  pair_coeff * * c delta s00 alpha = 1.6863e22 0.0015001 0.0005 0.25.
  The ``lattice sc 0.0005`` command is part of the model: peri/pmb takes its
  lattice constant (partial-volume factor, contact distance) from it.
* Free body (no boundary conditions), non-periodic fixed box with a margin
  of 5 a on every side.  Initial velocity
      v_x = 0.2 m/s * sin(pi x / L),  v_y = 0.1 m/s * sin(pi z / L),  v_z = 0
  with L = 9 a = 0.0045 m (extent of the lattice, first to last particle).
* dt = 1e-8 s, 400 steps (fix nve = velocity Verlet), units si.

Checks (printed)
----------------
* rmass read back from LAMMPS equals the density; LAMMPS' bond count equals
  the count of lattice pairs with r0^2 <= delta^2.
* Largest |stretch| over all bonds and all 400 steps (from positions dumped
  every step) compared with s00; smallest r / d_ij over all pairs of the
  contact neighbour list (contact acts only where r < d_ij).
* compute damage/atom: its maximum over all particles, written every step,
  stays 0.  A second run with s00 = 1 (no bond can break) must give
  bit-identical positions.
* Stable step: the Silling-Askari bound and the exact bound 2/omega_max of
  the linearised lattice (eigenvalues of the 3000 x 3000 stiffness matrix).
* An independent numpy re-implementation of the conventions written in
  reference/lammps/README.md must reproduce the LAMMPS displacements.
* Sensitivity: the same run with the partial-volume factor switched off
  (``lattice sc 1e-9`` makes vfrac_scale = 1 for every bond).
* Time discretisation: the same run at dt/2 (800 steps) and dt/4 (1600
  steps); differences at common times relative to max |u|.

Benchmark
---------
The same material and velocity field on 10^3 (the reference lattice), 20^3,
30^3 and 40^3 lattices for 200 steps; pair and total (loop) times from the
LAMMPS log, the bond count (sum of partner counts, i.e. each bond counted
from both ends, as LAMMPS evaluates it) and bond updates per second =
bonds * steps / pair time.  Serial runs, 2 OpenMP threads when LAMMPS has
the OPENMP package, and 2 MPI ranks when mpirun is available.  Each
configuration runs --repeats times (default 3) and the fastest pair time is
kept.  A run that shared the machine is repeated (at most 4 such reruns per
configuration): LAMMPS' "% CPU use" below 95 %, or other processes using
more than 0.1 core on average during the run (machine busy time from
/proc/stat minus the CPU time of the LAMMPS processes).

Output (reference/lammps/)
------
pmb_lattice/particles.csv      id,x,y,z,volume,vx,vy,vz (initial state)
pmb_lattice/displacements.csv  step,time,id,ux,uy,uz every --every steps
                               (default 40) from step 0 to 400, %.15e
                               (about 1 MB; --every 20 doubles it)
pmb_lattice/data.pmb_lattice   LAMMPS data file read by the deck
pmb_lattice/lammps.in          the LAMMPS deck of the reference run (it dumps
                               every step: dump.traj is about 89 MB)
pmb_lattice/log.lammps         its log (thermo every 20 steps; per-rank
                               histograms and the wall-clock line removed)
benchmark.csv                  particles,bonds,steps,threads,pair_seconds,
                               total_seconds,bond_updates_per_second,mpi_ranks
"""

import argparse
import math
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]

# material and lattice (SI units)
A = 0.0005                # lattice constant [m]
A_STR = "0.0005"
VOLUME_STR = "1.25e-10"   # a^3 [m^3]
C_STR = "1.6863e22"       # micromodulus c [N/m^6]
DELTA_STR = "0.0015001"   # horizon [m]
S00_STR = "0.0005"
ALPHA_STR = "0.25"
RHO_STR = "2200"          # density [kg/m^3]
VX_AMP = 0.2              # [m/s]
VY_AMP = 0.1              # [m/s]
SKIN_STR = "0.0001"       # neighbour skin [m] (contact list only)
MARGIN_CELLS = 5          # box margin in lattice constants

N_REF = 10
DT = 1.0e-8
DT_STR = "1e-8"
NSTEPS = 400
THERMO_EVERY = 20

BENCH_SIZES = (10, 20, 30, 40)
BENCH_STEPS = 200
MIN_CPU_USE = 95.0        # LAMMPS '% CPU use' below this: the run shared its cores, rerun it
MAX_OTHERS = 0.10         # other processes using more cores than this on average: rerun
MAX_REJECTED = 4

C = float(C_STR)
DELTA = float(DELTA_STR)
S00 = float(S00_STR)
ALPHA = float(ALPHA_STR)
RHO = float(RHO_STR)
VOLUME = float(VOLUME_STR)


# --------------------------------------------------------------------------
# LAMMPS executable and its build
# --------------------------------------------------------------------------

def find_lmp():
    for name in ("lmp", "lmp_serial", "lmp_mpi", "lammps"):
        path = shutil.which(name)
        if path:
            return path
    sys.exit("no LAMMPS executable (lmp, lmp_serial, lmp_mpi) on PATH; "
             "install the Debian package 'lammps'")


def lammps_info(lmp):
    out = subprocess.run([lmp, "-h"], capture_output=True, text=True).stdout
    version = ""
    for line in out.splitlines():
        if line.startswith("Large-scale Atomic/Molecular"):
            version = line.split(" - ", 1)[1].strip()
            break
    m = re.search(r"Installed packages:\s*\n\s*\n(.*?)\n\s*\n", out, re.S)
    packages = m.group(1).split() if m else []
    compiler = ""
    for line in out.splitlines():
        if line.startswith("Compiler:") or line.startswith("MPI v"):
            compiler += line.strip() + "; "
    deb = ""
    try:
        owner = subprocess.run(["dpkg", "-S", os.path.realpath(lmp)],
                               capture_output=True, text=True).stdout
        pkg = owner.split(":")[0].strip() if owner else ""
        if pkg:
            ver = subprocess.run(["dpkg-query", "-W", "-f", "${Version}", pkg],
                                 capture_output=True, text=True).stdout
            deb = "%s %s" % (pkg, ver)
    except OSError:
        pass
    return {"version": version, "packages": packages,
            "build": compiler.strip("; "), "debian": deb,
            "openmp": "OPENMP" in packages or "USER-OMP" in packages}


def machine_info():
    model = ""
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    nproc = subprocess.run(["nproc"], capture_output=True, text=True).stdout.strip()
    return nproc, model


# --------------------------------------------------------------------------
# lattice, data file, deck
# --------------------------------------------------------------------------

def coord_str(i):
    # exact decimal text of i*a; LAMMPS and any reader get the same double
    return "%.4f" % (i * A)


def make_lattice(n):
    """ids, coordinate strings, float positions, velocity strings (x fastest)."""
    ext_str = coord_str(n - 1)
    ext = float(ext_str)
    ids, pos_s, pos, vel_s = [], [], [], []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                xs, ys, zs = coord_str(i), coord_str(j), coord_str(k)
                x, y, z = float(xs), float(ys), float(zs)
                vx = VX_AMP * math.sin(math.pi * x / ext)
                vy = VY_AMP * math.sin(math.pi * z / ext)
                ids.append(len(ids) + 1)
                pos_s.append((xs, ys, zs))
                pos.append((x, y, z))
                vel_s.append((repr(vx), repr(vy), "0.0"))
    return {"n": n, "L": ext, "L_str": ext_str, "ids": np.array(ids),
            "pos_s": pos_s, "pos": np.array(pos), "vel_s": vel_s,
            "vel": np.array([[float(v) for v in t] for t in vel_s])}


def write_data(path, lat, model="PMB", dims=None):
    """The LAMMPS data file of a lattice (ids, coordinate and velocity strings as make_lattice
    gives them) with spacing A, box margin MARGIN_CELLS, VOLUME_STR and RHO_STR: this
    module's n^3 block, or `model`'s nx x ny x nz block with dims = (nx, ny, nz)."""
    dims = dims or (lat["n"],) * 3
    with open(path, "w") as fh:
        fh.write("LAMMPS data file: %s reference, %dx%dx%d simple-cubic lattice, a = %s m\n\n"
                 % ((model,) + tuple(dims) + (A_STR,)))
        fh.write("%d atoms\n1 atom types\n\n" % len(lat["ids"]))
        for ax, n in zip("xyz", dims):
            fh.write("%.4f %.4f %slo %shi\n" % (-MARGIN_CELLS * A, (n - 1 + MARGIN_CELLS) * A, ax, ax))
        fh.write("\nAtoms # peri\n\n")
        for idx, (xs, ys, zs) in zip(lat["ids"], lat["pos_s"]):
            fh.write("%d 1 %s %s %s %s %s\n" % (idx, VOLUME_STR, RHO_STR, xs, ys, zs))
        fh.write("\nVelocities\n\n")
        for idx, (vx, vy, vz) in zip(lat["ids"], lat["vel_s"]):
            fh.write("%d %s %s %s\n" % (idx, vx, vy, vz))


# the dump of rmass (atom_style peri: the density), written at step 0 only
MASS_DUMP = ["dump            m all custom 100000000 dump.mass id mass",
             "dump_modify     m sort id format float %.17g"]


def deck_start(title, model, style, coeff_names, coeffs, datafile, lattice_str):
    """The first lines of a deck on a free lattice, up to the damage computes: `model` names
    the model ("PMB bond-based"), `style` its pair style ("peri/pmb"), `coeffs` the values
    after "pair_coeff * *" and `coeff_names` their comment."""
    return [
        "# %s" % title,
        "# %s peridynamics (pair_style %s), free body, units si" % (model, style),
        "units           si",
        "dimension       3",
        "boundary        f f f",
        "atom_style      peri",
        "atom_modify     map array",
        "# %s takes its lattice constant lc from this command" % style,
        "# (vfrac_scale near the horizon, contact distance 1.35 lc)",
        "lattice         sc %s" % lattice_str,
        "read_data       %s" % datafile,
        "",
        "# %s" % coeff_names,
        "pair_style      %s" % style,
        "pair_coeff      * * %s" % " ".join(coeffs),
        "neighbor        %s bin" % SKIN_STR,
        "neigh_modify    every 1 delay 0 check yes",
        "",
        "compute         dmg all damage/atom",
        "compute         dmax all reduce max c_dmg",
    ]


def deck_end(nsteps, thermo_every, dump_every=None, dump_extra="", thermo_extra=""):
    """The last lines of a deck: with dump_every the trajectory dump.traj (id, x, u = c_u,
    v and `dump_extra`), then thermo (step time ke pe c_dmax and `thermo_extra`) and the run."""
    lines = []
    if dump_every is not None:
        lines += [
            "dump            d all custom %d dump.traj id x y z c_u[1] c_u[2] c_u[3] vx vy vz%s"
            % (dump_every, dump_extra),
            "dump_modify     d sort id format float %.17e",
        ]
    return lines + [
        "thermo_style    custom step time ke pe c_dmax%s" % thermo_extra,
        "thermo_modify   format float %.10e",
        "thermo          %d" % thermo_every,
        "run             %d" % nsteps,
        "",
    ]


def deck(datafile, dt_str, nsteps, s00_str, dump_every, thermo_every, title,
         damage_file=True, mass_dump=True, bench=False, lattice_str=A_STR):
    lines = deck_start(title, "PMB bond-based", "peri/pmb", "c [N/m^6], delta [m], s00, alpha",
                       (C_STR, DELTA_STR, s00_str, ALPHA_STR), datafile, lattice_str)
    lines += [
        "fix             1 all nve",
        "timestep        %s" % dt_str,
    ]
    if not bench:
        lines += [
            "compute         u all displace/atom",
        ]
        if damage_file:
            lines.append("fix             dmax all ave/time 1 1 1 c_dmax file damage_max.txt")
        if mass_dump:
            lines += MASS_DUMP
    return "\n".join(lines + deck_end(nsteps, thermo_every, None if bench else dump_every))


def busy_seconds():
    """CPU seconds spent by everything on the machine (all cores, incl. steal)."""
    with open("/proc/stat") as fh:
        vals = [int(v) for v in fh.readline().split()[1:9]]
    user, nice, system, idle, iowait, irq, softirq, steal = vals
    return (user + nice + system + irq + softirq + steal) / os.sysconf("SC_CLK_TCK")


def children_seconds():
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def run_lmp(lmp, workdir, deckname, prefix=(), env=None, extra=(), stats=None):
    """Run LAMMPS; with a dict `stats`, store there the average number of cores
    used by other processes during the run (machine busy time minus our own)."""
    cmd = list(prefix) + [lmp, "-in", deckname, "-log", deckname + ".log",
                          "-screen", "none", "-nocite"] + list(extra)
    b0, c0, t0 = busy_seconds(), children_seconds(), time.time()
    res = subprocess.run(cmd, cwd=workdir, capture_output=True, text=True, env=env)
    wall = time.time() - t0
    if stats is not None:
        stats["others"] = max(0.0, (busy_seconds() - b0) - (children_seconds() - c0)) / wall
    log = (Path(workdir) / (deckname + ".log"))
    text = log.read_text() if log.exists() else ""
    if res.returncode != 0 or "Loop time" not in text:
        sys.stderr.write(res.stdout[-3000:] + res.stderr[-3000:] + text[-3000:])
        sys.exit("LAMMPS run %s failed (rc %d)" % (deckname, res.returncode))
    return text, wall


# --------------------------------------------------------------------------
# parsing
# --------------------------------------------------------------------------

def read_dump(path, ncols):
    """{step: array (natoms, ncols)} of a sorted custom dump."""
    frames = {}
    text = Path(path).read_text()
    for chunk in text.split("ITEM: TIMESTEP\n")[1:]:
        head, body = chunk.split("\n", 1)
        step = int(head)
        body = body.split("ITEM: ATOMS", 1)[1].split("\n", 1)[1]
        frames[step] = np.array(body.split(), dtype=float).reshape(-1, ncols)
    return frames


def parse_log(text):
    out = {}
    m = re.search(r"total # of bonds = (\d+)", text)
    out["bonds"] = int(m.group(1)) if m else None
    m = re.search(r"Loop time of ([\d.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms", text)
    out["loop"] = float(m.group(1))
    out["procs"] = int(m.group(2))
    out["steps"] = int(m.group(3))
    out["atoms"] = int(m.group(4))
    m = re.search(r"^(\d+\.?\d*)% CPU use with (\d+) MPI tasks x (\d+) OpenMP threads", text, re.M)
    out["threads"] = int(m.group(3)) if m else 1
    out["cpu_use"] = float(m.group(1)) if m else float("nan")
    for sec in ("Pair", "Neigh", "Comm", "Output", "Modify", "Other"):
        m = re.search(r"^%s\s*\|\s*([\d.eE+-]+)\s*\|\s*([\d.eE+-]+)\s*\|\s*([\d.eE+-]+)" % sec,
                      text, re.M)
        if m:
            out[sec.lower()] = float(m.group(2))       # average over ranks
            out[sec.lower() + "_max"] = float(m.group(3))
        else:
            m = re.search(r"^%s\s*\|\s*([\d.eE+-]+)\s*\|" % sec, text, re.M)
            if m:
                out[sec.lower()] = out[sec.lower() + "_max"] = float(m.group(1))
    m = re.search(r"Total # of neighbors = (\d+)", text)
    out["neighbors"] = int(m.group(1)) if m else None
    return out


def trim_log(text):
    """Keep commands, bond statistics, thermo and timing; drop the per-rank
    histograms, the OpenMP default-thread notice and the wall-clock line."""
    drop = ("Histogram:", "OMP_NUM_THREADS environment", "  using 1 OpenMP thread",
            "Total wall time")
    keep = [l for l in text.splitlines() if not l.startswith(drop)]
    return "\n".join(keep) + "\n"


# --------------------------------------------------------------------------
# bonds on the lattice
# --------------------------------------------------------------------------

def lattice_offsets():
    """Integer offsets (di,dj,dk) of the bond family (r0^2 <= delta^2 on the lattice)."""
    m = int(math.ceil(DELTA / A)) + 1
    offs = []
    for di in range(-m, m + 1):
        for dj in range(-m, m + 1):
            for dk in range(-m, m + 1):
                if (di, dj, dk) == (0, 0, 0):
                    continue
                dx, dy, dz = di * A, dj * A, dk * A
                if dx * dx + dy * dy + dz * dz <= DELTA * DELTA:
                    offs.append((di, dj, dk))
    return offs


def bond_count(n, offs):
    """Sum over particles of the partner count on an n^3 block."""
    return sum((n - abs(a)) * (n - abs(b)) * (n - abs(c)) for a, b, c in offs)


def pairs_within(pos, rmax):
    """Unique pairs (i<j) with |x_i - x_j| <= rmax (squared distances as LAMMPS forms them)."""
    d = pos[None, :, :] - pos[:, None, :]
    rsq = d[:, :, 0] * d[:, :, 0] + d[:, :, 1] * d[:, :, 1] + d[:, :, 2] * d[:, :, 2]
    i, j = np.nonzero(np.triu(rsq <= rmax * rmax, k=1))
    return i, j, np.sqrt(rsq[i, j])


def vfrac_scale(r0, lc, delta=DELTA):
    half = 0.5 * lc
    s = (-1.0 / (2 * half)) * r0 + (1.0 + (delta - half) / (2 * half))
    return np.where(np.abs(r0 - delta) <= half, s, 1.0)


# --------------------------------------------------------------------------
# stable time step
# --------------------------------------------------------------------------

def stable_steps(pos, bi, bj, r0):
    scale = vfrac_scale(r0, A)
    k = C * VOLUME * scale / r0                  # bond stiffness per unit volume / length
    n = len(pos)
    # Silling-Askari: dt < sqrt(2 rho / sum_j c V_j scale / |xi|)
    ssum = np.zeros(n)
    np.add.at(ssum, bi, k)
    np.add.at(ssum, bj, k)
    dt_sa = math.sqrt(2.0 * RHO / ssum.max())
    # linearised lattice: rho u_i'' = sum_j k e e^T (u_j - u_i)
    e = (pos[bj] - pos[bi]) / r0[:, None]
    blocks = k[:, None, None] * e[:, :, None] * e[:, None, :]
    K = np.zeros((3 * n, 3 * n))
    for a in range(3):
        for b in range(3):
            v = blocks[:, a, b]
            np.add.at(K, (3 * bi + a, 3 * bj + b), -v)
            np.add.at(K, (3 * bj + a, 3 * bi + b), -v)
            np.add.at(K, (3 * bi + a, 3 * bi + b), v)
            np.add.at(K, (3 * bj + a, 3 * bj + b), v)
    lam = np.linalg.eigvalsh(K / RHO)
    omega_max = math.sqrt(lam[-1])
    return dt_sa, 2.0 / omega_max, lam


# --------------------------------------------------------------------------
# independent re-implementation of the documented LAMMPS conventions
# --------------------------------------------------------------------------

def numpy_pmb(pos0, vel0, bi, bj, r0, nsteps, dt, near_zero=2.2204e-16):
    """PMB as documented in reference/lammps/README.md (no breaking, no contact):
    f_i = sum_j c V_j beta(r0) s (x_j - x_i)/r, s = (r - r0)/r0, a = f/rho;
    f = 0 before the first step; velocity Verlet (half kick, drift, force,
    half kick).  Returns {step: displacement array}."""
    i = np.concatenate([bi, bj])
    j = np.concatenate([bj, bi])
    rr0 = np.concatenate([r0, r0])
    kb = C * VOLUME * vfrac_scale(rr0, A)
    n = len(pos0)
    x = pos0.copy()
    v = vel0.copy()

    def force(x):
        d = x[j] - x[i]
        r = np.sqrt((d * d).sum(axis=1))
        dr = r - rr0
        dr[np.abs(dr) < near_zero] = 0.0
        w = kb * (dr / rr0) / r
        return np.stack([np.bincount(i, weights=w * d[:, a], minlength=n) for a in range(3)], axis=1)

    f = np.zeros_like(x)
    hist = {0: x - pos0}
    for step in range(1, nsteps + 1):
        v += 0.5 * dt * f / RHO
        x += dt * v
        f = force(x)
        v += 0.5 * dt * f / RHO
        hist[step] = x - pos0
    return hist


# --------------------------------------------------------------------------
# the steps of a reference recipe (also make_lammps_lps_reference.py's)
# --------------------------------------------------------------------------

def parse_case_args(doc, case, every, nsteps, extra=()):
    """Arguments --out and --every (default `every`, dividing `nsteps`) and the `extra` ones,
    (flag, add_argument keywords) each; returns them and the folder --out/<case>, made."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--out", default=str(REPO / "reference" / "lammps"),
                    help="output directory (default reference/lammps)")
    ap.add_argument("--every", type=int, default=every,
                    help="steps between frames in displacements.csv (default %d)" % every)
    for flag, kw in extra:
        ap.add_argument(flag, **kw)
    args = ap.parse_args()
    if nsteps % args.every:
        sys.exit("--every must divide %d" % nsteps)
    case_dir = Path(args.out) / case
    case_dir.mkdir(parents=True, exist_ok=True)
    return args, case_dir


def report_lammps(details=False):
    """Find lmp and print what it is and the machine (with `details` also its build and its
    packages); stop if it has no PERI package.  Returns (lmp, lammps_info(lmp))."""
    lmp = find_lmp()
    info = lammps_info(lmp)
    nproc, cpu = machine_info()
    print("LAMMPS executable : %s" % lmp)
    print("LAMMPS version    : %s" % info["version"])
    print("Debian package    : %s" % info["debian"])
    if details:
        print("build             : %s" % info["build"])
        print("installed packages: %s" % " ".join(info["packages"]))
    have_peri = "PERI" in info["packages"]
    print("PERI package      : %s" % ("yes" if have_peri else "NO"))
    if details:
        print("OPENMP package    : %s" % ("yes" if info["openmp"] else "no"))
    print("machine           : nproc = %s, CPU = %s" % (nproc, cpu))
    if not have_peri:
        sys.exit("LAMMPS without the PERI package")
    return lmp, info


def reference_run(lmp, tmp, text, ncol, nsteps, bonds, source, rho_str):
    """Run the reference deck `text` (tmp/ref.in, dumping every step); check its steps, its
    bond count against `bonds` (named `source` in the printout) and its rmass against the
    density rho_str.  Returns (log, {step: dump frame with ncol columns}, steps)."""
    (tmp / "ref.in").write_text(text)
    t0 = time.time()
    log, _ = run_lmp(lmp, tmp, "ref.in")
    print("\nreference run: %.1f s" % (time.time() - t0))
    ref = read_dump(tmp / "dump.traj", ncol)
    steps = sorted(ref)
    if steps != list(range(nsteps + 1)):
        sys.exit("unexpected dump steps")
    lp = parse_log(log)
    print("LAMMPS bonds (sum of partner counts) = %d; %s %d" % (lp["bonds"], source, bonds))
    if lp["bonds"] != bonds:
        sys.exit("bond count mismatch")
    mass = read_dump(tmp / "dump.mass", 2)[0]
    print("rmass read back: min %.17g max %.17g (density %s)"
          % (mass[:, 1].min(), mass[:, 1].max(), rho_str))
    return log, ref, steps


def check_frames(ref, ids, pos0, delta, lc):
    """Check every frame of a reference dump (columns id x y z u v ...): ids in order, compute
    displace/atom equal to x - x0.  Returns the largest |u| and its step, the largest
    |u - mean u|, and the size of the contact list (pairs within delta + skin) and the
    smallest r / d_ij over it and over all frames (contact acts only below 1)."""
    ci, cj, cr0 = pairs_within(pos0, delta + float(SKIN_STR))
    dij = np.minimum(0.9 * cr0, 1.35 * lc)
    umax, umax_step, udef, contact_min = 0.0, 0, 0.0, np.inf
    for s in sorted(ref):
        fr = ref[s]
        if not np.array_equal(fr[:, 0], ids):
            sys.exit("ids out of order in dump")
        x, u = fr[:, 1:4], fr[:, 4:7]
        if np.abs(u - (x - pos0)).max() > 1e-18:
            sys.exit("compute displace/atom differs from x - x0")
        un = np.linalg.norm(u, axis=1).max()
        if un > umax:
            umax, umax_step = un, s
        udef = max(udef, np.linalg.norm(u - u.mean(axis=0), axis=1).max())
        dc = x[cj] - x[ci]
        rc = np.sqrt((dc * dc).sum(axis=1))
        contact_min = min(contact_min, (rc / dij).min())
    return umax, umax_step, udef, len(ci), contact_min


def check_contact(npairs, contact_min):
    print("contact: %d pairs in the contact list; min over steps of r/d_ij = %.6f (contact acts only below 1)"
          % (npairs, contact_min))
    if contact_min <= 1.0:
        sys.exit("the short-range contact force acted")


def run_displacements(lmp, tmp, name, text, ncol):
    """Run the deck `text` (tmp/<name>.in); {step: displacements} of its dump.traj."""
    (tmp / (name + ".in")).write_text(text)
    run_lmp(lmp, tmp, name + ".in")
    return {s: fr[:, 4:7] for s, fr in read_dump(tmp / "dump.traj", ncol).items()}


def max_difference(ref, frames):
    """Largest |u - u_ref| over the steps of `frames` ({step: displacements}) and particles."""
    return max(np.linalg.norm(ref[s][:, 4:7] - frames[s], axis=1).max() for s in frames)


def no_partial_volume(lmp, tmp, text, ncol, ref, umax):
    """Run `text`, the reference deck with lattice sc 1e-9, and print how far it moves."""
    e_nob = max_difference(ref, run_displacements(lmp, tmp, "nobeta", text, ncol))
    print("sensitivity: the same run with vfrac_scale = 1 for every bond (lattice sc 1e-9) differs by"
          " %.4e m = %.4e of max |u|" % (e_nob, e_nob / umax))


def refine_dt(lmp, tmp, deck_for, ncol, ref):
    """The reference run at dt/2 and dt/4 (deck_for(div) gives the deck at dt/div).  Returns
    the common steps (of dt), the largest |u(dt) - u(dt/2)| and |u(dt/2) - u(dt/4)| over them
    and {div: {step of dt: displacements}}."""
    fine = {}
    for div in (2, 4):
        fr = run_displacements(lmp, tmp, "dt%d" % div, deck_for(div), ncol)
        fine[div] = {s // div: u for s, u in fr.items()}
    common = sorted(fine[2])
    e12 = max_difference(ref, fine[2])
    e24 = max(np.linalg.norm(fine[2][s] - fine[4][s], axis=1).max() for s in common)
    return common, e12, e24, fine


def write_case(case_dir, data, text, log, lat, ref, every, dt):
    """The reference files: the data file `data`, lammps.in (`text`), log.lammps (`log`),
    particles.csv (the initial state of `lat`) and displacements.csv (every `every` steps of
    the dump frames `ref`, time = step * dt); prints their sizes."""
    shutil.copy(data, case_dir / data.name)
    (case_dir / "lammps.in").write_text(text)
    (case_dir / "log.lammps").write_text(log)
    with open(case_dir / "particles.csv", "w") as fh:
        fh.write("id,x,y,z,volume,vx,vy,vz\n")
        for idx, (xs, ys, zs), (vx, vy, vz) in zip(lat["ids"], lat["pos_s"], lat["vel_s"]):
            fh.write("%d,%s,%s,%s,%s,%s,%s,%s\n" % (idx, xs, ys, zs, VOLUME_STR, vx, vy, vz))
    with open(case_dir / "displacements.csv", "w") as fh:
        fh.write("step,time,id,ux,uy,uz\n")
        for s in range(0, max(ref) + 1, every):
            tstr = "%.15e" % (s * dt)
            for row in ref[s]:
                fh.write("%d,%s,%d,%.15e,%.15e,%.15e\n" % (s, tstr, int(row[0]), row[4], row[5], row[6]))
    sizes = {p.name: p.stat().st_size for p in case_dir.iterdir()}
    print("written %s: %s" % (case_dir, ", ".join("%s %d B" % kv for kv in sorted(sizes.items()))))


# --------------------------------------------------------------------------
# main
# --------------------------------------------------------------------------

def main():
    args, case_dir = parse_case_args(
        __doc__, "pmb_lattice", 40, NSTEPS,
        [("--no-benchmark", dict(action="store_true", help="skip the benchmark")),
         ("--repeats", dict(type=int, default=3,
                            help="runs per benchmark configuration; the fastest is kept (default 3)"))])
    out = case_dir.parent

    t_start = time.time()
    lmp, info = report_lammps(details=True)
    have_omp = info["openmp"]

    lat = make_lattice(N_REF)
    pos0 = lat["pos"]
    natoms = len(pos0)
    L = lat["L"]
    print("\n== pmb_lattice ==")
    print("particles %d (%d^3), a = %s m, L = %s m, volume %s m^3, density %s kg/m^3"
          % (natoms, N_REF, A_STR, lat["L_str"], VOLUME_STR, RHO_STR))
    print("pair_coeff c = %s, delta = %s, s00 = %s, alpha = %s" % (C_STR, DELTA_STR, S00_STR, ALPHA_STR))
    print("v_x = %g m/s sin(pi x/L), v_y = %g m/s sin(pi z/L), v_z = 0; max |v| = %.6g m/s"
          % (VX_AMP, VY_AMP, np.linalg.norm(lat["vel"], axis=1).max()))

    # bond family on the reference lattice
    offs = lattice_offsets()
    bi, bj, r0 = pairs_within(pos0, DELTA)
    nb_expected = bond_count(N_REF, offs)
    print("bond family: %d offsets per interior particle; unique bonds %d; sum of partner counts %d"
          % (len(offs), len(bi), 2 * len(bi)))
    if 2 * len(bi) != nb_expected:
        sys.exit("bond count from positions differs from the lattice count %d" % nb_expected)
    shells = {}
    for di, dj, dk in offs:
        n2 = di * di + dj * dj + dk * dk
        shells[n2] = shells.get(n2, 0) + 1
    print("shells (r0/a)^2 : count, r0 [m], vfrac_scale (lc = %s)" % A_STR)
    for n2 in sorted(shells):
        rr = math.sqrt(n2) * A
        print("  %2d : %2d  %.10f  %.10f" % (n2, shells[n2], rr, float(vfrac_scale(np.array([rr]), A)[0])))

    dt_sa, dt_lin, lam = stable_steps(pos0, bi, bj, r0)
    print("stable step: Silling-Askari %.4e s (dt/dt_c = %.4f, factor %.2f below);"
          % (dt_sa, DT / dt_sa, dt_sa / DT))
    print("             linearised lattice 2/omega_max = %.4e s (omega_max = %.4e rad/s; dt/dt_c = %.4f, factor %.2f below)"
          % (dt_lin, math.sqrt(lam[-1]), DT / dt_lin, dt_lin / DT))
    print("             rigid-body modes: %d eigenvalues below 1e-6 * max" % int(np.sum(lam < 1e-6 * lam[-1])))

    with tempfile.TemporaryDirectory(prefix="lammps_pmb_") as tmp:
        tmp = Path(tmp)
        write_data(tmp / "data.pmb_lattice", lat)
        title = "pmb_lattice: %d^3 simple-cubic lattice, a = %s m" % (N_REF, A_STR)

        # --- reference run (positions dumped every step) ---
        ref_deck = deck("data.pmb_lattice", DT_STR, NSTEPS, S00_STR, 1, THERMO_EVERY, title)
        ref_log, ref, steps = reference_run(lmp, tmp, ref_deck, 10, NSTEPS, nb_expected, "expected",
                                            RHO_STR)

        # --- damage ---
        dmg = np.loadtxt(tmp / "damage_max.txt", comments="#")
        print("damage/atom: max over particles written at %d steps (%d..%d); largest value %.3g"
              % (len(dmg), int(dmg[0, 0]), int(dmg[-1, 0]), dmg[:, 1].max()))
        if dmg[:, 1].max() != 0.0:
            sys.exit("a bond broke in the reference run")

        # --- displacement, stretch and contact ---
        umax, umax_step, udef, ncontact, contact_min = check_frames(ref, lat["ids"], pos0, DELTA, A)
        smax, smin, smax_step = -1.0, 1.0, 0
        for s in steps:
            x = ref[s][:, 1:4]
            d = x[bj] - x[bi]
            r = np.sqrt((d * d).sum(axis=1))
            st = (r - r0) / r0
            if st.max() > smax:
                smax, smax_step = st.max(), s
            smin = min(smin, st.min())
        ufin = ref[NSTEPS][:, 4:7]
        print("largest |u| over all steps = %.6e m (step %d); at step %d: max |u| = %.6e m, "
              "max |ux|, |uy|, |uz| = %.6e %.6e %.6e m"
              % (umax, umax_step, NSTEPS, np.linalg.norm(ufin, axis=1).max(),
                 np.abs(ufin[:, 0]).max(), np.abs(ufin[:, 1]).max(), np.abs(ufin[:, 2]).max()))
        drift = ufin.mean(axis=0)
        print("rigid translation (mean u) at step %d: %.6e %.6e %.6e m; mean(v0) * t = %.6e %.6e %.6e m"
              % ((NSTEPS,) + tuple(drift) + tuple(lat["vel"].mean(axis=0) * NSTEPS * DT)))
        print("largest |u - mean u| over all steps (deformation without the translation) = %.6e m = %.4f of max |u|"
              % (udef, udef / umax))
        print("bond stretch over all steps: max %.6e (step %d), min %.6e; max |s| / s00 = %.4f"
              % (smax, smax_step, smin, max(smax, -smin) / S00))
        print("breaking needs s > s00 - alpha*min_j s_ij >= %.6e at every step, i.e. %.2f x the largest stretch"
              % (S00 - ALPHA * max(smax, 0.0), (S00 - ALPHA * max(smax, 0.0)) / smax))
        check_contact(ncontact, contact_min)
        th = [l for l in ref_log.splitlines() if re.match(r"^\s+\d+\s+[\d.]+e", l)]
        if th:
            first, last = th[0].split(), th[-1].split()
            # thermo ke = sum_i rho v_i^2 / 2, pe = sum_i W_i, W_i = 1/4 sum_j c beta s^2 r0 V_j
            # (energy densities summed over particles, J/m^3; times a^3 for joules)
            x, vv = ref[NSTEPS][:, 1:4], ref[NSTEPS][:, 7:10]
            d = x[bj] - x[bi]
            st = (np.sqrt((d * d).sum(axis=1)) - r0) / r0
            pe = 2 * (0.25 * C * vfrac_scale(r0, A) * st * st * r0 * VOLUME).sum()
            ke = 0.5 * RHO * (vv * vv).sum()
            print("energies at step %d from the dumped state: ke %.10e, pe %.10e; thermo: ke %s, pe %s"
                  % (NSTEPS, ke, pe, last[2], last[3]))
            print("thermo: step %s ke %s pe %s; step %s ke %s pe %s; ke+pe change %.3e relative"
                  % (first[0], first[2], first[3], last[0], last[2], last[3],
                     (float(last[2]) + float(last[3]) - float(first[2]) - float(first[3]))
                     / (float(first[2]) + float(first[3]))))

        # --- independent check of the conventions ---
        t0 = time.time()
        hist = numpy_pmb(pos0, lat["vel"], bi, bj, r0, NSTEPS, DT)
        e_np = max(np.linalg.norm(hist[s] - ref[s][:, 4:7], axis=1).max() for s in steps)
        print("numpy re-implementation of the documented conventions (%.1f s): max |u_numpy - u_LAMMPS|"
              " over all steps = %.4e m = %.4e of max |u|" % (time.time() - t0, e_np, e_np / umax))

        hist0 = numpy_pmb(pos0, lat["vel"], bi, bj, r0, NSTEPS, DT, near_zero=0.0)
        e_nz = max(np.linalg.norm(hist[s] - hist0[s], axis=1).max() for s in steps)
        print("numpy without LAMMPS' |dr| < 2.2204e-16 m cut-off differs from it by %.4e m = %.4e of max |u|"
              % (e_nz, e_nz / umax))

        # --- same run with s00 = 1: nothing can break, must be bit-identical ---
        big = deck("data.pmb_lattice", DT_STR, NSTEPS, "1.0", 1, THERMO_EVERY,
                   title + " (s00 = 1)", damage_file=False, mass_dump=False)
        (tmp / "big.in").write_text(big)
        run_lmp(lmp, tmp, "big.in")
        bigd = read_dump(tmp / "dump.traj", 10)
        same = all(np.array_equal(bigd[s], ref[s]) for s in steps)
        print("run with s00 = 1.0: positions, displacements and velocities bit-identical at all %d steps: %s"
              % (len(steps), "yes" if same else "NO"))
        if not same:
            sys.exit("s00 = 1 run differs: a bond broke in the reference run")

        # --- sensitivity: no partial-volume factor (lc -> 1e-9 m makes vfrac_scale = 1) ---
        nob = deck("data.pmb_lattice", DT_STR, NSTEPS, S00_STR, THERMO_EVERY, THERMO_EVERY,
                   title + " (lattice sc 1e-9: vfrac_scale = 1)", damage_file=False,
                   mass_dump=False, lattice_str="1e-9")
        no_partial_volume(lmp, tmp, nob, 10, ref, umax)

        # --- time discretisation: dt/2 and dt/4 ---
        common, e12, e24, fine = refine_dt(
            lmp, tmp, lambda div: deck("data.pmb_lattice", repr(DT / div), NSTEPS * div, S00_STR,
                                       THERMO_EVERY * div, THERMO_EVERY * div, title + " (dt/%d)" % div,
                                       damage_file=False, mass_dump=False), 10, ref)
        e12_end = np.linalg.norm(ref[NSTEPS][:, 4:7] - fine[2][NSTEPS], axis=1).max()
        print("time step: max over %d common times (every %d dt) and particles of |u(dt) - u(dt/2)| = %.4e m"
              " = %.4e of max |u|" % (len(common), THERMO_EVERY, e12, e12 / umax))
        print("           at step %d: %.4e m = %.4e of max |u|" % (NSTEPS, e12_end, e12_end / umax))
        print("           |u(dt/2) - u(dt/4)| = %.4e m = %.4e of max |u|; ratio %.3f (4 for O(dt^2))"
              % (e24, e24 / umax, e12 / e24))

        # --- write the reference files ---
        write_case(case_dir, tmp / "data.pmb_lattice", ref_deck, trim_log(ref_log), lat, ref,
                   args.every, DT)

        if args.no_benchmark:
            print("\nbenchmark skipped; total %.0f s" % (time.time() - t_start))
            return

        # --- benchmark ---
        print("\n== benchmark (%d steps, dt = %s s, same material and velocity field) ==" % (BENCH_STEPS, DT_STR))
        mpirun = shutil.which("mpirun")
        mpi_prefix = None
        if mpirun:
            mpi_prefix = [mpirun, "-np", "2"]
            if os.geteuid() == 0:
                mpi_prefix.append("--allow-run-as-root")
        configs = [("serial", 1, 1, (), None, ())]
        if have_omp:
            env = dict(os.environ, OMP_NUM_THREADS="2")
            configs.append(("omp2", 2, 1, (), env, ("-sf", "omp", "-pk", "omp", "2")))
        else:
            print("OpenMP threads: not measured, this LAMMPS has no OPENMP package")
        if mpi_prefix:
            configs.append(("mpi2", 1, 2, mpi_prefix, None, ()))
        else:
            print("MPI ranks: not measured, no mpirun")
        rows = []
        print("each configuration is run %d times; the row is the run with the smallest pair time"
              % args.repeats)
        print("%9s %10s %6s %7s %5s %10s %10s %14s %8s  %s"
              % ("particles", "bonds", "steps", "threads", "ranks", "pair_s", "total_s", "bond_upd/s",
                 "maxdmg", "pair_s (LAMMPS CPU use/other cores busy) of the kept repeats"))
        for n in BENCH_SIZES:
            blat = make_lattice(n)
            dname = "data.bench%d" % n
            write_data(tmp / dname, blat)
            expected = bond_count(n, offs)
            for name, threads, ranks, prefix, env, extra in configs:
                bdeck = deck(dname, DT_STR, BENCH_STEPS, S00_STR, 0, BENCH_STEPS,
                             "benchmark %d^3" % n, bench=True)
                fname = "bench%d_%s.in" % (n, name)
                (tmp / fname).write_text(bdeck)
                runs, rejected = [], []
                while len(runs) < args.repeats and len(rejected) < MAX_REJECTED:
                    st = {}
                    text, _ = run_lmp(lmp, tmp, fname, prefix=prefix, env=env, extra=extra, stats=st)
                    p = parse_log(text)
                    p["others"] = st["others"]
                    if p["bonds"] != expected:
                        sys.exit("benchmark %d: LAMMPS bonds %s, expected %d" % (n, p["bonds"], expected))
                    th = [l for l in text.splitlines() if re.match(r"^\s+%d\s" % BENCH_STEPS, l)]
                    p["maxdmg"] = float(th[-1].split()[-1]) if th else float("nan")
                    # another process competing for the cores: LAMMPS CPU use < 100 %,
                    # or other processes' CPU time during the run
                    if p["cpu_use"] < MIN_CPU_USE or p["others"] > MAX_OTHERS:
                        rejected.append(p)
                        time.sleep(5)
                    else:
                        runs.append(p)
                if not runs:
                    print("  (no run of %d^3/%s on a quiet machine; keeping the best rejected one)"
                          % (n, name))
                    runs = rejected
                elif rejected:
                    print("  (%d^3/%s: %d run(s) sharing the cores discarded: %s)"
                          % (n, name, len(rejected),
                             " ".join("%.1f%%/%.2f" % (q["cpu_use"], q["others"]) for q in rejected)))
                p = min(runs, key=lambda q: q["pair"])
                rate = p["bonds"] * p["steps"] / p["pair"]
                rows.append((n ** 3, p["bonds"], p["steps"], p["threads"], p["pair"], p["loop"], rate, p["procs"]))
                print("%9d %10d %6d %7d %5d %10.4f %10.4f %14.4e %8.2g  %s"
                      % (n ** 3, p["bonds"], p["steps"], p["threads"], p["procs"], p["pair"], p["loop"], rate,
                         max(q["maxdmg"] for q in runs),
                         " ".join("%.4f (%.1f%%/%.2f)" % (q["pair"], q["cpu_use"], q["others"])
                                  for q in runs)))
        with open(out / "benchmark.csv", "w") as fh:
            fh.write("particles,bonds,steps,threads,pair_seconds,total_seconds,bond_updates_per_second,mpi_ranks\n")
            for r in rows:
                fh.write("%d,%d,%d,%d,%.4f,%.4f,%.4e,%d\n" % r)
        print("pair time = Pair row of the LAMMPS timing table (average over ranks); "
              "total = Loop time; bonds = LAMMPS 'total # of bonds'")
    print("\ntotal run time of this script: %.0f s" % (time.time() - t_start))


if __name__ == "__main__":
    main()
