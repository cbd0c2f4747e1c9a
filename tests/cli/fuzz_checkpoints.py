#!/usr/bin/env python3
"""Mutated checkpoints against `meshfree run --restart`: every mutant is refused cleanly (exit 2,
one line on stderr starting "meshfree: --restart ", nothing written into the folder or wherever a
link in it points) or restarted to completion (exit 0, a summary.json of status "completed", a
history.csv of finite numbers), within 60 CPU seconds; never a crash, a hang, exit 1 or a second
line. A refusal takes at most 2 CPU seconds and 100 MB of peak resident memory beyond a clean
restart's peak: what the program allocates is bounded by what the file holds, not by what a
damaged number in it claims (a flipped bit in a dimension once asked for 16.9 GB).
A mutant that damages what a restart must read (a cut file, a flipped bit in an array's values,
a checksum changed or removed, a dataset removed or renamed, another run's checkpoint, a time
that is not the state's, a marker naming no checkpoint, a link, a FIFO) must be refused; one that
leaves the state as it was (a flipped bit that lands outside the arrays, an attribute added)
may be restarted only to the results of the unchanged checkpoint, bit for bit.

The checkpoints are made once: the run's own of two problems, the blast-loaded slab
(problems/pd_slab_blast.yaml, peridynamics) and Sod's shock tube (problems/sph_sod_tube.yaml,
SPH), and foreign ones: the slab at another spacing, each problem over 2 MPI ranks, and
each problem's checkpoint given to the other. Each mutant is a copy of one own checkpoint with one
of: the state file cut short; a random bit of the file flipped, of an array's values, or of the
HDF5 metadata (outside every array); a checksum attribute removed, changed or joined by another
attribute; a dataset removed or renamed; a dataset replaced by the foreign checkpoint's (checksum
and all); the whole checkpoint replaced by a foreign one, its header (settings and identity)
sometimes copied from the own one so that it claims to be this run's; a dataset replaced by values
of another length or other values with a checksum that matches (a forged file: lengths anywhere,
values in the header and the loop's schedule); the header's time or step moved (into the future,
the past, not finite), its checksum forged; the marker naming another generation or none; and
links: checkpoint/, the state file or the marker a symbolic link to a copy, a FIFO or a folder in
their place, a dangling link. Restarts end three steps after the checkpoint (time.end may change
on restart), so a mutant that is accepted runs a few steps.

The seed is fixed unless --seed is given (scripts/fuzz_nightly.sh gives --seed today, the UTC
date, 20261127 on 27 November 2026); it is printed first, so that a failure is reproduced by --seed and its number; a failing mutant's
folder goes to OUT/mutant_<n> with its output. An exception in this script while a mutant is made
or judged is a failure of that mutant. JOBS restarts run at once (default: 4 per core: most of a
short restart's time is spent starting the program and reading, not computing). --mutations
draws from the named mutations only (flip_metadata, say).
Usage: fuzz_checkpoints.py MESHFREE SOURCE_DIR [--count N] [--seed S] [--out DIR] [--jobs J]
                           [--mutations NAME ...]
"""
import json
import math
import os
import random
import re
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
from fuzz_support import arguments, fnv, one_rank_env, parse, run_limited, status  # noqa: E402

FIRST_STEP = re.compile(r"(?:first CFL step|time step) ([0-9.]+(?:[eE][-+]?[0-9]+)?)")


class Base:
    """A problem whose checkpoint is mutated: its file, the settings every run of it is given,
    its own checkpoint, the foreign ones, and the history of a restart from the own one."""

    def __init__(self, name, problem, sets):
        self.name, self.problem, self.sets = name, problem, sets
        self.own, self.foreign, self.end, self.reference = None, {}, None, None
        self.peak_bytes = None  # a clean restart's peak resident memory


def generation(folder):
    try:
        return int(open(folder / "checkpoint" / "checkpoint.txt").read().split()[1])
    except (OSError, IndexError, ValueError):
        return 0


