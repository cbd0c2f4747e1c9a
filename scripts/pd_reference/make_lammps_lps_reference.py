#!/usr/bin/python3
"""Regenerate the LAMMPS reference for the state-based linear peridynamic solid (LPS).

Usage, from anywhere (``--out DIR`` writes into DIR instead of reference/lammps):

    /usr/bin/python3 scripts/pd_reference/make_lammps_lps_reference.py [--out DIR] [--every N] [--pulse P]

It needs what make_lammps_reference.py needs (LAMMPS ``lmp`` with the PERI package,
Debian ``lammps``; numpy, ``python3-numpy``) and imports from that script beside it
the generic helpers (finding lmp, running it, reading dumps and logs, the data file,
the deck's common lines), the steps the two recipes share (the reference run and its
checks, the sensitivity and time-step runs, writing the files) and with them its
lattice spacing, particle volume and density.  The LAMMPS runs happen in a temporary
directory; the files listed below are overwritten.  Every number in the "State-based
LPS" section of reference/lammps/README.md is taken from this script's printout.

Problem ``lps_lattice`` (a free bar hit at one end)
---------------------------------------------------
* 40 x 6 x 6 simple-cubic lattice, spacing a = 0.0005 m, positions
  (i a, j a, k a), i = 0..39, j, k = 0..5; id = 1 + i + 40 j + 240 k (x fastest).
  Volume per particle a^3 = 1.25e-10 m^3, density 2200 kg/m^3.
* pair_style peri/lps with K and G from E = 30 GPa, nu = 0.3:
  K = E / (3 (1 - 2 nu)), G = E / (2 (1 + nu)); delta = 0.0015001 m
  (3 a + 1e-7 m), s00 = 1.0 (nothing can break), alpha = 0.25.
  ``lattice sc 0.0005`` is part of the model (partial-volume factor, contact
  distance).
* Free body, non-periodic fixed box with a margin of 5 a on every side.
  Initial velocity: a smooth half-cosine pulse at the end x = 0,
      v_x = 0.5 m/s * cos^2(pi x / (2 w)) for x < w = 8 a = 0.004 m, else 0,
  v_y = v_z = 0 (``--pulse step`` instead gives v_x = 0.5 m/s on the
  particles with i < 4; the reference is made with the smooth pulse).
* dt = 1e-8 s, 600 steps (fix nve = velocity Verlet), units si.
* A ``run 0`` precedes the run: in this LAMMPS the first force evaluation
  (at the setup of the first run, before the bond family exists) stores an
  uninitialised s0 for every particle, so that every bond with a positive
  stretch would break in step 1 (see the README; the script shows it).

Checks (printed)
----------------
* LAMMPS' bond count equals the lattice count; rmass read back = density.
* compute damage/atom (max over particles) and s0 (min over particles) at
  every step; the same run with s00 = 0.5 gives a byte-identical trajectory;
  the same deck without ``run 0`` breaks bonds in step 1.
* Largest |stretch| over all bonds and steps; smallest r / d_ij over all pairs
  of the contact list at every step (contact acts only below 1).
* The weighted volume m_i and the dilatation theta_i: LAMMPS' theta
  (compute dilatation/atom) against numpy's theta of LAMMPS' positions.
* An independent numpy re-implementation of the conventions written in the
  README must reproduce the LAMMPS displacements at every step.
* Energies: thermo ke and pe against numpy from the dumped state; pe is
  LAMMPS' (half the deviatoric energy, see the README) and the consistent
  LPS energy; the drift of ke + pe for both.
* Stable step: the Silling-Askari-type bound of the linearised LPS operator
  (block Gershgorin), the exact 2/omega_max from its eigenvalues, and the
  Silling-Askari bound of the PMB with the same bulk modulus.
* Wave: P-wave and bar speeds against the arrival of the pulse at the far end.
* Sensitivity: without the partial-volume factor (``lattice sc 1e-9``), and
  numpy variants (no |dr| cut-off; m_i without the partial-volume factor).
* Time discretisation: the same run at dt/2 and dt/4.

Output (reference/lammps/lps_lattice/)
------
particles.csv      id,x,y,z,volume,vx,vy,vz (initial state; the strings of
                   the data file)
displacements.csv  step,time,id,ux,uy,uz every --every steps (default 50)
                   from step 0 to 600, %.15e (about 1.7 MB)
data.lps_lattice   LAMMPS data file read by the deck
lammps.in          the LAMMPS deck of the reference run (it dumps every step:
                   dump.traj is about 214 MB)
log.lammps         its log (thermo every 20 steps; the CPU and wall-clock times
                   removed, so that a second run gives the same file)
"""

