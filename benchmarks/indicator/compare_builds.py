#!/usr/bin/python3
"""Indicator cost of two (or more) builds on the small blocks meshes.

Each build is a directory holding `coulomb-adapt` and `libcoulomb_adapt.so`
(copy them out of build/ so that a rebuild does not change them under the
run). The builds run alternately, one cycle each, and the table gives the
median indicator time, contact-solve time and their ratio per mesh.

    /usr/bin/python3 benchmarks/indicator/compare_builds.py --repeats 9 \\
        old=/tmp/bin_old new=/tmp/bin_new
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))
PRM = os.path.join(ROOT, "prm", "blocks.prm")

MESHES = [
    ("P1 r = 0", "triangle", 0), ("P1 r = 1", "triangle", 1),
    ("P1 r = 2", "triangle", 2), ("Q1 r = 1", "quadrilateral", 1),
    ("Q1 r = 2", "quadrilateral", 2), ("Q1 r = 3", "quadrilateral", 3),
]


def run(build, cell, refinements, out_dir):
    args = [os.path.join(build, "coulomb-adapt"), PRM]
    for s in ["Mesh/Cell type=" + cell,
              "Mesh/Global refinements=%d" % refinements,
              "Adaptation/Strategy=uniform",
              "Adaptation/Minimum number of cycles=1",
              "Adaptation/Number of cycles=1",
              "Output/Write VTU=false",
              "Output/Output directory=" + out_dir]:
        args += ["-s", s]
    env = dict(os.environ, LD_LIBRARY_PATH=build, OMP_NUM_THREADS="1")
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL, env=env)
    with open(os.path.join(out_dir, "summary.json")) as f:
        cycle = json.load(f)["cycles"][0]
    t = cycle["timings_s"]
    return (cycle["n_dofs"], t["error indicator"], t["contact solve"],
            cycle["epsilon"])


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--repeats", type=int, default=9)
    p.add_argument("builds", nargs="+", help="label=directory")
    a = p.parse_args()
    builds = [b.split("=", 1) for b in a.builds]
    print("| mesh | DoFs | " + " | ".join(
        "%s indicator / solve [ms], fraction, epsilon" % l for l, _ in builds)
        + " |")
    print("|---|---|" + "---|" * len(builds))
    with tempfile.TemporaryDirectory() as tmp:
        for name, cell, r in MESHES:
            runs = {label: [] for label, _ in builds}
            for _ in range(a.repeats):
                for label, directory in builds:
                    runs[label].append(run(directory, cell, r, tmp))
            cells = []
            for label, _ in builds:
                x = runs[label]
                cells.append("%.2f / %.2f, %.1f %%, %.10g" % (
                    1e3 * statistics.median(v[1] for v in x),
                    1e3 * statistics.median(v[2] for v in x),
                    100 * statistics.median(v[1] / v[2] for v in x),
                    x[0][3]))
            print("| %s | %d | %s |" % (name, runs[builds[0][0]][0][0],
                                        " | ".join(cells)), flush=True)


if __name__ == "__main__":
    main()
