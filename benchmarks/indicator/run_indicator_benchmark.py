#!/usr/bin/python3
"""Error indicator benchmark of coulomb-adapt: the indicator's cost against
the contact solve, and its effectivity (ZZ and SPR recovery).

Part 'cost': serial runs (1 MPI rank), one cycle each, `Output/Write VTU =
false`, `Error indicator/Compute exact error = false`, default solvers
(contact system: MUMPS; corrected problem of the indicator: 'auto', i.e.
MUMPS up to 10000 DoFs per body and CG + AMG above). Measured per run, from
summary.json: timings_s['error indicator'] (contact correction + stress
recovery + element contributions) divided by timings_s['contact solve'].
Series:

  blocks P1   prm/blocks.prm (triangles), Global refinements r = 0..5
  blocks Q1   prm/blocks.prm + Mesh/Cell type=quadrilateral, r = 1..6, and
              the 10 x 10 / 20 x 20 mesh with r = 5 (1.03e6 DoFs)
  hertz  Q1   prm/hertz.prm (graded quadrilaterals), r = 0..3

Part 'effectivity': `Error indicator/Compute exact error = true`, i.e. the
exact error against the scene's exact solution (manufactured) or against a
reference solution on the same scene refined `Reference refinements` (2)
more times; effectivity = epsilon / epsilon_exact (summary.json), for the
recoveries given by --recovery (zz, spr). Series:

  manufactured Q1 (r = 2..5), manufactured P1 (r = 1..4): exact solution
  blocks P1 (prm/blocks.prm, r = 0..3), blocks Q1 (r = 1..3)
  punch Q1 (prm/punch.prm, r = 0..3)
  hertz Q1 with Scene/Hertz/Contact mesh size = 0.8 (r = 0..2), and the
  default graded mesh (Contact mesh size 0.1, r = 0)

A recovery the executable does not implement (it stops with "... not
implemented ...") is recorded as 'unavailable', not as a failure. Unless
--no-probe, one small probe run per recovery decides this before the sweep,
so that unavailable recoveries cost no contact solves.

Sizes are skipped (recorded as 'skipped') above --max-dofs, when the run
time predicted from the previous size of the series (x (DoF ratio)^1.5)
exceeds --max-run-s, or when it would exceed the --budget-s of run time.

Timing hygiene (part cost): before each run the script waits (at most
--quiet-wait s) until other processes use less than 0.3 cores, and it
measures the CPU time other processes used during the run (other_cpu_s;
clean = 0 when above 10 % of a core); a disturbed run shorter than 60 s is
repeated once and the least disturbed run kept. Runs shorter than 5 s are
done 3 times and the run with the median fraction is kept.

Part 'breakdown': the indicator's three parts as the program times them in
summary.json (timings_s 'error indicator: correction', 'error indicator:
smoothing', 'error indicator: contributions'), ZZ and SPR, on blocks at
1.8e3 and 1.1e5 DoFs and hertz at 1.4e5.

Usage:
  run_indicator_benchmark.py                         effectivity (zz, spr) and
                                                     cost (zz)
  run_indicator_benchmark.py --part cost             only the cost sweep (zz)
  run_indicator_benchmark.py --part cost --recovery spr --append --max-dofs 2e5
                                                     SPR cost up to 2e5 DoFs
  run_indicator_benchmark.py --part effectivity --recovery spr --append
                                                     (re)run SPR only, keep
                                                     the other rows
  run_indicator_benchmark.py --part breakdown        the indicator's parts
  run_indicator_benchmark.py --smoke                 one tiny run per part
                                                     (a few seconds; ctest)
Plots and tables: report_indicator_benchmark.py (the plots are drawn at the
end of a sweep).
Options: --exe (default build/coulomb-adapt), --outdir (of the CSVs and
plots; default: next to this script), --max-dofs, --max-run-s (300),
--budget-s (1500, per invocation), --quiet-wait (120), --quick (small sizes
only), --no-probe.

Only the Python standard library and matplotlib are used.
"""

import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(
    __file__))))
import common  # noqa: E402
import report_indicator_benchmark as report  # noqa: E402
from report_indicator_benchmark import (COST_SERIES, EFF_SERIES, fmt,  # noqa
                                        read_csv)

TIME_EXPONENT = 1.5
QUIET_THRESHOLD = 0.3

