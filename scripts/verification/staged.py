"""Staged runs' quiet starts: the suite's quiet-start tests (kinetic energy against the stored
strain energy, drift of the handed-over state) and the transfer of each staged problem in
problems/ (the out-of-balance left when the explicit stage starts)."""
import json
import subprocess

import yaml

from verification import suite_cases
from verification.page import Section, table

QUIET = ["an elastic strip preloaded by end tractions starts quietly in SPH",
         "a peridynamic stage after a Galerkin preload starts quiet at the Galerkin displacement",
         "a strip preloaded into plasticity starts quietly in SPH",
         "every held condition hands a homogeneous state to SPH quietly, with no settle",
         "every held condition hands a homogeneous state to peridynamics quietly",
         "greenfield sand column: a K0 = 0.5 geostatic preload is held quietly in SPH"]
PROBLEMS = ["staged_tunnel_blast", "staged_pmma_impact", "staged_strip_blast"]
# tests/cli/mpi_explicit_consistency.sh holds a staged run's initial out-of-balance to 1e-3.
OUT_OF_BALANCE = 1e-3
# As tests/cli/problems_run.sh: the preload in full, the explicit stage over 2% of its end time.
STAGE_FRACTION = 0.02


def short_stage(problem_path):
    """The --set that ends the explicit stage after STAGE_FRACTION of its time."""
    stages = yaml.safe_load(open(problem_path))["stages"]
    end = float(stages[1]["time"]["end"])
    return ["--set", f"stages.1.time.end={STAGE_FRACTION * end:.6g}"]


def transfer(ctx, name):
    path = ctx.root / "problems" / f"{name}.yaml"
    folder = ctx.out / "staged" / name
    subprocess.run([ctx.meshfree, "run", str(path), "--out", str(folder)] + short_stage(path),
                   check=True, capture_output=True)
    return json.load(open(folder / "summary.json"))["transfer"]


def transfer_rows(ctx, names):
    rows, passed = [], True
    for name in names:
        t = transfer(ctx, name)
        ok = t["initial_out_of_balance"] <= OUT_OF_BALANCE
        passed &= ok
        other = (f"PD equilibrium ({t['equilibrium']}) residual ratio "
                 f"{t['relaxation_residual_ratio']:.1e}, PD vs Galerkin displacement "
                 f"{t['pd_vs_galerkin_displacement']:.2e}" if "equilibrium" in t else
                 f"balanced residual {t['balanced_residual']:.2e}, density mismatch "
                 f"{t['density_mismatch']:.1e}, settle drift {t['settle_drift']:.1e}")
        rows.append((name, t["particles"], f"{t['stored_elastic_energy']:.4g}",
                     f"{t['initial_out_of_balance']:.2e}", f"<= {OUT_OF_BALANCE:g}",
                     "yes" if ok else "NO", other))
    return rows, passed


def staged_section(ctx):
    names = PROBLEMS[:2] if ctx.quick else PROBLEMS
    rows, passed = transfer_rows(ctx, names)
    # The quiet-start tests take minutes together (each a preload and a long held run).
    cases = (Section("<p>Quick mode: the staged tunnel and PMMA problems; the staged strip's "
                     "preload and the quiet-start tests are in the full report.</p>", True)
             if ctx.quick else suite_cases.section(ctx.tests, QUIET, (
                 "The suite's quiet-start tests: a Galerkin preload handed to SPH or "
                 "peridynamics, then run held and undamped; the kinetic energy against the "
                 "stored strain energy and the drift of the handed-over stresses and "
                 "displacements.")))
    body = (f"<p>The staged problems, the preload in full and the explicit stage over "
            f"{100 * STAGE_FRACTION:g}% of its end time: summary.json's transfer section, the "
            f"out-of-balance force left at the start of the explicit stage relative to the "
            f"preload's forces.</p>"
            + table(["problem", "particles", "stored elastic energy", "initial out-of-balance",
                     "suite's bound", "within", "transfer"], rows) + cases.body)
    return Section(body, passed and cases.passed)
