#!/usr/bin/env python3
"""Many seeds' settled layers, grouped: is one way of settling weaker than another, or a seed's draw?

Description
    A layer decides which units leave (docs/validation/stability.md "What makes a seat weak"):
    the proud units (outermost corner above every neighbour's within 1.5 Dn along the face,
    studies/seats.py) and the units at the foot (centre seaward of the face's foot) are most of
    the displaced. Four seeds cannot tell whether a way of settling (a density, a friction, a
    placement) makes more such seats or whether a few seeds drew them; `armour sweep
    --settle-only` settles a case's layer in a minute or two, so many seeds can.

    RUN is such a sweep's folder. Its cases are grouped by the value of the key the sweep varies
    (one group when it varies none). Per layer: porosity, packing (units per Dn^2), thickness
    coefficient k_t (the settle's summary), units at the foot, proud units, proud units low on
    the face (centre within LOW_ON_FACE of the foot along the face, where every unit the Dn/4
    curves displaced sat) and proud units at the foot. Per group: the mean and its 95 % interval
    over the seeds (Student's t, as the sweep's report takes it). Per other group: the mean
    difference from the --against group over the seeds both hold (one seed: one placed pile,
    settled two ways) with its 95 % interval, and the two-sided sign-test P of the per-seed
    differences.

    With --curve FOLDER (a kept curve, compare_curves.py's: results.csv and each case's
    damage.csv, run on each case's own settle, as RUN's cases are): each case of the curve that
    RUN settled again, its layer checked seat by seat against the case's damage.csv (1 mm), its
    units displaced against Van der Meer's expectation next to the layer's figures, and the rank
    correlation (Spearman) over those cases between each figure and where the case's count lies
    in the Poisson distribution of his expectation (its mid-P, P(X < count) + P(X = count) / 2:
    0.5 on average where the formula holds, whatever the case's Ns), with the chance of one as
    large or larger in either sign if the two were unrelated (20 000 random pairings, seeded).

    Writes OUT/layers.csv (one row per case), OUT/summary.json (per group: mean and interval of
    each figure; the paired differences; the correlations) and OUT/layers.png (each layer's
    proud units, units at the foot and porosity by group). Lengths in m, counts in units.

Usage
    build/apps/armour sweep studies/stability_cubes.toml --out RUN --settle-only --seeds 1,2,3,4,5,6,7,8
    (the layers kept in docs/results/settled_layers_dn4 add --set fluid.settle_stages=1: settled at once)
    python3 studies/settled_layers.py RUN --against 2050 [--curve docs/results/stability_curve_dn4] --out OUT
"""
import argparse
import csv
import json
import math
import os
import random
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_curves import fail, mean_interval, poisson_cdf, read_curve  # noqa: E402
from seats import at_foot, count_points, hypergeometric_sf, read_layer  # noqa: E402

LOW_ON_FACE = 0.27  # m along the face from its foot: every unit the Dn/4 curves displaced sat below
FIGURES = ["porosity", "packing_density", "layer_coefficient", "units_at_foot", "proud_units",
           "proud_units_low", "proud_units_at_foot"]


def proud(seat):
    """Whether a unit's outermost corner stands above every neighbour's (seats.py's measure)."""
    return seat["above_neighbours_Dn"] > 0


def numeric(text):
    """Whether a group label (a value of the varied key) is a number."""
    return re.fullmatch(r"-?[0-9.]+", str(text)) is not None


