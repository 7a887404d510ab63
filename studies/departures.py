#!/usr/bin/env python3
"""When each displaced unit left, under what load, and with which neighbours.

Description
    Reads the run folders of coupled damage runs (an `armour run` output, or
    RUN/cases/*/run of a sweep: bodies.h5, damage.csv, summary.json and
    scene.resolved.toml in each) and, for every unit damage.csv counts as
    displaced, finds
    - when it first passed the displaced threshold (analysis.displaced_threshold,
      in Dn, from its pose at the first record) and when its last move began
      (its last record under a fifth of the threshold before that);
    - the fluid load that moved it: the dynamic part of its fluid force (less
      the still water's load on it, its load at the record nearest --still s:
      buoyancy where it lies under water; the record at 0 s holds no fluid
      load yet, and the first steps' settle none) along the direction it
      finally moved (x-z plane), largest from 0.5 s before the move began to
      the pass, over the largest from --still on before: below 1, it left
      under a load it had survived before (its hold had dropped); in
      submerged weights W' = (rho_s - rho_w) g Dn^3 too (a unit dry in still
      water has its buoyancy in it once the run-up covers it);
    - the friction angle it would need to stay where it was as a free block
      face down on the slope, its weight W and whole fluid load F (buoyancy
      and all) taken together: atan2(|their part along the face|, W cos a -
      F.out), a the face's angle (the part along the face down, up or across
      it: friction holds all three); a unit at rest, under water or not,
      needs a itself, one lifted off the face more than 90 degrees. Its largest over the move's
      stretch and over the waves before, against the slope wall's friction
      angle (atan mu, mu the units' pair with the wall as the engines take
      it); and, for a unit of the inner layer (seated on the wall, its
      centre within 1 Dn of the face) that moved down the face in its plane
      (below), the same angle for the inner layer's units that stayed (moved under a quarter of the threshold) over the same
      stretch: whether the water asked more of the units that went;
    - its displaced neighbours (seats closer than --neighbour Dn) and how far
      apart in time they passed the threshold;
    - its move at the pass up and out of the scene's slope wall (in Dn): how
      many moved down the face in its plane (down it by 3/4 of the threshold or
      more, out of it by under 1/4), and how many of them met no load along
      their move beyond the still water's (a twentieth of W' or less). That
      load cannot tell a push from lost buoyancy: a unit the run-down uncovers
      loses its buoyancy, which counts there as a push down the face; the
      friction angle above takes the whole load and can. Whether such a unit
      slid or rolled there is its way out:
    - its way out, from the start of its last move to the pass: how far it
      turned (the angle between its orientations) per Dn its centre moved;
      rolled at 45 deg per Dn or more (half of a cube's roll over an edge,
      which turns it 90 deg while its centre moves 1 Dn), slid at 22.5 deg
      per Dn or less, slid and turned between; the share of those records in
      which it touched nothing (its contact force under a twentieth of W');
      and how far the water's upward load on it fell below the still water's
      (in its buoyancy submerged, rho_w g Dn^3: near 1 where the run-down
      uncovers a unit that lay under water);
    - its seat in the settled layer: at the foot, on top of the layer or in
      it (analysis/armour_results.py's unit_seats: damage.csv's at_foot, and
      n_m against the layer's thickness, or its on_top column), "unknown"
      where damage.csv does not say. Per seat the summary counts the ways out
      and the units whose move at the pass went down the face at all.
    A unit that passed the threshold before --still s (a layer still settling)
    has no load figures.
    Over all runs: how many displaced units left within --window s of a
    displaced neighbour, against the same count with each run's pass times
    shuffled among its displaced units (so that the waves units leave in are
    kept and only who leaves with whom is random): the chance of as many
    together if neighbours left independently. Writes OUT/departures.csv (one
    row per displaced unit, SI) and OUT/summary.json (the headline figures);
    prints the same.

Usage
    python3 studies/departures.py RUN/cases/*/run --out OUT
    python3 studies/departures.py OUT1 OUT2 --out OUT --neighbour 2.2 --window 1.0 --still 1.0
"""
import argparse
import csv
import json
import math
import os
import random
import statistics
import sys
import tomllib

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "analysis"))
from armour_results import SEATS, seat_name, seats_of_rows  # noqa: E402

