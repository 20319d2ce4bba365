#!/usr/bin/python3
"""Where an adaptive run spends its time (issue 18): prm/blocks.prm
(remesh, P1 triangles, mu = 0.3) for epsilon_0 = 0.25 % and 1 %, with the
fields written (the default, Output/Write cycles = all), per output variant
and executable. Each run is one process (1 rank, OMP_NUM_THREADS=1); its
summary.json gives the per-cycle phase times (timings_s), summed here over
the cycles; the wall time is the process's.

  benchmarks/adaptive_run/run_adaptive_run.py [--exe build/coulomb-adapt]
      [--baseline EXE] [--repeat N] [--ranks 1,2] [--targets 0.25,1]
      [--variants vtu,...] [--set "Path/Entry=value" ...]
      [--baseline-set "Path/Entry=value" ...] [--baseline-env NAME=VALUE ...]
      [--csv results.csv]

--baseline runs an older executable (e.g. a copy of main's build) with the
variant 'vtu' only (older builds know no Output/Format). --set adds a
setting (as -s) to every run of --exe, not of --baseline (e.g.
"Adaptation/Remeshing split above cells=0"); --baseline-set does so for
--baseline (which may be --exe: two settings of one build); --baseline-env sets an environment variable
for --baseline's runs. --ranks runs each
case on each number of MPI ranks (mpirun; the phase times are rank 0's).
Writes results.csv (or --csv) beside this script and prints a Markdown
table. The machine is shared:
other_cpu_s is the CPU time other processes took during the run.
"""

import argparse
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
TARGETS = ["0.25", "1"]
VARIANTS = {
    "vtu": [],
    "vtu last": ["Output/Write cycles=last"],
    "hdf5": ["Output/Format=hdf5"],
}
PHASES = ["setup", "assembly", "contact solve", "error indicator",
          "output", "adapt mesh"]
FIELDS = (["build", "ranks", "target_percent", "variant", "cycles", "dofs", "epsilon",
           "newton", "wall_s", "other_cpu_s", "peak_memory_MiB"]
          + [p.replace(" ", "_") + "_s" for p in PHASES]
          + ["output_share", "remesh_share", "wall_over_solve_estimate",
             "command"])


def one_run(build, exe, target, variant, ranks, settings=(), environment=()):
    out_dir = tempfile.mkdtemp(prefix="coulomb-bench-")
    args = common.program_command(
        exe, ["Adaptation/Target error=" + target]
        + VARIANTS[variant] + list(settings)
        + ["Output/Output directory=" + out_dir],
        prm=os.path.join(common.PRM_DIR, "blocks.prm"), ranks=ranks)
    env = common.program_env(exe)
    env.update(e.split("=", 1) for e in environment)
    run = common.run(args, 1800, env)
    summary = common.read_summary(out_dir)
    shutil.rmtree(out_dir, ignore_errors=True)
    if run.failure() or not summary:
        raise SystemExit("%s failed: %s" % (common.shell_command(args),
                                             run.failure()))
    cycles = summary["cycles"]
    row = dict(build=build, ranks=ranks, target_percent=target, variant=variant,
               cycles=len(cycles), dofs=cycles[-1]["n_dofs"],
               epsilon=cycles[-1]["epsilon"],
               newton=sum(c.get("newton_iterations", 0) for c in cycles),
               wall_s=run.wall_s, other_cpu_s=run.other_cpu_s,
               peak_memory_MiB=cycles[-1]["peak_memory_MiB"],
               command=common.shell_command(args))
    for p in PHASES:
        row[p.replace(" ", "_") + "_s"] = sum(
            c["timings_s"].get(p, 0.) for c in cycles)
    row["output_share"] = row["output_s"] / run.wall_s
    row["remesh_share"] = row["adapt_mesh_s"] / run.wall_s
    row["wall_over_solve_estimate"] = run.wall_s / (
        row["contact_solve_s"] + row["error_indicator_s"])
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--exe", default=common.DEFAULT_EXE)
    parser.add_argument("--baseline", help="an older executable")
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--ranks", default="1",
                        help="comma-separated numbers of MPI ranks")
    parser.add_argument("--targets", default=",".join(TARGETS))
    parser.add_argument("--variants", default=",".join(VARIANTS))
    parser.add_argument("--set", action="append", default=[],
                        metavar="PATH=VALUE",
                        help="a setting for the runs of --exe (repeatable)")
    parser.add_argument("--baseline-set", action="append", default=[],
                        metavar="PATH=VALUE",
                        help="a setting for the runs of --baseline "
                        "(repeatable): with --baseline = --exe, compares "
                        "two settings of one build")
    parser.add_argument("--baseline-env", action="append", default=[],
                        metavar="NAME=VALUE",
                        help="an environment variable for the runs of "
                        "--baseline (repeatable), e.g. an MPI setting the "
                        "program would otherwise choose itself")
    parser.add_argument("--csv", default="results.csv")
    args = parser.parse_args()
    ranks = [int(r) for r in args.ranks.split(",")]
    targets = args.targets.split(",")
    variants = args.variants.split(",")
    for v in variants:
        if v not in VARIANTS:
            raise SystemExit("--variants: '%s' is not one of %s"
                             % (v, ", ".join(VARIANTS)))
    builds = [("this", common.check_executable(args.exe), variants,
               args.set, [])]
    if args.baseline:
        builds.insert(0, ("baseline", common.check_executable(args.baseline),
                          [v for v in variants if v == "vtu"],
                          args.baseline_set, args.baseline_env))
    common.print_header(builds[-1][1])
    rows = []
    for _ in range(args.repeat):
        for target in targets:
            for n in ranks:
                for build, exe, build_variants, settings, env in builds:
                    for variant in build_variants:
                        rows.append(one_run(build, exe, target, variant, n,
                                            settings, env))
                        common.write_csv(os.path.join(HERE, args.csv),
                                         rows, FIELDS)
    print("| build | ranks | eps0 % | output | cycles | DoFs | wall s | output s "
          "| adapt mesh s | contact s | output % | remesh % | wall/(solve+est)"
          " | other CPU s |")
    print("|---" * 14 + "|")
    for r in rows:
        print("| %s | %d | %s | %s | %d | %d | %s | %s | %s | %s | %s | %s "
              "| %s | %s |" % (
                  r["build"], r["ranks"], r["target_percent"], r["variant"], r["cycles"],
                  r["dofs"], common.fmt(r["wall_s"]),
                  common.fmt(r["output_s"]), common.fmt(r["adapt_mesh_s"]),
                  common.fmt(r["contact_solve_s"]),
                  common.fmt(100 * r["output_share"], 2),
                  common.fmt(100 * r["remesh_share"], 2),
                  common.fmt(r["wall_over_solve_estimate"]),
                  common.fmt(r["other_cpu_s"], 2)))


if __name__ == "__main__":
    main()
