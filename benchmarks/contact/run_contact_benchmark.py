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
parsed from the program's per-step log lines), peak memory.

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
  run_contact_benchmark.py --quick              small sizes only (smoke test)
  run_contact_benchmark.py --plot-only          re-plot from results.csv
  run_contact_benchmark.py --table              print the README table
Nested iteration (ae9a23c): --nested-levels N passes 'Contact/Nested
iteration levels=N' (0 = cold start; default: the program's default, 3);
rows carry start = nested / cold and the coarse levels from summary.json
(coarse_newton_by_level, coarse_time_s, ...). --series (e.g. hertz or
hertz:0,blocks:0.3) runs a subset, --no-elastic keeps the CSV's elastic
references, --append keeps rows of other series and of the other start.
--table also prints a cold-vs-nested comparison.
Options: --exe, --blocks-max-ref (7), --hertz-max-ref (4), --max-run-s (480:
skip a size whose predicted run time exceeds it), --budget-s (1800: total
run time, waits not counted), --retries (2: reruns of a run disturbed by
other processes), --quiet-wait (600 s),
--repeats (3, for runs shorter than --repeat-below-s = 5 s).

Only the Python standard library and matplotlib are used.
"""

import argparse
import csv
import datetime
import json
import math
import os
import platform
import re
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
DEFAULT_EXE = os.path.join(ROOT, "build", "coulomb-adapt")
DEFAULT_CSV = os.path.join(HERE, "results.csv")
DEFAULT_PNG = os.path.join(HERE, "contact_timings.png")
ELASTICITY_CSV = os.path.join(ROOT, "benchmarks", "elasticity", "results.csv")

SERIES = [("blocks", 0.0), ("blocks", 0.3), ("hertz", 0.0), ("hertz", 0.3)]
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

NEWTON_LINE = re.compile(
    r"^\s*Newton\s+(?P<k>\d+):.*\(assembly (?P<a>[0-9.eE+-]+) s, "
    r"solve (?P<s>[0-9.eE+-]+) s(?:, [^)]*)?\)\s*$")
SOLVED_LINE = re.compile(
    r"^\s*(?P<body>.+?): solved by (?P<method>.+?)"
    r"(?: \((?P<its>\d+) iterations\))? in (?P<t>[0-9.eE+-]+) s\s*$")

# Other processes may use at most this many CPU seconds per second of a run
# (plus an allowance) for the run to count as clean.
CLEAN_FRACTION = 0.1
CLEAN_ALLOWANCE_S = 0.05
# Growth of the run time with the DoFs, used to predict the next size.
TIME_EXPONENT = 1.5


# ---------------------------------------------------------------- helpers

def busy_seconds():
    """CPU seconds (all cores) spent non-idle since boot."""
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


QUIET_THRESHOLD = 0.3


def wait_for_quiet(threshold=QUIET_THRESHOLD, max_wait=600.0):
    """Waits until other processes use less than 'threshold' cores over
    3 s, at most 'max_wait' s; returns the last measurement."""
    start = time.perf_counter()
    load = busy_cores(3.0)
    announced = False
    while load > threshold and time.perf_counter() - start < max_wait:
        if not announced:
            print("    machine busy (%.2f cores); waiting up to %.0f s" % (
                load, max_wait), flush=True)
            announced = True
        time.sleep(5)
        load = busy_cores(3.0)
    return load


def num(x, fmt="%.6g"):
    if x is None or x == "" or (isinstance(x, float) and math.isnan(x)):
        return ""
    return fmt % x


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
            kb = int(f.readline().split()[1])
            mem = "%.1f GiB" % (kb / 2 ** 20)
    except (OSError, ValueError, IndexError):
        pass
    return "%d cores (nproc), %s, %s RAM, %s" % (
        os.cpu_count() or 0, cpu, mem, platform.platform())


# ------------------------------------------------------------ elastic curve

def loglog_interp(points, x):
    """Piecewise linear interpolation in log-log of sorted (x, y) points,
    linear extrapolation in log-log with the first / last segment."""
    if not points:
        return float("nan")
    if len(points) == 1:
        return points[0][1] * (x / points[0][0])
    lx = math.log(x)
    pts = [(math.log(a), math.log(b)) for a, b in points]
    if lx <= pts[0][0]:
        (x0, y0), (x1, y1) = pts[0], pts[1]
    elif lx >= pts[-1][0]:
        (x0, y0), (x1, y1) = pts[-2], pts[-1]
    else:
        for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
            if x0 <= lx <= x1:
                break
    return math.exp(y0 + (y1 - y0) * (lx - x0) / (x1 - x0))


def single_body_curve(path=ELASTICITY_CSV):
    """(n, t) of one direct elastic solve of one body, from the elasticity
    benchmark: 1 rank, direct, ok; median over repeats and both bodies."""
    samples = {}
    if not os.path.exists(path):
        return []
    with open(path) as f:
        for r in csv.DictReader(f):
            if r.get("solver") != "direct" or r.get("ranks") != "1" or \
                    r.get("status") != "ok":
                continue
            for b in ("1", "2"):
                try:
                    n = int(r["n_dofs_body" + b])
                    t = float(r["solve_body%s_s" % b])
                except (KeyError, ValueError):
                    continue
                if t > 0:
                    samples.setdefault(n, []).append(t)
    return sorted((n, statistics.median(ts)) for n, ts in samples.items())


# ------------------------------------------------------------------- runs

def base_args(exe, out_dir, refinements):
    return [exe,
            "-s", "Mesh/Global refinements=%d" % refinements,
            "-s", "Mesh/Cell type=quadrilateral",
            "-s", "Finite elements/Polynomial degree=1",
            "-s", "Finite elements/Plane model=plane strain",
            "-s", "Adaptation/Number of cycles=1",
            "-s", "Output/Write VTU=false",
            "-s", "Output/Output directory=" + out_dir]


def contact_args(exe, out_dir, scene, mu, refinements, sub=4,
                 nested_levels=None, linear_solver="direct"):
    args = base_args(exe, out_dir, refinements) + [
        "-s", "Scene/Name=" + scene,
        "-s", "Contact/Friction coefficient=%g" % mu,
        "-s", "Linear solver/Type=" + linear_solver,
        "-s", "Linear solver/Direct solver=Amesos_Mumps"]
    if nested_levels is not None:
        args += ["-s", "Contact/Nested iteration levels=%d" % nested_levels]
    if scene == "blocks":
        args += ["-s", "Scene/Blocks/Upper body subdivisions=%d, %d" % (
                     sub, sub),
                 "-s", "Scene/Blocks/Lower body subdivisions=%d, %d" % (
                     2 * sub, 2 * sub)]
        if mu == 0:
            args += ["-s", "Scene/Blocks/Hold centre line=true"]
    return args


def elastic_args(exe, out_dir, refinements, sub=4):
    """The blocks meshes (sub x sub and 2sub x 2sub quadrilaterals) in the
    manufactured scene: an elastic problem on the same mesh."""
    return base_args(exe, out_dir, refinements) + [
        "-s", "Scene/Name=manufactured",
        "-s", "Scene/Manufactured/Body 1 subdivisions=%d, %d" % (sub, sub),
        "-s", "Scene/Manufactured/Body 2 subdivisions=%d, %d" % (2 * sub,
                                                                 2 * sub),
        "-s", "Linear solver/Type=direct",
        "-s", "Linear solver/Direct solver=Amesos_Mumps"]


def estimated_dofs(scene, refinements, sub=4):
    if scene == "blocks":
        n1, n2 = sub * 2 ** refinements + 1, 2 * sub * 2 ** refinements + 1
        return 2 * (n1 * n1 + n2 * n2)
    return 9.0e3 * 4 ** refinements


ELASTIC_SCENE = "blocks-mesh (manufactured)"
RUN_SECONDS = [0.0]   # time spent in runs (waits for quiet not counted)


def execute(args, timeout):
    """Runs one process in its own session; returns (rc, stdout, stderr,
    wall, other_cpu_s). On timeout the process group is killed."""
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


def read_summary(out_dir):
    try:
        with open(os.path.join(out_dir, "summary.json")) as f:
            s = json.load(f)
        return s, s["cycles"][-1]
    except (OSError, ValueError, KeyError, IndexError):
        return None, None


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


def run_contact(exe, scene, mu, refinements, timeout, sub=4,
                nested_levels=None, linear_solver="direct"):
    out_dir = tempfile.mkdtemp(prefix="coulomb-contact-bench-")
    rc, out, err, wall, other = execute(
        contact_args(exe, out_dir, scene, mu, refinements, sub,
                     nested_levels, linear_solver), timeout)
    row = {k: "" for k in FIELDS}
    row.update(kind="contact", scene=scene, mu=mu, refinements=refinements,
               subdivisions=sub if scene == "blocks" else "",
               process_wall_s=wall, other_cpu_s=other,
               clean=int(other < CLEAN_FRACTION * wall + CLEAN_ALLOWANCE_S),
               start=start_mode(nested_levels),
               nested_levels_setting="default (3)" if nested_levels is None
               else nested_levels)
    steps = []
    for line in out.splitlines():
        m = NEWTON_LINE.match(line)
        if m:
            steps.append((float(m.group("a")), float(m.group("s"))))
    summary, cyc = read_summary(out_dir)
    if cyc is not None:
        bodies = cyc.get("bodies", [])
        row.update(
            n_dofs=cyc.get("n_dofs", ""),
            n_dofs_body1=bodies[0]["n_dofs"] if bodies else "",
            n_dofs_body2=bodies[1]["n_dofs"] if len(bodies) > 1 else "",
            converged=int(bool(cyc.get("converged"))),
            newton_iterations=cyc.get("newton_iterations", ""),
            active_nodes=cyc.get("active_nodes", ""),
            stick_nodes=cyc.get("stick_nodes", ""),
            slip_nodes=cyc.get("slip_nodes", ""),
            contact_solve_s=cyc.get("timings_s", {}).get("contact solve", ""),
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
    if steps:
        tot = [a + s for a, s in steps]
        row.update(step_mean_s=statistics.mean(tot),
                   step_assembly_mean_s=statistics.mean(a for a, _ in steps),
                   step_solve_mean_s=statistics.mean(s for _, s in steps),
                   step_min_s=min(tot), step_max_s=max(tot))
    if rc is None:
        row.update(status="timeout", message="killed after %g s" % timeout)
    elif rc != 0 or cyc is None:
        row.update(status="failed",
                   message=" ".join((err or out).strip().split())[-300:])
    else:
        row.update(status="ok")
    shutil.rmtree(out_dir, ignore_errors=True)
    return row


def run_elastic(exe, refinements, timeout, sub=4):
    out_dir = tempfile.mkdtemp(prefix="coulomb-contact-bench-el-")
    rc, out, err, wall, other = execute(
        elastic_args(exe, out_dir, refinements, sub), timeout)
    row = {k: "" for k in FIELDS}
    row.update(kind="elastic", scene=ELASTIC_SCENE, subdivisions=sub,
               refinements=refinements, process_wall_s=wall,
               other_cpu_s=other,
               clean=int(other < CLEAN_FRACTION * wall + CLEAN_ALLOWANCE_S))
    times = []
    for line in out.splitlines():
        m = SOLVED_LINE.match(line)
        if m:
            times.append(float(m.group("t")))
            row["linear_solver"] = m.group("method")
    summary, cyc = read_summary(out_dir)
    if cyc is not None:
        bodies = cyc.get("bodies", [])
        row.update(n_dofs=cyc.get("n_dofs", ""),
                   n_dofs_body1=bodies[0]["n_dofs"] if bodies else "",
                   n_dofs_body2=bodies[1]["n_dofs"] if len(bodies) > 1
                   else "",
                   cycle_wall_s=cyc.get("wall_time_s", ""),
                   peak_memory_MiB=cyc.get("peak_memory_MiB", ""),
                   version=summary.get("version", ""))
    if len(times) == 2:
        row.update(elastic_body1_s=times[0], elastic_body2_s=times[1],
                   elastic_solve_s=times[0] + times[1])
    if rc is None:
        row.update(status="timeout", message="killed after %g s" % timeout)
    elif rc != 0 or cyc is None or len(times) != 2:
        row.update(status="failed",
                   message=" ".join((err or out).strip().split())[-300:])
    else:
        row.update(status="ok")
    shutil.rmtree(out_dir, ignore_errors=True)
    return row


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
        wait_for_quiet(QUIET_THRESHOLD, quiet_wait)
        row = fn(*args)
        rows.append(row)
        if row["status"] != "ok" or row["clean"] == 1:
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


def fill_references(rows, curve):
    """Elastic references and ratios of the contact rows."""
    elastic = {(r["subdivisions"], r["refinements"]): r for r in rows
               if r["kind"] == "elastic" and r["status"] == "ok"}
    for r in rows:
        if r["kind"] != "contact" or r["status"] != "ok" or \
                r["n_dofs_body1"] in ("", None):
            continue
        n, n1, n2 = (float(r[k]) for k in
                     ("n_dofs", "n_dofs_body1", "n_dofs_body2"))
        interp = loglog_interp(curve, n1) + loglog_interp(curve, n2)
        r["elastic_interp_s"] = interp
        r["single_system_ref_s"] = loglog_interp(curve, n)
        el = elastic.get((r["subdivisions"], r["refinements"])) \
            if r["scene"] == "blocks" else None
        if el is not None and int(el["n_dofs"]) == int(n):
            r["elastic_ref_s"] = el["elastic_solve_s"]
            r["elastic_ref_source"] = "measured (manufactured, same cells)"
        else:
            r["elastic_ref_s"] = interp
            r["elastic_ref_source"] = "interpolated (elasticity/results.csv)"
        if r.get("contact_solve_s") not in ("", None):
            r["solve_over_elastic"] = r["contact_solve_s"] / \
                r["elastic_ref_s"]
        if r["step_mean_s"] not in ("", None):
            r["ratio_step_elastic"] = r["step_mean_s"] / r["elastic_ref_s"]
            r["ratio_step_single"] = (r["step_mean_s"] /
                                      r["single_system_ref_s"])


# -------------------------------------------------------------------- I/O

def write_csv(rows, path):
    def fmt(v):
        if isinstance(v, float):
            return "%.6g" % v
        return v
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        for r in rows:
            w.writerow({k: fmt(r.get(k, "")) for k in FIELDS})


def read_csv(path):
    rows = []
    with open(path) as f:
        for r in csv.DictReader(f):
            for k, v in r.items():
                if k in ("kind", "scene", "status", "elastic_ref_source",
                         "linear_solver", "version", "message", "start",
                         "nested_levels_setting", "nested_status",
                         "coarse_levels", "coarse_newton_by_level"):
                    continue
                try:
                    r[k] = float(v) if v not in ("", None) else ""
                except ValueError:
                    pass
            if r.get("subdivisions") in ("", None) and \
                    r["scene"] != "hertz":
                r["subdivisions"] = 4
            # rows of builds before nested iteration: cold start
            if r["kind"] == "contact" and not r.get("start"):
                r["start"] = "cold"
            if r["kind"] == "elastic":
                r["start"] = ""
            for k in ("subdivisions", "refinements", "n_dofs",
                      "n_dofs_body1", "n_dofs_body2", "newton_iterations"):
                if r.get(k) not in ("", None):
                    r[k] = int(r[k])
                else:
                    r[k] = ""
            rows.append(r)
    return rows


def label(scene, mu):
    return "%s, μ = %g" % (scene, mu)


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    fig, (ax1, ax3, ax2) = plt.subplots(1, 3, figsize=(15, 4.6))
    styles = {("blocks", 0.0): ("C0", "o"), ("blocks", 0.3): ("C1", "s"),
              ("hertz", 0.0): ("C2", "^"), ("hertz", 0.3): ("C3", "D")}
    for start in STARTS:
        ls, mfc = ("-", None) if start == "nested" else ("--", "none")
        for scene, mu in SERIES:
            pts = [r for r in sorted_rows(rows, "contact", scene, mu, start)
                   if r["status"] == "ok"]
            if not pts:
                continue
            c, m = styles[(scene, mu)]
            x = [r["n_dofs"] for r in pts]
            kw = dict(color=c, marker=m, ls=ls, label="%s, %s" % (
                label(scene, mu), start))
            if mfc:
                kw["mfc"] = mfc
            ax1.plot(x, [r["newton_iterations"] for r in pts], **kw)
            ax3.plot(x, [r["contact_solve_s"] for r in pts], **kw)
            ax2.plot(x, [r["ratio_step_elastic"] for r in pts], **kw)
    el = [r for r in sorted_rows(rows, "elastic") if r["status"] == "ok"]
    if el:
        ax3.plot([r["n_dofs"] for r in el],
                 [r["elastic_solve_s"] for r in el], color="k", ls=":",
                 marker=".", label="one elastic solve (blocks mesh)")
    ax1.axhline(10, color="k", ls="--", lw=1, label="target ≤ 10")
    ax1.set_xscale("log")
    ax1.set_xlabel("DoFs (both bodies)")
    ax1.set_ylabel("Newton iterations on the fine mesh")
    ax1.set_ylim(0, 14)
    ax1.set_title("Semismooth Newton iterations (fine mesh)", fontsize=10)
    ax1.grid(True, which="both", alpha=0.3)
    ax1.legend(fontsize=6.5, loc="upper left", ncol=2)
    ax3.set_xscale("log")
    ax3.set_yscale("log")
    ax3.set_xlabel("DoFs (both bodies)")
    ax3.set_ylabel("contact solve [s]")
    ax3.set_title("Contact solve (coarse levels + fine Newton)",
                  fontsize=10)
    ax3.grid(True, which="both", alpha=0.3)
    ax3.legend(fontsize=6.5, loc="upper left")
    ax2.axhline(2, color="k", ls="--", lw=1, label="target ≤ 2")
    ax2.set_xscale("log")
    ax2.set_yscale("log")
    ax2.set_ylim(0.25, 3.0)
    ax2.set_yticks([0.3, 0.5, 0.7, 1, 1.5, 2, 3])
    ax2.yaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    ax2.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax2.set_xlabel("DoFs (both bodies)")
    ax2.set_ylabel("time per Newton step / elastic solve")
    ax2.set_title("Fine Newton step (assembly + solve) / elastic solve",
                  fontsize=10)
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend(fontsize=7, loc="lower center")
    fig.tight_layout()
    fig.savefig(path, dpi=85)
    plt.close(fig)


def solver_comparison(direct_csv, amg_csv, png):
    """Direct (MUMPS, row-replacing system) against Krylov + AMG (the
    eliminated system) on the same meshes: a markdown table, and a plot
    of the fine Newton step's time and the Krylov iterations."""
    def key(r):
        return (r["scene"], r["mu"], r["subdivisions"] or 4, r["refinements"])
    direct = {key(r): r for r in read_csv(direct_csv) if r["status"] == "ok"}
    amg = {key(r): r for r in read_csv(amg_csv) if r["status"] == "ok"}
    common = sorted(set(direct) & set(amg),
                    key=lambda k: (k[0], k[1], direct[k]["n_dofs"]))
    lines = ["| scene | μ | mesh | DoFs | Newton its (direct / amg) | "
             "Krylov its (last step) | step direct [s] | step amg [s] | "
             "step direct / amg | contact solve direct / amg [s] | "
             "peak mem direct / amg [MiB] |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for k in common:
        d, g = direct[k], amg[k]
        lines.append("| %s | %g | %s | %d | %s / %s | %s | %s | %s | **%.2f** "
                     "| %s / %s | %.0f / %.0f |" % (
                         d["scene"], d["mu"], mesh_label(d), d["n_dofs"],
                         d["newton_iterations"], g["newton_iterations"],
                         g["linear_solver"], num(d["step_mean_s"], "%.3g"),
                         num(g["step_mean_s"], "%.3g"),
                         d["step_mean_s"] / g["step_mean_s"],
                         num(d["contact_solve_s"], "%.3g"),
                         num(g["contact_solve_s"], "%.3g"),
                         d["peak_memory_MiB"], g["peak_memory_MiB"]))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.3))
    styles = {("blocks", 0.0): ("C0", "o"), ("blocks", 0.3): ("C1", "s"),
              ("hertz", 0.0): ("C2", "^"), ("hertz", 0.3): ("C3", "D")}
    for scene, mu in SERIES:
        ks = [k for k in common if k[0] == scene and k[1] == mu]
        if not ks:
            continue
        c, m = styles[(scene, mu)]
        x = [direct[k]["n_dofs"] for k in ks]
        ax1.plot(x, [direct[k]["step_mean_s"] for k in ks], color=c,
                 marker=m, ls="--", mfc="none",
                 label="%s, direct" % label(scene, mu))
        ax1.plot(x, [amg[k]["step_mean_s"] for k in ks], color=c, marker=m,
                 label="%s, amg" % label(scene, mu))
        its = [int(amg[k]["linear_solver"].split(":")[-1]) for k in ks]
        ax2.plot(x, its, color=c, marker=m, label=label(scene, mu))
    for ax in (ax1, ax2):
        ax.set_xscale("log")
        ax.set_xlabel("DoFs (both bodies)")
        ax.grid(True, which="both", alpha=0.3)
    ax1.set_yscale("log")
    ax1.set_ylabel("time per fine Newton step [s]")
    ax1.set_title("Direct (dashed) and Krylov + AMG (solid)", fontsize=10)
    ax1.legend(fontsize=6.5)
    ax2.set_ylabel("CG / GMRES iterations (to 1e-12)")
    ax2.set_title("Krylov iterations of the last Newton step", fontsize=10)
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=85)
    plt.close(fig)
    return "\n".join(lines)


