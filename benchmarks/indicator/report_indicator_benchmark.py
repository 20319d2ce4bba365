#!/usr/bin/python3
"""Plots and tables of the error indicator benchmark, from the CSVs that
run_indicator_benchmark.py and compare_builds.py write; runs nothing.

  report_indicator_benchmark.py            indicator_cost.png and
                                           effectivity.png from the CSVs
  report_indicator_benchmark.py --table    the tables of the README (cost,
                                           effectivity, breakdown)
  report_indicator_benchmark.py --outdir D the CSVs and plots in D
  report_indicator_benchmark.py --compare-builds CSV
                                           the table of compare_builds.py

Only the Python standard library and matplotlib are used.
"""

import argparse
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(
    __file__))))
import common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))

TARGET_FRACTION = 0.20
BAND = (0.7, 1.4)


def paths(outdir=HERE):
    """The CSVs and plots of the benchmark in 'outdir'."""
    return dict(cost_csv=os.path.join(outdir, "results_cost.csv"),
                eff_csv=os.path.join(outdir, "results_effectivity.csv"),
                breakdown_csv=os.path.join(outdir, "results_breakdown.csv"),
                cost_png=os.path.join(outdir, "indicator_cost.png"),
                eff_png=os.path.join(outdir, "effectivity.png"))


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


TEXT = ("series", "scene", "cell_type", "recovery", "status", "message",
        "reference", "correction_solver", "version", "command")
INTS = ("refinements", "subdivisions", "n_dofs", "newton_iterations")


def read_csv(path):
    return common.read_csv(path, text=TEXT, ints=INTS)


def fmt(v, f="%.4g"):
    if isinstance(v, float):
        return common.cell(v, f)
    return "" if v is None else str(v)


def ok_rows(rows, series, recovery=None):
    return sorted((r for r in rows if r["series"] == series and
                   r["status"] == "ok" and
                   (recovery is None or r["recovery"] == recovery)),
                  key=lambda r: r["n_dofs"])


def plot_cost(rows, path):
    plt = common.pyplot()
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
    plt = common.pyplot()
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


def compare_builds_table(path):
    """compare_builds.py's CSV: per mesh and build, the median indicator
    and contact-solve times, their ratio, and epsilon."""
    rows = read_csv(path)
    builds = list(dict.fromkeys(r["build"] for r in rows))
    meshes = list(dict.fromkeys(r["mesh"] for r in rows))
    lines = ["| mesh | DoFs | " + " | ".join(
        "%s indicator / solve [ms], fraction, epsilon" % b for b in builds)
        + " |", "|---|---|" + "---|" * len(builds)]
    for mesh in meshes:
        cells = []
        for b in builds:
            x = [r for r in rows if r["mesh"] == mesh and r["build"] == b]
            cells.append("%.2f / %.2f, %.1f %%, %.10g" % (
                1e3 * statistics.median(r["indicator_s"] for r in x),
                1e3 * statistics.median(r["contact_solve_s"] for r in x),
                100 * statistics.median(r["indicator_s"] /
                                        r["contact_solve_s"] for r in x),
                x[0]["epsilon"]))
        n_dofs = next(r["n_dofs"] for r in rows if r["mesh"] == mesh)
        lines.append("| %s | %d | %s |" % (mesh, n_dofs, " | ".join(cells)))
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--outdir", default=HERE,
                   help="directory of the CSVs and plots (default: "
                   "%(default)s)")
    p.add_argument("--table", action="store_true",
                   help="print the tables instead of plotting")
    p.add_argument("--compare-builds", metavar="CSV",
                   help="print the table of a compare_builds.py CSV")
    a = p.parse_args()
    if a.compare_builds:
        print(compare_builds_table(a.compare_builds))
        return 0
    f = paths(a.outdir)
    cost, eff = read_csv(f["cost_csv"]), read_csv(f["eff_csv"])
    breakdown = read_csv(f["breakdown_csv"])
    if not (cost or eff or breakdown):
        p.error("no results in %s" % a.outdir)
    if a.table:
        print(cost_table(cost))
        print()
        print(eff_table(eff))
        if breakdown:
            print()
            print(breakdown_table(breakdown))
        return 0
    if cost:
        plot_cost(cost, f["cost_png"])
    if eff:
        plot_effectivity(eff, f["eff_png"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
