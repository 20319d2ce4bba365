#!/usr/bin/python3
"""What the cre estimator costs against the contact solve (issue 17), two
executables alternated run after run, for each 'CRE minimisation tolerance'
(0 = the direct minimisation; 1e-3, the truncated CG, is the default since
the 23rd session), one thread:

    benchmarks/effectivity/run_cre_cost.py \
        --exe /work/main/build-lead/coulomb-adapt build/coulomb-adapt \
        --labels before,after --tolerances 0 1e-3 --repeats 2 \
        --csv benchmarks/effectivity/cre_cost.csv

Each run is prm/blocks.prm with Estimator = cre, 3 global refinements
(26,724 DoFs; --refinements 1 2 3 for several sizes) and one cycle under
DEAL_II_NUM_THREADS=1 (--threads N for N threads per rank) and
/usr/bin/time.
Per run the CSV holds the timer sections 'contact solve', 'error
indicator', 'error indicator: equilibration' and (where the executable has
it) 'error indicator: cell forms' from summary.json, epsilon to all its
digits, the truncated CG's steps, the peak resident memory (/usr/bin/time's
%M), the run's elapsed and CPU time (user + system) and the load average
at its start. (It replaces run_cell_forms_timing.py, which measured the
same runs for cell_forms.csv: `--tolerances 0` gives its columns.) The machine
is shared: compare sides of the same repeat, and read the load column.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SETTINGS = ["Error indicator/Estimator=cre", "Output/Write VTU=false",
            "Adaptation/Number of cycles=1",
            "Adaptation/Minimum number of cycles=1"]
SECTIONS = {"contact_solve_s": "contact solve",
            "error_indicator_s": "error indicator",
            "equilibration_s": "error indicator: equilibration",
            "cell_forms_s": "error indicator: cell forms"}
FIELDS = ["side", "threads", "refinements", "n_dofs", "tolerance", "repeat",
          "contact_solve_s",
          "error_indicator_s", "equilibration_s", "cell_forms_s",
          "indicator_over_solve", "epsilon", "cg_steps", "peak_kb",
          "elapsed_s", "cpu_s", "load_average"]


def run_once(exe, tolerance, refinements, outdir, threads):
    command = ["/usr/bin/time", "-f", "TIME %e s %M KB %U %S", exe,
               os.path.join(ROOT, "prm", "blocks.prm")]
    for s in SETTINGS + ["Error indicator/CRE minimisation tolerance=" +
                         tolerance, "Mesh/Global refinements=" + refinements,
                         "Output/Output directory=" + outdir]:
        command += ["-s", s]
    env = dict(os.environ, DEAL_II_NUM_THREADS=str(threads))
    load = os.getloadavg()[0]
    out = subprocess.run(command, env=env, capture_output=True, text=True)
    if out.returncode != 0:
        sys.stderr.write(out.stdout + out.stderr)
        return None
    with open(os.path.join(outdir, "summary.json")) as f:
        cycle = json.load(f)["cycles"][0]
    timings = cycle["timings_s"]
    row = {key: timings.get(name, "") for key, name in SECTIONS.items()}
    row["indicator_over_solve"] = round(row["error_indicator_s"] /
                                        row["contact_solve_s"], 2)
    row["epsilon"] = repr(cycle["epsilon"])
    row["n_dofs"] = cycle["n_dofs"]
    row["cg_steps"] = cycle["cre"].get("optimisation_cg_steps", "")
    m = re.search(r"TIME ([0-9.]+) s ([0-9]+) KB ([0-9.]+) ([0-9.]+)",
                  out.stderr)
    row["elapsed_s"], row["peak_kb"] = float(m.group(1)), int(m.group(2))
    row["cpu_s"] = round(float(m.group(3)) + float(m.group(4)), 2)
    row["load_average"] = round(load, 2)
    return row


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--exe", nargs=2, required=True)
    parser.add_argument("--labels", default="before,after")
    parser.add_argument("--tolerances", nargs="+", default=["0", "1e-3"])
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--refinements", nargs="+", default=["3"],
                        help="global refinements of blocks (3: 26,724 "
                        "DoFs)")
    parser.add_argument("--threads", type=int, default=1,
                        help="DEAL_II_NUM_THREADS of every run")
    parser.add_argument("--csv", default=os.path.join(
        os.path.dirname(__file__), "cre_cost.csv"))
    args = parser.parse_args()
    labels = args.labels.split(",")
    rows, failed = [], False
    with tempfile.TemporaryDirectory() as outdir:
        for repeat in range(args.repeats):
            for refinements in args.refinements:
                for tolerance in args.tolerances:
                    for label, exe in zip(labels, args.exe):
                        row = run_once(exe, tolerance, refinements, outdir,
                                       args.threads)
                        if row is None:
                            failed = True
                            continue
                        row = dict(side=label, threads=args.threads,
                                   refinements=refinements,
                                   tolerance=tolerance, repeat=repeat, **row)
                        print(row, flush=True)
                        rows.append(row)
    # All digits: the point is that the estimate did not change.
    common.write_csv(args.csv, rows, FIELDS, "%.17g")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
