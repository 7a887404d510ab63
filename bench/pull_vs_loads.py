"""Each pulled unit's resistance (bench/run_pull_test.sh) beside the fluid loads a coupled run put on it.

Description
    PULL is a pull test's folder (pull.csv: each pulled unit's resistance in
    its own weights), RUN a coupled `armour run` of the same settled layer
    (bodies.h5, the same bodies in the same order). For every pulled unit:
    its fluid load's swing along the test's pull (out of the face, turned by
    the test's pull_angle toward down the face), d . (F(t) - F_still), largest
    over the window [--from, --until]; F_still is its mean load over the
    still-water records [--still-from, --still-until] (before the waves reach
    the armour), so the swing is what the waves add to buoyancy. It is given
    in the unit's weight on its seat at rest, m g - F_still,z (the submerged
    weight under water, the full weight above it), the measure the pull
    test's resistance uses. Beside it the unit's motion in the run (largest
    displacement of its centre, Dn). A unit whose swing never reached its
    resistance was never pulled out of its seat the way the test pulls.

    Each unit's seat, from the run's damage.csv and summary.json: at the
    foot (centre seaward of the face's foot), on top of the layer (centre
    farther out of the face than the layer is thick,
    damage.settled_layer.layer_thickness) or in the layer; per seat the
    summary gives the hold, the swing, and the margin: the factor the waves'
    load would have to grow by to reach a unit's hold, resistance / swing
    (a unit that held the test's largest pull: at least that).

    Forces in unit weights (-), displacements in Dn (-), times in s; writes
    OUT/summary.json, OUT/pull_vs_loads.csv and OUT/pull_vs_loads.png.

Usage
    /usr/bin/python3 bench/pull_vs_loads.py PULL RUN --out OUT [--from 4.5] [--until T]
"""
import argparse
import csv
import json
import os
import sys
import tomllib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "analysis"))
from armour_results import SEATS, read_bodies, read_summary, seat_name, unit_seats, write_rows  # noqa: E402


def by_seat(rows, pull_max):
    """The hold, the waves' swing and the margin between them (hold / swing, where the swing is out of the
    face at all) of the pulled units of one seat. A unit that held the whole pull counts as pull_max: its hold
    and margin are lower bounds, and so are the medians where such units reach them."""
    import numpy as np

    held = [r["resistance_weights"] if r["resistance_weights"] is not None else pull_max for r in rows]
    swing = [r["peak_swing_out_weights"] for r in rows]
    margin = sorted(h / w for h, w in zip(held, swing) if w > 0)
    return {"units": len(rows), "resistance_median": float(np.median(held)),
            "held_the_whole_pull": sum(r["stayed_in_pull"] for r in rows),
            "peak_swing_out_median": float(np.median(swing)), "peak_swing_out_largest": float(max(swing)),
            "margins_smallest_three": [float(m) for m in margin[:3]],
            "margin_median": float(np.median(margin)) if margin else None,
            "never_loaded_out_of_the_face": sum(1 for w in swing if w <= 0),
            "moved_0.25_Dn_in_run": sum(1 for r in rows if r["largest_move_in_run_Dn"] >= 0.25)}


