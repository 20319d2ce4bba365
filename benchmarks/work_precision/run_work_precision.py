#!/usr/bin/python3
"""Work-precision benchmark of coulomb-adapt: how many DoFs and how much
wall time each mesh strategy needs to reach a prescribed estimated error
epsilon_0, on the scenes blocks, hertz and punch.

Every run is one process (1 MPI rank, no mpirun, OMP_NUM_THREADS=1) with
`Output/Write VTU = false`; each cycle of its summary.json becomes one row
of results.csv. Strategies (Adaptation/Strategy):

  uniform   every cell refined once per cycle, Target error = 0, until the
            first cycle with at least --uniform-max-dofs (scene dependent)
  refine    quadrilaterals (p4est, hanging nodes), criteria 'size ratio'
            (r_E of theory.md section 4), 'optimize', 'fixed fraction'
  remesh    triangles, gmsh with the size field h*_E = r_E h_E

Adaptive runs stop at the first cycle with epsilon <= epsilon_0 ('Target
error', in percent); all their cycles are recorded.

Parts (--part):

  blocks  prm/blocks.prm, mu = 0.3, upper/lower subdivisions 3 x 3 / 6 x 7
          (408 P1 triangles = the seed's mesh; the Q1 runs start from the
          same vertices: Global refinements = 1, 204 quadrilaterals; both
          488 DoFs). epsilon_0 = 1 %. uniform P1/Q1 up to 4e5 DoFs, remesh
          P1, refine Q1 (size ratio, optimize, fixed fraction); degree 2
          (uniform P2, remesh P2, refine Q2 size ratio); target sweeps
          (remesh P1 and refine Q1 size ratio with epsilon_0 = 3, 2, 1.5,
          0.7, 0.5 %) whose final cycles give the slope of the adaptive
          work-precision curve.
  warm    the adaptive blocks runs (and uniform P1/Q1 up to 1e5 DoFs) with
          `Adaptation/Warm start = false`; compared with the warm-started
          runs of part blocks (total Newton iterations).
  hertz   prm/hertz.prm with Scene/Hertz/Contact mesh size = 0.8 (a coarse,
          mildly graded start: 802 P1 / 1060 Q1 DoFs), epsilon_0 = 2 %;
          uniform P1/Q1 up to 1e5 DoFs, remesh P1, refine Q1 (size ratio,
          optimize); and uniform Q1 on the scene's default graded mesh
          (Contact mesh size = 0.1).
  punch   prm/punch.prm, epsilon_0 = 2 %; uniform P1/Q1 up to 1e5 DoFs,
          remesh P1, refine Q1 (size ratio, optimize).
  exact   blocks, `Error indicator/Compute exact error = true`: epsilon_exact
          against a reference solution. Adaptive strategies use ONE
          reference, `Reference refinements` uniform refinements finer than
          the initial mesh; here R = 4 from the 488-DoF initial mesh, i.e.
          the uniform level-4 mesh (105,668 DoFs). The uniform points are
          one-cycle runs with Global refinements g and R = 4 - g (P1) or
          5 - g (Q1, which starts at g = 1), so that every epsilon_exact
          of a cell type is measured against the same reference mesh.
          The remesh points come from runs with epsilon_0 = 2, 1.5 and
          1.25 % (at 1 % the first remeshed cycle has ~2e4 cells and the
          exact-error quadrature, 4^R sub-cells per cell, would need ~5 GB).
  all     blocks, warm, hertz, punch, exact (default).

Wall time: per cycle wall_time_s - timings_s['exact error'] (the cycle's
setup, adaptation/remeshing, assembly, contact solve and indicator); the
cumulative time of a run sums it over the cycles up to that one. The
process wall time (MPI and library start-up, ~0.5 s) is recorded per run
but not in the cumulative time.

Timing hygiene: before each run the script waits (at most --quiet-wait s)
until other processes use less than 0.3 cores, and it measures the CPU time
other processes used during the run (other_cpu_s). Runs shorter than
--repeat-below s (10) are done --repeats (3) times and the run with the
median total time is kept (exact part: once). A run whose resident memory
exceeds --max-rss-mb (5000) or whose wall time exceeds --max-run-s (600)
is killed and recorded as 'killed'.

Usage:
  run_work_precision.py --executable /work/wp-bin/coulomb-adapt
  run_work_precision.py --part blocks --executable EXE
  run_work_precision.py --resume         run only what results.csv lacks
  run_work_precision.py --quick          small targets only (smoke test)
  run_work_precision.py --plot-only      re-plot from results.csv
  run_work_precision.py --table          print the README tables
Options: --executable (default /work/main/build/coulomb-adapt; when
libcoulomb_adapt.so lies next to it, its directory is put on
LD_LIBRARY_PATH), --append (keep the rows of the other parts in
results.csv; default), --fresh (start a new results.csv).

Only the Python standard library, numpy and matplotlib are used.
"""

import argparse
import csv
import json
import math
import os
import platform
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
CSV_PATH = os.path.join(HERE, "results.csv")
QUIET_THRESHOLD = 0.3

SCENE_TARGET = {"blocks": 1.0, "hertz": 2.0, "punch": 2.0}
BLOCKS_MESH = ["Scene/Blocks/Upper body subdivisions=3, 3",
               "Scene/Blocks/Lower body subdivisions=6, 7"]
HERTZ_COARSE = ["Scene/Hertz/Contact mesh size=0.8"]
HERTZ_GRADED = ["Scene/Hertz/Contact mesh size=0.1"]


# ------------------------------------------------------------------ cases
# A case is one run of the program. 'series' names the line of the plots;
# role: main (a line of the work-precision plots), sweep (only its last
# cycle is a point of the target sweep), warm (warm start off), exact.

