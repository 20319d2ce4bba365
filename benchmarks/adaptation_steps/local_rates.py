#!/usr/bin/python3
"""How fast the error fell near a singular point between two cycles of a
remesh run (P1 triangles), cell by cell: the measurement behind
near_singular_point (include/coulomb_adapt/adaptation/optimal_size.h).

For every cell of cycle C (both bodies) within --within cell diameters of
a point, the cells of cycle C + 1 whose centres lie in it give its
measured error e_new^2 (the sum of their error_indicator^2) and its size
ratio r = sqrt(mean new cell area / old cell area); the measured rate is
q = log(e_new^2 / e_old^2) / (2 log r), the q_E of the plan's model
e_new^2 = r^(2 q) e_old^2. d/h is the cell's distance to the point (its
nearest vertex) over its diameter. At the end, the error-weighted rate of
the cells nearer than half a diameter and of the others.

usage: local_rates.py OUTPUT_DIR CYCLE --point=X,Y [--point=X,Y ...]
       [--within 3]
       local_rates.py --smoke --exe EXE
OUTPUT_DIR is a run's 'Output directory' with the fields of cycles C and
C + 1 written (VTU, the default). --smoke runs punch (remesh, epsilon_0 =
5 %) into a temporary directory and reads its cycle 1: it checks that the
script runs, not the numbers.
"""

import argparse
import math
import os
import shutil
import sys
import tempfile
import xml.etree.ElementTree as ElementTree

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tests"))
import common  # noqa: E402
from vtu_pieces import point_rows, pieces_of  # noqa: E402


def triangles(directory, cycle):
    """[(vertices, error_indicator^2)] of both bodies' cells."""
    cells = []
    for body in (1, 2):
        record = "body-%d_%03d.pvtu" % (body, cycle)
        root = ElementTree.parse(os.path.join(directory, record)).getroot()
        arrays = list(root.find("PUnstructuredGrid/PPointData"))
        names = [a.get("Name") for a in arrays]
        widths = [int(a.get("NumberOfComponents", "1")) for a in arrays]
        column = 3 + sum(widths[:names.index("error_indicator")])
        for piece in pieces_of(directory, record):
            n_cells, rows = point_rows(os.path.join(directory, piece))
            per_cell = len(rows) // n_cells
            if per_cell != 3:
                sys.exit("%s: %d points per cell: only P1 triangles are "
                         "supported" % (piece, per_cell))
            for c in range(n_cells):
                corner = rows[3 * c:3 * c + 3]
                cells.append(([(r[0], r[1]) for r in corner],
                              corner[0][column] ** 2))
    return cells


def area(t):
    (ax, ay), (bx, by), (cx, cy) = t
    return abs((bx - ax) * (cy - ay) - (cx - ax) * (by - ay)) / 2


def diameter(t):
    return max(math.dist(t[i], t[j]) for i in range(3) for j in range(i))


def contains(t, x, y):
    (ax, ay), (bx, by), (cx, cy) = t
    d1 = (bx - ax) * (y - ay) - (by - ay) * (x - ax)
    d2 = (cx - bx) * (y - by) - (cy - by) * (x - bx)
    d3 = (ax - cx) * (y - cy) - (ay - cy) * (x - cx)
    return (d1 >= 0 and d2 >= 0 and d3 >= 0) or \
        (d1 <= 0 and d2 <= 0 and d3 <= 0)


def smoke(exe):
    """Punch remeshed for 5 % (552 -> 1,316 -> ... DoFs), fields
    written; the rates of its cycle 1 at the punch's corners."""
    directory = tempfile.mkdtemp(prefix="coulomb-local-rates-")
    try:
        result = common.run(common.program_command(
            exe, ["Mesh/Cell type=triangle", "Adaptation/Strategy=remesh",
                  "Adaptation/Target error=5",
                  "Adaptation/Number of cycles=4",
                  "Adaptation/Minimum number of cycles=1",
                  "Output/Output directory=" + directory],
            prm=os.path.join(common.ROOT, "prm/punch.prm")),
            300, common.program_env(exe))
        failure = result.failure()
        if failure:
            sys.exit("the punch run failed (%s): %s" % failure)
        analyse(directory, 1, ["-10,0", "10,0"], 3)
    finally:
        shutil.rmtree(directory, ignore_errors=True)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("directory", nargs="?")
    p.add_argument("cycle", type=int, nargs="?")
    p.add_argument("--point", action="append")
    p.add_argument("--within", type=float, default=3)
    p.add_argument("--smoke", action="store_true")
    p.add_argument("--exe", default=os.path.join(common.ROOT,
                                                 "build/coulomb-adapt"))
    a = p.parse_args()
    if a.smoke:
        smoke(a.exe)
    elif a.directory is None or a.cycle is None or not a.point:
        p.error("OUTPUT_DIR, CYCLE and at least one --point are needed")
    else:
        analyse(a.directory, a.cycle, a.point, a.within)


def analyse(directory, cycle, points, within):
    old = triangles(directory, cycle)
    new = triangles(directory, cycle + 1)
    centres = [((sum(v[0] for v in t) / 3, sum(v[1] for v in t) / 3), e,
                area(t)) for t, e in new]
    weighted = {True: [0.0, 0.0], False: [0.0, 0.0]}
    for text in points:
        point = tuple(float(x) for x in text.split(","))
        near = [(t, e) for t, e in old
                if min(math.dist(v, point) for v in t) <
                within * diameter(t)]
        if not near:
            print("cycle %d, point (%g, %g): no cell within %g diameters"
                  % (cycle, point[0], point[1], within))
            continue
        reach = max(min(math.dist(v, point) for v in t) + diameter(t)
                    for t, _ in near)
        print("cycle %d, point (%g, %g): %d cells within %g diameters"
              % (cycle, point[0], point[1], len(near), within))
        print("  %7s %11s %7s %11s %7s" % ("d/h", "e_old^2", "r",
                                           "e_new^2", "q"))
        rows = []
        for t, e in near:
            e_new = n_new = area_new = 0
            for (x, y), e2, a2 in centres:
                if math.dist((x, y), point) <= reach and contains(t, x, y):
                    e_new += e2
                    n_new += 1
                    area_new += a2
            if n_new == 0 or e <= 0 or e_new <= 0:
                continue
            r = math.sqrt(area_new / n_new / area(t))
            relative = min(math.dist(v, point) for v in t) / diameter(t)
            q = math.log(e_new / e) / (2 * math.log(r)) if r < 0.8 else None
            rows.append((relative, e, r, e_new, q))
            if q is not None:
                w = weighted[relative < 0.5]
                w[0] += e
                w[1] += e * q
        if not rows:
            print("  no cell of cycle %d near it holds cycle %d cells with "
                  "an error" % (cycle, cycle + 1))
            continue
        largest = max(row[1] for row in rows)
        for relative, e, r, e_new, q in sorted(rows):
            if e >= 1e-3 * largest:
                print("  %7.3f %11.3e %7.3f %11.3e %7s"
                      % (relative, e, r, e_new,
                         "-" if q is None else "%.3f" % q))
    for is_near, (weight, sum_q) in weighted.items():
        if weight > 0:
            print("error-weighted q of the cells %s half a diameter: %.3f"
                  % ("nearer than" if is_near else "at or beyond",
                     sum_q / weight))


if __name__ == "__main__":
    main()
