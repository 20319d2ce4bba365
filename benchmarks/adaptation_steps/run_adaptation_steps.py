#!/usr/bin/python3
"""Adaptation steps from the initial mesh until epsilon <= epsilon_0 (issue
18, item 3): blocks, punch and hertz, `remesh` (P1 triangles) and `refine`
(Q1, size ratio), epsilon_0 from 5 % to 0.25 %. Every run starts from the
scene's initial mesh with at most 8 cycles; summary.json gives per cycle the
DoFs, epsilon, the epsilon its plan aimed at and predicted, and the Newton
steps.

    benchmarks/adaptation_steps/run_adaptation_steps.py --exe EXE --label L
        [--csv results.csv] [--smoke] [--max-dofs 4e5]
    benchmarks/adaptation_steps/run_adaptation_steps.py --report [--csv ...]

Appends the rows of one executable (label L) to the CSV; --report prints
the table of README.md from it (one row per case, one column group per
label).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
import common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = ["blocks", "punch", "hertz"]
STRATEGIES = {"remesh": ["Mesh/Cell type=triangle"],
              "refine": ["Mesh/Cell type=quadrilateral",
                         "Adaptation/Refinement criterion=size ratio"]}
TARGETS = ["5", "2", "1", "0.5", "0.25"]
FIELDS = ["label", "scene", "strategy", "target_percent", "steps", "reached",
          "final_dofs", "final_epsilon_percent", "dofs_per_cycle",
          "epsilon_per_cycle", "aimed_per_cycle", "newton_per_cycle",
          "newton_most_per_cycle", "start_per_cycle", "contact_solve_s",
          "wall_s", "status", "settings"]


def most_newton_steps(cycle):
    """The most Newton steps of any solve of a cycle: the fine mesh's and
    every coarser level's of its nested iteration."""
    levels = cycle.get("nested_iteration", {}).get("levels", [])
    return max([cycle.get("newton_iterations", 0)] +
               [l.get("newton_iterations", 0) for l in levels])


def start_of(cycle):
    if cycle.get("warm_start"):
        return "warm"
    if cycle.get("nested_iteration", {}).get("levels"):
        return "nested"
    return "gap"


def run_case(exe, label, scene, strategy, target, max_dofs, timeout,
             extra=()):
    settings = STRATEGIES[strategy] + [
        "Adaptation/Strategy=" + strategy,
        "Adaptation/Target error=" + target,
        "Adaptation/Number of cycles=8",
        "Adaptation/Minimum number of cycles=1",
        "Adaptation/Maximum number of DoFs=%g" % max_dofs] + list(extra)
    result, summary = common.run_program(exe, settings, timeout,
                                         prm="prm/%s.prm" % scene)
    row = {"label": label, "scene": scene, "strategy": strategy,
           "target_percent": target, "wall_s": result.wall_s,
           "settings": " ".join(extra)}
    failure = result.failure()
    if failure or not summary:
        row["status"] = failure[0] if failure else "no summary"
        return row
    cycles = summary["cycles"]
    row.update(
        status="ok", steps=len(cycles) - 1,
        reached=summary.get("stop_reason", "").startswith("target reached"),
        final_dofs=cycles[-1]["n_dofs"],
        final_epsilon_percent=100 * cycles[-1]["epsilon"],
        dofs_per_cycle=" ".join(str(c["n_dofs"]) for c in cycles),
        epsilon_per_cycle=" ".join("%.4g" % (100 * c["epsilon"])
                                   for c in cycles),
        aimed_per_cycle=" ".join(
            "%.4g" % (100 * c["adaptation"]["aimed_epsilon"])
            if "aimed_epsilon" in c.get("adaptation", {}) else "-"
            for c in cycles),
        newton_per_cycle=" ".join(str(c.get("newton_iterations", ""))
                                  for c in cycles),
        newton_most_per_cycle=" ".join(str(most_newton_steps(c))
                                       for c in cycles),
        start_per_cycle=" ".join(start_of(c) for c in cycles),
        contact_solve_s="%.3f" % sum(c.get("timings_s", {}).get(
            "contact solve", 0) for c in cycles))
    return row


