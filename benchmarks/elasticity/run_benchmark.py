#!/usr/bin/python3
"""Elasticity baseline benchmark of coulomb-adapt.

Runs the 'manufactured' scene (two independent unit squares, Q1, plane
strain, one cycle) over a ladder of uniform meshes, for the direct solver
(Amesos MUMPS) and CG + ML AMG, on 1 and 2 MPI ranks. Each run gets a fresh
output directory under /tmp; the numbers come from the run's summary.json
(phase timings, peak memory, iterations) and from the program's standard
output (wall time of each body's solve).

The machine is shared: before each run the script waits (--quiet-wait) for
the CPUs to be idle, and it records the CPU time other processes used during
the run. Plot and tables use the fastest 'clean' run of each point (other
processes below 0.1 core on average), or the fastest run if none is clean.
The executable (and the project library next to it) is copied to a private
directory first, so that a rebuild during the sweep does not affect it.

  run_benchmark.py                 full sweep (~1e3 .. ~2e6 DoFs), CSV + PNG
  run_benchmark.py --quick         small sizes, one repeat (smoke test)
  run_benchmark.py --max-dofs 3e5  restrict the sweep
  run_benchmark.py --plot-only     re-plot from an existing CSV
  run_benchmark.py --table         print the Markdown tables of the README

Only the Python standard library and matplotlib are used.
"""

import argparse
import csv
import json
import math
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_EXE = os.path.normpath(os.path.join(HERE, "..", "..", "build",
                                            "coulomb-adapt"))
DEFAULT_CSV = os.path.join(HERE, "results.csv")
DEFAULT_PNG = os.path.join(HERE, "elasticity_timings.png")

# Mesh ladder: (coarse subdivisions per direction, global refinements).
# Both bodies get the same mesh of n = s * 2^r cells per direction, so each
# body has 2 (n+1)^2 DoFs and the run 4 (n+1)^2. Factor ~4 per step from
# 1156 to 1,050,625 DoFs; the last entry (n = 704) is an extension that gives
# one body ~1e6 DoFs (994,050; 1,988,100 in total).
LADDER = [(2, 3), (2, 4), (2, 5), (2, 6), (2, 7), (2, 8), (11, 6)]

SOLVERS = ["direct", "amg"]
RANKS = [1, 2]

FIELDS = [
    "repeat", "solver", "ranks", "subdivisions", "refinements", "n_dofs",
    "n_dofs_body1", "n_dofs_body2", "status", "setup_s", "assembly_s",
    "solve_s", "solve_body1_s", "solve_body2_s", "cycle_wall_s",
    "process_wall_s", "peak_memory_MiB", "peak_memory_total_MiB",
    "iterations_body1", "iterations_body2", "method",
    "rel_energy_error_body1", "rel_energy_error_body2", "loadavg_1min",
    "busy_cores_before", "other_cpu_s", "clean", "version", "message",
]

# A run counts as 'clean' if the other processes on the machine used less
# than this many CPU seconds per second of the run (plus a small allowance).
CLEAN_OTHER_CPU_FRACTION = 0.1
CLEAN_OTHER_CPU_ALLOWANCE_S = 0.05


def is_clean(other_cpu_s, process_wall_s):
    return other_cpu_s < (CLEAN_OTHER_CPU_FRACTION * process_wall_s +
                          CLEAN_OTHER_CPU_ALLOWANCE_S)

SOLVE_LINE = re.compile(
    r"^\s*(?P<body>.+?): solved by (?P<method>.+?)"
    r"(?: \((?P<its>\d+) iterations\))? in (?P<t>[0-9.eE+-]+) s\s*$")


def expected_dofs(subdivisions, refinements):
    n = subdivisions * 2 ** refinements
    return 4 * (n + 1) ** 2


def busy_jiffies():
    """CPU time (all cores) spent non-idle since boot, in seconds."""
    with open("/proc/stat") as f:
        v = [int(x) for x in f.readline().split()[1:]]
    # user nice system idle iowait irq softirq steal (guest is in user)
    busy = v[0] + v[1] + v[2] + v[5] + v[6] + (v[7] if len(v) > 7 else 0)
    return busy / os.sysconf("SC_CLK_TCK")