SHUFFLES = 4000  # enough for a chance of 1e-3 to be told from 0 (seeded: the same figure every run)
PUSH = 0.05  # submerged weights: a load along a move below this is no push (the record's noise is ~1e-3 W')
ROLLED = 45.0  # deg turned per Dn moved: half a cube's roll over an edge (90 deg while its centre moves 1 Dn)
SLID = 22.5  # deg per Dn: a quarter of that roll
TOUCHING = 0.05  # submerged weights: a contact force below this is no contact


def fail(message):
    print(f"armour: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_run(folder, still):
    """The run's record and damage: times, positions, dynamic fluid forces, the displaced units and the scales."""
    paths = {name: os.path.join(folder, name)
             for name in ("bodies.h5", "damage.csv", "summary.json", "scene.resolved.toml")}
    for path in paths.values():
        if not os.path.isfile(path):
            fail(f"{path}: not found (not the folder of a coupled damage run)")
    with open(paths["summary.json"]) as f:
        damage = json.load(f).get("damage")
    if not isinstance(damage, dict) or "Dn" not in damage or "delta" not in damage:
        fail(f"{paths['summary.json']}: key 'damage' has no Dn and delta (not a damage analysis)")
    with open(paths["scene.resolved.toml"], "rb") as f:
        scene = tomllib.load(f)
    with open(paths["damage.csv"], newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    with h5py.File(paths["bodies.h5"], "r") as f:
        missing = [n for n in ("orientation", "contact_force") if "bodies/" + n not in f]
        if missing:
            fail(f"{paths['bodies.h5']}: no bodies/{missing[0]} (not a body record that armour run writes)")
        record = {"time": f["time"][:], "position": f["bodies/position"][:],
                  "orientation": f["bodies/orientation"][:], "contact": f["bodies/contact_force"][:],
                  "force": f["bodies/external_force"][:]}
    dn, g = damage["Dn"], abs(scene["run"]["gravity"][2])
    if still > record["time"][-1]:
        fail(f"{paths['bodies.h5']}: --still {still:g} s: the record ends at {record['time'][-1]:g} s")
    k_still = int(np.argmin(np.abs(record["time"] - still)))
    whole_force = record["force"]
    record["force"] = whole_force - whole_force[k_still]  # the dynamic part: less the still water's
    face = face_directions(scene)
    origin = face_origin(scene)
    off_wall = (record["position"][0] - origin) @ face[1] / dn if face and origin is not None else None
    weight_in_air = (1.0 + damage["delta"]) * scene["fluid"]["fluid_density"] * g * dn ** 3
    try:
        thickness = (damage.get("settled_layer") or {}).get("layer_thickness")
        seats = seats_of_rows(rows, thickness, paths["damage.csv"])
    except ValueError as e:
        fail(str(e))
    return {"k_still": k_still, "wall_friction": wall_friction(scene), "off_wall": off_wall,
            "hold": hold_angles(whole_force, weight_in_air, face[1]) if face else None, "name": folder, "face": face,
            "displaced": [int(r["body"]) for r in rows if r["displaced"] == "1"],
            "seat_s": {int(r["body"]): float(r["s_m"]) for r in rows},
            "seat": {body: seat_name(seat) for body, seat in seats.items()},
            "buoyancy": scene["fluid"]["fluid_density"] * g * dn ** 3, "dn": dn, "threshold": damage.get("displaced_threshold", 1.0),
            "weight": damage["delta"] * scene["fluid"]["fluid_density"] * g * dn ** 3,
            "moved": np.linalg.norm(record["position"] - record["position"][0], axis=2) / dn, **record}


def slope_wall(scene):
    """The scene's slope wall (its first [[wall]] of type "slope"), or None."""
    return next((w for w in scene.get("wall", []) if w.get("type") == "slope"), None)


def face_directions(scene):
    """(up the face, out of it): unit vectors of the scene's slope wall (rising in +x); None without one."""
    slope = slope_wall(scene)
    if slope is None:
        return None
    cot = float(slope["cot"])
    norm = math.hypot(cot, 1.0)
    return np.array([cot, 0.0, 1.0]) / norm, np.array([-1.0, 0.0, cot]) / norm


def face_origin(scene):
    """A point of the slope wall's face, its foot (toe_x, 0, floor_z), or None."""
    slope = slope_wall(scene)
    if slope is None or "toe_x" not in slope or "floor_z" not in slope:
        return None
    return np.array([float(slope["toe_x"]), 0.0, float(slope["floor_z"])])


def wall_friction(scene):
    """The friction between the units and the slope wall, as the engines take it: the scene's
    [[material_pair]] of the two materials, else the smaller of the two; None where it is not known."""
    slope = slope_wall(scene)
    units = scene.get("unit", [])
    if slope is None or not units:
        return None
    names = {slope.get("material"), units[0].get("material")}
    for pair in scene.get("material_pair", []):
        if {pair.get("a"), pair.get("b")} == names and "friction" in pair:
            return float(pair["friction"])
    frictions = [float(m["friction"]) for m in scene.get("material", []) if m.get("name") in names and "friction" in m]
    return min(frictions) if len(frictions) == len(names) else None


def departure(run, body):
    """One displaced unit: its pass of the threshold, the start of its last move and the load ratio."""
    t, moved = run["time"], run["moved"][:, body]
    k = int(np.argmax(moved >= run["threshold"]))
    start = k
    while start > 0 and moved[start] >= 0.2 * run["threshold"]:
        start -= 1
    way = run["position"][k, body] - run["position"][0, body]
    up, out = (float(way @ e / run["dn"]) for e in run["face"]) if run["face"] else (None, None)
    if np.hypot(way[0], way[2]) > 1e-3 * np.linalg.norm(way):
        way[1] = 0.0  # across the flume: not what the waves push (unless it is all the move)
    way /= np.linalg.norm(way)
    # down the face in its plane: down it by 3/4 of the threshold or more, out of it by under 1/4 (slid or rolled)
    in_plane = up is not None and up <= -0.75 * run["threshold"] and abs(out) < 0.25 * run["threshold"]
    row = {"run": run["name"], "body": body, "seat_s": run["seat_s"][body], "move_start": float(t[start]),
           "passed": float(t[k]), "load": None, "load_over_weight": None, "largest_before": None, "ratio": None,
           "hold_angle_deg": None, "hold_angle_before_deg": None, "inner_layer": inner_layer(run, body),
           "stayed_hold_angle_deg": None, "stayed_past_the_wall": None, "up_face_over_Dn": up,
           "out_of_face_over_Dn": out, "in_plane_down_the_face": in_plane, "seat": run["seat"].get(body, SEATS[3]),
           "upward_load_drop_over_buoyancy": None, **way_out(run, body, start, k)}
    still = run["k_still"]
    if k <= still:  # passed while the layer settled: no still water's load to read the water's against
        return row
    load = run["force"][:, body] @ way
    window = max(int(np.searchsorted(t, t[start] - 0.5)), still)
    now = load[window:k + 1].max()
    before = max(load[still:window].max(), 0.0) if window > still else 0.0
    pushed = lambda load: load > PUSH * run["weight"]
    # ratio None: no push along the move now, or none before (the first wave to push it so)
    lift = run["force"][max(start, still):k + 1, body, 2]  # the upward load less the still water's
    row.update(load=float(now), load_over_weight=float(now / run["weight"]),
               upward_load_drop_over_buoyancy=float(max(0.0, -lift.min()) / run["buoyancy"]),
               largest_before=float(before) if pushed(before) else 0.0,
               ratio=float(now / before) if pushed(now) and pushed(before) else None)
    if run["face"]:
        row.update(hold_figures(run, body, still, window, k + 1))
    return row


def way_out(run, body, start, k):
    """How a unit made its last move, records start to k (its pass): turned per Dn moved, and untouched."""
    q = run["orientation"][:, body]
    turn = math.degrees(2.0 * math.acos(min(1.0, abs(float(q[start] @ q[k])))))  # the angle between two poses
    span = float(np.linalg.norm(run["position"][k, body] - run["position"][start, body])) / run["dn"]
    per_dn = turn / span if span > 0.0 else None
    name = None if per_dn is None else "rolled" if per_dn >= ROLLED else "slid" if per_dn <= SLID else "slid and turned"
    touch = np.linalg.norm(run["contact"][start:k + 1, body], axis=1)
    return {"turn_deg": turn, "move_over_Dn": span, "turn_per_Dn_deg": per_dn, "way_out": name,
            "off_contact_share": float(np.mean(touch < TOUCHING * run["weight"]))}


def hold_figures(run, body, still, window, end):
    """The friction angles a unit needed to stay, over records [window, end) and before them from the still
    water's record; for a unit of the inner layer, the inner layer's units that stayed over the same records."""
    angle = run["hold"]
    figures = {"hold_angle_deg": float(angle[window:end, body].max()),
               "hold_angle_before_deg": float(angle[still:window, body].max()) if window > still else None}
    stayed = angle[window:end, inner_layer_that_stayed(run)].max(axis=0) if inner_layer(run, body) else []
    if len(stayed):
        wall = friction_angle(run["wall_friction"])
        figures.update(stayed_hold_angle_deg=float(np.median(stayed)),
                       stayed_past_the_wall=float(np.mean(stayed > wall)) if wall else None)
    return figures


def inner_layer(run, body):
    """Whether a unit sat on the slope wall's face (up the face from its foot, its centre within 1 Dn of it)."""
    return run["off_wall"] is not None and run["seat_s"][body] >= 0.0 and run["off_wall"][body] < 1.0


def inner_layer_that_stayed(run):
    """The units of the inner layer that the waves moved less than a quarter of the threshold."""
    displaced = set(run["displaced"])
    return [c for c in range(run["moved"].shape[1]) if c not in displaced and inner_layer(run, c)
            and run["moved"][-1, c] < 0.25 * run["threshold"]]


def friction_angle(mu):
    """atan(mu) in degrees, or None."""
    return math.degrees(math.atan(mu)) if mu else None


def hold_angles(whole_force, weight_in_air, out):
    """At each record (first axis), for each unit (second), the friction angle (deg) that would hold it as a free
    block face down on the slope whose outward normal is `out`, under its weight and whole fluid load."""
    total = whole_force - np.array([0.0, 0.0, weight_in_air])  # the water's and gravity's
    onto_the_face = -(total @ out)  # the weight's press onto the face less the water's lift
    along_the_face = np.linalg.norm(total + onto_the_face[..., None] * out, axis=-1)  # down, up or across it
    return np.degrees(np.arctan2(along_the_face, onto_the_face))


def neighbours(run, neighbour):
    """Each displaced unit's displaced neighbours: seats closer than `neighbour` Dn."""
    seats = run["position"][0]
    return {b: [c for c in run["displaced"]
                if c != b and np.linalg.norm(seats[b] - seats[c]) < neighbour * run["dn"]]
            for b in run["displaced"]}


def together(passed, near, window):
    """How many displaced units passed within `window` s of a displaced neighbour."""
    return sum(1 for b in passed if any(abs(passed[b] - passed[c]) <= window for c in near[b]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[1].strip(),
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", help="run folders of coupled damage runs")
    parser.add_argument("--out", required=True, help="folder to write departures.csv and summary.json")
    parser.add_argument("--neighbour", type=float, default=2.2, help="seats closer than this are neighbours [Dn]")
    parser.add_argument("--window", type=float, default=1.0, help="passes this close leave together [s]")
    parser.add_argument("--still", type=float, default=1.0,
                        help="the still water's instant: after the fluid's first steps, before the waves reach the "
                             "layer (the scenes' fronts arrive at ~4-5 s) [s]")
    args = parser.parse_args()
    if args.neighbour <= 0 or args.window <= 0 or args.still <= 0:
        fail("--neighbour, --window and --still: must be above 0")
    runs = [read_run(folder, args.still) for folder in args.runs]

    units, seen, shuffled, rng = [], 0, [0] * SHUFFLES, random.Random(1)
    for run in runs:
        rows = [departure(run, b) for b in run["displaced"]]
        units += rows
        passed = {r["body"]: r["passed"] for r in rows}
        near = neighbours(run, args.neighbour)
        seen += together(passed, near, args.window)
        times = list(passed.values())
        for i in range(SHUFFLES):
            rng.shuffle(times)
            shuffled[i] += together(dict(zip(passed, times)), near, args.window)
        for r in rows:
            print(f"{r['run']}: unit {r['body']} (seat {r['seat_s']:.3f} m up the slope) moved from "
                  f"{r['move_start']:.2f} s, passed the threshold at {r['passed']:.2f} s " + load_text(r) +
                  (f"; moved {r['up_face_over_Dn']:+.2f} Dn up the face, {r['out_of_face_over_Dn']:+.2f} Dn out of it"
                   if r["up_face_over_Dn"] is not None else "") + "; " + way_text(r))
    mu = next((run["wall_friction"] for run in runs if run["wall_friction"]), None)
    summary = headline(units, seen, shuffled, args, mu)
    write(args.out, units, summary)


def way_text(r):
    """A unit's seat and way out, as a line's words."""
    if r["way_out"] is None:
        return f"seat {r['seat']}; did not move between its records {r['move_start']:.2f} s and {r['passed']:.2f} s"
    text = (f"seat {r['seat']}; {r['way_out']}: turned {r['turn_deg']:.0f} deg over its last {r['move_over_Dn']:.2f} "
            f"Dn ({r['turn_per_Dn_deg']:.0f} deg per Dn), touching nothing in {100 * r['off_contact_share']:.0f} % "
            f"of its records")
    if r["upward_load_drop_over_buoyancy"] is not None:
        text += f", the upward load {r['upward_load_drop_over_buoyancy']:.2f} of its buoyancy below the still water's"
    return text


def load_text(r):
    """The load a unit left under, as a line's words."""
    if r["load"] is None:
        return "before the still water's record (no load figures)"
    if r["ratio"]:
        push = f"under {r['load_over_weight']:.2f} W', {r['ratio']:.2f} x the largest load before"
    elif r["largest_before"]:
        push = f"under no push along its move ({r['load_over_weight']:+.2f} W'; {r['largest_before']:.3g} N before)"
    else:
        push = (f"under {r['load_over_weight']:.2f} W', the first load that way" if r["load_over_weight"] > PUSH else
                f"under no push along its move ({r['load_over_weight']:+.2f} W')")
    hold = f", needing {r['hold_angle_deg']:.0f} deg of friction to stay" if r["hold_angle_deg"] is not None else ""
    return push + hold


def quartiles(values):
    """Median and quartiles (inclusive), or None for no values."""
    values = sorted(values)
    if not values:
        return None
    q = statistics.quantiles(values, n=4, method="inclusive") if len(values) > 1 else values * 3
    return q[1], [q[0], q[2]]


def headline(units, seen, shuffled, args, mu):
    """The figures over all runs, printed and returned for summary.json."""
    loaded = [r for r in units if r["load"] is not None]
    first = sum(1 for r in loaded if r["ratio"] is None and r["load_over_weight"] > PUSH)
    ratios = sorted(r["ratio"] for r in loaded if r["ratio"] is not None)
    summary = {"units_displaced": len(units), "neighbour": args.neighbour, "window": args.window,
               "still": args.still, "passed_before_the_still_record": len(units) - len(loaded),
               "left_under_the_first_load_that_way": first,
               "left_under_no_push": sum(1 for r in loaded if r["load_over_weight"] <= PUSH),
               "left_under_a_smaller_load_than_before": sum(1 for r in ratios if r < 1),
               "si_units": {"neighbour": "Dn", "window": "s", "still": "s", "hold_angle": "deg",
                            "turn_per_Dn": "deg per Dn moved", "off_contact_share": "-",
                            "upward_load_drop": "the unit's buoyancy submerged, rho_w g Dn^3 (-)"}}
    text = (f"{len(units)} displaced units: {summary['left_under_a_smaller_load_than_before']} left under a smaller "
            f"load than the largest before, {first} under the first load that way, {summary['left_under_no_push']} "
            f"under no push along their move")
    if ratios:
        median, (low, high) = quartiles(ratios)
        summary.update(load_ratio_median=median, load_ratio_quartiles=[low, high])
        text += f"; the ratio's median {median:.2f} (quartiles {low:.2f}-{high:.2f}, of the {len(ratios)} with both)"
    print(text)
    if summary["passed_before_the_still_record"]:
        print(f"{summary['passed_before_the_still_record']} passed the threshold before the still water's record at "
              f"{args.still:g} s (a layer still settling): no load figures")
    if any(r["up_face_over_Dn"] is not None for r in units):
        in_plane = [r for r in loaded if r["in_plane_down_the_face"]]
        summary.update(in_plane_down_the_face=sum(1 for r in units if r["in_plane_down_the_face"]),
                       in_plane_down_the_face_with_loads=len(in_plane),
                       in_plane_down_the_face_unpushed=sum(1 for r in in_plane if r["load_over_weight"] <= PUSH))
        print(f"moved down the face in its plane (down it >= 3/4 of the threshold, out of it < 1/4; slid or rolled): "
              f"{summary['in_plane_down_the_face']} of {len(units)}; of the {len(in_plane)} with load figures, "
              f"{summary['in_plane_down_the_face_unpushed']} met no load along their move beyond the still water's "
              f"(buoyancy a unit loses to the run-down counts there as a push down the face)")
        holds(summary, in_plane, [r for r in loaded if not r["in_plane_down_the_face"]], mu)
    summary["by_seat"] = ways_by_seat(units)
    chance = sum(1 for s in shuffled if s >= seen) / len(shuffled)
    summary.update(left_with_a_neighbour=seen, left_with_a_neighbour_shuffled=sum(shuffled) / len(shuffled),
                   chance_of_as_many=chance)
    print(f"left within {args.window:g} s of a displaced neighbour (seats < {args.neighbour:g} Dn apart): {seen} of "
          f"{len(units)}; with the pass times shuffled within each run: {summary['left_with_a_neighbour_shuffled']:.1f} "
          f"(P of {seen} or more {chance:.2g})")
    return summary


def ways_by_seat(units):
    """Per seat: the displaced units' ways out, printed and returned for summary.json."""
    result = {}
    for seat in SEATS:
        rows = [r for r in units if r["seat"] == seat]
        if not rows:
            continue
        median = lambda key: (float(np.median([r[key] for r in rows if r[key] is not None]))  # noqa: E731
                              if any(r[key] is not None for r in rows) else None)
        figures = {"units": len(rows), **{way.replace(" ", "_"): sum(r["way_out"] == way for r in rows)
                                          for way in ("rolled", "slid and turned", "slid")},
                   "moved_down_the_face": sum(1 for r in rows if (r["up_face_over_Dn"] or 0.0) < 0.0),
                   "turn_per_Dn_median_deg": median("turn_per_Dn_deg"),
                   "off_contact_share_median": median("off_contact_share"),
                   "upward_load_drop_median": median("upward_load_drop_over_buoyancy")}
        result[seat] = figures
        text = (f"{seat}: {len(rows)} displaced, {figures['rolled']} rolled, {figures['slid_and_turned']} slid and "
                f"turned, {figures['slid']} slid (rolled: turned {ROLLED:g} deg or more per Dn moved, slid: "
                f"{SLID:g} or less")
        if figures["turn_per_Dn_median_deg"] is not None:
            text += (f"; median {figures['turn_per_Dn_median_deg']:.0f} deg per Dn), touching nothing in a median "
                     f"{100 * figures['off_contact_share_median']:.0f} % of their move's records")
        else:
            text += ")"
        if figures["upward_load_drop_median"] is not None:
            text += (f", the upward load a median {figures['upward_load_drop_median']:.2f} of their buoyancy below "
                     f"the still water's")
        print(text + f"; {figures['moved_down_the_face']} moved down the face")
    return result


def holds(summary, in_plane, others, mu):
    """The friction angles the units that moved down the face in its plane and the other displaced needed to stay
    as free blocks, against the slope wall's (friction mu), and those of the inner layer against its units that
    stayed, over the same stretches."""
    wall = friction_angle(mu)
    summary["wall_friction_angle_deg"] = wall
    for name, words, rows in (("in_plane", "down the face in its plane", in_plane), ("others", "others", others)):
        q = quartiles(r["hold_angle_deg"] for r in rows if r["hold_angle_deg"] is not None)
        if not q:
            continue
        past = sum(1 for r in rows if wall is not None and r["hold_angle_deg"] > wall)
        summary[f"hold_angle_{name}_median_deg"], summary[f"hold_angle_{name}_quartiles_deg"] = q
        summary[f"hold_angle_{name}_past_the_wall"] = past
        print(f"friction angle needed to stay as a free block on the face while they moved, {words} ({len(rows)}): "
              f"median {q[0]:.0f} deg (quartiles {q[1][0]:.0f}-{q[1][1]:.0f})" +
              (f"; past the wall's {wall:.0f} deg (friction {mu:g}): {past}" if wall else ""))
    inner = [r for r in in_plane if r["stayed_hold_angle_deg"] is not None]
    if inner:
        own = float(np.median([r["hold_angle_deg"] for r in inner]))
        stayed = float(np.median([r["stayed_hold_angle_deg"] for r in inner]))
        share = float(np.mean([r["stayed_past_the_wall"] for r in inner]))
        summary.update(in_plane_inner_layer=len(inner), hold_angle_in_plane_inner_median_deg=own,
                       hold_angle_stayed_inner_same_stretches_median_deg=stayed,
                       stayed_inner_past_the_wall_share=share)
        print(f"of the inner layer (on the wall): the {len(inner)} in its plane needed a median {own:.0f} deg while they "
              f"moved; its units that stayed, over the same stretches, {stayed:.0f} deg, {100 * share:.0f} % of them "
              f"past the wall's")


def write(out, units, summary):
    """Both files whole or neither: each written beside itself and renamed."""
    os.makedirs(out, exist_ok=True)
    fields = ["run", "body", "seat_s", "move_start", "passed", "load", "load_over_weight", "largest_before", "ratio",
              "hold_angle_deg", "hold_angle_before_deg", "inner_layer", "stayed_hold_angle_deg", "stayed_past_the_wall",
              "up_face_over_Dn", "out_of_face_over_Dn", "in_plane_down_the_face", "seat", "way_out", "turn_deg",
              "move_over_Dn", "turn_per_Dn_deg", "off_contact_share", "upward_load_drop_over_buoyancy"]
    table = os.path.join(out, "departures.csv")
    with open(table + ".tmp", "w", newline="") as f:
        f.write("# displaced units (SI: seat_s m up the slope, times s, dynamic loads N along the unit's move; "
                "load_over_weight in submerged weights; ratio the load over the largest before; hold angles in deg (the "
                "friction angle a free block would need to stay on the face: over the move, over the waves before); the move at the pass up and out of the slope's face in Dn; "
                "the last move's turn in deg and length in Dn, its turn per Dn in deg; the share of its records touching nothing; "
                "the upward load's drop below the still water's in the unit's buoyancy rho_w g Dn^3; loads empty for a unit "
                "that passed before the still water's record)\n")
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        writer.writerows(units)
    with open(os.path.join(out, "summary.json.tmp"), "w") as f:
        json.dump(summary, f, indent=2)
    os.replace(table + ".tmp", table)
    os.replace(os.path.join(out, "summary.json.tmp"), os.path.join(out, "summary.json"))


if __name__ == "__main__":
    main()
