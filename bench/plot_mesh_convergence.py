#!/usr/bin/python3
"""Table, chart and summary of the mesh-convergence runs (run_mesh_convergence.sh).

Description
    Reads OUT/<case>_<n>/ for every case and level that ran (a platform run
    stopped after PLATFORM_WINDOW without a summary counts too), and for each
    headline figure (the dam break's: each cube's peak streamwise fluid force
    before the two cubes close, so not the squeeze spike of their collision;
    the platform's: over the first PLATFORM_WINDOW s) gives each level's
    difference to the finest, and estimates the observed order p and the
    extrapolated value from the three finest levels (Richardson with unequal
    refinement ratios: (f3 - f2) / (f2 - f1) = (h3^p - h2^p) / (h2^p - h1^p),
    h = the cube root of the cell volume, 1 the finest). Each level's error is
    |f - f_extrapolated| / |f_extrapolated|; the recommended resolution is the
    coarsest level within ERROR, and n_for_error the cells across that the
    error model |f1 - f_ext| (h / h1)^p puts at ERROR. Oscillating or
    diverging figures get no order (null) and say so.

Usage
    plot_mesh_convergence.py OUT_DIR [ERROR]   (writes OUT_DIR/mesh_convergence.{md,png}, summary.json)
"""
import glob
import json
import math
import os
import sys

from armour_results import read_summary



def bore_peaks(run, s):
    """Peak streamwise fluid force (N) on the first and second cube before the two close.

    When the first cube catches the second (centres within 1.1 a) the fluid squeezed
    between them gives a spike that depends on everything upstream of it (openfoam.md),
    so the headline is the bore's impact on each cube before that moment.
    """
    import numpy as np

    from armour_results import read_bodies

    b = read_bodies(run)
    i, j = s["first_body"], s["second_body"]
    a = s["per_unit"][i]["Dn"]  # a cube's Dn is its edge
    gap = np.linalg.norm(b.position[:, j] - b.position[:, i], axis=1)
    close = np.nonzero(gap < 1.1 * a)[0]
    end = close[0] if len(close) else len(b.time)
    s["_closing_time"] = float(b.time[end]) if len(close) else None
    return float(b.external_force[:end, i, 0].max()), float(b.external_force[:end, j, 0].max())


FIGURES = {  # case -> [(name, unit, reading from (run folder, summary), exact value or None)]
    "floating": [("draft", "m", lambda r, s: s["draft"], lambda s: s["draft_expected"])],
    "dambreak": [
        ("bore_peak_force_first", "N", lambda r, s: bore_peaks(r, s)[0], None),
        ("bore_peak_force_second", "N", lambda r, s: bore_peaks(r, s)[1], None),
        ("peak_force_first_any", "N", lambda r, s: s["per_unit"][s["first_body"]]["peak_force_x"], None),
    ],
    "platform": [
        ("max_displacement_3s", "m", lambda r, s: platform_figures(r, s)[0], None),
        ("crest_gauge_3s", "m", lambda r, s: platform_figures(r, s)[1], None),
    ],
}
PLATFORM_WINDOW = 3.0  # s: the cubes are on the floor by 2.6 s; at 3 cells across the 4 s maximum is reached by 2.8 s


def platform_figures(run, s):
    """Largest cube displacement (m) and crest above the still level at the gauge (m), t <= PLATFORM_WINDOW.

    Read from the records, not the summary, so that a finer run that was stopped after the
    window (it has no summary) counts alike.
    """
    import numpy as np

    from armour_results import read_bodies

    b = read_bodies(run)
    if b.time[-1] < PLATFORM_WINDOW - 1e-6:
        return None, None
    keep = b.time <= PLATFORM_WINDOW + 1e-9
    moved = np.linalg.norm(b.position[keep] - b.position[0], axis=2).max()
    crest = None
    for path in glob.glob(os.path.join(run, "case", "postProcessing", "gauges", "*", "surfaceElevation.dat")):
        rows = np.loadtxt(path, comments="#", ndmin=2)
        crest = float(rows[rows[:, 0] <= PLATFORM_WINDOW + 1e-9, 1].max()) - s["water_level"]
    return float(moved), crest


def read_run(run, case):
    """The run's summary.json; for a platform run stopped without one, what its records and log give."""
    path = os.path.join(run, "summary.json")
    if os.path.exists(path):
        s = read_summary(path)
        s.setdefault("water_level", s["fluid"].get("water_level"))
        return s
    if case != "platform" or not os.path.exists(os.path.join(run, "bodies.h5")):
        return None
    import re
    import tomllib

    with open(os.path.join(run, "scene.resolved.toml"), "rb") as f:
        scene = tomllib.load(f)
    with open(run + ".log") as f:
        cells = [int(c) for c in re.search(r"(\d+) x (\d+) x (\d+) cells", f.read()).groups()]
    extent = [hi - lo for lo, hi in zip(scene["run"]["domain_min"], scene["run"]["domain_max"])]
    from armour_results import read_bodies

    return {"fluid": {"cell_size": [e / c for e, c in zip(extent, cells)], "cells": cells, "cells_total": None,
                      "steps": None}, "simulated_seconds": float(read_bodies(run).time[-1]), "wall_seconds": None,
            "partial": True, "water_level": scene["fluid"]["water_level"]}