def children_cpu():
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def busy_cores(window=1.0):
    """Average number of busy cores over 'window' seconds (this process
    sleeps meanwhile)."""
    b0, t0 = busy_jiffies(), time.perf_counter()
    time.sleep(window)
    return (busy_jiffies() - b0) / (time.perf_counter() - t0)


def wait_for_quiet(threshold, max_wait):
    """Waits until the machine is idle (other processes use less than
    'threshold' cores), at most 'max_wait' seconds; returns the last
    measurement."""
    start = time.perf_counter()
    load = busy_cores()
    announced = False
    while load > threshold and time.perf_counter() - start < max_wait:
        if not announced:
            print("    machine busy (%.2f cores used by other processes); "
                  "waiting up to %.0f s" % (load, max_wait), flush=True)
            announced = True
        time.sleep(4)
        load = busy_cores()
    return load


def snapshot_executable(exe):
    """Copies the executable and the shared libraries it loads from its own
    directory (the project library) to a private directory, so that a
    rebuild during the sweep cannot change or crash the runs. Returns the
    copied executable and the LD_LIBRARY_PATH to use."""
    exe = os.path.abspath(exe)
    exe_dir = os.path.dirname(exe)
    target = tempfile.mkdtemp(prefix="coulomb-elasticity-bin-")
    shutil.copy2(exe, target)
    try:
        # Libraries next to the executable win (as they will in the runs).
        env = dict(os.environ, LD_LIBRARY_PATH=exe_dir + (
            ":" + os.environ["LD_LIBRARY_PATH"]
            if os.environ.get("LD_LIBRARY_PATH") else ""))
        ldd = subprocess.run(["ldd", exe], stdout=subprocess.PIPE, env=env,
                             stderr=subprocess.DEVNULL, text=True).stdout
    except OSError:
        ldd = ""
    for line in ldd.splitlines():
        parts = line.split("=>")
        if len(parts) == 2:
            path = parts[1].split("(")[0].strip()
            if path and os.path.dirname(os.path.realpath(path)) == \
                    os.path.realpath(exe_dir):
                shutil.copy2(path, target)
    return os.path.join(target, os.path.basename(exe)), target


def loadavg():
    try:
        with open("/proc/loadavg") as f:
            return float(f.read().split()[0])
    except OSError:
        return float("nan")


