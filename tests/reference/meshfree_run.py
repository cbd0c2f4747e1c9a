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
