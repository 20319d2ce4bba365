#!/usr/bin/env python3
"""Hertz with a block much wider than the disc (R = 10 mm, block 200 mm
wide: the scene's default block under a disc a tenth of its default
radius), frictionless, P1 triangles and Q1 quadrilaterals: the peak
pressure within 2 % of Hertz's p0 = 2 P' / (pi a) (summary.json's
reference) and no initial overlap beyond the mesh's round-off (1e-4 mm).

The disc's flanks turn away from the block: segments there face it at
up to 90 degrees. Paired with the block's far ends (which a block wider
than about 7 R puts in front of them), their weighted gaps came out at
-34 mm (P1) and -48 mm (Q1), two flank nodes carried the load, the
peak pressure was 630 MPa against Hertz's 1,508 MPa and epsilon 2867 %
(3372 % on Q1), with no warning. The mortar pairs only segments within
60 degrees of facing each other (mortar_interface.cc).

usage: hertz_wide_block.py EXE PRM_DIR OUTPUT_DIR
"""

import json
import os
import sys

from coulomb_adapt_run import report, run_cycles


def main():
    exe, prm_dir, output = [os.path.abspath(a) for a in sys.argv[1:4]]
    failures = []
    for cell_type in ("triangle", "quadrilateral"):
        cycles, _ = run_cycles(
            exe, os.path.join(prm_dir, "hertz.prm"),
            os.path.join(output, cell_type),
            ["Scene/Hertz/Radius=10", "Scene/Hertz/Block width=200",
             "Contact/Friction coefficient=0",
             "Mesh/Cell type=" + cell_type,
             "Adaptation/Number of cycles=1",
             "Output/Write cycles=none"])
        with open(os.path.join(output, cell_type, "summary.json")) as f:
            p0 = json.load(f)["reference"]["hertz_peak_pressure"]
        cycle = cycles[0]
        ratio = cycle["max_contact_pressure"] / p0
        overlap = cycle["initial_overlap"]
        print("%s: peak pressure / Hertz's p0 %s, initial overlap %s" %
              (cell_type,
               "within 2 %" if abs(ratio - 1) <= 0.02 else "%.3f" % ratio,
               "<= 1e-4 mm" if overlap <= 1e-4 else "%g mm" % overlap))
        if not (abs(ratio - 1) <= 0.02 and overlap <= 1e-4):
            failures.append("%s: p / p0 = %.4f, initial overlap %g mm" %
                            (cell_type, ratio, overlap))
    return report(failures)


if __name__ == "__main__":
    sys.exit(main())
