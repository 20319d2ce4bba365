#!/usr/bin/python3
"""Numerical stress test of the contact solver (semismooth Newton / PDAS).

Runs build/coulomb-adapt on the `blocks` scene over one-at-a-time variations
around a base case, a few parameter grids and combined extreme cases, plus a
subset on the `hertz` scene and a set of inputs that must stop with a
diagnosis. Every case must either converge or exit non-zero with a
diagnosis; no output may contain NaN/Inf.

The cases are defined in stability_cases.py. Writes (next to this script
unless told otherwise):
  stability.csv       one row per case
  stability_run.json  date, run time, binary and machine of the sweep
  stability.md        the block between the GENERATED markers is
                      (re)written by stability_report.py; the hand-written
                      text around it is kept.

Usage:
  benchmarks/contact/stability_sweep.py [--binary build/coulomb-adapt]
      [--workdir /tmp/coulomb-stability] [--jobs 1] [--groups a,b]
      [--cases 000,001] [--keep-vtu] [--no-markdown]
  benchmarks/contact/stability_sweep.py --smoke --outdir DIR
      the base case and one input that must stop (a few seconds; ctest)

Standard library only.
"""

import argparse
import concurrent.futures
import csv
import datetime
import hashlib
import json
import math
import os
import re
import shlex
import shutil
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(
    __file__))))
import common  # noqa: E402
import stability_report as report  # noqa: E402
from stability_cases import (BLOCKS_BASE, MESH_RATIOS,  # noqa: E402
                             applied_load, build_cases, describe,
                             existence_bound, held_sideways, hertz_reference,
                             overrides, overrides_hold)

HERE = os.path.dirname(os.path.abspath(__file__))


# --------------------------------------------------------------------------
# running and reading one case

NAN_RE = re.compile(r"(?i)(?<![a-z])-?(nan|inf|infinity)(?![a-z])")


