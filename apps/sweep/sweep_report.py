#!/usr/bin/env python3
"""Charts and report.md of an `armour sweep` folder.

Description
    Reads DIR/summary.json (written by armour sweep) and draws, into
    DIR/figures/, each headline figure against each varied key: the mean over
    seeds with its 95 % interval (Student t), one line per combination of the
    other varied keys, and the predicted value dashed where the analysis gives
    one. When the cases report N_od and Ns (the damage analysis), it also
    draws N_od (and damage_S) against the stability number Ns = Hs/(Delta Dn),
    a point per set of varied values (the mean of its realisations, with 95 %
    intervals in Ns and N_od, each realisation dotted), with the Van der Meer curve for cubes at the sweep's N and s_om,
        Ns = (6.7 N_od^0.4 / N^0.3 + 1.0) s_om^-0.1,
    and Hudson's lines Ns = (K_D cot alpha)^(1/3) for K_D = 6.5 and 7.5 (the runs' own
    Ns_hudson_breaking and Ns_hudson_nonbreaking, the median over the cases). Around
    the curve, a band: where 90 % of the counts of displaced units fall in a
    section as wide as the cases' (units per N_od) if the formula's N_od is the
    mean (Poisson). A narrow flume sees few units, and 0 or 1 of them can agree
    with the formula or not; the band says which. It is not the formula's own
    scatter (Van der Meer's spread for cubes is not in the sources we read).
    Where the cases kept their damage history (cases/<case>/run/damage_history.csv),
    it also draws N_od against time, a line per realisation coloured by its set
    of varied values, with Van der Meer's N_od at the run's end as a marker.
    Writes DIR/report.md last, through a temporary file.

Usage
    python3 apps/sweep/sweep_report.py DIR
"""
import json
import math
import os
import sys
from collections import defaultdict

# Two-sided 95 % quantiles of Student's t for 1..30 degrees of freedom.
T95 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145,
       2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048,
       2.045, 2.042]
HUDSON_KD = (6.5, 7.5)  # cubes, breaking and non-breaking waves (stability.md)


def van_der_meer_ns(n_od, waves, s_om):
    """Stability number of cubes for damage N_od after `waves` waves of steepness s_om."""
    return (6.7 * n_od ** 0.4 / waves ** 0.3 + 1.0) * s_om ** -0.1


def van_der_meer_n_od(ns, waves, s_om):
    """Damage N_od of cubes at Ns after `waves` waves of steepness s_om (0 below the onset)."""
    excess = ns * s_om ** 0.1 - 1.0
    return (excess * waves ** 0.3 / 6.7) ** 2.5 if excess > 0 else 0.0


def poisson_quantile(mean, p):
    """Smallest count k with P(X <= k) >= p for X ~ Poisson(mean)."""
    term = total = math.exp(-mean)
    k = 0
    while total < p and k < 10000:
        k += 1
        term *= mean / k
        total += term
    return k


def section_width(points):
    """Width of the test section in Dn (units per N_od), from Van der Meer's two figures of the cases."""
    widths = [c["figures"]["units_displaced_van_der_meer"] / c["figures"]["N_od_van_der_meer"]
              for c in points if number(c["figures"].get("units_displaced_van_der_meer"))
              and number(c["figures"].get("N_od_van_der_meer")) and c["figures"]["N_od_van_der_meer"] > 0]
    return median(widths) if widths else None


def mean_interval(values):
    """Mean and half-width of its 95 % interval (0 for a single value)."""
    n = len(values)
    mean = sum(values) / n
    if n < 2:
        return mean, 0.0
    sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
    t = T95[n - 2] if n - 2 < len(T95) else 1.96
    return mean, t * sd / math.sqrt(n)


def number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def first_number(figures, *keys):
    for k in keys:
        if number(figures.get(k)):
            return figures[k]
    return None