import math
import re
import sys
import tempfile
import time
from fractions import Fraction
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent

sys.dont_write_bytecode = True     # no __pycache__ beside the scripts
sys.path.insert(0, str(HERE))
from make_lammps_reference import (  # noqa: E402  (the helpers and steps shared with PMB's recipe)
    MASS_DUMP, check_contact, check_frames, deck_end, deck_start, no_partial_volume, pairs_within,
    parse_case_args, read_dump, reference_run, refine_dt, report_lammps, run_lmp, vfrac_scale,
    write_case, write_data)
# lattice (SI units): spacing a, volume a^3 and density (atom_style peri: rmass holds it) of
# the PMB reference; its data file, deck and contact-list helpers use them
from make_lammps_reference import A, A_STR, VOLUME_STR, RHO_STR  # noqa: E402

NX, NY, NZ = 40, 6, 6

# material: K and G from E and nu, correctly rounded
E_FR = Fraction(30 * 10 ** 9)
NU_FR = Fraction(3, 10)
K = float(E_FR / (3 * (1 - 2 * NU_FR)))
G = float(E_FR / (2 * (1 + NU_FR)))
K_STR = "%.17g" % K
G_STR = "%.17g" % G
DELTA_STR = "0.0015001"
S00_STR = "1.0"
ALPHA_STR = "0.25"

# loading and time
V_AMP = 0.5                 # [m/s]
PULSE_CELLS = 8             # smooth pulse: half width w = 8 a
STEP_CELLS = 4              # --pulse step: particles with i < 4
DT = 1.0e-8
DT_STR = "1e-8"
NSTEPS = 600
THERMO_EVERY = 20
NEAR_ZERO = 2.2204e-16      # LAMMPS' |dr| cut-off

DELTA = float(DELTA_STR)
DELTA_FIX = math.sqrt(DELTA * DELTA)   # fix PERI_NEIGH uses sqrt(cutsq) for the horizon
S00 = float(S00_STR)
ALPHA = float(ALPHA_STR)
RHO = float(RHO_STR)
VOLUME = float(VOLUME_STR)
NCOL = 11                   # id x y z ux uy uz vx vy vz theta


# --------------------------------------------------------------------------
# lattice, data file, deck
# --------------------------------------------------------------------------

def coord_str(i):
    return "%.4f" % (i * A)


def make_lattice(pulse):
    ids, pos_s, pos, vel_s, idx = [], [], [], [], []
    w = float(coord_str(PULSE_CELLS))
    for k in range(NZ):
        for j in range(NY):
            for i in range(NX):
                xs, ys, zs = coord_str(i), coord_str(j), coord_str(k)
                x = float(xs)
                if pulse == "step":
                    vx = V_AMP if i < STEP_CELLS else 0.0
                else:
                    vx = V_AMP * math.cos(math.pi * x / (2.0 * w)) ** 2 if x < w else 0.0
                ids.append(len(ids) + 1)
                idx.append((i, j, k))
                pos_s.append((xs, ys, zs))
                pos.append((x, float(ys), float(zs)))
                vel_s.append((repr(vx), "0.0", "0.0"))
    return {"ids": np.array(ids), "idx": np.array(idx), "pos_s": pos_s, "pos": np.array(pos),
            "vel_s": vel_s, "vel": np.array([[float(v) for v in t] for t in vel_s]),
            "L": float(coord_str(NX - 1)), "L_str": coord_str(NX - 1)}


