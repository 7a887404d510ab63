#!/usr/bin/env python3
"""When in the wave train the units left, and from which seats.

Description
    Reads the cases of one or more kept stability curves (folders written by
    studies/keep_results.py, or a sweep's own --out: cases/<case>/run/ with
    summary.json, damage_history.csv and damage.csv) and answers two
    questions about the damage they counted.

    When: each displaced unit is put at the time it left (damage.csv's
    left_at_s: since when it has stayed displaced), or, where damage.csv
    predates that column, at the time the case's count of displaced units
    first reached its number (damage_history.csv), as a share u of the case's wave train at the toe (the incident-wave analysis'
    window in summary.json: u = 0 where its first wave starts, 1 at the end;
    a unit gone before the window counts at 0 and is reported apart). Van der
    Meer's formula for cubes, Ns = (6.7 N_od^0.4 / N^0.3 + 1.0) s_om^-0.1
    (Van der Meer 1988), holds N_od proportional to N^0.75 at one Ns, so a
    stationary sea that damages a layer as his did has u^0.75 of its units
    gone by the share u of its waves: 35 % by the first quarter, 59 % by the
    first half. A layer that loses its units in the first large waves and
    then holds lies above that. The shares come with 95 % intervals from
    resampling the cases (units leave with their neighbours, so a case, not
    a unit, is one draw; 2000 resamples, a fixed seed; a draw with nothing
    displaced is left out).

    From where: each unit's settled centre (damage.csv: n_m out of the face,
    at_foot) against the layer's measured thickness (summary.json:
    damage.settled_layer.layer_thickness): on top of the layer where the
    centre lies farther out of the face than the layer is thick (more than
    half of the unit outside the double layer: a unit resting on it, not in
    it), in the layer otherwise; at the foot or on the face as the damage
    analysis flags it. Per class, the units and the displaced, in all and per
    point of the curve (the case folders' names less their _seed-N, with the
    points' mean Ns and Van der Meer's expected count summed). Cases whose
    damage.csv has no n_m column (written before it) count in the timing only.

    Prints a table per curve; with --out writes OUT/summary.json (the
    figures, dimensionless shares and counts) and OUT/timing.png (the
    cumulative share of the displaced against the share of the waves, each
    curve beside Van der Meer's u^0.75).

Usage
    python3 studies/damage_timing.py docs/results/settled_layers_dn4/staged_11_waves \\
        docs/results/stability_curve_dn4 --label staged --label "at once" --out OUT
"""
import argparse
import glob
import json
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "analysis"))
from armour_results import read_rows, seats_of_rows  # noqa: E402

EXPONENT = 0.75  # N_od ~ N^(0.3/0.4) at one Ns: Van der Meer (1988), cubes
SHARES = (0.25, 0.5)
RESAMPLES = 2000


def fail(message):
    print(f"armour: error: {message}", file=sys.stderr)
    sys.exit(2)


def departures(run, displaced):
    """The times (s) the case's displaced units left, and damage.csv's rows."""
    rows = read_rows(os.path.join(run, "damage.csv"))
    gone = [r for r in rows if r.get("displaced") == "1"]
    if len(gone) != displaced:
        fail(f"{os.path.join(run, 'damage.csv')}: {len(gone)} units displaced where summary.json says {displaced}")
    if rows and "left_at_s" in rows[0]:
        times = sorted(float(r["left_at_s"]) for r in gone)
    else:  # written before left_at_s: when the count first reached each number
        times, count = [], 0
        for row in read_rows(os.path.join(run, "damage_history.csv")):
            while count < min(int(row["units_displaced"]), displaced):
                count += 1
                times.append(float(row["time_s"]))
        if len(times) < displaced:
            fail(f"{os.path.join(run, 'damage_history.csv')}: the count reaches {len(times)}, "
                 f"summary.json's units_displaced is {displaced}")
    return times, rows


