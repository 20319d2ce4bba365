#!/usr/bin/python3
"""Contact benchmark of coulomb-adapt: Newton iterations and time per Newton
step against the number of DoFs.

Series (scene x friction coefficient), serial (1 MPI rank), Q1, plane strain,
one cycle per run, direct solver (MUMPS) for the contact system:

  blocks, mu = 0    (Scene/Blocks/Hold centre line = true)
  blocks, mu = 0.3  (the seed's problem, upper block held by friction)
  hertz,  mu = 0    (graded meshes, Hold axis on, the default)
  hertz,  mu = 0.3

Each run uses `Mesh/Global refinements = r`. Recorded per run: n_dofs (and per
body), Newton iterations, convergence, active/stick/slip nodes, the
'contact solve' wall time, the time of each Newton step (assembly + solve,
parsed from the program's per-step log lines: summary.json does not have
them), peak memory.

Elastic reference ("one elastic solve on the same mesh"):

* blocks: measured. The `manufactured` scene with Body 1 subdivisions 4 x 4
  and Body 2 subdivisions 8 x 8 has exactly the cell layout of the blocks
  meshes (4 x 4 and 8 x 8 quadrilaterals, r global refinements), so it is
  the same mesh up to scaling. It is solved with 'Linear solver/Type =
  direct'; the reference is the sum of the two bodies' solve times (the
  bodies are independent without contact).
* hertz: interpolated. The graded hertz meshes cannot be reproduced in the
  manufactured scene, so the reference is T1(n_body1) + T1(n_body2), with
  T1(n) the time of one direct (MUMPS) solve of a single elastic body of n
  DoFs, interpolated log-log in benchmarks/elasticity/results.csv (1 rank,
  solver 'direct', status ok, median over repeats and over both bodies) and
  extrapolated with the slope of the last two sizes beyond them. The same
  interpolation is also written for blocks, as a cross-check of the
  measured reference.

A second, stricter reference is also written: T1(n_dofs), a single elastic
system of the same total size as the coupled contact system.

Usage:
  run_contact_benchmark.py                      full sweep, CSV + PNG
  run_contact_benchmark.py --quick              small sizes only
  run_contact_benchmark.py --smoke              two tiny blocks runs and
                                                their elastic reference
                                                (a few seconds; ctest)
Plot and tables: report_contact_benchmark.py (the plot is drawn at the end
of a sweep).
Nested iteration (ae9a23c): --nested-levels N passes 'Contact/Nested
iteration levels=N' (0 = cold start; default: the program's default, 3);
rows carry start = nested / cold and the coarse levels from summary.json
(coarse_newton_by_level, coarse_time_s, ...). --series (e.g. hertz or
hertz:0,blocks:0.3) runs a subset, --no-elastic keeps the CSV's elastic
references, --append keeps rows of other series and of the other start.
Options: --exe, --blocks-max-ref (7), --hertz-max-ref (4), --max-run-s (480:
skip a size whose predicted run time exceeds it), --budget-s (1800: total
run time, waits not counted), --retries (2: reruns of a run disturbed by
other processes), --quiet-wait (600 s),
--repeats (3, for runs shorter than --repeat-below-s = 5 s).

Only the Python standard library and matplotlib are used.
"""

import argparse
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(
    __file__))))
import common  # noqa: E402
import report_contact_benchmark as report  # noqa: E402
from report_contact_benchmark import num  # noqa: E402


# Blocks meshes beyond the 4 x 4 / 8 x 8 ladder: (upper coarse subdivisions,
# refinements). 10 x 10 / 20 x 20 with 5 refinements is the 5 x 5 / 10 x 10
# mesh refined 6 times (h = 100/320 mm): 1,027,844 DoFs, between r = 6
# (658,436) and r = 7 (2,627,588) of the ladder. (5 x 5 itself is refused
# with 'Hold centre line': odd number of cells.)
BLOCKS_EXTENSIONS = [(10, 5)]