HERTZ_BASE = {0.8: 1060, 0.4: 1720, 0.2: 3500, 0.1: 9198}

COST_FIELDS = [
    "series", "scene", "cell_type", "recovery", "subdivisions",
    "refinements", "n_dofs", "n_dofs_body1", "n_dofs_body2", "status",
    "newton_iterations", "contact_solve_s", "indicator_s", "fraction",
    "assembly_s", "setup_s", "cycle_wall_s", "process_wall_s",
    "correction_skipped", "projected_nodes", "correction_solver",
    "epsilon", "peak_memory_MiB", "repeats", "load_before", "other_cpu_s",
    "clean", "version", "message",
]

EFF_FIELDS = [
    "series", "scene", "cell_type", "recovery", "contact_mesh_size",
    "subdivisions", "refinements", "n_dofs", "status", "epsilon",
    "epsilon_volume_1", "epsilon_volume_2", "epsilon_contact",
    "epsilon_exact", "effectivity", "elem_eff_mean", "elem_eff_std",
    "elem_eff_min", "elem_eff_max", "n_elements", "reference",
    "correction_skipped", "projected_nodes", "newton_iterations",
    "contact_solve_s", "indicator_s", "exact_error_s", "process_wall_s",
    "version", "message",
]


def estimated_dofs(series, r, sub=None):
    """DoFs of both bodies (P1 meshes: the quadrilateral mesh refined once
    more, split into triangles: same vertices)."""
    k = r + (1 if series["cell"] == "triangle" else 0)

    def rect(nx, ny):
        return 2 * (nx * 2 ** k + 1) * (ny * 2 ** k + 1)
    scene = series["scene"]
    if scene == "blocks":
        s = sub or 4
        return rect(s, s) + rect(2 * s, 2 * s)
    if scene == "punch":
        return rect(4, 2) + rect(10, 5)
    if scene == "manufactured":
        return rect(2, 2) + rect(3, 3)
    if scene == "hertz":
        return HERTZ_BASE.get(series.get("cms", 0.1), 9198) * 4 ** r
    return float("nan")


# ---------------------------------------------------------------- machine

def settings(series, r, recovery, exact, sub=None):
    sets = ["Scene/Name=" + series["scene"],
            "Mesh/Cell type=" + series["cell"],
            "Mesh/Global refinements=%d" % r,
            # One cycle: no adaptation, so the strategy only has to be
            # valid for the cell type (blocks.prm remeshes triangles).
            "Adaptation/Strategy=uniform",
            "Adaptation/Minimum number of cycles=1",
            "Adaptation/Number of cycles=1",
            "Error indicator/Estimator=" + recovery,
            "Error indicator/Compute exact error=" + (
                "true" if exact else "false")]
    if "cms" in series:
        sets.append("Scene/Hertz/Contact mesh size=%g" % series["cms"])
    if sub:
        sets += ["Scene/Blocks/Upper body subdivisions=%d, %d" % (sub, sub),
                 "Scene/Blocks/Lower body subdivisions=%d, %d" % (
                     2 * sub, 2 * sub)]
    return sets


def prm(series):
    return os.path.join(common.PRM_DIR, series["prm"]) if series["prm"] \
        else None


def command(series, r, recovery, exact, sub=None):
    """The command line of a run, for the README (relative paths)."""
    return common.shell_command(common.program_command(
        common.DEFAULT_EXE, settings(series, r, recovery, exact, sub) + [
            "Output/Write VTU=false", "Output/Output directory=/tmp/run"],
        prm(series)))


def unavailable_message(text):
    for line in text.splitlines():
        if "not implemented" in line:
            return line.replace("coulomb-adapt: error:", "").strip()
    return None


