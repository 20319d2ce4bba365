#!/usr/bin/python3
"""Elasticity baseline benchmark of coulomb-adapt.

Runs the 'manufactured' scene (two independent unit squares, Q1, plane
strain, one cycle) over a ladder of uniform meshes, for the direct solver
(Amesos MUMPS) and CG + ML AMG, on 1 and 2 MPI ranks. Each run gets a fresh
output directory under /tmp; the numbers come from the run's summary.json
(phase timings, peak memory, iterations), except each body's solve time,
which the program only prints.

The machine is shared: before each run the script waits (--quiet-wait) for
the CPUs to be idle, and it records the CPU time other processes used during
the run. The executable (and the project library next to it) is copied to a
private directory first, so that a rebuild during the sweep does not affect
it. Plot and tables: report_benchmark.py (drawn at the end of a sweep).

  run_benchmark.py                 full sweep (~1e3 .. ~2e6 DoFs), CSV + PNG
  run_benchmark.py --quick         small sizes, one repeat
  run_benchmark.py --smoke         the smallest size, 1 rank (a few seconds)
  run_benchmark.py --max-dofs 3e5  restrict the sweep

Only the Python standard library and matplotlib are used.
"""

import argparse
import os
import shutil
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(
    __file__))))
import common  # noqa: E402
from common import fmt  # noqa: E402
import report_benchmark as report  # noqa: E402

# Mesh ladder: (coarse subdivisions per direction, global refinements).
# Both bodies get the same mesh of n = s * 2^r cells per direction, so each
# body has 2 (n+1)^2 DoFs and the run 4 (n+1)^2. Factor ~4 per step from
# 1156 to 1,050,625 DoFs; the last entry (n = 704) is an extension that gives
# one body ~1e6 DoFs (994,050; 1,988,100 in total).
LADDER = [(2, 3), (2, 4), (2, 5), (2, 6), (2, 7), (2, 8), (11, 6)]

FIELDS = [
    "repeat", "solver", "ranks", "subdivisions", "refinements", "n_dofs",
    "n_dofs_body1", "n_dofs_body2", "status", "setup_s", "assembly_s",
    "solve_s", "solve_body1_s", "solve_body2_s", "cycle_wall_s",
    "process_wall_s", "peak_memory_MiB", "peak_memory_total_MiB",
    "iterations_body1", "iterations_body2", "method",
    "rel_energy_error_body1", "rel_energy_error_body2", "loadavg_1min",
    "busy_cores_before", "other_cpu_s", "clean", "version", "message",
]


def expected_dofs(subdivisions, refinements):
    n = subdivisions * 2 ** refinements
    return 4 * (n + 1) ** 2


