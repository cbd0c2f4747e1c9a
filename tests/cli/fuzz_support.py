"""What the fuzzers (fuzz_inputs.py, fuzz_checkpoints.py) and the checkpoint tests share: the
command line every fuzzer takes, its seed (fixed in the suite, the day's in
scripts/fuzz_nightly.sh), the environment of a one-rank case, a case run under a limit of CPU
time, and meshfree's checksum of an array."""
import argparse
import datetime
import os
import signal
import subprocess
import tempfile
import time
from collections import namedtuple

import numpy as np

# The suite's seed: a test must not pass on one day and fail on the next for a defect no change
# introduced. scripts/fuzz_nightly.sh searches anew with the day's seed (--seed today).
SUITE_SEED = 1


def arguments(description):
    """The fuzzer's command line: MESHFREE SOURCE [--count N] [--seed S] [--out DIR] [--jobs J];
    the caller adds its own options, then calls `parse` with it."""
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("meshfree")
    ap.add_argument("source")
    ap.add_argument("--count", type=int, default=2000)
    ap.add_argument("--seed", default=str(SUITE_SEED),
                    help="a number, or 'today' for the UTC date as YYYYMMDD (default %d)"
                    % SUITE_SEED)
    ap.add_argument("--out", default=None)
    ap.add_argument("--jobs", type=int, default=4 * (os.cpu_count() or 1))
    return ap


def parse(ap):
    """The parsed arguments, the seed a number ('today': the UTC date as YYYYMMDD), printed first
    so that a failure can be replayed."""
    a = ap.parse_args()
    if a.seed == "today":
        a.seed = datetime.datetime.now(datetime.timezone.utc).strftime("%Y%m%d")
    try:
        a.seed = int(a.seed)
    except ValueError:
        ap.error("--seed: %r is neither a number nor 'today'" % a.seed)
    print("seed %d (replay with --seed %d)" % (a.seed, a.seed), flush=True)
    return a


# What a case did: its exit status (negative: the signal that ended it; "hung": it used no CPU
# for the wall-clock guard's length), its output, and the CPU seconds and peak resident bytes
# the kernel counted for it.
Outcome = namedtuple("Outcome", "returncode stdout stderr cpu_s peak_bytes")

# A case that exceeds its CPU time is ended by SIGXCPU: a limit of CPU time holds on a loaded
# machine, where a wall-clock one fails cases that only waited for a core.
CPU_LIMIT_SIGNAL = signal.SIGXCPU


def run_limited(cmd, cpu_s, env, cwd=None, hang_s=600):
    """Runs `cmd` under a limit of `cpu_s` CPU seconds (prlimit: the kernel ends it with SIGXCPU)
    and returns its Outcome. A case that neither ends nor uses up its CPU time (it blocks on a
    FIFO, say) is killed after `hang_s` of wall time and reported "hung": long enough that no
    load makes a working case reach it."""
    limit = max(1, int(round(cpu_s)))
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        p = subprocess.Popen(["prlimit", "--cpu=%d:%d" % (limit, limit + 2), "--"] + list(cmd),
                             stdin=subprocess.DEVNULL, stdout=out, stderr=err, env=env, cwd=cwd,
                             start_new_session=True)
        deadline, hung = time.monotonic() + hang_s, False
        while True:
            pid, status, usage = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() > deadline:
                os.killpg(p.pid, signal.SIGKILL)
                pid, status, usage = os.wait4(p.pid, 0)
                hung = True
                break
            time.sleep(0.005)
        p.returncode = os.waitstatus_to_exitcode(status)  # Popen must not wait for it again
        out.seek(0), err.seek(0)
        return Outcome("hung" if hung else p.returncode, out.read(), err.read(),
                       usage.ru_utime + usage.ru_stime, usage.ru_maxrss * 1024)


def status(rc):
    """An exit status in words."""
    if rc == "hung":
        return "hung (no end and no CPU used for the wall-clock guard's length)"
    if rc == -CPU_LIMIT_SIGNAL:
        return "over its CPU-time limit"
    return "killed by signal %d" % -rc if rc < 0 else "exit %d" % rc


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
