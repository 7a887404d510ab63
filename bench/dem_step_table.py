"""Table and OUT/summary.json of bench/run_dem_step.sh (SI units).

Reads, on stdin, one line per run: `drop VARIANT MULTIPLE DIR` or
`hold layer MULTIPLE DIR`; arguments: OUT, the drop's step limit, the
layer's step limit (s). A drop's first multiple is its reference.
"""

import json
import sys

import h5py
import numpy as np

DN = 0.04  # m, the stability scene's cube
DEFAULT_MULTIPLE = 0.2  # the DEM's default step, x its limit (engines/time_step.h, kDefaultSafety)


def drop_figures(run):
    with h5py.File(run + "/bodies.h5", "r", locking=False) as f:
        v = f["bodies/velocity"][:, 0]
        w = f["bodies/angular_velocity"][:, 0]
    i = int(np.argmin(v[:, 2]))  # the fastest fall: the frame before impact
    return {"impact_speed": float(-v[i, 2]), "rebound_speed": float(v[i:, 2].max()),
            "spin_max": float(np.linalg.norm(w[i:], axis=1).max())}


def hold_figures(run):
    with h5py.File(run + "/bodies.h5", "r", locking=False) as f:
        p = f["bodies/position"][:]
    moved = np.linalg.norm(p[-1] - p[0], axis=1) / DN
    summary = json.load(open(run + "/summary.json"))
    stepping = summary["seconds_per_unit_step"] * summary["steps"] * p.shape[1]
    return {"moved_0.01_dn": int((moved >= 0.01).sum()), "moved_0.25_dn": int((moved >= 0.25).sum()),
            "displaced": int((moved >= 1.0).sum()), "moved_max_dn": float(moved.max()),
            "sinking_mean": float((p[0, :, 2] - p[-1, :, 2]).mean()),
            "dem_seconds_per_simulated_second": stepping / summary["simulated_seconds"]}


def main():
    out, drop_limit, hold_limit = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    rows, reference = [], {}
    for line in sys.stdin:
        kind, variant, multiple, run = line.split()
        row = {"kind": kind, "variant": variant, "multiple": float(multiple),
               "dt": float(multiple) * (drop_limit if kind == "drop" else hold_limit)}
        try:
            row.update(drop_figures(run) if kind == "drop" else hold_figures(run))
            row["status"] = "ok"
        except (OSError, KeyError, ValueError) as error:
            row["status"] = "failed: %s" % error
        rows.append(row)
        if kind == "drop" and row["status"] == "ok":
            ref = reference.setdefault(variant, row)
            row["rebound_vs_reference"] = row["rebound_speed"] / ref["rebound_speed"] - 1.0
            row["spin_vs_reference"] = row["spin_max"] / ref["spin_max"] - 1.0
    default = next((r for r in rows if r["kind"] == "hold" and abs(r["multiple"] - DEFAULT_MULTIPLE) < 1e-9 and r["status"] == "ok"), None)
    print("%-6s %-6s %7s %10s  %s" % ("test", "", "x limit", "dt [s]", "figures"))
    for r in rows:
        if r["status"] != "ok":
            text = r["status"]
        elif r["kind"] == "drop":
            text = "rebound %.4f m/s (%+.1f %%), spin %.2f rad/s (%+.1f %%)" % (
                r["rebound_speed"], 100 * r["rebound_vs_reference"], r["spin_max"], 100 * r["spin_vs_reference"])
        else:
            if default:
                r["dem_cost_vs_default"] = r["dem_seconds_per_simulated_second"] / default["dem_seconds_per_simulated_second"]
            text = "moved >=0.01/0.25/1 Dn: %d/%d/%d, max %.3f Dn, sinking %.3f mm; DEM %.1f s per s%s" % (
                r["moved_0.01_dn"], r["moved_0.25_dn"], r["displaced"], r["moved_max_dn"], 1e3 * r["sinking_mean"],
                r["dem_seconds_per_simulated_second"],
                " (%.2f x the default's)" % r["dem_cost_vs_default"] if default else "")
        print("%-6s %-6s %7g %10.3g  %s" % (r["kind"], r["variant"], r["multiple"], r["dt"], text))
    doc = {"units": {"dt": "s", "impact_speed": "m/s", "rebound_speed": "m/s", "spin_max": "rad/s",
                     "sinking_mean": "m", "moved_max_dn": "Dn (0.04 m)",
                     "dem_seconds_per_simulated_second": "wall s of DEM stepping per s simulated",
                     "rebound_vs_reference": "relative to the finest step's", "spin_vs_reference": "relative"},
           "drop_dt_limit": drop_limit, "hold_dt_limit": hold_limit, "default_multiple": DEFAULT_MULTIPLE, "rows": rows}
    json.dump(doc, open(out + "/summary.json", "w"), indent=2)


if __name__ == "__main__":
    main()