def run_one(exe, solver, ranks, subdivisions, refinements, timeout, keep,
            busy_before=float("nan")):
    """Runs one configuration; returns a dict with the FIELDS (minus
    'repeat')."""
    sub = "%d, %d" % (subdivisions, subdivisions)
    settings = [
        "Scene/Name=manufactured",
        "Scene/Manufactured/Body 1 subdivisions=" + sub,
        "Scene/Manufactured/Body 2 subdivisions=" + sub,
        "Mesh/Global refinements=%d" % refinements,
        "Mesh/Cell type=quadrilateral",
        "Finite elements/Polynomial degree=1",
        "Finite elements/Plane model=plane strain",
        "Adaptation/Number of cycles=1",
        "Linear solver/Type=" + solver,
    ]
    row = {k: "" for k in FIELDS if k != "repeat"}
    row.update(solver=solver, ranks=ranks, subdivisions=subdivisions,
               refinements=refinements,
               n_dofs=expected_dofs(subdivisions, refinements),
               loadavg_1min=common.loadavg(),
               busy_cores_before=round(busy_before, 3))
    result, summary = common.run_program(exe, settings, timeout,
                                         ranks=ranks, keep=keep)
    if result.killed:
        status, message = result.failure()
        row.update(status=status, message=message)
        return row
    row["process_wall_s"] = round(result.wall_s, 3)
    row["other_cpu_s"] = round(result.other_cpu_s, 2)
    row["clean"] = int(result.clean)
    cycle = common.last_cycle(summary)
    failure = result.failure() or (None if cycle else (
        "failed", "no cycle in summary.json"))
    if failure:
        row.update(status=failure[0], message=failure[1])
        return row
    solvers = cycle["linear_solver"]
    row.update(
        status="ok",
        n_dofs=cycle["n_dofs"],
        n_dofs_body1=common.body_field(cycle, 0, "n_dofs"),
        n_dofs_body2=common.body_field(cycle, 1, "n_dofs"),
        setup_s=common.timing(cycle, "setup"),
        assembly_s=common.timing(cycle, "assembly"),
        solve_s=common.timing(cycle, "solve"),
        cycle_wall_s=cycle["wall_time_s"],
        peak_memory_MiB=cycle["peak_memory_MiB"],
        peak_memory_total_MiB=cycle["peak_memory_total_MiB"],
        iterations_body1=solvers[0]["iterations"],
        iterations_body2=solvers[1]["iterations"],
        method=solvers[0]["method"],
        rel_energy_error_body1=common.body_field(
            cycle, 0, "exact_error", {}).get("relative_energy", ""),
        rel_energy_error_body2=common.body_field(
            cycle, 1, "exact_error", {}).get("relative_energy", ""),
        version=summary.get("version", ""),
    )
    # Each body's solve wall time is only printed (3 significant digits).
    per_body = common.body_solve_times(result.stdout)
    if len(per_body) == 2:
        row["solve_body1_s"], row["solve_body2_s"] = \
            per_body[0][1], per_body[1][1]
    return row


