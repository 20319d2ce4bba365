#!/usr/bin/python3
"""Numerical stress test of the contact solver (semismooth Newton / PDAS).

Runs build/coulomb-adapt on the `blocks` scene over one-at-a-time variations
around a base case, a few parameter grids and combined extreme cases, plus a
subset on the `hertz` scene and a set of inputs that must stop with a
diagnosis. Every case must either converge or exit non-zero with a
diagnosis; no output may contain NaN/Inf.

Writes (next to this script unless told otherwise):
  stability.csv   one row per case
  stability.md    the block between the GENERATED markers is (re)written;
                  the hand-written text around it is kept.

Usage:
  benchmarks/contact/stability_sweep.py [--binary build/coulomb-adapt]
      [--workdir /tmp/coulomb-stability] [--jobs 1] [--groups a,b]
      [--keep-vtu] [--no-markdown]

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
import platform
import re
import shlex
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))

E0 = 130000.0                       # MPa, default of both bodies
MUS = [0.0, 0.1, 0.3, 0.6, 0.95, 1.5]
NUS = [0.0, 0.3, 0.45, 0.49, 0.499]
E_RATIOS = [1e-3, 1.0, 1e3]         # E1 / E2, E2 = 130000 MPa
LOAD_SCALES = [1e-6, 1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6]
C_SCALES = [1e-3, 1e-2, 1e-1, 1.0, 1e1, 1e2, 1e3]
# mesh ratio across the interface, (lower nx / 2) : (upper nx); (lower, upper)
# coarse x-subdivisions. "1:k": slave (upper) finer, "k:1": master finer.
MESH_RATIOS = {
    "8:1": (64, 4), "4:1": (32, 4), "2:1": (16, 4), "1:1": (8, 4),
    "1:2": (8, 8), "1:4": (8, 16), "1:8": (8, 32),
}

BLOCKS_BASE = dict(scene="blocks", cell="quadrilateral", degree=1, ref=1,
                   plane="plane strain", mu=0.3, nu1=0.3, nu2=0.3,
                   E1=E0, E2=E0, load_scale=1.0, mesh="1:1", c=1.0,
                   hold=None, extra=())
HERTZ_BASE = dict(scene="hertz", cell="quadrilateral", degree=1, ref=0,
                  plane="plane strain", mu=0.3, nu1=0.3, nu2=0.3,
                  E1=E0, E2=E0, load_scale=1.0, mesh="graded", c=1.0,
                  hold=None, extra=())
BLOCKS_PRESSURE = 10.0              # MPa on a 100 mm wide top: 1000 N/mm
HERTZ_LINE_LOAD = 1000.0            # N/mm
HERTZ_RADIUS = 100.0


def num(x):
    return "%.12g" % x


def existence_bound(nu):
    """mu bound sqrt(3 - 4 nu) / (2 - 2 nu) for existence/uniqueness."""
    return math.sqrt(3.0 - 4.0 * nu) / (2.0 - 2.0 * nu)


def applied_load(case):
    """Total external load on body 1 (N/mm); contact force must cancel it."""
    if case["scene"] == "blocks":
        return (0.0, -BLOCKS_PRESSURE * case["load_scale"] * 100.0)
    return (0.0, -HERTZ_LINE_LOAD * case["load_scale"])


def held_sideways(case):
    """Whether the case's hold option (scene default if unset) holds body 1
    horizontally: blocks 'Hold centre line' (default: mu = 0 only), hertz
    'Hold axis' (default true)."""
    if case["hold"] is not None:
        return case["hold"]
    return case["mu"] == 0 if case["scene"] == "blocks" else True


def hertz_reference(case):
    """Hertz a and p0 (plane strain) for the case's load and materials."""
    inv = ((1 - case["nu1"] ** 2) / case["E1"] +
           (1 - case["nu2"] ** 2) / case["E2"])
    if case["plane"] == "plane stress":
        inv = 1 / case["E1"] + 1 / case["E2"]
    P = HERTZ_LINE_LOAD * case["load_scale"]
    a = math.sqrt(4 * P * HERTZ_RADIUS * inv / math.pi)
    return a, 2 * P / (math.pi * a)