def save(fig, path):
    """The chart at `path` whole or not at all (written beside it and renamed), its folder made if need be."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=110, bbox_inches="tight")
    os.replace(tmp, path)


def figure_charts(plt, summary, done, folder):
    """Each headline figure against each numeric varied key; returns (title, file) pairs."""
    charts = []
    varied = summary.get("varied", [])
    predicted = summary.get("predicted", {})
    for key in varied:
        if not all(number(c["values"].get(key)) for c in done):
            continue
        others = [k for k in varied if k != key]
        for fig_key in summary.get("headline", []):
            points = [c for c in done if number(c["figures"].get(fig_key))]
            if not points:
                continue
            series = defaultdict(lambda: defaultdict(list))
            guess = defaultdict(lambda: defaultdict(list))
            for c in points:
                label = ", ".join(f"{k} = {c['values'].get(k)}" for k in others)
                series[label][c["values"][key]].append(c["figures"][fig_key])
                p = c["figures"].get(predicted.get(fig_key, ""))
                if number(p):
                    guess[label][c["values"][key]].append(p)
            fig, ax = plt.subplots(figsize=(6, 4))
            for label, by_x in sorted(series.items()):
                xs = sorted(by_x)
                stats = [mean_interval(by_x[x]) for x in xs]
                line = ax.errorbar(xs, [s[0] for s in stats], yerr=[s[1] for s in stats], marker="o",
                                   capsize=3, label=label or fig_key)
                if guess[label]:
                    gx = sorted(guess[label])
                    ax.plot(gx, [sum(guess[label][x]) / len(guess[label][x]) for x in gx], "--",
                            color=line[0].get_color(), label=f"{predicted[fig_key]} ({label})" if label
                            else predicted[fig_key])
            ax.set_xlabel(key)
            ax.set_ylabel(fig_key)
            ax.set_title(f"{fig_key} against {key} (mean, 95 % interval over seeds)", fontsize=9)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
            name = f"{fig_key}_vs_{key}.png".replace("/", "_")
            save(fig, os.path.join(folder, "figures", name))
            plt.close(fig)
            charts.append((f"{fig_key} against {key}", "figures/" + name))
    return charts


def hudson_lines(points):
    """(cot α, [(K_D, Ns)]) of Hudson's two lines from the runs' own figures, or None.

    The damage analysis writes Ns_hudson_* for the slope it measured; a case
    gathered from --kept holds that summary, not its scene."""
    own = [(c["figures"]["Ns_hudson_breaking"], c["figures"]["Ns_hudson_nonbreaking"]) for c in points
           if number(c["figures"].get("Ns_hudson_breaking")) and number(c["figures"].get("Ns_hudson_nonbreaking"))]
    if not own:
        return None
    lines = [(HUDSON_KD[0], median([o[0] for o in own])), (HUDSON_KD[1], median([o[1] for o in own]))]
    return lines[1][1] ** 3 / HUDSON_KD[1], lines  # Ns³ = K_D cot α


def median(values):
    v = sorted(values)
    return v[len(v) // 2] if len(v) % 2 else 0.5 * (v[len(v) // 2 - 1] + v[len(v) // 2])


def stability_chart(plt, done, path):
    """Draws N_od (and damage_S) against Ns with Van der Meer and Hudson into the PNG `path`.

    `done`: cases as summary.json lists them ("figures", and "values" whose set
    makes a point). Returns the chart's caption lines; None, drawing nothing,
    without damage figures."""
    points = [c for c in done if number(c["figures"].get("N_od")) and number(c["figures"].get("Ns"))]
    if not points:
        return None
    # N and s_om: the damage analysis's own, else those of the measured waves.
    waves = [x for x in (first_number(c["figures"], "waves", "waves.waves") for c in points) if x is not None]
    steep = [x for x in (first_number(c["figures"], "s_om", "waves.s_om") for c in points) if x is not None]
    with_s = [c for c in points if number(c["figures"].get("damage_S"))]
    fig, axes = plt.subplots(1, 2 if with_s else 1, figsize=(11 if with_s else 6, 4), squeeze=False)
    ax = axes[0][0]
    ns = [c["figures"]["Ns"] for c in points]
    n_od = [c["figures"]["N_od"] for c in points]
    # A point of the curve: the realisations (seeds) of one set of varied
    # values, their mean Ns and N_od with 95 % intervals; each realisation dotted.
    groups = defaultdict(list)
    for c in points:
        groups[json.dumps(c.get("values", {}), sort_keys=True)].append(c["figures"])
    means = [(mean_interval([f["Ns"] for f in g]), mean_interval([f["N_od"] for f in g]), len(g))
             for g in groups.values()]
    ax.plot(ns, n_od, ".", color="0.6", label="each realisation")
    ax.errorbar([m[0][0] for m in means], [m[1][0] for m in means], xerr=[m[0][1] for m in means],
                yerr=[m[1][1] for m in means], fmt="o", capsize=3, label="mean, 95 % interval")
    top = max(2.0, 1.3 * max(n_od))
    counts = sorted({m[2] for m in means})
    text = [f"{len(means)} points, each the mean of {'/'.join(map(str, counts))} realisation(s) with its 95 % "
            "interval (Student t) in Ns and N_od; grey dots: each realisation"]
    if waves and steep:
        n, s = median(waves), median(steep)
        grid = [top * i / 200 for i in range(201)]
        xs = [van_der_meer_ns(d, n, s) for d in grid]
        curve = ax.plot(xs, grid, "-", label=f"Van der Meer cubes (N = {n:g}, s_om = {s:.3g})")
        text.append(f"Van der Meer curve for N = {n:g} waves, s_om = {s:.3g} (medians of the cases)")
        width = section_width(points)
        if width:
            # The count a section this narrow sees scatters about the formula's
            # mean even if the formula is exact: Poisson, 5 % and 95 % quantiles.
            ax.fill_between(xs, [poisson_quantile(d * width, 0.05) / width for d in grid],
                            [poisson_quantile(d * width, 0.95) / width for d in grid], step="mid",
                            color=curve[0].get_color(), alpha=0.15,
                            label=f"90 % of counts in a {width:.3g} Dn wide section (Poisson)")
            text.append(f"band: 90 % of the displaced-unit counts a {width:.3g} Dn wide section sees when "
                        "Van der Meer's N_od is the mean (Poisson; the formula's own scatter for cubes is "
                        "not in it)")
    hudson = hudson_lines(points)
    if hudson:
        cot, lines = hudson
        for (k_d, x), style in zip(lines, (":", "-.")):
            ax.axvline(x, linestyle=style, color="grey", label=f"Hudson K_D = {k_d:g}, cot α = {cot:.3g}")
        text.append(f"Hudson lines for cot α = {cot:.3g}")
    ax.set_xlabel("Ns = Hs / (Δ Dn) [-]")
    ax.set_ylabel("N_od [units per Dn width]")
    ax.set_ylim(0, top)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    if with_s:
        ax2 = axes[0][1]
        ax2.plot([c["figures"]["Ns"] for c in with_s], [c["figures"]["damage_S"] for c in with_s], "s")
        ax2.set_xlabel("Ns = Hs / (Δ Dn) [-]")
        ax2.set_ylabel("S = Ae / Dn² (eroded area) [-]")
        ax2.grid(alpha=0.3)
    save(fig, path)
    plt.close(fig)
    return text


def read_history(path):
    """(time s, N_od) columns of a damage_history.csv; None when absent or unreadable."""
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = [line.strip().split(",") for line in f if line.strip() and not line.startswith("#")]
    if not rows or "time_s" not in rows[0] or "N_od" not in rows[0]:
        return None
    t, n = rows[0].index("time_s"), rows[0].index("N_od")
    return [float(r[t]) for r in rows[1:]], [float(r[n]) for r in rows[1:]]


def history_chart(plt, done, folder):
    """N_od against time per realisation, Van der Meer's end value marked; None without histories."""
    groups = defaultdict(list)
    for c in done:
        history = read_history(os.path.join(folder, c["folder"], "run", "damage_history.csv"))
        if history:
            label = ", ".join(f"{k.split('.')[-1]} {v}" for k, v in sorted(c.get("values", {}).items()))
            groups[label].append((c, history))
    if not groups:
        return None
    fig, ax = plt.subplots(figsize=(7, 4))
    marked = False
    for k, (label, members) in enumerate(sorted(groups.items())):
        colour = f"C{k % 10}"
        for i, (c, (t, n_od)) in enumerate(members):
            ax.plot(t, n_od, "-", color=colour, alpha=0.8, label=(label or "N_od") if i == 0 else None)
            vdm = c["figures"].get("N_od_van_der_meer")
            if number(vdm) and t:
                ax.plot([t[-1]], [vdm], "x", color=colour, markersize=8,
                        label=None if marked else "Van der Meer at the run's end")
                marked = True
    ax.set_xlabel("time [s]")
    ax.set_ylabel("N_od [units per Dn width]")
    ax.set_title("N_od against time, a line per realisation", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=6)
    save(fig, os.path.join(folder, "figures", "stability_Nod_vs_time.png"))
    plt.close(fig)
    count = sum(len(m) for m in groups.values())
    return "figures/stability_Nod_vs_time.png", [
        f"{count} realisations' damage histories (cases/<case>/run/damage_history.csv); "
        "x: Van der Meer's N_od at the run's own N, Ns and s_om"]


