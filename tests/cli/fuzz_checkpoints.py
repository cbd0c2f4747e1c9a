#!/usr/bin/env python3
"""Mutated checkpoints against `meshfree run --restart`: every mutant is refused cleanly (exit 2,
one line on stderr starting "meshfree: --restart ", nothing written into the folder) or restarted
to completion (exit 0, "completed"), within 60 seconds; never a crash, a hang, exit 1 or a
second line.

Two checkpoints of the LAMMPS disk impact (problems/pd_disk_impact.yaml) are made once: the run's
own and one of another spacing (a foreign one). Each mutant is a copy of the own checkpoint with
one of: the state file cut short at a random length; a random bit of the file flipped; a random
bit of a random dataset's values flipped; a random dataset replaced by the foreign checkpoint's
(checksum and all); a random dataset replaced by values of another length or other values, with
a checksum that matches (a forged file: lengths anywhere, values in the header and the loop's
schedule); the marker naming another generation. Restarts end
shortly after the checkpoint (time.end may change on restart), so a mutant that is accepted runs
a few steps. The seed changes every day (the UTC date, 20261127 on 27 November 2026) unless
--seed is given; it is printed first, so that a failure is reproduced by --seed and its number; a
failing mutant's folder goes to OUT/mutant_<n> with its output. An exception in this script while
a mutant is made or judged is a failure of that mutant. JOBS restarts run at once (default: 4 per
core: most of a short restart's time is spent starting MPI and reading, not computing).
Usage: fuzz_checkpoints.py MESHFREE SOURCE_DIR [--count N] [--seed S] [--out DIR] [--jobs J]
"""
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import traceback
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fuzz_support import arguments, fnv, parse  # noqa: E402

SETS = ["--set", "output.checkpoint_interval=1.0e-5"]
ONE_THREAD = dict(os.environ, OMP_NUM_THREADS="1")


def generation(folder):
    try:
        return int(open(folder / "checkpoint" / "checkpoint.txt").read().split()[1])
    except (OSError, IndexError, ValueError):
        return 0


def make_checkpoint(meshfree, problem, folder, extra):
    """A run killed once its second checkpoint is in place."""
    p = subprocess.Popen([meshfree, "run", problem, "--out", str(folder)] + SETS + extra,
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=ONE_THREAD)
    for _ in range(30000):
        if generation(folder) >= 2 or p.poll() is not None:
            break
        time.sleep(0.01)
    p.kill()
    p.wait()
    if generation(folder) < 2:
        sys.exit("no checkpoint was written in %s" % folder)


def datasets(f):
    names = []
    f.visit(lambda n: names.append(n) if isinstance(f[n], h5py.Dataset) else None)
    return sorted(names)


def forge(f, name, values):
    """Replaces a dataset by `values`, with a checksum that matches them."""
    del f[name]
    f.create_dataset(name, data=values)
    f[name].attrs.create("fnv1a64", fnv(values.tobytes()), dtype="u8")


def mutate(folder, foreign, rng):
    """Mutates the checkpoint in `folder`; returns what was done."""
    g = generation(folder)
    state = folder / "checkpoint" / ("state-%d.0.h5" % g)
    kind = rng.randrange(6)
    if kind == 0:
        size = state.stat().st_size
        n = rng.randrange(size)
        os.truncate(state, n)
        return "cut to %d of %d bytes" % (n, size)
    if kind == 1:
        data = bytearray(state.read_bytes())
        at, bit = rng.randrange(len(data)), rng.randrange(8)
        data[at] ^= 1 << bit
        state.write_bytes(bytes(data))
        return "bit %d of byte %d flipped" % (bit, at)
    with h5py.File(state, "r+") as f:
        names = datasets(f)
        name = rng.choice(names)
        d = f[name]
        if kind == 2 and d.size > 0:
            offset = d.id.get_offset()
            nbytes = d.size * d.dtype.itemsize
            f.close()
            data = bytearray(state.read_bytes())
            at, bit = offset + rng.randrange(nbytes), rng.randrange(8)
            data[at] ^= 1 << bit
            state.write_bytes(bytes(data))
            return "bit %d of '%s' flipped" % (bit, name)
        if kind == 3:
            fg = generation(foreign)
            with h5py.File(foreign / "checkpoint" / ("state-%d.0.h5" % fg), "r") as other:
                if name in other:
                    del f[name]
                    other.copy(other[name], f, name)
                    return "'%s' from the foreign checkpoint" % name
            return "nothing (the foreign checkpoint has no '%s')" % name
        how = rng.randrange(4)
        if how >= 2:  # values forged only in the header and the loop's schedule: elsewhere a
            # forged value is a state the physics may take on or fail with, not a foreign file
            name = rng.choice([n for n in names if n.startswith(("meta.", "loop.", "count."))])
            d = f[name]
        values = np.atleast_1d(d[()])
        if how == 0 and values.size > 1:
            values = values[:rng.randrange(values.size)]
            what = "shortened"
        elif how == 1:
            values = np.concatenate([values, values[:1] if values.size else np.zeros(1, d.dtype)])
            what = "lengthened"
        elif how == 2 and values.size and values.dtype.kind == "f":
            values = values.copy()
            values[rng.randrange(values.size)] = rng.choice([np.nan, np.inf, -1e300, 1e300, -1.0])
            what = "a value made extreme"
        else:
            values = values.copy()
            if values.size:
                k = rng.randrange(values.size)
                if values.dtype.kind in "iu":
                    info = np.iinfo(values.dtype)
                    values[k] = rng.choice([-1, 0, info.max, info.min])
                else:
                    values[k] = values[k] * 1.5
            what = "a value changed"
        forge(f, name, values.astype(d.dtype))
        return "'%s' %s, checksum forged" % (name, what)
    # kind 5: the marker names another generation.
    (folder / "checkpoint" / "checkpoint.txt").write_text("generation %d\n" % rng.choice([g - 1, g + 1, 10**18]))
    return "marker changed"


