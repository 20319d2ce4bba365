#!/usr/bin/python3
"""The cre estimator's equilibration and its cells' quadratic forms, two
executables run after run (alternated, so that a loaded machine loads both
alike), one thread:

    benchmarks/effectivity/run_cell_forms_timing.py \
        --exe /work/main/build/coulomb-adapt build/coulomb-adapt \
        --labels before,after --repeats 3 --csv benchmarks/effectivity/cell_forms.csv

Each run is prm/blocks.prm with Estimator = cre, 3 global refinements and
one cycle (26,724 DoFs, the lower block's 21,504 P1 triangles) under
DEAL_II_NUM_THREADS=1. Per run the CSV holds the timer table's wall times
of 'contact solve', 'error indicator: equilibration' and (where the
executable has it) 'error indicator: cell forms', the run's CPU time
(user + system, from getrusage of the child), epsilon and the load average
at the start of the run. Timings are for benchmarks only: the machine is
shared, so compare sides of the same repeat.
"""
import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SETTINGS = ["Error indicator/Estimator=cre", "Output/Write VTU=false",
            "Mesh/Global refinements=3", "Adaptation/Number of cycles=1",
            "Adaptation/Minimum number of cycles=1"]
SECTIONS = {"contact_solve_s": "contact solve",
            "equilibration_s": "error indicator: equilibration",
            "cell_forms_s": "error indicator: cell forms"}


def run_once(exe, outdir):
    command = [exe, os.path.join(ROOT, "prm", "blocks.prm")]
    for s in SETTINGS + ["Output/Output directory=" + outdir]:
        command += ["-s", s]
    env = dict(os.environ, DEAL_II_NUM_THREADS="1")
    load = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(command, env=env, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode != 0:
        sys.stderr.write(out.stdout + out.stderr)
        return None
    row = {"cpu_s": round((after.ru_utime - before.ru_utime) +
                          (after.ru_stime - before.ru_stime), 3),
           "load_average": load}
    for key, name in SECTIONS.items():
        m = re.search(r"\| " + re.escape(name) + r"\s*\|\s*\d+\s*\|\s*([0-9.e+-]+)s",
                      out.stdout)
        row[key] = float(m.group(1)) if m else ""
    m = re.search(r"error indicator \(cre\): epsilon = ([0-9.]+) %", out.stdout)
    row["epsilon_percent"] = m.group(1) if m else ""
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--exe", nargs=2, required=True)
    parser.add_argument("--labels", default="before,after")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--csv", default=os.path.join(os.path.dirname(__file__),
                                                      "cell_forms.csv"))
    args = parser.parse_args()
    labels = args.labels.split(",")
    rows, failed = [], False
    with tempfile.TemporaryDirectory() as outdir:
        for repeat in range(args.repeats):
            for label, exe in zip(labels, args.exe):
                row = run_once(exe, outdir)
                if row is None:
                    failed = True
                    continue
                row = dict(side=label, repeat=repeat, **row)
                print(row, flush=True)
                rows.append(row)
    fields = ["side", "repeat", "contact_solve_s", "equilibration_s",
              "cell_forms_s", "cpu_s", "epsilon_percent", "load_average"]
    # All digits: the point is that the estimate did not change.
    common.write_csv(args.csv, rows, fields, "%.17g")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