def deck(datafile, dt_str, nsteps, title, s00_str=S00_STR, dump_every=1, thermo_every=THERMO_EVERY,
         lattice_str=A_STR, guard=True, diag=True):
    lines = deck_start(title, "LPS state-based", "peri/lps",
                       "K [Pa], G [Pa], delta [m], s00, alpha  (E = 30e9 Pa, nu = 0.3)",
                       (K_STR, G_STR, DELTA_STR, s00_str, ALPHA_STR), datafile, lattice_str)
    lines += [
        "compute         dsum all reduce sum c_dmg",
        "compute         s0 all property/atom s0",
        "compute         s0min all reduce min c_s0",
        "compute         theta all dilatation/atom",
        "fix             1 all nve",
        "timestep        %s" % dt_str,
    ]
    if guard:
        lines += [
            "",
            "# the first force evaluation happens before the bond family exists and leaves",
            "# s0 uninitialised (0 in practice): without this 'run 0' every bond with a",
            "# positive stretch breaks in step 1.  The setup of the next run sets s0 = s00.",
            "thermo_style    custom step time ke pe c_dmax c_s0min",
            "run             0",
            "",
        ]
    lines += [
        "compute         u all displace/atom",
        "fix             dmax all ave/time 1 1 1 c_dmax c_dsum c_s0min file damage_s0.txt format \" %.17g\"",
    ]
    if diag:
        lines += MASS_DUMP
    return "\n".join(lines + deck_end(nsteps, thermo_every, dump_every, " c_theta", " c_s0min"))


def trim_log(text):
    """Drop what changes from run to run: CPU and wall-clock times (read_data CPU, loop
    time, CPU use, the timing table, per-rank histograms)."""
    keep, skip = [], False
    for line in text.splitlines():
        if line.startswith("MPI task timing breakdown:"):
            skip = True
        if skip:
            if line.startswith("Other "):
                skip = False
            continue
        if line.startswith(("Loop time of", "Total wall time")) or "% CPU use with" in line \
                or "read_data CPU =" in line or "Histogram:" in line:
            continue
        keep.append(line)
    return "\n".join(keep) + "\n"


# --------------------------------------------------------------------------
# bonds, weighted volume, the LPS force (numpy, independent of LAMMPS)
# --------------------------------------------------------------------------

class LPS:
    """The conventions of reference/lammps/README.md ("State-based LPS"),
    for one material, no breaking, no contact.  Directed bonds (i, j): every
    unordered pair appears twice, once in the family of each end."""

    def __init__(self, pos0, lc=A, near_zero=NEAR_ZERO, beta_in_m=True):
        bi, bj, r0 = pairs_within(pos0, DELTA)       # r0^2 <= delta^2, squares as LAMMPS forms them
        self.n = len(pos0)
        self.pos0 = pos0
        self.i = np.concatenate([bi, bj])
        self.j = np.concatenate([bj, bi])
        self.r0 = np.concatenate([r0, r0])
        self.near_zero = near_zero
        self.omega = 1.0 / self.r0                   # influence function 1/|xi|
        self.beta = vfrac_scale(self.r0, lc, DELTA)  # pair: delta = cut
        beta_m = vfrac_scale(self.r0, lc, DELTA_FIX) if beta_in_m else np.ones_like(self.r0)
        # weighted volume, once, with the initial family: m_i = sum_j omega |xi|^2 V_j beta
        self.m = np.bincount(self.i, weights=self.omega * self.r0 * self.r0 * VOLUME * beta_m,
                             minlength=self.n)
        self.vb = VOLUME * self.beta

    def stretch_state(self, x):
        d = x[self.i] - x[self.j]                    # LAMMPS' del = x_i - x_j
        r = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1] + d[:, 2] * d[:, 2])
        dr = r - self.r0
        dr[np.abs(dr) < self.near_zero] = 0.0
        return d, r, dr

    def theta(self, x, dr=None):
        if dr is None:
            dr = self.stretch_state(x)[2]
        s = np.bincount(self.i, weights=self.omega * self.r0 * dr * self.vb, minlength=self.n)
        return (3.0 / self.m) * s

    def force(self, x):
        d, r, dr = self.stretch_state(x)
        th = self.theta(x, dr)
        i, j = self.i, self.j
        rk = (3.0 * K - 5.0 * G) * self.vb * (self.omega * th[i] / self.m[i]
                                              + self.omega * th[j] / self.m[j]) * self.r0
        rk += 15.0 * G * self.vb * (self.omega / self.m[i] + self.omega / self.m[j]) * dr
        fb = -rk / r
        return np.stack([np.bincount(i, weights=fb * d[:, a], minlength=self.n)
                         for a in range(3)], axis=1)

    def energies(self, x):
        """(pe as LAMMPS tallies it, consistent LPS strain energy), both sums of
        energy densities over particles [J/m^3]."""
        d, r, dr = self.stretch_state(x)
        th = self.theta(x, dr)
        ed = dr - th[self.i] * self.r0 / 3.0
        dev = np.bincount(self.i, weights=15.0 * G / self.m[self.i] * self.omega * ed * ed * self.vb,
                          minlength=self.n)
        vol = 0.5 * K * th * th
        return (vol + 0.25 * dev).sum(), (vol + 0.5 * dev).sum()

    def run(self, vel0, nsteps, dt, frames=None):
        x = self.pos0.copy()
        v = vel0.copy()
        f = np.zeros_like(x)             # no bond force at the setup evaluation
        dtf = 0.5 * dt
        hist = {0: x - self.pos0}
        for step in range(1, nsteps + 1):
            v += (dtf / RHO) * f
            x += dt * v
            f = self.force(x)
            v += (dtf / RHO) * f
            if frames is None or step in frames:
                hist[step] = x - self.pos0
        return hist

    def linear_operator(self):
        """S (3n x 3n) with f = -S u for small u, per unit volume."""
        n = self.n
        e = (self.pos0[self.j] - self.pos0[self.i]) / self.r0[:, None]
        # deviatoric part: a spring along each bond, counted from both ends
        kd = 15.0 * G * self.vb * (1.0 / self.m[self.i] + 1.0 / self.m[self.j]) / self.r0
        S = np.zeros((3 * n, 3 * n))
        for a in range(3):
            for b in range(3):
                v = kd * e[:, a] * e[:, b]
                np.add.at(S, (3 * self.i + a, 3 * self.j + b), -v)
                np.add.at(S, (3 * self.i + a, 3 * self.i + b), v)
        # dilatation: theta = T u, f = -(3K - 5G)/3 T^T theta
        T = np.zeros((n, 3 * n))
        c = 3.0 * self.vb / self.m[self.i]
        for a in range(3):
            np.add.at(T, (self.i, 3 * self.j + a), c * e[:, a])
            np.add.at(T, (self.i, 3 * self.i + a), -c * e[:, a])
        S += (3.0 * K - 5.0 * G) / 3.0 * (T.T @ T)
        return S