def file_sha(path):
    """sha256 of the program and, if present, the project library next to
    it (the program links it dynamically)."""
    h = hashlib.sha256()
    for p in (path, os.path.join(os.path.dirname(path),
                                 "libcoulomb_adapt.so")):
        if not os.path.exists(p):
            continue
        with open(p, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                h.update(block)
    return h.hexdigest()[:12]


def read_contact_csv(path):
    """Rows of contact_000.csv; values as float where possible."""
    rows, bad = [], []
    with open(path) as f:
        for i, row in enumerate(csv.DictReader(f)):
            r = {}
            for k, v in row.items():
                if k == "status":
                    r[k] = v
                    continue
                try:
                    x = float(v)
                except ValueError:
                    x = float("nan")
                if not math.isfinite(x):
                    bad.append("contact_000.csv row %d %s=%s" % (i, k, v))
                r[k] = x
            rows.append(r)
    return rows, bad


def json_nonfinite(obj, where="summary.json"):
    """nlohmann::json writes NaN/Inf as null: report nulls and non-finite."""
    bad = []
    if isinstance(obj, dict):
        for k, v in obj.items():
            bad += json_nonfinite(v, where + "." + k)
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            bad += json_nonfinite(v, "%s[%d]" % (where, i))
    elif obj is None:
        bad.append(where + "=null")
    elif isinstance(obj, float) and not math.isfinite(obj):
        bad.append(where + "=" + repr(obj))
    return bad


def check_rows(rows, case):
    """Discrete contact conditions read back from contact_000.csv:
    no penetration (gap >= 0 up to 1e-6 of the displacement scale
    |load| / min E), pressure >= 0 and |traction| <= mu pressure (up to
    1e-6 of the largest pressure), nothing on open nodes."""
    u_ref = math.hypot(*applied_load(case)) / min(case["E1"], case["E2"])
    p_max = max([abs(r["contact_pressure"]) for r in rows] + [1e-300])
    out = []
    covered = [r for r in rows if r["covered"]]
    pen = [r for r in covered if r["gap"] < -1e-6 * u_ref]
    if pen:
        worst = min(pen, key=lambda r: r["gap"])
        out.append("penetration at %d %s node(s), worst gap %.3g mm at "
                   "(%.4g, %.4g) (displacement scale %.3g mm)"
                   % (len(pen), "/".join(sorted(set(r["status"] for r in pen))),
                      worst["gap"], worst["x"], worst["y"], u_ref))
    neg = [r for r in rows if r["contact_pressure"] < -1e-6 * p_max]
    if neg:
        out.append("negative pressure at %d node(s)" % len(neg))
    cone = [r for r in rows if abs(r["tangential_traction"]) >
            case["mu"] * max(r["contact_pressure"], 0) + 1e-6 * p_max]
    if cone:
        out.append("traction outside the friction cone at %d node(s)"
                   % len(cone))
    return "; ".join(out)


def master_plane(case):
    """(y, x_min, x_max) of body 2's straight contact boundary."""
    if case["scene"] == "blocks":
        return 200.0, 0.0, 200.0
    return 0.0, -100.0, 100.0     # hertz, default Block width 200


def mark_coverage(rows, case):
    """A slave node is covered when the ray along its normal meets body 2's
    contact boundary strictly inside (a node whose ray ends at the corner of
    body 2 counts as uncovered). For an uncovered node the program's
    weighted initial gap is 0, so its CSV 'gap' is just -u1.n; 'reach' is
    the distance along the normal to the plane of body 2's boundary."""
    ym, x0, x1 = master_plane(case)
    eps = 1e-6 * (x1 - x0)
    for r in rows:
        nx, ny = r["normal_x"], r["normal_y"]
        if ny >= 0:
            r["covered"], r["reach"] = False, float("inf")
            continue
        t = (ym - r["y"]) / ny
        xp = r["x"] + t * nx
        r["covered"] = x0 + eps < xp < x1 - eps
        r["reach"] = t


def uncovered_warning(rows):
    """Uncovered nodes whose normal displacement exceeds their distance to
    the plane of body 2: they may have passed through body 2 unnoticed."""
    far = [r for r in rows if not r["covered"] and -r["gap"] > r["reach"]]
    if not far:
        return ""
    worst = max(far, key=lambda r: -r["gap"] - r["reach"])
    return ("%d uncovered node(s) moved further along their normal than "
            "their distance to body 2 (possible undetected penetration), "
            "worst at (%.4g, %.4g): u.n = %.3g mm, distance %.3g mm"
            % (len(far), worst["x"], worst["y"], -worst["gap"],
               worst["reach"]))


def signature(rows, mu):
    """o open, t stick, +/- slip in the direction of the tangential
    traction (frictionless: s, the traction is round-off)."""
    s = ""
    for r in rows:
        st = r["status"]
        if st == "open":
            s += "o"
        elif st == "stick":
            s += "t"
        elif mu == 0:
            s += "s"
        else:
            s += "+" if r["tangential_traction"] >= 0 else "-"
    return s


def run_case(case, binary, workdir, keep_vtu, timeout):
    out = os.path.join(workdir, "case_" + case["id"])
    if os.path.isdir(out):
        shutil.rmtree(out)
    # Write VTU must be on: it also writes contact_000.csv.
    args = [binary]
    for o in overrides(case) + ["Output/Write VTU=true",
                                "Output/Output directory=" + out]:
        args += ["-s", o]
    rec = dict(case)
    rec["command"] = " ".join(shlex.quote(a) for a in args)
    env = common.program_env(binary)
    for attempt in range(4):
        result = common.run(args, timeout, env, cwd=common.ROOT)
        rec["exit_code"] = "timeout" if result.killed else result.rc
        rec["wall_time_s"] = result.wall_s
        stdout = result.stdout
        stderr = ("TIMEOUT after %g s" % timeout if result.killed
                  else result.stderr)
        # 127: the loader failed, i.e. the program is being rebuilt (another
        # engineer); wait and run again.
        if rec["exit_code"] != 127:
            break
        time.sleep(30)
    rec["binary_sha"] = file_sha(binary)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "stdout.txt"), "w") as f:
        f.write(stdout)
    with open(os.path.join(out, "stderr.txt"), "w") as f:
        f.write(stderr)
    rec["diagnosis"] = " ".join(stderr.replace("coulomb-adapt: error: ", "")
                                .split())
    nan = []
    for name, text in (("stdout", stdout), ("stderr", stderr)):
        for m in NAN_RE.finditer(text):
            nan.append("%s: ...%s..." % (name, text[max(0, m.start() - 40):
                                                     m.end() + 10]))
    summary_path = os.path.join(out, "summary.json")
    cyc = None
    if os.path.exists(summary_path):
        summary = common.read_summary(out)
        if summary is None:
            nan.append("summary.json unreadable")
        else:
            nan += json_nonfinite(summary)
            rec["version"] = summary.get("version", "")
            cyc = common.last_cycle(summary)
    rows = []
    csv_path = os.path.join(out, "contact_000.csv")
    if os.path.exists(csv_path):
        rows, bad = read_contact_csv(csv_path)
        nan += bad
    rec["nan"] = "; ".join(nan[:5]) + (" (+%d more)" % (len(nan) - 5)
                                        if len(nan) > 5 else "")
    rec["n_nan"] = len(nan)
    rec["converged"] = bool(cyc and cyc.get("converged"))
    for k in ("newton_iterations", "active_nodes", "stick_nodes",
              "slip_nodes", "max_contact_pressure", "n_dofs"):
        rec[k] = cyc.get(k) if cyc else None
    rec["final_residual"] = (cyc["residual_history"][-1]
                             if cyc and cyc.get("residual_history") else None)
    load = applied_load(case)
    if cyc and cyc.get("contact_force") and None not in cyc["contact_force"]:
        fx, fy = cyc["contact_force"]
        rec["contact_fx"], rec["contact_fy"] = fx, fy
        nl = math.hypot(*load)
        # A symmetry line holding body 1 sideways takes a horizontal
        # reaction where the mesh is not symmetric (gmsh triangles): only
        # the vertical balance is the contact's alone.
        ex = 0.0 if held_sideways(case) else fx + load[0]
        rec["equilibrium_error"] = (math.hypot(ex, fy + load[1]) / nl
                                    if nl > 0 else None)
    else:
        rec["contact_fx"] = rec["contact_fy"] = rec["equilibrium_error"] = None
    # A run that stopped has no cycle in summary.json: its Newton steps are
    # only in the log.
    rec["steps_run"] = common.newton_steps_run(stdout)
    rec["n_slave_nodes"] = len(rows)
    if rows:
        mark_coverage(rows, case)
    rec["n_uncovered"] = sum(1 for r in rows if not r["covered"])
    rec["csv_check"] = check_rows(rows, case) if rows else ""
    rec["warning"] = uncovered_warning(rows) if rows else ""
    rec["signature"] = signature(rows, case["mu"]) if rows else ""
    rec["_rows"] = rows
    if case["scene"] == "hertz":
        a, p0 = hertz_reference(case)
        rec["hertz_p0"] = p0
        rec["hertz_a"] = a
    if not keep_vtu:
        for fn in os.listdir(out):
            if fn.endswith((".vtu", ".pvtu", ".pvd")):
                os.remove(os.path.join(out, fn))
    return rec


