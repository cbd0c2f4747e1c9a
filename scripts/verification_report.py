#!/usr/bin/python3
"""Regenerates the comparisons the test suite asserts, from fresh runs and the reference data in
reference/, as one self-contained HTML page (PNG plots embedded, no network). Each section says
what is compared, shows the plot or table, the error against the reference beside the bound the
suite asserts, and whether it passed:

- CalculiX load-displacement curves of perforated_strip and cook_membrane (scripts/compare.py),
- Timoshenko cantilever and Kirsch plate convergence (scripts/convergence_study.py),
- LAMMPS: peri/pmb disk impact (tests/reference/pd_disk_impact_vs_lammps.py) and PMB lattice,
- elastic waves against one-dimensional theory, Sod's shock tube, the Chapman-Jouguet detonation
  (the unit tests that assert them, run through build/tests/meshfree_tests),
- the Taylor bar (scripts/taylor_bar.py), staged quiet starts (the staged problems' transfer and
  the quiet-start tests), the tunnel study's trends (scripts/tunnel_study.py),
- the peridynamic, implicit and SPH performance tables (scripts/pd_benchmark.py,
  scripts/benchmark_implicit.py, scripts/sph_benchmark.py).

    scripts/verification_report.py [--meshfree build/meshfree] [--tests build/tests/meshfree_tests]
                                   [--out out/verification] [--quick]

--quick (the suite's smoke test) makes every section in a reduced form: smaller sizes, shorter
runs, the cheaper of the unit tests; each section says what it reduced.
Exit 1 if a section could not be made (the page is written with its error); with --strict, also
if a section failed its tolerances.
"""
import argparse
import sys
import time
import traceback
from dataclasses import dataclass
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
sys.path.insert(0, str(ROOT / "tests" / "reference"))
from verification import explicit, implicit, performance, staged, tunnel  # noqa: E402
from verification.page import render  # noqa: E402

CALCULIX_PROBLEMS = ["perforated_strip", "cook_membrane"]


@dataclass
class Context:
    meshfree: str
    tests: str
    out: Path
    quick: bool
    root: Path = ROOT


def makers(ctx):
    """(title, maker) for every section, in the page's order."""
    problems = CALCULIX_PROBLEMS[:1] if ctx.quick else CALCULIX_PROBLEMS
    out = [(f"CalculiX: {p}", lambda p=p: implicit.calculix_section(p, ctx)) for p in problems]
    return out + [
        ("Convergence against exact solutions", lambda: implicit.convergence_section(ctx)),
        ("LAMMPS: peridynamic disk impact", lambda: explicit.disk_section(ctx)),
        ("LAMMPS: PMB lattice", lambda: explicit.lattice_section(ctx)),
        ("Elastic waves against one-dimensional theory", lambda: explicit.waves_section(ctx)),
        ("Sod's shock tube", lambda: explicit.sod_section(ctx)),
        ("Chapman-Jouguet detonation", lambda: explicit.detonation_section(ctx)),
        ("Taylor bar", lambda: explicit.taylor_section(ctx)),
        ("Staged runs: quiet starts", lambda: staged.staged_section(ctx)),
        ("Buried-tunnel study: trends", lambda: tunnel.tunnel_section(ctx)),
        ("Performance: peridynamics beside LAMMPS", lambda: performance.pd_section(ctx)),
        ("Performance: implicit solves", lambda: performance.implicit_section(ctx)),
        ("Performance: SPH", lambda: performance.sph_section(ctx)),
    ]


def make_all(ctx):
    """[(title, Section or None, error or None)], printing each section's outcome as it ends."""
    sections = []
    for title, make in makers(ctx):
        start = time.time()
        try:
            section, error = make(), None
        except (Exception, SystemExit) as e:  # compare.py reports a failed run as SystemExit
            section, error = None, "".join(traceback.format_exception_only(type(e), e))
        state = ("not made: " + error.strip().splitlines()[-1] if section is None else
                 {True: "passed", False: "FAILED", None: "measured"}[section.passed])
        print(f"{title}: {state} ({time.time() - start:.0f} s)", flush=True)
        sections.append((title, section, error))
    return sections


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshfree", default=str(ROOT / "build" / "meshfree"))
    ap.add_argument("--tests", default=str(ROOT / "build" / "tests" / "meshfree_tests"))
    ap.add_argument("--out", default=str(ROOT / "out" / "verification"))
    ap.add_argument("--quick", action="store_true", help="the suite's smoke test: every section reduced")
    ap.add_argument("--strict", action="store_true", help="exit 1 if a section failed its tolerances")
    args = ap.parse_args()
    ctx = Context(args.meshfree, args.tests, Path(args.out), args.quick)
    ctx.out.mkdir(parents=True, exist_ok=True)
    start = time.time()
    sections = make_all(ctx)
    mode = "quick mode: every section reduced (see each)" if ctx.quick else "full"
    report = ctx.out / "report.html"
    report.write_text(render(sections, mode, time.time() - start))
    missing = [t for t, s, _ in sections if s is None]
    failed = [t for t, s, _ in sections if s is not None and s.passed is False]
    print(f"wrote {report} ({len(sections) - len(missing)} of {len(sections)} sections; "
          f"{len(failed)} outside the suite's tolerances) in {time.time() - start:.0f} s")
    if missing:
        raise SystemExit("sections that could not be made: " + ", ".join(missing))
    if failed and args.strict:
        raise SystemExit("sections outside the suite's tolerances: " + ", ".join(failed))


if __name__ == "__main__":
    main()
