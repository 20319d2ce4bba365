#!/usr/bin/python3
"""Newton steps per contact solve on every built-in scene (issue 18 item 4):
each prm/*.prm with linear elements (P1 triangles and Q1 quadrilaterals),
one cycle (the cold run: no previous cycle to warm-start from), at several
sizes ('Mesh/Global refinements' 0, 1, 2, ...; a size is not tried once
the last one had more than --max-dofs DoFs or took more than --max-time s).

Per run: DoFs, the fine mesh's Newton steps per load step, the largest
count of any coarser (nested iteration) solve, how the start was chosen,
the contact-solve wall time (summary.json's timings_s, which includes
the coarser solves) and the whole run's CPU time (cpu_s: this process's
children, 1 rank, 1 thread). Newton counts are deterministic; the times
are on a shared 2-core machine (other_cpu_s says how busy it was): on a
busy machine compare cpu_s, or runs of both builds made one after the
other.

  benchmarks/contact/run_newton_steps.py [--exe build/coulomb-adapt]
      [--build NAME] [--scenes hertz,punch] [--cells triangle,quadrilateral]
      [--refinements 0,1,2,3] [--max-dofs 150000] [--csv newton_steps.csv]
      [-s 'Contact/Nested iteration minimum DoFs=0'] [--smoke]

Writes the CSV (default newton_steps.csv beside this script; rows of an
existing file that this run did not repeat are kept) and prints a
Markdown table.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
# two_body_demo has no contact (two bodies side by side).
SCENES = ["patch", "hertz", "punch", "blocks", "cattaneo", "gmsh_blocks", "blocks_gmsh", "hertz_gmsh", "press_fit",
          "press_fit_quarter", "press_fit_torque", "dovetail"]
CELLS = ["triangle", "quadrilateral"]
FIELDS = ["build", "scene", "cell", "refinements", "dofs", "status",
          "newton_per_load_step", "max_newton", "start", "coarser_levels",
          "max_coarser_newton", "stopped_steps", "contact_solve_s", "wall_s",
          "cpu_s", "other_cpu_s", "settings", "command"]


def one_run(exe, build, scene, cell, r, extra, timeout):
    settings = ["Adaptation/Number of cycles=1",
                "Adaptation/Minimum number of cycles=1",
                "Output/Write cycles=none",
                "Finite elements/Polynomial degree=1",
                "Mesh/Cell type=" + cell,
                "Mesh/Global refinements=%d" % r] + (
                    # one cycle: no adaptation, but gmsh remeshes triangles
                    # only, and the entry is checked
                    ["Adaptation/Strategy=uniform"]
                    if cell == "quadrilateral" else []) + extra
    prm = os.path.join(common.PRM_DIR, scene + ".prm")
    cpu0 = common.children_cpu()
    run, summary = common.run_program(exe, settings, timeout, prm=prm)
    cpu_s = common.children_cpu() - cpu0
    row = {"build": build, "scene": scene, "cell": cell, "refinements": r,
           "wall_s": run.wall_s, "cpu_s": cpu_s,
           "other_cpu_s": run.other_cpu_s,
           "settings": "; ".join(extra),
           "command": common.shell_command(
               common.program_command(exe, settings, prm))}
    failure = run.failure()
    c = common.last_cycle(summary)
    if failure or c is None:
        row["status"] = failure[0] if failure else "no cycle"
        msg = failure[1] if failure else common.error_message(run.stderr,
                                                              run.stdout)
        row["start"] = msg.replace("\n", " ")[:200]
        return row
    steps = c.get("newton_iterations_per_load_step",
                  [c.get("newton_iterations")])
    nested = c.get("nested_iteration", {})
    levels = nested.get("levels", [])
    row.update({
        "status": "ok",
        "dofs": c["n_dofs"],
        "newton_per_load_step": " ".join(str(s) for s in steps),
        "max_newton": max(steps),
        "start": ("warm" if c.get("warm_start") else
                  "nested" if levels else
                  "cold: " + nested.get("skipped", "")[:80]),
        "coarser_levels": " ".join(str(lv["n_dofs"]) for lv in levels),
        "max_coarser_newton": max([lv["newton_iterations"] for lv in levels],
                                  default=""),
        "stopped_steps": c.get("newton_iterations_of_stopped_starts", 0),
        "contact_solve_s": common.timing(c, "contact solve"),
    })
    return row


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--exe", default=common.DEFAULT_EXE)
    p.add_argument("--build", default="this")
    p.add_argument("--scenes", default=",".join(SCENES))
    p.add_argument("--cells", default=",".join(CELLS))
    p.add_argument("--refinements", default="0,1,2,3")
    p.add_argument("--max-dofs", type=float, default=1.5e5)
    p.add_argument("--max-time", type=float, default=60)
    p.add_argument("--timeout", type=float, default=300)
    p.add_argument("-s", dest="settings", action="append", default=[])
    p.add_argument("--csv", default=os.path.join(HERE, "newton_steps.csv"))
    p.add_argument("--cases", default="",
                   help="scene:cell:r,... instead of the sweep, e.g. "
                   "hertz:triangle:1 (with --baseline: the timing table)")
    p.add_argument("--baseline", default="",
                   help="an older executable run on each case right "
                   "before this one (build name --baseline-build), so that "
                   "both see the same load on a shared machine")
    p.add_argument("--baseline-build", default="before")
    p.add_argument("--smoke", action="store_true",
                   help="hertz and punch, P1, refinements 0 only")
    a = p.parse_args()
    if a.smoke:
        a.scenes, a.cells, a.refinements = "hertz,punch", "triangle", "0"
    exe = os.path.abspath(a.exe)
    common.check_executable(exe)
    rows = []
    for case in [c for c in a.cases.split(",") if c]:
        scene, cell, r = case.split(":")
        pairs = ([(os.path.abspath(a.baseline), a.baseline_build)]
                 if a.baseline else []) + [(exe, a.build)]
        for e, build in pairs:
            row = one_run(e, build, scene, cell, int(r), a.settings,
                          a.timeout)
            rows.append(row)
            print("  %-8s %-18s %-13s r=%s %7s DoFs  Newton %-14s "
                  "solve %s s, cpu %s s, other %s s" % (
                      build, scene, cell, r, row.get("dofs", "-"),
                      row.get("newton_per_load_step", "-"),
                      common.cell(row.get("contact_solve_s", ""), "%.3g"),
                      common.cell(row.get("cpu_s", ""), "%.3g"),
                      common.cell(row.get("other_cpu_s", ""), "%.3g")),
                  flush=True)
    for scene in ([] if a.cases else a.scenes.split(",")):
        for cell in a.cells.split(","):
            for r in [int(x) for x in a.refinements.split(",")]:
                row = one_run(exe, a.build, scene, cell, r, a.settings,
                              a.timeout)
                rows.append(row)
                print("  %-18s %-13s r=%d %7s DoFs  Newton %-14s %-8s "
                      "coarser max %-3s solve %s s" % (
                          scene, cell, r, row.get("dofs", "-"),
                          row.get("newton_per_load_step", "-"),
                          row["status"], row.get("max_coarser_newton", ""),
                          common.cell(row.get("contact_solve_s", ""),
                                      "%.3g")), flush=True)
                if row["status"] != "ok" or \
                        float(row.get("dofs") or 0) > a.max_dofs or \
                        row["wall_s"] > a.max_time:
                    break
    if os.path.exists(a.csv):
        old = common.read_csv(a.csv, text=FIELDS)
        key = lambda r: (r["build"], r["scene"], r["cell"],  # noqa: E731
                         int(float(r["refinements"])))
        new = set(key(r) for r in rows)
        rows = [r for r in old if key(r) not in new] + rows
    common.write_csv(a.csv, rows, FIELDS)
    if a.smoke:
        bad = [r for r in rows if r["status"] != "ok"]
        sys.exit(1 if bad else 0)
    print("\n| build | scene | cell | DoFs | Newton per load step | start "
          "| coarser max | contact solve s |\n|---|---|---|---|---|---|---|---|")
    for r in rows:
        if r["status"] == "ok":
            print("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
                r["build"], r["scene"], "P1" if r["cell"] == "triangle"
                else "Q1", r["dofs"], r["newton_per_load_step"],
                r["start"].split(":")[0], r["max_coarser_newton"],
                common.cell(r["contact_solve_s"], "%.3g")))


if __name__ == "__main__":
    main()
