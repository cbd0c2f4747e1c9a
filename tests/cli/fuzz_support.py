"""What the fuzzers (fuzz_inputs.py, fuzz_checkpoints.py) and the checkpoint tests share: the
command line every fuzzer takes, its seed of the day, the environment of a one-rank case, and
meshfree's checksum of an array."""
import argparse
import datetime
import os

import numpy as np


def arguments(description):
    """The fuzzer's command line: MESHFREE SOURCE [--count N] [--seed S] [--out DIR] [--jobs J];
    the caller adds its own options, then calls `parse` with it."""
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("meshfree")
    ap.add_argument("source")
    ap.add_argument("--count", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--out", default=None)
    ap.add_argument("--jobs", type=int, default=4 * (os.cpu_count() or 1))
    return ap


def parse(ap):
    """The parsed arguments, the seed that of the day (the UTC date as YYYYMMDD) unless given,
    printed first so that a failure can be replayed."""
    a = ap.parse_args()
    if a.seed is None:
        a.seed = int(datetime.datetime.now(datetime.timezone.utc).strftime("%Y%m%d"))
    print("seed %d (replay with --seed %d)" % (a.seed, a.seed), flush=True)
    return a


def one_rank_env():
    """The environment of a case: one rank, one thread, and none of the start-up work that a
    one-rank process does not need, which is most of a short case's cost (measured in README.md,
    "Running"). meshfree runs itself again to set OMP_WAIT_POLICY=passive unless it is set, so it
    is set here (the same policy, one program load less); OpenBLAS starts no threads that spin in
    sched_yield. What meshfree computes is the same. (A process started without mpirun already
    tells Open MPI it is alone: no orted, no network transports, no session folder.)"""
    return dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive",
                OPENBLAS_NUM_THREADS="1")


def fnv(data):
    """meshfree's checksum of an array: FNV-1a over 64-bit words, seeded with the length."""
    h, prime, mask = 0xcbf29ce484222325 ^ len(data), 0x100000001b3, (1 << 64) - 1
    whole = len(data) // 8 * 8
    for w in np.frombuffer(data[:whole], "<u8"):
        h = ((h ^ int(w)) * prime) & mask
    for b in data[whole:]:
        h = ((h ^ b) * prime) & mask
    return h