def main(folder):
    with open(os.path.join(folder, "summary.json")) as f:
        summary = json.load(f)
    cases = summary["cases"]
    done = [c for c in cases if c["status"] == "done"]
    os.makedirs(os.path.join(folder, "figures"), exist_ok=True)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lines = [f"# Sweep report: {os.path.basename(summary.get('sweep_file', ''))}", "",
             f"Scene `{summary.get('scene', '')}`, analysis `{summary.get('analysis', '')}`, "
             f"executor {summary.get('executor', '')}.", "",
             f"{summary['done']} of {summary['total']} cases done, {summary['failed']} failed, "
             f"{summary['pending'] + summary['running']} not finished. Table: results.csv; "
             "each case's outputs: cases/<case>/run/.", ""]
    stability = stability_chart(plt, done, os.path.join(folder, "figures", "stability_Nod_vs_Ns.png"))
    if stability:
        lines += ["## Damage against the stability number", "", *[f"- {t}" for t in stability], "",
                  "![N_od against Ns](figures/stability_Nod_vs_Ns.png)", ""]
    history = history_chart(plt, done, folder)
    if history:
        lines += ["## Damage against time", "", *[f"- {t}" for t in history[1]], "",
                  f"![N_od against time]({history[0]})", ""]
    charts = figure_charts(plt, summary, done, folder)
    if charts:
        lines += ["## Headline figures against the varied keys", ""]
        for title, path in charts:
            lines += [f"### {title}", "", f"![{title}]({path})", ""]
    headline = [k for k in summary.get("headline", [])]
    lines += ["## Cases", "", "| " + " | ".join(["case", *summary.get("varied", []), "seed", "status", *headline]) + " |",
              "|" + "---|" * (4 + len(summary.get("varied", [])) + len(headline) - 1)]
    for c in cases:
        cells = [c["case"], *[str(c["values"].get(k, "")) for k in summary.get("varied", [])],
                 "" if c.get("seed") is None else str(c["seed"]), c["status"]]
        cells += [f"{c['figures'][k]:.4g}" if number(c["figures"].get(k)) else "" for k in headline]
        lines.append("| " + " | ".join(cells) + " |")
    failed = [c for c in cases if c["status"] == "failed"]
    if failed:
        lines += ["", "## Failed cases", ""]
        lines += [f"- {c['case']}: {c.get('reason', '')}"
                  + (f" (Slurm: {c['slurm_state']})" if c.get("slurm_state") else "")
                  + f"; log cases/{c['case']}/log.txt" for c in failed]
    tmp = os.path.join(folder, "report.md.tmp")
    with open(tmp, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, os.path.join(folder, "report.md"))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: sweep_report.py SWEEP_OUTPUT_DIR")
    main(sys.argv[1])
