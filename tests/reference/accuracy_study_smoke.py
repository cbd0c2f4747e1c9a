#!/usr/bin/python3
"""scripts/accuracy_study.py on its first level of the force-driven Cook's membrane: every method
gives a row (Q8 on the adapted cloud's boxes, and the cloud refined between increments from
twice the file's spacing and from the file's own cloud, every increment or the first only,
too), the first-increment runs estimate no later increment, and CalculiX's error is the tip deflection's,
the coarsest recipe mesh against the finest, as the committed curves give it; the report made
again from runs.csv (--report-only) bounds each ratio by CalculiX's finest run, which stays above
1% on this level.

    accuracy_study_smoke.py MESHFREE OUT
"""
import csv
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
meshfree, out = sys.argv[1], Path(sys.argv[2])
subprocess.run([sys.executable, str(ROOT / "scripts" / "accuracy_study.py"), "--meshfree", meshfree,
                "--problems", "cook_membrane_force", "--levels", "1", "--out", str(out)],
               check=True)
with open(out / "runs.csv", newline="") as f:
    rows = {r["method"]: r for r in csv.DictReader(f)}
methods = {"meshfree", "meshfree_vci", "fem", "meshfree_adaptive", "meshfree_vci_adaptive",
           "meshfree_vci_every", "meshfree_vci_every_file", "meshfree_vci_first",
           "meshfree_vci_first_file", "fem_adapted", "calculix"}
if set(rows) != methods:
    sys.exit(f"FAIL: methods {sorted(rows)}, expected {sorted(methods)}")
ref_dir = ROOT / "reference" / "calculix_plastic" / "cook_membrane_force"
with open(ref_dir / "curve.csv", newline="") as f:
    fine = [float(r["uy_48_60"]) for r in csv.DictReader(f)]
with open(ref_dir / "curve_level0.csv", newline="") as f:
    coarse = [float(r["uy_48_60"]) for r in csv.DictReader(f)]
expected = max(abs(a - b) for a, b in zip(coarse, fine)) / max(abs(v) for v in fine)
got = float(rows["calculix"]["error"])
if abs(got - expected) > 1e-6 * expected:
    sys.exit(f"FAIL: CalculiX's error {got:.6e}, the committed curves give {expected:.6e}")
for m in methods:
    if not 0 < float(rows[m]["error"]) < 0.1:
        sys.exit(f"FAIL: {m}: error {rows[m]['error']} outside (0, 0.1) on the first level")
# until: 1 ends the estimates after the first increment; the every-increment run goes on past it.
for m in ("meshfree_vci_first", "meshfree_vci_first_file", "meshfree_vci_every"):
    level = rows[m]["level"]
    summary = json.loads((out / f"cook_membrane_force_{m}_{level}" / "summary.json").read_text())
    a = summary["results"]["adaptivity"]
    estimated = set(a["passes"]["increment"])
    if m == "meshfree_vci_every":
        if max(estimated) <= 1:
            sys.exit(f"FAIL: {m}: no increment past the first estimated")
    elif a["ended"] != "until reached" or estimated != {1}:
        sys.exit(f"FAIL: {m}: refinement ended '{a['ended']}', increments estimated "
                 f"{sorted(estimated)}; expected 'until reached' after increment 1 alone")
# The report again from runs.csv alone (--report-only), for every problem the study knows: the
# two it did not run are reported as not reached, and on this first level CalculiX (3.9% off)
# is above 1%, so every method that reached 1% has its ratio to CalculiX as a bound ("<" its
# finest run's time).
(out / "reach.csv").unlink()
subprocess.run([sys.executable, str(ROOT / "scripts" / "accuracy_study.py"), "--out", str(out),
                "--report-only"], check=True, stdout=subprocess.DEVNULL)
with open(out / "reach.csv", newline="") as f:
    reach = list(csv.DictReader(f))
cook = [r for r in reach if r["problem"] == "cook_membrane_force" and float(r["target"]) == 0.01]
if {r["method"] for r in cook} != methods:
    sys.exit(f"FAIL: the report's methods {sorted(r['method'] for r in cook)}")
if next(r for r in cook if r["method"] == "calculix")["note"] != "not reached":
    sys.exit("FAIL: CalculiX's first level is above 1%, the report says it reached it")
reached = [r for r in cook if r["method"] != "calculix" and r["note"] != "not reached"]
if not reached:
    sys.exit("FAIL: no method reached 1% on the first level")
for r in reached:
    bound = float(rows["calculix"]["wall_s"])
    if not r["ratio_to_calculix"].startswith("<") or \
            abs(float(r["ratio_to_calculix"][1:]) - float(r["wall_s"]) / bound) > 2e-3:
        sys.exit(f"FAIL: {r['method']}: ratio {r['ratio_to_calculix']!r}, expected "
                 f"<{float(r['wall_s']) / bound:.3f} (CalculiX's finest run, {bound:.2f} s)")
others = [r for r in reach if r["problem"] != "cook_membrane_force"]
if not others or any(r["note"] != "not reached" for r in others):
    sys.exit("FAIL: problems the study did not run are not all reported as not reached")
print(f"ok: {len(methods)} methods; CalculiX's tip error {got:.4e} as the committed curves give it")