def observed_order(h, f):
    """p and f_extrapolated from three levels, h[0] finest; (None, None, why) if it does not converge."""
    d21, d32 = f[1] - f[0], f[2] - f[1]
    if d21 == 0.0:
        return None, f[0], "the two finest levels agree exactly"
    r = d32 / d21
    if r <= 0.0:
        return None, None, "oscillating (differences change sign)"

    def g(p):
        return (h[2] ** p - h[1] ** p) / (h[1] ** p - h[0] ** p)

    lo, hi = 1e-3, 12.0
    if not g(lo) < r < g(hi):
        return None, None, "diverging (differences grow under refinement)" if r < g(lo) else "order above 12"
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if g(mid) < r else (lo, mid)
    p = 0.5 * (lo + hi)
    return p, f[0] + (f[0] - f[1]) / ((h[1] / h[0]) ** p - 1.0), ""


def main():
    out = sys.argv[1]
    error = float(sys.argv[2]) if len(sys.argv) > 2 else 0.05
    result = {"bench": "mesh_convergence", "error": error, "cases": {},
              "si_units": {"draft": "m", "force": "N", "displacement": "m", "h": "m", "wall_seconds": "s"}}
    lines = [f"| case | figure | value at n cells across | difference to the finest | p (3 finest) | extrapolated | "
             f"error per level | coarsest within {100 * error:g} % of the extrapolated |", "|---|---|---|---|---|---|---|---|"]
    for case, figures in FIGURES.items():
        runs = []
        for run in glob.glob(os.path.join(out, f"{case}_*[0-9]")):
            s = read_run(run, case)
            if s is None or not os.path.isdir(run):
                continue
            n = int(os.path.basename(run).split("_")[-1])
            h = math.prod(s["fluid"]["cell_size"]) ** (1.0 / 3.0)
            runs.append((n, h, s, run))
        if not runs:
            continue
        runs.sort(key=lambda r: r[0])
        values_of = {name: [read(r, s) for _, _, s, r in runs] for name, _, read, _ in figures}
        entry = {"levels": [{"cells_across": n, "h": h, "cells": s["fluid"]["cells"],
                             "cells_total": s["fluid"]["cells_total"], "fluid_steps": s["fluid"]["steps"],
                             "simulated_seconds": s["simulated_seconds"], "wall_seconds": s["wall_seconds"],
                             **({"closing_time": s["_closing_time"]} if "_closing_time" in s else {}),
                             **({"partial": True} if s.get("partial") else {})}
                            for n, h, s, _ in runs], "figures": {}}
        for name, unit, read, exact in figures:
            done = [(r, v) for r, v in zip(runs, values_of[name]) if v is not None]  # a run still under way: none
            levels_done, values = [r for r, _ in done], [v for _, v in done]
            fig = {"unit": unit, "cells_across": [r[0] for r in levels_done], "values": values}
            if exact:
                fig["exact"] = exact(runs[0][2])
            if len(done) >= 2:  # what the finest level says of the others, whether or not an order exists
                finest = values[-1]
                fig["difference_to_finest"] = [abs(v - finest) / abs(finest) for v in values]
                within = [r[0] for r, e in zip(levels_done, fig["difference_to_finest"]) if e <= error]
                fig["coarsest_within_error_of_finest"] = within[0]
            if len(done) >= 3:
                fine = levels_done[-3:][::-1]
                p, f_ext, why = observed_order([r[1] for r in fine], values[-3:][::-1])
                fig.update(observed_order=p, extrapolated=f_ext, from_levels=[r[0] for r in fine[::-1]])
                if why:
                    fig["note"] = why
                if f_ext:
                    errs = [abs(v - f_ext) / abs(f_ext) for v in values]
                    fig["error_per_level"] = errs
                    within = [r[0] for r, e in zip(levels_done, errs) if e <= error]
                    fig["coarsest_within_error"] = within[0] if within else None
                    if p:
                        e1 = errs[-1]
                        fig["cells_across_for_error"] = levels_done[-1][0] * (e1 / error) ** (1.0 / p) if e1 > 0 else None
            entry["figures"][name] = fig
            levels = ", ".join(f"{n}: {v:.4g}" for (n, *_), v in done)
            p, f_ext, errs = fig.get("observed_order"), fig.get("extrapolated"), fig.get("error_per_level")
            order = f"{p:.2f}" if p else fig.get("note", "-")
            extrapolated = f"{f_ext:.4g}" if f_ext else "-"
            per_level = ", ".join(f"{100 * e:.1f} %" for e in errs) if errs else "-"
            to_finest = ", ".join(f"{100 * e:.1f} %" for e in fig.get("difference_to_finest", [])) or "-"
            lines.append(f"| {case} | {name} ({unit}) | {levels} | {to_finest} | {order} | {extrapolated} | "
                         f"{per_level} | {fig.get('coarsest_within_error') or '-'} |")
        result["cases"][case] = entry
    table = "\n".join(lines)
    print(table)
    with open(os.path.join(out, "mesh_convergence.md"), "w") as f:
        f.write(table + "\n")
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(result, f, indent=2)
    chart(out, result)


def chart(out, result):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels = [(c, n, f) for c, e in result["cases"].items() for n, f in e["figures"].items()]
    if not panels:
        return
    fig, axes = plt.subplots(1, len(panels), figsize=(3.4 * len(panels), 3.4), squeeze=False)
    for ax, (case, name, f) in zip(axes[0], panels):
        levels = f["cells_across"]
        ax.plot(levels, f["values"], "o-", color="tab:blue", label="run")
        if f.get("extrapolated"):
            ax.axhline(f["extrapolated"], ls="--", color="tab:green",
                       label=f"extrapolated (p = {f['observed_order']:.2f})" if f.get("observed_order")
                       else "extrapolated")
        if f.get("exact"):
            ax.axhline(f["exact"], ls=":", color="k", label="exact")
        ax.set_xticks(levels)
        ax.set_xlabel("cells across a unit")
        ax.set_title(f"{case}: {name} ({f['unit']})", fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "mesh_convergence.png"), dpi=100)


if __name__ == "__main__":
    main()