def read_case(run):
    """A case's departures (shares of its wave train) and its units' seats, or None without its files."""
    names = ("summary.json", "damage_history.csv", "damage.csv")
    if not all(os.path.isfile(os.path.join(run, n)) for n in names):
        return None
    path = os.path.join(run, "summary.json")
    try:
        with open(path) as f:
            summary = json.load(f)
        key = "waves.window"
        start, end = (float(v) for v in summary["waves"]["window"])
        key = "units_displaced"
        displaced = int(summary["units_displaced"])
        key = "damage.settled_layer.layer_thickness"
        layer = (summary.get("damage") or {}).get("settled_layer") or {}
        thickness = layer.get("layer_thickness")
    except json.JSONDecodeError as e:
        fail(f"{path}: not JSON ({e})")
    except (KeyError, TypeError, ValueError):
        fail(f"{path}: key '{key}': missing or not a number (not a coupled damage run's summary)")
    if end <= start:
        fail(f"{path}: key 'waves.window' [{start:g}, {end:g}] s holds no waves")
    try:
        times, rows = departures(run, displaced)
    except (KeyError, ValueError) as e:
        fail(f"{run}: damage.csv or damage_history.csv: a column missing or not a number ({e})")
    shares = [min(max((t - start) / (end - start), 0.0), 1.0) for t in times]
    case = {"shares": shares, "before_waves": sum(t < start for t in times), "seats": None,
            "Ns": summary.get("Ns"), "expected": summary.get("units_displaced_van_der_meer")}
    if rows and "n_m" in rows[0] and "at_foot" in rows[0] and thickness is not None:
        try:
            by_body = seats_of_rows(rows, thickness, os.path.join(run, "damage.csv"))
            seats = [by_body[int(r["body"])] for r in rows]
        except ValueError as e:
            fail(str(e))
        if all(s.at_foot is not None and s.above_layer is not None for s in seats):
            case["seats"] = [(("foot" if s.at_foot else "face"), ("on top" if s.above_layer else "in the layer"),
                              r["displaced"] == "1") for s, r in zip(seats, rows)]
    return case


def read_curve(folder):
    cases = []
    for run in sorted(glob.glob(os.path.join(folder, "cases", "*", "run"))):
        case = read_case(run)
        if case is not None:
            # The point: the case's folder name less its seed (density-1685_seed-2 -> density-1685).
            case["point"] = re.sub(r"_seed-\d+$", "", os.path.basename(os.path.dirname(run)))
            cases.append(case)
    if not cases:
        fail(f"{folder}: no case with summary.json, damage_history.csv and damage.csv under cases/*/run/")
    return cases


def share_by(shares, cut):
    return sum(u <= cut for u in shares) / len(shares) if shares else None


def interval(cases, cut, rng):
    """95 % interval of the pooled share by `cut`, the cases resampled with replacement (a draw with
    nothing displaced has no share and is left out)."""
    draws = []
    for _ in range(RESAMPLES):
        picked = rng.integers(0, len(cases), len(cases))
        shares = [u for i in picked for u in cases[i]["shares"]]
        if shares:
            draws.append(share_by(shares, cut))
    return [float(np.percentile(draws, 2.5)), float(np.percentile(draws, 97.5))] if draws else None


def seat_table(cases):
    table = {}
    for case in cases:
        for where, height, displaced in case["seats"] or []:
            entry = table.setdefault(f"{where}, {height}", {"units": 0, "displaced": 0})
            entry["units"] += 1
            entry["displaced"] += displaced
    return table


def by_point(cases):
    """Per point of the curve (its cases with seats): mean Ns, Van der Meer's expected count, the seats."""
    points = {}
    for case in cases:
        if case["seats"] is not None:
            points.setdefault(case["point"], []).append(case)
    return {point: {"cases": len(group),
                    "Ns": (sum(c["Ns"] for c in group) / len(group)
                           if all(c["Ns"] is not None for c in group) else None),
                    "van_der_meer_units": (sum(c["expected"] for c in group)
                                           if all(c["expected"] is not None for c in group) else None),
                    "seats": seat_table(group)} for point, group in sorted(points.items())}