def case(part, scene, series, strategy, cell, degree=1, criterion="",
         target=0.0, refs=0, max_dofs=2e6, cycles=40, warm=True, exact_r=None,
         extra=(), role="main"):
    prm = {"blocks": "blocks.prm", "hertz": "hertz.prm",
           "punch": "punch.prm"}[scene]
    base = list(BLOCKS_MESH) if scene == "blocks" else []
    run = "%s/%s%s%s%s" % (
        part, series, "" if role != "sweep" else " eps0=%g" % target,
        "" if warm else " (no warm start)",
        "" if exact_r is None else " g=%d R=%d" % (refs, exact_r))
    return dict(part=part, run=run, scene=scene, series=series, prm=prm,
                strategy=strategy, cell=cell, degree=degree,
                criterion=criterion if strategy == "refine" else "",
                target=target, refs=refs, max_dofs=max_dofs, cycles=cycles,
                warm=warm, exact_r=exact_r, extra=base + list(extra),
                role=role)


def blocks_cases(quick):
    big = 3e4 if quick else 4e5
    c = [case("blocks", "blocks", "uniform P1", "uniform", "triangle",
              max_dofs=big),
         case("blocks", "blocks", "uniform Q1", "uniform", "quadrilateral",
              refs=1, max_dofs=big),
         case("blocks", "blocks", "remesh P1", "remesh", "triangle",
              target=1),
         case("blocks", "blocks", "refine Q1 (size ratio)", "refine",
              "quadrilateral", criterion="size ratio", target=1, refs=1),
         case("blocks", "blocks", "refine Q1 (optimize)", "refine",
              "quadrilateral", criterion="optimize", target=1, refs=1),
         case("blocks", "blocks", "refine Q1 (fixed fraction)", "refine",
              "quadrilateral", criterion="fixed fraction", target=1, refs=1),
         case("blocks", "blocks", "uniform P2", "uniform", "triangle",
              degree=2, max_dofs=3e4 if quick else 1e5),
         case("blocks", "blocks", "remesh P2", "remesh", "triangle",
              degree=2, target=1),
         case("blocks", "blocks", "refine Q2 (size ratio)", "refine",
              "quadrilateral", degree=2, criterion="size ratio", target=1,
              refs=1)]
    sweep = [3, 2] if quick else [3, 2, 1.5, 0.7, 0.5]
    for t in sweep:
        c.append(case("blocks", "blocks", "remesh P1", "remesh", "triangle",
                      target=t, role="sweep"))
        c.append(case("blocks", "blocks", "refine Q1 (size ratio)", "refine",
                      "quadrilateral", criterion="size ratio", target=t,
                      refs=1, role="sweep"))
    return c


def warm_cases(quick):
    c = []
    for x in blocks_cases(quick):
        if x["role"] != "main" or x["degree"] != 1:
            continue
        y = dict(x)
        y = case("warm", x["scene"], x["series"], x["strategy"], x["cell"],
                 x["degree"], x["criterion"], x["target"], x["refs"],
                 1e4 if quick else (1e5 if x["strategy"] == "uniform"
                                    else x["max_dofs"]),
                 x["cycles"], False, None, x["extra"][len(BLOCKS_MESH):],
                 "warm")
        c.append(y)
    return c


def scene_cases(scene, quick):
    t = SCENE_TARGET[scene]
    big = 1.5e4 if quick else 1e5
    mesh = HERTZ_COARSE if scene == "hertz" else []
    tq = 4 if quick else t
    c = [case(scene, scene, "uniform P1", "uniform", "triangle",
              max_dofs=big, extra=mesh),
         case(scene, scene, "uniform Q1", "uniform", "quadrilateral",
              max_dofs=big, extra=mesh),
         case(scene, scene, "remesh P1", "remesh", "triangle", target=tq,
              extra=mesh),
         case(scene, scene, "refine Q1 (size ratio)", "refine",
              "quadrilateral", criterion="size ratio", target=tq,
              extra=mesh),
         case(scene, scene, "refine Q1 (optimize)", "refine",
              "quadrilateral", criterion="optimize", target=tq, extra=mesh)]
    if scene == "hertz" and not quick:
        c.append(case(scene, scene, "uniform Q1 (graded mesh)", "uniform",
                      "quadrilateral", max_dofs=big, extra=HERTZ_GRADED))
    return c


def exact_cases(quick):
    R = 2 if quick else 4
    c = []
    # uniform: one cycle each, reference = level R (P1) / R + 1 (Q1)
    for g in range(0, R):
        c.append(case("exact", "blocks", "uniform P1", "uniform", "triangle",
                      refs=g, cycles=1, exact_r=R - g, role="exact"))
    for g in range(1, R + 1):
        c.append(case("exact", "blocks", "uniform Q1", "uniform",
                      "quadrilateral", refs=g, cycles=1, exact_r=R + 1 - g,
                      role="exact"))
    for t in ([3] if quick else [2, 1.5, 1.25]):
        x = case("exact", "blocks", "remesh P1", "remesh", "triangle",
                 target=t, exact_r=R, role="exact")
        x["run"] += " eps0=%g" % t
        c.append(x)
    for crit in ("size ratio", "optimize"):
        c.append(case("exact", "blocks", "refine Q1 (%s)" % crit, "refine",
                      "quadrilateral", criterion=crit,
                      target=3 if quick else 1, refs=1, exact_r=R,
                      role="exact"))
    return c


def all_cases(part, quick):
    parts = ["blocks", "warm", "hertz", "punch", "exact"] \
        if part == "all" else [part]
    out = []
    for p in parts:
        if p == "blocks":
            out += blocks_cases(quick)
        elif p == "warm":
            out += warm_cases(quick)
        elif p == "exact":
            out += exact_cases(quick)
        else:
            out += scene_cases(p, quick)
    return out


# ---------------------------------------------------------------- machine

