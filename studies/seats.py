#!/usr/bin/env python3
"""What makes a seat weak: each settled cube's seat against whether it left, on a curve's layers.

Description
    On a curve whose points share one settled layer per seed (`fluid.settle_density`: a
    body is the same seat at every point), reads each seed's settled layer (its
    scene.settled.toml) and measures every unit's seat there:
      - how far its outermost corner stands out of the slope's face (out_of_face_Dn), and
      - how far that stands above the outermost corner of its highest neighbour, the units
        whose centres lie within 1.5 Dn of its own along the face (above_neighbours_Dn;
        the pattern's slots are 1.24 Dn apart, so 1.5 Dn takes in the ring of nearest
        units of both layers). A unit above every neighbour (> 0) is proud: the local top
        of the layer, its upper faces open to the flow, no unit beside it as high.
    Then, from the kept cases' damage.csv (compare_curves.py's CURVE), how many of the
    curve's points each unit was displaced at (ended >= displaced_threshold from its settled
    pose, the damage analysis' own flag) and left its seat at (>= 0.25 Dn, the pull test's
    mark), and prints the units that did by how far they stood above their neighbours, with
    the chance that the displaced would fall among the proud units as often if they were
    drawn at random from the layers (the hypergeometric tail). A body in damage.csv that does
    not sit where the layer has it (1 mm) is refused: the curve did not run on that layer.

    The foot as a suspect of its own: the units at the foot, whose centres lie seaward of the
    face's foot (x < the slope's toe_x: over the toe, not on the face), set against the rest,
    proud or not, and the curve's factor on Ns (compare_curves.py's) with their displacements
    taken out, as a laboratory that counts only the units seated on the face would count.

    Without a curve, the layers alone, before any waves: each seed's proud units and units at
    the foot (a settle's layer judged before a wave is run on it).

    Where proud seats come from, with --placed SEED=FILE: FILE is the seed's layer as placed,
    before the settle (studies/dry_scene.py of the settled layer with --run RUN/.../settle
    --time 0: the settle's first record). Each seat's slide down the face in the settle
    (settle_down_face_Dn), the units by it against how many came out proud and were displaced,
    and the units at the foot placed there against those the settle slid there.

    Why a proud seat is weak, with --pulled SEED=FOLDER: FOLDER is bench/pull_vs_loads.py's output
    for a pull test of that seed's layer (bench/run_pull_test.sh) and a coupled run on it, so each
    pulled unit has its resistance (the pull it held before it moved 0.25 Dn) and the largest
    swing of the waves' load out of the face, both in its weight on its seat at rest. Their
    medians for the proud units and the rest, with the two-sided chance of a split as wide if
    the two were one population (Mann-Whitney's rank sum, normal approximation, ties averaged),
    tell a seat that holds less from one the waves load more.

    Cubes only (the stability scene's units): a unit's corners are its centre +- half its
    size along its own axes.

    Writes OUT/seats.csv (one row per seed and unit) and OUT/summary.json; lengths in m
    where named _m, in Dn where named _Dn.

Usage
    python3 studies/seats.py docs/results/stability_one_layer_dn4+docs/results/stability_curve_dn4:2050 \\
        --layer 1=docs/results/stability_one_layer_dn4/layers/seed-1.toml \\
        --layer 2=docs/results/stability_one_layer_dn4/layers/seed-2.toml \\
        --layer 3=docs/results/stability_one_layer_dn4/layers/seed-3.toml \\
        --layer 4=docs/results/stability_one_layer_dn4/layers/seed-4.toml --out OUT \\
        [--placed 1=docs/results/stability_one_layer_dn4/layers/seed-1.placed.toml ...] \\
        [--pulled 4=PULL_VS_LOADS]
    python3 studies/seats.py --layer 1=LAYER.toml [--placed 1=PLACED.toml] --out OUT
"""
import argparse
import csv
import itertools
import json
import math
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_curves import SEAT_LEFT, fail, print_ns_factor, read_curve, without_displaced  # noqa: E402

NEIGHBOUR_RADIUS = 1.5  # Dn, along the face: the ring of nearest units of both layers
BINS = [(-math.inf, -0.5), (-0.5, 0.0), (0.0, 0.5), (0.5, math.inf)]  # above_neighbours_Dn
SETTLE_BINS = [(-math.inf, 1.0), (1.0, 2.0), (2.0, math.inf)]  # settle_down_face_Dn


