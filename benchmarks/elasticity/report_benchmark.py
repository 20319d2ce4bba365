#!/usr/bin/python3
"""Plot and tables of the elasticity baseline benchmark, from the CSV that
run_benchmark.py writes; runs nothing.

  report_benchmark.py                 elasticity_timings.png from results.csv
  report_benchmark.py --table         the Markdown tables of the README
  report_benchmark.py --csv C --png P another CSV, another plot file

Plot and tables use the fastest 'clean' run of each point (other processes
below 0.1 core on average during the run), or the fastest run if none is
clean.
"""

import argparse
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(
    __file__))))
import common  # noqa: E402
from common import fmt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_CSV = os.path.join(HERE, "results.csv")
DEFAULT_PNG = os.path.join(HERE, "elasticity_timings.png")
SOLVERS = ["direct", "amg"]


# ----------------------------------------------------------------------------
# Reading and aggregating the CSV


# Columns read as text; the others are numbers (empty: None).
TEXT = ("repeat", "solver", "subdivisions", "refinements", "status",
        "method", "rel_energy_error_body1", "rel_energy_error_body2",
        "loadavg_1min", "busy_cores_before", "clean", "version", "message")


def read_rows(path):
    rows = common.read_csv(path, text=TEXT, ints=("ranks", "n_dofs"),
                           empty=None)
    for row in rows:
        # Recomputed, so that the criterion can be changed afterwards.
        if row["other_cpu_s"] is not None and row["process_wall_s"]:
            row["clean"] = common.is_clean(row["other_cpu_s"],
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
    plt = common.pyplot()

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
        print("- %s: %.2f" % (label(*k), common.loglog_slope(pts)))
    for nr in sorted({k[1] for k in keys}):
        pts = [(r["n_dofs"], r["assembly_s"]) for r in
               series.get(("amg", nr), []) if r["status"] == "ok"
               and r["n_dofs"] >= 6e4]
        print("- assembly, %d rank(s): %.2f" % (nr, common.loglog_slope(pts)))

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


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--csv", default=DEFAULT_CSV,
                   help="results file (default: %(default)s)")
    p.add_argument("--png", default=DEFAULT_PNG,
                   help="plot file (default: %(default)s)")
    p.add_argument("--table", action="store_true",
                   help="print the Markdown tables instead of plotting")
    a = p.parse_args()
    if not os.path.exists(a.csv):
        p.error("no results file %s" % a.csv)
    if a.table:
        table(a.csv)
    else:
        plot(a.csv, a.png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