def overrides(case):
    """The -s overrides that define the case."""
    s = []
    if case["scene"] == "blocks":
        sec = "Scene/Blocks/"
        lower_nx, upper_nx = MESH_RATIOS[case["mesh"]]
        # keep the cells square: ny = nx
        s += ["Scene/Name=blocks",
              sec + "Pressure=" + num(BLOCKS_PRESSURE * case["load_scale"]),
              sec + "Upper body subdivisions=%d, %d" % case.get(
                  "upper_sub", (upper_nx, upper_nx)),
              sec + "Lower body subdivisions=%d, %d" % (lower_nx, lower_nx)]
        hold = case["hold"]
        if hold is None:
            hold = case["mu"] == 0
        s.append(sec + "Hold centre line=" + ("true" if hold else "false"))
    else:
        sec = "Scene/Hertz/"
        s += ["Scene/Name=hertz",
              sec + "Line load=" + num(HERTZ_LINE_LOAD * case["load_scale"])]
        if case["hold"] is not None:
            s.append(sec + "Hold axis=" + ("true" if case["hold"] else "false"))
    for b, (E, nu) in enumerate([(case["E1"], case["nu1"]),
                                 (case["E2"], case["nu2"])], start=1):
        s.append(sec + "Body %d/Young's modulus=%s" % (b, num(E)))
        s.append(sec + "Body %d/Poisson's ratio=%s" % (b, num(nu)))
    s += ["Mesh/Cell type=" + case["cell"],
          "Mesh/Global refinements=%d" % case["ref"],
          "Finite elements/Polynomial degree=%d" % case["degree"],
          "Finite elements/Plane model=" + case["plane"],
          "Contact/Friction coefficient=" + num(case["mu"]),
          "Contact/Complementarity scale=" + num(case["c"])]
    s += list(case["extra"])
    return s


# --------------------------------------------------------------------------
# the cases