def make_checkpoint(meshfree, base, folder, extra=(), ranks=1):
    """A run killed once its second checkpoint is in place."""
    cmd = [meshfree, "run", base.problem, "--out", str(folder)] + base.sets + list(extra)
    env = one_rank_env()
    if ranks > 1:
        cmd = ["mpirun", "-np", str(ranks)] + cmd
        env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_MCA_rmaps_base_oversubscribe="1",
                   OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env,
                         start_new_session=True)
    for _ in range(30000):
        if generation(folder) >= 2 or p.poll() is not None:
            break
        time.sleep(0.01)
    try:
        os.killpg(p.pid, signal.SIGKILL)
    except ProcessLookupError:  # it ended by itself
        pass
    p.wait()
    if generation(folder) < 2:
        sys.exit("no checkpoint was written in %s" % folder)
    return folder


def state_files(folder):
    g = generation(folder)
    return sorted((folder / "checkpoint").glob("state-%d.*.h5" % g))


def datasets(f):
    names = []
    f.visit(lambda n: names.append(n) if isinstance(f[n], h5py.Dataset) else None)
    return sorted(names)


def forge(f, name, values):
    """Replaces a dataset by `values`, with a checksum that matches them."""
    del f[name]
    f.create_dataset(name, data=values)
    f[name].attrs.create("fnv1a64", fnv(values.tobytes()), dtype="u8")


def flip(path, at, rng):
    data = bytearray(path.read_bytes())
    bit = rng.randrange(8)
    data[at] ^= 1 << bit
    path.write_bytes(bytes(data))
    return bit


def data_ranges(path):
    with h5py.File(path, "r") as f:
        out = []
        for name in datasets(f):
            d = f[name]
            offset = d.id.get_offset()
            if offset is not None and d.size:
                out.append((offset, offset + d.size * d.dtype.itemsize, name))
        return out


# Each mutation changes the copy in `folder` and returns (what it did, whether a restart must
# refuse it, whether the state it holds is still the run's own).

def cut(folder, state, base, rng):
    size = state.stat().st_size
    n = rng.randrange(size)
    os.truncate(state, n)
    return "cut to %d of %d bytes" % (n, size), True, False


def flip_anywhere(folder, state, base, rng):
    at = rng.randrange(state.stat().st_size)
    inside = [name for lo, hi, name in data_ranges(state) if lo <= at < hi]
    bit = flip(state, at, rng)
    if inside:
        return "bit %d of byte %d flipped, in '%s'" % (bit, at, inside[0]), True, False
    return "bit %d of byte %d flipped" % (bit, at), False, True


def flip_data(folder, state, base, rng):
    lo, hi, name = rng.choice(data_ranges(state))
    bit = flip(state, rng.randrange(lo, hi), rng)
    return "bit %d of '%s' flipped" % (bit, name), True, False


def flip_metadata(folder, state, base, rng):
    ranges = data_ranges(state)
    size = state.stat().st_size
    for _ in range(100):
        at = rng.randrange(min(size, 4096)) if rng.random() < 0.5 else rng.randrange(size)
        if not any(lo <= at < hi for lo, hi, _ in ranges):
            bit = flip(state, at, rng)
            return "bit %d of metadata byte %d flipped" % (bit, at), False, True
    return "nothing (no metadata byte found)", False, True


def attribute(folder, state, base, rng):
    with h5py.File(state, "r+") as f:
        name = rng.choice(datasets(f))
        attrs = f[name].attrs
        how = rng.randrange(3)
        if how == 0:
            del attrs["fnv1a64"]
            return "'%s' without its checksum" % name, True, False
        if how == 1:
            value = int(attrs["fnv1a64"]) ^ (1 << rng.randrange(64))
            attrs.create("fnv1a64", value, dtype="u8")
            return "'%s' checksum changed" % name, True, False
        attrs.create("note", 1.0)
        return "'%s' with another attribute" % name, False, True


def removed(folder, state, base, rng):
    with h5py.File(state, "r+") as f:
        name = rng.choice(datasets(f))
        if rng.random() < 0.5:
            del f[name]
            return "'%s' removed" % name, True, False
        other = name + rng.choice(["_", ".old", "x"])
        f.move(name, other)
        return "'%s' renamed '%s'" % (name, other), True, False