def report(path):
    rows = common.read_csv(path, text=FIELDS)
    labels = sorted({r["label"] for r in rows})
    by_key = {(r["label"], r["scene"], r["strategy"], r["target_percent"]): r
              for r in rows}
    keys = sorted({(r["scene"], r["strategy"], r["target_percent"])
                   for r in rows},
                  key=lambda k: (SCENES.index(k[0]), k[1], -float(k[2])))
    head = "| scene | strategy | ε₀ % |" + "".join(
        " %s: steps | DoFs | ε %% |" % l for l in labels)
    print(head)
    print("|---|---|---|" + "---|---|---|" * len(labels))
    for k in keys:
        line = "| %s | %s | %s |" % k
        for l in labels:
            r = by_key.get((l,) + k)
            if not r or r["status"] != "ok":
                line += " %s | | |" % (r["status"] if r else "")
                continue
            line += " %s%s | %s | %.3f |" % (
                r["steps"], "" if r["reached"] == "True" else " (not reached)",
                r["final_dofs"], float(r["final_epsilon_percent"]))
        print(line)


def report_newton(path):
    rows = common.read_csv(path, text=FIELDS)
    labels = sorted({r["label"] for r in rows if r.get("newton_most_per_cycle")})
    by_key = {(r["label"], r["scene"], r["strategy"], r["target_percent"]): r
              for r in rows}
    keys = sorted({(r["scene"], r["strategy"], r["target_percent"])
                   for r in rows},
                  key=lambda k: (SCENES.index(k[0]), k[1], -float(k[2])))
    print("| scene | strategy | ε₀ % | DoFs per cycle |" + "".join(
        " %s: Newton (most of any level) | contact solve s | wall s |" % l
        for l in labels))
    print("|---|---|---|---|" + "---|---|---|" * len(labels))
    for k in keys:
        first = next((by_key[(l,) + k] for l in labels
                      if (l,) + k in by_key), None)
        line = "| %s | %s | %s | %s |" % (k + (
            first["dofs_per_cycle"] if first else "",))
        for l in labels:
            r = by_key.get((l,) + k)
            if not r or r["status"] != "ok":
                line += " %s | | |" % (r["status"] if r else "")
                continue
            steps = ["%s (%s)" % (n, m) if n != m else n for n, m in zip(
                r["newton_per_cycle"].split(),
                r["newton_most_per_cycle"].split())]
            line += " %s | %.2f | %.1f |" % (
                " ".join(steps), float(r["contact_solve_s"]),
                float(r["wall_s"]))
        print(line)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--exe", default=os.path.join(common.ROOT,
                                                 "build/coulomb-adapt"))
    p.add_argument("--label", default="this build")
    p.add_argument("--csv", default=os.path.join(HERE, "results.csv"))
    p.add_argument("--max-dofs", type=float, default=4e5)
    p.add_argument("--timeout", type=float, default=900)
    p.add_argument("--smoke", action="store_true",
                   help="one small case, to check that the script runs")
    p.add_argument("--report", action="store_true")
    p.add_argument("--newton", action="store_true",
                   help="with --report: the Newton steps per cycle (most "
                        "of any level) and the contact solve time instead")
    p.add_argument("--set", action="append", default=[],
                   metavar="ENTRY=VALUE",
                   help="a parameter for every run (repeatable)")
    p.add_argument("--cases", default="",
                   help="scene:strategy:target,... (default: all)")
    a = p.parse_args()
    if a.report:
        (report_newton if a.newton else report)(a.csv)
        return
    common.check_executable(a.exe)
    common.print_header(a.exe)
    os.chdir(common.ROOT)
    cases = [(s, st, t) for s in SCENES for st in STRATEGIES for t in TARGETS]
    if a.cases:
        cases = [tuple(c.split(":")) for c in a.cases.split(",")]
    if a.smoke:
        cases = [("blocks", "remesh", "5")]
    rows = common.read_csv(a.csv, text=FIELDS) if (
        os.path.exists(a.csv) and not a.smoke) else []
    rows = [r for r in rows if r["label"] != a.label]
    for scene, strategy, target in cases:
        row = run_case(a.exe, a.label, scene, strategy, target, a.max_dofs,
                       a.timeout, a.set)
        print("%-7s %-7s %5s %%: %s steps, DoFs %s, eps %s, %.1f s" % (
            scene, strategy, target, row.get("steps", row.get("status")),
            row.get("dofs_per_cycle", ""), row.get("epsilon_per_cycle", ""),
            row["wall_s"]), flush=True)
        rows.append(row)
        if not a.smoke:
            common.write_csv(a.csv, rows, FIELDS)


if __name__ == "__main__":
    main()
