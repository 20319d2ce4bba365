#!/usr/bin/python3
"""The cre estimator's and the contact solve's time with the reference BLAS
against OpenBLAS, run after run (alternated, so that a loaded machine loads
both alike).

    benchmarks/effectivity/run_blas_comparison.py --exe build/coulomb-adapt \
        --openblas /usr/lib/x86_64-linux-gnu/openblas-serial \
        --reference /usr/lib/x86_64-linux-gnu/blas --repeats 2

Each run puts the chosen directories (holding libblas.so.3 and
liblapack.so.3; several joined by ':') first on LD_LIBRARY_PATH, so both
BLAS are measured with the same executable whichever the system's
alternative selects. Writes benchmarks/effectivity/blas.csv: per run the
phase times summed over the cycles (summary.json's timings_s), the final
DoFs and epsilon. Exits 1 when a run failed (after writing the others).

The same comparison serves two builds of the library: give each side the
directory holding its libcoulomb_adapt.so (the executable's RUNPATH gives
way to LD_LIBRARY_PATH) and name the sides with --labels, e.g.

    benchmarks/effectivity/run_blas_comparison.py --exe build/coulomb-adapt \
        --reference /tmp/old-lib --openblas /tmp/new-lib \
        --labels amesos-lu,mumps-ldlt --csv benchmarks/effectivity/ldlt.csv

    benchmarks/effectivity/run_blas_comparison.py --smoke \
        --exe build/coulomb-adapt --openblas DIRS --reference DIRS \
        --csv /tmp/blas.csv --outdir /tmp/blas-runs

runs only the seed's first cycle with cre, once per side (a few seconds;
ctest's benchmark.blas_comparison.run passes the reference BLAS for both
sides, so it runs on a machine without OpenBLAS).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
PRM = os.path.join(common.ROOT, "prm", "blocks.prm")
CRE = ["Error indicator/Estimator=cre"]
RUNS = {
    "seed cre eps0=5%": CRE,
    "cre eps0=1%": CRE + ["Adaptation/Target error=1"],
    "cre 3 refinements, 1 cycle": CRE + [
        "Mesh/Global refinements=3", "Adaptation/Number of cycles=1",
        "Adaptation/Minimum number of cycles=1"],
    "zz eps0=0.25%": ["Adaptation/Target error=0.25"],
}
# The smoke run: the seed mesh's solve and cre estimate, one cycle.
SMOKE = {
    "seed cre, 1 cycle": CRE + ["Adaptation/Number of cycles=1",
                                "Adaptation/Minimum number of cycles=1"],
}
FIELDS = ["run", "blas", "repeat", "dofs", "cycles", "wall_s",
          "contact_solve_s", "equilibration_s", "indicator_s",
          "adapt_mesh_s", "epsilon", "load_average"]


def summed(summary, section):
    return sum(c.get("timings_s", {}).get(section, 0.0)
               for c in summary["cycles"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--exe", required=True)
    parser.add_argument("--openblas", required=True)
    parser.add_argument("--reference", required=True)
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--csv", default=os.path.join(HERE, "blas.csv"))
    parser.add_argument("--outdir", default="/tmp/coulomb-bench-blas",
                        help="the runs' output directory (overwritten)")
    parser.add_argument("--labels", default="reference,openblas",
                        help="the two sides' names in the CSV "
                        "(--reference's first)")
    parser.add_argument("--smoke", action="store_true",
                        help="only the seed's first cycle with cre, once")
    args = parser.parse_args()
    args.exe = common.check_executable(args.exe)
    common.print_header(args.exe)
    runs, repeats = (SMOKE, 1) if args.smoke else (RUNS, args.repeats)
    labels = args.labels.split(",")
    if len(labels) != 2:
        sys.exit("--labels: two names separated by a comma, got '%s'"
                 % args.labels)
    rows, failed = [], 0
    for repeat in range(repeats):
        for name, settings in runs.items():
            for blas, directory in zip(labels, (args.reference,
                                                args.openblas)):
                out_dir = args.outdir
                command = common.program_command(
                    args.exe, settings + ["Output/Write VTU=false",
                                          "Output/Output directory=" + out_dir],
                    PRM)
                env = common.program_env(args.exe)
                env["LD_LIBRARY_PATH"] = directory + ":" + env.get(
                    "LD_LIBRARY_PATH", "")
                load = common.loadavg()
                result = common.run(command, 900, env)
                failure = result.failure()
                if failure:
                    print("%s, %s: %s" % (name, blas, failure[1]), flush=True)
                    failed += 1
                    continue
                summary = common.read_summary(out_dir)
                last = common.last_cycle(summary)
                row = dict(run=name, blas=blas, repeat=repeat,
                           dofs=last["n_dofs"], cycles=len(summary["cycles"]),
                           wall_s=result.wall_s,
                           contact_solve_s=summed(summary, "contact solve"),
                           equilibration_s=summed(
                               summary, "error indicator: equilibration"),
                           indicator_s=summed(summary, "error indicator"),
                           adapt_mesh_s=summed(summary, "adapt mesh"),
                           epsilon=last["epsilon"], load_average=load)
                rows.append(row)
                print(", ".join("%s %s" % (k, common.cell(row[k]))
                                for k in FIELDS), flush=True)
    common.write_csv(args.csv, rows, FIELDS)
    if failed:
        sys.exit("%d run(s) failed" % failed)


if __name__ == "__main__":
    main()
