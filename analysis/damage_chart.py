"""The damage chart of a `damage` analysis: units on the slope coloured by displacement, damage against time.

Description
    Reads the analysis's damage.csv (one row per unit: its settled position on
    the slope, s up the face and y across, m; displacements in Dn) and
    damage_history.csv (units displaced and N_od against time, s) and writes
    one PNG: left, every unit at its settled place on the slope coloured by
    its final displacement / Dn (displaced units ringed); right, N_od against
    time and, on its own axis, the largest displacement of any unit / Dn (what
    moves before anything is displaced: a run without damage is not a flat
    line). Needs python3-matplotlib (numpy comes with it).

Usage
    python3 analysis/damage_chart.py OUT/damage.csv OUT/damage_history.csv OUT/damage.png
"""
import sys

from armour_results import read_rows  # this folder: Python puts a script's own folder on its path


def main(units_csv, history_csv, png):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    units = read_rows(units_csv)
    history = read_rows(history_csv)
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    s = [float(u["s_m"]) for u in units]
    y = [float(u["y_m"]) for u in units]
    final = [float(u["final_displacement_over_Dn"]) for u in units]
    dots = left.scatter(y, s, c=final, cmap="viridis", vmin=0.0, vmax=max(1.0, max(final, default=1.0)), s=80)
    for u, ys, ss in zip(units, y, s):
        if u["displaced"] == "1":
            left.scatter([ys], [ss], s=220, facecolors="none", edgecolors="red")
    left.axhline(0.0, color="grey", linestyle="--", linewidth=1)  # the toe: below it, off the face
    fig.colorbar(dots, ax=left, label="final displacement / Dn")
    left.set_xlabel("across the slope y (m)")
    left.set_ylabel("up the slope from the toe s (m)")
    left.set_title("units at their settled place (red ring: displaced)")
    left.set_aspect("equal", adjustable="datalim")
    t = [float(h["time_s"]) for h in history]
    n_od = [float(h["N_od"]) for h in history]
    right.plot(t, n_od, color="black")
    right.set_ylim(0.0, max(0.5, 1.1 * max(n_od, default=0.0)))  # N_od 0.5: start of damage for cubes
    right.set_xlabel("time (s)")
    right.set_ylabel("N_od (units displaced per Dn of width)")
    right.set_title("damage against time")
    right.grid(alpha=0.3)
    largest = right.twinx()
    largest.plot(t, [float(h["max_displacement_over_Dn"]) for h in history], color="tab:orange")
    largest.set_ylabel("largest displacement of a unit / Dn", color="tab:orange")
    largest.tick_params(axis="y", labelcolor="tab:orange")
    largest.set_ylim(bottom=0.0)
    fig.tight_layout()
    fig.savefig(png + ".tmp.png", dpi=100)
    import os

    os.replace(png + ".tmp.png", png)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit("usage: damage_chart.py DAMAGE_CSV HISTORY_CSV PNG")
    main(*sys.argv[1:])
