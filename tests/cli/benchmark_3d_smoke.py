#!/usr/bin/python3
"""The 3D paths of the scaling study and of the cost comparison, on small sizes (about 35 s).

- scripts/benchmark_implicit.py --quick on the 3D cases (meshfree box, hex8, hex20) on
  multigrid under a cap of 0.08 GB above the program's own baseline (whatever the machine's
  baseline is: 34 MiB on one, 113 MB on another): hex8 runs both sizes (its second predicted at
  about 0.06 GB above the baseline) and its CG iterations at the larger stay within 30% of those
  at the smaller (criteria.csv); the box's and hex20's second sizes (predicted at about 0.26 and
  0.10 GB above it) are not run, and predicted.csv gives for each the baseline plus the bytes per
  DOF above it of the case's first run times the size.
- scripts/thick_plate_cost.py on the first 2 increments, meshfree at spacing 1: the CalculiX
  level it times is as close to the converged curve as meshfree's run, each code ran once (the
  study's repeats are its own business: here one meshfree run is 27 s of the test's 35), and the
  DOFs are those of the meshes (3 x the nodes of the recipe's n = 2 mesh: 381).

    benchmark_3d_smoke.py MESHFREE ROOT
"""
import csv
import os
import subprocess
import sys
import tempfile

MESHFREE, ROOT = sys.argv[1], sys.argv[2]
CAP_GB = 0.08  # above the baseline: hex8's second size needs about 0.06, hex20's 0.10
failed = False


def check(ok, message):
    global failed
    failed |= not ok
    print(f"{'ok' if ok else 'FAIL'}: {message}", flush=True)


def rows_of(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def script(name, args):
    cmd = [sys.executable, os.path.join(ROOT, "scripts", name), "--meshfree", MESHFREE] + args
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(done.stdout[-3000:])
    return done.returncode


with tempfile.TemporaryDirectory() as work:
    out = os.path.join(work, "scaling")
    rc = script("benchmark_implicit.py", ["--out", out, "--quick", "--cases", "box", "hex8", "hex20",
                                          "--layouts", "1x2", "--solvers", "multigrid",
                                          "--max-added-memory-gb", str(CAP_GB)])
    check(rc == 0, f"benchmark_implicit.py on the 3D cases exited {rc}")
    runs = rows_of(os.path.join(out, "runs.csv"))
    count = {c: sum(r["case"] == c for r in runs) for c in ("box", "hex8", "hex20")}
    check(count == {"box": 1, "hex8": 2, "hex20": 1},
          f"sizes run under the cap of {CAP_GB} GB above the baseline: {count} "
          "(box 1, hex8 2, hex20 1)")
    predicted = {p["case"]: p for p in rows_of(os.path.join(out, "predicted.csv"))}
    for case in ("box", "hex20"):
        first = next((r for r in runs if r["case"] == case), None)
        p = predicted.get(case)
        if first is None or p is None:
            check(False, f"{case}: {'no run' if first is None else 'no prediction'} at 1e4 DOFs")
            continue
        baseline, added = float(p["baseline_bytes"]), float(first["added_bytes_per_dof"])
        expected = baseline + added * 1e4
        check(abs(float(p["predicted_peak_bytes"]) / expected - 1) < 1e-5
              and expected - baseline > CAP_GB * 1e9,
              f"{case} at 1e4 DOFs not run, predicted at {expected / 1e9:.3f} GB: the baseline "
              f"{baseline / 1e6:.0f} MB and {added:.0f} bytes per DOF above it")
    hex8 = [c for c in rows_of(os.path.join(out, "criteria.csv")) if c["case"] == "hex8"]
    check(len(hex8) == 1 and abs(float(hex8[0]["iterations_ratio"]) - 1) <= 0.3
          and hex8[0]["iterations_ok"] == "True",
          "hex8's CG iterations: " + (f"{hex8[0]['iterations_from']} at {hex8[0]['dofs_from']} "
                                      f"DOFs, {hex8[0]['iterations_to']} at {hex8[0]['dofs_to']}"
                                      if hex8 else "no criteria row"))

    out = os.path.join(work, "cost")
    rc = script("thick_plate_cost.py", ["--out", out, "--increments", "2", "--levels", "2", "3",
                                        "--repeats", "1", "--set", "discretisation.spacing=1.0"])
    check(rc == 0, f"thick_plate_cost.py exited {rc}")
    table = {r["code"]: r for r in rows_of(os.path.join(out, "table.csv"))}
    mf, ccx = table.get("meshfree"), table.get("CalculiX")
    check(mf is not None and ccx is not None
          and float(ccx["force_error"]) <= float(mf["force_error"]) < 0.01,
          "CalculiX's timed level within meshfree's force error: "
          + (f"{float(ccx['force_error']):.3%} <= {float(mf['force_error']):.3%}"
             if mf and ccx else "rows missing"))
    check(bool(mf and ccx) and ccx["dofs"] == "381" and all(len(r["wall_s"].split()) == 1
                                                            for r in (mf, ccx)),
          "CalculiX on n = 2 (381 DOFs), one timed run of each code")
sys.exit(1 if failed else 0)