def listing(folder):
    out = []
    for root, dirs, files in os.walk(folder):
        for n in sorted(dirs + files):
            p = Path(root) / n
            st = p.lstat()
            out.append((str(p), st.st_size, st.st_mtime_ns))
    return sorted(out)


def restart(meshfree, problem, folder, end):
    args = [meshfree, "run", problem, "--restart", str(folder)] + SETS + ["--set", "time.end=%r" % end]
    try:
        p = subprocess.run(args, capture_output=True, timeout=60, env=ONE_THREAD)
        return p.returncode, p.stderr.decode(errors="replace")
    except subprocess.TimeoutExpired as e:
        return "timeout", (e.stderr or b"").decode(errors="replace") if isinstance(e.stderr, bytes) else str(e.stderr)


def judge(rc, err, before, after, folder):
    lines = [l for l in err.split("\n") if l.strip() and not l.startswith("[meshfree] warning")]
    if rc == 2:
        if len(lines) != 1 or not lines[0].startswith("meshfree: --restart "):
            return "refused without one '--restart' line: %r" % err[-400:]
        if before != after:
            return "refused, but the folder changed"
        return None
    if rc == 0:
        return None if '"status": "completed"' in (folder / "summary.json").read_text() \
            else "exit 0 without a completed summary"
    if isinstance(rc, int) and rc < 0:
        return "killed by signal %d: %s" % (-rc, err[-400:])
    return "exit %s: %s" % (rc, err[-400:])


def main():
    a = parse(arguments(__doc__))
    problem = str(Path(a.source) / "problems" / "pd_disk_impact.yaml")
    work = Path(tempfile.mkdtemp(prefix="fuzz_checkpoints_"))
    try:
        own, foreign = work / "own", work / "foreign"
        make_checkpoint(a.meshfree, problem, own, [])
        make_checkpoint(a.meshfree, problem, foreign, ["--set", "discretisation.spacing=0.0006"])
        with h5py.File(own / "checkpoint" / ("state-%d.0.h5" % generation(own)), "r") as f:
            t = float(f["meta.time"][0])
        end = t + 3e-7  # three steps past the checkpoint

        def one(n):
            rng = random.Random(a.seed * 100003 + n)
            folder = work / ("m%d" % n)
            what, rc, err = "(not made)", None, ""
            try:
                shutil.copytree(own / "checkpoint", folder / "checkpoint", symlinks=True)
                what = mutate(folder, foreign, rng)
                before = listing(folder)
                rc, err = restart(a.meshfree, problem, folder, end)
                failure = judge(rc, err, before, listing(folder), folder)
            except Exception:
                err = traceback.format_exc()
                failure = "exception in the fuzzer: " + err.strip().split("\n")[-1]
            if failure and a.out:
                keep = Path(a.out) / ("mutant_%d" % n)
                shutil.rmtree(keep, ignore_errors=True)
                shutil.copytree(folder, keep, symlinks=True)
                (keep / "output.txt").write_text("%s\nexit %s\n%s" % (what, rc, err))
            shutil.rmtree(folder, ignore_errors=True)
            return n, what, rc, failure

        outcomes = {"refused": 0, "restarted": 0}
        failures = []
        with ThreadPoolExecutor(a.jobs) as pool:
            for n, what, rc, failure in pool.map(one, range(a.count)):
                if failure:
                    failures.append((n, what, failure))
                    print("FAIL mutant %d (%s): %s" % (n, what, failure), flush=True)
                else:
                    outcomes["refused" if rc == 2 else "restarted"] += 1
        print("seed %d: %d mutants: %d refused cleanly, %d restarted to completion, %d failures"
              % (a.seed, a.count, outcomes["refused"], outcomes["restarted"], len(failures)))
        return 1 if failures else 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