# --------------------------------------------------------------------------
# checks across cases

# --------------------------------------------------------------------------
# checks across cases

def compare(rec, ref):
    """Same contact sets? Largest difference of the load-normalised
    pressure, tangential traction and slip, relative to the reference."""
    if not rec["_rows"] or not ref["_rows"] or \
            len(rec["_rows"]) != len(ref["_rows"]):
        return None, None
    same = rec["signature"] == ref["signature"]
    L, Lr = rec["load_scale"], ref["load_scale"]
    # Tractions relative to the largest reference pressure, slips relative
    # to the displacement scale |load| / min E (both per unit load scale;
    # E is the same within the comparisons here).
    p_scale = max(abs(r["contact_pressure"]) / Lr for r in ref["_rows"])
    u_scale = (math.hypot(*applied_load(ref)) / Lr /
               min(ref["E1"], ref["E2"]))
    worst = 0.0
    for key, scale in (("contact_pressure", p_scale),
                       ("tangential_traction", p_scale), ("slip", u_scale)):
        a = [r[key] / L for r in rec["_rows"]]
        b = [r[key] / Lr for r in ref["_rows"]]
        worst = max(worst, max(abs(x - y) for x, y in zip(a, b)) / scale)
    return same, worst


def verdict(rec):
    problems = []
    if rec["n_nan"]:
        problems.append("NaN/Inf in output")
    code = rec["exit_code"]
    if code == "timeout":
        problems.append("timeout")
    elif code == 0:
        if not rec["converged"]:
            problems.append("exit 0 but not converged")
        if rec["equilibrium_error"] is None or rec["equilibrium_error"] > 1e-6:
            problems.append("equilibrium error")
        if rec["csv_check"]:
            problems.append("converged, but " + rec["csv_check"])
    else:
        if code < 0 or code > 1:
            problems.append("crash (exit %s)" % code)
        if not rec["diagnosis"]:
            problems.append("no diagnosis")
        if rec["converged"]:
            problems.append("non-zero exit but converged")
    if problems:
        return "BUG: " + ", ".join(problems)
    if rec["warning"] and code == 0:
        return "SUSPECT: converged, but " + rec["warning"]
    if code == 0:
        return "ok (expected a stop)" if rec["expect"] == "diagnose" else "ok"
    return ("diagnosed (expected)" if rec["expect"] == "diagnose"
            else "diagnosed")


