#!/usr/bin/env python3
"""What the fuzzers found, one case each, with its expected one-line outcome: an SPH checkpoint
whose per-particle arrays, ghosts or neighbour lists do not go together (a lengthened array, an
owned count of another layout, a neighbour that is no particle, a mirror image of no particle;
each with a checksum that matches) was restarted and failed in its first step (exit 1, "particle
1808 has material 1202590843 of 1", "the half neighbour list is not built"), crashed (SIGSEGV, a
mirror image read past the particles) or completed (a neighbour past the particles); a marker
"generation 2e3" was read as generation 2; a PD checkpoint with the LAMMPS rule's s0 where the
run's laws keep none crashed (SIGSEGV); a flipped bit in the dimension of an array (bit 31 of
'meta.version', bit 27 of a per-particle array) made a restart allocate 16.9 GB (or 1.1 GB) and
read for 76 s before it refused the file. Each is refused: exit 2, one line naming what differs,
the folder as it was; the flipped dimensions in at most 2 CPU seconds and 100 MB of peak memory
beyond a clean restart's.
Usage: fuzz_findings.py MESHFREE SOURCE_DIR
"""
import shutil
import struct
import sys
import tempfile
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fuzz_checkpoints import (REFUSAL_CPU_S, REFUSAL_EXTRA_BYTES, Base, generation,  # noqa: E402
                              listing, make_checkpoint, restart, state_files)
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


def dimension_flipped(name, bit):
    """A mutation: bit `bit` of the first dimension of dataset `name` flipped in the file's bytes
    (the dataspace message of its version-1 object header), nothing else changed."""
    def mutate(folder):
        path = folder / "checkpoint" / ("state-%d.0.h5" % generation(folder))
        with h5py.File(path, "r") as f:
            header, shape = h5py.h5o.get_info(f[name].id).addr, f[name].shape
        data = bytearray(path.read_bytes())
        if data[header] != 1:
            raise RuntimeError("the object header of %s is not of version 1" % name)
        at = header + 16  # the first message, after the 12-byte prefix and its padding
        while struct.unpack_from("<H", data, at)[0] != 1:  # to the dataspace message
            at += 8 + struct.unpack_from("<H", data, at + 2)[0]
        dims = at + 8 + 8  # past the message's header and the dataspace's own 8 bytes
        data[dims + bit // 8] ^= 1 << (bit % 8)
        path.write_bytes(bytes(data))
        with h5py.File(path, "r") as f:  # the file says what the mutation meant it to say
            if f[name].shape[0] != shape[0] ^ (1 << bit):
                raise RuntimeError("the flip did not land on the dimension of %s" % name)
    return mutate


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
    (SOD, "bit 31 of the dimension of 'meta.version'", dimension_flipped("meta.version", 31),
     "cannot read 'meta.version' (a damaged file?)"),
    (SLAB, "bit 27 of the dimension of a per-particle array",
     dimension_flipped("particles.u", 27), "'particles.u' cannot be read (a damaged file?)"),
]
BOUNDED = ("bit 31", "bit 27")  # the cases whose CPU time and memory are bounded too


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
            clean = work / (name + ".clean")
            shutil.copytree(base.own / "checkpoint", clean / "checkpoint")
            base.peak_bytes = restart(meshfree, base, clean).peak_bytes
            bases[name] = base
        for k, ((name, _, _), what, mutate, expected) in enumerate(CASES):
            base = bases[name]
            folder = work / ("case%d" % k)
            shutil.copytree(base.own / "checkpoint", folder / "checkpoint")
            mutate(folder)
            before = listing(folder)
            o = restart(meshfree, base, folder)
            rc, err = o.returncode, o.stderr.decode(errors="replace")
            lines = [l for l in err.split("\n") if l.strip()]
            ok = rc == 2 and len(lines) == 1 and expected in lines[0] and \
                listing(folder) == before
            cost = "%.2f CPU s, peak %.0f MB (a clean restart %.0f MB)" % (
                o.cpu_s, o.peak_bytes / 1e6, base.peak_bytes / 1e6)
            if what.startswith(BOUNDED):
                ok = ok and o.cpu_s <= REFUSAL_CPU_S and \
                    o.peak_bytes <= base.peak_bytes + REFUSAL_EXTRA_BYTES
            print("%s: %s (exit %s, %s: %s)" % ("ok" if ok else "FAIL", what, rc, cost,
                                                 err.strip()[-300:]))
            fails += not ok
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print("%d failure(s)" % fails)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
