#!/usr/bin/python3
"""Plots and tables of the work-precision benchmark, from the CSV that
run_work_precision.py writes; runs nothing.

  report_work_precision.py              work_precision_<scene>.png and
                                        exact_error_blocks.png from
                                        results.csv
  report_work_precision.py --table      the tables of the README
  report_work_precision.py --csv C --outdir D   another CSV, plots in D

Uniform refinement that does not reach epsilon_0 is extrapolated from its
last three cycles (see extrapolate_uniform). Only the Python standard
library and matplotlib are used.
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(
    __file__))))
import common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
CSV_PATH = os.path.join(HERE, "results.csv")

SCENE_TARGET = {"blocks": 1.0, "hertz": 2.0, "punch": 2.0}

TEXT = {"part", "run", "role", "scene", "series", "strategy", "cell_type",
        "criterion", "stop_reason", "status", "message", "version",
        "command"}
INTS = {"degree", "cycle", "n_dofs", "n_cells", "n_cells_1", "n_cells_2",
        "newton_iterations", "warm_start", "warm_start_param",
        "reference_refinements", "repeats"}


def read_csv(path=CSV_PATH):
    return common.read_csv(path, text=TEXT, ints=INTS)


def runs_of(rows):
    """{run: [cycle rows sorted by cycle]} for the ok runs."""
    out = {}
    for r in rows:
        if r["status"] == "ok" and r["cycle"] != "":
            out.setdefault(r["run"], []).append(r)
    for v in out.values():
        v.sort(key=lambda r: r["cycle"])
    return out


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
    plt = common.pyplot()
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
    plt = common.pyplot()
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


def plot_all(rows, outdir=HERE):
    scenes = {r["scene"] for r in rows if r["part"] in
              ("blocks", "hertz", "punch")}
    for s in sorted(scenes):
        plot_scene(rows, s, os.path.join(outdir, "work_precision_%s.png" % s))
    if any(r["part"] == "exact" for r in rows):
        plot_exact(rows, os.path.join(outdir, "exact_error_blocks.png"))


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


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--csv", default=CSV_PATH)
    p.add_argument("--outdir", default=HERE, help="directory of the plots")
    p.add_argument("--table", action="store_true",
                   help="print the tables instead of plotting")
    a = p.parse_args()
    rows = read_csv(a.csv)
    if not rows:
        p.error("no results in %s" % a.csv)
    if a.table:
        print(tables(rows))
    else:
        plot_all(rows, a.outdir)
    return 0


if __name__ == "__main__":
    sys.exit(main())