def busy_seconds():
    with open("/proc/stat") as f:
        v = [int(x) for x in f.readline().split()[1:]]
    busy = v[0] + v[1] + v[2] + v[5] + v[6] + (v[7] if len(v) > 7 else 0)
    return busy / os.sysconf("SC_CLK_TCK")


def busy_cores(window=1.0):
    b0, t0 = busy_seconds(), time.perf_counter()
    time.sleep(window)
    return (busy_seconds() - b0) / (time.perf_counter() - t0)


def wait_for_quiet(max_wait):
    start = time.perf_counter()
    load = busy_cores(1.0)
    announced = False
    while load > QUIET_THRESHOLD and time.perf_counter() - start < max_wait:
        if not announced:
            print("    machine busy (%.2f cores); waiting up to %.0f s" % (
                load, max_wait), flush=True)
            announced = True
        time.sleep(3)
        load = busy_cores(1.0)
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


def rss_mb(pid):
    """Resident memory of pid and its children (MiB)."""
    total = 0
    pids = [pid]
    try:
        with open("/proc/%d/task/%d/children" % (pid, pid)) as f:
            pids += [int(x) for x in f.read().split()]
    except OSError:
        pass
    for p in pids:
        try:
            with open("/proc/%d/status" % p) as f:
                for line in f:
                    if line.startswith("VmRSS:"):
                        total += int(line.split()[1])
        except OSError:
            pass
    return total / 1024.0


# ------------------------------------------------------------------- runs

RUN_SECONDS = [0.0]


def execute(args, env, timeout, max_rss):
    """Run; returns rc (None if killed), output, wall, other cpu, peak RSS,
    kill reason."""
    cpu0 = children_cpu()
    busy0 = busy_seconds()
    start = time.perf_counter()
    with tempfile.TemporaryFile("w+") as log:
        proc = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT,
                                text=True, env=env, start_new_session=True)
        peak, reason = 0.0, ""
        while proc.poll() is None:
            time.sleep(0.2)
            m = rss_mb(proc.pid)
            peak = max(peak, m)
            if m > max_rss:
                reason = "resident memory %.0f MiB > %.0f MiB" % (m, max_rss)
            elif time.perf_counter() - start > timeout:
                reason = "wall time > %.0f s" % timeout
            if reason:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
                break
        wall = time.perf_counter() - start
        log.seek(0)
        out = log.read()
    RUN_SECONDS[0] += wall
    other = (busy_seconds() - busy0) - (children_cpu() - cpu0)
    rc = None if reason else proc.returncode
    return rc, out, wall, max(0.0, other), peak, reason


def children_cpu():
    import resource
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def settings(c, out_dir):
    sets = ["Scene/Name=" + c["scene"]] + c["extra"] + [
        "Mesh/Cell type=" + c["cell"],
        "Mesh/Global refinements=%d" % c["refs"],
        "Finite elements/Polynomial degree=%d" % c["degree"],
        "Adaptation/Strategy=" + c["strategy"],
        "Adaptation/Target error=%g" % c["target"],
        "Adaptation/Number of cycles=%d" % c["cycles"],
        "Adaptation/Maximum number of DoFs=%g" % c["max_dofs"],
        "Adaptation/Warm start=" + ("true" if c["warm"] else "false")]
    if c["strategy"] == "refine":
        sets.append("Adaptation/Refinement criterion=" + c["criterion"])
    sets.append("Error indicator/Compute exact error=" + (
        "false" if c["exact_r"] is None else "true"))
    if c["exact_r"] is not None:
        sets.append("Error indicator/Reference refinements=%d" % c["exact_r"])
    sets += ["Output/Write VTU=false", "Output/Output directory=" + out_dir]
    return sets


def command(exe, c, out_dir):
    args = [exe, os.path.join(PRM, c["prm"])]
    for s in settings(c, out_dir):
        args += ["-s", s]
    return args


def shell_command(c):
    """The command line of a run, for the README (relative paths)."""
    out = ["build/coulomb-adapt", "prm/" + c["prm"]]
    for s in settings(c, "/tmp/run"):
        out += ["-s", "'%s'" % s]
    return " ".join(out)


def environment(exe):
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    d = os.path.dirname(exe)
    if os.path.exists(os.path.join(d, "libcoulomb_adapt.so")):
        env["LD_LIBRARY_PATH"] = d + (":" + env["LD_LIBRARY_PATH"] if
                                      env.get("LD_LIBRARY_PATH") else "")
    return env


def run_once(exe, c, args):
    out_dir = tempfile.mkdtemp(prefix="coulomb-wp-bench-")
    load = "" if c["part"] == "exact" else wait_for_quiet(args.quiet_wait)
    rc, out, wall, other, peak, reason = execute(
        command(exe, c, out_dir), environment(exe), args.max_run_s,
        args.max_rss_mb)
    summary = None
    try:
        with open(os.path.join(out_dir, "summary.json")) as f:
            summary = json.load(f)
    except (OSError, ValueError):
        pass
    shutil.rmtree(out_dir, ignore_errors=True)
    info = dict(process_wall_s=wall, other_cpu_s=other, load_before=load,
                peak_rss_MiB=peak)
    if reason:
        info.update(status="killed", message=reason)
    elif rc != 0:
        info.update(status="failed",
                    message=" ".join(out.strip().split())[-300:])
    elif not summary or not summary.get("cycles"):
        info.update(status="failed", message="no cycle in summary.json")
    else:
        info.update(status="ok", message="")
    return summary, info


