#!/usr/bin/python3
"""cre on a body held on a line: the line's reaction is carried.

punch (P1 triangles, remesh, mu = 0.3, cre) to epsilon_0 = 2 %, two cycles,
once with 'Hold centre line' (the default: u_x = 0 on the punch's nodes on
x = 0) and once without (friction holds the punch). The first cycle's mesh
is symmetric about x = 0, the remeshed one is not: there the FE solution
has a reaction on the held line, which the equilibrated stress carries as
a jump of sigma^ n across the line (held_reactions.h). Before, it did not:
the local problems' loads missed equilibrium by 1.1e-3 there. Checks, per
cycle (summary.json's cre record and the log):
  - held: the node systems' defect and the local problems' rigid-motion
    load are round-off (< 1e-10) on both meshes, nothing is left
    uncarried (cre.uncarried_held_reaction), no warning;
  - not held: below 1e-5 (the floating body's resultant, spread by the
    corrected solve), no warning.
And prm/press_fit.prm with cre: its point supports hold single nodes, on
no line of faces, so their (small) reaction stays uncarried: reported
above 1e-8 of the largest element residual, with the warning.

usage: cre_held_line.py EXE PRM_DIR OUTPUT_DIR
"""

import os
import re
import sys

from coulomb_adapt_run import report, run_cycles

WARNING = "cre: warning: the reaction of nodes held"


def run(exe, prm_dir, directory, hold):
    cycles, log = run_cycles(
        exe, os.path.join(prm_dir, "punch.prm"), directory,
        ["Mesh/Cell type=triangle", "Adaptation/Strategy=remesh",
         "Error indicator/Estimator=cre",
         "Adaptation/Target error=2",
         "Adaptation/Number of cycles=2",
         "Adaptation/Minimum number of cycles=2",
         "Output/Write cycles=none",
         "Scene/Punch/Hold centre line=" + str(hold).lower()])
    # The log's cycles: the text up to each cycle's "Cycle N: ..." line.
    return cycles, re.split(r"\nCycle [0-9]+: ", log)


def main():
    exe, prm_dir, output = [os.path.abspath(a) for a in sys.argv[1:4]]
    failures = []
    for hold in (True, False):
        cycles, logs = run(exe, prm_dir,
                           os.path.join(output, "hold" if hold else "free"),
                           hold)
        if len(cycles) != 2:
            failures.append("hold = %s: %d cycles, expected 2" %
                            (hold, len(cycles)))
            continue
        for c, cycle in enumerate(cycles):
            cre = cycle["cre"]
            defect = cre["local_problem_defect"]
            warned = WARNING in logs[c]
            print("hold = %-5s cycle %d: %6d DoFs, local problems' "
                  "rigid-motion load %s, warning %s" %
                  (hold, c, cycle["n_dofs"],
                   "< 1e-10" if defect < 1e-10 else
                   "< 1e-5" if defect < 1e-5 else "> 1e-5",
                   "yes" if warned else "no"))
            if hold and not (defect < 1e-10 and
                             cre["node_system_defect"] < 1e-10 and
                             cre["uncarried_held_reaction"] < 1e-12 and
                             not warned):
                failures.append("held, cycle %d: defect %g, node systems "
                                "%g, uncarried %g, warning %s" %
                                (c, defect, cre["node_system_defect"],
                                 cre["uncarried_held_reaction"], warned))
            if not hold and not (defect < 1e-5 and not warned):
                failures.append("not held, cycle %d: defect %g, warning %s"
                                % (c, defect, warned))
    cycles, log = run_cycles(
        exe, os.path.join(prm_dir, "press_fit.prm"),
        os.path.join(output, "press_fit"),
        ["Error indicator/Estimator=cre", "Output/Write cycles=none"],
        cwd=os.path.dirname(prm_dir))
    cre = cycles[0]["cre"]
    warned = WARNING in log
    print("press_fit (point supports): uncarried reaction %s, warning %s" %
          ("> 1e-8" if cre["uncarried_held_reaction"] > 1e-8 else "<= 1e-8",
           "yes" if warned else "no"))
    if not (cre["uncarried_held_reaction"] > 1e-8 and warned):
        failures.append("press_fit: uncarried %g, warning %s" %
                        (cre["uncarried_held_reaction"], warned))

    return report(failures)


if __name__ == "__main__":
    sys.exit(main())
