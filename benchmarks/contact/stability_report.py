#!/usr/bin/python3
"""The generated part of stability.md, from the CSV of stability_sweep.py
(which calls it at the end of a sweep); runs nothing.

  stability_report.py                   rewrites the block between the
                                        GENERATED markers of stability.md
                                        from stability.csv
  stability_report.py --csv C --markdown M   other files (M is created if
                                        missing)
  stability_report.py --print           print the block instead

The case parameters come from stability_cases.py (matched by id, checked
against the command line of each row); the sweep's date, run time, binary
and machine from stability_run.json next to the CSV.
"""

import argparse
import csv
import json
import os
import shlex
import sys

from stability_cases import (C_SCALES, E_RATIOS, LOAD_SCALES, MESH_RATIOS,
                             MUS, NUS, build_cases, describe, overrides)

HERE = os.path.dirname(os.path.abspath(__file__))
CSV_PATH = os.path.join(HERE, "stability.csv")
MARKDOWN_PATH = os.path.join(HERE, "stability.md")

# Result columns of stability.csv and how to read them back.
INTS = ("newton_iterations", "active_nodes", "stick_nodes", "slip_nodes",
        "n_slave_nodes", "n_dofs", "steps_run", "n_uncovered", "n_nan")
FLOATS = ("contact_fx", "contact_fy", "equilibrium_error",
          "max_contact_pressure", "final_residual", "wall_time_s")
OPTIONAL_FLOATS = ("p_max_over_hertz_p0", "rel_diff_to_ref", "hertz_p0")
TEXTS = ("csv_check", "warning", "ref_case", "signature", "nan", "verdict",
         "diagnosis", "binary_sha", "version", "command")


def run_info_path(csv_path):
    return os.path.splitext(csv_path)[0] + "_run.json"


def read_results(path):
    """The records of a sweep: each case of stability_cases.py joined with
    its row of the CSV."""
    cases = {c["id"]: c for c in build_cases()}
    recs = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            case = cases.get(row["id"])
            if case is None or not set(overrides(case)) <= set(
                    shlex.split(row["command"])):
                raise SystemExit(
                    "%s: the row of case %s does not match case %s of "
                    "stability_cases.py (the case list changed since the "
                    "sweep): run the sweep again" % (path, row["id"],
                                                     row["id"]))
            rec = dict(case)
            for k in INTS:
                rec[k] = int(row[k]) if row[k] != "" else None
            for k in FLOATS:
                rec[k] = float(row[k]) if row[k] != "" else None
            for k in OPTIONAL_FLOATS:
                rec[k] = float(row[k]) if row.get(k, "") != "" else ""
            for k in TEXTS:
                rec[k] = row[k]
            rec["exit_code"] = int(row["exit_code"]) if row["exit_code"] \
                .lstrip("-").isdigit() else row["exit_code"]
            rec["converged"] = row["converged"] == "True"
            rec["same_sets_as_ref"] = {"True": True, "False": False}.get(
                row["same_sets_as_ref"], "")
            recs.append(rec)
    return recs


def fmt(x, spec="%.1e"):
    if x is None or x == "":
        return "–"
    return spec % x


def short_diag(d, n=150):
    d = d.replace("|", "\\|")
    return d if len(d) <= n else d[:n - 1] + "…"


def table(recs, with_ref=False):
    head = ("| id | case | exit | conv | it | act/stick/slip | eq. err "
            "| p_max | " + ("sets = ref, Δ | " if with_ref else "") +
            "time s | verdict / diagnosis |")
    sep = "|" + "---|" * (head.count("|") - 1)
    lines = [head, sep]
    for r in recs:
        d = r["verdict"]
        if r["diagnosis"]:
            d += ": " + short_diag(r["diagnosis"])
        refcol = ""
        if with_ref:
            if r["ref_case"]:
                refcol = "%s, %s | " % ("yes" if r["same_sets_as_ref"] else
                                        "**no**", fmt(r["rel_diff_to_ref"]))
            else:
                refcol = "– | "
        ass = ("%s/%s/%s" % (r["active_nodes"], r["stick_nodes"],
                             r["slip_nodes"]) if r["converged"] else "–")
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s%.2f | %s |"
                     % (r["id"], describe(r), r["exit_code"],
                        "yes" if r["converged"] else "no",
                        r["newton_iterations"] if r["converged"]
                        else r["steps_run"], ass,
                        fmt(r["equilibrium_error"]),
                        fmt(r["max_contact_pressure"], "%.4g"), refcol,
                        r["wall_time_s"], d))
    return "\n".join(lines)


