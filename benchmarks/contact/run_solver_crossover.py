#!/usr/bin/python3
"""Direct (MUMPS) against Krylov + AMG for the contact Newton system: the
mean time of one fine Newton step (assembly + solve, as the program prints
them) with 'Linear solver/Type = direct' and '= amg', on the same case one
right after the other, to find the size where AMG becomes faster (the
threshold 'Linear solver/Maximum DoFs for direct contact' of 'auto').

Cases: scene:cell:r[:ranks], e.g. blocks:quadrilateral:4 or
hertz:triangle:4:2 (2 MPI ranks); linear elements, one cycle, the scene's
own parameter file (prm/SCENE.prm). Each case is run --repeats times per
solver, alternating direct / amg, and the CSV keeps every run (the report
takes the median per case and solver). The AMG path's "assembly" contains
the product Z~^T K Z of the eliminated system, the direct path's the row
replacement: their sum is what a Newton step costs.

  benchmarks/contact/run_solver_crossover.py [--exe build/coulomb-adapt]
      [--cases blocks:quadrilateral:2,...] [--repeats 2]
      [--csv benchmarks/contact/solver_crossover.csv] [--report-only]

Prints a Markdown table (median per case: DoFs, Newton steps, step direct,
step amg, ratio direct / amg) and the load average before each run.
"""

import argparse
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
FIELDS = ["scene", "cell", "refinements", "ranks", "solver", "repeat",
          "status", "dofs", "newton_steps", "step_mean_s",
          "step_assembly_mean_s", "step_solve_mean_s", "step_min_s",
          "contact_solve_s", "wall_s", "other_cpu_s", "loadavg_1min",
          "linear_solver", "command"]
DEFAULT_CASES = (
    "blocks:quadrilateral:2,blocks:quadrilateral:3,blocks:quadrilateral:4,"
    "blocks:quadrilateral:5,blocks:quadrilateral:6,"
    "blocks:triangle:1,blocks:triangle:2,blocks:triangle:3,"
    "blocks:triangle:4,blocks:triangle:5,"
    "hertz:quadrilateral:0,hertz:quadrilateral:1,hertz:quadrilateral:2,"
    "hertz:quadrilateral:3,"
    "hertz:triangle:0,hertz:triangle:1,hertz:triangle:2,hertz:triangle:3,"
    "punch:triangle:1,punch:triangle:2,punch:triangle:3,punch:triangle:4,"
    "punch:triangle:5")


def settings_for(cell, r, solver):
    return ["Adaptation/Number of cycles=1",
            "Adaptation/Minimum number of cycles=1",
            "Output/Write cycles=none",
            "Finite elements/Polynomial degree=1",
            "Mesh/Cell type=" + cell,
            "Mesh/Global refinements=%d" % r,
            "Linear solver/Type=" + solver] + (
                ["Adaptation/Strategy=uniform"]
                if cell == "quadrilateral" else [])


def one_run(exe, scene, cell, r, ranks, solver, repeat, timeout):
    settings = settings_for(cell, r, solver)
    prm = os.path.join(common.PRM_DIR, scene + ".prm")
    load = common.loadavg()
    run, summary = common.run_program(exe, settings, timeout, prm=prm,
                                      ranks=ranks)
    row = {"scene": scene, "cell": cell, "refinements": r, "ranks": ranks,
           "solver": solver, "repeat": repeat, "wall_s": run.wall_s,
           "other_cpu_s": run.other_cpu_s,
           "loadavg_1min": load,
           "command": common.shell_command(
               common.program_command(exe, settings, prm, ranks))}
    failure = run.failure()
    c = common.last_cycle(summary)
    if failure or c is None:
        row["status"] = failure[0] if failure else "no cycle"
        return row
    steps = common.newton_step_times(run.stdout)
    tot = [a + s for a, s in steps]
    ls = c.get("linear_solver")
    row.update(status="ok", dofs=c["n_dofs"], newton_steps=len(steps),
               step_mean_s=statistics.mean(tot) if tot else "",
               step_assembly_mean_s=statistics.mean(a for a, _ in steps)
               if steps else "",
               step_solve_mean_s=statistics.mean(s for _, s in steps)
               if steps else "",
               step_min_s=min(tot) if tot else "",
               contact_solve_s=common.timing(c, "contact solve"),
               linear_solver=str(ls)[:80] if ls is not None else "")
    return row