def foreign_dataset(folder, state, base, rng):
    other_state = state_files(base.foreign["spacing"])[0] if "spacing" in base.foreign else \
        state_files(rng.choice(list(base.foreign.values())))[0]
    with h5py.File(state, "r+") as f, h5py.File(other_state, "r") as other:
        name = rng.choice(datasets(f))
        if name not in other:
            return "nothing (the foreign checkpoint has no '%s')" % name, False, True
        same = f[name].dtype == other[name].dtype and f[name].shape == other[name].shape and \
            np.array_equal(f[name][()], other[name][()])
        del f[name]
        other.copy(other[name], f, name)
        return "'%s' from the foreign checkpoint" % name, False, same


def foreign_whole(folder, state, base, rng):
    kind = rng.choice(sorted(base.foreign))
    shutil.rmtree(folder / "checkpoint")
    shutil.copytree(base.foreign[kind] / "checkpoint", folder / "checkpoint")
    what = "the checkpoint of %s" % kind
    if rng.random() < 0.5:  # its header made to claim this run
        with h5py.File(state_files(base.own)[0], "r") as own:
            for s in state_files(folder):
                with h5py.File(s, "r+") as f:
                    for name in ("meta.settings", "meta.identity"):
                        if name in f:
                            del f[name]
                        own.copy(own[name], f, name)
        what += ", its header this run's"
    return what, True, False


def forged(folder, state, base, rng):
    with h5py.File(state, "r+") as f:
        names = datasets(f)
        name = rng.choice(names)
        d = f[name]
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
        return "'%s' %s, checksum forged" % (name, what), False, False


def moved_in_time(folder, state, base, rng):
    with h5py.File(state, "r+") as f:
        t, step = float(f["meta.time"][0]), int(f["meta.step"][0])
        if rng.random() < 0.7:
            value = rng.choice([1e300, math.inf, math.nan, -1.0, -t, 2 * base.end, base.end * 1.01,
                                t * (1 + 1e-9), t / 2, 0.0])
            forge(f, "meta.time", np.array([value]))
            return "the header's time %r (the state's %r)" % (value, t), True, False
        value = rng.choice([step + 1, step - 1, 0, -1, 2**62])
        forge(f, "meta.step", np.array([value], dtype=f["meta.step"].dtype))
        return "the header's step %d (the state's %d)" % (value, step), True, False


def marker(folder, state, base, rng):
    g = generation(folder)
    text = rng.choice(["generation %d\n" % (g - 1), "generation %d\n" % (g + 1),
                       "generation %d\n" % 10**18, "generation -1\n", "generation 0\n", "",
                       "generation\n", "generation 1e3\n", "\x00\xff" * 8, "g" * 10000])
    (folder / "checkpoint" / "checkpoint.txt").write_text(text, errors="surrogateescape")
    # A run killed between naming generation g and removing g - 1 leaves both: a marker that
    # names the older one, as the run wrote it, restarts from there.
    older = text == "generation %d\n" % (g - 1) and \
        (folder / "checkpoint" / ("state-%d.0.h5" % (g - 1))).exists()
    return "marker %r" % text[:40], not older, False


def link(folder, state, base, rng):
    """A link or something other than a file where the checkpoint's files are; what a link
    points at lies in `folder`.outside, which must stay as it was."""
    outside = Path(str(folder) + ".outside")
    outside.mkdir()
    checkpoint = folder / "checkpoint"
    marker_file = checkpoint / "checkpoint.txt"
    how = rng.randrange(7)
    if how == 0:
        shutil.move(str(checkpoint), str(outside / "checkpoint"))
        checkpoint.symlink_to(outside / "checkpoint")
        return "checkpoint/ a link", True, False
    if how == 1:
        shutil.move(str(state), str(outside / state.name))
        state.symlink_to(outside / state.name)
        return "the state file a link", True, False
    if how == 2:
        shutil.move(str(marker_file), str(outside / "checkpoint.txt"))
        marker_file.symlink_to(outside / "checkpoint.txt")
        return "checkpoint.txt a link", True, False
    if how == 3:
        marker_file.unlink()
        os.mkfifo(marker_file)
        return "checkpoint.txt a FIFO", True, False
    if how == 4:
        state.unlink()
        os.mkfifo(state)
        return "the state file a FIFO", True, False
    if how == 5:
        state.unlink()
        state.mkdir()
        return "the state file a folder", True, False
    state.unlink()
    state.symlink_to(outside / "nothing")
    return "the state file a dangling link", True, False