def run_one(exe, series, r, recovery, exact, timeout, sub=None):
    result, summary = common.run_program(
        exe, settings(series, r, recovery, exact, sub), timeout,
        prm(series))
    row = dict(series=series["key"], scene=series["scene"],
               cell_type=series["cell"], recovery=recovery,
               subdivisions=sub or "", refinements=r,
               contact_mesh_size=series.get("cms", 0.1)
               if series["scene"] == "hertz" else "",
               process_wall_s=result.wall_s, other_cpu_s=result.other_cpu_s,
               clean=int(result.clean))
    cyc = common.last_cycle(summary)
    if cyc is not None:
        t = cyc.get("timings_s", {})
        bodies = cyc.get("bodies", [])
        exact_s = t.get("exact error", 0.0)
        # 'exact error' is timed inside 'error indicator' (nested scope):
        # the indicator alone is the difference.
        indicator = t.get("error indicator", float("nan")) - exact_s
        contact = t.get("contact solve", t.get("solve", float("nan")))
        corr = cyc.get("correction", {})
        ee = cyc.get("element_effectivity", {})
        ev = cyc.get("epsilon_volume", ["", ""])
        row.update(
            n_dofs=cyc.get("n_dofs", ""),
            n_dofs_body1=bodies[0]["n_dofs"] if bodies else "",
            n_dofs_body2=bodies[1]["n_dofs"] if len(bodies) > 1 else "",
            newton_iterations=cyc.get("newton_iterations", ""),
            contact_solve_s=contact, indicator_s=indicator,
            exact_error_s=t.get("exact error", ""),
            fraction=indicator / contact if contact else "",
            assembly_s=t.get("assembly", ""), setup_s=t.get("setup", ""),
            cycle_wall_s=cyc.get("wall_time_s", ""),
            correction_skipped=int(bool(corr.get("skipped")))
            if corr else "",
            projected_nodes=corr.get("projected_nodes", ""),
            epsilon=cyc.get("epsilon", ""),
            epsilon_volume_1=ev[0], epsilon_volume_2=ev[1],
            epsilon_contact=cyc.get("epsilon_contact", ""),
            epsilon_exact=cyc.get("epsilon_exact", ""),
            effectivity=cyc.get("effectivity", ""),
            elem_eff_mean=ee.get("mean", ""), elem_eff_std=ee.get("std", ""),
            elem_eff_min=ee.get("min", ""), elem_eff_max=ee.get("max", ""),
            n_elements=ee.get("n_elements", ""),
            reference=cyc.get("exact_error_reference", ""),
            peak_memory_MiB=cyc.get("peak_memory_MiB", ""),
            version=summary.get("version", ""))
        # The corrected problem is solved with 'Linear solver/Type = auto':
        # each body directly up to 10000 DoFs, CG + AMG above.
        row["correction_solver"] = "" if not corr or corr.get("skipped") \
            else "+".join("direct" if b["n_dofs"] <= 10000 else "amg"
                          for b in bodies)
    failure = result.failure()
    if result.killed:
        row.update(status="timeout", message="killed after %g s" % timeout)
    elif failure:
        msg = unavailable_message(result.stderr + "\n" + result.stdout)
        if msg:
            row.update(status="unavailable", message=msg)
        else:
            row.update(status="failed", message=failure[1])
    elif cyc is None:
        row.update(status="failed", message="no cycle in summary.json")
    elif exact and row.get("effectivity") in ("", None):
        row.update(status="failed", message="no effectivity in summary")
    else:
        row.update(status="ok")
    row["command"] = command(series, r, recovery, exact, sub)
    return row


def probe(exe, recovery):
    """None if the executable implements the recovery, else the message."""
    series = dict(key="probe", scene="manufactured", prm=None,
                  cell="quadrilateral")
    row = run_one(exe, series, 0, recovery, False, 120)
    if row["status"] == "unavailable":
        return row["message"]
    return None


# ------------------------------------------------------------- breakdown
# Part 'breakdown': the indicator's three parts as the program times them
# (summary.json, timings_s 'error indicator: correction', '...: smoothing',
# '...: contributions'), for both recoveries, on the small blocks meshes
# where the target is tightest and at about 1e5 DoFs. Runs shorter than
# 5 s are done 3 times and the one with the median indicator time kept.

BREAKDOWN_FIELDS = [
    "series", "scene", "cell_type", "recovery", "refinements", "n_dofs",
    "status", "newton_iterations", "contact_solve_s", "indicator_s",
    "fraction", "correction_s", "smoothing_s", "contributions_s",
    "unaccounted_s", "repeats", "version", "message",
]
BREAKDOWN_JOBS = [("blocks P1", 1), ("blocks Q1", 2), ("blocks P1", 4),
                  ("blocks Q1", 5), ("hertz Q1", 2)]
BREAKDOWN_PARTS = [("correction_s", "error indicator: correction"),
                   ("smoothing_s", "error indicator: smoothing"),
                   ("contributions_s", "error indicator: contributions")]