def main():
    import numpy as np

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("pull")
    p.add_argument("run")
    p.add_argument("--out", required=True)
    p.add_argument("--from", dest="start", type=float, default=4.5, help="window start, s")
    p.add_argument("--until", type=float, help="window end, s (default: the record's end)")
    p.add_argument("--still-from", type=float, default=0.5, help="still-water records from, s")
    p.add_argument("--still-until", type=float, default=3.0, help="still-water records until, s")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.pull, "pull.csv")) as f:
        pulled = [r for r in csv.DictReader(line for line in f if not line.startswith("#")) if r.get("unseated") != "1"]
    damage = read_summary(a.run)["damage"]
    dn, delta = damage["Dn"], damage["delta"]
    # The resolved scene holds every key, defaults filled in.
    with open(os.path.join(a.run, "scene.resolved.toml"), "rb") as f:
        scene = tomllib.load(f)
    rho_w = scene["fluid"]["fluid_density"]
    cot = next(w["cot"] for w in scene["wall"] if w["type"] == "slope")
    alpha = np.arctan2(1.0, cot)
    # The pull test's direction: the face's outward normal turned by its angle toward down the face.
    try:
        pull_summary = read_summary(a.pull)
    except OSError:
        pull_summary = {}
    beta = np.radians(pull_summary.get("pull_angle_deg", 0.0))
    # A unit that held the whole pull held pull_max (without the test's summary: at least the largest pull any
    # unit of it held).
    pull_max = pull_summary.get("pull_max", max(
        (float(r["resistance_weights"]) for r in pulled if r["resistance_weights"]), default=0.0))
    normal = np.cos(beta) * np.array([-np.sin(alpha), 0.0, np.cos(alpha)]) - np.sin(beta) * np.array(
        [np.cos(alpha), 0.0, np.sin(alpha)])
    g = float(np.linalg.norm(scene["run"]["gravity"]))
    weight = (delta + 1.0) * rho_w * dn**3 * g  # N, a cube of edge Dn
    b = read_bodies(a.run)
    until = b.time[-1] if a.until is None else a.until
    still = (b.time >= a.still_from) & (b.time <= a.still_until)
    window = (b.time >= a.start) & (b.time <= until)
    if still.sum() < 2 or window.sum() < 2:
        sys.exit("pull_vs_loads: fewer than 2 records in the still-water window or the window")
    try:
        seats = {body: seat_name(seat) for body, seat in unit_seats(a.run).items()}
    except ValueError as e:
        sys.exit(f"armour: error: {e}")
    rows = []
    for r in pulled:
        i = int(r["body"])
        f_still = b.external_force[still, i].mean(axis=0)
        seat = weight - f_still[2]
        swing = (b.external_force[window, i] - f_still) @ normal / seat
        moved = np.linalg.norm(b.position[b.time <= until, i] - b.position[0, i], axis=1).max() / dn
        resistance = float(r["resistance_weights"]) if r["resistance_weights"] else None
        rows.append({"body": i, "seat": seats.get(i, SEATS[3]), "s_over_Dn": float(r["s_over_Dn"]), "resistance_weights": resistance,
                     "stayed_in_pull": r["stayed"] == "1", "seat_weight_N": float(seat),
                     "peak_swing_out_weights": float(swing.max()), "largest_move_in_run_Dn": float(moved)})
    reached = [r for r in rows if r["resistance_weights"] is not None and r["peak_swing_out_weights"] >= r["resistance_weights"]]
    summary = {
        "command": "bench/pull_vs_loads.py", "pull": a.pull, "run": a.run, "window": [a.start, float(until)],
        "still_window": [a.still_from, a.still_until], "pulled_units": len(rows),
        "peak_swing_out_median": float(np.median([r["peak_swing_out_weights"] for r in rows])),
        "peak_swing_out_largest": float(max(r["peak_swing_out_weights"] for r in rows)),
        "units_whose_swing_reached_their_resistance": len(reached),
        "of_those_moved_0.25_Dn_in_run": sum(1 for r in reached if r["largest_move_in_run_Dn"] >= 0.25),
        "units_that_moved_0.25_Dn_in_run": sum(1 for r in rows if r["largest_move_in_run_Dn"] >= 0.25),
        "by_seat": {seat: by_seat([r for r in rows if r["seat"] == seat], pull_max)
                    for seat in SEATS if any(r["seat"] == seat for r in rows)},
        "si_units": {"forces": "unit weights on the seat at rest (-)", "seat_weight_N": "N", "moves": "Dn (-)",
                     "window": "s", "margins": "resistance / largest swing (-)"},
    }
    json.dump(summary, open(os.path.join(a.out, "summary.json"), "w"), indent=2)
    write_rows(os.path.join(a.out, "pull_vs_loads.csv"), rows,
               "forces in unit weights on the seat at rest (-), moves in Dn (-)")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 5))
    top = max([r["resistance_weights"] or 0 for r in rows] + [r["peak_swing_out_weights"] for r in rows]) * 1.1
    colours, labelled = dict(zip(SEATS, ("tab:blue", "tab:orange", "tab:green", "tab:grey"))), set()
    for seat in SEATS:
        for moved in (False, True):
            for stayed in (False, True):
                part = [r for r in rows if r["seat"] == seat and r["stayed_in_pull"] == stayed
                        and (r["largest_move_in_run_Dn"] >= 0.25) == moved]
                if not part:
                    continue
                # A unit that held the test's largest pull sits at it (a lower bound).
                y = [r["resistance_weights"] if not stayed else pull_max for r in part]
                ax.scatter([r["peak_swing_out_weights"] for r in part], y, marker="^" if stayed else "o", s=24,
                           facecolors=colours[seat] if moved else "none", edgecolors=colours[seat],
                           label=None if seat in labelled else seat)
                labelled.add(seat)
    ax.plot([0, top], [0, top], "k--", lw=0.8, label="load = resistance")
    ax.set_xlabel("largest wave load out of the face [unit weights]")
    ax.set_ylabel("pull held in the pull test [unit weights]")
    ax.set_title("filled: moved >= 0.25 Dn in the run; triangles: held the test's largest pull", fontsize=8)
    ax.legend(fontsize=8)
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "pull_vs_loads.png"), dpi=110)
    print(json.dumps({k: summary[k] for k in summary if k.startswith(("units", "of_", "peak"))}))


if __name__ == "__main__":
    main()
