#!/usr/bin/python3
"""cre on a body held on a line: the warning, and what it is about.

punch (P1 triangles, remesh, mu = 0.3, cre) to epsilon_0 = 2 %, two cycles,
once with 'Hold centre line' (the default: u_x = 0 on the punch's nodes on
x = 0) and once without (friction holds the punch). The first cycle's mesh
is symmetric about x = 0, the remeshed one is not: there the FE solution
has a reaction on the held line, which the equilibrated stress does not
carry. Checks, per cycle (summary.json's cre record and the log):
  - held: the defect is round-off (< 1e-10) on the symmetric mesh, without
    a warning, and above 1e-5 on the remeshed one, with the warning and
    cre.held_line = true;
  - not held: below 1e-5 on both meshes, no warning, held_line = false.

usage: cre_held_line.py EXE PRM_DIR OUTPUT_DIR
"""

import json
import os
import re
import shutil
import subprocess
import sys

WARNING = "cre: warning: a body is held at nodes"


def run(exe, prm_dir, directory, hold):
    shutil.rmtree(directory, ignore_errors=True)
    command = [exe, os.path.join(prm_dir, "punch.prm")]
    for setting in ["Mesh/Cell type=triangle", "Adaptation/Strategy=remesh",
                    "Error indicator/Estimator=cre",
                    "Adaptation/Target error=2",
                    "Adaptation/Number of cycles=2",
                    "Adaptation/Minimum number of cycles=2",
                    "Output/Write cycles=none",
                    "Scene/Punch/Hold centre line=" + str(hold).lower(),
                    "Output/Output directory=" + directory]:
        command += ["-s", setting]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("run failed (%s):\n%s%s" %
                 (" ".join(command), result.stdout, result.stderr))
    with open(os.path.join(directory, "summary.json")) as f:
        cycles = json.load(f)["cycles"]
    # The log's cycles: the text up to each cycle's "Cycle N: ..." line.
    logs = re.split(r"\nCycle [0-9]+: ", result.stdout)
    return cycles, logs


def main():
    exe, prm_dir, output = sys.argv[1:4]
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
                  "rigid-motion load %s, held_line %s, warning %s" %
                  (hold, c, cycle["n_dofs"],
                   "< 1e-10" if defect < 1e-10 else
                   "< 1e-5" if defect < 1e-5 else "> 1e-5",
                   str(cre["held_line"]).lower(),
                   "yes" if warned else "no"))
            if cre["held_line"] != hold:
                failures.append("hold = %s, cycle %d: held_line = %s" %
                                (hold, c, cre["held_line"]))
            if hold and c == 0 and not (defect < 1e-10 and not warned):
                failures.append("symmetric mesh: defect %g, warning %s" %
                                (defect, warned))
            if hold and c == 1 and not (defect > 1e-5 and warned):
                failures.append("remeshed, held: defect %g, warning %s" %
                                (defect, warned))
            if not hold and not (defect < 1e-5 and not warned):
                failures.append("not held, cycle %d: defect %g, warning %s"
                                % (c, defect, warned))
    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        return 1
    print("OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