def rows_of(c, summary, info, repeats):
    base = dict(part=c["part"], run=c["run"], role=c["role"],
                scene=c["scene"], series=c["series"],
                strategy=c["strategy"], cell_type=c["cell"],
                degree=c["degree"], criterion=c["criterion"],
                target_pct=c["target"], warm_start_param=int(c["warm"]),
                reference_refinements=""
                if c["exact_r"] is None else c["exact_r"],
                repeats=repeats, command=shell_command(c))
    base.update(info)
    if not summary or not summary.get("cycles"):
        return [dict(base, cycle="")]
    base["stop_reason"] = summary.get("stop_reason", "")
    base["version"] = summary.get("version", "")
    rows, cum = [], 0.0
    for cyc in summary["cycles"]:
        t = cyc.get("timings_s", {})
        ex = t.get("exact error", 0.0)
        wall = cyc.get("wall_time_s", float("nan")) - ex
        cum += wall
        bodies = cyc.get("bodies", [])
        ad = cyc.get("adaptation", {}) or {}
        cells = [b.get("n_cells", 0) for b in bodies]
        rows.append(dict(
            base, cycle=cyc.get("cycle", len(rows)),
            n_dofs=cyc.get("n_dofs", ""), n_cells=sum(cells),
            n_cells_1=cells[0] if cells else "",
            n_cells_2=cells[1] if len(cells) > 1 else "",
            epsilon=cyc.get("epsilon", ""),
            epsilon_contact=cyc.get("epsilon_contact", ""),
            epsilon_exact=cyc.get("epsilon_exact", ""),
            effectivity=cyc.get("effectivity", ""),
            cycle_wall_s=wall, cumulative_wall_s=cum,
            exact_error_s=t.get("exact error", ""),
            contact_solve_s=t.get("contact solve", ""),
            adapt_mesh_s=t.get("adapt mesh", ""),
            newton_iterations=cyc.get("newton_iterations", ""),
            warm_start=int(bool(cyc.get("warm_start")))
            if "warm_start" in cyc else "",
            predicted_n_cells=ad.get("predicted_n_cells", ""),
            obtained_n_cells=ad.get("obtained_n_cells", ""),
            peak_memory_MiB=cyc.get("peak_memory_MiB", "")))
    return rows


def run_case(exe, c, args):
    runs = []
    while True:
        summary, info = run_once(exe, c, args)
        runs.append((summary, info))
        if info["status"] != "ok" or c["part"] == "exact":
            break
        if info["process_wall_s"] >= args.repeat_below or \
                len(runs) >= args.repeats:
            break
    ok = [r for r in runs if r[1]["status"] == "ok"]
    if not ok:
        return rows_of(c, runs[-1][0], runs[-1][1], len(runs))

    def total(r):
        return sum(x.get("wall_time_s", 0) - x.get("timings_s", {}).get(
            "exact error", 0) for x in r[0]["cycles"])
    ok.sort(key=total)
    summary, info = ok[len(ok) // 2]
    info = dict(info, other_cpu_s=max(r[1]["other_cpu_s"] for r in ok))
    return rows_of(c, summary, info, len(runs))


# -------------------------------------------------------------------- I/O

FIELDS = [
    "part", "run", "role", "scene", "series", "strategy", "cell_type",
    "degree", "criterion", "target_pct", "warm_start_param",
    "reference_refinements", "cycle", "n_dofs", "n_cells", "n_cells_1",
    "n_cells_2", "epsilon", "epsilon_contact", "epsilon_exact",
    "effectivity", "cycle_wall_s", "cumulative_wall_s", "exact_error_s",
    "contact_solve_s", "adapt_mesh_s", "newton_iterations", "warm_start",
    "predicted_n_cells", "obtained_n_cells", "stop_reason", "status",
    "message", "process_wall_s", "repeats", "load_before", "other_cpu_s",
    "peak_rss_MiB", "peak_memory_MiB", "version", "command",
]
TEXT = {"part", "run", "role", "scene", "series", "strategy", "cell_type",
        "criterion", "stop_reason", "status", "message", "version",
        "command"}
INTS = {"degree", "cycle", "n_dofs", "n_cells", "n_cells_1", "n_cells_2",
        "newton_iterations", "warm_start", "warm_start_param",
        "reference_refinements", "repeats"}


def fmt(v, f="%.6g"):
    if v is None or v == "":
        return ""
    if isinstance(v, float):
        return "nan" if math.isnan(v) else f % v
    return str(v)


def write_csv(rows, path=CSV_PATH):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: fmt(r.get(k, "")) for k in FIELDS})


def read_csv(path=CSV_PATH):
    rows = []
    if not os.path.exists(path):
        return rows
    with open(path) as f:
        for r in csv.DictReader(f):
            for k, v in r.items():
                if k in TEXT or v in ("", None):
                    continue
                try:
                    r[k] = int(float(v)) if k in INTS else float(v)
                except ValueError:
                    pass
            rows.append(r)
    return rows


def runs_of(rows):
    """{run: [cycle rows sorted by cycle]} for the ok runs."""
    out = {}
    for r in rows:
        if r["status"] == "ok" and r["cycle"] != "":
            out.setdefault(r["run"], []).append(r)
    for v in out.values():
        v.sort(key=lambda r: r["cycle"])
    return out


# --------------------------------------------------------------- analysis

def fit_rate(points):
    """eps ~ C N^-r by least squares in log-log: returns r (or None)."""
    pts = [(math.log(n), math.log(e)) for n, e in points if n > 0 and e > 0]
    if len(pts) < 2:
        return None
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    if sxx == 0:
        return None
    return -sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx


def fit_power(points):
    """y = C x^s: returns (C, s)."""
    pts = [(math.log(x), math.log(y)) for x, y in points if x > 0 and y > 0]
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    s = sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx
    return math.exp(my - s * mx), s