def build_cases():
    cases = {}      # key (tuple of overrides) -> case
    order = []

    def add(group, expect="converge", note="", **changes):
        base = HERTZ_BASE if changes.get("scene") == "hertz" else BLOCKS_BASE
        case = dict(base)
        case.update(changes)
        case["extra"] = tuple(case["extra"])
        key = tuple(overrides(case))
        if key in cases:
            c = cases[key]
            if group not in c["groups"]:
                c["groups"].append(group)
            if note and not c["note"]:
                c["note"] = note
            return c
        case["groups"] = [group]
        case["expect"] = expect
        case["note"] = note
        case["id"] = "%03d" % len(order)
        cases[key] = case
        order.append(case)
        return case

    # one at a time around the base case
    add("oat", note="base case")
    for mu in MUS:
        add("oat", mu=mu)
    for nu in NUS:
        add("oat", nu1=nu, nu2=nu)
    add("oat", nu1=0.0, nu2=0.499, note="different nu: friction acts")
    add("oat", nu1=0.499, nu2=0.0, note="different nu: friction acts")
    for r in E_RATIOS:
        add("oat", E1=E0 * r)
    add("oat", E1=1.3, E2=1.3, note="both E x 1e-5 (homogeneity in E)")
    add("oat", E1=1.3e10, E2=1.3e10, note="both E x 1e5 (homogeneity in E)")
    for s in LOAD_SCALES:
        add("oat", load_scale=s)
    for m in MESH_RATIOS:
        add("oat", mesh=m)
    for c in C_SCALES:
        add("oat", c=c)
    for ref in (0, 1, 2, 3):
        add("oat", ref=ref)
    add("oat", cell="triangle")
    add("oat", degree=2, note="Q2")
    add("oat", cell="triangle", degree=2, note="P2")
    add("oat", plane="plane stress")

    # grids (always with the base values of everything else)
    for mu in MUS:
        for nu in NUS:
            for r in E_RATIOS:
                add("grid mu x nu x E1/E2", mu=mu, nu1=nu, nu2=nu, E1=E0 * r)
    for mu in MUS:
        for c in C_SCALES:
            add("grid mu x c", mu=mu, c=c)
    for mu in MUS:
        for s in LOAD_SCALES:
            add("grid mu x load", mu=mu, load_scale=s)
    for mu in MUS:
        for m in MESH_RATIOS:
            add("grid mu x mesh ratio", mu=mu, mesh=m)
    for mu in MUS:
        add("grid mu x cell", mu=mu, cell="triangle")
        add("grid mu x cell", mu=mu, degree=2)
        add("grid mu x cell", mu=mu, cell="triangle", degree=2)

    # combined extremes
    X = "extreme"
    add(X, mu=1.5, nu1=0.499, nu2=0.499)
    add(X, mu=0.95, nu1=0.0, nu2=0.0, note="mu above the bound 0.866")
    add(X, mu=1.5, nu1=0.499, nu2=0.499, c=1e3)
    add(X, mu=1.5, nu1=0.499, nu2=0.499, c=1e-3)
    add(X, mu=1.5, nu1=0.0, nu2=0.499, note="different nu, mu over bound")
    add(X, mu=0.95, nu1=0.499, nu2=0.0, E1=E0 * 1e-3)
    add(X, E1=E0 * 1e3, mesh="1:8")
    add(X, E1=E0 * 1e-3, mesh="1:8")
    add(X, E1=E0 * 1e-3, mesh="8:1")
    add(X, E1=E0 * 1e3, mesh="8:1")
    add(X, cell="triangle", mu=1.5, nu1=0.499, nu2=0.499)
    add(X, cell="triangle", mesh="1:8", E1=E0 * 1e3)
    add(X, cell="triangle", degree=2, mu=0.95, nu1=0.499, nu2=0.499)
    add(X, mu=0.6, load_scale=1e6, c=1e-3)
    add(X, mu=0.1, load_scale=1e-6, c=1e3)
    add(X, mu=0.0, nu1=0.499, nu2=0.499, E1=E0 * 1e-3)
    add(X, ref=3, mu=1.5, E1=E0 * 1e3)
    add(X, ref=3, mu=0.1, E1=E0 * 1e-3, mesh="1:4")
    add(X, degree=2, mesh="1:8", nu1=0.49, nu2=0.49)
    add(X, plane="plane stress", mu=0.95, nu1=0.499, nu2=0.499)
    add(X, cell="triangle", mu=1.5, nu1=0.499, nu2=0.499, E1=E0 * 1e3,
        load_scale=1e6, mesh="1:8", c=1e3, note="everything at once (high)")
    add(X, cell="triangle", mu=0.1, nu1=0.499, nu2=0.0, E1=E0 * 1e-3,
        load_scale=1e-6, mesh="8:1", c=1e-3, note="everything at once (low)")
    add(X, mu=0.6, nu1=0.45, nu2=0.0, E1=E0 * 1e3, mesh="1:8", c=1e3)

    # inputs that must stop with a diagnosis
    D = "diagnosis"
    add(D, expect="diagnose", mu=0.0, hold=False,
        note="mu = 0 without Hold centre line: body 1 not held sideways")
    add(D, expect="diagnose", mu=0.0, hold=True, ref=0, upper_sub=(5, 4),
        note="Hold centre line with odd upper nx: no vertex on x = 100")
    add(D, expect="diagnose", load_scale=-1.0,
        note="pressure -10 MPa: body 1 pulled away from body 2")
    add(D, expect="diagnose", load_scale=0.0,
        note="pressure 0: nothing presses body 1 on body 2")
    add(D, expect="diagnose", extra=("Contact/Maximum Newton iterations=1",),
        note="iteration limit 1 (base needs 2)")
    add(D, expect="diagnose", extra=("Contact/Tolerance=0",),
        note="tolerance 0: unreachable")
    add(D, expect="diagnose", scene="hertz", mu=0.0, hold=False,
        note="hertz mu = 0 without Hold axis")

    # follow-ups of the failures above: does the hint of the diagnosis help?
    F = "follow-up"
    nu499 = dict(nu1=0.499, nu2=0.499)
    add(F, expect="either", nu1=0.49, nu2=0.49, E1=E0 * 1e3, c=1e-3,
        note="074 with c x 1e-3 (the cycling diagnosis suggests another c)")
    add(F, expect="either", nu1=0.49, nu2=0.49, E1=E0 * 1e3, c=1e3,
        note="074 with c x 1e3")
    add(F, expect="either", mu=0.95, E1=E0 * 1e3, c=1e-2, **nu499,
        note="104 with c x 1e-2")
    add(F, expect="either", mu=1.5, E1=E0 * 1e3, c=1e-3, **nu499,
        note="118 with c x 1e-3")
    add(F, expect="either", mu=1.5, E1=E0 * 1e3, c=1e-3, **nu499,
        extra=("Contact/Tolerance=1e-8",),
        note="118 with c x 1e-3 and tolerance 1e-8")
    add(F, expect="either", mu=0.6, E1=E0 * 1e3, **nu499,
        extra=("Contact/Tolerance=1e-9",), note="090 with tolerance 1e-9")
    add(F, expect="either", E1=E0 * 1e3, mesh="8:1",
        extra=("Contact/Tolerance=1e-7",), note="231 with tolerance 1e-7")
    add(F, expect="either", E1=E0 * 1e3, mesh="8:1",
        extra=("Linear solver/Direct solver=Amesos_Klu",),
        note="231 with KLU instead of MUMPS")
    add(F, expect="either", cell="triangle", E1=E0 * 1e3, mesh="1:8", **nu499,
        note="241 reduced: no tangential load, yet 'slides' diagnosis?")
    add(F, expect="either", cell="triangle", E1=E0 * 1e3, mesh="1:8", c=1e-3,
        **nu499, note="the same with c x 1e-3")
    add(F, expect="either", cell="triangle", E1=E0 * 1e3, mesh="1:8", c=1e-3,
        extra=("Contact/Tolerance=1e-7",), **nu499,
        note="the same with c x 1e-3 and tolerance 1e-7")
    add(F, expect="either", cell="triangle", E1=E0 * 1e3, mesh="1:8", mu=1.5,
        **nu499, note="241 at load x1, c x1")
    add(F, expect="either", mu=1e-3, note="near-frictionless, no hold")
    add(F, expect="either", mu=1e-6, note="near-frictionless, no hold")
    add(F, expect="either", mu=1e-6, nu1=0.499, nu2=0.499,
        note="near-frictionless, no hold")
    add(F, expect="either", scene="hertz", E1=E0 * 1e3,
        extra=("Contact/Tolerance=1e-6",), note="260 with tolerance 1e-6")
    add(F, expect="either", scene="hertz", E1=E0 * 1e3, c=1e-3,
        note="260 with c x 1e-3")

    # hertz subset
    H = "hertz"
    add(H, scene="hertz", note="hertz base")
    for mu in MUS:
        add(H, scene="hertz", mu=mu)
    for nu in (0.0, 0.499):
        add(H, scene="hertz", nu1=nu, nu2=nu)
    add(H, scene="hertz", E1=E0 * 1e-3, note="soft disc: friction acts")
    add(H, scene="hertz", E1=E0 * 1e3, note="stiff disc: friction acts")
    add(H, scene="hertz", E1=E0 * 1e3, mu=1.5)
    add(H, scene="hertz", E1=E0 * 1e-3, mu=0.0)
    for s in (1e-6, 1e-3, 1e3, 1e6):
        add(H, scene="hertz", load_scale=s)
    for c in (1e-3, 1e3):
        add(H, scene="hertz", c=c)
    add(H, scene="hertz", cell="triangle")
    add(H, scene="hertz", cell="triangle", mu=1.5, nu1=0.499, nu2=0.499)
    add(H, scene="hertz", ref=1)
    return order


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
    for attempt in range(4):
        t0 = time.perf_counter()
        try:
            p = subprocess.run(args, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True,
                               timeout=timeout, cwd=ROOT)
            rec["exit_code"] = p.returncode
            stdout, stderr = p.stdout, p.stderr
        except subprocess.TimeoutExpired as e:
            rec["exit_code"] = "timeout"
            stdout = (e.stdout or b"").decode() if isinstance(
                e.stdout, bytes) else (e.stdout or "")
            stderr = "TIMEOUT after %g s" % timeout
        rec["wall_time_s"] = time.perf_counter() - t0
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
        with open(summary_path) as f:
            text = f.read()
        try:
            summary = json.loads(text)
            nan += json_nonfinite(summary)
            rec["version"] = summary.get("version", "")
            if summary.get("cycles"):
                cyc = summary["cycles"][-1]
        except ValueError as e:
            nan.append("summary.json unreadable: %s" % e)
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
    steps = re.findall(r"^\s*Newton\s+(\d+):", stdout, re.M)
    rec["steps_run"] = int(steps[-1]) if steps else 0
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


