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
  run_indicator_benchmark.py --plot-only             re-plot from the CSVs
  run_indicator_benchmark.py --table                 print the README tables
Options: --executable (default /work/main/build/coulomb-adapt), --max-dofs,
--max-run-s (300), --budget-s (1500, per invocation), --quiet-wait (120),
--quick (small sizes only, a smoke test), --no-probe.

Only the Python standard library and matplotlib are used.
"""

import argparse
import csv
import json
import math
import os
import platform
import resource
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
DEFAULT_EXE = "/work/main/build/coulomb-adapt"
PRM = os.path.join(ROOT, "prm")
COST_CSV = os.path.join(HERE, "results_cost.csv")
EFF_CSV = os.path.join(HERE, "results_effectivity.csv")
COST_PNG = os.path.join(HERE, "indicator_cost.png")
EFF_PNG = os.path.join(HERE, "effectivity.png")

TARGET_FRACTION = 0.20
BAND = (0.7, 1.4)
TIME_EXPONENT = 1.5
QUIET_THRESHOLD = 0.3
CLEAN_FRACTION = 0.1
CLEAN_ALLOWANCE_S = 0.05

# ------------------------------------------------------------------ series
# A series: scene, parameter file (None: no file), cell type, extra
# overrides, coarse-mesh description for the DoF estimate, refinements.
# 'sub' (blocks only) is the number of upper-body cells per direction
# (lower body: twice as many).

COST_SERIES = [
    dict(key="blocks P1", scene="blocks", prm="blocks.prm",
         cell="triangle", refs=list(range(0, 6)), ext=[]),
    dict(key="blocks Q1", scene="blocks", prm="blocks.prm",
         cell="quadrilateral", refs=list(range(1, 7)), ext=[(10, 5)]),
    dict(key="hertz Q1", scene="hertz", prm="hertz.prm",
         cell="quadrilateral", refs=list(range(0, 4)), ext=[]),
]

EFF_SERIES = [
    dict(key="manufactured Q1", scene="manufactured", prm=None,
         cell="quadrilateral", refs=list(range(2, 6))),
    dict(key="manufactured P1", scene="manufactured", prm=None,
         cell="triangle", refs=list(range(1, 5))),
    dict(key="blocks P1", scene="blocks", prm="blocks.prm",
         cell="triangle", refs=list(range(0, 4))),
    dict(key="blocks Q1", scene="blocks", prm="blocks.prm",
         cell="quadrilateral", refs=list(range(1, 4))),
    dict(key="punch Q1", scene="punch", prm="punch.prm",
         cell="quadrilateral", refs=list(range(0, 4))),
    dict(key="hertz Q1 (cms 0.8)", scene="hertz", prm="hertz.prm",
         cell="quadrilateral", refs=list(range(0, 3)), cms=0.8),
    dict(key="hertz Q1 (cms 0.1)", scene="hertz", prm="hertz.prm",
         cell="quadrilateral", refs=[0]),
]

# Measured DoFs of hertz at r = 0 per 'Contact mesh size' (x 4 per r).
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

def busy_seconds():
    with open("/proc/stat") as f:
        v = [int(x) for x in f.readline().split()[1:]]
    busy = v[0] + v[1] + v[2] + v[5] + v[6] + (v[7] if len(v) > 7 else 0)
    return busy / os.sysconf("SC_CLK_TCK")


def children_cpu():
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def busy_cores(window=1.0):
    b0, t0 = busy_seconds(), time.perf_counter()
    time.sleep(window)
    return (busy_seconds() - b0) / (time.perf_counter() - t0)


def wait_for_quiet(max_wait):
    start = time.perf_counter()
    load = busy_cores(2.0)
    announced = False
    while load > QUIET_THRESHOLD and time.perf_counter() - start < max_wait:
        if not announced:
            print("    machine busy (%.2f cores); waiting up to %.0f s" % (
                load, max_wait), flush=True)
            announced = True
        time.sleep(5)
        load = busy_cores(2.0)
    return load


def machine_info():
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    mem = ""
    try:
        with open("/proc/meminfo") as f:
            mem = "%.1f GiB" % (int(f.readline().split()[1]) / 2 ** 20)
    except (OSError, ValueError, IndexError):
        pass
    return "%d cores (nproc), %s, %s RAM, %s" % (
        os.cpu_count() or 0, cpu, mem, platform.platform())


# ------------------------------------------------------------------- runs

RUN_SECONDS = [0.0]


def execute(args, timeout):
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    cpu0, busy0 = children_cpu(), busy_seconds()
    start = time.perf_counter()
    proc = subprocess.Popen(args, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env,
                            start_new_session=True)
    try:
        out, err = proc.communicate(timeout=timeout)
        rc = proc.returncode
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        out, err = proc.communicate()
        rc = None
    wall = time.perf_counter() - start
    RUN_SECONDS[0] += wall
    other = (busy_seconds() - busy0) - (children_cpu() - cpu0)
    return rc, out, err, wall, max(0.0, other)


def command(exe, series, r, out_dir, recovery, exact, sub=None):
    args = [exe]
    if series["prm"]:
        args.append(os.path.join(PRM, series["prm"]))
    sets = ["Scene/Name=" + series["scene"],
            "Mesh/Cell type=" + series["cell"],
            "Mesh/Global refinements=%d" % r,
            # One cycle: no adaptation, so the strategy only has to be
            # valid for the cell type (blocks.prm remeshes triangles).
            "Adaptation/Strategy=uniform",
            "Adaptation/Minimum number of cycles=1",
            "Adaptation/Number of cycles=1",
            "Output/Write VTU=false",
            "Output/Output directory=" + out_dir,
            "Error indicator/Recovery=" + recovery,
            "Error indicator/Compute exact error=" + (
                "true" if exact else "false")]
    if "cms" in series:
        sets.append("Scene/Hertz/Contact mesh size=%g" % series["cms"])
    if sub:
        sets += ["Scene/Blocks/Upper body subdivisions=%d, %d" % (sub, sub),
                 "Scene/Blocks/Lower body subdivisions=%d, %d" % (
                     2 * sub, 2 * sub)]
    for s in sets:
        args += ["-s", s]
    return args


def shell_command(args):
    """The command line of a run, for the README (relative paths)."""
    out = ["build/coulomb-adapt"]
    for a in args[1:]:
        if a.startswith(ROOT + "/"):
            a = os.path.relpath(a, ROOT)
        if a.startswith("Output/Output directory="):
            a = "Output/Output directory=/tmp/run"
        out.append("'%s'" % a if (" " in a or "=" in a) else a)
    return " ".join(out)


def unavailable_message(text):
    for line in text.splitlines():
        if "not implemented" in line:
            return line.replace("coulomb-adapt: error:", "").strip()
    return None


def run_one(exe, series, r, recovery, exact, timeout, sub=None):
    out_dir = tempfile.mkdtemp(prefix="coulomb-indicator-bench-")
    args = command(exe, series, r, out_dir, recovery, exact, sub)
    rc, out, err, wall, other = execute(args, timeout)
    row = dict(series=series["key"], scene=series["scene"],
               cell_type=series["cell"], recovery=recovery,
               subdivisions=sub or "", refinements=r,
               contact_mesh_size=series.get("cms", 0.1)
               if series["scene"] == "hertz" else "",
               process_wall_s=wall, other_cpu_s=other,
               clean=int(other < CLEAN_FRACTION * wall + CLEAN_ALLOWANCE_S))
    summary, cyc = None, None
    try:
        with open(os.path.join(out_dir, "summary.json")) as f:
            summary = json.load(f)
        cyc = summary["cycles"][-1]
    except (OSError, ValueError, KeyError, IndexError):
        pass
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
    text = (err or "") + "\n" + (out or "")
    if rc is None:
        row.update(status="timeout", message="killed after %g s" % timeout)
    elif rc != 0:
        msg = unavailable_message(text)
        if msg:
            row.update(status="unavailable", message=msg)
        else:
            row.update(status="failed",
                       message=" ".join(text.strip().split())[-300:])
    elif cyc is None:
        row.update(status="failed", message="no cycle in summary.json")
    elif exact and row.get("effectivity") in ("", None):
        row.update(status="failed", message="no effectivity in summary")
    else:
        row.update(status="ok")
    row["command"] = shell_command(
        command(exe, series, r, "/tmp/run", recovery, exact, sub))
    shutil.rmtree(out_dir, ignore_errors=True)
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

BREAKDOWN_CSV = os.path.join(HERE, "results_breakdown.csv")
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
    rows = [x for x in read_csv(BREAKDOWN_CSV) if x["status"] == "ok"] \
        if args.append else []
    done = {(x["series"], int(x["refinements"]), x["recovery"])
            for x in rows}
    n_failed = 0
    for key, r in BREAKDOWN_JOBS:
        s = series[key]
        if args.max_dofs and estimated_dofs(s, r) > args.max_dofs:
            continue
        for rec in recoveries:
            if (key, r, rec) in done:
                continue
            runs = []
            while True:
                wait_for_quiet(args.quiet_wait)
                out_dir = tempfile.mkdtemp(prefix="coulomb-indicator-bench-")
                cmd = command(exe, s, r, out_dir, rec, False)
                rc, out, err, wall, other = execute(cmd, 2.5 * args.max_run_s)
                row = dict(series=key, scene=s["scene"], cell_type=s["cell"],
                           recovery=rec, refinements=r, status="ok",
                           message="", command=shell_command(command(
                               exe, s, r, "/tmp/run", rec, False)))
                try:
                    with open(os.path.join(out_dir, "summary.json")) as f:
                        summary = json.load(f)
                    cyc = summary["cycles"][-1]
                except (OSError, ValueError, KeyError, IndexError):
                    summary, cyc = None, None
                shutil.rmtree(out_dir, ignore_errors=True)
                t = cyc.get("timings_s", {}) if cyc else {}
                if rc != 0 or cyc is None:
                    row.update(status="failed", message=" ".join(
                        ((err or "") + (out or "")).split())[-300:])
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
                if row["status"] != "ok" or wall >= 5.0 or len(runs) == 3:
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
            write_csv(rows, BREAKDOWN_CSV, BREAKDOWN_FIELDS)
    print(breakdown_table(rows))
    return 1 if n_failed else 0


def breakdown_table(rows):
    lines = ["| series | recovery | DoFs | contact solve [s] | indicator [s] "
             "(fraction) | correction | smoothing | contributions |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["status"] != "ok":
            lines.append("| %s, r = %s | %s | %s | | | | | |" % (
                r["series"], r["refinements"], r["recovery"], r["status"]))
            continue
        ind = float(r["indicator_s"])

        def pc(x):
            return "%.2g s (%.0f %%)" % (float(x), 100 * float(x) / ind)
        lines.append("| %s, r = %s | %s | %s | %.3g | %.3g (%.1f %%) | %s | "
                     "%s | %s |" % (
                         r["series"], r["refinements"], r["recovery"],
                         r["n_dofs"], float(r["contact_solve_s"]), ind,
                         100 * float(r["fraction"]), pc(r["correction_s"]),
                         pc(r["smoothing_s"]), pc(r["contributions_s"])))
    return "\n".join(lines)


# --------------------------------------------------------------- the parts

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
    path = EFF_CSV if exact else COST_CSV
    fields = EFF_FIELDS if exact else COST_FIELDS
    jobs = eff_jobs(args) if exact else cost_jobs(args)
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
                elif RUN_SECONDS[0] + pred > budget:
                    reason = "time budget (%.0f s used, %.0f s predicted, "\
                             "%.0f s allowed)" % (RUN_SECONDS[0], pred,
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
                load = wait_for_quiet(args.quiet_wait)
            row = run_one(exe, s, r, rec, exact, timeout, sub)
            row["load_before"] = load
            runs.append(row)
            if exact or row["status"] != "ok":
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


# -------------------------------------------------------------------- I/O

def fmt(v, f="%.4g"):
    if v is None or v == "":
        return ""
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        return f % v
    return str(v)


def write_csv(rows, path, fields):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields + ["command"],
                           extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: fmt(r.get(k, ""), "%.6g") for k in
                        fields + ["command"]})


TEXT = {"series", "scene", "cell_type", "recovery", "status", "message",
        "reference", "correction_solver", "version", "command"}


def read_csv(path):
    rows = []
    if not os.path.exists(path):
        return rows
    with open(path) as f:
        for r in csv.DictReader(f):
            for k, v in r.items():
                if k in TEXT or v in ("", None):
                    continue
                try:
                    r[k] = float(v)
                except ValueError:
                    pass
            for k in ("refinements", "subdivisions", "n_dofs",
                      "newton_iterations"):
                if r.get(k) not in ("", None):
                    r[k] = int(r[k])
            rows.append(r)
    return rows


def ok_rows(rows, series, recovery=None):
    return sorted((r for r in rows if r["series"] == series and
                   r["status"] == "ok" and
                   (recovery is None or r["recovery"] == recovery)),
                  key=lambda r: r["n_dofs"])


# ------------------------------------------------------------------ plots

def plot_cost(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    styles = {"blocks P1": ("C0", "^"), "blocks Q1": ("C1", "s"),
              "hertz Q1": ("C2", "o")}
    for s in COST_SERIES:
        for rec, ls in (("zz", "-"), ("spr", "--")):
            pts = ok_rows(rows, s["key"], rec)
            if not pts:
                continue
            c, m = styles.get(s["key"], ("k", "x"))
            ax.plot([r["n_dofs"] for r in pts],
                    [100 * r["fraction"] for r in pts], color=c, marker=m,
                    ls=ls, mfc="none" if rec == "spr" else c,
                    label="%s (%s)" % (s["key"], rec))
    ax.axhline(100 * TARGET_FRACTION, color="k", ls="--", lw=1,
               label="target ≤ 20 %")
    ax.set_xscale("log")
    ax.set_ylim(bottom=0)
    ax.set_xlabel("DoFs (both bodies)")
    ax.set_ylabel("indicator time / contact solve time [%]")
    ax.set_title("Error indicator cost (correction + recovery + "
                 "contributions)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def plot_effectivity(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = ["manufactured", "blocks", "punch", "hertz"]
    fig, axes = plt.subplots(1, 4, figsize=(15, 4.2), sharey=True)
    markers = {"zz": "o", "spr": "s"}
    colors = {}
    for i, s in enumerate(EFF_SERIES):
        colors[s["key"]] = "C%d" % i
    ymax = 1.5
    for ax, scene in zip(axes, scenes):
        ax.axhspan(BAND[0], BAND[1], color="green", alpha=0.12,
                   label="0.7–1.4")
        ax.axhline(1.0, color="k", lw=0.8)
        any_spr = False
        for s in EFF_SERIES:
            if s["scene"] != scene:
                continue
            for rec in ("zz", "spr"):
                pts = ok_rows(rows, s["key"], rec)
                if not pts:
                    continue
                any_spr = any_spr or rec == "spr"
                y = [r["effectivity"] for r in pts]
                ymax = max(ymax, max(y) * 1.1)
                ax.plot([r["n_dofs"] for r in pts], y, color=colors[s["key"]],
                        marker=markers[rec], ls="-" if rec == "zz" else "--",
                        mfc="none" if rec == "spr" else colors[s["key"]],
                        label="%s, %s" % (s["key"].replace(scene + " ", ""),
                                          rec))
        unavailable = [r for r in rows if r["scene"] == scene and
                       r["recovery"] == "spr" and
                       r["status"] == "unavailable"]
        if unavailable and not any_spr:
            ax.text(0.03, 0.03, "spr: not available in this executable",
                    transform=ax.transAxes, fontsize=8, color="gray")
        ax.set_xscale("log")
        ax.set_title(scene + ("" if scene == "manufactured" else
                              " (reference: +2 refinements)"), fontsize=10)
        ax.set_xlabel("DoFs (both bodies)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="upper left")
    axes[0].set_ylabel("effectivity ε / ε_exact")
    for ax in axes:
        ax.set_ylim(0.5, ymax)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


# ----------------------------------------------------------------- tables

def mesh_label(r):
    if r["scene"] == "hertz":
        return "graded, cms %g, r = %d" % (
            float(r.get("contact_mesh_size") or 0.1), r["refinements"])
    if r.get("subdivisions"):
        s = int(r["subdivisions"])
        return "%d×%d / %d×%d, r = %d" % (s, s, 2 * s, 2 * s,
                                          r["refinements"])
    return "r = %d" % r["refinements"]


def cost_table(rows):
    lines = ["| series | mesh | DoFs | Newton its | contact solve [s] | "
             "indicator [s] | **indicator / contact solve** | correction "
             "| correction solve | ε |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for s in COST_SERIES:
        for rec in ("zz", "spr"):
            for r in sorted((x for x in rows if x["series"] == s["key"] and
                             x["recovery"] == rec),
                            key=lambda x: float(x["n_dofs"] or 0)):
                if r["status"] != "ok":
                    lines.append("| %s (%s) | %s | %s | %s: %s | | | | | | |"
                                 % (s["key"], rec, mesh_label(r),
                                    r["n_dofs"] or "—", r["status"],
                                    r["message"]))
                    continue
                corr = "skipped" if r["correction_skipped"] == 1 else \
                    "%d nodes" % r["projected_nodes"]
                lines.append(
                    "| %s (%s) | %s | %d | %d | %.3g | %.3g | **%.1f %%** | "
                    "%s | %s | %.2f %% |" % (
                        s["key"], rec, mesh_label(r), r["n_dofs"],
                        r["newton_iterations"], r["contact_solve_s"],
                        r["indicator_s"], 100 * r["fraction"], corr,
                        r["correction_solver"] or "—",
                        100 * r["epsilon"]))
    return "\n".join(lines)


def eff_table(rows):
    lines = ["| series | mesh | recovery | DoFs | ε [%] | ε_exact [%] | "
             "**effectivity** | elements: mean ± std [min, max] | "
             "ε contact [%] | reference |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for s in EFF_SERIES:
        for rec in ("zz", "spr"):
            sel = sorted((x for x in rows if x["series"] == s["key"] and
                          x["recovery"] == rec),
                         key=lambda x: (x["refinements"]))
            for r in sel:
                if r["status"] != "ok":
                    lines.append("| %s | %s | %s | %s | %s | | | | | |" % (
                        s["key"], mesh_label(r), rec, r["n_dofs"] or "—",
                        r["status"] + (": " + r["message"] if
                                       r["status"] != "unavailable" else "")))
                    continue
                flag = "" if BAND[0] <= r["effectivity"] <= BAND[1] else " ⚠"
                lines.append(
                    "| %s | %s | %s | %d | %.3f | %.3f | **%.3f**%s | "
                    "%.2f ± %.2f [%.2f, %.2f] | %.3f | %s |" % (
                        s["key"], mesh_label(r), rec, r["n_dofs"],
                        100 * r["epsilon"], 100 * r["epsilon_exact"],
                        r["effectivity"], flag, r["elem_eff_mean"],
                        r["elem_eff_std"], r["elem_eff_min"],
                        r["elem_eff_max"], 100 * (r["epsilon_contact"] or 0),
                        r["reference"]))
    return "\n".join(lines)


# ------------------------------------------------------------------- main

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
    p.add_argument("--executable", "--exe", default=DEFAULT_EXE)
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
    p.add_argument("--plot-only", action="store_true")
    p.add_argument("--table", action="store_true")
    a = p.parse_args()
    recovery_given = any(x.startswith("--recovery") for x in sys.argv)
    a.recovery = [x.strip() for x in a.recovery.split(",") if x.strip()]
    for x in a.recovery:
        if x not in ("zz", "spr"):
            p.error("unknown recovery '%s' (zz, spr)" % x)

    if a.plot_only or a.table:
        cost, eff = read_csv(COST_CSV), read_csv(EFF_CSV)
        if a.plot_only:
            if cost:
                plot_cost(cost, COST_PNG)
            if eff:
                plot_effectivity(eff, EFF_PNG)
        if a.table:
            print(cost_table(cost))
            print()
            print(eff_table(eff))
            if os.path.exists(BREAKDOWN_CSV):
                print()
                print(breakdown_table(read_csv(BREAKDOWN_CSV)))
        return 0

    exe = os.path.abspath(a.executable)
    if not os.access(exe, os.X_OK):
        p.error("executable %s not found (build it, or --executable)" % exe)
    print("machine:", machine_info(), flush=True)
    print("executable:", exe, time.ctime(os.path.getmtime(exe)), flush=True)
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
            plot_cost(rows, COST_PNG)
            print(cost_table(rows))
        else:
            plot_effectivity(rows, EFF_PNG)
            print(eff_table(rows))
    print("total %.0f s (%.0f s in runs)" % (time.perf_counter() - start,
                                             RUN_SECONDS[0]), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
