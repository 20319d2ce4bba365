#!/usr/bin/python3
"""Table and plot of benchmarks/effectivity/results.csv (no runs):
theta = epsilon / epsilon_exact of zz, spr and cre per case and mesh, and
from cost.csv each estimator's cost relative to the contact solve.

    benchmarks/effectivity/report_effectivity.py [--csv results.csv] [--png effectivity.png]
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
import common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def report_cost(path):
    """Each estimator's wall time over the contact solve's, per case summed
    over its cycles (the same solutions)."""
    rows = common.read_csv(path, text=("case",), ints=("cycle", "n_dofs"))
    print()
    print("| case | largest DoFs | contact solve s | zz | spr | cre |")
    print("|---|---|---|---|---|---|")
    cases = []
    for r in rows:
        if r["case"] not in cases:
            cases.append(r["case"])
    for case in cases:
        mine = [r for r in rows if r["case"] == case]
        solve = sum(r["contact_solve_s"] or 0 for r in mine)
        ratios = []
        for e in ("zz", "spr", "cre"):
            t = sum(r[e + "_s"] or 0 for r in mine)
            ratios.append("%.2f×" % (t / solve) if solve > 0 else "")
        print("| %s | %d | %.3f | %s | %s | %s |" % (
            case, max(r["n_dofs"] for r in mine), solve, *ratios))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--csv", default=os.path.join(HERE, "results.csv"))
    parser.add_argument("--png", default=os.path.join(HERE, "effectivity.png"))
    parser.add_argument("--cost-csv", default=os.path.join(HERE, "cost.csv"))
    args = parser.parse_args()
    rows = common.read_csv(args.csv, text=("case", "estimator", "reference"),
                           ints=("cycle", "n_dofs"))
    if not rows:
        sys.exit("report_effectivity: no rows in " + args.csv)
    # θ against the exact error extrapolated over the reference's levels
    # (the computed exact error alone, in brackets, is low by the
    # reference's own error).
    print("| case | DoFs | exact ε extrapolated (against the reference) "
          "| θ zz | θ spr | θ cre | reference |")
    print("|---|---|---|---|---|---|---|")
    keys = []
    for r in rows:
        if (r["case"], r["cycle"]) not in keys:
            keys.append((r["case"], r["cycle"]))
    for case, cycle in keys:
        by = {r["estimator"]: r for r in rows
              if r["case"] == case and r["cycle"] == cycle}
        any_row = next(iter(by.values()))
        print("| %s | %d | %.3f %% (%.3f %%) | %s | %s | %s | %s |" % (
            case, any_row["n_dofs"],
            100 * any_row["epsilon_exact_extrapolated"],
            100 * any_row["epsilon_exact"],
            *["%.2f (%.2f)" % (by[e]["effectivity_extrapolated"],
                               by[e]["effectivity"]) if e in by else ""
              for e in ("zz", "spr", "cre")], any_row["reference"]))

    if os.path.exists(args.cost_csv):
        report_cost(args.cost_csv)

    plt = common.pyplot()
    cases = []
    for case, _ in keys:
        if case not in cases:
            cases.append(case)
    figure, axes = plt.subplots(1, 3, figsize=(13, 5.2), sharey=True)
    # One colour per case (more cases than the default cycle's 10 colours);
    # degree 2 dashed with squares, so the two degrees tell apart.
    colours = plt.get_cmap("tab20").colors
    for axis, estimator in zip(axes, ("zz", "spr", "cre")):
        for i, case in enumerate(cases):
            points = [(r["n_dofs"], r["effectivity_extrapolated"])
                      for r in rows
                      if r["case"] == case and r["estimator"] == estimator]
            degree_2 = " P2" in case or " Q2" in case
            if points:
                axis.semilogx(*zip(*points), "s--" if degree_2 else "o-",
                              color=colours[i % len(colours)], label=case)
        axis.axhline(1, color="grey", linewidth=0.8)
        axis.axhline(2, color="grey", linewidth=0.8, linestyle=":")
        axis.set_title(estimator)
        axis.set_xlabel("DoFs")
    axes[0].set_ylabel("θ = ε / ε_exact (extrapolated)")
    handles, labels = axes[2].get_legend_handles_labels()
    figure.legend(handles, labels, loc="lower center", ncol=4, fontsize=7)
    figure.tight_layout(rect=(0, 0.2, 1, 1))
    figure.savefig(args.png, dpi=110)
    print("wrote " + args.png)


if __name__ == "__main__":
    main()