# --------------------------------------------------------------------------
# output

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


def overrides_hold(r):
    for o in overrides(r):
        if "Hold" in o:
            return o.split("=")[1]
    return ""


def fmt(x, spec="%.1e"):
    if x is None or x == "":
        return "–"
    return spec % x


def short_diag(d, n=150):
    d = d.replace("|", "\\|")
    return d if len(d) <= n else d[:n - 1] + "…"


def describe(r):
    """Case parameters that differ from the scene's base case."""
    base = HERTZ_BASE if r["scene"] == "hertz" else BLOCKS_BASE
    parts = []
    names = {"cell": "", "degree": "p=", "ref": "ref ", "plane": "",
             "mu": "μ=", "nu1": "ν1=", "nu2": "ν2=", "E1": "E1/E2=",
             "E2": "E2=", "load_scale": "load×", "mesh": "ratio ",
             "c": "c×"}
    if r["nu1"] == r["nu2"] and r["nu1"] != base["nu1"]:
        parts.append("ν=%g" % r["nu1"])
    for k, lab in names.items():
        if k in ("nu1", "nu2") and r["nu1"] == r["nu2"]:
            continue
        if r[k] == base[k]:
            continue
        if k == "E1" and r["E1"] == r["E2"]:
            parts.append("E1=E2=%g" % r["E1"])
        elif k == "E2" and r["E1"] == r["E2"]:
            continue
        elif k == "E1":
            parts.append("E1/E2=%g" % (r["E1"] / r["E2"]))
        elif k in ("cell", "plane"):
            parts.append(r[k])
        else:
            parts.append("%s%g" % (lab, r[k]) if not isinstance(r[k], str)
                         else lab + r[k])
    if r["hold"] is not None:
        parts.append("hold=%s" % ("true" if r["hold"] else "false"))
    if "upper_sub" in r:
        parts.append("upper %d×%d" % r["upper_sub"])
    parts += [e.split("/")[-1] for e in r["extra"]]
    if r["scene"] == "hertz":
        parts.insert(0, "hertz")
    return ", ".join(parts) if parts else "base"


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


