#!/usr/bin/env python3
"""Mutated problem files against `meshfree check`: every mutant is accepted (exit 0) or refused
cleanly (exit 2 with one line on stderr, "meshfree: ...", of at most 400 characters), within 60
CPU seconds (check builds the set-up a run builds, and a mutated size that is still valid can make it
large: tens of millions of bonds), never with a crash, a hang or another exit code.

The mutants are drawn from every problems/*.yaml with a fixed seed unless --seed is given (the
suite's runs; scripts/fuzz_nightly.sh gives --seed today, the UTC date, 20261127 on 27 November
2026); the seed is printed first, so that a failure is reproduced by --seed and its number: a number replaced by an extreme or wrong value, a line deleted, doubled or moved,
a key renamed, stray characters inserted, the file cut short. A failing mutant is written to
OUT/mutant_<n>.yaml with its output.

With --run, the mutants of the explicit problems (peridynamics, SPH) are checked and then run,
with a short end time (--set time.end=END, or STEPS of the first time step that check reports,
if sooner): each completes (exit 0, a summary.json of status "completed" and a history.csv whose
numbers are all finite), is refused as input (exit 2, one clean line, nothing written; a mutant
that `check` said was valid must not be refused so), or fails (exit 1, one line "meshfree: run
failed..." on stderr besides the log's "[meshfree] ..." lines, and a failed/summary.json of status
"failed"), within 60 CPU seconds. The bodies are made smaller first: every `spacing:` of a problem is
doubled where `check` still finds it valid (1/8 of the particles in 3D), since a short run's cost
is its set-up, the bonds and neighbours of every particle.

Any other outcome is a failure: a signal (a crash), its CPU time used up, a hang (no end after
10 minutes of wall time: a limit that no load reaches), another exit status, a
message of more than one line, files written on exit 2, or an exception in this script.
JOBS processes run at once (default: 4 per core: most of a short run's time is spent starting
MPI and writing, not computing).
Usage: fuzz_inputs.py MESHFREE SOURCE_DIR [--count N] [--seed S] [--out DIR] [--jobs J]
                      [--run [--end T] [--steps S]]
"""
import math
import os
import random
import re
import shutil
import sys
import tempfile
import traceback
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fuzz_support import arguments, one_rank_env, parse, run_limited, status  # noqa: E402

CPU_S = 60  # a case's limit of CPU time (one costs 0.04 to 0.13 CPU seconds)

VALUES = ["-1", "0", "1e308", "-1e308", "1e-308", "1e999", ".nan", ".inf", "-.inf",
          "99999999999999999999", "abc", "[]", "{}", "[1, 2, 3, 4]", "''", "null", "true",
          "0x10", "1e30", "-0", "2147483648", "'\\x00'", "\"a\\tb\""]
KEYS = ["E", "spacing", "material", "box", "end", "name", "type", "radius", "x", "zz", "points"]
FIRST_STEP = re.compile(r"(?:first CFL step|time step) ([0-9.]+(?:[eE][-+]?[0-9]+)?)")
SPACING = re.compile(r"^([^#\n]*\bspacing: *)([0-9.eE+-]+)", re.M)
NUMBER = re.compile(r"(?<![\w.])-?\d+(\.\d*)?([eE][-+]?\d+)?(?![\w.])")


def mutate(text, rng):
    lines = text.split("\n")
    kind = rng.randrange(8)
    if kind <= 1:  # a number replaced (twice as often: most keys are numbers)
        spots = [m for m in NUMBER.finditer(text)]
        if spots:
            m = rng.choice(spots)
            return text[:m.start()] + rng.choice(VALUES) + text[m.end():]
    if kind == 2 and len(lines) > 1:  # a line deleted
        del lines[rng.randrange(len(lines))]
    elif kind == 3:  # a line doubled (duplicate keys, duplicate list items)
        k = rng.randrange(len(lines))
        lines.insert(k, lines[k])
    elif kind == 4 and len(lines) > 2:  # a line moved
        line = lines.pop(rng.randrange(len(lines)))
        lines.insert(rng.randrange(len(lines)), line)
    elif kind == 5:  # a key renamed
        keyed = [i for i, l in enumerate(lines) if re.search(r"\w+:", l)]
        if keyed:
            i = rng.choice(keyed)
            lines[i] = re.sub(r"\w+:", rng.choice(KEYS) + ":", lines[i], count=1)
    elif kind == 6:  # stray characters
        at = rng.randrange(len(text) + 1)
        junk = "".join(rng.choice("{}[],:&*!|>'\"#%@`\t\\-?0.e ") for _ in range(rng.randint(1, 4)))
        return text[:at] + junk + text[at:]
    else:  # cut short
        return text[:rng.randrange(len(text) + 1)]
    return "\n".join(lines)