def run_one(exe, solver, ranks, subdivisions, refinements, timeout, keep,
            lib_dir=None, busy_before=float("nan")):
    """Runs one configuration; returns a dict with the FIELDS (minus
    'repeat')."""
    out_dir = tempfile.mkdtemp(prefix="coulomb-elasticity-bench-")
    sub = "%d, %d" % (subdivisions, subdivisions)
    args = [
        exe,
        "-s", "Scene/Name=manufactured",
        "-s", "Scene/Manufactured/Body 1 subdivisions=" + sub,
        "-s", "Scene/Manufactured/Body 2 subdivisions=" + sub,
        "-s", "Mesh/Global refinements=%d" % refinements,
        "-s", "Mesh/Cell type=quadrilateral",
        "-s", "Finite elements/Polynomial degree=1",
        "-s", "Finite elements/Plane model=plane strain",
        "-s", "Adaptation/Number of cycles=1",
        "-s", "Output/Write VTU=false",
        "-s", "Output/Output directory=" + out_dir,
        "-s", "Linear solver/Type=" + solver,
    ]
    if ranks > 1:
        args = ["mpirun", "-np", str(ranks), "--oversubscribe"] + args
    env = dict(os.environ)
    env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1",
                "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                "OMP_NUM_THREADS": "1"})
    if lib_dir:
        env["LD_LIBRARY_PATH"] = lib_dir + (
            ":" + env["LD_LIBRARY_PATH"] if env.get("LD_LIBRARY_PATH")
            else "")

    row = {k: "" for k in FIELDS if k != "repeat"}
    row.update(solver=solver, ranks=ranks, subdivisions=subdivisions,
               refinements=refinements,
               n_dofs=expected_dofs(subdivisions, refinements),
               loadavg_1min=loadavg(), busy_cores_before=round(busy_before, 3))
    cpu0, busy0 = children_cpu(), busy_jiffies()
    start = time.perf_counter()
    try:
        proc = subprocess.run(args, env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True,
                              timeout=timeout, start_new_session=True)
    except subprocess.TimeoutExpired:
        row.update(status="timeout",
                   message="no result within %g s (killed)" % timeout)
        if not keep:
            shutil.rmtree(out_dir, ignore_errors=True)
        return row
    row["process_wall_s"] = round(time.perf_counter() - start, 3)
    # CPU time used on the machine during the run by anything but this run.
    other = (busy_jiffies() - busy0) - (children_cpu() - cpu0)
    row["other_cpu_s"] = round(max(other, 0.), 2)
    row["clean"] = int(is_clean(other, row["process_wall_s"]))

    if proc.returncode != 0:
        text = (proc.stderr.strip() or proc.stdout.strip()).splitlines()
        last = text[-1] if text else ""
        if proc.returncode in (-9, 137):
            status = "killed"
            last = "killed by SIGKILL (likely out of memory) " + last
        else:
            status = "failed"
        row.update(status=status,
                   message=("exit code %d: %s" % (proc.returncode, last))
                   .replace("\n", " ")[:300])
        if not keep:
            shutil.rmtree(out_dir, ignore_errors=True)
        return row

    with open(os.path.join(out_dir, "summary.json")) as f:
        summary = json.load(f)
    cycle = summary["cycles"][-1]
    bodies = cycle["bodies"]
    timings = cycle["timings_s"]
    solvers = cycle["linear_solver"]
    row.update(
        status="ok",
        n_dofs=cycle["n_dofs"],
        n_dofs_body1=bodies[0]["n_dofs"],
        n_dofs_body2=bodies[1]["n_dofs"],
        setup_s=timings.get("setup", ""),
        assembly_s=timings.get("assembly", ""),
        solve_s=timings.get("solve", ""),
        cycle_wall_s=cycle["wall_time_s"],
        peak_memory_MiB=cycle["peak_memory_MiB"],
        peak_memory_total_MiB=cycle["peak_memory_total_MiB"],
        iterations_body1=solvers[0]["iterations"],
        iterations_body2=solvers[1]["iterations"],
        method=solvers[0]["method"],
        rel_energy_error_body1=bodies[0].get("exact_error", {})
        .get("relative_energy", ""),
        rel_energy_error_body2=bodies[1].get("exact_error", {})
        .get("relative_energy", ""),
        version=summary.get("version", ""),
    )
    # Per-body solve wall times are only printed (3 significant digits).
    per_body = [m.group("t") for m in map(SOLVE_LINE.match,
                                          proc.stdout.splitlines()) if m]
    if len(per_body) == 2:
        row["solve_body1_s"], row["solve_body2_s"] = per_body
    if not keep:
        shutil.rmtree(out_dir, ignore_errors=True)
    return row


