#!/usr/bin/python3
"""cre with 'CRE lift of displacement data' (the default since
2026-12-02): a bound where the FE space misses the displacement data
between its nodes.

The manufactured scene's Dirichlet data are a sinusoid; u_c meets them at
its nodes only. With the option, the equilibration is relaxed there too,
the local problems measure sigma^ - sigma(u_c + r), r the lift of the
data's interpolation error (dirichlet_data_lift.h), and the estimate adds
||sigma(r)|| (without it, the estimate falls below the exact error on
Q1 and P1: theta 0.871 on the coarsest Q1 mesh). Checks, on P1/P2 triangles
and Q1/Q2 quadrilaterals, three uniform cycles each, against the exact
solution:
  - epsilon >= epsilon_exact on every mesh (the bound) and <= 2
    epsilon_exact (issue 17's target); on P2 triangles <= 1.15
    epsilon_exact (the quadratic relaxed modes; 1.61-1.90 without);
  - the prolongation conditions are relaxed in both bodies;
  - ||sigma(r)|| falls as h^(p + 1/2) (d = u_D - u_c ~ h^(p+1) on a strip
    of cells of width h): the rate between the last two meshes within
    0.05 of p + 1/2, measured 1.51 (p = 1) and 2.49-2.50 (p = 2);
  - 2 ranks give the 1-rank numbers (Q2, P1 and P2 triangles, to 1e-10);
  - the runs above leave the option at its default, which lifts;
  - compare mode (zz driving) reports cre's lift in its estimators.cre
    record, and cre's epsilon and lift there are those of the cre-driven
    run on the same first mesh (to 1e-12);
  - with the option false nothing is lifted and the conditions are kept;
  - a contact scene (blocks, whose data are interpolated exactly) gets
    no lift and the same estimate, to every digit, with the option true
    or false;
  - summary.json records blocks' friction coefficient and none for the
    manufactured scene, which has no contact.

usage: cre_dirichlet_lift.py EXE PRM_DIR OUTPUT_DIR MPIEXEC
"""

import json
import math
import os
import sys

from coulomb_adapt_run import run_cycles


def run(exe, prm_dir, directory, cell_type, degree, lift=None, ranks=1,
        mpiexec=None, extra=(), prm="two_body_demo.prm"):
    settings = ["Mesh/Cell type=" + cell_type,
                "Finite elements/Polynomial degree=%d" % degree,
                "Mesh/Global refinements=0",
                "Adaptation/Number of cycles=3",
                "Error indicator/Estimator=cre",
                "Error indicator/Compute exact error=true",
                "Output/Write VTU=false"] + \
        ([] if lift is None else
         ["Error indicator/CRE lift of displacement data=" +
          str(lift).lower()]) + list(extra)
    return run_cycles(exe, os.path.join(prm_dir, prm), directory, settings,
                      ranks, mpiexec)[0]