def stable_steps(model):
    S = model.linear_operator()
    n = model.n
    asym = np.abs(S - S.T).max() / np.abs(S).max()
    # Silling-Askari type bound: rows of S sum to zero (translation), so
    # lambda_max <= 2 max_i sum_{j != i} ||S_ij||_2 and dt_c = sqrt(2 rho / max_i sum_j ||S_ij||)
    B = S.reshape(n, 3, n, 3).transpose(0, 2, 1, 3)
    bsum = np.zeros(n)
    for i in range(n):
        blk = B[i]
        nz = np.nonzero(np.abs(blk).reshape(n, 9).max(axis=1) > 0)[0]
        nz = nz[nz != i]
        bsum[i] = np.linalg.norm(blk[nz], ord=2, axis=(1, 2)).sum()
    dt_sa = math.sqrt(2.0 * RHO / bsum.max())
    lam = np.linalg.eigvalsh(0.5 * (S + S.T) / RHO)
    # PMB with the same bulk modulus: c = 18 K / (pi delta^4), Silling-Askari
    c = 18.0 * K / (math.pi * DELTA ** 4)
    i, r0 = model.i, model.r0
    ssum = np.bincount(i, weights=c * model.vb / r0, minlength=n)
    dt_pmb = math.sqrt(2.0 * RHO / ssum.max())
    return dt_sa, 2.0 / math.sqrt(lam[-1]), lam, asym, dt_pmb, c, int(np.count_nonzero(
        np.abs(B).reshape(n, n, 9).max(axis=2).max(axis=0) > 0))


# --------------------------------------------------------------------------
# main
# --------------------------------------------------------------------------