def rotation(q):
    """The rotation matrix of a quaternion [w, x, y, z] (the scene's order), normalised."""
    w, x, y, z = np.asarray(q, dtype=float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def read_layer(path):
    """Each unit's seat in a settled layer: s and y along the face (m), out of it and above its neighbours (Dn)."""
    try:
        with open(path, "rb") as f:
            scene = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        fail(f"{path}: not a readable scene ({e})")
    slopes = [w for w in scene.get("wall", []) if w.get("type") == "slope"]
    if len(slopes) != 1:
        fail(f"{path}: wall: needs one wall of type 'slope' (the face the seats are measured from)")
    units = {u["name"]: u for u in scene.get("unit", [])}
    bodies = scene.get("body", [])
    if not bodies:
        fail(f"{path}: body: none (not a settled layer: a settle writes scene.settled.toml)")
    for i, b in enumerate(bodies):
        if units.get(b.get("unit"), {}).get("shape") != "cube":
            fail(f"{path}: body.{i}.unit: not a cube (seats are measured for cubes)")
    size = units[bodies[0]["unit"]]["size"]
    slope = slopes[0]
    foot = np.array([slope.get("toe_x", 0.0), 0.0, slope.get("floor_z", 0.0)])
    cot = slope["cot"]
    normal = np.array([-1.0, 0.0, cot]) / math.hypot(1.0, cot)  # out of the face
    along = np.array([cot, 0.0, 1.0]) / math.hypot(1.0, cot)  # up the face
    corners = np.array(list(itertools.product((-0.5, 0.5), repeat=3))) * size
    seats = []
    for b in bodies:
        centre = np.array(b["position"], dtype=float)
        outermost = max((centre + corners @ rotation(b["orientation"]).T - foot) @ normal)
        seats.append({"s_m": float((centre - foot) @ along), "y_m": float(centre[1]), "size_m": size,
                      "x_from_foot_m": float(centre[0] - foot[0]), "out_of_face_Dn": float(outermost / size)})
    for i, seat in enumerate(seats):
        neighbours = [o["out_of_face_Dn"] for j, o in enumerate(seats) if j != i and
                      math.hypot(o["s_m"] - seat["s_m"], o["y_m"] - seat["y_m"]) < NEIGHBOUR_RADIUS * size]
        seat["above_neighbours_Dn"] = seat["out_of_face_Dn"] - max(neighbours) if neighbours else math.inf
    return seats


def count_points(seats, rows, layer_path):
    """Each seat's points displaced and left at, from the seed's rows of the curve (checked against the layer)."""
    for seat in seats:
        seat.update(points=0, points_left_seat=0, points_displaced=0)
    for r in rows:
        units = r.get("kept_units")
        if units is None or r["left_seat"] is None:
            fail(f"case {r['case']}: its damage.csv is not kept (cases/<case>/run/damage.csv, with body and "
                 f"final_displacement_over_Dn)")
        if len(units) != len(seats):
            fail(f"case {r['case']}: damage.csv has {len(units)} units, the layer {layer_path} {len(seats)}")
        for u in units:
            seat = seats[int(u["body"])]
            if max(abs(float(u["s_m"]) - seat["s_m"]), abs(float(u["y_m"]) - seat["y_m"])) > 1e-3:
                fail(f"case {r['case']}: body {u['body']} sits at s_m {float(u['s_m']):.4f}, y_m "
                     f"{float(u['y_m']):.4f} in damage.csv, at {seat['s_m']:.4f}, {seat['y_m']:.4f} in "
                     f"{layer_path}: the case did not run on this layer")
            seat["points"] += 1
            seat["points_left_seat"] += u["body"] in r["left_seat"]
            seat["points_displaced"] += u["displaced"] == "1"


def hypergeometric_sf(k, total, marked, drawn):
    """P(at least k of `drawn` units drawn at random from `total` are among the `marked`)."""
    ways = math.comb(total, drawn)
    return sum(math.comb(marked, i) * math.comb(total - marked, drawn - i)
               for i in range(k, min(marked, drawn) + 1)) / ways


def tally(seats, key):
    """(units, of them proud; units that `key` counts at >= 1 point, of them proud; points counted, proud's; P)."""
    proud = [s for s in seats if s["above_neighbours_Dn"] > 0]
    hit = [s for s in seats if s[key] > 0]
    hit_proud = [s for s in hit if s["above_neighbours_Dn"] > 0]
    points = sum(s[key] for s in seats)
    points_proud = sum(s[key] for s in proud)
    p = hypergeometric_sf(len(hit_proud), len(seats), len(proud), len(hit)) if hit else 1.0
    return len(seats), len(proud), len(hit), len(hit_proud), points, points_proud, p


def bin_label(lo, hi):
    if lo == -math.inf:
        return f"below {hi:+.1f} Dn"
    if hi == math.inf:
        return f"{lo:+.1f} Dn or more"
    return f"{lo:+.1f} to {hi:+.1f} Dn"


def print_table(seats):
    print("units by how far they stood above their highest neighbour (outermost corners, out of the face):")
    for lo, hi in BINS:
        group = [s for s in seats if lo <= s["above_neighbours_Dn"] < hi]
        left = sum(1 for s in group if s["points_left_seat"] > 0)
        displaced = sum(1 for s in group if s["points_displaced"] > 0)
        print(f"  {bin_label(lo, hi):>18}: {len(group):4d} units; left their seat at a point {left:3d} "
              f"({100 * left / max(1, len(group)):.1f} %), displaced at a point {displaced:3d} "
              f"({100 * displaced / max(1, len(group)):.1f} %), unit-points displaced "
              f"{sum(s['points_displaced'] for s in group)}")


def at_foot(seat):
    """Whether a unit's centre lies seaward of the face's foot: over the toe, not on the face."""
    return seat["x_from_foot_m"] < 0


def print_foot(seats, rows, figures):
    """Where the displaced sat: at the foot or over the face, proud or not; the curve without the foot's."""
    print("by where the centre sat (at the foot: seaward of the face's foot, over the toe) and whether it was proud:")
    for where, foot in (("at the foot", True), ("over the face", False)):
        for kind, proud in (("proud", True), ("not proud", False)):
            group = [s for s in seats if at_foot(s) == foot and (s["above_neighbours_Dn"] > 0) == proud]
            displaced = sum(1 for s in group if s["points_displaced"] > 0)
            print(f"  {where:>13}, {kind:>9}: {len(group):4d} units, displaced at a point {displaced:3d} "
                  f"({100 * displaced / max(1, len(group)):.1f} %), unit-points "
                  f"{sum(s['points_displaced'] for s in group)}")
    hit = [s for s in seats if s["points_displaced"] > 0]
    marked = sum(1 for s in seats if at_foot(s))
    hit_marked = sum(1 for s in hit if at_foot(s))
    points_marked = sum(s["points_displaced"] for s in seats if at_foot(s))
    p = hypergeometric_sf(hit_marked, len(seats), marked, len(hit)) if hit else 1.0
    print(f"units at the foot: {marked} of {len(seats)}; of the {len(hit)} displaced at a point, {hit_marked} "
          f"({points_marked} of {sum(s['points_displaced'] for s in seats)} unit-points), "
          f"{len(hit) * marked / len(seats):.1f} at random (P {p:.2g} of so many)")
    foot = {(s["seed"], s["body"]) for s in seats if at_foot(s)}
    taken = [sum(1 for u in r["kept_units"] if u["displaced"] == "1" and (int(r["seed"]), int(u["body"])) in foot)
             for r in rows]
    fit = print_ns_factor("the curve, every unit", rows)
    fit_face = print_ns_factor("the curve without the units at the foot", without_displaced(rows, taken))
    figures.update({"units_at_foot": marked, "displaced_units_at_foot": hit_marked,
                    "displaced_unit_points_at_foot": points_marked, "displaced_at_foot_p_value": p,
                    "ns_factor": list(fit) if fit else None,
                    "ns_factor_without_units_at_foot": list(fit_face) if fit_face else None})


def read_placed(seats, seed, path):
    """Each seat's slide down the face in the settle, from the seed's layer as placed (before the settle)."""
    placed = read_layer(path)
    mine = [s for s in seats if s["seed"] == seed]
    if len(placed) != len(mine):
        fail(f"--placed {seed}={path}: {len(placed)} bodies, the seed's settled layer {len(mine)}")
    for seat, before in zip(mine, placed):
        seat["settle_down_face_Dn"] = (before["s_m"] - seat["s_m"]) / seat["size_m"]
        seat["placed_at_foot"] = at_foot(before)


def print_placed(seats, figures, damage):
    """The units by how far the settle slid them down the face: how many came out proud and, with a curve
    (`damage`), how many were displaced."""
    placed = [s for s in seats if "settle_down_face_Dn" in s]
    hit = [s for s in placed if damage and s["points_displaced"] > 0]
    print(f"units by how far the settle slid them down the face (placed pose to settled seat; {len(placed)} units):")
    rows = []
    for lo, hi in SETTLE_BINS:
        group = [s for s in placed if lo <= s["settle_down_face_Dn"] < hi]
        proud = sum(1 for s in group if s["above_neighbours_Dn"] > 0)
        line = (f"  {bin_label(lo, hi):>18}: {len(group):4d} units, proud {proud:3d} "
                f"({100 * proud / max(1, len(group)):.1f} %)")
        row = {"from_Dn": lo if math.isfinite(lo) else None, "to_Dn": hi if math.isfinite(hi) else None,
               "units": len(group), "proud": proud}
        if damage:
            displaced = sum(1 for s in group if s["points_displaced"] > 0)
            line += (f", displaced at a point {displaced:3d} ({100 * displaced / max(1, len(group)):.1f} %), "
                     f"unit-points {sum(s['points_displaced'] for s in group)}")
            row["displaced_units"] = displaced
        print(line)
        rows.append(row)
    far = [s for s in placed if s["settle_down_face_Dn"] >= SETTLE_BINS[-1][0]]
    proud = [s for s in placed if s["above_neighbours_Dn"] > 0]
    for name, group in (("proud", proud), ("displaced at a point", hit))[:2 if damage else 1]:
        k = sum(1 for s in group if s["settle_down_face_Dn"] >= SETTLE_BINS[-1][0])
        p = hypergeometric_sf(k, len(placed), len(far), len(group)) if group else 1.0
        print(f"  slid {SETTLE_BINS[-1][0]:g} Dn or more: {k} of the {len(group)} {name}, "
              f"{len(group) * len(far) / len(placed):.1f} at random (P {p:.2g} of so many)")
        figures[f"settle_slid_far_{name.split()[0]}"] = k
        figures[f"settle_slid_far_{name.split()[0]}_p_value"] = p
    foot = [s for s in placed if at_foot(s)]
    for name, was in (("placed there", True), ("slid there in the settle", False)):
        group = [s for s in foot if s["placed_at_foot"] == was]
        print(f"  at the foot, {name}: {len(group)} units, proud "
              f"{sum(1 for s in group if s['above_neighbours_Dn'] > 0)}"
              + (f", displaced at a point {sum(1 for s in group if s['points_displaced'] > 0)}"
                 if damage else ""))
    figures["settle_slide_bins"] = rows


def read_pulled(seats, seed, folder):
    """Each pulled unit's resistance and peak load swing out of the face (unit weights) into its seat."""
    path = os.path.join(folder, "pull_vs_loads.csv")
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    except OSError as e:
        fail(f"--pulled {seed}={folder}: {path}: not readable ({e}; bench/pull_vs_loads.py writes it)")
    mine = {s["body"]: s for s in seats if s["seed"] == seed}
    for r in rows:
        body = int(r["body"])
        if body not in mine:
            fail(f"{path}: body {body}: seed {seed}'s layer has {len(mine)} units")
        # A unit the pull never moved held more than the test's largest pull: it ranks above every other.
        mine[body]["resistance_weights"] = float(r["resistance_weights"]) if r["resistance_weights"] else math.inf
        mine[body]["peak_swing_out_weights"] = float(r["peak_swing_out_weights"])


def rank_sum_p(a, b):
    """Two-sided P of Mann-Whitney's U for samples a and b (normal approximation, ties averaged)."""
    values = sorted(a + b)
    rank = {}
    for v in set(values):
        first = values.index(v)
        rank[v] = first + (values.count(v) + 1) / 2
    n1, n2, n = len(a), len(b), len(a) + len(b)
    u = sum(rank[v] for v in a) - n1 * (n1 + 1) / 2
    ties = sum(c**3 - c for c in (values.count(v) for v in set(values)))
    variance = n1 * n2 / 12 * ((n + 1) - ties / (n * (n - 1)))
    if variance <= 0:
        return 1.0
    z = (abs(u - n1 * n2 / 2) - 0.5) / math.sqrt(variance)
    return min(1.0, math.erfc(max(z, 0.0) / math.sqrt(2)))


def quartiles(values):
    """Lower quartile, median, upper quartile as text: sample values (a unit that held every pull: 'held')."""
    return [f"{v:.2f}" if math.isfinite(v) else "held" for v in np.percentile(values, [25, 50, 75], method="lower")]


def print_pulled(seats, figures):
    """Proud units against the rest: what they held in the pull test, and what the waves put on them."""
    pulled = [s for s in seats if "resistance_weights" in s]
    proud = [s for s in pulled if s["above_neighbours_Dn"] > 0]
    rest = [s for s in pulled if s["above_neighbours_Dn"] <= 0]
    if not proud or not rest:
        print(f"pulled units: {len(proud)} proud, {len(rest)} not: nothing to set side by side")
        return
    for key, what in (("resistance_weights", "held in the pull"),
                      ("peak_swing_out_weights", "largest load swing out of the face")):
        a, b = [s[key] for s in proud], [s[key] for s in rest]
        p = rank_sum_p(a, b)
        qa, qb = quartiles(a), quartiles(b)
        print(f"{what} (unit weights): proud {qa[1]} (quartiles {qa[0]}-{qa[2]}, {len(a)} units), the rest "
              f"{qb[1]} ({qb[0]}-{qb[2]}, {len(b)}); P {p:.2g} of a split as wide")
        medians = [float(np.percentile(v, 50, method="lower")) for v in (a, b)]
        medians = [m if math.isfinite(m) else None for m in medians]  # null: the median unit held every pull
        figures.update({f"{key}_median_proud": medians[0], f"{key}_median_rest": medians[1], f"{key}_p_value": p})
    figures.update({"pulled_units_proud": len(proud), "pulled_units_rest": len(rest)})
    gone = [s["resistance_weights"] for s in pulled if s["points_displaced"] > 0]
    stayed = [s["resistance_weights"] for s in pulled if s["points_displaced"] == 0]
    if gone and stayed:
        qg, qs = quartiles(gone), quartiles(stayed)
        p = rank_sum_p(gone, stayed)
        print(f"held in the pull by the units displaced at a point: {qg[1]} (quartiles {qg[0]}-{qg[2]}, "
              f"{len(gone)} units), by the rest {qs[1]} ({qs[0]}-{qs[2]}, {len(stayed)}); P {p:.2g} of a split "
              f"as wide")
        figures["resistance_weights_displaced_p_value"] = p


def write_outputs(seats, out, figures):
    os.makedirs(out, exist_ok=True)
    columns = ["seed", "body", "s_m", "y_m", "x_from_foot_m", "out_of_face_Dn", "above_neighbours_Dn",
               "settle_down_face_Dn", "points", "points_left_seat", "points_displaced", "resistance_weights",
               "peak_swing_out_weights"]
    with open(os.path.join(out, "seats.csv"), "w", newline="") as f:
        f.write("# each unit's seat on its settled layer, and the curve's points it left it at "
                "(lengths in m where _m, in Dn where _Dn; counts)\n")
        writer = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore", lineterminator="\n")
        writer.writeheader()
        for s in seats:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in s.items()})
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(dict(figures, si_units={"neighbour_radius": "Dn", "counts": "units or unit-points",
                                           "weights": "unit weights on the seat at rest (-)",
                                           "p_value": "probability"}), f, indent=2)
        f.write("\n")