def main():
    exe, prm_dir, output = [os.path.abspath(a) for a in sys.argv[1:4]]
    mpiexec = sys.argv[4]
    failures = []
    for cell_type, degree in [("triangle", 1), ("triangle", 2),
                              ("quadrilateral", 1), ("quadrilateral", 2)]:
        name = "%s P%d" % (cell_type, degree)
        cycles = run(exe, prm_dir,
                     os.path.join(output, "%s_%d" % (cell_type, degree)),
                     cell_type, degree)
        if name == "triangle P1":
            driving = cycles[0]
        for c in cycles:
            eps, exact = c["epsilon"], c["epsilon_exact"]
            print("%s, %d DoFs: epsilon %.4f %%, exact %.4f %%, theta "
                  "%.3f, lift %.4f %%" %
                  (name, c["n_dofs"], 100 * eps, 100 * exact, eps / exact,
                   100 * c["cre"]["epsilon_dirichlet_lift"]))
            if not exact <= eps <= 2 * exact:
                failures.append("%s, %d DoFs: theta %.3f outside [1, 2]" %
                                (name, c["n_dofs"], eps / exact))
            # P2's quadratic relaxed modes (traction_optimisation.cc):
            # without them theta was 1.61-1.90 on these meshes and rose
            # with refinement; with them 1.06-1.12.
            if name == "triangle P2" and eps > 1.15 * exact:
                failures.append("%s, %d DoFs: theta %.3f > 1.15 (the "
                                "quadratic relaxed modes?)" %
                                (name, c["n_dofs"], eps / exact))
            if c["cre"]["relaxed_equilibration"] != [True, True]:
                failures.append("%s: prolongation conditions not relaxed" %
                                name)
        lifts = [c["cre"]["epsilon_dirichlet_lift"] for c in cycles]
        if min(lifts) <= 0:
            failures.append("%s: no lift by default (%s)" % (name, lifts))
            continue
        rate = math.log2(lifts[-2] / lifts[-1])
        print("%s: lift rate %.3f (h^(p + 1/2): %.1f)" %
              (name, rate, degree + 0.5))
        if abs(rate - (degree + 0.5)) > 0.05:
            failures.append("%s: lift rate %.3f, expected %.1f" %
                            (name, rate, degree + 0.5))

    # Triangles too: their ghost cells on 2 ranks come from a serial
    # mesh partitioned by METIS, quadrilaterals' from p4est.
    for cell_type, degree in (("quadrilateral", 2), ("triangle", 1),
                              ("triangle", 2)):
        tag = "%s_%d" % (cell_type, degree)
        one = run(exe, prm_dir, os.path.join(output, tag + "_1rank"),
                  cell_type, degree)
        two = run(exe, prm_dir, os.path.join(output, tag + "_2ranks"),
                  cell_type, degree, None, 2, mpiexec)
        for a, b in zip(one, two):
            for key in ("epsilon", "epsilon_exact"):
                if abs(a[key] - b[key]) > 1e-10 * a[key]:
                    failures.append("%s, 2 ranks: %s %.12g instead of %.12g"
                                    % (tag, key, b[key], a[key]))
            if abs(a["cre"]["epsilon_dirichlet_lift"] -
                   b["cre"]["epsilon_dirichlet_lift"]) > \
                    1e-10 * a["cre"]["epsilon_dirichlet_lift"]:
                failures.append("%s, 2 ranks: a different lift" % tag)

    compared = run(exe, prm_dir, os.path.join(output, "compare"), "triangle",
                   1, extra=["Error indicator/Estimator=zz",
                             "Error indicator/Compare estimators=true",
                             "Adaptation/Number of cycles=1"])[0]
    cre = compared["estimators"]["cre"]
    print("compare mode, zz driving: cre epsilon %.6f %% (driving %.6f %%), "
          "lift %.6f %% (driving %.6f %%)" %
          (100 * cre["epsilon"], 100 * driving["epsilon"],
           100 * cre.get("epsilon_dirichlet_lift", -1),
           100 * driving["cre"]["epsilon_dirichlet_lift"]))
    for key, value in (("epsilon", driving["epsilon"]),
                       ("epsilon_dirichlet_lift",
                        driving["cre"]["epsilon_dirichlet_lift"])):
        if key not in cre or not value > 0 or \
                abs(cre[key] - value) > 1e-12 * value:
            failures.append("compare mode: estimators.cre.%s %s instead of "
                            "%.12g" % (key, cre.get(key), value))
    for other in ("zz", "spr"):
        if "epsilon_dirichlet_lift" in compared["estimators"][other]:
            failures.append("compare mode: %s has a lift" % other)

    blocks = [run(exe, prm_dir, os.path.join(output, "blocks_%s" % lift),
                  "triangle", 1, lift, prm="blocks.prm",
                  extra=["Adaptation/Number of cycles=1",
                         "Adaptation/Minimum number of cycles=1",
                         "Error indicator/Compute exact error=false"])[0]
              for lift in (True, False)]
    print("blocks: epsilon %.15g (lift true), %.15g (false), lifts %g, %g" %
          (blocks[0]["epsilon"], blocks[1]["epsilon"],
           blocks[0]["cre"]["epsilon_dirichlet_lift"],
           blocks[1]["cre"]["epsilon_dirichlet_lift"]))
    if blocks[0]["epsilon"] != blocks[1]["epsilon"] or \
            blocks[0]["epsilon_contact"] != blocks[1]["epsilon_contact"] or \
            blocks[0]["cre"]["epsilon_dirichlet_lift"] != 0:
        failures.append("blocks: the lift option changed a contact scene")

    for c in run(exe, prm_dir, os.path.join(output, "without"), "triangle",
                 1, False):
        if c["cre"]["epsilon_dirichlet_lift"] != 0 or \
                c["cre"]["relaxed_equilibration"] != [False, False]:
            failures.append("without the option: lift %g, relaxed %s" %
                            (c["cre"]["epsilon_dirichlet_lift"],
                             c["cre"]["relaxed_equilibration"]))

    # summary.json's friction coefficient: the parameter's on a contact
    # scene, no entry on the manufactured one, which has no contact.
    def top_level(directory):
        with open(os.path.join(output, directory, "summary.json")) as f:
            return json.load(f)
    mu_blocks = top_level("blocks_True").get("friction_coefficient")
    mu_manufactured = top_level("without").get("friction_coefficient")
    print("summary.json friction_coefficient: blocks %s, manufactured %s" %
          (mu_blocks, mu_manufactured))
    if mu_blocks != 0.3 or mu_manufactured is not None:
        failures.append("friction_coefficient: blocks %s (expected 0.3), "
                        "manufactured %s (expected no entry)" %
                        (mu_blocks, mu_manufactured))

    if failures:
        sys.exit("FAILED:\n  " + "\n  ".join(failures))
    print("OK")


if __name__ == "__main__":
    main()
