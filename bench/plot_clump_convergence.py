#!/usr/bin/python3
"""Charts of clump error against sphere count, and against the DEM time step each clump
allows, from clump_convergence.json.

Usage: plot_clump_convergence.py [--out] OUT_DIR   (reads and writes in OUT_DIR; run by run_clump_bench.sh)
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

args = [a for a in sys.argv[1:] if a != "--out"]
if len(args) != 1:
    sys.exit("usage: plot_clump_convergence.py [--out] OUT_DIR")
out = args[0]
with open(f"{out}/clump_convergence.json") as f:
    rows = json.load(f)["rows"]

metrics = [
    ("volume_error", "|volume error| [%]", True),
    ("surface_rms", "surface RMS [% of Dn]", False),
    ("surface_max", "surface max [% of Dn]", False),
    ("inertia_error", "inertia error [%]", False),
    ("topple_error_deg", "topple angle error [deg]", False),
    ("dt_limit", "DEM time step limit [s]", False),
    ("build_seconds", "build time [s]", False),
]
unscaled = ("build_seconds", "topple_error_deg", "dt_limit")
fig, axes = plt.subplots(2, 4, figsize=(16.8, 7.6))
axes = axes.ravel()
styles = {"greedy": "--", "optimised": "-"}
colours = {"cube": "tab:blue", "dolos": "tab:red"}
for ax, (key, label, absolute) in zip(axes, metrics):
    for shape in ("cube", "dolos"):
        for method in ("greedy", "optimised"):
            pts = [r for r in rows if r["shape"] == shape and r["method"] == method]
            if not pts:
                continue
            n = [r["spheres"] for r in pts]
            y = [abs(r[key]) if absolute else r[key] for r in pts]
            if key not in unscaled:
                y = [100 * v for v in y]
            if key == "topple_error_deg":
                y = [max(v, 1e-2) for v in y]  # log axis: 0 shown at the floor
            ax.plot(n, y, styles[method], color=colours[shape], marker="o", ms=3, label=f"{shape} {method}")
    if key == "surface_rms":
        ax.axhline(2.0, color="grey", lw=0.8, ls=":")
    if key in ("volume_error", "topple_error_deg"):
        ax.axhline(1.0, color="grey", lw=0.8, ls=":")
    if key == "dt_limit":  # the smallest-sphere rule it replaced, for comparison
        for shape in ("cube", "dolos"):
            pts = [r for r in rows if r["shape"] == shape and r["method"] == "optimised"]
            ax.plot([r["spheres"] for r in pts], [r["rayleigh_time"] for r in pts], ":", color=colours[shape],
                    label=f"{shape} optimised, smallest-sphere Rayleigh time")
        ax.legend(fontsize=6)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("spheres N")
    ax.set_ylabel(label)
    ax.grid(True, which="both", lw=0.3)
# The trade: topple error against the time step each clump allows.
ax = axes[7]
for shape in ("cube", "dolos"):
    for method in ("greedy", "optimised"):
        pts = [r for r in rows if r["shape"] == shape and r["method"] == method]
        ax.plot([r["dt_limit"] for r in pts], [max(r["topple_error_deg"], 1e-2) for r in pts], styles[method],
                color=colours[shape], marker="o", ms=3, label=f"{shape} {method}")
ax.axhline(1.0, color="grey", lw=0.8, ls=":")
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("DEM time step limit [s]")
ax.set_ylabel("topple angle error [deg]")
ax.grid(True, which="both", lw=0.3)
axes[0].legend(fontsize=8)
fig.suptitle("armour-fsi clump builder: error and cost against sphere count and time step (dotted: "
             "default tolerances)")
fig.tight_layout()
fig.savefig(f"{out}/clump_convergence.png", dpi=110)
print(f"wrote {out}/clump_convergence.png")