def sweep(opts):
    ladder = [(s, r) for s, r in LADDER
              if opts.min_dofs <= expected_dofs(s, r) <= opts.max_dofs]
    configs = [(sv, nr) for nr in opts.ranks for sv in opts.solvers]
    if not ladder or not configs:
        sys.exit("nothing to run: check --min-dofs/--max-dofs/--solvers/"
                 "--ranks")
    if not os.access(opts.exe, os.X_OK):
        sys.exit("executable not found: %s (use --exe)" % opts.exe)
    exe, lib_dir = opts.exe, None
    if not opts.no_snapshot:
        exe, lib_dir = snapshot_executable(opts.exe)
        print("running a private copy of %s in %s" % (opts.exe, lib_dir))

    # The CSV is rewritten after every run so that an interrupted sweep
    # keeps what it measured. With --append the new runs are added to the
    # existing rows (numbered after the repeats already there).
    rows = []
    first_repeat = 0
    if opts.append and os.path.exists(opts.csv):
        with open(opts.csv, newline="") as f:
            rows = [dict(r) for r in csv.DictReader(f)]
        for r in rows:
            r["ranks"] = int(r["ranks"])
            r["n_dofs"] = int(r["n_dofs"])
            first_repeat = max(first_repeat, int(r["repeat"]) + 1)
        old_failures = [r for r in rows if r["status"] != "ok"]
    else:
        old_failures = []

    def flush():
        tmp = opts.csv + ".tmp"
        with open(tmp, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=FIELDS)
            w.writeheader()
            w.writerows(rows)
        os.replace(tmp, opts.csv)

    t0 = time.perf_counter()
    broken = {}  # config -> first failing size: larger sizes are skipped
    # Repeats are the outer loop so that a slow phase of the machine does
    # not hit all repeats of one configuration.
    for x in old_failures:
        key = (x["solver"], x["ranks"])
        broken[key] = min(broken.get(key, x["n_dofs"]), x["n_dofs"])
    for rep in range(first_repeat, first_repeat + opts.repeats):
        for s, r in ladder:
            for sv, nr in configs:
                n = expected_dofs(s, r)
                if (sv, nr) in broken and n > broken[(sv, nr)]:
                    if rep == first_repeat and not any(
                            x["solver"] == sv and x["ranks"] == nr
                            and x["n_dofs"] == n for x in rows):
                        row = {k: "" for k in FIELDS}
                        row.update(repeat=rep, solver=sv, ranks=nr,
                                   subdivisions=s, refinements=r, n_dofs=n,
                                   status="skipped",
                                   message="a smaller size failed")
                        rows.append(row)
                        flush()
                    continue
                if any(x["status"] != "ok" and x["solver"] == sv
                        and x["ranks"] == nr and x["n_dofs"] == n
                        for x in rows):
                    continue  # do not repeat a failure or a timeout
                busy = (wait_for_quiet(opts.quiet_threshold,
                                       opts.quiet_wait)
                        if opts.quiet_wait > 0 else float("nan"))
                row = run_one(exe, sv, nr, s, r, opts.timeout, opts.keep,
                              lib_dir, busy)
                row["repeat"] = rep
                rows.append(row)
                flush()
                if row["status"] != "ok":
                    broken[(sv, nr)] = n
                print("[%7.1f s] repeat %d  %-6s %d rank(s)  %9d DoFs  %s"
                      "  solve %s s  wall %s s  mem %s MiB  its %s/%s"
                      "  other CPU %s s" %
                      (time.perf_counter() - t0, rep, sv, nr, row["n_dofs"],
                       row["status"], fmt(row["solve_s"]),
                       fmt(row["process_wall_s"]),
                       fmt(row["peak_memory_MiB"]), row["iterations_body1"],
                       row["iterations_body2"], fmt(row["other_cpu_s"], 2)),
                      flush=True)
                if row["status"] != "ok":
                    print("    " + row["message"], flush=True)
    print("sweep done in %.0f s; results in %s" %
          (time.perf_counter() - t0, opts.csv))
    if lib_dir:
        shutil.rmtree(lib_dir, ignore_errors=True)


def fmt(x, digits=3):
    if x == "" or x is None:
        return "-"
    x = float(x)
    if x == 0:
        return "0"
    return "%.*g" % (digits, x)


# ----------------------------------------------------------------------------
# Reading and aggregating the CSV


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        row["ranks"] = int(row["ranks"])
        row["n_dofs"] = int(row["n_dofs"])
        for k in ("setup_s", "assembly_s", "solve_s", "solve_body1_s",
                  "solve_body2_s", "cycle_wall_s", "process_wall_s",
                  "peak_memory_MiB", "peak_memory_total_MiB",
                  "n_dofs_body1", "n_dofs_body2", "iterations_body1",
                  "iterations_body2", "other_cpu_s"):
            row[k] = float(row[k]) if row.get(k, "") != "" else None
        # Recomputed, so that the criterion can be changed afterwards.
        if row["other_cpu_s"] is not None and row["process_wall_s"]:
            row["clean"] = is_clean(row["other_cpu_s"],
                                    row["process_wall_s"])
        else:
            row["clean"] = row.get("clean", "1") in ("1", "")
    return rows