def breakdown(args, exe):
    """Returns 1 if a job failed. With --append, as in the other parts, the
    CSV's finished (ok) rows are kept and their jobs not run again."""
    series = {s["key"]: s for s in COST_SERIES}
    recoveries = args.recovery
    rows = [x for x in read_csv(args.paths["breakdown_csv"])
            if x["status"] == "ok"] \
        if args.append else []
    done = {(x["series"], int(x["refinements"]), x["recovery"])
            for x in rows}
    n_failed = 0
    jobs = BREAKDOWN_JOBS[:1] if args.smoke else BREAKDOWN_JOBS
    for key, r in jobs:
        s = series[key]
        if args.max_dofs and estimated_dofs(s, r) > args.max_dofs:
            continue
        for rec in recoveries:
            if (key, r, rec) in done:
                continue
            runs = []
            while True:
                common.wait_for_quiet(args.quiet_wait, QUIET_THRESHOLD)
                result, summary = common.run_program(
                    exe, settings(s, r, rec, False), 2.5 * args.max_run_s,
                    prm(s))
                cyc = common.last_cycle(summary)
                row = dict(series=key, scene=s["scene"], cell_type=s["cell"],
                           recovery=rec, refinements=r, status="ok",
                           message="", command=command(s, r, rec, False))
                t = cyc.get("timings_s", {}) if cyc else {}
                if result.failure() or cyc is None:
                    row.update(status="failed", message=common.error_message(
                        result.stderr, result.stdout))
                elif any(section not in t for _, section in BREAKDOWN_PARTS):
                    print("summary.json has no '%s' timings: the executable "
                          "predates them" % BREAKDOWN_PARTS[0][1], flush=True)
                    return 1
                else:
                    row.update(n_dofs=cyc["n_dofs"],
                               newton_iterations=cyc.get("newton_iterations",
                                                         ""),
                               contact_solve_s=t["contact solve"],
                               indicator_s=t["error indicator"],
                               version=summary.get("version", ""))
                    row["fraction"] = row["indicator_s"] / \
                        row["contact_solve_s"] if row["contact_solve_s"] \
                        else ""
                    for field, section in BREAKDOWN_PARTS:
                        row[field] = t[section]
                    row["unaccounted_s"] = row["indicator_s"] - sum(
                        row[f] for f, _ in BREAKDOWN_PARTS)
                runs.append(row)
                if row["status"] != "ok" or result.wall_s >= 5.0 or \
                        len(runs) == 3 or args.smoke:
                    break
            ok = sorted((x for x in runs if x["status"] == "ok"),
                        key=lambda x: x["indicator_s"])
            row = dict(ok[len(ok) // 2]) if ok else runs[-1]
            row["repeats"] = len(runs)
            if ok and len(ok) < len(runs):
                row["message"] = "a repeat failed: " + runs[-1]["message"]
            n_failed += not ok
            print("breakdown %s r=%d %s: %s" % (key, r, rec, ", ".join(
                "%s %s" % (k, fmt(row.get(k))) for k in BREAKDOWN_FIELDS[5:-1]
                if row.get(k) not in ("", None))), flush=True)
            rows.append(row)
            write_csv(rows, args.paths["breakdown_csv"], BREAKDOWN_FIELDS)
    print(report.breakdown_table(rows))
    return 1 if n_failed else 0


def cost_jobs(args):
    jobs = []
    for s in COST_SERIES:
        for r in s["refs"]:
            jobs.append((s, r, None))
        for sub, r in s["ext"]:
            jobs.append((s, r, sub))
    return jobs


def eff_jobs(args):
    return [(s, r, None) for s in EFF_SERIES for r in s["refs"]]


def job_key(series_key, recovery, r, sub):
    return (series_key, recovery, int(r), int(sub) if sub else 0)


def row_key(row):
    return job_key(row["series"], row["recovery"], row["refinements"],
                   row["subdivisions"] or 0)


def median_by_fraction(rows):
    ok = [r for r in rows if r["status"] == "ok"]
    if not ok:
        return rows[-1]
    ok.sort(key=lambda r: r["fraction"])
    best = dict(ok[len(ok) // 2])
    best["repeats"] = len(rows)
    best["clean"] = int(all(r["clean"] for r in ok))
    best["other_cpu_s"] = max(r["other_cpu_s"] for r in ok)
    return best


def sweep(part, args, exe, unavailable, budget):
    exact = (part == "effectivity")
    path = args.paths["eff_csv" if exact else "cost_csv"]
    fields = EFF_FIELDS if exact else COST_FIELDS
    jobs = eff_jobs(args) if exact else cost_jobs(args)
    if args.smoke:
        jobs = [min(jobs, key=lambda j: estimated_dofs(*j))]
    if args.quick:
        limit = 3e3 if exact else 1.2e4
        jobs = [j for j in jobs if estimated_dofs(j[0], j[1], j[2]) <= limit]
    recoveries = args.recovery
    old = []
    if args.append and os.path.exists(path):
        old = read_csv(path)
    keep = {row_key(r): r for r in old}
    rows = {}
    # Smallest first across the series (a fair share of the budget).
    order = sorted(((s, r, sub, rec) for s, r, sub in jobs
                    for rec in recoveries),
                   key=lambda j: (estimated_dofs(j[0], j[1], j[2]),
                                  j[3] != "zz"))
    last = {}
    for s, r, sub, rec in order:
        key = job_key(s["key"], rec, r, sub)
        est = estimated_dofs(s, r, sub)
        what = "%s %s r=%d%s %s" % (part, s["key"], r,
                                     " sub=%d" % sub if sub else "", rec)
        base = dict(series=s["key"], scene=s["scene"], cell_type=s["cell"],
                    recovery=rec, subdivisions=sub or "", refinements=r,
                    contact_mesh_size=s.get("cms", 0.1)
                    if s["scene"] == "hertz" else "")
        if key in keep and keep[key]["status"] in ("ok", "unavailable") and \
                not (keep[key]["status"] == "unavailable" and
                     rec not in unavailable):
            rows[key] = keep[key]
            last[(s["key"], rec)] = keep[key]
            continue
        if rec in unavailable:
            rows[key] = dict(base, n_dofs="", status="unavailable",
                             message=unavailable[rec])
            print("%s: unavailable (%s)" % (what, unavailable[rec]),
                  flush=True)
            continue
        reason = None
        if args.max_dofs and est > args.max_dofs:
            reason = "estimated %.3g DoFs > --max-dofs %.3g" % (
                est, args.max_dofs)
        prev = last.get((s["key"], rec))
        pred = None
        if prev is not None and reason is None:
            if prev["status"] != "ok":
                reason = "the previous size did not finish (%s)" % \
                    prev["status"]
            else:
                pred = float(prev["process_wall_s"]) * (
                    est / float(prev["n_dofs"])) ** TIME_EXPONENT
                if pred > args.max_run_s:
                    reason = "predicted %.0f s > %.0f s per run" % (
                        pred, args.max_run_s)
                elif common.RUN_SECONDS[0] + pred > budget:
                    reason = "time budget (%.0f s used, %.0f s predicted, "\
                             "%.0f s allowed)" % (common.RUN_SECONDS[0], pred,
                                                  budget)
        if reason:
            print("skip %s: %s" % (what, reason), flush=True)
            rows[key] = dict(base, n_dofs=int(est), status="skipped",
                             message=reason)
            continue
        timeout = 2.5 * args.max_run_s
        runs = []
        load = ""
        while True:
            if not exact:
                load = common.wait_for_quiet(args.quiet_wait, QUIET_THRESHOLD)
            row = run_one(exe, s, r, rec, exact, timeout, sub)
            row["load_before"] = load
            runs.append(row)
            if exact or row["status"] != "ok" or args.smoke:
                break
            short = row["process_wall_s"] < 5.0
            disturbed = not row["clean"] and row["process_wall_s"] < 60.0
            n_ok = sum(1 for x in runs if x["status"] == "ok")
            if short and n_ok < 3:
                continue
            if disturbed and len(runs) < 2:
                continue
            break
        row = runs[0] if exact else median_by_fraction(runs)
        if not exact and len(runs) > 1 and not row["clean"]:
            clean = [x for x in runs if x["clean"] and x["status"] == "ok"]
            if clean:
                row = dict(clean[0], repeats=len(runs))
        row.setdefault("repeats", len(runs))
        rows[key] = row
        last[(s["key"], rec)] = row
        if exact:
            print("%s: %s n=%s eps=%s eps_exact=%s effectivity=%s "
                  "(indicator %s s, exact error %s s, wall %.1f s)%s" % (
                      what, row["status"], row.get("n_dofs"),
                      fmt(row.get("epsilon")), fmt(row.get("epsilon_exact")),
                      fmt(row.get("effectivity")),
                      fmt(row.get("indicator_s")),
                      fmt(row.get("exact_error_s")), row["process_wall_s"],
                      "" if row["status"] == "ok" else " " + row["message"]),
                  flush=True)
        else:
            print("%s: %s n=%s its=%s contact %s s, indicator %s s, "
                  "fraction %s, wall %.1f s, other cpu %.2f s, load %.2f, "
                  "repeats %d%s" % (
                      what, row["status"], row.get("n_dofs"),
                      row.get("newton_iterations"),
                      fmt(row.get("contact_solve_s")),
                      fmt(row.get("indicator_s")), fmt(row.get("fraction")),
                      row["process_wall_s"], row["other_cpu_s"], load or 0,
                      len(runs),
                      "" if row["status"] == "ok" else " " + row["message"]),
                  flush=True)
        write_csv(merge(old, rows), path, fields)
    all_rows = merge(old, rows)
    write_csv(all_rows, path, fields)
    return all_rows


def merge(old, new):
    out = {row_key(r): r for r in old}
    out.update(new)
    return sorted(out.values(), key=lambda r: (
        r["series"], r["recovery"], float(r.get("n_dofs") or 0)))


def write_csv(rows, path, fields):
    common.write_csv(path, rows, fields + ["command"])


def main():
    p = argparse.ArgumentParser(
        description=__doc__.split("\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=__doc__.split("\n", 2)[2])
    p.add_argument("--part", default="all",
                   choices=["cost", "effectivity", "breakdown", "all"],
                   help="all = effectivity + cost; breakdown: the "
                        "indicator's parts (correction, smoothing, "
                        "contributions)")
    p.add_argument("--recovery", default="zz,spr",
                   help="comma-separated recoveries: zz,spr (default both; "
                        "part cost: zz only unless given)")
    p.add_argument("--exe", "--executable", default=common.DEFAULT_EXE,
                   dest="executable")
    p.add_argument("--outdir", default=report.HERE,
                   help="directory of the CSVs and plots")
    p.add_argument("--max-dofs", type=float, default=None)
    p.add_argument("--max-run-s", type=float, default=300.0)
    p.add_argument("--budget-s", type=float, default=1500.0,
                   help="run time allowed to this invocation (waits for a "
                        "quiet machine not counted)")
    p.add_argument("--quiet-wait", type=float, default=120.0)
    p.add_argument("--append", action="store_true",
                   help="keep the finished (ok/unavailable) rows of the "
                        "CSVs and run only the others")
    p.add_argument("--no-probe", action="store_true")
    p.add_argument("--quick", action="store_true")
    p.add_argument("--smoke", action="store_true",
                   help="the smallest run of each part, once, no wait, no "
                   "probe (ctest)")
    a = p.parse_args()
    recovery_given = any(x.startswith("--recovery") for x in sys.argv)
    a.recovery = [x.strip() for x in a.recovery.split(",") if x.strip()]
    for x in a.recovery:
        if x not in ("zz", "spr"):
            p.error("unknown recovery '%s' (zz, spr)" % x)

    a.paths = report.paths(a.outdir)
    if a.smoke:
        a.quiet_wait, a.no_probe = 0, True
    exe = common.check_executable(a.executable)
    common.print_header(exe)
    start = time.perf_counter()
    if a.part == "breakdown":
        return breakdown(a, exe)
    unavailable = {}
    if not a.no_probe:
        for rec in a.recovery:
            msg = probe(exe, rec)
            if msg:
                unavailable[rec] = msg
                print("recovery %s unavailable: %s" % (rec, msg), flush=True)
    parts = ["effectivity", "cost"] if a.part == "all" else [a.part]
    for part in parts:
        args = argparse.Namespace(**vars(a))
        if part == "cost" and not recovery_given:
            args.recovery = ["zz"]
        rows = sweep(part, args, exe, unavailable, a.budget_s)
        if part == "cost":
            report.plot_cost(rows, a.paths["cost_png"])
            print(report.cost_table(rows))
        else:
            report.plot_effectivity(rows, a.paths["eff_png"])
            print(report.eff_table(rows))
    print("total %.0f s (%.0f s in runs)" % (time.perf_counter() - start,
                                             common.RUN_SECONDS[0]), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