def print_layers(seats, figures):
    """A layer's seats before any waves: how many units stand proud, and how many sit at the foot."""
    for seed in sorted({s["seed"] for s in seats}):
        mine = [s for s in seats if s["seed"] == seed]
        proud = sum(1 for s in mine if s["above_neighbours_Dn"] > 0)
        print(f"seed {seed}: {proud} of {len(mine)} units proud (above every neighbour within {NEIGHBOUR_RADIUS} "
              f"Dn, {100 * proud / len(mine):.1f} %), {sum(1 for s in mine if at_foot(s))} at the foot")
    proud = sum(1 for s in seats if s["above_neighbours_Dn"] > 0)
    print(f"all: {proud} of {len(seats)} units proud ({100 * proud / len(seats):.1f} %), "
          f"{sum(1 for s in seats if at_foot(s))} at the foot")
    figures.update({"units": len(seats), "proud_units": proud, "units_at_foot": sum(1 for s in seats if at_foot(s))})


def print_curve(seats, rows, figures):
    """The seats against the curve's damage: by height above the neighbours, proud or not, at the foot or not."""
    print_table(seats)
    for key, name in (("points_displaced", "displaced"), ("points_left_seat", "left_seat")):
        units, proud, hit, hit_proud, points, points_proud, p = tally(seats, key)
        verb = "were displaced" if name == "displaced" else "left their seat"
        print(f"proud units (above every neighbour within {NEIGHBOUR_RADIUS} Dn): {proud} of {units}; "
              f"of the {hit} units that {verb} at a point, {hit_proud} were proud "
              f"({points_proud} of {points} unit-points), {hit * proud / units:.1f} at random "
              f"(P {p:.2g} of so many)")
        figures.update({"units": units, "proud_units": proud, f"{name}_units": hit,
                        f"{name}_units_proud": hit_proud, f"{name}_unit_points": points,
                        f"{name}_unit_points_proud": points_proud, f"{name}_p_value": p})
    print_foot(seats, rows, figures)