def check(meshfree, path, workdir):
    p = run_limited([meshfree, "check", str(path)], CPU_S, one_rank_env(), cwd=workdir)
    if not isinstance(p.returncode, int) or p.returncode < 0:
        return status(p.returncode), p.stdout, p.stderr
    err_lines = p.stderr.decode(errors="replace").strip().split("\n") if p.stderr.strip() else []
    # Unit-sanity warnings (a mutated number may be implausible) come before the refusal line.
    err_lines = [l for l in err_lines if not l.startswith("[meshfree] warning: ")]
    if p.returncode == 0:
        return None, p.stdout, p.stderr
    if p.returncode != 2:
        return status(p.returncode), p.stdout, p.stderr
    if len(err_lines) != 1 or not err_lines[0].startswith("meshfree: ") or len(err_lines[0]) > 400:
        return "not one clean line on stderr", p.stdout, p.stderr
    return None, p.stdout, p.stderr


def clean_line(stderr, prefix):
    """The one line of stderr that is not the log's, if it starts with `prefix` and is short."""
    lines = [l for l in stderr.decode(errors="replace").strip().split("\n")
             if l and not l.startswith("[meshfree]")]
    return len(lines) == 1 and lines[0].startswith(prefix) and len(lines[0]) <= 2000


def run_mutant(meshfree, path, workdir, end, steps):
    why, stdout, stderr = check(meshfree, path, workdir)
    if why:
        return "check: " + why, stdout, stderr
    valid = b": valid" in stdout
    # A few steps exercise the loop, its output and its failures as well as many: the end time
    # is cut to `steps` of the first step that check reports.
    dt = FIRST_STEP.search(stdout.decode(errors="replace"))
    if dt:
        end = min(end, steps * float(dt.group(1)))
    folder = Path(tempfile.mkdtemp(dir=workdir))
    try:
        return judge_run(meshfree, path, folder / "out", workdir, end, valid)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def completed(out):
    """Why a run that exited 0 did not complete with finite results, or None."""
    summary = out / "summary.json"
    if not summary.exists() or '"status": "completed"' not in summary.read_text(errors="replace"):
        return "exit 0 without a summary.json of status completed"
    history = out / "history.csv"
    if history.exists():
        for row in history.read_text(errors="replace").split("\n")[1:]:
            if row and not all(math.isfinite(float(v)) for v in row.split(",")):
                return "completed with a non-finite value in history.csv: " + row[:200]
    return None


def coarser(text, meshfree, path, workdir):
    """`text` with every spacing doubled, if check finds it valid; else `text`."""
    coarse = SPACING.sub(lambda m: m.group(1) + repr(2 * float(m.group(2))), text)
    path.write_text(coarse)
    try:
        p = run_limited([meshfree, "check", str(path)], CPU_S, one_rank_env(), cwd=workdir)
    finally:
        path.unlink(missing_ok=True)
    return coarse if p.returncode == 0 and b": valid" in p.stdout else text


