#!/usr/bin/python3
"""Where stability runs sit against Van der Meer (1988) and Hudson.

Description
    Draws Van der Meer's double-layer cube curve Ns = (6.7 N_od^0.4 / N^0.3 + 1.0)
    s_om^-0.1 for each run's own number of waves N and wave steepness s_om (in
    the run's colour), the same curve at N = 1000 and the first run's s_om (the
    usual reference), Hudson's Ns = (K_D cot a)^(1/3) for K_D 6.5 and 7.5, and
    each run's point (N_od, Ns) from its summary.json (analysis kind "damage"
    of a wave run; docs/stability.md). One realisation per run: one point
    each, no spread.

Usage
    /usr/bin/python3 bench/plot_stability_position.py RUN_DIR [RUN_DIR ...] OUT.png
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def van_der_meer(n_od, waves, s_om):
    return (6.7 * n_od**0.4 / waves**0.3 + 1.0) * s_om**-0.1


def read_run(run_dir):
    s = json.load(open(f"{run_dir}/summary.json"))
    waves = s["waves"]["waves"] if isinstance(s["waves"], dict) else s["waves"]
    if None in (waves, s["s_om"], s["Ns"]):
        sys.exit(f"{run_dir}/summary.json: no measured waves (Ns, s_om or N is null)")
    return waves, s["s_om"], s["Ns"], s["N_od"]


def main(run_dirs, png):
    runs = [read_run(d) for d in run_dirs]
    grid = [i / 100 for i in range(0, 301)]
    fig, ax = plt.subplots(figsize=(6, 4))
    for k, (waves, s_om, ns, n_od) in enumerate(runs):
        colour = f"C{k}"
        ax.plot(grid, [van_der_meer(x, waves, s_om) for x in grid], color=colour, lw=1,
                label=f"Van der Meer, N = {waves:.0f}, s_om = {s_om:.3f}")
        ax.plot([n_od], [ns], "o", color=colour, ms=8, label=f"run: N_od {n_od:.2f}, Ns {ns:.2f}")
    s_om = runs[0][1]
    ax.plot(grid, [van_der_meer(x, 1000, s_om) for x in grid], "k--", lw=1, label="Van der Meer, N = 1000")
    for kd, style in ((6.5, ":"), (7.5, "-.")):
        ax.axhline((kd * 1.5) ** (1 / 3), color="grey", ls=style, label=f"Hudson K_D {kd} (0-5 % displaced)")
    ax.set_xlabel("N_od (units displaced per Dn width)")
    ax.set_ylabel("Ns = Hs / (Delta Dn)")
    ax.set_title("double-layer cubes, 1:1.5 (one realisation per point)")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    if sys.argv[1:] in (["-h"], ["--help"]):
        print(__doc__)
        sys.exit(0)
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1:-1], sys.argv[-1])