def postprocess(recs):
    by_key = {}
    for r in recs:
        k = dict(r)
        by_key[tuple(sorted((kk, str(vv)) for kk, vv in k.items()
                            if kk in BLOCKS_BASE))] = r

    def find(r, **changes):
        k = {kk: r[kk] for kk in BLOCKS_BASE}
        k.update(changes)
        return by_key.get(tuple(sorted((kk, str(vv)) for kk, vv in k.items())))

    for r in recs:
        r["ref_case"] = ""
        r["same_sets_as_ref"] = ""
        r["rel_diff_to_ref"] = ""
        if r["expect"] == "diagnose" or not r["converged"]:
            continue
        # reference: same case with load scale 1 and c scale 1
        if r["load_scale"] == 1.0 and r["c"] == 1.0:
            continue
        ref = find(r, load_scale=1.0, c=1.0)
        if ref is None or ref is r or not ref["converged"]:
            continue
        if r["scene"] == "hertz" and r["load_scale"] != 1.0:
            continue        # Hertz is not homogeneous in the load
        same, diff = compare(r, ref)
        r["ref_case"] = ref["id"]
        r["same_sets_as_ref"] = same
        r["rel_diff_to_ref"] = diff
        if r["scene"] == "hertz":
            pass
    for r in recs:
        r["verdict"] = verdict(r)
        if r["scene"] == "hertz" and r.get("max_contact_pressure"):
            r["p_max_over_hertz_p0"] = r["max_contact_pressure"] / r["hertz_p0"]
        else:
            r["p_max_over_hertz_p0"] = ""


CSV_FIELDS = [
    "id", "groups", "scene", "cell", "degree", "ref", "plane", "mu", "nu1",
    "nu2", "E1", "E2", "E1_over_E2", "load_scale", "load", "mesh", "c",
    "hold", "extra", "mu_bound", "expect", "note", "exit_code", "converged",
    "newton_iterations", "active_nodes", "stick_nodes", "slip_nodes",
    "n_slave_nodes", "n_dofs", "contact_fx", "contact_fy",
    "equilibrium_error", "max_contact_pressure", "p_max_over_hertz_p0",
    "final_residual", "steps_run", "n_uncovered", "csv_check", "warning",
    "ref_case", "same_sets_as_ref", "rel_diff_to_ref",
    "signature", "wall_time_s", "n_nan", "nan", "verdict", "diagnosis",
    "binary_sha", "version", "command"]


def row_for_csv(r):
    out = {}
    for f in CSV_FIELDS:
        v = r.get(f, "")
        if f == "groups":
            v = "|".join(r["groups"])
        elif f == "E1_over_E2":
            v = "%.6g" % (r["E1"] / r["E2"])
        elif f == "load":
            v = "%.6g" % -applied_load(r)[1]
        elif f == "mu_bound":
            v = "%.4f" % min(existence_bound(r["nu1"]),
                             existence_bound(r["nu2"]))
        elif f == "hold":
            v = overrides_hold(r)
        elif f == "extra":
            v = " ".join(r["extra"]) + (
                " Upper body subdivisions=%d, %d" % r["upper_sub"]
                if "upper_sub" in r else "")
        elif f == "mesh" and r["scene"] == "blocks":
            lower, upper = MESH_RATIOS[r["mesh"]]
            v = "%s (upper %dx%d, lower %dx%d)" % (
                r["mesh"], *(r.get("upper_sub", (upper, upper))),
                lower, lower)
        elif isinstance(v, float):
            v = "%.6g" % v
        elif v is None:
            v = ""
        out[f] = v
    return out


