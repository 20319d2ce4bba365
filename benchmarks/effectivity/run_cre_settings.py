#!/usr/bin/python3
"""What cre's cheaper settings buy and cost: for each settings variant of
the cre estimator (doc/parameters.md, 'Error indicator'), its estimate, its
effectivity theta = epsilon / epsilon_exact_extrapolated (the exact
solution's error on the manufactured scene, the reference solution's
extrapolated error elsewhere) and its wall time against the contact solve's,
on one mesh of three scenes; zz on the same meshes for comparison:

    benchmarks/effectivity/run_cre_settings.py --exe build/coulomb-adapt \
        --repeats 2 --csv benchmarks/effectivity/cre_settings.csv \
        --md /tmp/cre_settings.md

Variants: 'default'; 'no evaluation degree increase' (CRE evaluation degree
increase = 0); 'kept prolongation conditions' (CRE relaxed equilibration =
false); 'classical tractions' (CRE traction optimisation = false);
'classical, degree p+2' (classical tractions, CRE degree increase = 2,
evaluation degree increase = 0); 'zz (for comparison)' (Estimator = zz).
Each run is one cycle with `Compute exact error = true` and no VTU output,
one process at a time (one rank, the program's default threads). Before
each run the script waits (up to --quiet-wait s) until other processes use
less than 0.3 cores (common.wait_for_quiet), and records that load and
whether the run stayed clean (other processes' CPU time during it). Within
a repeat the variants alternate (case after case; the second repeat runs
them in the reverse order); the tables (--md) give per case and variant the
minimum time over the repeats (--report: only the tables, from the
CSV). A variant the program refuses (non-zero exit)
is reported and dropped.

The CSV holds one row per run: case, variant, n_dofs, epsilon,
epsilon_exact_extrapolated, theta, the timer sections 'contact solve',
'error indicator' and 'error indicator: equilibration' (s), their ratio,
the repeat, the timer section taken for the solve ('contact solve'; the
manufactured scene has no contact and takes 'solve', its two bodies' separate
elastic solves without the assembly), the other processes' busy cores
before the run and whether it stayed clean (common.Run.clean). The
committed cre_settings.csv (2026-12-03) has the 1-minute load average at
each run's start instead of the last two.
"""
import argparse
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
import common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))

# (name, prm, settings); every case also gets the variant's estimator.
CASES = [
    ("manufactured P1", "prm/two_body_demo.prm",
     ["Mesh/Cell type=triangle", "Mesh/Global refinements=3",
      "Adaptation/Number of cycles=1"]),
    ("blocks mu=0 P1", "prm/blocks.prm",
     ["Adaptation/Strategy=uniform", "Adaptation/Number of cycles=1",
      "Adaptation/Minimum number of cycles=1",
      "Contact/Friction coefficient=0", "Scene/Blocks/Hold centre line=true",
      "Scene/Blocks/Upper body subdivisions=2, 2",
      "Scene/Blocks/Lower body subdivisions=4, 4",
      "Mesh/Global refinements=2",
      "Error indicator/Reference refinements=3"]),
    ("hertz mu=0 P1", "prm/hertz.prm",
     ["Mesh/Cell type=triangle", "Adaptation/Strategy=uniform",
      "Adaptation/Number of cycles=1",
      "Adaptation/Minimum number of cycles=1",
      "Contact/Friction coefficient=0",
      "Error indicator/Reference refinements=2"]),
]
CRE = "Error indicator/Estimator=cre"
VARIANTS = [
    ("default", [CRE]),
    ("no evaluation degree increase",
     [CRE, "Error indicator/CRE evaluation degree increase=0"]),
    ("kept prolongation conditions",
     [CRE, "Error indicator/CRE relaxed equilibration=false"]),
    ("classical tractions",
     [CRE, "Error indicator/CRE traction optimisation=false"]),
    ("classical, degree p+2",
     [CRE, "Error indicator/CRE traction optimisation=false",
      "Error indicator/CRE degree increase=2",
      "Error indicator/CRE evaluation degree increase=0"]),
    ("zz (for comparison)", ["Error indicator/Estimator=zz"]),
]
COMMON = ["Error indicator/Compute exact error=true"]
FIELDS = ["case", "variant", "n_dofs", "epsilon", "epsilon_exact_extrapolated",
          "theta", "contact_solve_s", "error_indicator_s",
          "indicator_over_solve", "repeat", "equilibration_s",
          "solve_section", "busy_cores_before", "clean"]
# Other processes' load (cores) below which a repeat starts.
QUIET_THRESHOLD = 0.3


