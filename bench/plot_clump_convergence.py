#!/usr/bin/python3
"""Chart of clump error against sphere count from clump_convergence.json.

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
    ("build_seconds", "build time [s]", False),
]
fig, axes = plt.subplots(1, len(metrics), figsize=(4.2 * len(metrics), 3.8))
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
            if key != "build_seconds":
                y = [100 * v for v in y]
            ax.plot(n, y, styles[method], color=colours[shape], marker="o", ms=3, label=f"{shape} {method}")
    if key == "surface_rms":
        ax.axhline(2.0, color="grey", lw=0.8, ls=":")
    if key == "volume_error":
        ax.axhline(1.0, color="grey", lw=0.8, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("spheres N")
    ax.set_ylabel(label)
    ax.grid(True, which="both", lw=0.3)
axes[0].legend(fontsize=8)
fig.suptitle("armour-fsi clump builder: error and cost against sphere count (dotted: targets)")
fig.tight_layout()
fig.savefig(f"{out}/clump_convergence.png", dpi=110)
print(f"wrote {out}/clump_convergence.png")