def reach(cycles, target_pct):
    """Measured cost of reaching epsilon <= target: the first such cycle."""
    newton = 0
    nmax = 0
    for r in cycles:
        newton += r["newton_iterations"] or 0
        nmax = max(nmax, r["n_dofs"])
        if r["epsilon"] * 100 <= target_pct + 1e-12:
            return dict(measured=True, n_dofs=r["n_dofs"], max_dofs=nmax,
                        cum_s=r["cumulative_wall_s"], cycle=r["cycle"],
                        epsilon=r["epsilon"], newton=newton,
                        process_s=r["process_wall_s"])
    return None


def extrapolate_uniform(cycles, target_pct):
    """Uniform refinement that did not reach the target: continue the
    measured last 3 points. Rate r from eps(N) of the last 3 cycles; cycle
    time ~ N^s from the last 3 cycle times; the DoFs grow by the ratio of
    the last two cycles. Returns the first extrapolated cycle below the
    target, and the continuous N at which the fit crosses it."""
    last = cycles[-3:]
    r = fit_rate([(x["n_dofs"], x["epsilon"]) for x in last])
    c_t, s_t = fit_power([(x["n_dofs"], x["cycle_wall_s"]) for x in last])
    n, e = last[-1]["n_dofs"], last[-1]["epsilon"]
    cum = last[-1]["cumulative_wall_s"]
    grow = last[-1]["n_dofs"] / last[-2]["n_dofs"]
    n_cont = n * (e * 100 / target_pct) ** (1 / r) if r and r > 0 else None
    cum_cont = None
    if n_cont:
        cum_cont = cum
        m = n
        while m * grow <= n_cont:
            m *= grow
            cum_cont += c_t * m ** s_t
        cum_cont += c_t * n_cont ** s_t
    k = 0
    while e * 100 > target_pct and k < 10 and r and r > 0:
        n *= grow
        e *= grow ** (-r)
        cum += c_t * n ** s_t
        k += 1
    return dict(measured=False, n_dofs=n, cum_s=cum, epsilon=e, rate=r,
                time_exponent=s_t, n_continuous=n_cont,
                cum_continuous=cum_cont, extra_cycles=k,
                max_dofs=n)


def summary_numbers(rows):
    """Per scene and series of the timed parts: reach, rates."""
    runs = runs_of(rows)
    res = {}
    for run, cyc in runs.items():
        r0 = cyc[0]
        if r0["part"] not in ("blocks", "hertz", "punch") or \
                r0["role"] != "main":
            continue
        t = SCENE_TARGET[r0["scene"]]
        info = dict(series=r0["series"], scene=r0["scene"], cycles=cyc,
                    strategy=r0["strategy"], cell=r0["cell_type"],
                    degree=r0["degree"], run=run, command=r0["command"],
                    stop=r0["stop_reason"],
                    total_newton=sum(x["newton_iterations"] for x in cyc),
                    process_s=r0["process_wall_s"])
        info["reach"] = reach(cyc, t)
        if r0["strategy"] == "uniform":
            info["rate_last3"] = fit_rate(
                [(x["n_dofs"], x["epsilon"]) for x in cyc[-3:]])
            info["rate_all"] = fit_rate(
                [(x["n_dofs"], x["epsilon"]) for x in cyc])
            if info["reach"] is None:
                info["reach"] = extrapolate_uniform(cyc, t)
            else:
                # continuous crossing on the measured points around it
                k = [x["cycle"] for x in cyc].index(info["reach"]["cycle"])
                if k > 0:
                    # log-log interpolation between the last cycle above
                    # and the first below the target: the DoFs where the
                    # measured curve crosses epsilon_0, and the cumulative
                    # time there (what a uniform sequence stopping exactly
                    # at epsilon_0 would cost)
                    a, b = cyc[k - 1], cyc[k]
                    rr = fit_rate([(a["n_dofs"], a["epsilon"]),
                                   (b["n_dofs"], b["epsilon"])])
                    nc = a["n_dofs"] * (a["epsilon"] * 100 / t) ** (1 / rr)
                    w = math.log(nc / a["n_dofs"]) / math.log(
                        b["n_dofs"] / a["n_dofs"])
                    info["reach"]["n_continuous"] = nc
                    info["reach"]["cum_continuous"] = math.exp(
                        (1 - w) * math.log(a["cumulative_wall_s"]) +
                        w * math.log(b["cumulative_wall_s"]))
        else:
            info["rate_all"] = fit_rate(
                [(x["n_dofs"], x["epsilon"]) for x in cyc])
            info["rate_after0"] = fit_rate(
                [(x["n_dofs"], x["epsilon"]) for x in cyc[1:]])
        res[(r0["scene"], r0["series"])] = info
    # target sweeps: final cycle of each run (with the main run's)
    sweeps = {}
    for run, cyc in runs.items():
        r0 = cyc[0]
        if r0["part"] == "blocks" and r0["role"] in ("sweep", "main") and \
                r0["strategy"] != "uniform" and r0["degree"] == 1:
            sweeps.setdefault(r0["series"], []).append(
                (r0["target_pct"], cyc[-1]["n_dofs"], cyc[-1]["epsilon"],
                 max(x["n_dofs"] for x in cyc),
                 cyc[-1]["cumulative_wall_s"]))
    for k in sweeps:
        sweeps[k].sort()
    return res, sweeps


def uniform_of(res, scene, cell, degree=1):
    for (s, series), info in res.items():
        if s == scene and info["strategy"] == "uniform" and \
                info["cell"] == cell and info["degree"] == degree and \
                "graded" not in series:
            return info
    return None


# ------------------------------------------------------------------ plots

STYLE = {
    "uniform P1": ("C0", "v", "-"), "uniform Q1": ("C1", "^", "-"),
    "uniform P2": ("C7", "v", ":"),
    "uniform Q1 (graded mesh)": ("C8", "<", "-"),
    "remesh P1": ("C2", "o", "-"), "remesh P2": ("C2", "o", ":"),
    "refine Q1 (size ratio)": ("C3", "s", "-"),
    "refine Q2 (size ratio)": ("C3", "s", ":"),
    "refine Q1 (optimize)": ("C4", "D", "-"),
    "refine Q1 (fixed fraction)": ("C5", "P", "-"),
}