MUTATIONS = [cut, flip_anywhere, flip_data, flip_metadata, attribute, removed, foreign_dataset,
             foreign_whole, forged, moved_in_time, marker, link]


def listing(folder):
    out = []
    if not folder.exists():
        return out
    for root, dirs, files in os.walk(folder):
        for n in sorted(dirs + files):
            p = Path(root) / n
            st = p.lstat()
            out.append((str(p), st.st_mode, st.st_size, st.st_mtime_ns))
    return sorted(out)


CPU_S = 60  # any restart's limit of CPU time
REFUSAL_CPU_S = 2.0  # a refusal's
REFUSAL_EXTRA_BYTES = 100e6  # a refusal's peak memory beyond a clean restart's


def restart(meshfree, base, folder):
    """A restart from `folder`: its Outcome."""
    args = [meshfree, "run", base.problem, "--restart", str(folder)] + base.sets + \
        ["--set", "time.end=%r" % base.end]
    return run_limited(args, CPU_S, one_rank_env())


def finite_history(folder):
    history = folder / "history.csv"
    if not history.exists():
        return "no history.csv"
    for row in history.read_text(errors="replace").split("\n")[1:]:
        if row and not all(math.isfinite(float(v)) for v in row.split(",")):
            return "a non-finite value in history.csv: " + row[:200]
    return None


def judge(outcome, before, after, folder, must_refuse, same_state, base):
    rc, err = outcome.returncode, outcome.stderr.decode(errors="replace")
    lines = [l for l in err.split("\n") if l.strip() and not l.startswith("[meshfree] warning")]
    if rc == 2:
        if len(lines) != 1 or not lines[0].startswith("meshfree: --restart "):
            return "refused without one '--restart' line: %r" % err[-400:]
        if before != after:
            return "refused, but the folder (or what its links point at) changed"
        if outcome.cpu_s > REFUSAL_CPU_S:
            return "refused after %.2f CPU seconds (at most %g)" % (outcome.cpu_s, REFUSAL_CPU_S)
        if outcome.peak_bytes > base.peak_bytes + REFUSAL_EXTRA_BYTES:
            return "refused at a peak of %.0f MB, a clean restart's is %.0f MB" % (
                outcome.peak_bytes / 1e6, base.peak_bytes / 1e6)
        return None
    if rc == 0:
        summary = folder / "summary.json"
        if not summary.exists() or json.loads(summary.read_text())["status"] != "completed":
            return "exit 0 without a completed summary"
        if must_refuse:
            return "restarted to completion, but this mutant must be refused"
        why = finite_history(folder)
        if why:
            return "completed with " + why
        if same_state and (folder / "history.csv").read_text() != base.reference:
            return "restarted from the run's own state to other results than its own restart"
        return None
    return "%s: %s" % (status(rc), err[-400:])


def copy_file(src, dst):
    """Copies a plain file; a FIFO or device is kept as its name only (opening one blocks)."""
    if os.path.isfile(src) or os.path.islink(src):
        return shutil.copy2(src, dst, follow_symlinks=False)
    Path(dst).write_text("(not a plain file)\n")
    return dst