def aggregate(rows):
    """(solver, ranks) -> sorted list of per-size records. Times: minimum
    over the repeats (interference from other processes only adds time),
    taken over the clean runs (no other load on the machine) if there are
    any; memory and iterations: median. Sizes without a successful run keep
    their status."""
    groups = {}
    for row in rows:
        groups.setdefault((row["solver"], row["ranks"], row["n_dofs"]),
                          []).append(row)
    series = {}
    for (sv, nr, n), rs in groups.items():
        ok = [x for x in rs if x["status"] == "ok"]
        n_ok = len(ok)
        if any(x["clean"] for x in ok):
            ok = [x for x in ok if x["clean"]]
        rec = {"n_dofs": n, "n_runs": n_ok, "n_clean": sum(
            1 for x in ok if x["clean"]),
               "status": "ok" if ok else rs[0]["status"],
               "message": "" if ok else rs[0]["message"]}
        if ok:
            for k in ("setup_s", "assembly_s", "solve_s", "solve_body1_s",
                      "solve_body2_s", "cycle_wall_s", "process_wall_s"):
                vals = [x[k] for x in ok if x[k] is not None]
                rec[k] = min(vals) if vals else None
                rec[k + "_max"] = max(vals) if vals else None
            for k in ("peak_memory_MiB", "peak_memory_total_MiB",
                      "iterations_body1", "iterations_body2",
                      "n_dofs_body1", "n_dofs_body2"):
                vals = [x[k] for x in ok if x[k] is not None]
                rec[k] = statistics.median(vals) if vals else None
            # Other processes' load (cores) during the fastest run.
            fastest = min(ok, key=lambda x: x["solve_s"] or float("inf"))
            rec["other_load"] = ((fastest["other_cpu_s"] or 0.) /
                                 fastest["process_wall_s"]
                                 if fastest["other_cpu_s"] is not None
                                 and fastest["process_wall_s"] else None)
            # One body's solve: the slower of the two (same mesh size).
            b = [rec["solve_body1_s"], rec["solve_body2_s"]]
            rec["solve_one_body_s"] = (max(b) if None not in b else None)
        series.setdefault((sv, nr), []).append(rec)
    for v in series.values():
        v.sort(key=lambda rec: rec["n_dofs"])
    return series


def loglog_slope(points):
    """Least-squares slope of log(y) over log(x)."""
    pts = [(math.log(x), math.log(y)) for x, y in points if x and y]
    if len(pts) < 2:
        return float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    sxy = sum((p[0] - mx) * (p[1] - my) for p in pts)
    return sxy / sxx


def crossover(series, ranks):
    """Per-body DoFs above which AMG solves one body faster than the direct
    solver: log-log interpolation between the last size where direct wins
    and the first size from which AMG wins at every larger size."""
    d = {rec["n_dofs"]: rec for rec in series.get(("direct", ranks), [])
         if rec["status"] == "ok"}
    a = {rec["n_dofs"]: rec for rec in series.get(("amg", ranks), [])
         if rec["status"] == "ok"}
    sizes = sorted(set(d) & set(a))
    pts = []
    for n in sizes:
        td, ta = d[n]["solve_one_body_s"], a[n]["solve_one_body_s"]
        if td and ta:
            pts.append((d[n]["n_dofs_body1"], td / ta))
    if not pts:
        return None, pts
    # First index from which the ratio stays > 1.
    k = len(pts)
    while k > 0 and pts[k - 1][1] > 1:
        k -= 1
    if k == len(pts):
        return None, pts  # AMG never wins in the measured range
    if k == 0:
        return 0, pts  # AMG wins everywhere
    (n0, r0), (n1, r1) = pts[k - 1], pts[k]
    # ratio is <= 1 at n0, > 1 at n1: interpolate log(ratio) over log(n).
    # Clamp r0 to avoid log(0); ratios are positive.
    t = (0 - math.log(r0)) / (math.log(r1) - math.log(r0))
    return math.exp(math.log(n0) + t * (math.log(n1) - math.log(n0))), pts


# ----------------------------------------------------------------------------
# Plot

STYLE = {("direct", 1): ("tab:red", "o", "-"),
         ("direct", 2): ("tab:red", "s", "--"),
         ("amg", 1): ("tab:blue", "o", "-"),
         ("amg", 2): ("tab:blue", "s", "--")}


def label(sv, nr):
    return "%s, %d rank%s" % ("direct (MUMPS)" if sv == "direct" else
                              "CG+AMG (ML)", nr, "" if nr == 1 else "s")