def sweep(opts):
    ladder = [(s, r) for s, r in LADDER
              if opts.min_dofs <= expected_dofs(s, r) <= opts.max_dofs]
    configs = [(sv, nr) for nr in opts.ranks for sv in opts.solvers]
    if not ladder or not configs:
        sys.exit("nothing to run: check --min-dofs/--max-dofs/--solvers/"
                 "--ranks")
    exe = common.check_executable(opts.exe)
    common.print_header(exe)
    if not opts.no_snapshot:
        exe = common.snapshot_executable(exe)
        print("running a private copy of %s in %s" % (
            opts.exe, os.path.dirname(exe)), flush=True)

    # The CSV is rewritten after every run so that an interrupted sweep
    # keeps what it measured. With --append the new runs are added to the
    # existing rows (numbered after the repeats already there).
    rows = []
    first_repeat = 0
    if opts.append:
        rows = common.read_csv(opts.csv, text=report.TEXT,
                               ints=("ranks", "n_dofs"))
        for r in rows:
            first_repeat = max(first_repeat, int(r["repeat"]) + 1)
    old_failures = [r for r in rows if r["status"] != "ok"]

    def flush():
        common.write_csv(opts.csv, rows, FIELDS, float_format="%r")

    t0 = time.perf_counter()
    broken = {}  # config -> first failing size: larger sizes are skipped
    # Repeats are the outer loop so that a slow phase of the machine does
    # not hit all repeats of one configuration.
    for x in old_failures:
        key = (x["solver"], x["ranks"])
        broken[key] = min(broken.get(key, x["n_dofs"]), x["n_dofs"])
    for rep in range(first_repeat, first_repeat + opts.repeats):
        for s, r in ladder:
            for sv, nr in configs:
                n = expected_dofs(s, r)
                if (sv, nr) in broken and n > broken[(sv, nr)]:
                    if rep == first_repeat and not any(
                            x["solver"] == sv and x["ranks"] == nr
                            and x["n_dofs"] == n for x in rows):
                        row = {k: "" for k in FIELDS}
                        row.update(repeat=rep, solver=sv, ranks=nr,
                                   subdivisions=s, refinements=r, n_dofs=n,
                                   status="skipped",
                                   message="a smaller size failed")
                        rows.append(row)
                        flush()
                    continue
                if any(x["status"] != "ok" and x["solver"] == sv
                        and x["ranks"] == nr and x["n_dofs"] == n
                        for x in rows):
                    continue  # do not repeat a failure or a timeout
                busy = common.wait_for_quiet(opts.quiet_wait,
                                             opts.quiet_threshold)
                row = run_one(exe, sv, nr, s, r, opts.timeout, opts.keep,
                              busy)
                row["repeat"] = rep
                rows.append(row)
                flush()
                if row["status"] != "ok":
                    broken[(sv, nr)] = n
                print("[%7.1f s] repeat %d  %-6s %d rank(s)  %9d DoFs  %s"
                      "  solve %s s  wall %s s  mem %s MiB  its %s/%s"
                      "  other CPU %s s" %
                      (time.perf_counter() - t0, rep, sv, nr, row["n_dofs"],
                       row["status"], fmt(row["solve_s"]),
                       fmt(row["process_wall_s"]),
                       fmt(row["peak_memory_MiB"]), row["iterations_body1"],
                       row["iterations_body2"], fmt(row["other_cpu_s"], 2)),
                      flush=True)
                if row["status"] != "ok":
                    print("    " + row["message"], flush=True)
    print("sweep done in %.0f s; results in %s" %
          (time.perf_counter() - t0, opts.csv))
    if not opts.no_snapshot:
        shutil.rmtree(os.path.dirname(exe), ignore_errors=True)


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.
                                RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=common.DEFAULT_EXE,
                   help="coulomb-adapt executable (default: %(default)s)")
    p.add_argument("--csv", default=report.DEFAULT_CSV,
                   help="results file (default: %(default)s)")
    p.add_argument("--png", default=report.DEFAULT_PNG,
                   help="plot file (default: %(default)s)")
    p.add_argument("--max-dofs", type=float, default=2.1e6,
                   help="largest total DoF count to run (default: "
                        "%(default)g; 1.1e6 stops at the ~1e6 step)")
    p.add_argument("--min-dofs", type=float, default=0,
                   help="smallest total DoF count to run")
    p.add_argument("--solvers", default="direct,amg",
                   help="comma-separated subset of direct,amg")
    p.add_argument("--ranks", default="1,2",
                   help="comma-separated MPI rank counts (default 1,2)")
    p.add_argument("--repeats", type=int, default=3,
                   help="runs per configuration; the plot and tables use "
                        "the fastest clean one (default: %(default)s)")
    p.add_argument("--timeout", type=float, default=900,
                   help="seconds before a run is killed and recorded as "
                        "'timeout' (default: %(default)s)")
    p.add_argument("--quick", action="store_true",
                   help="up to ~7e4 DoFs, one repeat")
    p.add_argument("--smoke", action="store_true",
                   help="the smallest size, 1 rank, one repeat, no wait "
                        "for a quiet machine, no private copy (ctest)")
    p.add_argument("--append", action="store_true",
                   help="add the runs to the existing CSV instead of "
                        "starting a new one (e.g. more repeats of some "
                        "sizes)")
    p.add_argument("--quiet-wait", type=float, default=300,
                   help="before each run, wait up to this many seconds for "
                        "other processes to leave the CPUs idle (0: do not "
                        "wait; default: %(default)s)")
    p.add_argument("--quiet-threshold", type=float, default=0.15,
                   help="CPU cores that other processes may use for the "
                        "machine to count as idle (default: %(default)s)")
    p.add_argument("--no-snapshot", action="store_true",
                   help="run the executable in place instead of a private "
                        "copy made at the start of the sweep")
    p.add_argument("--keep", action="store_true",
                   help="keep the /tmp output directories")
    p.add_argument("--no-plot", action="store_true",
                   help="do not write the PNG after the sweep")
    opts = p.parse_args()
    opts.solvers = [s.strip() for s in opts.solvers.split(",") if s.strip()]
    opts.ranks = [int(s) for s in opts.ranks.split(",") if s.strip()]
    for s in opts.solvers:
        if s not in ("direct", "amg", "auto"):
            p.error("unknown solver '%s'" % s)
    if opts.quick:
        opts.max_dofs = min(opts.max_dofs, 7e4)
        opts.repeats = 1
    if opts.smoke:
        opts.max_dofs, opts.ranks, opts.repeats = 2e3, [1], 1
        opts.quiet_wait, opts.no_snapshot = 0, True
    sweep(opts)
    if not opts.no_plot:
        report.plot(opts.csv, opts.png)


if __name__ == "__main__":
    main()