def grid_table(recs, rows, cols, rowkey, colkey, rowlab, collab, sel):
    """Newton iterations per cell; F = stopped (see the case list)."""
    idx = {}
    for r in recs:
        if sel(r):
            idx[(r[rowkey], r[colkey])] = r
    lines = ["| %s \\ %s | %s |" % (rowlab, collab,
                                   " | ".join("%g" % c if not isinstance(c, str)
                                              else c for c in cols)),
             "|" + "---|" * (len(cols) + 1)]
    for rv in rows:
        cells = []
        for cv in cols:
            r = idx.get((rv, cv))
            if r is None:
                cells.append("")
            elif r["verdict"].startswith("BUG"):
                cells.append("**BUG %s**" % r["id"])
            elif r["converged"]:
                cells.append(str(r["newton_iterations"]))
            else:
                cells.append("F (%s)" % r["id"])
        lines.append("| %g | %s |" % (rv, " | ".join(cells)))
    return "\n".join(lines)


def markdown(recs, info):
    L = []
    L.append("Generated by `stability_sweep.py` on %s: %d runs, %.0f s of "
             "run time in total, binary `%s` (sha256 %s), version `%s`."
             % (info["date"], len(recs), info["total"], info["binary"],
                ", ".join(sorted(set(r["binary_sha"] for r in recs))),
                ", ".join(sorted(set(r.get("version") for r in recs
                                     if r.get("version"))))))
    L.append("")
    n_ok = sum(r["verdict"].startswith("ok") for r in recs)
    n_diag = sum(r["verdict"].startswith("diagnosed") for r in recs)
    n_bug = sum(r["verdict"].startswith("BUG") for r in recs)
    n_sus = sum(r["verdict"].startswith("SUSPECT") for r in recs)
    n_nan = sum(bool(r["n_nan"]) for r in recs)
    conv = [r for r in recs if r["converged"]]
    its = sorted(r["newton_iterations"] for r in conv)
    eq = [r["equilibrium_error"] for r in conv
          if r["equilibrium_error"] is not None]
    L.append("**Totals.** %d converged, %d stopped with a diagnosis "
             "(%d of them expected), %d converged but suspect, %d flagged as "
             "bugs, %d with NaN/Inf in "
             "any output. Newton iterations of the converged runs: median %s, "
             "max %s. Largest equilibrium error of a converged run: %s."
             % (n_ok, n_diag,
                sum(r["verdict"] == "diagnosed (expected)" for r in recs),
                n_sus, n_bug, n_nan, its[len(its) // 2] if its else "–",
                its[-1] if its else "–", fmt(max(eq) if eq else None)))
    hist = {}
    for i in its:
        hist[i] = hist.get(i, 0) + 1
    L.append("")
    L.append("Newton iterations of the converged runs (iterations: runs): " +
             ", ".join("%d: %d" % kv for kv in sorted(hist.items())) + ".")
    L.append("")
    L.append("Machine: " + info["machine"] + ".")
    L.append("")
    L.append("Columns: *exit* exit code; *conv* `converged`; *it* Newton "
             "iterations; *act/stick/slip* node counts at convergence; "
             "*eq. err* |F_contact + F_applied| / |F_applied|; *p_max* "
             "largest contact pressure (MPa); *sets = ref, Δ* (load and c "
             "sweeps): same node-wise contact sets as the same case at load "
             "×1, c ×1, and the largest difference of the load-normalised "
             "pressure, tangential traction and slip relative to it; "
             "*verdict*: ok, diagnosed (exit 1 with a message), or BUG (NaN, "
             "crash, timeout, exit 0 without convergence, exit ≠ 0 without a "
             "message, equilibrium error > 1e-6, or a converged result whose "
             "contact CSV violates the contact conditions: penetration "
             "beyond 1e-6 of |load|/min E, negative pressure, traction "
             "outside the cone, all on *covered* nodes: those whose normal "
             "ray meets body 2's contact boundary); SUSPECT (converged, but "
             "an uncovered node moved along its normal further than its "
             "distance to body 2). *it* of a stopped run: the Newton steps it "
             "made. The case column lists what "
             "differs from the base case.")
    L.append("")

    def sel_group(g):
        return [r for r in recs if g in r["groups"]]

    L.append("### One at a time around the base case (blocks)")
    L.append("")
    L.append(table(sel_group("oat"), with_ref=True))
    L.append("")
    L.append("### Grid μ × ν × E1/E2 (blocks; Newton iterations, F = stopped)")
    L.append("")
    for ratio in E_RATIOS:
        L.append("E1/E2 = %g:" % ratio)
        L.append("")
        L.append(grid_table(recs, MUS, NUS, "mu", "nu1", "μ", "ν",
                            lambda r, ratio=ratio: "grid mu x nu x E1/E2" in
                            r["groups"] and r["E1"] / r["E2"] == ratio))
        L.append("")
    L.append("### Grid μ × c scale (blocks; Newton iterations)")
    L.append("")
    L.append(grid_table(recs, MUS, C_SCALES, "mu", "c", "μ", "c scale",
                        lambda r: "grid mu x c" in r["groups"]))
    L.append("")
    L.append("### Grid μ × load scale (blocks; Newton iterations)")
    L.append("")
    L.append(grid_table(recs, MUS, LOAD_SCALES, "mu", "load_scale", "μ",
                        "load ×", lambda r: "grid mu x load" in r["groups"]))
    L.append("")
    L.append("### Grid μ × mesh ratio (lower nx/2 : upper nx) (blocks; Newton "
             "iterations)")
    L.append("")
    L.append(grid_table(recs, MUS, list(MESH_RATIOS), "mu", "mesh", "μ",
                        "ratio", lambda r: "grid mu x mesh ratio" in
                        r["groups"]))
    L.append("")
    L.append("### Homogeneity and c-scale independence (all grid cases)")
    L.append("")
    for label, key in (("load scale", "load_scale"), ("c scale", "c")):
        sub = [r for r in recs if r["ref_case"] and r[key] != 1.0
               and r["scene"] == "blocks"]
        same = sum(1 for r in sub if r["same_sets_as_ref"])
        worst = max((r["rel_diff_to_ref"] for r in sub), default=None)
        diff_sets = [r["id"] for r in sub if not r["same_sets_as_ref"]]
        L.append("- %s ≠ 1: %d converged cases compared with their ×1 "
                 "reference, %d with identical node-wise sets%s; largest "
                 "relative difference of the normalised pressure / traction "
                 "/ slip %s." % (label, len(sub), same,
                                 (" (different: %s)" % ", ".join(diff_sets))
                                 if diff_sets else "", fmt(worst)))
    L.append("")
    L.append("### Combined extremes (blocks)")
    L.append("")
    L.append(table(sel_group("extreme"), with_ref=True))
    L.append("")
    L.append("### Inputs that must stop with a diagnosis")
    L.append("")
    L.append(table(sel_group("diagnosis")))
    L.append("")
    L.append("### Follow-ups of the failures")
    L.append("")
    L.append(table(sel_group("follow-up"), with_ref=True))
    L.append("")
    L.append("### Hertz subset")
    L.append("")
    hz = sel_group("hertz")
    L.append(table(hz, with_ref=True))
    L.append("")
    L.append("p_max / Hertz p0 of the converged Hertz runs: " + ", ".join(
        "%s: %.3f" % (r["id"], r["p_max_over_hertz_p0"]) for r in hz
        if r["converged"] and r["p_max_over_hertz_p0"] != ""))
    L.append("")
    bad = [r for r in recs if not r["verdict"].startswith("ok")]
    L.append("### Every run that did not end ok")
    L.append("")
    L.append("| id | case | exit | steps | verdict | diagnosis (stderr, full) |")
    L.append("|---|---|---|---|---|---|")
    for r in bad:
        L.append("| %s | %s | %s | %s | %s | %s |" % (
            r["id"], describe(r), r["exit_code"],
            r["newton_iterations"] if r["converged"] else r["steps_run"],
            r["verdict"], short_diag(r["diagnosis"], 10000)))
    L.append("")
    nanr = [r for r in recs if r["n_nan"]]
    L.append("### NaN / Inf scan")
    L.append("")
    L.append("Scanned: stdout, stderr, every value of summary.json (nlohmann "
             "writes NaN as null), every value of contact_000.csv "
             "(present for %d of %d runs: a failed run writes none). "
             % (sum(1 for r in recs if r["n_slave_nodes"]), len(recs)) +
             ("Found in: " + "; ".join("%s (%s)" % (r["id"], r["nan"])
                                       for r in nanr) if nanr else
              "**None found.**"))
    return "\n".join(L)


BEGIN = "<!-- BEGIN GENERATED by stability_sweep.py -->"
END = "<!-- END GENERATED -->"


def write_markdown(path, body):
    text = ""
    if os.path.exists(path):
        with open(path) as f:
            text = f.read()
    block = BEGIN + "\n\n" + body + "\n\n" + END
    if BEGIN in text and END in text:
        pre = text.split(BEGIN)[0]
        post = text.split(END, 1)[1]
        text = pre + block + post
    else:
        text = "# Contact solver stability sweep\n\n" + block + "\n"
    with open(path, "w") as f:
        f.write(text)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--csv", default=CSV_PATH)
    p.add_argument("--markdown", default=MARKDOWN_PATH)
    p.add_argument("--print", action="store_true",
                   help="print the generated block, write nothing")
    a = p.parse_args()
    if not os.path.exists(a.csv):
        p.error("no results file %s" % a.csv)
    recs = read_results(a.csv)
    try:
        with open(run_info_path(a.csv)) as f:
            info = json.load(f)
    except OSError:
        info = dict(date="(date not recorded)", binary="(not recorded)",
                    machine="not recorded",
                    total=sum(r["wall_time_s"] or 0 for r in recs))
    body = markdown(recs, info)
    if a.print:
        print(body)
    else:
        write_markdown(a.markdown, body)
    return 0


if __name__ == "__main__":
    sys.exit(main())
