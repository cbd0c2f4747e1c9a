#!/usr/bin/python3
"""Regenerates comparisons the test suite asserts, from fresh runs and the reference data in
reference/, as one self-contained HTML page (PNG plots embedded, no network):

- CalculiX load-displacement curves of perforated_strip and cook_membrane (scripts/compare.py),
- LAMMPS's peri/pmb disk impact: indenter force and damaged particles
  (tests/pd_disk_impact_vs_lammps.py),
- Timoshenko cantilever and Kirsch plate convergence (scripts/convergence_study.py).

    scripts/verification_report.py [--meshfree build/meshfree] [--out out/verification] [--quick]

--quick (the suite's smoke test) runs the perforated strip with the meshfree discretisation only
(Cook's membrane takes the same path at three times the cost), the first 250 steps of the disk
impact and the three coarsest spacings of each convergence study; the page says so.
Exit 1 if a section could not be made (the page is written with its error).
"""
import argparse
import base64
import html
import sys
import time
import traceback
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
sys.path.insert(0, str(ROOT / "tests"))
import compare as calculix  # noqa: E402  scripts/compare.py
import convergence_study  # noqa: E402
import pd_disk_impact_vs_lammps as disk  # noqa: E402

CALCULIX_PROBLEMS = ["perforated_strip", "cook_membrane"]


def image(path):
    data = base64.b64encode(Path(path).read_bytes()).decode()
    return f'<img src="data:image/png;base64,{data}" alt="{html.escape(Path(path).name)}">'


def table(header, rows):
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in r) + "</tr>"
                   for r in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def calculix_section(problem, args, out):
    methods = ["meshfree"] if args.quick else ["meshfree", "fem"]
    runs = {m: calculix.run(problem, m, str(out), args.meshfree) for m in methods}
    worst = calculix.compare(problem, runs, str(out))
    rows = [(m, label, f"{d:.3e}") for (m, label), d in worst.items()]
    return (f"<p>Largest difference from the converged CalculiX curve, over its points, divided "
            f"by the largest |CalculiX| value (reference/calculix_plastic/{problem}).</p>"
            + table(["discretisation", "quantity", "difference"], rows)
            + image(out / f"{problem}.png"))


def disk_section(args, out):
    folder = out / "pd_disk_impact"
    disk.run(args.meshfree, ROOT, folder, steps=250 if args.quick else None)
    c = disk.compare(ROOT, folder, verbose=False)
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
    fig.savefig(out / "pd_disk_impact.png", dpi=100)
    plt.close(fig)
    rows = [("largest indenter-force difference / LAMMPS peak", f"{c['force_error']:.2e}"),
            ("peak force difference", f"{c['peak_error']:.2e}"),
            ("damaged-particle count, largest relative difference", f"{c['worst_damage']:.2e}"),
            ("energy balance to step 150", f"{c['early_balance']:.2e}")]
    return (f"<p>Steps compared: {len(c['steps'])} (reference/lammps/disk_impact).</p>"
            + table(["measure", "value"], rows) + image(out / "pd_disk_impact.png"))


def convergence_section(args, out):
    fig_rows, rows = {}, []
    for problem, spacings in convergence_study.STUDIES.items():
        spacings = spacings[:3] if args.quick else spacings
        h, l2, en, rate_l2, rate_en, _ = convergence_study.run_study(args.meshfree, out, problem, spacings)
        fig_rows[problem] = (h, l2, en, rate_l2, rate_en)
        rows.append((problem, len(h), f"{h[-1]:g}", f"{l2[-1]:.2e}", f"{en[-1]:.2e}",
                     f"{rate_l2:.2f}", f"{rate_en:.2f}"))
    convergence_study.plot(fig_rows, out / "convergence.png")
    return (table(["problem", "spacings", "finest h", "L2 error", "energy error", "L2 rate",
                   "energy rate"], rows) + image(out / "convergence.png"))


def page(sections, quick, seconds):
    parts = []
    for title, body in sections:
        parts.append(f"<h2>{html.escape(title)}</h2>{body}")
    mode = ("quick mode: the strip meshfree only, 250 disk-impact steps, three spacings per study"
            if quick else "full")
    return ("<!DOCTYPE html><html><head><meta charset='utf-8'><title>meshfree verification"
            "</title><style>body{font-family:sans-serif;max-width:1150px;margin:auto}"
            "img{max-width:100%}table{border-collapse:collapse;margin:0.5em 0}"
            "td,th{border:1px solid #bbb;padding:2px 8px}pre{color:#a00}</style></head><body>"
            f"<h1>meshfree verification report</h1><p>{mode}; made in {seconds:.0f} s.</p>"
            + "".join(parts) + "</body></html>")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshfree", default=str(ROOT / "build" / "meshfree"))
    ap.add_argument("--out", default=str(ROOT / "out" / "verification"))
    ap.add_argument("--quick", action="store_true", help="the suite's smoke test (under a minute)")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    start = time.time()
    problems = CALCULIX_PROBLEMS[:1] if args.quick else CALCULIX_PROBLEMS
    makers = [(f"CalculiX: {p}", lambda p=p: calculix_section(p, args, out)) for p in problems]
    makers += [("LAMMPS: peridynamic disk impact", lambda: disk_section(args, out)),
               ("Convergence against exact solutions", lambda: convergence_section(args, out))]
    sections, failed = [], []
    for title, make in makers:
        try:
            sections.append((title, make()))
        except (Exception, SystemExit) as e:  # compare.py reports a failed run as SystemExit
            failed.append(title)
            sections.append((title, f"<pre>{html.escape(''.join(traceback.format_exception_only(type(e), e)))}</pre>"))
    report = out / "report.html"
    report.write_text(page(sections, args.quick, time.time() - start))
    print(f"wrote {report} ({len(sections) - len(failed)} of {len(sections)} sections)")
    if failed:
        raise SystemExit("sections that failed: " + ", ".join(failed))


if __name__ == "__main__":
    main()
