#!/usr/bin/python3
"""Charts and a readable report for `armour compare` (reads DIR/summary.json).

Writes DIR/pareto.png (error against cost, Pareto front marked), DIR/stability_dt.png
(energy gain against time step / stability limit, both engines), DIR/bumpiness.png
(headline figure against sphere count, exact hulls as a line) and DIR/report.md.
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "analysis"))
from armour_results import read_summary  # noqa: E402

out = sys.argv[1]
s = read_summary(out)
keys = s["headline_keys"]
key = keys[0] if keys else None
runs = [r for r in s["runs"] if r["status"] == "ok"]
failed = [r for r in s["runs"] if r["status"] != "ok"]


def error_of(r):
    if key is None:
        return None
    e = r["error_vs_exact"].get(key)
    if e is None and r.get("error_vs_analytic"):
        e = r["error_vs_analytic"].get(key)
    return None if e is None else abs(e)


def energy_gain(r):
    """(E_max - E_0) / sum(m g Dn): zero or below for a stable, dissipative run."""
    return (r["energy_max"] - r["energy_initial"]) / max(r.get("energy_scale") or 1.0, 1e-300)


def label(r):
    return "exact hulls" if r["engine"] == "bullet" else f"{r['spheres']} spheres"


# Pareto: error against cost (wall seconds per simulated second).
fig, ax = plt.subplots(figsize=(6.5, 4.5))
points = []
for r in runs:
    cost = r["wall_seconds_per_simulated_second"]
    if r["engine"] == "bullet":
        # The exact hulls are the reference (zero error by definition): show their cost only.
        ax.axvline(cost, color="black", ls=":", lw=0.8)
        ax.annotate("exact hulls", (cost, 1), xycoords=("data", "axes fraction"), fontsize=7, rotation=90,
                    va="top", ha="right")
        continue
    err = error_of(r)
    if err is None:
        continue
    points.append((cost, err, r))
    ax.scatter(cost, max(err, 1e-6), color="tab:blue")
    ax.annotate(label(r), (cost, max(err, 1e-6)), fontsize=7, xytext=(3, 3), textcoords="offset points")
front = []
best = math.inf
for cost, err, r in sorted(points, key=lambda p: p[0]):
    if err < best:
        front.append((cost, max(err, 1e-6)))
        best = err
if front:
    ax.plot(*zip(*front), "--o", mfc="none", ms=10, color="tab:red", label="Pareto front")
    ax.legend(fontsize=8)
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("cost: wall seconds per simulated second")
ax.set_ylabel(f"|error| of {key}" if key else "error")
ax.set_title(f"{s['scene']}: accuracy against cost")
ax.grid(True, which="both", lw=0.3)
fig.tight_layout()
fig.savefig(f"{out}/pareto.png", dpi=110)

# Time step past the limit: energy gain (E_max - E_0) / sum(m g Dn); failures on top.
fig, ax = plt.subplots(figsize=(6.5, 4.5))
for engine, colour in (("liggghts", "tab:blue"), ("bullet", "black")):
    pts = [r for r in s["dt_sweep"] if r["engine"] == engine]
    ok = [r for r in pts if r["status"] == "ok"]
    bad = [r for r in pts if r["status"] != "ok"]
    if ok:
        xs = [r["dt_factor"] for r in ok]
        ys = [max(energy_gain(r), 1e-8) for r in ok]
        ax.plot(xs, ys, "o-", color=colour, label=f"{engine}")
    if bad:
        ax.scatter([r["dt_factor"] for r in bad], [10.0] * len(bad), marker="x", s=60, color=colour,
                   label=f"{engine}: run failed (unit left the domain)")
ax.axvline(1.0, color="tab:red", ls=":", label="computed stability limit")
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("time step / computed stability limit")
ax.set_ylabel("energy gain / (sum m g Dn)")
ax.set_title("Where the time step breaks each engine")
ax.grid(True, which="both", lw=0.3)
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(f"{out}/stability_dt.png", dpi=110)

# Bumpiness: headline figure against sphere count.
fig, ax = plt.subplots(figsize=(6.5, 4.5))
if key:
    clumps = sorted([r for r in runs if r["engine"] == "liggghts"], key=lambda r: r["spheres"])
    ax.plot([r["spheres"] for r in clumps], [r["figures"][key] for r in clumps], "o", label="clumps (each seed)")
    exact = s["exact_mean"].get(key)
    if exact is not None:
        ax.axhline(exact, color="black", label="exact hulls (mean)")
    ax.set_ylabel(key)
ax.set_xscale("log")
ax.set_xlabel("spheres per unit")
ax.set_title("When do clumps agree with the exact shape?")
ax.grid(True, which="both", lw=0.3)
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(f"{out}/bumpiness.png", dpi=110)

# Report.
lines = [f"# Clumps against exact shapes: {s['scene']}", ""]
lines.append(f"Analysis: `{s['analysis']}`; headline figure: `{key}`; exact engine: {s['exact_engine']}; "
             f"seeds: {s['seeds']}. Errors are run minus the mean of the exact-hull runs "
             "(or minus the analytic value where there is no exact run).")
lines += ["", "| run | {} | error | wall s per simulated s | s per unit-step |".format(key), "|---|---|---|---|---|"]
for r in s["runs"]:
    if r["status"] != "ok":
        lines.append(f"| {r['label']} | failed: {r['failure']} | | | |")
        continue
    v = r["figures"].get(key) if key else None
    e = error_of(r)
    lines.append("| {} | {} | {} | {:.3g} | {:.3g} |".format(
        r["label"], "–" if v is None else f"{v:.4g}", "–" if e is None else f"{e:.3g}",
        r["wall_seconds_per_simulated_second"], r["seconds_per_unit_step"]))
lines += ["", "![accuracy against cost](pareto.png)", ""]
exact_costs = [r["wall_seconds_per_simulated_second"] for r in runs if r["engine"] == "bullet"]
if exact_costs:
    lines.append(f"Exact hulls (the reference) cost {min(exact_costs):.3g} wall s per simulated s.")
    lines.append("")
if key and front:
    lines.append("Which clump for what accuracy (cheapest clump run within each error, in the figure's unit):")
    lines.append("")
    for tolerance in sorted({10 ** k for k in range(-3, 2)}, reverse=True):
        ok = [(c, e, r) for c, e, r in points if e <= tolerance]
        if ok:
            c, e, r = min(ok, key=lambda p: p[0])
            lines.append(f"- |error| ≤ {tolerance:g}: {label(r)} ({c:.3g} wall s per simulated s)")
    lines.append("")
lines += ["## Stability where methods fail", ""]
if not s["dt_sweep"]:
    lines += ["No time-step sweep: it measures energy gain, which needs fixed gravity (a tilt scene turns it). "
              "Run `armour compare` on a settling scene (e.g. scenes/drop_bounce.toml) for the sweep.", ""]
lines += [
          "Time step swept past each engine's computed limit (`dt_limit` in each run's summary). "
          "Energy gain is (E_max − E_0) / Σ m g Dn; a stable dissipative run stays at or below 0.", "",
          "![time step](stability_dt.png)", "", "| run | dt / limit | status | energy gain |", "|---|---|---|---|"]
for r in s["dt_sweep"]:
    if r["status"] == "ok":
        lines.append(f"| {r['label']} | {r['dt_factor']:g} | ok | {energy_gain(r):.3g} |")
    else:
        lines.append(f"| {r['label']} | {r['dt_factor']:g} | failed | {r['failure']} |")
lines += ["", "![bumpiness](bumpiness.png)", ""]
with open(f"{out}/report.md", "w") as f:
    f.write("\n".join(lines) + "\n")
print(f"wrote {out}/pareto.png, stability_dt.png, bumpiness.png, report.md")