def read_json(path, why):
    """The JSON file at path; `armour: error: PATH: not readable (WHY)` and exit 2 if it cannot be read."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError):
        fail(f"{path}: not readable ({why})")


def layer_figures(run):
    """A settle-only run's layer: the summary's figures and the seats' counts, with its seats."""
    summary = read_json(os.path.join(run, "summary.json"), "a case not done? `armour sweep` again goes on")
    if not summary.get("settle_only") or not isinstance(summary.get("settled_layer"), dict):
        fail(f"{run}/summary.json: not an `armour run --settle-only` summary (no settled_layer)")
    layer = summary["settled_layer"]
    seats = read_layer(os.path.join(run, "settle", "scene.settled.toml"))
    tops = [s for s in seats if proud(s)]
    return {"porosity": layer["porosity"], "packing_density": layer["packing_density"],
            "layer_coefficient": layer["layer_coefficient"], "units": len(seats),
            "units_at_foot": sum(1 for s in seats if at_foot(s)),
            "proud_units": len(tops),
            "proud_units_low": sum(1 for s in tops if s["s_m"] < LOW_ON_FACE),
            "proud_units_at_foot": sum(1 for s in tops if at_foot(s))}, seats


def read_sweep(folder):
    """[(group label, {seed: figures})] of a settle-only sweep's done cases, {case id: seats}, the varied key."""
    plan = read_json(os.path.join(folder, "sweep.json"), "not an `armour sweep` folder")
    if not plan.get("settle_only"):
        fail(f"{folder}/sweep.json: not a settle-only sweep (run `armour sweep ... --settle-only`)")
    groups, seats = {}, {}
    for case in plan.get("cases", []):
        run = os.path.join(folder, "cases", case["case"], "run")
        if not os.path.isfile(os.path.join(run, "summary.json")):
            continue  # not done (yet): the groups hold the seeds done
        values = case.get("values", [])
        label = ",".join(f"{float(v):g}" if numeric(v) else str(v) for v in values) if values else "all"
        figures, case_seats = layer_figures(run)
        seed = case.get("seed")
        groups.setdefault(label, {})[seed] = dict(figures, case=case["case"], group=label)
        seats[case["case"]] = case_seats
    if not groups:
        fail(f"{folder}: no case done")
    return list(groups.items()), seats, " x ".join(plan.get("varied", [])) or "layers"


def finite(x):
    """x for JSON: None where it is not a number (no seeds in common, a constant figure's rank correlation)."""
    return None if isinstance(x, float) and not math.isfinite(x) else x


def interval(mean, half):
    return [finite(mean - half), finite(mean + half)]


def sign_test_p(differences):
    """Two-sided sign test of paired differences (ties dropped)."""
    up = sum(1 for d in differences if d > 0)
    down = sum(1 for d in differences if d < 0)
    n = up + down
    if n == 0:
        return 1.0
    tail = sum(math.comb(n, k) for k in range(0, min(up, down) + 1)) / 2 ** n
    return min(1.0, 2 * tail)


