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
    - the fluid load that moved it: the dynamic part of its fluid force (less its
      value at the first record) along the direction it finally moved (x-z
      plane), largest from 0.5 s before the move began to the pass, over the
      largest in all the waves before: below 1, it left under a load it had
      survived before (its hold had dropped); in submerged weights
      W' = (rho_s - rho_w) g Dn^3 too;
    - its displaced neighbours (seats closer than --neighbour Dn) and how far
      apart in time they passed the threshold;
    - its move at the pass up and out of the scene's slope wall (in Dn): a unit
      that slid down the face in its plane (down it by 3/4 of the threshold or
      more, out of it by under 1/4) while the water's load along its move was
      nowhere above 0 was moved by gravity (the units below it gone, or the
      water lifting it off its seat), not carried off by the water.
    Over all runs: how many displaced units left within --window s of a
    displaced neighbour, against the same count with each run's pass times
    shuffled among its displaced units (so that the waves units leave in are
    kept and only who leaves with whom is random): the chance of as many
    together if neighbours left independently. Writes OUT/departures.csv (one
    row per displaced unit, SI) and OUT/summary.json (the headline figures);
    prints the same.

Usage
    python3 studies/departures.py RUN/cases/*/run --out OUT
    python3 studies/departures.py OUT1 OUT2 --out OUT --neighbour 2.2 --window 1.0
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

SHUFFLES = 4000  # enough for a chance of 1e-3 to be told from 0 (seeded: the same figure every run)


def fail(message):
    print(f"armour: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_run(folder):
    """The run's record and damage: times, positions, fluid forces, the displaced units and the scales."""
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
        record = {"time": f["time"][:], "position": f["bodies/position"][:],
                  "force": f["bodies/external_force"][:]}
    dn, g = damage["Dn"], abs(scene["run"]["gravity"][2])
    return {"name": folder, "face": face_directions(scene),
            "displaced": [int(r["body"]) for r in rows if r["displaced"] == "1"],
            "seat_s": {int(r["body"]): float(r["s_m"]) for r in rows},
            "dn": dn, "threshold": damage.get("displaced_threshold", 1.0),
            "weight": damage["delta"] * scene["fluid"]["fluid_density"] * g * dn ** 3,
            "moved": np.linalg.norm(record["position"] - record["position"][0], axis=2) / dn, **record}


def face_directions(scene):
    """(up the face, out of it): unit vectors of the scene's slope wall (rising in +x); None without one."""
    slope = next((w for w in scene.get("wall", []) if w.get("type") == "slope"), None)
    if slope is None:
        return None
    cot = float(slope["cot"])
    norm = math.hypot(cot, 1.0)
    return np.array([cot, 0.0, 1.0]) / norm, np.array([-1.0, 0.0, cot]) / norm


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
    load = (run["force"][:, body] - run["force"][0, body]) @ way
    window = int(np.searchsorted(t, t[start] - 0.5))
    now = load[window:k + 1].max()
    before = max(load[:window].max(), 0.0) if window > 0 else 0.0
    # slid down the face in its plane: down it by 3/4 of the threshold or more, out of it by under 1/4
    slid = up is not None and up <= -0.75 * run["threshold"] and abs(out) < 0.25 * run["threshold"]
    # None: no load that way before (the first wave to push it so, or no wave before the move)
    return {"run": run["name"], "body": body, "seat_s": run["seat_s"][body], "move_start": float(t[start]),
            "passed": float(t[k]), "load": float(now), "load_over_weight": float(now / run["weight"]),
            "largest_before": float(before), "ratio": float(now / before) if before > 0 else None,
            "up_face_over_Dn": up, "out_of_face_over_Dn": out, "slid_down_the_face": slid}


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
    args = parser.parse_args()
    if args.neighbour <= 0 or args.window <= 0:
        fail("--neighbour and --window: must be above 0")
    runs = [read_run(folder) for folder in args.runs]

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
                  f"{r['move_start']:.2f} s, passed the threshold at {r['passed']:.2f} s under "
                  f"{r['load_over_weight']:.2f} W', " + (f"{r['ratio']:.2f} x the largest load before" if r["ratio"]
                                                        else "the first load that way") +
                  (f"; moved {r['up_face_over_Dn']:+.2f} Dn up the face, {r['out_of_face_over_Dn']:+.2f} Dn out of it"
                   if r["up_face_over_Dn"] is not None else ""))
    summary = headline(units, seen, shuffled, args)
    write(args.out, units, summary)


def headline(units, seen, shuffled, args):
    """The figures over all runs, printed and returned for summary.json."""
    first = sum(1 for r in units if r["ratio"] is None)
    ratios = sorted(r["ratio"] for r in units if r["ratio"] is not None)
    summary = {"units_displaced": len(units), "neighbour": args.neighbour, "window": args.window,
               "left_under_the_first_load_that_way": first,
               "left_under_a_smaller_load_than_before": sum(1 for r in ratios if r < 1),
               "si_units": {"neighbour": "Dn", "window": "s"}}
    if ratios:
        q = statistics.quantiles(ratios, n=4, method="inclusive") if len(ratios) > 1 else [ratios[0]] * 3
        summary.update(load_ratio_median=q[1], load_ratio_quartiles=[q[0], q[2]])
        print(f"{len(units)} displaced units: {summary['left_under_a_smaller_load_than_before']} left under a "
              f"smaller load than the largest before, {first} under the first load that way; the ratio's median "
              f"{q[1]:.2f} (quartiles {q[0]:.2f}-{q[2]:.2f}, of the {len(ratios)} with a load before)")
    if any(r["up_face_over_Dn"] is not None for r in units):
        slid = [r for r in units if r["slid_down_the_face"]]
        summary.update(slid_down_the_face=len(slid),
                       slid_down_the_face_unpushed=sum(1 for r in slid if r["load"] <= 0))
        print(f"slid down the face in its plane (down it >= 3/4 of the threshold, out of it < 1/4): {len(slid)} of "
              f"{len(units)}, {summary['slid_down_the_face_unpushed']} of them with no water load along their move "
              f"while they moved (gravity's move, not the water's)")
    chance = sum(1 for s in shuffled if s >= seen) / len(shuffled)
    summary.update(left_with_a_neighbour=seen, left_with_a_neighbour_shuffled=sum(shuffled) / len(shuffled),
                   chance_of_as_many=chance)
    print(f"left within {args.window:g} s of a displaced neighbour (seats < {args.neighbour:g} Dn apart): {seen} of "
          f"{len(units)}; with the pass times shuffled within each run: {summary['left_with_a_neighbour_shuffled']:.1f} "
          f"(P of {seen} or more {chance:.2g})")
    return summary


def write(out, units, summary):
    """Both files whole or neither: each written beside itself and renamed."""
    os.makedirs(out, exist_ok=True)
    fields = ["run", "body", "seat_s", "move_start", "passed", "load", "load_over_weight", "largest_before", "ratio",
              "up_face_over_Dn", "out_of_face_over_Dn", "slid_down_the_face"]
    table = os.path.join(out, "departures.csv")
    with open(table + ".tmp", "w", newline="") as f:
        f.write("# displaced units (SI: seat_s m up the slope, times s, loads N along the unit's move; "
                "load_over_weight in submerged weights; ratio the load over the largest before; the move at the pass "
                "up and out of the slope's face in Dn)\n")
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        writer.writerows(units)
    with open(os.path.join(out, "summary.json.tmp"), "w") as f:
        json.dump(summary, f, indent=2)
    os.replace(table + ".tmp", table)
    os.replace(os.path.join(out, "summary.json.tmp"), os.path.join(out, "summary.json"))


if __name__ == "__main__":
    main()
