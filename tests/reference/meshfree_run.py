"""meshfree run from a test script, on one rank or on several under mpirun (with Open MPI's two
consents, which CI's root user needs, and one thread a rank): the run's summary.json, or the
script stops with the command and the end of its output."""
import json
import os
import subprocess
import sys


def run_meshfree(meshfree, problem_file, out, sets=(), ranks=1):
    cmd = [meshfree, "run", problem_file, "--out", out]
    for s in sets:
        cmd += ["--set", s]
    env = dict(os.environ)
    if ranks > 1:
        cmd = ["mpirun", "-n", str(ranks)] + cmd
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1", OMP_NUM_THREADS="1")
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    if done.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {done.returncode}:\n{done.stdout[-2000:]}")
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


class Checks:
    """A script's checks: each printed as ok or FAIL, and whether any failed, for its exit."""

    def __init__(self):
        self.failed = False

    def __call__(self, ok, text):
        self.failed |= not ok
        print(f"{'ok' if ok else 'FAIL'}: {text}", flush=True)


def calculix_3d_curve(root, name, increments):
    """The rows of reference/calculix_3d/NAME/curve.csv (row 0 the unloaded state), the script
    stopping where it has fewer than `increments` past it."""
    import csv
    with open(os.path.join(root, "reference", "calculix_3d", name, "curve.csv")) as f:
        reference = list(csv.DictReader(f))
    if not 1 <= increments < len(reference):
        sys.exit(f"--increments: 1 to {len(reference) - 1}, got {increments}")
    return reference
