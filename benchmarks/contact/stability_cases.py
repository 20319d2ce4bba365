"""The cases of the contact solver's stability sweep (stability_sweep.py
runs them, stability_report.py tabulates them): one-at-a-time variations
around a base case on the `blocks` scene, parameter grids, combined
extremes, inputs that must stop with a diagnosis, follow-ups of the
failures, and a `hertz` subset. A case is a dict of parameters; its id is
its position in build_cases(), so the CSV of a sweep belongs to the case
list it was run with.
"""

import math

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


def overrides_hold(r):
    for o in overrides(r):
        if "Hold" in o:
            return o.split("=")[1]
    return ""


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