def mesh_label(r):
    if r["scene"] == "hertz":
        return "graded, r = %d" % r["refinements"]
    sub = r["subdivisions"] or 4
    return "%d×%d / %d×%d, r = %d" % (sub, sub, 2 * sub, 2 * sub,
                                       r["refinements"])


def sorted_rows(rows, kind, scene=None, mu=None, start=None):
    def dofs(r):
        return float(r["n_dofs"]) if r["n_dofs"] not in ("", None) else 0.
    return sorted((r for r in rows if r["kind"] == kind and
                   (scene is None or r["scene"] == scene) and
                   (mu is None or float(r["mu"]) == mu) and
                   (start is None or r.get("start") == start)), key=dofs)


STARTS = ("cold", "nested")


def table(rows):
    lines = [
        "| scene | μ | start | mesh | DoFs | fine Newton its | coarse its "
        "(coarse → fine) | coarse time [s] | contact solve [s] | "
        "step mean [s] (assembly + solve) | elastic solve [s] | "
        "step / elastic | step / one N-DoF system | contact solve / "
        "elastic | peak mem [MiB] |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for scene, mu in SERIES:
        for start in STARTS:
            for r in sorted_rows(rows, "contact", scene, mu, start):
                if r["status"] != "ok":
                    lines.append("| %s | %g | %s | %s | %s | %s |"
                                 " | | | | | | | | |" % (
                                     scene, mu, start, mesh_label(r),
                                     r["n_dofs"] or "—", r["status"] + (
                                         ": " + r["message"] if r["message"]
                                         else "")))
                    continue
                src = "" if r["elastic_ref_source"].startswith(
                    "measured") else " (i)"
                coarse = r.get("coarse_newton_by_level") or (
                    "– (off)" if start == "cold" else "– (skipped)")
                ctime = r.get("coarse_time_s")
                lines.append(
                    "| %s | %g | %s | %s | %d | %d | %s | %s | %.3g%s | "
                    "%.3g (%.2g + %.3g) | %.3g%s | **%.2f** | %.2f | "
                    "%.1f | %.0f |" % (
                        scene, mu, start, mesh_label(r), r["n_dofs"],
                        r["newton_iterations"], coarse,
                        "%.3g" % ctime if ctime not in ("", None, 0, 0.0)
                        else "–",
                        r["contact_solve_s"], dist(r), r["step_mean_s"],
                        r["step_assembly_mean_s"], r["step_solve_mean_s"],
                        r["elastic_ref_s"], src, r["ratio_step_elastic"],
                        r["ratio_step_single"], r["solve_over_elastic"],
                        r["peak_memory_MiB"]))
    return "\n".join(lines)


def dist(r):
    """Marks a run during which other processes used the CPU."""
    return "" if r.get("clean") in (1, 1.0, "1") else " †"


def compare_table(rows):
    """Cold start against nested iteration, per series and size (†: other
    processes used more than 10 % of a core during the run)."""
    lines = ["| series | DoFs | Newton its cold | nested: fine its | "
             "nested: coarse its (coarse → fine) | contact solve cold [s] | "
             "nested [s] (coarse part) | speed-up | step / elastic cold, "
             "nested |", "|---|---|---|---|---|---|---|---|---|"]
    for scene, mu in SERIES:
        cold = {r["n_dofs"]: r for r in sorted_rows(
            rows, "contact", scene, mu, "cold") if r["status"] == "ok"}
        nest = {r["n_dofs"]: r for r in sorted_rows(
            rows, "contact", scene, mu, "nested") if r["status"] == "ok"}
        for n in sorted(set(cold) | set(nest)):
            c, m = cold.get(n), nest.get(n)
            lines.append("| %s | %d | %s | %s | %s | %s | %s | %s | %s |" % (
                label(scene, mu), n,
                c["newton_iterations"] if c else "–",
                m["newton_iterations"] if m else "–",
                (m.get("coarse_newton_by_level") or "– (skipped)")
                if m else "–",
                "%.3g%s" % (c["contact_solve_s"], dist(c)) if c else "–",
                "%.3g (%.3g)%s" % (m["contact_solve_s"],
                                   m["coarse_time_s"] or 0, dist(m))
                if m else "–",
                "%.2f×" % (c["contact_solve_s"] / m["contact_solve_s"])
                if c and m else "–",
                ", ".join("%.2f" % r["ratio_step_elastic"] if r else "–"
                          for r in (c, m))))
    return "\n".join(lines)


def elastic_table(rows):
    lines = ["| mesh | DoFs | body 1 solve [s] | body 2 solve [s] | "
             "sum [s] | interpolated from elasticity/results.csv [s] |",
             "|---|---|---|---|---|---|"]
    curve = single_body_curve()
    for r in sorted_rows(rows, "elastic"):
        if r["status"] != "ok":
            lines.append("| %s | %s | %s | | | |" % (
                mesh_label(r), r["n_dofs"], r["status"] + (
                    ": " + r["message"] if r["message"] else "")))
            continue
        interp = loglog_interp(curve, r["n_dofs_body1"]) + \
            loglog_interp(curve, r["n_dofs_body2"])
        lines.append("| %s | %d | %.3g | %.3g | %.3g%s | %.3g |" % (
            mesh_label(r), r["n_dofs"], r["elastic_body1_s"],
            r["elastic_body2_s"], r["elastic_solve_s"], dist(r), interp))
    return "\n".join(lines)


def summary_table(rows):
    """Compact table: iterations and step ratio per series and size."""
    lines = ["| series | " + " | ".join(
        "%s" % m for m in ("DoFs", "Newton its (fine)",
                           "contact solve [s]", "step / elastic")) + " |",
        "|---|---|---|---|---|"]
    for scene, mu in SERIES:
        for start in STARTS:
            pts = [r for r in sorted_rows(rows, "contact", scene, mu, start)
                   if r["status"] == "ok"]
            if not pts:
                continue
            lines.append("| %s, μ = %g, %s | %s | %s | %s | %s |" % (
                scene, mu, start,
                ", ".join("%.3g" % r["n_dofs"] for r in pts),
                ", ".join("%d" % r["newton_iterations"] for r in pts),
                ", ".join("%.3g" % r["contact_solve_s"] for r in pts),
                ", ".join("%.2f" % r["ratio_step_elastic"] for r in pts)))
    return "\n".join(lines)


# ------------------------------------------------------------------- main

def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--exe", default=DEFAULT_EXE)
    p.add_argument("--csv", default=DEFAULT_CSV)
    p.add_argument("--png", default=DEFAULT_PNG)
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
    p.add_argument("--plot-only", action="store_true")
    p.add_argument("--table", action="store_true")
    p.add_argument("--solver-table", nargs=3,
                   metavar=("DIRECT_CSV", "AMG_CSV", "PNG"),
                   help="compare runs with --linear-solver direct and amg: "
                   "print a table, draw PNG, run nothing")
    a = p.parse_args()

    if a.solver_table:
        print(solver_comparison(*a.solver_table))
        return 0

    if a.plot_only or a.table:
        rows = read_csv(a.csv)
        if a.plot_only:
            fill_references(rows, single_body_curve())
            write_csv(rows, a.csv)
            plot(rows, a.png)
        if a.table:
            print(table(rows))
            print()
            print(elastic_table(rows))
            print()
            print(summary_table(rows))
            print()
            print(compare_table(rows))
        return 0

    if a.quick:
        a.blocks_max_ref, a.hertz_max_ref, extensions = 3, 1, []
    else:
        extensions = BLOCKS_EXTENSIONS
    exe = os.path.abspath(a.exe)
    exe_mtime = os.path.getmtime(exe)
    print("machine:", machine_info(), flush=True)
    print("executable:", exe, time.ctime(exe_mtime), flush=True)
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
        for r in read_csv(a.csv):
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
            elif RUN_SECONDS[0] + pred > a.budget_s:
                reason = "time budget (%.0f s used, %.0f s predicted)" % (
                    RUN_SECONDS[0], pred)
            if reason:
                print("skip %s: %s" % (what, reason), flush=True)
                rows.append(dict({k: "" for k in FIELDS}, kind=kind,
                                 scene=scene, mu=mu, subdivisions=sub,
                                 refinements=r, n_dofs=int(est(job)),
                                 status="skipped", message=reason,
                                 start=job_start))
                continue
        load = wait_for_quiet(max_wait=a.quiet_wait)
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
        fill_references(rows, single_body_curve())
        write_csv(rows, a.csv)
    fill_references(rows, single_body_curve())
    write_csv(rows, a.csv)
    plot(rows, a.png)
    print("total %.0f s (%.0f s in runs); wrote %s and %s" % (
        time.perf_counter() - start, RUN_SECONDS[0], a.csv, a.png))
    print(table(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
