#!/usr/bin/python3
"""doc/figures/dovetail.png from a run of prm/dovetail.prm.

Usage (from the repository's root, after build/coulomb-adapt prm/dovetail.prm):
  doc/figures/dovetail.py [OUTPUT_DIR] [FILE.png]
(defaults output/dovetail and doc/figures/dovetail.png).

Three panels: (a) the last cycle's meshes of blade and disc; (b) the right
flank's edge region of that mesh, the blade's contact nodes coloured by
their state (stick, slip, open); (c) the contact pressure p, mu p and the
tangential traction |lambda_t| along the right flank, on the first and the
last cycle. Reads the meshes with scripts/plot-mesh's reader and the
contact_CCC.csv files; the friction coefficient from parameters.prm.
"""

import csv
import importlib.machinery
import os
import re
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

root = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", ".."))
plot_mesh = importlib.machinery.SourceFileLoader(
    "plot_mesh", os.path.join(root, "scripts", "plot-mesh")).load_module()

outdir = sys.argv[1] if len(sys.argv) > 1 else "output/dovetail"
png = sys.argv[2] if len(sys.argv) > 2 else "doc/figures/dovetail.png"
cycles = plot_mesh.available_cycles(outdir)
last = cycles[-1]

mu = float(re.search(r"set Friction coefficient\s*=\s*([0-9.eE+-]+)",
                     open(os.path.join(outdir, "parameters.prm")).read())
           .group(1))


def contact(cycle):
    with open(os.path.join(outdir, "contact_%03d.csv" % cycle)) as f:
        rows = [r for r in csv.DictReader(f) if float(r["x"]) > 0]
    rows.sort(key=lambda r: float(r["y"]))
    return rows


fig = plt.figure(figsize=(13, 4.6))
ax_mesh = fig.add_subplot(1, 3, 1)
ax_zoom = fig.add_subplot(1, 3, 2)
ax_p = fig.add_subplot(1, 3, 3)
colours = {1: "#c8d8f0", 2: "#e8e0c8"}
n_cells = {}
for ax, width in ((ax_mesh, 0.15), (ax_zoom, 0.3)):
    for body in (1, 2):
        polys, _ = plot_mesh.read_body(outdir, body, last, "error_indicator",
                                       0.0)
        n_cells[body] = len(polys)
        ax.add_collection(PolyCollection(polys, facecolors=colours[body],
                                         edgecolors="k", linewidths=width))
    ax.set_aspect("equal")
ax_mesh.set_xlim(-26, 26)
ax_mesh.set_ylim(-31, 41)
ax_mesh.set_title("(a) cycle %d: %d + %d triangles" % (last, n_cells[1],
                                                       n_cells[2]))
ax_zoom.set_xlim(5.8, 11.4)
ax_zoom.set_ylim(0.6, 4.6)
rows = contact(last)
style = {"stick": ("tab:blue", "stick"), "slip": ("tab:red", "slip"),
         "open": ("0.5", "open")}
for state, (c, label) in style.items():
    pts = [(float(r["x"]), float(r["y"])) for r in rows
           if r["status"] == state and r["facing_master"] == "1"]
    if pts:
        ax_zoom.plot(*zip(*pts), "o", ms=3.5, color=c, label=label, zorder=3)
ax_zoom.legend(loc="upper right", fontsize=8)
ax_zoom.set_title("(b) right flank, blade's contact nodes")


def along_flank(rows):
    # Distance along the flank from the blade's lower corner (10, 2).
    return np.array([np.hypot(float(r["x"]) - 10, float(r["y"]) - 2)
                     for r in rows])


for cycle, ls, tag in ((cycles[0], "--", "cycle %d" % cycles[0]),
                       (last, "-", "cycle %d" % last)):
    rows = [r for r in contact(cycle) if r["facing_master"] == "1"]
    s = along_flank(rows)
    p = np.array([float(r["contact_pressure"]) for r in rows])
    t = np.abs([float(r["tangential_traction"]) for r in rows])
    order = np.argsort(s)
    s, p, t = s[order], p[order], t[order]
    ax_p.plot(s, p, ls, color="k", lw=1, label="p, " + tag)
    ax_p.plot(s, mu * p, ls, color="tab:green", lw=1,
              label="mu p, " + tag)
    ax_p.plot(s, t, ls, color="tab:red", lw=1, label="|lambda_t|, " + tag)
ax_p.set_xlabel("distance along the flank from (10, 2), mm")
ax_p.set_ylabel("MPa")
ax_p.set_ylim(0, 800)
ax_p.legend(fontsize=7)
ax_p.set_title("(c) right flank, mu = %g (p up to %.0f MPa)"
               % (mu, max(float(r["contact_pressure"]) for r in contact(last))))
fig.tight_layout()
fig.savefig(png, dpi=130)
print("wrote", png)