def seed_specs(specs, option, seeds, what):
    """{seed: value} of SEED=VALUE options, each seed one of `seeds`."""
    given = {}
    for spec in specs:
        seed, eq, value = spec.partition("=")
        if not eq or seed.strip() not in seeds:
            fail(f"{option} {spec}: give SEED={what}, SEED one of the seeds ({', '.join(seeds)})")
        given[seed.strip()] = value
    return given


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("curve", nargs="?", help="kept curve(s), as compare_curves.py's CURVE: "
                        "FOLDER[:VALUE,...][+...]; without one, the layers' seats alone")
    parser.add_argument("--layer", action="append", default=[], metavar="SEED=FILE",
                        help="a seed's settled layer: its cases' RUN/.../settle/scene.settled.toml")
    parser.add_argument("--placed", action="append", default=[], metavar="SEED=FILE",
                        help="a seed's layer as placed, before the settle: studies/dry_scene.py of its "
                        "settled layer with --run RUN/.../settle --time 0")
    parser.add_argument("--pulled", action="append", default=[], metavar="SEED=FOLDER",
                        help="bench/pull_vs_loads.py's output for a pull test of the seed's layer")
    parser.add_argument("--out", required=True, help="output folder: seats.csv, summary.json")
    args = parser.parse_args()
    rows = read_curve(args.curve)[0] if args.curve else []
    for spec in args.layer:
        if not spec.partition("=")[0].strip().isdigit() or "=" not in spec:
            fail(f"--layer {spec}: give SEED=FILE (a seed and its settled layer)")
    layer_seeds = sorted({spec.partition("=")[0].strip() for spec in args.layer}, key=int)
    seeds = sorted({r["seed"] for r in rows}, key=int) if rows else layer_seeds
    if not seeds:
        fail("--layer: none given (give --layer SEED=FILE for each seed)")
    layers = seed_specs(args.layer, "--layer", seeds, "FILE")
    seats = []
    for seed in seeds:
        if seed not in layers:
            fail(f"--layer: seed {seed} of {args.curve} has no layer (give --layer {seed}=FILE)")
        layer = read_layer(layers[seed])
        if rows:
            count_points(layer, [r for r in rows if r["seed"] == seed], layers[seed])
        seats += [dict(s, seed=int(seed), body=i) for i, s in enumerate(layer)]
    figures = {"neighbour_radius_Dn": NEIGHBOUR_RADIUS, "seat_left_Dn": SEAT_LEFT}
    if rows:
        print_curve(seats, rows, figures)
    else:
        print_layers(seats, figures)
    for seed, path in seed_specs(args.placed, "--placed", seeds, "FILE").items():
        read_placed(seats, int(seed), path)
    if args.placed:
        print_placed(seats, figures, damage=bool(rows))
    for seed, folder in seed_specs(args.pulled, "--pulled", seeds, "FOLDER").items():
        read_pulled(seats, int(seed), folder)
    if args.pulled:
        print_pulled(seats, figures)
    write_outputs(seats, args.out, figures)


if __name__ == "__main__":
    main()