def plot(csv_path, png_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = read_rows(csv_path)
    series = aggregate(rows)
    keys = [k for k in STYLE if k in series] + \
        sorted(k for k in series if k not in STYLE)

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8))
    ax_t, ax_p, ax_m = axes

    for key in keys:
        col, mk, ls = STYLE.get(key, ("k", "x", ":"))
        ok = [r for r in series[key] if r["status"] == "ok"]
        bad = [r for r in series[key] if r["status"] != "ok"]
        x = [r["n_dofs"] for r in ok]
        ax_t.plot(x, [r["solve_s"] for r in ok], color=col, marker=mk,
                  ls=ls, label="solve: " + label(*key))
        # Spread over the repeats (min .. max).
        ax_t.vlines(x, [r["solve_s"] for r in ok],
                    [r["solve_s_max"] for r in ok], color=col, lw=1.5,
                    alpha=0.5)
        ax_p.plot(x, [1e6 * r["solve_s"] / r["n_dofs"] for r in ok],
                  color=col, marker=mk, ls=ls, label=label(*key))
        ax_m.plot(x, [r["peak_memory_MiB"] for r in ok], color=col,
                  marker=mk, ls=ls, label="max over ranks: " + label(*key))
        if key[1] > 1:
            ax_m.plot(x, [r["peak_memory_total_MiB"] for r in ok], color=col,
                      marker=mk, ls=":", mfc="none",
                      label="sum over ranks: " + label(*key))
        for r in bad:
            ax_t.annotate(r["status"], (r["n_dofs"], ax_t.get_ylim()[1]),
                          color=col, fontsize=7, rotation=90)
    # Assembly does not depend on the solver: one curve per rank count.
    for nr, mk in ((1, "o"), (2, "s")):
        by_n = {}
        for sv in SOLVERS:
            for r in series.get((sv, nr), []):
                if r["status"] == "ok" and r["assembly_s"] is not None:
                    by_n.setdefault(r["n_dofs"], []).append(r["assembly_s"])
        if by_n:
            x = sorted(by_n)
            ax_t.plot(x, [min(by_n[n]) for n in x], color="tab:gray",
                      marker=mk, mfc="none", ls="-" if nr == 1 else "--",
                      label="assembly, %d rank%s" % (nr, "" if nr == 1
                                                      else "s"))
            ax_p.plot(x, [1e6 * min(by_n[n]) / n for n in x],
                      color="tab:gray", marker=mk, mfc="none",
                      ls="-" if nr == 1 else "--",
                      label="assembly, %d rank%s" % (nr, "" if nr == 1
                                                      else "s"))
    # O(N) reference through the largest successful AMG 1-rank solve.
    all_x = sorted({r["n_dofs"] for v in series.values() for r in v})
    anchor = [r for r in series.get(("amg", 1), []) if r["status"] == "ok"]
    if all_x and anchor:
        x1, y1 = anchor[-1]["n_dofs"], anchor[-1]["solve_s"]
        ax_t.plot(all_x, [y1 * x / x1 for x in all_x], color="k", lw=0.8,
                  ls=":", label="slope 1 (O(N))")

    # The program's default 'Maximum DoFs for direct' (per body).
    for ax in (ax_t, ax_p):
        ax.axvline(2 * 200000, color="k", lw=0.8, ls="-.", alpha=0.6)
        ax.text(2 * 200000 * 1.08, 0.9, "default direct limit\n(2e5 DoFs/body)",
                transform=ax.get_xaxis_transform(), fontsize=7)
    ax_t.set(xscale="log", yscale="log", xlabel="DoFs (both bodies)",
             ylabel="wall time [s]",
             title="Solve (2 bodies, one after the other) and assembly")
    ax_p.set(xscale="log", yscale="log", xlabel="DoFs (both bodies)",
             ylabel="wall time per DoF [µs]", title="Time per DoF")
    ax_m.set(xscale="log", yscale="log", xlabel="DoFs (both bodies)",
             ylabel="peak resident memory (VmHWM) [MiB]",
             title="Peak memory of the run")
    from matplotlib.ticker import FixedLocator, ScalarFormatter, NullLocator
    ax_m.yaxis.set_major_locator(FixedLocator([100, 200, 500, 1000, 2000,
                                               5000]))
    ax_m.yaxis.set_minor_locator(NullLocator())
    ax_m.yaxis.set_major_formatter(ScalarFormatter())
    for ax in axes:
        ax.grid(True, which="both", lw=0.3, alpha=0.6)
        ax.legend(fontsize=7, loc="upper left")
    fig.suptitle("coulomb-adapt elasticity baseline: manufactured scene, Q1, "
                 "plane strain; fastest run without other load on the "
                 "machine (bars: spread of those runs)", fontsize=10)
    fig.tight_layout()
    fig.savefig(png_path, dpi=90)
    plt.close(fig)
    print("wrote %s (%d kB)" % (png_path, os.path.getsize(png_path) // 1024))


# ----------------------------------------------------------------------------
# Markdown tables for the README


def table(csv_path):
    rows = read_rows(csv_path)
    series = aggregate(rows)
    keys = [k for k in STYLE if k in series]
    sizes = sorted({r["n_dofs"] for v in series.values() for r in v})

    print("Solve phase (both bodies) [s], iterations (body 1/body 2) and "
          "peak memory per rank / total [MiB]:\n")
    head = "| DoFs total | DoFs/body |"
    for sv, nr in keys:
        head += " %s %dr solve [s] | mem [MiB] |" % (sv, nr)
    print(head)
    print("|" + "---|" * (2 + 2 * len(keys)))
    for n in sizes:
        recs = {k: next((r for r in series[k] if r["n_dofs"] == n), None)
                for k in keys}
        body = next((r["n_dofs_body1"] for r in recs.values()
                     if r and r.get("n_dofs_body1")), None)
        line = "| %s | %s |" % (f"{n:,}", f"{int(body):,}" if body else "-")
        for k in keys:
            r = recs[k]
            if r is None:
                line += " - | - |"
            elif r["status"] != "ok":
                line += " %s | - |" % r["status"]
            else:
                its = ""
                if k[0] == "amg":
                    its = " (%d/%d it)" % (r["iterations_body1"],
                                           r["iterations_body2"])
                mem = fmt(r["peak_memory_MiB"], 4)
                if k[1] > 1:
                    mem += " / " + fmt(r["peak_memory_total_MiB"], 4)
                line += " %s%s | %s |" % (fmt(r["solve_s"]), its, mem)
        print(line)

    print("\nOne body's solve [s] (slower of the two bodies; same mesh):\n")
    print("| DoFs/body |" + "".join(" %s %dr |" % k for k in keys))
    print("|" + "---|" * (1 + len(keys)))
    for n in sizes:
        recs = {k: next((r for r in series[k] if r["n_dofs"] == n), None)
                for k in keys}
        body = next((r["n_dofs_body1"] for r in recs.values()
                     if r and r.get("n_dofs_body1")), None)
        line = "| %s |" % (f"{int(body):,}" if body else "-")
        for k in keys:
            r = recs[k]
            line += " %s |" % (fmt(r["solve_one_body_s"]) if r and
                               r["status"] == "ok" else
                               (r["status"] if r else "-"))
        print(line)

    print("\nSetup / assembly / cycle wall / process wall [s]:\n")
    print("| DoFs total |" + "".join(" %s %dr |" % k for k in keys))
    print("|" + "---|" * (1 + len(keys)))
    for n in sizes:
        line = "| %s |" % f"{n:,}"
        for k in keys:
            r = next((r for r in series[k] if r["n_dofs"] == n), None)
            if r is None or r["status"] != "ok":
                line += " %s |" % (r["status"] if r else "-")
            else:
                line += " %s / %s / %s / %s |" % (
                    fmt(r["setup_s"]), fmt(r["assembly_s"]),
                    fmt(r["cycle_wall_s"]), fmt(r["process_wall_s"]))
        print(line)

    print("\nLog-log slopes of the solve time over DoFs (sizes >= 6e4 "
          "DoFs):\n")
    for k in keys:
        pts = [(r["n_dofs"], r["solve_s"]) for r in series[k]
               if r["status"] == "ok" and r["n_dofs"] >= 6e4]
        print("- %s: %.2f" % (label(*k), loglog_slope(pts)))
    for nr in sorted({k[1] for k in keys}):
        pts = [(r["n_dofs"], r["assembly_s"]) for r in
               series.get(("amg", nr), []) if r["status"] == "ok"
               and r["n_dofs"] >= 6e4]
        print("- assembly, %d rank(s): %.2f" % (nr, loglog_slope(pts)))

    print("\nDirect/AMG ratio of one body's solve time (> 1: AMG faster):\n")
    for nr in sorted({k[1] for k in keys}):
        n_x, pts = crossover(series, nr)
        print("- %d rank(s): %s" % (nr, ", ".join(
            "%s: %.2f" % (f"{int(n):,}", q) for n, q in pts)))
        if n_x is None:
            print("  AMG does not win in the measured range")
        elif n_x == 0:
            print("  AMG wins at every measured size")
        else:
            print("  crossover at ~%s DoFs per body" % f"{int(n_x):,}")

    print("\nRuns per point: clean/successful (clean: other processes used "
          "< 0.1 core on average; if there is a clean run, only clean runs "
          "are used), and the other processes' average load [cores] during "
          "the fastest run used:\n")
    print("| DoFs total |" + "".join(" %s %dr |" % k for k in keys))
    print("|" + "---|" * (1 + len(keys)))
    for n in sizes:
        line = "| %s |" % f"{n:,}"
        for k in keys:
            r = next((r for r in series[k] if r["n_dofs"] == n), None)
            if r is None or r["status"] != "ok":
                line += " - |"
            else:
                line += " %d/%d, %s |" % (r.get("n_clean", 0), r["n_runs"],
                                         fmt(r.get("other_load"), 2))
        print(line)

    bad = [r for v in series.values() for r in v if r["status"] != "ok"]
    if bad:
        print("\nUnsuccessful configurations:")
        for (sv, nr), v in series.items():
            for r in v:
                if r["status"] != "ok":
                    print("- %s, %d DoFs: %s %s" % (label(sv, nr),
                                                    r["n_dofs"], r["status"],
                                                    r["message"]))


# ----------------------------------------------------------------------------


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.
                                RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=DEFAULT_EXE,
                   help="coulomb-adapt executable (default: %(default)s)")
    p.add_argument("--csv", default=DEFAULT_CSV,
                   help="results file (default: %(default)s)")
    p.add_argument("--png", default=DEFAULT_PNG,
                   help="plot file (default: %(default)s)")
    p.add_argument("--max-dofs", type=float, default=2.1e6,
                   help="largest total DoF count to run (default: "
                        "%(default)g; 1.1e6 stops at the ~1e6 step)")
    p.add_argument("--min-dofs", type=float, default=0,
                   help="smallest total DoF count to run")
    p.add_argument("--solvers", default="direct,amg",
                   help="comma-separated subset of direct,amg")
    p.add_argument("--ranks", default="1,2",
                   help="comma-separated MPI rank counts (default 1,2)")
    p.add_argument("--repeats", type=int, default=3,
                   help="runs per configuration; the plot and tables use "
                        "the fastest clean one (default: %(default)s)")
    p.add_argument("--timeout", type=float, default=900,
                   help="seconds before a run is killed and recorded as "
                        "'timeout' (default: %(default)s)")
    p.add_argument("--quick", action="store_true",
                   help="smoke test: up to ~7e4 DoFs, one repeat")
    p.add_argument("--append", action="store_true",
                   help="add the runs to the existing CSV instead of "
                        "starting a new one (e.g. more repeats of some "
                        "sizes)")
    p.add_argument("--quiet-wait", type=float, default=300,
                   help="before each run, wait up to this many seconds for "
                        "other processes to leave the CPUs idle (0: do not "
                        "wait; default: %(default)s)")
    p.add_argument("--quiet-threshold", type=float, default=0.15,
                   help="CPU cores that other processes may use for the "
                        "machine to count as idle (default: %(default)s)")
    p.add_argument("--no-snapshot", action="store_true",
                   help="run the executable in place instead of a private "
                        "copy made at the start of the sweep")
    p.add_argument("--keep", action="store_true",
                   help="keep the /tmp output directories")
    p.add_argument("--plot-only", "--replot", action="store_true",
                   dest="plot_only",
                   help="only re-plot from the existing CSV")
    p.add_argument("--table", action="store_true",
                   help="only print Markdown tables from the existing CSV")
    p.add_argument("--no-plot", action="store_true",
                   help="do not write the PNG after the sweep")
    opts = p.parse_args()
    opts.solvers = [s.strip() for s in opts.solvers.split(",") if s.strip()]
    opts.ranks = [int(s) for s in opts.ranks.split(",") if s.strip()]
    for s in opts.solvers:
        if s not in ("direct", "amg", "auto"):
            p.error("unknown solver '%s'" % s)
    if opts.quick:
        opts.max_dofs = min(opts.max_dofs, 7e4)
        opts.repeats = 1

    if opts.table:
        table(opts.csv)
        return
    if not opts.plot_only:
        sweep(opts)
    if not opts.no_plot:
        plot(opts.csv, opts.png)


if __name__ == "__main__":
    main()
