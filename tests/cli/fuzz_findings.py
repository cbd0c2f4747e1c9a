#!/usr/bin/env python3
"""What the fuzzers found, one case each, with its expected one-line outcome: an SPH checkpoint
whose per-particle arrays, ghosts or neighbour lists do not go together (a lengthened array, an
owned count of another layout, a neighbour that is no particle, a mirror image of no particle;
each with a checksum that matches) was restarted and failed in its first step (exit 1, "particle
1808 has material 1202590843 of 1", "the half neighbour list is not built"), crashed (SIGSEGV, a
mirror image read past the particles) or completed (a neighbour past the particles); a marker
"generation 2e3" was read as generation 2; a PD checkpoint with the LAMMPS rule's s0 where the
run's laws keep none crashed (SIGSEGV). Each is refused: exit 2, one line naming what
differs, the folder as it was.
Usage: fuzz_findings.py MESHFREE SOURCE_DIR
"""
import shutil
import sys
import tempfile
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fuzz_checkpoints import (Base, generation, listing, make_checkpoint, restart,  # noqa: E402
                              state_files)
from fuzz_support import fnv  # noqa: E402


def forged(name, change):
    """A mutation: dataset `name` replaced by change(its values), with a checksum that matches."""
    return lambda folder: forge(folder / "checkpoint" / ("state-%d.0.h5" % generation(folder)),
                                name, change)


def forge(path, name, change):
    with h5py.File(path, "r+") as f:
        values = np.asarray(change(np.atleast_1d(f[name][()]).copy()), dtype=f[name].dtype)
        del f[name]
        f.create_dataset(name, data=values)
        f[name].attrs.create("fnv1a64", fnv(values.tobytes()), dtype="u8")


def marker(text):
    """A mutation: checkpoint.txt says `text` (% the generation it named)."""
    return lambda folder: (folder / "checkpoint" / "checkpoint.txt").write_text(
        text % generation(folder))


SOD = ("sph_sod_tube", ["--set", "output.checkpoint_interval=1.0e-3"], 2.4e-4)
SLAB = ("pd_slab_blast", ["--set", "output.checkpoint_interval=1.0e-5"], 2.5e-6)
CASES = [
    (SLAB, "critical stretches s0 where the run keeps none",
     forged("bonds.s0", lambda v: np.concatenate([v, np.zeros(1, v.dtype)])),
     "the checkpoint holds 1 and 0 critical stretches s0, this run has 0 and 0"),
    (SOD, "a per-particle array one particle longer",
     forged("sph.particles.volume", lambda v: np.concatenate([v, v[:1]])),
     "'sph.particles.volume' holds 1809 particles, the positions 1808"),
    (SOD, "the owned particles of another layout",
     forged("sph.particles.owned", lambda v: v * 0 + 1000),
     "the checkpoint's ranks own 1000 particles, this run has 1808"),
    (SOD, "a neighbour that is no particle",
     forged("sph.pairs.partner", lambda v: np.where(np.arange(v.size) == 7, 1808, v)),
     "neighbour lists and material groups do not go together"),
    (SOD, "a mirror image of no particle",
     forged("sph.ghost_source", lambda v: np.concatenate([v, np.zeros(1, v.dtype)])),
     "neighbour lists and material groups do not go together"),
    (SOD, "a marker 'generation <g>e3'", marker("generation %de3\n"), ": no checkpoint in "),
]


def main():
    meshfree, source = sys.argv[1], Path(sys.argv[2])
    work = Path(tempfile.mkdtemp(prefix="fuzz_findings_"))
    fails = 0
    try:
        bases = {}
        for name, sets, step in (SOD, SLAB):
            base = Base(name, str(source / "problems" / (name + ".yaml")), sets)
            base.own = make_checkpoint(meshfree, base, work / name)
            with h5py.File(state_files(base.own)[0], "r") as f:
                base.end = float(f["meta.time"][0]) + 3 * step
            bases[name] = base
        for k, ((name, _, _), what, mutate, expected) in enumerate(CASES):
            base = bases[name]
            folder = work / ("case%d" % k)
            shutil.copytree(base.own / "checkpoint", folder / "checkpoint")
            mutate(folder)
            before = listing(folder)
            rc, err = restart(meshfree, base, folder)
            lines = [l for l in err.split("\n") if l.strip()]
            ok = rc == 2 and len(lines) == 1 and expected in lines[0] and \
                listing(folder) == before
            print("%s: %s (exit %s: %s)" % ("ok" if ok else "FAIL", what, rc, err.strip()[-300:]))
            fails += not ok
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print("%d failure(s)" % fails)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
