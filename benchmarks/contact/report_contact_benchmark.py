#!/usr/bin/python3
"""Plot and tables of the contact benchmark, from the CSV that
run_contact_benchmark.py writes; runs nothing.

  report_contact_benchmark.py                  contact_timings.png from
                                               results.csv
  report_contact_benchmark.py --table          the tables of the README
                                               (with a cold-vs-nested
                                               comparison)
  report_contact_benchmark.py --csv C --png P  another CSV, another plot
  report_contact_benchmark.py --solver-table DIRECT_CSV AMG_CSV PNG
                                               direct against Krylov + AMG
                                               (runs made with
                                               --linear-solver direct / amg)

The elastic references of the contact rows (interpolated in
benchmarks/elasticity/results.csv where not measured) are recomputed from
the CSVs.
"""

import argparse
import csv
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(
    __file__))))
import common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_CSV = os.path.join(HERE, "results.csv")
DEFAULT_PNG = os.path.join(HERE, "contact_timings.png")
ELASTICITY_CSV = os.path.join(common.ROOT, "benchmarks", "elasticity",
                              "results.csv")

SERIES = [("blocks", 0.0), ("blocks", 0.3), ("hertz", 0.0), ("hertz", 0.3)]
STARTS = ("cold", "nested")
TEXT = ("kind", "scene", "status", "elastic_ref_source", "linear_solver",
        "version", "message", "start", "nested_levels_setting",
        "nested_status", "coarse_levels", "coarse_newton_by_level")
INTS = ("subdivisions", "refinements", "n_dofs", "n_dofs_body1",
        "n_dofs_body2", "newton_iterations")


def num(x, fmt="%.6g"):
    if x is None or x == "" or (isinstance(x, float) and math.isnan(x)):
        return ""
    return fmt % x


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


def read_csv(path):
    rows = common.read_csv(path, text=TEXT, ints=INTS)
    for r in rows:
        if r.get("subdivisions") in ("", None) and r["scene"] != "hertz":
            r["subdivisions"] = 4
        # rows of builds before nested iteration: cold start
        if r["kind"] == "contact" and not r.get("start"):
            r["start"] = "cold"
        if r["kind"] == "elastic":
            r["start"] = ""
    return rows


def label(scene, mu):
    return "%s, μ = %g" % (scene, mu)


def plot(rows, path):
    import matplotlib.ticker
    plt = common.pyplot()

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
    shared = sorted(set(direct) & set(amg),
                    key=lambda k: (k[0], k[1], direct[k]["n_dofs"]))
    lines = ["| scene | μ | mesh | DoFs | Newton its (direct / amg) | "
             "Krylov its (last step) | step direct [s] | step amg [s] | "
             "step direct / amg | contact solve direct / amg [s] | "
             "peak mem direct / amg [MiB] |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for k in shared:
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

    plt = common.pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.3))
    styles = {("blocks", 0.0): ("C0", "o"), ("blocks", 0.3): ("C1", "s"),
              ("hertz", 0.0): ("C2", "^"), ("hertz", 0.3): ("C3", "D")}
    for scene, mu in SERIES:
        ks = [k for k in shared if k[0] == scene and k[1] == mu]
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



def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--csv", default=DEFAULT_CSV)
    p.add_argument("--png", default=DEFAULT_PNG)
    p.add_argument("--table", action="store_true",
                   help="print the tables instead of plotting")
    p.add_argument("--solver-table", nargs=3,
                   metavar=("DIRECT_CSV", "AMG_CSV", "PNG"),
                   help="compare runs with --linear-solver direct and amg: "
                   "print a table, draw PNG")
    a = p.parse_args()
    if a.solver_table:
        print(solver_comparison(*a.solver_table))
        return 0
    if not os.path.exists(a.csv):
        p.error("no results file %s" % a.csv)
    rows = read_csv(a.csv)
    fill_references(rows, single_body_curve())
    if a.table:
        print(table(rows))
        print()
        print(elastic_table(rows))
        print()
        print(summary_table(rows))
        print()
        print(compare_table(rows))
    else:
        plot(rows, a.png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
