"""One run of coulomb-adapt for the Python tests: the command line from a
parameter file and '-s ENTRY=VALUE' settings, on one rank or several, the
run's end checked, its summary.json's cycles and its log returned."""

import json
import os
import shutil
import subprocess
import sys


def run_cycles(exe, prm, directory, settings, ranks=1, mpiexec=None,
               cwd=None):
    """Runs EXE on PRM with SETTINGS into DIRECTORY (emptied first); ends
    the test with the command and its output if the run fails. Returns
    (summary.json's cycles, the log). CWD: where to run it (a parameter
    file's relative paths, e.g. a gmsh geometry, are the run's)."""
    shutil.rmtree(directory, ignore_errors=True)
    command = ([mpiexec, "-np", str(ranks)] if ranks > 1 else []) + \
        [exe, prm]
    for setting in list(settings) + ["Output/Output directory=" + directory]:
        command += ["-s", setting]
    result = subprocess.run(command, capture_output=True, text=True,
                            cwd=cwd)
    if result.returncode != 0:
        sys.exit("run failed (%s):\n%s%s" %
                 (" ".join(command), result.stdout, result.stderr))
    with open(os.path.join(directory, "summary.json")) as f:
        return json.load(f)["cycles"], result.stdout


def report(failures):
    """The test's verdict: each failure on its own line and 1, or "OK" and
    0 (the exit code)."""
    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        return 1
    print("OK")
    return 0
