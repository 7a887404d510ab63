#!/usr/bin/python3
"""Chart of a submerged cube's buoyancy error against cells across, ramp vs exact.

Usage: plot_buoyancy_positions.py OUT_DIR   (reads and writes in OUT_DIR; run by run_buoyancy_positions.sh)
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

if len(sys.argv) != 2:
    sys.exit("usage: plot_buoyancy_positions.py OUT_DIR")
out = sys.argv[1]
with open(f"{out}/buoyancy_positions.json") as f:
    rows = json.load(f)["rows"]

fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
styles = {"ramp": ("tab:red", "sampled cosine ramp (before)"), "exact": ("tab:blue", "exact fractions (after)")}
for ax, orientation in zip(axes, ["aligned", "random"]):
    for fraction, (colour, label) in styles.items():
        sel = [r for r in rows if r["fraction"] == fraction and r["orientation"] == orientation]
        x = [r["cells_across"] for r in sel]
        ax.fill_between(x, [100 * r["min"] for r in sel], [100 * r["max"] for r in sel], color=colour, alpha=0.2)
        ax.plot(x, [100 * r["mean"] for r in sel], "o-", color=colour, label=f"{label}: mean, min-max band")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xscale("log")
    ax.set_xticks([3, 4, 6, 12])
    ax.set_xticklabels(["3", "4", "6", "12"])
    ax.set_xlabel("cells across the cube")
    ax.set_title(f"cube {'axis-aligned' if orientation == 'aligned' else 'randomly oriented'}, "
                 f"{sel[0]['poses']} random positions")
    ax.grid(True, alpha=0.3)
axes[0].set_ylabel("buoyancy error  sum(chi V) / a^3 - 1  [%]")
axes[0].legend(fontsize=8)
fig.tight_layout()
fig.savefig(f"{out}/buoyancy_positions.png", dpi=110)
