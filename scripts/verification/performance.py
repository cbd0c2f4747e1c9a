"""Performance tables: the peridynamic bond loop beside LAMMPS peri/pmb (scripts/pd_benchmark.py),
the implicit solves' growth with size (scripts/benchmark_implicit.py) and SPH throughput
(scripts/sph_benchmark.py), each run through its script and read from the files it writes."""
import csv
import os
import shutil
import subprocess
import sys

from verification.page import Section, image, markdown, table

# Lattices of n^3 particles: 20^3 and 40^3 are rows of reference/lammps/benchmark.csv.
PD_SIZES, PD_QUICK_SIZES = ["20", "40"], ["10"]
# Full mode: the implicit study up to 4e5 DOFs (its default, 2.6e6, is the long scaling study)
# with a 1 GiB memory probe; quick mode is the suite's smoke test on the elastic plate alone.
IMPLICIT = ["--max-dofs", "4e5", "--first-touch", "1"]
IMPLICIT_QUICK = ["--quick", "--layouts", "1x2", "--cases", "plate"]
MAX_ITERATIONS_GROWTH = 1.15  # tests/CMakeLists.txt, scripts.benchmark_implicit_smoke
SPH = ["--sizes", "1e4,1e5", "--threads", "1,2", "--ranks", "2", "--repeats", "1"]
SPH_QUICK = ["--skip-problems", "--sizes", "1e4", "--steps", "3", "--threads", "1", "--ranks", "",
             "--repeats", "1"]
MPI_AS_ROOT = dict(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1")


def script(ctx, name, args):
    env = dict(os.environ, **MPI_AS_ROOT)
    subprocess.run([sys.executable, str(ctx.root / "scripts" / name)] + args, check=True,
                   capture_output=True, env=env)


def rows_of(path):
    return list(csv.DictReader(open(path)))


def lammps_rates(root):
    """reference/lammps/benchmark.csv: LAMMPS's bond updates per second by (particles, ranks)."""
    return {(int(r["particles"]), int(r["mpi_ranks"])): float(r["bond_updates_per_second"])
            for r in rows_of(root / "reference" / "lammps" / "benchmark.csv")}


def pd_section(ctx):
    folder = ctx.out / "pd_benchmark"
    interleaved = shutil.which("lmp") is not None
    sizes = PD_QUICK_SIZES if ctx.quick else PD_SIZES
    script(ctx, "pd_benchmark.py", ["--meshfree", ctx.meshfree, "--out", str(folder), "--sizes"]
           + sizes + ["--threads", "1", "2", "--repeats", "1"] + ([] if interleaved else ["--no-lammps"]))
    stored = {} if interleaved else lammps_rates(ctx.root)
    rows = []
    for r in rows_of(folder / "benchmark.csv"):
        n, t, rate = int(r["particles"]), int(r["threads"]), float(r["bond_evaluations_per_second"])
        lammps = float(r["lammps_loop_rate"]) if r.get("lammps_loop_rate") else stored.get((n, t))
        rows.append((n, r["bonds"], t, f"{float(r['step_seconds']):.3g}", f"{rate:.3g}",
                     f"{float(r['bytes_steady']):.1f}", "-" if lammps is None else f"{lammps:.3g}",
                     "-" if lammps is None else f"{rate / lammps:.2f}"))
    source = ("LAMMPS run beside it, interleaved, so that both see the same load" if interleaved
              else "LAMMPS's rates as measured when reference/lammps was made, on a quiet machine, "
                   "while meshfree's are of this machine as it is loaded now; with Debian's "
                   "<code>lammps</code> installed the runs are interleaved")
    return Section(f"<p>Directed bond evaluations per second of a free PMB lattice, meshfree with k "
                   f"threads against LAMMPS peri/pmb with k MPI ranks ({source}); the ratio is "
                   f"meshfree's rate over LAMMPS's whole-loop rate.</p>"
                   + table(["particles", "directed bonds", "threads / ranks", "all steps [s]",
                            "bond evaluations/s", "bytes per bond", "LAMMPS evaluations/s",
                            "meshfree / LAMMPS"], rows))


def implicit_section(ctx):
    folder = ctx.out / "benchmark_implicit"
    script(ctx, "benchmark_implicit.py", ["--meshfree", ctx.meshfree, "--out", str(folder)]
           + (IMPLICIT_QUICK if ctx.quick else IMPLICIT))
    runs = [(r["case"], r["solver"], r["layout"], r["dofs"], f"{float(r['total_s']):.2f}",
             f"{float(r['assembly_s']):.2f}", f"{float(r['solve_s']):.2f}",
             f"{float(r['iterations_per_solve']):.1f}", f"{float(r['bytes_per_dof']):.0f}")
            for r in rows_of(folder / "runs.csv")]
    growth, passed = [], True
    for e in rows_of(folder / "exponents.csv"):
        g = float(e["iterations_growth"])
        ok = e["solver"] != "multigrid" or g <= MAX_ITERATIONS_GROWTH
        passed &= ok
        growth.append((e["case"], e["solver"], e["layout"], f"{e['dofs_from']}..{e['dofs_to']}",
                       f"{float(e['total']):.2f}", f"{float(e['memory']):.2f}", f"x{g:.2f}",
                       f"<= {MAX_ITERATIONS_GROWTH}" if e["solver"] == "multigrid" else "-",
                       "yes" if ok else "NO"))
    return Section("<p>The elastic plate and the elastoplastic perforated strip against size, "
                   "MUMPS and CG + GAMG, 1 rank x 2 threads and 2 ranks x 1 thread: wall times "
                   "of one run each, growth exponents (time ~ DOFs^e) and the multigrid's "
                   "iterations per solve from the smallest to the largest size, which the suite "
                   f"holds to x{MAX_ITERATIONS_GROWTH}.</p>"
                   + table(["case", "solver", "layout", "DOFs", "exponent of total time",
                            "of memory", "iterations per solve", "suite's bound", "within"], growth)
                   + table(["case", "solver", "layout", "DOFs", "total [s]", "assembly [s]",
                            "solve [s]", "iterations per solve", "bytes per DOF"], runs)
                   + image(folder / "benchmark_implicit.png"), passed)


def sph_section(ctx):
    folder = ctx.out / "sph_benchmark"
    script(ctx, "sph_benchmark.py", ["--old", ctx.meshfree, "--new", ctx.meshfree, "--out",
                                     str(folder)] + (SPH_QUICK if ctx.quick else SPH))
    return Section("<p>SPH throughput (particle-steps and pair evaluations per second). LAMMPS has "
                   "no counterpart in Debian's build (no SPH or SMD package), so the script's "
                   "reference binary is this build itself: its 'old' rows and speed-ups show the "
                   "run-to-run spread.</p>" + markdown((folder / "table.md").read_text()))
