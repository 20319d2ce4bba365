#!/usr/bin/python3
"""Indicator cost of two (or more) builds on the small blocks meshes.

Each build is a directory holding `coulomb-adapt` and `libcoulomb_adapt.so`
(copy them out of build/ so that a rebuild does not change them under the
run). The builds run alternately, one cycle each; every run is a row of the
CSV (--csv), and the table (report_indicator_benchmark.py --compare-builds
CSV, printed at the end) gives the median indicator time, contact-solve
time and their ratio per mesh.

    /usr/bin/python3 benchmarks/indicator/compare_builds.py --repeats 9 \\
        old=/tmp/bin_old new=/tmp/bin_new
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(
    __file__))))
import common  # noqa: E402
import report_indicator_benchmark as report  # noqa: E402

PRM = os.path.join(common.PRM_DIR, "blocks.prm")

MESHES = [
    ("P1 r = 0", "triangle", 0), ("P1 r = 1", "triangle", 1),
    ("P1 r = 2", "triangle", 2), ("Q1 r = 1", "quadrilateral", 1),
    ("Q1 r = 2", "quadrilateral", 2), ("Q1 r = 3", "quadrilateral", 3),
]
FIELDS = ["build", "directory", "mesh", "repeat", "n_dofs", "indicator_s",
          "contact_solve_s", "epsilon", "version"]


def run(build, cell, refinements, timeout):
    result, summary = common.run_program(
        os.path.join(build, "coulomb-adapt"),
        ["Mesh/Cell type=" + cell,
         "Mesh/Global refinements=%d" % refinements,
         "Adaptation/Strategy=uniform",
         "Adaptation/Minimum number of cycles=1",
         "Adaptation/Number of cycles=1"], timeout, PRM)
    cycle = common.last_cycle(summary)
    failure = result.failure()
    if failure or cycle is None:
        raise SystemExit("%s, %s r = %d: %s" % (
            build, cell, refinements, failure[1] if failure
            else "no cycle in summary.json"))
    return dict(n_dofs=cycle["n_dofs"],
                indicator_s=common.timing(cycle, "error indicator"),
                contact_solve_s=common.timing(cycle, "contact solve"),
                epsilon=cycle["epsilon"], version=summary.get("version", ""))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--repeats", type=int, default=9)
    p.add_argument("--csv", default="/tmp/compare_builds.csv",
                   help="the runs (default: %(default)s)")
    p.add_argument("--timeout", type=float, default=300)
    p.add_argument("--smoke", action="store_true",
                   help="the smallest mesh, once (ctest)")
    p.add_argument("builds", nargs="+", help="label=directory")
    a = p.parse_args()
    builds = []
    for b in a.builds:
        label, sep, directory = b.partition("=")
        if not sep or not os.access(os.path.join(directory, "coulomb-adapt"),
                                    os.X_OK):
            p.error("'%s': expected label=directory with coulomb-adapt in "
                    "the directory" % b)
        builds.append((label, os.path.abspath(directory)))
    meshes, repeats = (MESHES[:1], 1) if a.smoke else (MESHES, a.repeats)
    rows = []
    for name, cell, r in meshes:
        for k in range(repeats):
            for label, directory in builds:
                rows.append(dict(run(directory, cell, r, a.timeout),
                                 build=label, directory=directory, mesh=name,
                                 repeat=k))
        common.write_csv(a.csv, rows, FIELDS, float_format="%.10g")
        print("%s done" % name, flush=True)
    print(report.compare_builds_table(a.csv))
    return 0


if __name__ == "__main__":
    sys.exit(main())
