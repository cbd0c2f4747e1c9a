#!/usr/bin/env python3
"""Remake the CalculiX reference of the staged_strip_blast preload.

    /usr/bin/python3 reference/calculix_plastic/staged_strip/make_reference.py          # full
    /usr/bin/python3 reference/calculix_plastic/staged_strip/make_reference.py --quick  # check

Full: CPE8 on the meshes N = 16, 32, 64 (elements per 45-degree hole arc)
and CPE8R on N = 32; writes reaction_curve.csv, points.csv, summary.csv of
the finest CPE8 level, the same files of every run under runs/, and
convergence.csv into this folder.  About 40 min on the 2-core machine (N = 64
alone about 30 min).  --quick: remakes N = 8 in a temporary folder
(about 5 s) and compares its reaction curve with runs/N8_CPE8/reaction_curve.csv;
exits 1 if any value differs by more than 1e-6 of its column's largest |value|.
--work DIR runs in DIR (kept) instead of a new temporary folder; a run whose
folder already holds wall_s.txt (written when ccx finished) is not repeated.
Needs ccx (CalculiX 2.20) on the PATH and python3 with numpy.  CalculiX runs
single-threaded (OMP_NUM_THREADS=1): its output is then bit-reproducible.
"""

import csv
import os
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import mesh_and_deck  # noqa: E402

LEVELS = [(16, "CPE8"), (32, "CPE8"), (64, "CPE8"), (32, "CPE8R")]
REFERENCE = (64, "CPE8")
QUICK = (8, "CPE8")


def run(n, element, work):
    tag = "N%d_%s" % (n, element)
    d = os.path.join(work, tag)
    os.makedirs(d, exist_ok=True)
    job = os.path.join(d, "staged_strip")
    mesh_and_deck.write_deck(job + ".inp", n, element)
    done = os.path.join(d, "wall_s.txt")
    if os.path.exists(done):      # --work DIR: a finished run of this deck is kept
        wall = float(open(done).read())
    else:
        env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1")
        t0 = time.time()
        with open(job + ".log", "w") as log:
            rc = subprocess.run(["ccx", "-i", "staged_strip"], cwd=d, env=env,
                                stdout=log, stderr=subprocess.STDOUT).returncode
        wall = time.time() - t0
        if rc != 0 or "*ERROR" in open(job + ".log").read():
            raise SystemExit("ccx failed for %s, see %s.log" % (tag, job))
        with open(done, "w") as f:
            f.write("%.1f\n" % wall)
    out = os.path.join(d, "out")
    subprocess.run([sys.executable, os.path.join(HERE, "extract.py"), job, out], check=True,
                   stdout=subprocess.DEVNULL)
    iters = sum(int(s.split()[3]) for s in open(job + ".sta") if s.split()[:1] == ["1"])
    print("%s: ccx %.1f s, %d Newton iterations" % (tag, wall, iters), flush=True)
    return tag, out, job, wall, iters


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def summary(out):
    return {r["quantity"]: r["value"] for r in read_csv(os.path.join(out, "summary.csv"))}


def curve_diff(ref_curve, out):
    """Largest difference over all increments from the reference curve: the
    force divided by its largest |value|, and the largest of the monitor
    displacements, each divided by its own largest |value| (monitors that
    are zero by the boundary conditions left out)."""
    cur = read_csv(os.path.join(out, "reaction_curve.csv"))
    res = []
    for cols in (["force_top"], [c for c in ref_curve[0] if c.startswith("u")]):
        worst = 0.0
        for c in cols:
            scale = max(abs(float(r[c])) for r in ref_curve)
            if scale < 1e-12:
                continue
            worst = max(worst, max(abs(float(a[c]) - float(b[c])) for a, b in zip(ref_curve, cur))
                        / scale)
        res.append(worst)
    return res


def quick():
    work = tempfile.mkdtemp(prefix="staged_strip_quick_")
    try:
        _tag, out, _job, _w, _i = run(QUICK[0], QUICK[1], work)
        new = read_csv(os.path.join(out, "reaction_curve.csv"))
        old = read_csv(os.path.join(HERE, "runs", "N8_CPE8", "reaction_curve.csv"))
        worst = 0.0
        for col in old[0]:
            scale = max(abs(float(r[col])) for r in old) or 1.0
            worst = max(worst, max(abs(float(a[col]) - float(b[col])) / scale
                                   for a, b in zip(old, new)))
        print("quick check: max relative difference %.3e" % worst)
        return 0 if worst <= 1e-6 and len(old) == len(new) else 1
    finally:
        shutil.rmtree(work, ignore_errors=True)


def main():
    if "--quick" in sys.argv:
        sys.exit(quick())
    if "--work" in sys.argv:
        work = sys.argv[sys.argv.index("--work") + 1]
    else:
        work = tempfile.mkdtemp(prefix="staged_strip_")
    results = {}
    for n, element in [QUICK] + LEVELS:
        tag, out, job, wall, iters = run(n, element, work)
        results[(n, element)] = (tag, out, wall, iters)
        dst = os.path.join(HERE, "runs", tag)
        os.makedirs(dst, exist_ok=True)
        for name in ("reaction_curve.csv", "points.csv", "summary.csv"):
            shutil.copy(os.path.join(out, name), dst)
    ref_tag, ref_out, _w, _i = results[REFERENCE]
    for name in ("reaction_curve.csv", "points.csv", "summary.csv"):
        shutil.copy(os.path.join(ref_out, name), HERE)
    ref = summary(ref_out)
    cols = ["run", "n", "element", "hole_edge_size", "elements", "nodes", "ccx_s",
            "newton_iterations", "force_end", "rel_diff_force_end", "peeq_max_node",
            "rel_diff_peeq_max_node", "peeq_max_ip", "plastic_area_fraction_ip",
            "net_section_plastic_x_max_ip", "max_rel_diff_force_curve", "max_rel_diff_monitors"]
    ref_curve = read_csv(os.path.join(ref_out, "reaction_curve.csv"))
    with open(os.path.join(HERE, "convergence.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for (n, element), (tag, out, wall, iters) in results.items():
            s = summary(out)
            w.writerow([tag, n, element, "%.4e" % (0.25 * 3.141592653589793 * 0.05 / n),
                        s["elements"], s["nodes"], "%.1f" % wall, iters, s["force_top_at_v_end"],
                        "%.3e" % (float(s["force_top_at_v_end"]) / float(ref["force_top_at_v_end"]) - 1),
                        s["peeq_max_node"],
                        "%.3e" % (float(s["peeq_max_node"]) / float(ref["peeq_max_node"]) - 1),
                        s["peeq_max_ip"], s["plastic_area_fraction_ip"],
                        s["net_section_plastic_x_max_ip"]]
                       + ["%.3e" % v for v in curve_diff(ref_curve, out)])
    print("reference: %s; work folder %s (delete it when done)" % (ref_tag, work))


if __name__ == "__main__":
    main()