def report(rows):
    groups = {}
    for r in rows:
        if r["status"] != "ok" or r["step_mean_s"] in ("", None):
            continue
        key = (r["scene"], r["cell"], int(float(r["refinements"])),
               int(float(r["ranks"])))
        groups.setdefault(key, {}).setdefault(r["solver"], []).append(r)
    print("\n| scene | cell | ranks | DoFs | Newton steps | step direct [s] "
          "| step amg [s] | direct / amg | load avg |\n"
          "|---|---|---|---|---|---|---|---|---|")
    for key in sorted(groups, key=lambda k: (k[0], k[1], k[3],
                                             float(next(iter(
                                                 groups[k].values()))[0]
                                                 ["dofs"]))):
        g = groups[key]
        if "direct" not in g or "amg" not in g:
            continue
        med = {s: statistics.median(float(r["step_mean_s"]) for r in g[s])
               for s in ("direct", "amg")}
        loads = [float(r["loadavg_1min"]) for s in g for r in g[s]
                 if r.get("loadavg_1min") not in ("", None)]
        print("| %s | %s | %d | %s | %s / %s | %.3g | %.3g | **%.2f** | "
              "%.1f-%.1f |" % (
                  key[0], "P1" if key[1] == "triangle" else "Q1", key[3],
                  g["direct"][0]["dofs"], g["direct"][0]["newton_steps"],
                  g["amg"][0]["newton_steps"], med["direct"], med["amg"],
                  med["direct"] / med["amg"], min(loads or [0]),
                  max(loads or [0])))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--exe", default=common.DEFAULT_EXE)
    p.add_argument("--cases", default=DEFAULT_CASES)
    p.add_argument("--repeats", type=int, default=2)
    p.add_argument("--timeout", type=float, default=900)
    p.add_argument("--csv", default=os.path.join(HERE,
                                                 "solver_crossover.csv"))
    p.add_argument("--report-only", action="store_true")
    a = p.parse_args()
    rows = []
    if os.path.exists(a.csv):
        rows = common.read_csv(a.csv, text=FIELDS)
    if a.report_only:
        report(rows)
        return
    exe = os.path.abspath(a.exe)
    common.check_executable(exe)
    new = []
    for case in [c for c in a.cases.split(",") if c]:
        parts = case.split(":")
        scene, cell, r = parts[0], parts[1], int(parts[2])
        ranks = int(parts[3]) if len(parts) > 3 else 1
        for repeat in range(a.repeats):
            order = ("direct", "amg") if repeat % 2 == 0 else ("amg",
                                                                "direct")
            for solver in order:
                row = one_run(exe, scene, cell, r, ranks, solver, repeat,
                              a.timeout)
                new.append(row)
                print("  %-6s %-13s r=%d np=%d %-6s %8s DoFs  steps %-3s "
                      "step %s s (solve %s s)  load %s  other %.1f s" % (
                          scene, cell, r, ranks, solver, row.get("dofs", "-"),
                          row.get("newton_steps", "-"),
                          common.cell(row.get("step_mean_s", ""), "%.3g"),
                          common.cell(row.get("step_solve_mean_s", ""),
                                      "%.3g"),
                          row["loadavg_1min"], row["other_cpu_s"]),
                      flush=True)
                rows.append(row)
                common.write_csv(a.csv, rows, FIELDS)
    report(rows)


if __name__ == "__main__":
    main()