def prepare(meshfree, source, work):
    """The bases, their checkpoints (own and foreign) and the history of a clean restart."""
    problems = Path(source) / "problems"
    pd = Base("pd_slab_blast", str(problems / "pd_slab_blast.yaml"),
              ["--set", "output.checkpoint_interval=1.0e-5"])
    sph = Base("sph_sod_tube", str(problems / "sph_sod_tube.yaml"),
               ["--set", "output.checkpoint_interval=1.0e-3"])
    for b in (pd, sph):
        b.own = make_checkpoint(meshfree, b, work / (b.name + ".own"))
        b.foreign["2 MPI ranks"] = make_checkpoint(meshfree, b, work / (b.name + ".ranks"),
                                                   ranks=2)
    pd.foreign["another spacing"] = make_checkpoint(
        meshfree, pd, work / "pd.spacing", ["--set", "discretisation.spacing=0.02"])
    pd.foreign["another problem"], sph.foreign["another problem"] = sph.own, pd.own
    for b in (pd, sph):
        with h5py.File(state_files(b.own)[0], "r") as f:
            t = float(f["meta.time"][0])
        out = subprocess.run([meshfree, "check", b.problem] + b.sets, capture_output=True,
                             env=one_rank_env()).stdout.decode()
        b.end = t + 3 * float(FIRST_STEP.search(out).group(1))  # three steps or so
        ref = work / (b.name + ".reference")
        shutil.copytree(b.own / "checkpoint", ref / "checkpoint", symlinks=True)
        clean = restart(meshfree, b, ref)
        if clean.returncode != 0:
            sys.exit("the own checkpoint of %s does not restart: %s" % (b.name, clean.stderr))
        b.reference = (ref / "history.csv").read_text()
        b.peak_bytes = clean.peak_bytes
        print("%s: a clean restart peaks at %.0f MB in %.2f CPU seconds"
              % (b.name, clean.peak_bytes / 1e6, clean.cpu_s), flush=True)
    return [pd, sph]


def main():
    ap = arguments(__doc__)
    ap.add_argument("--mutations", nargs="+", default=[m.__name__ for m in MUTATIONS],
                    choices=[m.__name__ for m in MUTATIONS])
    a = parse(ap)
    mutations = [m for m in MUTATIONS if m.__name__ in a.mutations]
    work = Path(tempfile.mkdtemp(prefix="fuzz_checkpoints_"))
    try:
        bases = prepare(a.meshfree, a.source, work)

        def one(n):
            rng = random.Random(a.seed * 100003 + n)
            base = bases[n % len(bases)]
            folder = work / ("m%d" % n)
            outside = Path(str(folder) + ".outside")
            what, rc, err = "(not made)", None, ""
            outcome = None
            try:
                shutil.copytree(base.own / "checkpoint", folder / "checkpoint", symlinks=True)
                mutation = rng.choice(mutations)
                state = folder / "checkpoint" / state_files(base.own)[0].name
                what, must_refuse, same_state = mutation(folder, state, base, rng)
                before = listing(folder) + listing(outside)
                outcome = restart(a.meshfree, base, folder)
                rc, err = outcome.returncode, outcome.stderr.decode(errors="replace")
                failure = judge(outcome, before, listing(folder) + listing(outside), folder,
                                must_refuse, same_state, base)
            except Exception:
                err = traceback.format_exc()
                failure = "exception in the fuzzer: " + err.strip().split("\n")[-1]
            if failure and a.out:
                keep = Path(a.out) / ("mutant_%d" % n)
                shutil.rmtree(keep, ignore_errors=True)
                shutil.copytree(folder, keep, symlinks=True, copy_function=copy_file)
                (keep / "output.txt").write_text("%s: %s\nexit %s\n%s" % (base.name, what, rc, err))
            shutil.rmtree(folder, ignore_errors=True)
            shutil.rmtree(outside, ignore_errors=True)
            return n, base.name + ": " + what, rc, failure, outcome

        outcomes = {"refused": 0, "restarted": 0}
        failures, refusals = [], []
        with ThreadPoolExecutor(a.jobs) as pool:
            for n, what, rc, failure, outcome in pool.map(one, range(a.count)):
                if failure:
                    failures.append((n, what, failure))
                    print("FAIL mutant %d (%s): %s" % (n, what, failure), flush=True)
                else:
                    outcomes["refused" if rc == 2 else "restarted"] += 1
                if rc == 2 and outcome:
                    refusals.append(outcome)
        print("seed %d: %d mutants: %d refused cleanly, %d restarted to completion, %d failures"
              % (a.seed, a.count, outcomes["refused"], outcomes["restarted"], len(failures)))
        if refusals:
            print("refusals: at most %.2f CPU seconds (median %.2f), peak resident memory at most "
                  "%.0f MB" % (max(o.cpu_s for o in refusals),
                               sorted(o.cpu_s for o in refusals)[len(refusals) // 2],
                               max(o.peak_bytes for o in refusals) / 1e6))
        return 1 if failures else 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