def main():
    args, case_dir = parse_case_args(
        __doc__, "lps_lattice", 50, NSTEPS,
        [("--pulse", dict(choices=("smooth", "step"), default="smooth",
                          help="initial velocity (default smooth; the reference uses smooth)"))])

    t_start = time.time()
    lmp, _ = report_lammps()

    lat = make_lattice(args.pulse)
    pos0 = lat["pos"]
    natoms = len(pos0)
    L = lat["L"]
    print("\n== lps_lattice ==")
    print("particles %d (%d x %d x %d), a = %s m, L = %s m (first to last particle in x), "
          "volume %s m^3, density %s kg/m^3" % (natoms, NX, NY, NZ, A_STR, lat["L_str"], VOLUME_STR, RHO_STR))
    E = float(E_FR)
    print("material: E = %.17g Pa, nu = %.17g -> K = E/(3(1-2nu)) = %s Pa, G = E/(2(1+nu)) = %s Pa"
          % (E, float(NU_FR), K_STR, G_STR))
    print("          nu from K, G: (3K - 2G)/(2(3K + G)) = %.17g; 3K - 5G = %.17g Pa"
          % ((3 * K - 2 * G) / (2 * (3 * K + G)), 3 * K - 5 * G))
    print("pair_coeff * * %s %s %s %s %s (K, G, delta, s00, alpha)" % (K_STR, G_STR, DELTA_STR, S00_STR, ALPHA_STR))
    if args.pulse == "step":
        print("initial velocity: v_x = %g m/s for the %d particle layers i < %d, else 0"
              % (V_AMP, STEP_CELLS, STEP_CELLS))
    else:
        print("initial velocity: v_x = %g m/s cos^2(pi x / (2 w)) for x < w = %s m (%d a), else 0; "
              "v_y = v_z = 0" % (V_AMP, coord_str(PULSE_CELLS), PULSE_CELLS))
    vmom = lat["vel"].mean(axis=0)
    print("  nonzero v_x on %d layers; mean velocity (momentum / mass) = %.10e m/s"
          % (len(set(lat["idx"][lat["vel"][:, 0] != 0, 0])), vmom[0]))
    cP = math.sqrt((K + 4.0 * G / 3.0) / RHO)
    cS = math.sqrt(G / RHO)
    cB = math.sqrt(E / RHO)
    print("wave speeds: P sqrt((K + 4G/3)/rho) = %.2f m/s, bar sqrt(E/rho) = %.2f m/s, S sqrt(G/rho) = %.2f m/s"
          % (cP, cB, cS))
    print("  L / c_P = %.4e s, L / c_bar = %.4e s; t_end = %d dt = %.4e s: %.3f L/c_P, %.3f L/c_bar"
          % (L / cP, L / cB, NSTEPS, NSTEPS * DT, NSTEPS * DT * cP / L, NSTEPS * DT * cB / L))

    # --- family, partial-volume factor, weighted volume ---
    model = LPS(pos0)
    counts = np.bincount(model.i, minlength=natoms)
    print("bond family: %d directed bonds (sum of partner counts), %d bonds; partners per particle %d..%d"
          % (len(model.i), len(model.i) // 2, counts.min(), counts.max()))
    print("horizon: cut = %.17g, sqrt(cutsq) used by fix PERI_NEIGH = %.17g (%s)"
          % (DELTA, DELTA_FIX, "equal" if DELTA == DELTA_FIX else "DIFFERENT"))
    bF = vfrac_scale(model.r0, A, DELTA)
    bM = vfrac_scale(model.r0, A, DELTA_FIX)
    print("vfrac_scale with the two horizons: max difference %.3e" % np.abs(bF - bM).max())
    print("shells (r0/a)^2 : r0 [m], vfrac_scale (lc = %s)" % A_STR)
    for n2 in sorted(set(np.rint((model.r0 / A) ** 2).astype(int))):
        sel = np.rint((model.r0 / A) ** 2).astype(int) == n2
        print("  %2d : %.10f  %.10f" % (n2, model.r0[sel][0], bF[sel][0]))
    inner = (lat["idx"][:, 0] >= 3) & (lat["idx"][:, 0] <= NX - 4)
    interior = inner & (lat["idx"][:, 1] >= 3) & (lat["idx"][:, 1] <= NY - 4)
    m_full = model.m.max()
    print("weighted volume m_i = sum_j (1/|xi|) |xi|^2 V beta: max %.10e m^5 (full family, %d partners), "
          "min %.10e (corner); continuum pi delta^4 = %.10e; max m / (pi delta^4) = %.6f"
          % (m_full, counts.max(), model.m.min(), math.pi * DELTA ** 4, m_full / (math.pi * DELTA ** 4)))
    print("  (no particle of a 6 x 6 cross-section has the full 122-partner family: %s)"
          % ("true" if counts.max() < 122 and not interior.any() else "false"))

    # --- stable step ---
    t0 = time.time()
    dt_sa, dt_lin, lam, asym, dt_pmb, c_pmb, _ = stable_steps(model)
    print("stable step (%.0f s): linearised LPS operator S (%d x %d), relative asymmetry %.2e"
          % (time.time() - t0, 3 * natoms, 3 * natoms, asym))
    print("  Silling-Askari type bound sqrt(2 rho / max_i sum_j ||S_ij||_2) = %.4e s: dt is a factor %.2f below"
          % (dt_sa, dt_sa / DT))
    print("  exact 2/omega_max = %.4e s (omega_max = %.4e rad/s): dt is a factor %.2f below; "
          "%d eigenvalues below 1e-9 max (rigid-body modes)"
          % (dt_lin, 2.0 / dt_lin, dt_lin / DT, int(np.sum(lam < 1e-9 * lam[-1]))))
    print("  PMB with the same K (c = 18K/(pi delta^4) = %.5e N/m^6): Silling-Askari %.4e s"
          % (c_pmb, dt_pmb))

    with tempfile.TemporaryDirectory(prefix="lammps_lps_") as tmp:
        tmp = Path(tmp)
        write_data(tmp / "data.lps_lattice", lat, "LPS", (NX, NY, NZ))
        title = "lps_lattice: %dx%dx%d simple-cubic bar, a = %s m, %s pulse at x = 0" % (
            NX, NY, NZ, A_STR, args.pulse)

        # --- reference run (dumped every step) ---
        ref_deck = deck("data.lps_lattice", DT_STR, NSTEPS, title)
        ref_log, ref, steps = reference_run(lmp, tmp, ref_deck, NCOL, NSTEPS, len(model.i), "numpy",
                                            RHO_STR)
        ds = np.loadtxt(tmp / "damage_s0.txt", comments="#")
        print("damage/atom: max over particles at %d steps (%d..%d): largest %.3g; sum of damage: largest %.3g"
              % (len(ds), int(ds[0, 0]), int(ds[-1, 0]), ds[:, 1].max(), ds[:, 2].max()))
        print("s0 (min over particles): at step 0 (after the guard's setup) %.17g; over all steps %.17g..%.17g"
              % (ds[0, 3], ds[:, 3].min(), ds[:, 3].max()))
        if ds[:, 1].max() != 0.0:
            sys.exit("a bond broke in the reference run")
        bond_dmp = ref_log.split("Peridynamic bonds:")[1].split("\n")[1].strip()
        print("log: '%s'" % bond_dmp)
        (tmp / "dump.traj").rename(tmp / "dump.ref")

        # --- displacements, stretch, contact, dilatation ---
        umax, umax_step, udef, ncontact, contact_min = check_frames(ref, lat["ids"], pos0, DELTA, A)
        smax, smin, smax_step = -1.0, 1.0, 0
        th_err, th_max = 0.0, 0.0
        for s in steps:
            fr = ref[s]
            x = fr[:, 1:4]
            d, r, dr = model.stretch_state(x)
            st = dr / model.r0
            if st.max() > smax:
                smax, smax_step = st.max(), s
            smin = min(smin, st.min())
            th = model.theta(x, dr)
            th_err = max(th_err, np.abs(th - fr[:, 10]).max())
            th_max = max(th_max, np.abs(fr[:, 10]).max())
        ufin = ref[NSTEPS][:, 4:7]
        print("largest |u| over all steps = %.6e m (step %d); at step %d: max |ux|, |uy|, |uz| = %.6e %.6e %.6e m"
              % (umax, umax_step, NSTEPS, np.abs(ufin[:, 0]).max(), np.abs(ufin[:, 1]).max(),
                 np.abs(ufin[:, 2]).max()))
        print("mean u at step %d: %.6e %.6e %.6e m; mean(v0) * t = %.6e m"
              % ((NSTEPS,) + tuple(ufin.mean(axis=0)) + (vmom[0] * NSTEPS * DT,)))
        print("largest |u - mean u| over all steps = %.6e m = %.4f of max |u|" % (udef, udef / umax))
        print("bond stretch over all steps: max %.6e (step %d), min %.6e; max |s| / s00 = %.3e"
              % (smax, smax_step, smin, max(smax, -smin) / S00))
        check_contact(ncontact, contact_min)
        print("dilatation: max |theta| over all steps %.6e; numpy theta of LAMMPS' positions vs compute "
              "dilatation/atom: max difference %.3e = %.3e of max |theta|" % (th_max, th_err, th_err / th_max))

        # wave arrival at the far end (mean v_x over the end face i = NX-1)
        far = lat["idx"][:, 0] == NX - 1
        vfar = np.array([ref[s][far, 7].mean() for s in steps])
        s_pk = int(np.argmax(vfar))
        s_on = int(np.argmax(vfar > 0.1 * vfar.max()))
        print("far end (i = %d) mean v_x: peak %.4f m/s at step %d (t = %.4e s), first above 10%% of it at step %d"
              % (NX - 1, vfar[s_pk], s_pk, s_pk * DT, s_on))
        print("  the pulse peak starts at x = 0: L / t_peak = %.1f m/s (c_P %.1f, c_bar %.1f)"
              % (L / (s_pk * DT), cP, cB))

        # energies
        th_lines = [l for l in ref_log.split("Step Time")[-1].splitlines() if re.match(r"^\s+\d+\s+[\d.]+e", l)]
        print("energies from the dumped state (numpy) vs thermo [J/m^3 summed over particles]:")
        rel_l, rel_c = [], []
        for l in th_lines:
            p = l.split()
            s = int(p[0])
            x, vv = ref[s][:, 1:4], ref[s][:, 7:10]
            ke = 0.5 * RHO * (vv * vv).sum()
            pe_l, pe_c = model.energies(x)
            rel_l.append((s, ke + pe_l))
            rel_c.append((s, ke + pe_c))
            if s in (0, NSTEPS // 2, NSTEPS):
                print("  step %3d: ke %.10e (thermo %s), pe %.10e (thermo %s), consistent pe %.10e"
                      % (s, ke, p[2], pe_l, p[3], pe_c))
            if abs(pe_l - float(p[3])) > 1e-8 * max(abs(pe_l), 1e-30) + 1e-12 or \
                    abs(ke - float(p[2])) > 1e-9 * ke:
                print("  step %d: thermo differs from numpy (ke %s vs %.10e, pe %s vs %.10e)"
                      % (s, p[2], ke, p[3], pe_l))
        tot0 = rel_l[0][1]
        dl = max(abs(t - tot0) for _, t in rel_l) / tot0
        dc = max(abs(t - tot0) for _, t in rel_c) / tot0
        print("  ke + pe over the thermo steps: largest change %.3e (LAMMPS pe), %.3e (consistent pe) relative;"
              " at step %d: %.3e, %.3e" % (dl, dc, NSTEPS, (rel_l[-1][1] - tot0) / tot0,
                                           (rel_c[-1][1] - tot0) / tot0))

        # --- independent check of the conventions ---
        t0 = time.time()
        hist = model.run(lat["vel"], NSTEPS, DT)
        e_np = max(np.linalg.norm(hist[s] - ref[s][:, 4:7], axis=1).max() for s in steps)
        e_np_fin = np.linalg.norm(hist[NSTEPS] - ref[NSTEPS][:, 4:7], axis=1).max()
        print("numpy re-implementation of the documented conventions (%.1f s): max |u_numpy - u_LAMMPS|"
              " over all %d steps = %.4e m = %.4e of max |u| (step %d: %.4e)"
              % (time.time() - t0, len(steps), e_np, e_np / umax, NSTEPS, e_np_fin / umax))
        for label, kw in (("without LAMMPS' |dr| < 2.2204e-16 m cut-off", {"near_zero": 0.0}),
                          ("with m_i without the partial-volume factor", {"beta_in_m": False})):
            h2 = LPS(pos0, **kw).run(lat["vel"], NSTEPS, DT)
            e2 = max(np.linalg.norm(h2[s] - hist[s], axis=1).max() for s in steps)
            print("numpy %s differs from it by %.4e m = %.4e of max |u|" % (label, e2, e2 / umax))

        # --- same run with s00 = 0.5: byte-identical trajectory ---
        dk = deck("data.lps_lattice", DT_STR, NSTEPS, title + " (s00 = 0.5)", s00_str="0.5", diag=False)
        (tmp / "s00.in").write_text(dk)
        run_lmp(lmp, tmp, "s00.in")
        same = (tmp / "dump.traj").read_bytes() == (tmp / "dump.ref").read_bytes()
        print("run with s00 = 0.5: dump (x, u, v, theta at all %d steps) byte-identical: %s"
              % (len(steps), "yes" if same else "NO"))
        if not same:
            sys.exit("s00 = 0.5 run differs")

        # --- the same deck without the 'run 0' guard ---
        dk = deck("data.lps_lattice", DT_STR, NSTEPS, title + " (no run 0)", guard=False, diag=False,
                  dump_every=THERMO_EVERY)
        (tmp / "noguard.in").write_text(dk)
        ng_log, _ = run_lmp(lmp, tmp, "noguard.in")
        dsn = np.loadtxt(tmp / "damage_s0.txt", comments="#")
        print("without 'run 0': s0 min at step 0 = %.17g; after step 1: max damage %.6f, damage sum %.4f, "
              "s0 min %.17g; at step %d: max damage %.6f" % (dsn[0, 3], dsn[1, 1], dsn[1, 2], dsn[1, 3],
                                                            NSTEPS, dsn[-1, 1]))
        frn = read_dump(tmp / "dump.traj", NCOL)
        e_ng = max(np.linalg.norm(frn[s][:, 4:7] - ref[s][:, 4:7], axis=1).max() for s in frn)
        print("  its displacements differ from the reference by %.4e m = %.4e of max |u|" % (e_ng, e_ng / umax))
        # which bonds had a positive stretch after step 1
        x1 = ref[1][:, 1:4]
        st1 = model.stretch_state(x1)[2] / model.r0
        print("  in the reference, %d of %d directed bonds have a positive stretch after step 1 (max %.3e)"
              % (int(np.sum(st1 > 0)), len(st1), st1.max()))

        # the same bug with a tensile start (v -> -v), one step, with and without 'run 0'
        lat_t = dict(lat)
        lat_t["vel_s"] = [(repr(-float(vx)) if float(vx) != 0.0 else "0.0", vy, vz)
                          for vx, vy, vz in lat["vel_s"]]
        write_data(tmp / "data.tensile", lat_t, "LPS", (NX, NY, NZ))
        x1t = pos0 - DT * lat["vel"]          # positions after one drift (f = 0 before step 1)
        st1t = model.stretch_state(x1t)[2] / model.r0
        for guard in (False, True):
            dk = deck("data.tensile", DT_STR, 1, title + " (tensile start, one step)", guard=guard,
                      diag=False)
            dk = dk.replace("run             1\n",
                            "dump            g all custom 1 dump.dmg id c_dmg\n"
                            "dump_modify     g sort id format float %.17g\nrun             1\n")
            (tmp / "tensile.in").write_text(dk)
            run_lmp(lmp, tmp, "tensile.in")
            dmg1 = read_dump(tmp / "dump.dmg", 2)[1][:, 1]
            nbroken = int(round((dmg1 * counts).sum()))
            print("tensile start (v_x -> -v_x), %s 'run 0': after step 1 %d directed bonds broken "
                  "(sum_i damage_i * partners_i), max damage %.6f; bonds with a positive stretch after "
                  "the first drift: %d (numpy, smallest %.3e)"
                  % ("with" if guard else "without", nbroken, dmg1.max(), int(np.sum(st1t > 0)),
                     st1t[st1t > 0].min() if np.any(st1t > 0) else 0.0))

        # --- sensitivity: no partial-volume factor ---
        dk = deck("data.lps_lattice", DT_STR, NSTEPS, title + " (lattice sc 1e-9: vfrac_scale = 1)",
                  lattice_str="1e-9", diag=False, dump_every=THERMO_EVERY)
        no_partial_volume(lmp, tmp, dk, NCOL, ref, umax)

        # --- time discretisation ---
        common, e12, e24, _ = refine_dt(
            lmp, tmp, lambda div: deck("data.lps_lattice", repr(DT / div), NSTEPS * div,
                                       title + " (dt/%d)" % div, diag=False,
                                       dump_every=THERMO_EVERY * div, thermo_every=THERMO_EVERY * div),
            NCOL, ref)
        print("time step: max over %d common times (every %d dt) of |u(dt) - u(dt/2)| = %.4e m = %.4e of max |u|"
              % (len(common), THERMO_EVERY, e12, e12 / umax))
        print("           |u(dt/2) - u(dt/4)| = %.4e m = %.4e of max |u|; ratio %.3f (4 for O(dt^2))"
              % (e24, e24 / umax, e12 / e24))

        # --- write the reference files ---
        write_case(case_dir, tmp / "data.lps_lattice", ref_deck, trim_log(ref_log), lat, ref,
                   args.every, DT)
    print("\ntotal run time of this script: %.0f s" % (time.time() - t_start))


if __name__ == "__main__":
    main()
