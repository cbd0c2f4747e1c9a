"""The buried-tunnel study (scripts/tunnel_study.py): its arrival table beside the thesis', the
plots, and whether the trends problems/sph_tunnel/README.md reports hold in this run."""
import csv
import subprocess
import sys

import tunnel_study

from verification.page import Section, image, markdown, table

# Quick mode: the suite's smoke case (spacing 0.5 m, half the run time) at two depths.
QUICK = ["--cases", "10:500,20:500", "--spacing", "0.5", "--end-scale", "0.5"]


def tunnel_section(ctx):
    folder = ctx.out / "tunnel_study"
    subprocess.run([sys.executable, str(ctx.root / "scripts" / "tunnel_study.py"), "--meshfree",
                    ctx.meshfree, "--out", str(folder)] + (QUICK if ctx.quick else []),
                   check=True, capture_output=True)
    trends = tunnel_study.trends(list(csv.DictReader(open(folder / "results.csv"))))
    mode = ("Quick mode: " + " ".join(QUICK) + "; the full study runs the nine cases at 0.25 m. "
            if ctx.quick else "")
    body = (f"<p>{mode}SPH of a concrete lining in dry sand under a TNT surface burst against the "
            "thesis' first-arrival table (x1000) and TM 5-855-1's free field. The suite runs one "
            "case and asserts only that the study writes its outputs; here a section passes when "
            "every trend problems/sph_tunnel/README.md reports holds over the cases run.</p>"
            + table(["trend", "holds"], [(t, "yes" if ok else "NO") for t, ok in trends])
            + image(folder / "arrival_vs_depth.png") + image(folder / "max_von_mises_vs_depth.png")
            + markdown((folder / "table.md").read_text()))
    return Section(body, all(ok for _, ok in trends), "the trends the study reports")