def judge_run(meshfree, path, out, workdir, end, valid):
    p = run_limited([meshfree, "run", str(path), "--out", str(out), "--set", "time.end=%g" % end],
                    CPU_S, one_rank_env(), cwd=workdir)
    if not isinstance(p.returncode, int) or p.returncode < 0:
        return status(p.returncode), p.stdout, p.stderr
    if p.returncode == 0:
        return completed(out), p.stdout, p.stderr
    if p.returncode == 2:
        if not clean_line(p.stderr, "meshfree: "):
            return "exit 2 without one clean line on stderr", p.stdout, p.stderr
        if out.exists() and any(out.iterdir()):
            return "exit 2 with files written", p.stdout, p.stderr
        if valid:
            return "'valid' from check, then refused by run", p.stdout, p.stderr
        return None, p.stdout, p.stderr
    if p.returncode != 1:
        return status(p.returncode), p.stdout, p.stderr
    summary = out / "failed" / "summary.json"
    if not clean_line(p.stderr, "meshfree: run failed"):
        return "exit 1 without one line 'meshfree: run failed'", p.stdout, p.stderr
    if not summary.exists() or '"status": "failed"' not in summary.read_text(errors="replace"):
        return "exit 1 without failed/summary.json of status failed", p.stdout, p.stderr
    return None, p.stdout, p.stderr


def main():
    ap = arguments(__doc__)
    ap.add_argument("--run", action="store_true")
    ap.add_argument("--end", type=float, default=1e-5)
    ap.add_argument("--steps", type=float, default=3)
    a = parse(ap)
    a.meshfree = os.path.abspath(a.meshfree)
    source = Path(a.source).resolve()
    # Not the mutants another fuzzer is writing beside them (".fuzz_*").
    bases = sorted(b for b in (source / "problems").glob("*.yaml") if not b.name.startswith("."))
    if a.run:
        bases = [b for b in bases if b.name.startswith(("pd_", "sph_"))]
    rng = random.Random(a.seed)
    work = Path(tempfile.mkdtemp())
    out = Path(a.out) if a.out else work / "failures"
    texts = {b: b.read_text() for b in bases}
    if a.run:
        texts = {b: coarser(t, a.meshfree, b.parent / (".fuzz_%d_%s" % (os.getpid(), b.name)), work)
                 for b, t in texts.items()}
    jobs = []
    for n in range(a.count):
        base = rng.choice(bases)
        text = texts[base]
        for _ in range(rng.choice([1, 1, 1, 2, 3])):
            text = mutate(text, rng)
        # Beside the original, so that relative paths (meshes, load tables) resolve as there; named
        # by this process too, as another fuzzer may be writing beside it.
        path = base.parent / (".fuzz_%d_%d_%s" % (os.getpid(), n, base.name))
        jobs.append((n, base, path, text))
    failures, refused, failed_cleanly = [], 0, 0

    def run(job):
        n, base, path, text = job
        case = work / ("case%d" % n)  # its working folder
        try:
            case.mkdir()
            path.write_text(text, errors="replace")
            if a.run:
                return n, base, text, run_mutant(a.meshfree, path, case, a.end, a.steps)
            return n, base, text, check(a.meshfree, path, case)
        except Exception:  # the fuzzer's own error is a failure of the case, not of the run
            return n, base, text, ("exception in the fuzzer", b"",
                                   traceback.format_exc().encode())
        finally:
            path.unlink(missing_ok=True)
            shutil.rmtree(case, ignore_errors=True)

    with ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        for n, base, text, (why, stdout, stderr) in pool.map(run, jobs):
            if why:
                failures.append(n)
                out.mkdir(parents=True, exist_ok=True)
                (out / ("mutant_%d.yaml" % n)).write_text(text, errors="replace")
                (out / ("mutant_%d.txt" % n)).write_bytes(stdout + b"\n--- stderr ---\n" + stderr)
                print("FAIL mutant %d of %s: %s: %s" % (n, base.name, why,
                      stderr.decode(errors="replace").strip()[:300]))
            elif b"meshfree: run failed" in stderr:
                failed_cleanly += 1
            elif b"meshfree: " in stderr:
                refused += 1
    if not failures or a.out:
        shutil.rmtree(work, ignore_errors=True)
    print("seed %d: %d mutants of %d problem files: %d refused cleanly, %d %s, %s%d failures%s"
          % (a.seed, a.count, len(bases), refused,
             a.count - refused - failed_cleanly - len(failures),
             "completed" if a.run else "accepted",
             "%d failed cleanly (exit 1), " % failed_cleanly if a.run else "",
             len(failures), " (in %s)" % out if failures else ""))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