FIELDS = [
    "kind", "scene", "mu", "subdivisions", "refinements", "n_dofs", "n_dofs_body1",
    "n_dofs_body2", "status", "converged", "newton_iterations",
    "active_nodes", "stick_nodes", "slip_nodes", "contact_solve_s",
    "cycle_wall_s", "process_wall_s", "step_mean_s", "step_assembly_mean_s",
    "step_solve_mean_s", "step_min_s", "step_max_s", "elastic_solve_s",
    "elastic_body1_s", "elastic_body2_s", "elastic_ref_s",
    "elastic_ref_source", "elastic_interp_s", "single_system_ref_s",
    "ratio_step_elastic", "ratio_step_single", "peak_memory_MiB",
    "linear_solver", "repeats", "other_cpu_s", "clean", "version",
    "message",
    # nested iteration (ae9a23c): how the first static solve started
    "start", "nested_levels_setting", "nested_status", "coarse_levels",
    "coarse_newton_by_level", "coarse_newton_total", "coarse_time_s",
    "fine_solve_s", "solve_over_elastic",
]

# Growth of the run time with the DoFs, used to predict the next size.
TIME_EXPONENT = 1.5
QUIET_THRESHOLD = 0.3
ELASTIC_SCENE = "blocks-mesh (manufactured)"


def base_settings(refinements):
    return ["Mesh/Global refinements=%d" % refinements,
            "Mesh/Cell type=quadrilateral",
            "Finite elements/Polynomial degree=1",
            "Finite elements/Plane model=plane strain",
            "Adaptation/Number of cycles=1"]


def contact_settings(scene, mu, refinements, sub=4, nested_levels=None,
                     linear_solver="direct"):
    s = base_settings(refinements) + [
        "Scene/Name=" + scene,
        "Contact/Friction coefficient=%g" % mu,
        "Linear solver/Type=" + linear_solver,
        "Linear solver/Direct solver=Amesos_Mumps"]
    if nested_levels is not None:
        s.append("Contact/Nested iteration levels=%d" % nested_levels)
    if scene == "blocks":
        s += ["Scene/Blocks/Upper body subdivisions=%d, %d" % (sub, sub),
              "Scene/Blocks/Lower body subdivisions=%d, %d" % (2 * sub,
                                                               2 * sub)]
        if mu == 0:
            s.append("Scene/Blocks/Hold centre line=true")
    return s


def elastic_settings(refinements, sub=4):
    """The blocks meshes (sub x sub and 2sub x 2sub quadrilaterals) in the
    manufactured scene: an elastic problem on the same mesh."""
    return base_settings(refinements) + [
        "Scene/Name=manufactured",
        "Scene/Manufactured/Body 1 subdivisions=%d, %d" % (sub, sub),
        "Scene/Manufactured/Body 2 subdivisions=%d, %d" % (2 * sub, 2 * sub),
        "Linear solver/Type=direct",
        "Linear solver/Direct solver=Amesos_Mumps"]


def estimated_dofs(scene, refinements, sub=4):
    if scene == "blocks":
        n1, n2 = sub * 2 ** refinements + 1, 2 * sub * 2 ** refinements + 1
        return 2 * (n1 * n1 + n2 * n2)
    return 9.0e3 * 4 ** refinements



def start_mode(nested_levels):
    """'cold' if nested iteration is switched off, else 'nested' (whether it
    actually ran is in nested_status)."""
    return "cold" if nested_levels == 0 else "nested"


def describe_linear_solver(record):
    """summary.json's linear_solver: a dict (elastic runs) or a list of
    dicts, one per load step (contact runs: the last Newton step's solve)."""
    if isinstance(record, dict):
        record = [record]
    if not isinstance(record, list):
        return ""
    return " ".join("%s:%s" % (r.get("method", ""), r.get("iterations", ""))
                    for r in record)



