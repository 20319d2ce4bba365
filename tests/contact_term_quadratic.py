#!/usr/bin/python3
"""The contact term of the indicator with quadratic elements (P2, Q2).

Its density c = mu |R_n||W_t| + R_t W_t + R_n W_n is >= 0 for admissible
tractions (theory.md section 3.4), and the nodal tractions are admissible,
but their quadratic interpolants overshoot between the nodes. Without the
projection onto the admissible set (indicator/contact_error.cc) c went
negative: epsilon fell below its own volume parts and "target reached"
was claimed for a mesh whose volume error alone exceeded the target
(hertz P2: 0.413 % against 0.423 %). Checks, for each run:
  - epsilon^2 = vol_1^2 + vol_2^2 + contact^2, the printed parts to their
    3 decimals and summary.json's to 1e-12 of epsilon^2, hence epsilon >=
    its volume part;
  - the contact error density is >= 0 at every slave node (contact CSV).
Usage: contact_term_quadratic.py EXE OUTPUT_DIR PRM_DIR
"""
import csv
import json
import math
import os
import re
import subprocess
import sys

RUNS = {
    "hertz_p2_triangles": ["Mesh/Cell type=triangle"],
    "hertz_q2_frictionless": ["Mesh/Cell type=quadrilateral",
                              "Contact/Friction coefficient=0"],
    # cre adds the same contact term to its own volume parts.
    "hertz_p2_frictionless_cre": ["Mesh/Cell type=triangle",
                                  "Contact/Friction coefficient=0",
                                  "Error indicator/Estimator=cre"],
}
LINE = re.compile(r"error indicator \((?:zz|spr|cre)\): epsilon = "
                  r"([0-9.]+) % \(volume: body 1 ([0-9.]+) %, body 2 "
                  r"([0-9.]+) %; contact ([0-9.]+) %\)")


def main():
    exe, out, prm_dir = sys.argv[1:4]
    failures = []
    for name, settings in RUNS.items():
        directory = os.path.join(out, name)
        args = [exe, os.path.join(prm_dir, "hertz.prm"),
                "-s", "Output/Output directory=" + directory,
                "-s", "Finite elements/Polynomial degree=2",
                "-s", "Adaptation/Number of cycles=1",
                "-s", "Adaptation/Minimum number of cycles=1"]
        for s in settings:
            args += ["-s", s]
        run = subprocess.run(args, capture_output=True, text=True)
        if run.returncode != 0:
            failures.append("%s: exit %d: %s" % (name, run.returncode,
                                                 run.stderr[-500:]))
            continue
        match = LINE.search(run.stdout)
        if not match:
            failures.append(name + ": no indicator line in the log")
            continue
        eps, vol1, vol2, contact = (float(x) for x in match.groups())
        # Each printed part is rounded to 5e-4 %.
        parts = math.sqrt(vol1 ** 2 + vol2 ** 2 + contact ** 2)
        bound = 5e-4 * (vol1 + vol2 + contact) / max(parts, 1e-300) + 5e-4
        print("%s: epsilon %.3f %%, volume %.3f %% and %.3f %%, contact "
              "%.3f %%" % (name, eps, vol1, vol2, contact))
        if abs(eps - parts) > bound:
            failures.append("%s: epsilon %.3f %% but its parts give %.4f %%"
                            % (name, eps, parts))
        summary = json.load(open(os.path.join(directory, "summary.json")))
        cycle = summary["cycles"][0]
        if abs(100 * cycle["epsilon"] - eps) > 5e-4:
            failures.append(name + ": summary.json's epsilon differs from "
                            "the log's")
        squares = (sum(v ** 2 for v in cycle["epsilon_volume"]) +
                   cycle["epsilon_contact"] ** 2)
        mismatch = abs(squares - cycle["epsilon"] ** 2) / cycle["epsilon"] ** 2
        print("%s: |epsilon^2 - sum of the parts' squares| / epsilon^2 = "
              "%.1e (summary.json)" % (name, mismatch))
        if mismatch > 1e-12:
            failures.append("%s: summary.json's parts miss epsilon^2 by "
                            "%.1e of it" % (name, mismatch))
        with open(os.path.join(directory, "contact_000.csv")) as f:
            densities = [float(r["contact_error_density"])
                         for r in csv.DictReader(f)]
        negative = [d for d in densities if d < 0]
        if negative:
            failures.append("%s: contact error density < 0 at %d nodes "
                            "(smallest %g)" % (name, len(negative),
                                              min(negative)))
    for f in failures:
        print("FAILED: " + f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