def run_once(exe, prm, settings, timeout):
    """One run; (row, None) or (None, failure message)."""
    result, summary = common.run_program(exe, settings + COMMON, timeout,
                                         prm=os.path.join(common.ROOT, prm))
    failure = result.failure()
    cycle = common.last_cycle(summary)
    if failure or cycle is None:
        return None, (failure[1] if failure else "no cycle in summary.json")
    # Against a reference the exact error extrapolated (doc/indicator.md
    # 5); with the exact solution (manufactured) the exact error itself.
    exact = cycle.get("epsilon_exact_extrapolated",
                      cycle.get("epsilon_exact"))
    # The manufactured scene has no contact: its bodies are solved
    # separately, in the section 'solve' (assembly not included).
    section = ("contact solve" if "contact solve" in cycle.get("timings_s",
                                                              {})
               else "solve")
    solve = common.timing(cycle, section, None)
    indicator = common.timing(cycle, "error indicator", None)
    row = {"n_dofs": cycle["n_dofs"], "epsilon": cycle["epsilon"],
           "clean": result.clean,
           "epsilon_exact_extrapolated": exact,
           "theta": cycle["epsilon"] / exact if exact else None,
           "contact_solve_s": solve, "solve_section": section,
           "error_indicator_s": indicator,
           "indicator_over_solve":
               indicator / solve if solve and indicator is not None else None,
           "equilibration_s":
               common.timing(cycle, "error indicator: equilibration", None)}
    return row, None


def markdown(rows, refused, command):
    """The tables: per case and variant the estimate and the minimum
    times over the repeats."""
    lines = ["Command: `%s`" % command, ""]
    for name, _, _ in CASES:
        mine = [r for r in rows if r["case"] == name]
        if not mine:
            continue
        note = ("" if mine[0]["solve_section"] == "contact solve" else
                "; no contact: 'contact solve' is the section '%s'"
                % mine[0]["solve_section"])
        lines += ["**%s** (%s DoFs%s)" % (
            name, "{:,}".format(mine[0]["n_dofs"]), note), "",
                  "| variant | epsilon | exact (extrapolated) | theta | "
                  "indicator s | indicator / contact solve |",
                  "|---|---|---|---|---|---|"]
        for variant, _ in VARIANTS:
            runs = [r for r in mine if r["variant"] == variant]
            if not runs:
                if (name, variant) in refused:
                    lines.append("| %s | refused | | | | |" % variant)
                continue
            fastest = min(r["error_indicator_s"] for r in runs)
            # The minimum indicator time over the minimum solve time.
            ratio = fastest / min(r["contact_solve_s"] for r in runs)
            r = runs[0]
            lines.append("| %s | %.4f %% | %.4f %% | %.3f | %s | %s |" % (
                variant, 100 * r["epsilon"],
                100 * r["epsilon_exact_extrapolated"], r["theta"],
                common.fmt(fastest), common.fmt(ratio)))
        lines.append("")
    for (name, variant), message in sorted(refused.items()):
        lines.append("Refused: %s, %s: %s" % (name, variant, message))
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--exe", default=common.DEFAULT_EXE)
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--quiet-wait", type=float, default=300,
                        help="at most this many seconds of waiting for a "
                        "quiet machine before each run")
    parser.add_argument("--timeout", type=float, default=1800)
    parser.add_argument("--csv", default=os.path.join(HERE,
                                                      "cre_settings.csv"))
    parser.add_argument("--md", help="also write the tables (markdown)")
    parser.add_argument("--report", action="store_true",
                        help="no runs: only the tables (--md) of the CSV")
    args = parser.parse_args()
    if args.report:
        rows = common.read_csv(args.csv, text=("case", "variant",
                                               "solve_section"),
                               ints=("n_dofs", "repeat"))
        with open(args.md, "w") as f:
            f.write(markdown(rows, {}, " ".join(
                ["benchmarks/effectivity/run_cre_settings.py"] +
                sys.argv[1:])))
        return 0
    exe = common.check_executable(args.exe)
    common.print_header(exe)
    start = time.perf_counter()
    rows, refused = [], {}
    for repeat in range(args.repeats):
        print("repeat %d" % repeat, flush=True)
        variants = VARIANTS if repeat % 2 == 0 else VARIANTS[::-1]
        for name, prm, settings in CASES:
            for variant, extra in variants:
                if (name, variant) in refused:
                    continue
                load = common.wait_for_quiet(args.quiet_wait,
                                             QUIET_THRESHOLD)
                row, message = run_once(exe, prm, settings + extra,
                                        args.timeout)
                if row is None:
                    print("  %s, %s: refused: %s" % (name, variant, message),
                          flush=True)
                    refused[(name, variant)] = message
                    continue
                row.update(case=name, variant=variant, repeat=repeat,
                           busy_cores_before=load)
                rows.append(row)
                print("  %s, %s: %d DoFs, theta %.3f, indicator %.3f s, "
                      "contact solve %.3f s (busy cores before %.2f%s)" % (
                          name, variant, row["n_dofs"], row["theta"],
                          row["error_indicator_s"], row["contact_solve_s"],
                          load, "" if row["clean"] else ", not clean"),
                      flush=True)
                common.write_csv(args.csv, rows, FIELDS)
    common.write_csv(args.csv, rows, FIELDS)
    print("wrote %s; %.0f s in all" % (args.csv, time.perf_counter() - start))
    if args.md:
        command = " ".join(["benchmarks/effectivity/run_cre_settings.py"] +
                           sys.argv[1:])
        with open(args.md, "w") as f:
            f.write(markdown(rows, refused, command))
        print("wrote " + args.md)
    return 0


if __name__ == "__main__":
    sys.exit(main())