def new_row(kind, result, **values):
    row = {k: "" for k in FIELDS}
    row.update(kind=kind, process_wall_s=result.wall_s,
               other_cpu_s=result.other_cpu_s, clean=int(result.clean),
               **values)
    return row


def finish(row, result, cyc, timeout, complete=True):
    """Status and message of a row."""
    failure = result.failure()
    if result.killed:
        row.update(status="timeout", message="killed after %g s" % timeout)
    elif failure or cyc is None or not complete:
        row.update(status="failed", message=common.error_message(
            result.stderr, result.stdout))
    else:
        row.update(status="ok")
    return row


def run_contact(exe, scene, mu, refinements, timeout, sub=4,
                nested_levels=None, linear_solver="direct"):
    result, summary = common.run_program(
        exe, contact_settings(scene, mu, refinements, sub, nested_levels,
                              linear_solver), timeout)
    row = new_row("contact", result, scene=scene, mu=mu,
                  refinements=refinements,
                  subdivisions=sub if scene == "blocks" else "",
                  start=start_mode(nested_levels),
                  nested_levels_setting="default (3)"
                  if nested_levels is None else nested_levels)
    cyc = common.last_cycle(summary)
    if cyc is not None:
        row.update(
            n_dofs=cyc.get("n_dofs", ""),
            n_dofs_body1=common.body_field(cyc, 0, "n_dofs"),
            n_dofs_body2=common.body_field(cyc, 1, "n_dofs"),
            converged=int(bool(cyc.get("converged"))),
            newton_iterations=cyc.get("newton_iterations", ""),
            active_nodes=cyc.get("active_nodes", ""),
            stick_nodes=cyc.get("stick_nodes", ""),
            slip_nodes=cyc.get("slip_nodes", ""),
            contact_solve_s=common.timing(cyc, "contact solve"),
            cycle_wall_s=cyc.get("wall_time_s", ""),
            peak_memory_MiB=cyc.get("peak_memory_MiB", ""),
            linear_solver=describe_linear_solver(cyc.get("linear_solver")),
            version=summary.get("version", ""))
        nested = cyc.get("nested_iteration")
        if nested is None:
            row["nested_status"] = "not in summary.json (older build)"
        elif nested.get("skipped"):
            row["nested_status"] = "skipped: " + nested["skipped"]
        levels = (nested or {}).get("levels") or []
        if levels:
            row["nested_status"] = "ran, %d level(s)" % len(levels)
            row["coarse_levels"] = "; ".join(
                "r%d: %d DoFs, %d its, %d active, %.3g s" % (
                    l["global_refinements"], l["n_dofs"],
                    l["newton_iterations"], l["active_nodes"],
                    l["wall_time_s"]) for l in levels)
            row["coarse_newton_by_level"] = "/".join(
                str(l["newton_iterations"]) for l in levels)
            row["coarse_newton_total"] = sum(l["newton_iterations"]
                                             for l in levels)
            row["coarse_time_s"] = sum(l["wall_time_s"] for l in levels)
        else:
            row["coarse_newton_total"] = 0
            row["coarse_time_s"] = 0.0
        if row["contact_solve_s"] != "":
            row["fine_solve_s"] = row["contact_solve_s"] - \
                row["coarse_time_s"]
    # The time of each Newton step is only printed.
    steps = common.newton_step_times(result.stdout)
    if steps:
        tot = [a + s for a, s in steps]
        row.update(step_mean_s=statistics.mean(tot),
                   step_assembly_mean_s=statistics.mean(a for a, _ in steps),
                   step_solve_mean_s=statistics.mean(s for _, s in steps),
                   step_min_s=min(tot), step_max_s=max(tot))
    return finish(row, result, cyc, timeout)