def chart(groups, varied, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.6))
    for ax, key, title in zip(axes, ("proud_units", "units_at_foot", "porosity"),
                              ("proud units", "units at the foot", "porosity")):
        for i, (label, layers) in enumerate(groups):
            values = [layer[key] for layer in layers.values()]
            ax.plot([i + (j % 5 - 2) * 0.05 for j in range(len(values))], values, "o", alpha=0.6)
            mean, half = mean_interval(values)
            ax.errorbar(i + 0.3, mean, yerr=half, fmt="ks", capsize=4)
        ax.set_xticks(range(len(groups)), [label for label, _ in groups])
        ax.set_title(title)
        ax.set_xlabel(varied)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("per layer (black: mean, 95 % interval)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def ranks(values):
    """Ranks from 1, ties given their mean rank."""
    order = sorted(range(len(values)), key=lambda i: values[i])
    r = [0.0] * len(values)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and values[order[j + 1]] == values[order[i]]:
            j += 1
        for k in range(i, j + 1):
            r[order[k]] = (i + j) / 2 + 1
        i = j + 1
    return r


def spearman(x, y):
    """Spearman's rank correlation (nan where either has one value only)."""
    rx, ry = ranks(x), ranks(y)
    mx, my = sum(rx) / len(rx), sum(ry) / len(ry)
    sxy = sum((a - mx) * (b - my) for a, b in zip(rx, ry))
    sxx = sum((a - mx) ** 2 for a in rx)
    syy = sum((b - my) ** 2 for b in ry)
    return sxy / math.sqrt(sxx * syy) if sxx > 0 and syy > 0 else math.nan


def permutation_p(x, y, rho, trials=20000):
    """P(|rho| at least as large) under random pairings of x with y (seeded: the same answer each time)."""
    if math.isnan(rho):
        return math.nan
    rng = random.Random(1)
    y = list(y)
    hits = 0
    for _ in range(trials):
        rng.shuffle(y)
        hits += abs(spearman(x, y)) >= abs(rho) - 1e-12
    return (hits + 1) / (trials + 1)


def poisson_mid_p(count, mean):
    """Where a count lies in Poisson(mean): P(X < count) + P(X = count) / 2 (0.5 on average under the mean)."""
    k = int(round(count))
    return 0.5 * ((poisson_cdf(k - 1, mean) if k > 0 else 0.0) + poisson_cdf(k, mean))


def against_curve(curve, labels, seats_by_case, layers_by_case, summary):
    """Each curve case RUN settled again: its layer checked, displaced against expected, the correlations."""
    rows, _ = read_curve(curve)
    joined = []
    for r in rows:
        seats = seats_by_case.get(r["case"])
        if seats is None:
            continue
        count_points(seats, [r], f"RUN's case {r['case']}")  # refuses a case that ran on another layer
        joined.append((r, layers_by_case[r["case"]]))
    if len(joined) < 3:
        fail(f"--curve {curve}: {len(joined)} of its cases settled again in RUN (the same case ids); need 3")
    score = [poisson_mid_p(float(r["units_displaced"]), float(r["units_displaced_van_der_meer"]))
             for r, _ in joined]
    print(f"the curve's cases on the layers settled again ({len(joined)}; displaced of Van der Meer's "
          f"expectation, and where the count lies in his Poisson distribution, the mid-P):")
    for (r, layer), mid_p in zip(joined, score):
        print(f"  {r['case']:>22}: displaced {float(r['units_displaced']):3.0f} of "
              f"{float(r['units_displaced_van_der_meer']):5.2f} (mid-P {mid_p:.2f}); proud {layer['proud_units']:3d} "
              f"(low {layer['proud_units_low']:2d}), at the foot {layer['units_at_foot']:3d}, "
              f"porosity {layer['porosity']:.3f}")
    correlations = {}
    for key in FIGURES:
        x = [layer[key] for _, layer in joined]
        rho = spearman(x, score)
        p = permutation_p(x, score, rho)
        correlations[key] = {"spearman": finite(rho), "p_value": finite(p)}
        print(f"  {key:>20} against the count's Poisson mid-P: Spearman {rho:+.2f} (P {p:.2g})")
    seats = [seat for r, _ in joined for seat in seats_by_case[r["case"]]]
    displaced = [seat for seat in seats if seat["points_displaced"] > 0]
    where = {}
    for name, weak in (("proud", proud), ("at_foot", at_foot)):
        marked = sum(1 for seat in seats if weak(seat))
        hit = sum(1 for seat in displaced if weak(seat))
        p = hypergeometric_sf(hit, len(seats), marked, len(displaced)) if displaced else 1.0
        where[name] = {"units": marked, "displaced": hit, "at_random": len(displaced) * marked / len(seats),
                       "p_value": p}
        print(f"  the displaced on their own layers: {hit} of {len(displaced)} {name.replace('_', ' ')} "
              f"({marked} of {len(seats)} units; {where[name]['at_random']:.1f} at random, P {p:.2g} of so many)")
    for label in labels:
        gone = [seat for r, layer in joined if layer["group"] == label for seat in seats_by_case[r["case"]]
                if seat["points_displaced"] > 0]
        if any(layer["group"] == label for _, layer in joined):
            print(f"    {label}: {len(gone)} displaced, {sum(1 for seat in gone if proud(seat))} proud, "
                  f"{sum(1 for seat in gone if at_foot(seat))} at the foot")
    summary["curve"] = {"folder": curve, "cases": [r["case"] for r, _ in joined], "correlations": correlations,
                        "displaced_units": len(displaced), "displaced_by_seat": where}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", help="an `armour sweep --settle-only` folder")
    parser.add_argument("--against", help="the group the others are paired with, seed by seed (a value of the "
                        "sweep's varied key; default: the first)")
    parser.add_argument("--curve", help="a kept curve whose cases RUN settled again (their own settles)")
    parser.add_argument("--out", required=True, help="output folder: layers.csv, summary.json, layers.png")
    args = parser.parse_args()
    groups, seats_by_case, varied = read_sweep(args.run)
    if all(numeric(label) for label, _ in groups):
        groups.sort(key=lambda g: float(g[0]))
    labels = [label for label, _ in groups]
    against = args.against if args.against is not None else labels[0]
    matches = [label for label in labels
               if label == against or (numeric(against) and numeric(label) and float(label) == float(against))]
    if not matches:
        fail(f"--against {against}: not a group of {args.run} (its groups: {', '.join(labels)})")
    reference_label = matches[0]
    summary = {"low_on_face_m": LOW_ON_FACE, "against": reference_label}
    summary["groups"], summary["paired"] = group_figures(groups, reference_label)
    layers_by_case = {layer["case"]: layer for _, layers in groups for layer in layers.values()}
    if args.curve:
        against_curve(args.curve, labels, seats_by_case, layers_by_case, summary)
    write_outputs(groups, varied, summary, args.out)


def group_figures(groups, reference_label):
    """Per group, each figure's mean and interval; per other group, its differences from the reference's."""
    figures, paired_all = {}, {}
    reference = dict(groups)[reference_label]
    for label, layers in groups:
        print(f"{label}: {len(layers)} layers (seeds {', '.join(str(s) for s in sorted(layers))})")
        entry = {"seeds": sorted(layers)}
        for key in FIGURES:
            mean, half = mean_interval([layer[key] for layer in layers.values()])
            entry[key] = {"mean": mean, "interval_95": interval(mean, half)}
            print(f"  {key:>20}: {mean:8.3f} +- {half:.3f}")
        figures[label] = entry
        if label == reference_label:
            continue
        common = sorted(set(layers) & set(reference))
        paired = {}
        for key in FIGURES:
            differences = [layers[s][key] - reference[s][key] for s in common]
            mean, half = mean_interval(differences) if differences else (math.nan, math.nan)
            paired[key] = {"mean_difference": finite(mean), "interval_95": interval(mean, half),
                           "sign_test_p": sign_test_p(differences), "seeds": len(common)}
            print(f"  {key:>20} minus {reference_label}'s, seed by seed ({len(common)}): {mean:+8.3f} "
                  f"+- {half:.3f} (sign test P {paired[key]['sign_test_p']:.2g})")
        paired_all[label] = paired
    return figures, paired_all


def write_outputs(groups, varied, summary, out):
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "layers.csv"), "w", newline="") as f:
        f.write("# each settled layer's figures (porosity -, packing units per Dn^2, k_t -, counts in units; "
                f"low: centre within {LOW_ON_FACE} m of the face's foot along the face)\n")
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(["case", "group", "seed", "units"] + FIGURES)
        for label, layers in groups:
            for seed in sorted(layers):
                layer = layers[seed]
                writer.writerow([layer["case"], label, seed, layer["units"]] +
                                [f"{layer[k]:.6g}" if isinstance(layer[k], float) else layer[k] for k in FIGURES])
    summary["si_units"] = {"low_on_face_m": "m", "packing_density": "units per Dn^2", "counts": "units"}
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")
    chart(groups, varied, os.path.join(out, "layers.png"))


if __name__ == "__main__":
    main()