def describe(label, cases, rng):
    shares = [u for c in cases for u in c["shares"]]
    result = {"label": label, "cases": len(cases), "displaced": len(shares),
              "before_waves": sum(c["before_waves"] for c in cases), "by_share_of_waves": {},
              "seats": seat_table(cases), "cases_with_seats": sum(c["seats"] is not None for c in cases),
              "seats_by_point": by_point(cases)}
    for cut in SHARES:
        result["by_share_of_waves"][f"{cut:g}"] = {
            "share_displaced": share_by(shares, cut), "interval_95": interval(cases, cut, rng),
            "van_der_meer": cut**EXPONENT}
    return result, shares


def print_result(r):
    print(f"{r['label']}: {r['cases']} cases, {r['displaced']} displaced ({r['before_waves']} before the first wave)")
    for cut, s in r["by_share_of_waves"].items():
        if s["share_displaced"] is None:
            continue  # nothing displaced: no share to give
        lo, hi = s["interval_95"]
        print(f"  gone by {float(cut):.0%} of the waves: {s['share_displaced']:.0%} (95 % {lo:.0%}-{hi:.0%}); "
              f"Van der Meer {s['van_der_meer']:.0%}")
    if r["seats"]:
        print(f"  seats ({r['cases_with_seats']} cases with n_m): units / displaced")
        for key in sorted(r["seats"]):
            print(f"    {key:24s} {r['seats'][key]['units']:5d} / {r['seats'][key]['displaced']}")
        for point, p in r["seats_by_point"].items():
            seats = ", ".join(f"{key} {v['displaced']} of {v['units']}" for key, v in sorted(p["seats"].items()))
            ns = f"Ns {p['Ns']:.2f}" if p["Ns"] is not None else "Ns -"
            vdm = f"{p['van_der_meer_units']:.1f}" if p["van_der_meer_units"] is not None else "-"
            print(f"    {point} ({p['cases']} cases, {ns}, Van der Meer {vdm}): {seats}")


def chart(curves, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4.5))
    u = np.linspace(0, 1, 101)
    ax.plot(u, u**EXPONENT, "k--", label="Van der Meer: N_od ~ N^0.75 at one Ns")
    for label, shares in curves:
        s = np.sort(shares)
        ax.step(np.concatenate([[0], s, [1]]), np.concatenate([[0], np.arange(1, len(s) + 1) / len(s), [1]]),
                where="post", label=f"{label} ({len(s)} displaced)")
    ax.set_xlabel("share of the wave train at the toe (-)")
    ax.set_ylabel("share of the displaced units gone (-)")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.02)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("curves", nargs="+", metavar="KEPT", help="a kept curve's folder (or a sweep's --out)")
    parser.add_argument("--label", action="append", default=[], help="a name per KEPT, in order")
    parser.add_argument("--out", help="folder for summary.json and timing.png")
    args = parser.parse_args()
    if args.label and len(args.label) != len(args.curves):
        fail(f"--label: {len(args.label)} given for {len(args.curves)} curves (one each, or none)")
    if args.out and os.path.exists(args.out) and not os.path.isdir(args.out):
        fail(f"--out {args.out}: exists and is not a folder")
    results, curves = [], []
    for i, folder in enumerate(args.curves):
        label = args.label[i] if args.label else folder
        # Each curve its own fixed seed: its interval does not depend on the curves before it.
        result, shares = describe(label, read_curve(folder), np.random.default_rng(1))
        print_result(result)
        results.append(result)
        curves.append((label, shares))
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        chart(curves, os.path.join(args.out, "timing.png"))
        with open(os.path.join(args.out, "summary.json"), "w") as f:
            json.dump({"command": "damage_timing", "exponent": EXPONENT, "curves": results,
                       "files": {"chart": "timing.png"},
                       "units": "shares and counts, dimensionless"}, f, indent=2, allow_nan=False)
            f.write("\n")


if __name__ == "__main__":
    main()