def run_elastic(exe, refinements, timeout, sub=4):
    result, summary = common.run_program(
        exe, elastic_settings(refinements, sub), timeout)
    row = new_row("elastic", result, scene=ELASTIC_SCENE, subdivisions=sub,
                  refinements=refinements)
    cyc = common.last_cycle(summary)
    if cyc is not None:
        row.update(n_dofs=cyc.get("n_dofs", ""),
                   n_dofs_body1=common.body_field(cyc, 0, "n_dofs"),
                   n_dofs_body2=common.body_field(cyc, 1, "n_dofs"),
                   cycle_wall_s=cyc.get("wall_time_s", ""),
                   peak_memory_MiB=cyc.get("peak_memory_MiB", ""),
                   version=summary.get("version", ""))
    # Each body's solve time is only printed.
    solves = common.body_solve_times(result.stdout)
    if solves:
        row["linear_solver"] = solves[-1][0]
    if len(solves) == 2:
        row.update(elastic_body1_s=solves[0][1], elastic_body2_s=solves[1][1],
                   elastic_solve_s=solves[0][1] + solves[1][1])
    return finish(row, result, cyc, timeout, len(solves) == 2)


def median_rows(rows, keys):
    """One row from repeats: the first row with the median of 'keys'."""
    out = dict(rows[0])
    for k in keys:
        vals = [r[k] for r in rows if r.get(k) not in ("", None)]
        if vals:
            out[k] = statistics.median(vals)
    out["repeats"] = len(rows)
    out["clean"] = int(all(r.get("clean") == 1 for r in rows))
    out["other_cpu_s"] = max(r.get("other_cpu_s") or 0 for r in rows)
    return out


TIME_KEYS = ["contact_solve_s", "cycle_wall_s", "process_wall_s",
             "step_mean_s", "step_assembly_mean_s", "step_solve_mean_s",
             "step_min_s", "step_max_s", "elastic_solve_s",
             "elastic_body1_s", "elastic_body2_s", "peak_memory_MiB",
             "coarse_time_s", "fine_solve_s"]


def run_clean(fn, args, retries, quiet_wait):
    """Runs until the run is clean (other processes used < 10 % of a core
    meanwhile), at most 1 + retries times; returns the least disturbed."""
    rows = []
    for attempt in range(1 + retries):
        common.wait_for_quiet(quiet_wait, QUIET_THRESHOLD, 3.0)
        row = fn(*args)
        rows.append(row)
        if row["status"] != "ok" or row["clean"] == 1 or \
                attempt == retries:
            break
        print("    disturbed run (other processes used %.1f CPU s in %.1f s)"
              "; again" % (row["other_cpu_s"], row["process_wall_s"]),
              flush=True)
    return min(rows, key=lambda r: (r["status"] != "ok", r["other_cpu_s"] /
                                    max(r["process_wall_s"], 1e-9)))


def run_repeated(fn, args, repeats, repeat_below_s, retries=2,
                 quiet_wait=600.0):
    rows = [run_clean(fn, args, retries, quiet_wait)]
    while (len(rows) < repeats and rows[0]["status"] == "ok" and
           rows[0]["process_wall_s"] < repeat_below_s):
        rows.append(run_clean(fn, args, retries, quiet_wait))
    return median_rows(rows, TIME_KEYS)


