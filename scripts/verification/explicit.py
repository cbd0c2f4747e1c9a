"""Explicit sections: LAMMPS (disk impact, PMB lattice), waves, Sod, Chapman-Jouguet, the Taylor
bar. The comparisons the unit tests make are run as those tests (verification.suite_cases); the
whole-program ones through the scripts and problem files the suite uses."""
import subprocess

import matplotlib.pyplot as plt
import pd_disk_impact_vs_lammps as disk  # tests/reference/pd_disk_impact_vs_lammps.py
import taylor_bar  # scripts/taylor_bar.py

from verification import suite_cases
from verification.page import Section, image, table

SOD = ["Sod's shock tube with the Wendland C2 kernel",
       "Sod's shock tube against the exact Riemann solution"]
DETONATION = ["JWL TNT: the Chapman-Jouguet point of the Dobratz constants",
              "a detonation plane lights a 2D TNT strip as a plane wave at D_CJ",
              "TNT slab: programmed burn runs at D_CJ and the front obeys the jump conditions",
              "TNT slab with an unreacted equation of state: a self-sustained ZND front at D_CJ "
              "that ends at the Chapman-Jouguet pressure"]
LATTICE = ["PMB on a lattice matches LAMMPS peri/pmb step for step before any bond breaks"]
WAVES = ["elastic wave in a bar: speed and stress against the one-dimensional theory",
         "elastic-plastic bar impact: precursor at the Hugoniot elastic limit, plastic wave at "
         "the bulk speed",
         "a long pulse travels at the dilatational speed of the continuum"]
# tests/CMakeLists.txt, sph.taylor_bar_final_length: the final length within 5% at 0.6 mm.
TAYLOR_SPACING, TAYLOR_QUICK_SPACING, TAYLOR_CHECK = 0.6e-3, 1.2e-3, 0.05


def cases_section(ctx, full, quick_count, intro):
    """The suite's test cases `full`, or their first `quick_count` in quick mode."""
    names = full[:quick_count] if ctx.quick else full
    return suite_cases.section(ctx.tests, names, intro)


def lattice_section(ctx):
    return cases_section(ctx, LATTICE, 1, (
        "meshfree's bond-based PMB against LAMMPS 29 Sep 2021 <code>pair_style peri/pmb</code> on "
        "the 10&times;10&times;10 lattice of reference/lammps/pmb_lattice (a wave started by a "
        "smooth initial velocity in a free block): displacements at every 40th of 400 steps."))


def waves_section(ctx):
    return cases_section(ctx, WAVES, 1, (
        "Wave speeds and the stress behind the front against one-dimensional elastic theory "
        "(SPH bar, peridynamic plate and column) and the Hugoniot elastic limit."))


def sod_section(ctx):
    return cases_section(ctx, SOD, 1, (
        "SPH against the exact Riemann solution of Sod's shock tube (Toro 2009, test 1): the "
        "star-state pressure and velocity, the shock position, the L1 density error and its "
        "rate over 400, 800 and 1600 particles."))


def detonation_section(ctx):
    return cases_section(ctx, DETONATION, 2, (
        "TNT (JWL, Dobratz constants): the Chapman-Jouguet point, detonation fronts at D_CJ by "
        "programmed burn (1D slab and 2D plane), the Rayleigh-line jump conditions, and a "
        "self-sustained ZND front that ends at P_CJ."))


def disk_section(ctx):
    folder = ctx.out / "pd_disk_impact"
    disk.run(ctx.meshfree, ctx.root, folder, steps=250 if ctx.quick else None)
    c = disk.compare(ctx.root, folder, verbose=False)
    plot_disk(c, ctx.out / "pd_disk_impact.png")
    labels = {"force_error": "largest indenter-force difference / LAMMPS peak",
              "peak_error": "peak force difference",
              "worst_damage": "damaged-particle count, largest relative difference",
              "early_balance": "energy balance to step 150"}
    rows = [(text, f"{c[k]:.2e}", f"<= {disk.TOLERANCES[k]:g}",
             "yes" if c[k] <= disk.TOLERANCES[k] else "NO") for k, text in labels.items()]
    reduced = " (quick mode: the first 250 steps)" if ctx.quick else ""
    return Section(f"<p>LAMMPS's shipped disk-impact example (peri/pmb target, indenter sphere) "
                   f"against reference/lammps/disk_impact; steps compared: {len(c['steps'])}"
                   f"{reduced}.</p>"
                   + table(["measure", "value", "suite's bound", "within"], rows)
                   + image(ctx.out / "pd_disk_impact.png"), disk.passes(c, whole_run=not ctx.quick))


def plot_disk(c, path):
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    a.plot(c["steps"], c["lammps_force"], "k-", lw=2.5, alpha=0.4, label="LAMMPS")
    a.plot(c["steps"], c["ours_force"], "C0-", lw=1, label="meshfree")
    a.set_xlabel("step (dt = 1e-7 s)")
    a.set_ylabel("indenter force [N]")
    steps, ours, lammps = zip(*c["damage"]) if c["damage"] else ([], [], [])
    b.plot(steps, lammps, "ko", mfc="none", ms=4, label="LAMMPS")
    b.plot(steps, ours, "C0-", label="meshfree")
    b.set_xlabel("step")
    b.set_ylabel("damaged particles")
    for ax in (a, b):
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def taylor_section(ctx):
    spacing = TAYLOR_QUICK_SPACING if ctx.quick else TAYLOR_SPACING
    folder = ctx.out / "taylor_bar"
    subprocess.run([ctx.meshfree, "run", str(ctx.root / "problems" / "sph_taylor_bar.yaml"),
                    "--out", str(folder), "--set", f"regions.0.spacing={spacing}"],
                   check=True, capture_output=True)
    length, radius, strain = taylor_bar.measure(folder, spacing)
    dl = length / taylor_bar.REFERENCE_LENGTH - 1.0
    dr = radius / taylor_bar.REFERENCE_RADIUS - 1.0
    rows = [("final length [mm]", f"{1e3 * length:.3f}", f"{1e3 * taylor_bar.REFERENCE_LENGTH:.2f}",
             f"{100 * dl:+.2f}%", f"within {100 * TAYLOR_CHECK:g}%"),
            ("footprint radius [mm]", f"{1e3 * radius:.3f}",
             f"{1e3 * taylor_bar.REFERENCE_RADIUS:.2f}", f"{100 * dr:+.2f}%", "-"),
            ("largest plastic strain", f"{strain:.3f}", "-", "-", "-")]
    note = ("" if spacing == TAYLOR_SPACING else
            f" Quick mode: spacing {1e3 * spacing:g} mm; the suite asserts at "
            f"{1e3 * TAYLOR_SPACING:g} mm.")
    return Section("<p>The SPH Taylor bar (problems/sph_taylor_bar.yaml, copper rod at 227 m/s on "
                   "a rigid wall) against the benchmark's converged finite-element final length "
                   f"and footprint radius (scripts/taylor_bar.py); spacing {1e3 * spacing:g} mm."
                   f"{note}</p>" + table(["quantity", "meshfree", "reference", "difference",
                                          "suite's bound"], rows),
                   abs(dl) <= TAYLOR_CHECK)
