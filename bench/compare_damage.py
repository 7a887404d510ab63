"""Two runs of one scene, unit by unit, over a common time window.

Description
    Compares what the units did in two `armour run` results of the same
    scene and layer (e.g. the stability scene at Dn/2 and at Dn/4 from the
    same settled layer, docs/stability.md): per unit, the largest
    displacement of its centre from its first recorded pose (in Dn) and the
    largest rotation from it (deg) over 0 .. T, T the shorter record (or
    --until). Prints both runs' distributions and their unit-by-unit
    differences; writes OUT/summary.json (SI; displacements in Dn, rotations
    in deg) and OUT/compare_damage.png (run B against run A, unit by unit).
    Refuses runs with different body counts or units; reports how far their
    first poses differ (the same settled layer gives ~0).
    With --loads-from T, the units' fluid loads too (bodies/external_force,
    N) at the records from T to the window's end, as bench/run_stability_speed.sh
    compares them: the rms of B - A over the rms of A's changing part (each
    unit's load less its mean over the window), for every unit and for the
    units that moved less than 0.1 Dn in both runs (whose loads are the
    mesh's, not their moves'), and each unit's largest load swing about its
    mean, B over A (median and quartiles), and the units' load intensities
    (each unit's rms swing about its mean, B against A unit by unit: rms of
    the differences over the rms of A's): summary.json "loads".

Usage
    /usr/bin/python3 bench/compare_damage.py RUN_A RUN_B --out OUT [--until S] [--dn M] [--loads-from S]
    (RUN_A, RUN_B: `armour run` output folders; Dn from RUN_A's summary.json
    damage.Dn, or --dn in m when the run has not finished)
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "analysis"))
from armour_results import read_bodies, read_summary  # noqa: E402
from load_measures import intensity_difference, swings, time_series_difference  # noqa: E402


def unit_motion(b, until, dn):
    """Largest displacement (Dn) and rotation (deg) per body over time <= until."""
    import numpy as np

    n = int(np.searchsorted(b.time, until, side="right"))
    pos, q = b.position[:n], b.orientation[:n]
    disp = np.linalg.norm(pos - pos[0], axis=2).max(axis=0) / dn
    dot = np.abs(np.einsum("tbk,bk->tb", q, q[0])).clip(max=1.0)
    rot = np.degrees(2.0 * np.arccos(dot)).max(axis=0)
    return disp, rot, b.time[n - 1]


def compare_loads(ba, bb, start, until, moved):
    """The loads of B against A at the records in [start, until] (see --loads-from)."""
    import numpy as np

    n = min(int(np.searchsorted(ba.time, until, side="right")), int(np.searchsorted(bb.time, until, side="right")))
    keep = np.flatnonzero(ba.time[:n] >= start - 1e-9)
    if len(keep) < 2:
        sys.exit(f"compare_damage: --loads-from {start}: fewer than 2 records before {until} s")
    out = {"window": [float(ba.time[keep[0]]), float(ba.time[keep[-1]])], "records": int(len(keep)),
           "record_time_shift": float(np.abs(ba.time[keep] - bb.time[keep]).max())}
    for name, sel in (("all_units", np.ones(ba.bodies, bool)), ("units_that_stayed", ~moved)):
        fa, fb = ba.external_force[keep][:, sel], bb.external_force[keep][:, sel]
        swing_a, swing_b = swings(fa), swings(fb)
        ratio = swing_b.max(axis=0) / swing_a.max(axis=0)
        out[name] = {"units": int(sel.sum()),
                     "intensity_difference": intensity_difference(fa, fb),
                     "rms_difference_over_changing_part": time_series_difference(fa, fb),
                     "peak_swing_ratio": {"median": float(np.median(ratio)), "quartiles": [
                         float(np.percentile(ratio, 25)), float(np.percentile(ratio, 75))]},
                     "mean_peak_swing": [float(swing_a.max(axis=0).mean()), float(swing_b.max(axis=0).mean())]}
    return out


def stats(x):
    import numpy as np

    return {"mean": float(np.mean(x)), "median": float(np.median(x)), "largest": float(np.max(x)),
            "above_0.1": int(np.sum(x >= 0.1)), "above_0.5": int(np.sum(x >= 0.5)), "above_1": int(np.sum(x >= 1.0))}


def main():
    import numpy as np

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run_a")
    p.add_argument("run_b")
    p.add_argument("--out", required=True, help="output folder (summary.json, compare_damage.png)")
    p.add_argument("--until", type=float, help="end of the window, s (default: the shorter record)")
    p.add_argument("--dn", type=float, help="Dn, m (default: RUN_A's summary.json damage.Dn)")
    p.add_argument("--loads-from", type=float, help="compare the units' fluid loads from this time on, s")
    a = p.parse_args()
    try:
        dn = a.dn or read_summary(a.run_a)["damage"]["Dn"]
    except (OSError, KeyError) as e:
        sys.exit(f"compare_damage: {a.run_a}: no damage.Dn in summary.json ({e}); give --dn in m")
    ba, bb = read_bodies(a.run_a), read_bodies(a.run_b)
    if ba.bodies != bb.bodies or not np.array_equal(ba.unit, bb.unit):
        sys.exit(f"compare_damage: {a.run_b}: {bb.bodies} bodies, {a.run_a} has {ba.bodies}: not the same layer")
    until = min(ba.time[-1], bb.time[-1]) if a.until is None else a.until
    da, ra, ta = unit_motion(ba, until, dn)
    db, rb, tb = unit_motion(bb, until, dn)
    start_gap = float(np.linalg.norm(ba.position[0] - bb.position[0], axis=1).max())
    rel = np.abs(db - da)
    summary = {
        "command": "compare_damage", "run_a": a.run_a, "run_b": a.run_b, "Dn": dn, "window_end": float(until),
        "recorded_end": [float(ta), float(tb)], "units": int(ba.bodies), "first_pose_gap": start_gap,
        "max_displacement_over_Dn": {"a": stats(da), "b": stats(db)},
        "max_rotation_deg": {"a": stats(ra), "b": stats(rb)},
        "unit_by_unit": {"mean_abs_difference_Dn": float(rel.mean()), "largest_abs_difference_Dn": float(rel.max()),
                         "correlation": float(np.corrcoef(da, db)[0, 1]) if da.std() > 0 and db.std() > 0 else None},
        "si_units": {"Dn": "m", "window_end": "s", "recorded_end": "s", "first_pose_gap": "m",
                     "loads": {"window": "s", "record_time_shift": "s", "mean_peak_swing": "N"}},
    }
    if a.loads_from is not None:
        summary["loads"] = compare_loads(ba, bb, a.loads_from, until, (da >= 0.1) | (db >= 0.1))
    os.makedirs(a.out, exist_ok=True)
    tmp = os.path.join(a.out, "summary.json.tmp")
    with open(tmp, "w") as f:
        json.dump(summary, f, indent=2)
    os.replace(tmp, os.path.join(a.out, "summary.json"))
    print(f"window 0 .. {until:g} s, {ba.bodies} units, first poses within {start_gap:.2e} m")
    for name, s in (("displacement (Dn)", summary["max_displacement_over_Dn"]),
                    ("rotation (deg)", summary["max_rotation_deg"])):
        for run in ("a", "b"):
            v = s[run]
            print(f"  largest {name:18s} {run}: mean {v['mean']:.4f}, median {v['median']:.4f}, "
                  f"largest {v['largest']:.4f}, >=0.1: {v['above_0.1']}, >=0.5: {v['above_0.5']}, >=1: {v['above_1']}")
    if "loads" in summary:
        lo = summary["loads"]
        for name in ("all_units", "units_that_stayed"):
            v = lo[name]
            print(f"  loads, {lo['records']} records {lo['window'][0]:g} .. {lo['window'][1]:g} s, {v['units']} "
                  f"{name.replace('_', ' ')}: rms of b - a {v['rms_difference_over_changing_part']:.3f} of a's "
                  f"changing part; intensities {v['intensity_difference']:.3f}; largest swing b / a median {v['peak_swing_ratio']['median']:.3f} (quartiles "
                  f"{v['peak_swing_ratio']['quartiles'][0]:.3f}-{v['peak_swing_ratio']['quartiles'][1]:.3f})")
    u = summary["unit_by_unit"]
    print(f"  unit by unit: mean |b - a| {u['mean_abs_difference_Dn']:.4f} Dn, largest "
          f"{u['largest_abs_difference_Dn']:.4f} Dn, correlation {u['correlation']}")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(9, 4))
    for axis, x, y, label in ((ax[0], da, db, "largest displacement (Dn)"), (ax[1], ra, rb, "largest rotation (deg)")):
        axis.loglog(np.maximum(x, 1e-4), np.maximum(y, 1e-4), ".")
        lim = [1e-4, max(x.max(), y.max(), 1e-3) * 1.5]
        axis.plot(lim, lim, "k:", lw=0.8)
        axis.set_xlabel(f"{os.path.basename(os.path.normpath(a.run_a))}: {label}")
        axis.set_ylabel(f"{os.path.basename(os.path.normpath(a.run_b))}: {label}")
    fig.suptitle(f"each unit over 0 .. {until:g} s")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "compare_damage.tmp.png"), dpi=120)
    os.replace(os.path.join(a.out, "compare_damage.tmp.png"), os.path.join(a.out, "compare_damage.png"))


if __name__ == "__main__":
    main()
