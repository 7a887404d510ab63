"""Several pull tests (bench/run_pull_test.sh folders) on one chart: each unit's resistance up the face.

Usage
    /usr/bin/python3 bench/plot_pull_tests.py OUT.png FOLDER=LABEL [FOLDER=LABEL ...]

Resistance in the unit's own weight m|g| (-), position up the face in Dn (-); a unit that held
the test's largest pull is drawn at it, hollow (a lower bound). Each test's median (its
summary.json's, such units counted at the largest pull) in the legend.
"""
import csv
import json
import os
import sys


def main():
    if sys.argv[1:] in (["-h"], ["--help"]):
        print(__doc__)
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    if len(sys.argv) < 3 or any("=" not in a for a in sys.argv[2:]):
        sys.exit(__doc__)
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    lone = None
    for k, arg in enumerate(sys.argv[2:]):
        folder, label = arg.split("=", 1)
        summary = json.load(open(os.path.join(folder, "summary.json")))
        with open(os.path.join(folder, "pull.csv")) as f:
            rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))
                    if r.get("unseated") != "1"]  # moved by the dry start before any pull
        s = np.array([float(r["s_over_Dn"]) for r in rows])
        held = np.array([r["stayed"] == "1" for r in rows])
        r = np.array([float(r["resistance_weights"]) if r["resistance_weights"] else summary["pull_max"]
                      for r in rows])
        colour = f"C{k}"
        ax.scatter(s[~held], r[~held], color=colour, s=20,
                   label=f"{label}: median {summary['resistance_median']:.2f} ({len(r)} units)")
        ax.scatter(s[held], r[held], facecolors="none", edgecolors=colour, s=20)
        lone = summary["lone_unit_lift"]
    if lone is not None:
        ax.axhline(lone, color="k", lw=0.8, ls="--", label=f"a cube held against sliding lifts off ({lone:.2f})")
    ax.set_xlabel("s: up the face from its toe [Dn]")
    ax.set_ylabel("pull held [unit weights m|g|]")
    ax.set_title("pull-out tests of settled layers (hollow: held the largest pull)", fontsize=10)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(sys.argv[1], dpi=110)


if __name__ == "__main__":
    main()