def machine(jobs):
    cpu = "?"
    osname = platform.system()
    try:
        with open("/etc/os-release") as f:
            for line in f:
                if line.startswith("PRETTY_NAME="):
                    osname = line.split("=", 1)[1].strip().strip('"')
    except OSError:
        pass
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
            mem = ", %.0f GiB RAM" % (kb / 2 ** 20)
    except (OSError, ValueError, IndexError):
        pass
    return "%s, %d logical CPUs%s, %s (kernel %s), Python %s; %d run(s) " \
           "at a time (--jobs), 1 MPI rank each; other work may have run " \
           "on the machine (times are indicative)" % (
               cpu, os.cpu_count() or 0, mem, osname, platform.release(),
               platform.python_version(), jobs)


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
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--binary", default=os.path.join(ROOT, "build",
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
    ap.add_argument("--list", action="store_true", help="list cases, run none")
    args = ap.parse_args()

    cases = build_cases()
    if args.groups:
        want = set(g.strip() for g in args.groups.split(","))
        cases = [c for c in cases if want & set(c["groups"])]
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
    with open(os.path.join(args.outdir, "stability.csv"), "w",
              newline="") as f:
        w = csv.DictWriter(f, fieldnames=CSV_FIELDS)
        w.writeheader()
        for r in recs:
            w.writerow(row_for_csv(r))
    info = dict(date=datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
                total=total, binary=os.path.relpath(binary, ROOT),
                machine=machine(args.jobs))
    if not args.no_markdown:
        write_markdown(os.path.join(args.outdir, "stability.md"),
                       markdown(recs, info))
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