def write_csv(rows, path):
    common.write_csv(path, rows, FIELDS)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--exe", default=common.DEFAULT_EXE)
    p.add_argument("--csv", default=report.DEFAULT_CSV)
    p.add_argument("--png", default=report.DEFAULT_PNG)
    p.add_argument("--blocks-max-ref", type=int, default=7)
    p.add_argument("--hertz-max-ref", type=int, default=4)
    p.add_argument("--max-run-s", type=float, default=480.0)
    p.add_argument("--budget-s", type=float, default=1800.0)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--repeat-below-s", type=float, default=5.0)
    p.add_argument("--retries", type=int, default=2,
                   help="reruns of a run disturbed by other processes")
    p.add_argument("--quiet-wait", type=float, default=600.0,
                   help="longest wait for an idle machine before a run [s]")
    p.add_argument("--append", action="store_true",
                   help="keep the finished runs of --csv, run the rest")
    p.add_argument("--quick", action="store_true")
    p.add_argument("--nested-levels", type=int, default=None,
                   help="'Contact/Nested iteration levels' of the contact "
                   "runs (default: the program's default, 3); 0 = cold "
                   "start. Rows are tagged start = nested / cold, and "
                   "--append keeps the rows of the other start.")
    p.add_argument("--linear-solver", default="direct",
                   choices=["direct", "amg", "auto"],
                   help="'Linear solver/Type' of the contact runs (default "
                   "direct: MUMPS on the row-replacing system; amg: "
                   "Krylov + AMG on the eliminated system). Use another "
                   "--csv for each.")
    p.add_argument("--series", default="",
                   help="comma-separated series to run, e.g. "
                   "'hertz' or 'hertz:0,blocks:0.3' (default: all)")
    p.add_argument("--no-elastic", action="store_true",
                   help="do not (re)run the elastic references")
    p.add_argument("--smoke", action="store_true",
                   help="blocks, mu = 0.3, r = 0 and 1, and the elastic "
                   "reference; once each, no wait (ctest)")
    p.add_argument("--no-plot", action="store_true")
    a = p.parse_args()

    if a.smoke:
        a.blocks_max_ref, a.hertz_max_ref = 1, -1
        a.series, a.repeats, a.retries, a.quiet_wait = "blocks:0.3", 1, 0, 0
    if a.quick or a.smoke:
        if a.quick:
            a.blocks_max_ref, a.hertz_max_ref = 3, 1
        extensions = []
    else:
        extensions = BLOCKS_EXTENSIONS
    exe = common.check_executable(a.exe)
    exe_mtime = os.path.getmtime(exe)
    common.print_header(exe)
    start = time.perf_counter()

    # Jobs: (kind, scene, mu, subdivisions, refinements).
    start_tag = start_mode(a.nested_levels)

    def wanted(scene, mu):
        if not a.series:
            return True
        for item in a.series.split(","):
            name, _, m = item.strip().partition(":")
            if name == scene and (m == "" or float(m) == mu):
                return True
        return False

    # Jobs: (kind, scene, mu, subdivisions, refinements, start).
    jobs = []
    blocks_meshes = [(4, r) for r in range(a.blocks_max_ref + 1)] + \
        list(extensions)
    for sub, r in blocks_meshes:
        if not a.no_elastic and (wanted("blocks", 0.0) or
                                 wanted("blocks", 0.3)):
            jobs.append(("elastic", ELASTIC_SCENE, "", sub, r, ""))
        for mu in (0.0, 0.3):
            if wanted("blocks", mu):
                jobs.append(("contact", "blocks", mu, sub, r, start_tag))
    for r in range(a.hertz_max_ref + 1):
        for mu in (0.0, 0.3):
            if wanted("hertz", mu):
                jobs.append(("contact", "hertz", mu, "", r, start_tag))

    def est(job):
        return estimated_dofs("hertz" if job[1] == "hertz" else "blocks",
                              job[4], job[3] or 4)
    # Smallest first; hertz beyond ~1.5e6 DoFs last (optional sizes).
    jobs.sort(key=lambda j: (j[1] == "hertz" and est(j) > 1.5e6, est(j),
                             j[0] == "contact"))

    def job_key(r):
        return (r["kind"], r["scene"],
                "" if r["kind"] == "elastic" else float(r["mu"]),
                r["subdivisions"], r["refinements"],
                "" if r["kind"] == "elastic" else r.get("start") or "cold")

    done = {}
    kept = []     # --append: rows of other series / starts, kept as they are
    job_set = set(jobs)
    if a.append and os.path.exists(a.csv):
        for r in report.read_csv(a.csv):
            if job_key(r) not in job_set:
                kept.append(r)
            elif r["status"] == "ok":
                done[job_key(r)] = r
        print("reusing %d finished runs from %s, keeping %d other rows" % (
            len(done), a.csv, len(kept)), flush=True)

    rows = list(kept)
    last = {}     # per series: the largest finished run (for predictions)
    for job in jobs:
        kind, scene, mu, sub, r, job_start = job
        series = (kind, scene, mu, job_start)
        what = "%s %s mu=%s sub=%s r=%d %s" % (kind, scene, mu, sub, r,
                                               job_start)
        if job in done:
            row = done[job]
            rows.append(row)
            last[series] = row
            continue
        pred = None
        if series in last:
            prev = last[series]
            if prev["status"] != "ok":
                print("skip %s: the previous size failed" % what, flush=True)
                continue
            pred = prev["process_wall_s"] * (
                est(job) / float(prev["n_dofs"])) ** TIME_EXPONENT
            reason = None
            if pred > a.max_run_s:
                reason = "predicted %.0f s > %.0f s per run" % (pred,
                                                                a.max_run_s)
            elif common.RUN_SECONDS[0] + pred > a.budget_s:
                reason = "time budget (%.0f s used, %.0f s predicted)" % (
                    common.RUN_SECONDS[0], pred)
            if reason:
                print("skip %s: %s" % (what, reason), flush=True)
                rows.append(dict({k: "" for k in FIELDS}, kind=kind,
                                 scene=scene, mu=mu, subdivisions=sub,
                                 refinements=r, n_dofs=int(est(job)),
                                 status="skipped", message=reason,
                                 start=job_start))
                continue
        load = common.wait_for_quiet(a.quiet_wait, QUIET_THRESHOLD, 3.0)
        timeout = 2.5 * a.max_run_s
        if kind == "elastic":
            row = run_repeated(run_elastic, (exe, r, timeout, sub),
                               a.repeats, a.repeat_below_s, a.retries,
                               a.quiet_wait)
            print("elastic sub=%d r=%d n=%s: %s, solve %s s (%s + %s), "
                  "wall %.1f s (load before %.2f)" % (
                      sub, r, row["n_dofs"], row["status"],
                      num(row["elastic_solve_s"]),
                      num(row["elastic_body1_s"]),
                      num(row["elastic_body2_s"]), row["process_wall_s"],
                      load), flush=True)
        else:
            row = run_repeated(run_contact,
                               (exe, scene, mu, r, timeout, sub or 4,
                                a.nested_levels, a.linear_solver),
                               a.repeats, a.repeat_below_s, a.retries,
                               a.quiet_wait)
            print("%-6s mu=%-3g sub=%s r=%d n=%s: %s, %s its, step %s s "
                  "(asm %s, solve %s), contact solve %s s, wall %.1f s, "
                  "%s MiB (load before %.2f) [%s: %s %s, %s s]%s" % (
                      scene, mu, sub, r, row["n_dofs"], row["status"],
                      row["newton_iterations"], num(row["step_mean_s"]),
                      num(row["step_assembly_mean_s"]),
                      num(row["step_solve_mean_s"]),
                      num(row["contact_solve_s"]), row["process_wall_s"],
                      num(row["peak_memory_MiB"], "%.0f"), load,
                      row["start"], row["nested_status"],
                      row["coarse_newton_by_level"],
                      num(row["coarse_time_s"]),
                      "" if row["status"] == "ok" else " " + row["message"]),
                  flush=True)
        if os.path.getmtime(exe) != exe_mtime:
            row["message"] = (row.get("message") or "") + \
                " executable changed during the sweep"
            print("WARNING: the executable changed during the sweep",
                  flush=True)
        last[series] = row
        rows.append(row)
        report.fill_references(rows, report.single_body_curve())
        write_csv(rows, a.csv)
    report.fill_references(rows, report.single_body_curve())
    write_csv(rows, a.csv)
    if not a.no_plot:
        report.plot(rows, a.png)
    print("total %.0f s (%.0f s in runs); wrote %s and %s" % (
        time.perf_counter() - start, common.RUN_SECONDS[0], a.csv, a.png))
    print(report.table(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