def slope_line(ax, xs, ys, rate=0.5, label="N^-1/2"):
    x0, x1 = min(xs), max(xs)
    y0 = max(ys) * 0.55
    ax.plot([x0, x1], [y0, y0 * (x1 / x0) ** (-rate)], "k--", lw=1,
            label=label)


def plot_scene(rows, scene, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    runs = runs_of(rows)
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    target = SCENE_TARGET[scene]
    allx, ally, allt = [], [], []
    for run, cyc in sorted(runs.items()):
        r0 = cyc[0]
        if r0["scene"] != scene or r0["part"] != scene or \
                r0["role"] != "main":
            continue
        c, m, ls = STYLE.get(r0["series"], ("k", "x", "-"))
        n = [x["n_dofs"] for x in cyc]
        e = [100 * x["epsilon"] for x in cyc]
        t = [x["cumulative_wall_s"] for x in cyc]
        axes[0].plot(n, e, color=c, marker=m, ls=ls, label=r0["series"])
        axes[1].plot(t, e, color=c, marker=m, ls=ls, label=r0["series"])
        allx += n
        ally += e
        allt += t
    if scene == "blocks":
        for run, cyc in sorted(runs.items()):
            r0 = cyc[0]
            if r0["part"] != "blocks" or r0["role"] != "sweep":
                continue
            c = STYLE.get(r0["series"], ("k",))[0]
            last = cyc[-1]
            for ax, x in ((axes[0], last["n_dofs"]),
                          (axes[1], last["cumulative_wall_s"])):
                ax.plot([x], [100 * last["epsilon"]], color=c, marker="*",
                        ms=11, ls="none", mfc="none")
        axes[0].plot([], [], "k*", mfc="none", ms=11,
                     label="last cycle of a run with ε0 = 3, 2, 1.5, 0.7, "
                           "0.5 % (P1 remesh, Q1 size ratio)")
    if allx:
        slope_line(axes[0], allx, ally)
    for ax in axes:
        ax.axhline(target, color="gray", ls=":", lw=1.2,
                   label="ε0 = %g %%" % target)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylabel("estimated error ε [%]")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_xlabel("DoFs (both bodies)")
    axes[1].set_xlabel("cumulative wall time of the run up to the cycle [s]"
                       " (1 rank, without exact-error time)")
    axes[0].legend(fontsize=7.5)
    axes[1].legend(fontsize=7.5)
    axes[0].set_title("%s: ε against DoFs, one point per cycle" % scene,
                      fontsize=10)
    axes[1].set_title("%s: ε against cumulative wall time" % scene,
                      fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def plot_exact(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    runs = runs_of(rows)
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    done = set()
    allx, ally = [], []
    for run, cyc in sorted(runs.items()):
        r0 = cyc[0]
        if r0["part"] != "exact":
            continue
        ax = axes[0] if r0["cell_type"] == "triangle" else axes[1]
        c, m, _ = STYLE.get(r0["series"], ("k", "x", "-"))
        lab = r0["series"] if r0["series"] not in done else None
        done.add(r0["series"])
        if r0["strategy"] == "uniform":
            continue
        n = [x["n_dofs"] for x in cyc]
        ax.plot(n, [100 * x["epsilon_exact"] for x in cyc], color=c,
                marker=m, ls="-", label=(lab + ": ε_exact") if lab else None)
        ax.plot(n, [100 * x["epsilon"] for x in cyc], color=c, marker=m,
                ls="--", mfc="none", alpha=0.6,
                label=(lab + ": ε") if lab else None)
        allx += n
        ally += [100 * x["epsilon_exact"] for x in cyc]
    # uniform: one-cycle runs with the same reference
    for cell, ax in (("triangle", axes[0]), ("quadrilateral", axes[1])):
        pts = sorted((cyc[0]["n_dofs"], cyc[0]["epsilon_exact"],
                      cyc[0]["epsilon"], cyc[0]["series"])
                     for run, cyc in runs.items()
                     if cyc[0]["part"] == "exact" and
                     cyc[0]["strategy"] == "uniform" and
                     cyc[0]["cell_type"] == cell)
        if pts:
            c, m, _ = STYLE.get(pts[0][3], ("k", "x", "-"))
            ax.plot([p[0] for p in pts], [100 * p[1] for p in pts], color=c,
                    marker=m, label=pts[0][3] + ": ε_exact")
            ax.plot([p[0] for p in pts], [100 * p[2] for p in pts], color=c,
                    marker=m, ls="--", mfc="none", alpha=0.6,
                    label=pts[0][3] + ": ε")
            allx += [p[0] for p in pts]
            ally += [100 * p[1] for p in pts]
    ref = {"triangle": None, "quadrilateral": None}
    for r in rows:
        if r["part"] == "blocks" and r["strategy"] == "uniform" and \
                r["status"] == "ok" and r.get("n_dofs") == 105668 and \
                r["degree"] == 1:
            ref[r["cell_type"]] = 100 * r["epsilon"]
    for cell, ax in (("triangle", axes[0]), ("quadrilateral", axes[1])):
        if allx:
            slope_line(ax, allx, ally)
        if ref[cell]:
            ax.axhline(ref[cell], color="k", ls=":", lw=1,
                       label="ε of the reference mesh itself "
                             "(%.2f %%)" % ref[cell])
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("DoFs (both bodies)")
        ax.set_ylabel("error [%]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7.5)
    axes[0].set_title("blocks P1: ε_exact against one reference solution "
                      "(uniform level 4, 105,668 DoFs)", fontsize=9)
    axes[1].set_title("blocks Q1: ε_exact against one reference solution "
                      "(uniform level 5, 105,668 DoFs)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def plot_all(rows):
    scenes = {r["scene"] for r in rows if r["part"] in
              ("blocks", "hertz", "punch")}
    for s in sorted(scenes):
        plot_scene(rows, s, os.path.join(HERE, "work_precision_%s.png" % s))
    if any(r["part"] == "exact" for r in rows):
        plot_exact(rows, os.path.join(HERE, "exact_error_blocks.png"))


# ----------------------------------------------------------------- tables

def g(x, f="%.3g"):
    return "—" if x is None or x == "" else f % x


def tables(rows):
    res, sweeps = summary_numbers(rows)
    out = []
    for scene in ("blocks", "hertz", "punch"):
        t = SCENE_TARGET[scene]
        items = [v for (s, _), v in sorted(res.items()) if s == scene]
        if not items:
            continue
        out.append("\n### %s: reaching ε0 = %g %%\n" % (scene, t))
        out.append("| series | cycles run | first cycle with ε ≤ ε0: DoFs "
                   "| ε [%] | largest DoFs on the way | cumulative wall [s] "
                   "| process wall [s] | Newton its (total) | DoFs vs "
                   "uniform (same element): first cycle ≤ ε0 / crossing | "
                   "time vs uniform: first cycle ≤ ε0 / crossing | measured "
                   "rate r (ε ~ N^-r) |")
        out.append("|---|---|---|---|---|---|---|---|---|---|---|")
        order = sorted(items, key=lambda v: (v["strategy"] != "uniform",
                                             v["degree"], v["series"]))
        for v in order:
            rc = v["reach"]
            u = uniform_of(res, scene, v["cell"], v["degree"])
            ratio_n = ratio_t = "—"
            if u and u is not v and rc and u["reach"]:
                ur = u["reach"]
                ratio_n = "%.1f× / %s" % (
                    ur["n_dofs"] / rc["n_dofs"],
                    g(ur.get("n_continuous", 0) / rc["n_dofs"], "%.1f×")
                    if ur.get("n_continuous") else "—")
                ratio_t = "%.1f× / %s" % (
                    ur["cum_s"] / rc["cum_s"],
                    g(ur.get("cum_continuous", 0) / rc["cum_s"], "%.1f×")
                    if ur.get("cum_continuous") else "—")
                if not ur["measured"]:
                    ratio_n += " (extrap.)"
                    ratio_t += " (extrap.)"
            if v["strategy"] == "uniform":
                rate = "%.3f (last 3), %.3f (all)" % (v["rate_last3"],
                                                      v["rate_all"])
            else:
                rate = "%s (all cycles), %s (from cycle 1)" % (
                    g(v["rate_all"]), g(v.get("rate_after0")))
            if rc is None:
                out.append("| %s | %d | not reached (%s) | | | | | %d | | | "
                           "%s |" % (v["series"], len(v["cycles"]),
                                     v["stop"], v["total_newton"], rate))
                continue
            if rc["measured"]:
                nd = "%d (cycle %d)" % (rc["n_dofs"], rc["cycle"])
                if rc.get("n_continuous"):
                    nd += "; crossing %.3g DoFs at %.3g s" % (
                        rc["n_continuous"], rc["cum_continuous"])
                out.append("| %s | %d | %s | %.3f | %d | %.2f | %.2f | %d | "
                           "%s | %s | %s |" % (
                               v["series"], len(v["cycles"]), nd,
                               100 * rc["epsilon"], rc["max_dofs"],
                               rc["cum_s"], v["process_s"], rc["newton"],
                               ratio_n, ratio_t, rate))
            else:
                out.append("| %s | %d | **extrapolated**: %.3g (%d more "
                           "cycles; crossing %.3g DoFs at %.3g s) | %.3f "
                           "(extrap.) | %.3g "
                           "| %.3g (extrap.) | %.2f (measured run) | %d "
                           "(measured run) | — | — | %s |" % (
                               v["series"], len(v["cycles"]), rc["n_dofs"],
                               rc["extra_cycles"], rc["n_continuous"],
                               rc["cum_continuous"],
                               100 * rc["epsilon"], rc["max_dofs"],
                               rc["cum_s"], v["process_s"],
                               v["total_newton"], rate))
    if sweeps:
        out.append("\n### blocks: target sweep (last cycle of each adaptive "
                   "run)\n")
        out.append("| series | ε0 [%] | final DoFs | final ε [%] | largest "
                   "DoFs | cumulative wall [s] |")
        out.append("|---|---|---|---|---|---|")
        for k, pts in sorted(sweeps.items()):
            for tt, n, e, nmax, cum in pts:
                out.append("| %s | %g | %d | %.3f | %d | %.2f |" % (
                    k, tt, n, 100 * e, nmax, cum))
            if len(pts) >= 2:
                out.append("| %s | **fitted rate over the final cycles: "
                           "r = %.3f** | | | | |" % (
                               k, fit_rate([(p[1], p[2]) for p in pts])))
    # warm start
    runs = runs_of(rows)
    warm = [(run, cyc) for run, cyc in runs.items()
            if cyc[0]["part"] == "warm"]
    if warm:
        out.append("\n### blocks: warm start (Newton iterations summed over "
                   "the cycles)\n")
        out.append("| series | cycles | Newton its, warm start | Newton its,"
                   " cold start | saved | cumulative wall warm / cold [s] "
                   "| same meshes (DoFs per cycle) |")
        out.append("|---|---|---|---|---|---|---|")
        for run, cold in sorted(warm):
            r0 = cold[0]
            hot = None
            for run2, cyc in runs.items():
                c0 = cyc[0]
                if c0["part"] == "blocks" and c0["role"] == "main" and \
                        c0["series"] == r0["series"]:
                    hot = cyc
            if not hot:
                continue
            k = min(len(hot), len(cold))
            nh = sum(x["newton_iterations"] for x in hot[:k])
            nc = sum(x["newton_iterations"] for x in cold[:k])
            same = [x["n_dofs"] for x in hot[:k]] == \
                [x["n_dofs"] for x in cold[:k]]
            out.append("| %s | %d%s | %d | %d | %d (%.0f %%) | %.2f / %.2f "
                       "| %s |" % (
                           r0["series"], k,
                           "" if len(hot) == len(cold) else
                           " (warm run: %d)" % len(hot), nh, nc, nc - nh,
                           100.0 * (nc - nh) / nc if nc else 0,
                           hot[k - 1]["cumulative_wall_s"],
                           cold[k - 1]["cumulative_wall_s"],
                           ("yes" if len(hot) == len(cold) else
                            "yes (first %d cycles)" % k)
                           if same else "no: %s vs %s" % (
                               [x["n_dofs"] for x in hot],
                               [x["n_dofs"] for x in cold])))
    exact = sorted(((run, cyc) for run, cyc in runs.items()
                    if cyc[0]["part"] == "exact"),
                   key=lambda x: (x[1][0]["cell_type"], x[1][0]["series"],
                                  x[1][0]["n_dofs"]))
    if exact:
        out.append("\n### blocks: exact error against the reference "
                   "solution\n")
        out.append("| run | cycle | DoFs | ε [%] | ε_exact [%] | effectivity"
                   " | exact-error time [s] | peak RSS [MiB] |")
        out.append("|---|---|---|---|---|---|---|---|")
        for run, cyc in exact:
            for x in cyc:
                out.append("| %s | %d | %d | %.3f | %.3f | %.3f | %.1f | "
                           "%.0f |" % (
                               run.replace("exact/", ""), x["cycle"],
                               x["n_dofs"], 100 * x["epsilon"],
                               100 * x["epsilon_exact"], x["effectivity"],
                               x["exact_error_s"], x["peak_rss_MiB"]))
        bad = [r for r in rows if r["part"] == "exact" and
               r["status"] != "ok"]
        for r in bad:
            out.append("| %s | %s: %s | | | | | | |" % (
                r["run"], r["status"], r["message"]))
    bad = [r for r in rows if r["status"] != "ok" and r["part"] != "exact"]
    if bad:
        out.append("\nRuns that did not finish:\n")
        for r in bad:
            out.append("- %s: %s %s" % (r["run"], r["status"], r["message"]))
    return "\n".join(out)


# ------------------------------------------------------------------- main

def main():
    p = argparse.ArgumentParser(
        description=__doc__.split("\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=__doc__.split("\n", 2)[2])
    p.add_argument("--part", default="all",
                   choices=["blocks", "warm", "hertz", "punch", "exact",
                            "all"])
    p.add_argument("--executable", "--exe", default=DEFAULT_EXE)
    p.add_argument("--quick", action="store_true")
    p.add_argument("--fresh", action="store_true",
                   help="start a new results.csv (default: keep the rows "
                        "of the runs not run now)")
    p.add_argument("--resume", action="store_true",
                   help="skip the runs that results.csv already holds as "
                        "ok")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--repeat-below", type=float, default=10.0)
    p.add_argument("--quiet-wait", type=float, default=60.0)
    p.add_argument("--max-run-s", type=float, default=600.0)
    p.add_argument("--max-rss-mb", type=float, default=5000.0)
    p.add_argument("--csv", default=CSV_PATH)
    p.add_argument("--plot-only", action="store_true")
    p.add_argument("--table", action="store_true")
    a = p.parse_args()

    if a.plot_only or a.table:
        rows = read_csv(a.csv)
        if a.plot_only:
            plot_all(rows)
        if a.table:
            print(tables(rows))
        return 0

    exe = os.path.abspath(a.executable)
    if not os.access(exe, os.X_OK):
        p.error("executable %s not found (build it, or --executable)" % exe)
    print("machine:", machine_info(), flush=True)
    print("executable:", exe, time.ctime(os.path.getmtime(exe)), flush=True)
    start = time.perf_counter()
    cases = all_cases(a.part, a.quick)
    old = [] if a.fresh else read_csv(a.csv)
    if a.resume:
        done = {r["run"] for r in old if r["status"] == "ok"}
        cases = [c for c in cases if c["run"] not in done]
    now = {c["run"] for c in cases}
    kept = [r for r in old if r["run"] not in now]
    new = []
    for c in cases:
        rows = run_case(exe, c, a)
        new += rows
        r = rows[-1]
        if r["status"] == "ok":
            print("%-55s %2d cycles, last: %7d DoFs, eps %.3f %%%s, cum "
                  "%.2f s, process %.1f s, Newton %d, peak %.0f MiB, "
                  "other cpu %.1f s, repeats %d; %s" % (
                      c["run"], len(rows), r["n_dofs"], 100 * r["epsilon"],
                      "" if r["epsilon_exact"] in ("", None) else
                      " (exact %.3f %%)" % (100 * r["epsilon_exact"]),
                      r["cumulative_wall_s"], r["process_wall_s"],
                      sum(x["newton_iterations"] for x in rows),
                      r["peak_rss_MiB"], r["other_cpu_s"], r["repeats"],
                      r["stop_reason"]), flush=True)
        else:
            print("%-55s %s: %s" % (c["run"], r["status"], r["message"]),
                  flush=True)
        write_csv(kept + new, a.csv)
    rows = kept + new
    write_csv(rows, a.csv)
    plot_all(rows)
    print(tables(rows))
    print("total %.0f s (%.0f s in runs)" % (time.perf_counter() - start,
                                             RUN_SECONDS[0]), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
