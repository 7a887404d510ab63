#!/usr/bin/python3
"""Charts and a readable report for `armour compare` (reads DIR/summary.json).

Writes DIR/pareto.png (signed error of each group's mean against its cost, 95 % intervals, the
tolerance band), DIR/stability_dt.png (energy gain / sum(m g Dn) against the time step over each
run's own stability limit, both engines, failures and blow-ups marked per engine),
DIR/bumpiness.png (every headline figure against sphere count: seeds, group means with 95 %
intervals, the exact hulls and the analytic value) and DIR/report.md. The statistics come from
summary.json (`groups`, `advice`: apps/compare_stats.cpp); this script only draws and tabulates.
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import NullFormatter  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "analysis"))
from armour_results import read_summary  # noqa: E402

out = sys.argv[1]
s = read_summary(out)
keys = s["headline_keys"]
exact_engine = s.get("exact_engine")
groups = s.get("groups", [])
advice = s.get("advice", {})
threshold = s.get("blow_up_gain", 0.1)
engines = sorted({r["engine"] for r in s["runs"] + s["dt_sweep"]}, key=lambda e: e == exact_engine)
# One look per engine, failures included: the exact engine black, clumps blue.
style = {e: ("black", "s", "+") if e == exact_engine else ("tab:blue", "o", "x") for e in engines}


def fmt(v, spec=".3g", signed=False):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "–"
    return format(v, ("+" if signed else "") + spec)


def pm(mean, ci, signed=False):
    if mean is None:
        return "–"
    return fmt(mean, signed=signed) + ("" if ci is None else f" ± {fmt(ci)}")


def reference_field(key):
    return "error_vs_analytic" if advice.get(key, {}).get("reference") == "analytic" else "error_vs_exact"


def panels(n):
    fig, axes = plt.subplots(1, max(n, 1), figsize=(max(6.5, 5.2 * n), 4.5), squeeze=False)
    return fig, axes[0]


# Accuracy against cost: one panel per headline figure, group means with 95 % intervals.
fig, axes = panels(len(keys))
for ax, key in zip(axes, keys):
    field = reference_field(key)
    tol = advice.get(key, {}).get("tolerance")
    if tol:
        ax.axhspan(-tol, tol, color="tab:green", alpha=0.12, label=f"tolerance ±{tol:g}")
    ax.axhline(0.0, color="grey", lw=0.6)
    for g in groups:
        f = g["figures"][key]
        e, ci, cost = f.get(field + "_mean"), f.get(field + "_ci95"), g["cost"]["mean"]
        if e is None or cost is None:
            continue
        colour, marker, _ = style[g["engine"]]
        ax.errorbar(cost, e, yerr=ci if ci is not None else None, fmt=marker, color=colour, capsize=3)
        ax.annotate(f"{g['label']} (n={f['n']})", (cost, e), fontsize=7, xytext=(4, 3), textcoords="offset points")
    choice = advice.get(key, {}).get("choice")
    ax.set_xscale("log")
    ax.xaxis.set_minor_formatter(NullFormatter())  # a narrow cost range crowds the minor labels
    ax.set_xlabel("cost: wall seconds per simulated second")
    ref = "analytic" if field == "error_vs_analytic" else "exact hulls"
    ax.set_ylabel(f"signed error of {key} vs {ref}")
    ax.set_title(f"{key}: advice {choice or 'none'}", fontsize=9)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
fig.suptitle(f"{s['scene']}: accuracy against cost (mean, 95 % interval over seeds)", fontsize=10)
fig.tight_layout()
fig.savefig(f"{out}/pareto.png", dpi=110)

# Time step past each run's own limit: energy gain / sum(m g Dn); every failure marked per engine.
fig, ax = plt.subplots(figsize=(6.5, 4.5))
top = threshold * 30.0
for k, engine in enumerate(engines):
    colour, marker, fail_marker = style[engine]
    pts = sorted([r for r in s["dt_sweep"] if r["engine"] == engine and r.get("dt_factor")],
                 key=lambda r: r["dt_factor"])
    ok = [r for r in pts if r["status"] == "ok" and r.get("energy_gain") is not None]
    if ok:
        ax.plot([r["dt_factor"] for r in ok], [r["energy_gain"] for r in ok], marker + "-", color=colour,
                label=f"{engine}")
    # Failures: blow-ups at their own gain (clipped), crashed runs at the top; the engines are
    # shifted apart so that neither hides the other.
    shift = 1.0 + 0.06 * k
    blown = [r for r in pts if r.get("blow_up")]
    if blown:
        ax.scatter([r["dt_factor"] * shift for r in blown], [min(r["energy_gain"], top) for r in blown],
                   marker=fail_marker, s=70, color=colour, label=f"{engine}: blow-up (failure)")
    crashed = [r for r in s["dt_sweep"] if r["engine"] == engine and r["status"] != "ok" and not r.get("blow_up")]
    if crashed:
        xs = [(r.get("dt_factor") or r.get("dt_factor_requested") or 1.0) * shift for r in crashed]
        ax.scatter(xs, [top] * len(crashed), marker=fail_marker, s=70, color=colour, lw=2,
                   label=f"{engine}: run failed (left the domain)")
ax.axhline(threshold, color="tab:red", ls="--", lw=0.8, label=f"blow-up threshold {threshold:g}")
gains = [r["energy_gain"] for r in s["dt_sweep"] if r.get("energy_gain") is not None]
ax.set_ylim(bottom=min(gains + [-1e-3]) * 1.5, top=top * 3.0)
ax.axvline(1.0, color="tab:red", ls=":", label="each run's own stability limit")
ax.set_xscale("log")
ax.set_yscale("symlog", linthresh=1e-4)
ax.set_xlabel("time step / the run's own stability limit (dt / dt_limit)")
ax.set_ylabel("energy gain (E_max − E_0) / Σ m g Dn  [-]")
ax.set_title("Where the time step breaks each engine")
ax.grid(True, which="both", lw=0.3)
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(f"{out}/stability_dt.png", dpi=110)

# Every headline figure against sphere count: seeds, group mean ± 95 %, exact and analytic values.
fig, axes = panels(len(keys))
for ax, key in zip(axes, keys):
    clumps = [g for g in groups if g["spheres"] > 0]
    seeds = [r for r in s["runs"] if r["status"] == "ok" and r["spheres"] > 0 and r["figures"].get(key) is not None]
    ax.plot([r["spheres"] for r in seeds], [r["figures"][key] for r in seeds], ".", color="tab:blue", alpha=0.5,
            label="clumps, each seed")
    pts = [(g["spheres"], g["figures"][key]) for g in clumps if g["figures"][key]["mean"] is not None]
    if pts:
        ax.errorbar([n for n, _ in pts], [f["mean"] for _, f in pts],
                    yerr=[f["ci95"] or 0.0 for _, f in pts], fmt="o", color="tab:blue", capsize=3,
                    label="clumps, mean ± 95 %")
    for g in groups:
        f = g["figures"][key]
        if g["spheres"] == 0 and f["mean"] is not None:
            ax.axhline(f["mean"], color="black", label="exact hulls (mean)")
            if f["ci95"]:
                ax.axhspan(f["mean"] - f["ci95"], f["mean"] + f["ci95"], color="black", alpha=0.1)
    analytic = [r["figures"][key] - r["error_vs_analytic"][key] for r in s["runs"]
                if r["status"] == "ok" and r.get("error_vs_analytic", {}).get(key) is not None]
    if analytic:
        ax.axhline(analytic[0], color="tab:green", ls="--", label="analytic")
    ax.set_xscale("log")
    ax.set_xlabel("spheres per unit")
    ax.set_ylabel(key)
    ax.set_title(f"{key}", fontsize=9)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
fig.suptitle("When do clumps agree with the exact shape?", fontsize=10)
fig.tight_layout()
fig.savefig(f"{out}/bumpiness.png", dpi=110)

# Report.
lines = [f"# Clumps against exact shapes: {s['scene']}", ""]
lines.append(f"Analysis: `{s['analysis']}`; headline figures: {', '.join(f'`{k}`' for k in keys) or 'none'}; "
             f"exact engine: {exact_engine}; seeds: {s['seeds']}. Errors are signed (run minus reference). "
             "Intervals are 95 % intervals of the mean over seeds (Student t; Welch for differences); a group "
             "of one run has none.")
lines += ["", "## Groups (engine and sphere count)", ""]
for key in keys:
    lines += [f"### `{key}`", "",
              "| group | ok / runs | mean ± 95 % | std | error vs exact ± 95 % | error vs analytic ± 95 % "
              "| wall s per simulated s |", "|---|---|---|---|---|---|---|"]
    for g in groups:
        f = g["figures"][key]
        lines.append("| {} ({}) | {} / {} | {} | {} | {} | {} | {} |".format(
            g["label"], g["engine"], g["n_runs"] - g["n_failed"], g["n_runs"], pm(f["mean"], f["ci95"]),
            fmt(f["std"]), pm(f["error_vs_exact_mean"], f["error_vs_exact_ci95"], True),
            pm(f.get("error_vs_analytic_mean"), f.get("error_vs_analytic_ci95"), True), fmt(g["cost"]["mean"])))
    lines.append("")
lines += ["![accuracy against cost](pareto.png)", "", "## Advice", ""]
for key in keys:
    a = advice.get(key)
    if not a:
        continue
    lines.append(f"- `{key}`, tolerance ±{fmt(a['tolerance'])} ({a['tolerance_source']}), against the "
                 f"{a['reference']}: **{a['choice'] or 'no advice'}**. {a['reason']}.")
    verdicts = ", ".join(f"{v['label']}: {v['verdict']}" for v in a["groups"])
    lines.append(f"  Verdicts: {verdicts}.")
lines.append("")
lines += ["## Every run", "", "| run | status | " + " | ".join(keys) + " | dt [s] | dt_limit [s] "
          "| wall s per simulated s |", "|---|---|" + "---|" * len(keys) + "---|---|---|"]
for r in s["runs"]:
    figures = " | ".join(fmt((r.get("figures") or {}).get(k), ".4g") for k in keys)
    status = r["status"] if r["status"] == "ok" else f"failed: {r.get('failure', '')}"
    lines.append(f"| {r['label']} | {status} | {figures} | {fmt(r.get('dt'))} | {fmt(r.get('dt_limit'))} "
                 f"| {fmt(r.get('wall_seconds_per_simulated_second'))} |")
lines += ["", "## Stability where methods fail", ""]
if not s["dt_sweep"]:
    lines += ["No time-step sweep: it measures energy gain, which needs fixed gravity (a tilt scene turns it). "
              "Run `armour compare` on a settling scene (e.g. scenes/drop_bounce.toml) for the sweep.", ""]
else:
    lines += [f"Each point's time step over its own run's limit (`dt / dt_limit`, each clump its own limit). "
              f"Energy gain is (E_max − E_0) / Σ m g Dn; a stable dissipative run stays at or below 0; above "
              f"{threshold:g} the run counts as blown up (a failure, `--blow-up-gain`).", "",
              "![time step](stability_dt.png)", "",
              "| run | spheres | dt [s] | dt_limit [s] | dt / dt_limit | status | energy gain |",
              "|---|---|---|---|---|---|---|"]
    for r in s["dt_sweep"]:
        status = "ok" if r["status"] == "ok" else ("blow-up" if r.get("blow_up") else f"failed: {r['failure']}")
        lines.append(f"| {r['label']} | {r['spheres']} | {fmt(r.get('dt'))} | {fmt(r.get('dt_limit'))} | "
                     f"{fmt(r.get('dt_factor') or r.get('dt_factor_requested'))} | {status} | {fmt(r.get('energy_gain'))} |")
lines += ["", "![bumpiness](bumpiness.png)", ""]
with open(f"{out}/report.md", "w") as f:
    f.write("\n".join(lines) + "\n")
print(f"wrote {out}/pareto.png, stability_dt.png, bumpiness.png, report.md")