def machine(jobs):
    return "%s; %d run(s) at a time (--jobs), 1 MPI rank each; other work " \
           "may have run on the machine (times are indicative)" % (
               common.machine_info(), jobs)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--binary", default=os.path.join(common.ROOT, "build",
                                                     "coulomb-adapt"))
    ap.add_argument("--workdir", default="/tmp/coulomb-stability")
    ap.add_argument("--outdir", default=HERE)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=300.0)
    ap.add_argument("--passes", type=int, default=3,
                    help="passes over cases run with an outdated build")
    ap.add_argument("--groups", default="",
                    help="comma-separated groups to run (default: all)")
    ap.add_argument("--keep-vtu", action="store_true")
    ap.add_argument("--no-markdown", action="store_true")
    ap.add_argument("--cases", default="",
                    help="comma-separated case ids to run (default: all)")
    ap.add_argument("--smoke", action="store_true",
                    help="the base case and the first input that must stop "
                    "with a diagnosis, one pass (ctest)")
    ap.add_argument("--list", action="store_true", help="list cases, run none")
    args = ap.parse_args()

    cases = build_cases()
    if args.groups:
        want = set(g.strip() for g in args.groups.split(","))
        cases = [c for c in cases if want & set(c["groups"])]
    if args.smoke:
        args.passes = 1
        cases = [cases[0], next(c for c in cases
                                if c["expect"] == "diagnose")]
    if args.cases:
        want = set(x.strip() for x in args.cases.split(","))
        cases = [c for c in cases if c["id"] in want]
    if args.list:
        for c in cases:
            print(c["id"], "|".join(c["groups"]), describe(c))
        print(len(cases), "cases")
        return 0
    os.makedirs(args.workdir, exist_ok=True)
    binary = os.path.abspath(args.binary)
    t0 = time.time()
    done = {}
    todo = cases
    # The program may be rebuilt while the sweep runs (other engineers):
    # rerun the cases that ran with another build than the final one.
    for sweep_pass in range(args.passes):
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            futs = {pool.submit(run_case, c, binary, args.workdir,
                                args.keep_vtu, args.timeout): c for c in todo}
            for i, fut in enumerate(concurrent.futures.as_completed(futs)):
                r = fut.result()
                done[r["id"]] = r
                print("[%3d/%d] %s %-60s exit %-3s it %-4s %.2fs %s" % (
                    i + 1, len(todo), r["id"], describe(r)[:60],
                    r["exit_code"], r["steps_run"], r["wall_time_s"],
                    r["diagnosis"][:80]), flush=True)
        final = file_sha(binary)
        todo = [c for c in cases if done[c["id"]]["binary_sha"] != final]
        if not todo:
            break
        print("the program changed during the sweep: rerunning %d case(s)"
              % len(todo), flush=True)
    recs = sorted(done.values(), key=lambda r: r["id"])
    postprocess(recs)
    total = time.time() - t0
    csv_path = os.path.join(args.outdir, "stability.csv")
    common.write_csv(csv_path, [row_for_csv(r) for r in recs], CSV_FIELDS)
    info = dict(date=datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
                total=round(total), binary=os.path.relpath(binary,
                                                           common.ROOT),
                machine=machine(args.jobs))
    with open(report.run_info_path(csv_path), "w") as f:
        json.dump(info, f, indent=2)
        f.write("\n")
    if not args.no_markdown:
        report.write_markdown(os.path.join(args.outdir, "stability.md"),
                              report.markdown(report.read_results(csv_path),
                                              info))
    bugs = [r for r in recs if r["verdict"].startswith(("BUG", "SUSPECT"))]
    print("%d runs in %.0f s: %d ok, %d diagnosed, %d BUG or SUSPECT" % (
        len(recs), total, sum(r["verdict"].startswith("ok") for r in recs),
        sum(r["verdict"].startswith("diagnosed") for r in recs), len(bugs)))
    for r in bugs:
        print("  ", r["id"], describe(r), r["verdict"], r["diagnosis"])
    if len(set(r["binary_sha"] for r in recs)) > 1:
        print("WARNING: the binary changed during the sweep; rerun.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
