#!/usr/bin/env python3
"""The body-fitted reference of bench/run_body_fitted_loads.sh: its case and its comparison.

Description
    prepare: turns a copy of an `armour run` wave-flume case into a stock
    interFoam case with the held cube (body 0 of the resolved scene) cut out:
    an empty wall patch `cube` in blockMeshDict for subsetMesh to fill, a
    topoSetDict whose cellSet `fluid` is every cell but those with their
    centre inside the cube, the cube's boundary conditions in 0/*.orig
    (no-slip, fixedFluxPressure, zeroGradient), no coupling library, and
    OpenFOAM's forces function object on `cube` about the cube's centre.
    --compare: the loads of both runs over the window from FROM s to the end
    (and, with REFERENCE, of both against REFERENCE's body-fitted loads: a
    finer run); writes OUT/summary.json and OUT/body_fitted_loads.png.

Usage
    python3 bench/body_fitted_case.py CASE RESOLVED_SCENE.toml END_TIME
    python3 bench/body_fitted_case.py --compare OUT FROM [REFERENCE]
"""
import json
import os
import re
import sys
import tomllib


def cube_of(scene_file):
    with open(scene_file, "rb") as f:
        scene = tomllib.load(f)
    body = scene["body"][0]
    unit = next(u for u in scene["unit"] if u["name"] == body["unit"])
    return [float(v) for v in body["position"]], float(unit["size"])


def edit(path, change):
    with open(path) as f:
        text = f.read()
    new = change(text)
    if new == text:
        sys.exit(f"body_fitted_case.py: {path}: nothing to change (a template changed?)")
    with open(path, "w") as f:
        f.write(new)


def prepare(case, scene_file, end_time):
    centre, size = cube_of(scene_file)
    lo = [c - size / 2 for c in centre]
    hi = [c + size / 2 for c in centre]
    vec = lambda v: "(" + " ".join(f"{x:.9g}" for x in v) + ")"
    # subsetMesh -patch puts the exposed faces into an existing patch.
    edit(f"{case}/system/blockMeshDict",
         lambda t: re.sub(r"\n\);\s*$", "\n    cube\n    {\n        type wall;\n        faces ();\n    }\n);\n", t))
    with open(f"{case}/system/topoSetDict", "w") as f:
        f.write("FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n"
                "    object topoSetDict;\n}\n"
                "actions\n(\n"
                f"    {{ name fluid; type cellSet; action new; source boxToCell; box {vec(lo)} {vec(hi)}; }}\n"
                "    { name fluid; type cellSet; action invert; }\n);\n")
    patch = {"U": "type noSlip;", "p_rgh": "type fixedFluxPressure; value uniform 0;",
             "alpha.water": "type zeroGradient;"}
    for field, condition in patch.items():
        edit(f"{case}/0/{field}.orig",
             lambda t: re.sub(r"(boundaryField\s*\{)", r"\1\n    cube\n    {\n        " + condition + "\n    }",
                              t, count=1))

    def control(t):
        t = re.sub(r'"[^"]*libarmourFoamCoupling\.so"\s*', "", t)  # the coupling plugin
        t = re.sub(r"endTime\s+[^;]+;", f"endTime         {end_time};", t)
        t = re.sub(r"writeInterval\s+[^;]+;", f"writeInterval   {end_time};", t)
        forces = ("    cubeLoads\n    {\n        type forces;\n        libs (\"libforces.so\");\n"
                  "        writeControl timeStep;\n        writeInterval 1;\n        patches (cube);\n"
                  f"        rho rho;\n        CofR {vec(centre)};\n        log false;\n    }}\n")
        return re.sub(r"(functions\s*\{)", r"\1\n" + forces, t, count=1)
    edit(f"{case}/system/controlDict", control)


def table(path):
    """Rows of an OpenFOAM postProcessing .dat file: the header's names and the numbers."""
    names, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                words = line[1:].replace("(", " ").replace(")", " ").split()
                if words and words[0] == "Time":
                    names = words
                continue
            values = [float(v) for v in line.replace("(", " ").replace(")", " ").split()]
            if values:
                rows.append(values)
    return names, rows


def stock_loads(case):
    """Time, total force and total moment (about CofR) from the forces function object."""
    folder = f"{case}/postProcessing/cubeLoads/0"
    loads = {}
    for kind in ("force", "moment"):
        names, rows = table(f"{folder}/{kind}.dat")
        if not names or "total_x" not in names:  # v1912 writes (total) (pressure) (viscous) triples
            sys.exit(f"body_fitted_case.py: {folder}/{kind}.dat: no total_x column in its header")
        i = names.index("total_x")
        loads["time"] = [r[0] for r in rows]
        loads[kind] = [r[i:i + 3] for r in rows]
    return loads


def differences(a, r):
    """How far a is from the reference r: rms over the changing part of r, its ranges and peaks."""
    import numpy as np
    changing = r - r.mean()
    return {"rms_difference_over_changing_part": float(np.sqrt(np.mean((a - r) ** 2) / np.mean(changing ** 2))),
            "mean": float(a.mean()), "reference_mean": float(r.mean()),
            "range": float(np.ptp(a)), "reference_range": float(np.ptp(r)),
            "peak_ratio": float(np.max(np.abs(a - a.mean())) / np.max(np.abs(changing)))}


def body_fitted_series(folder, t):
    """Fx, Fz, My of a body-fitted run at the times t, and the time its record ends (s)."""
    import numpy as np
    ref = stock_loads(folder)
    rt = np.asarray(ref["time"])
    force, moment = np.asarray(ref["force"]), np.asarray(ref["moment"])
    return {"Fx": np.interp(t, rt, force[:, 0]), "Fz": np.interp(t, rt, force[:, 2]),
            "My": np.interp(t, rt, moment[:, 1])}, float(rt[-1])


def compare(out, start, reference=None):
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "analysis"))
    from armour_results import read_bodies

    b = read_bodies(f"{out}/immersed")
    t = np.asarray(b.time)
    window = t >= start
    ours = {"Fx": b.external_force[:, 0, 0], "Fz": b.external_force[:, 0, 2], "My": b.external_torque[:, 0, 1]}
    theirs, end = body_fitted_series(f"{out}/body_fitted", t)
    if end < t[-1] - 1e-6:
        sys.exit(f"body_fitted_case.py: the stock run ended at {end} s, before {t[-1]} s (log.interFoam)")
    wall = lambda p: float(open(p).read())
    # "loads": the immersed run against the body-fitted one on the same mesh (its reference).
    summary = {"window": [float(start), float(t[-1])], "units": "N, N m, s",
               "wall_seconds": {"immersed": wall(f"{out}/immersed.wall_seconds"),
                                "body_fitted": wall(f"{out}/body_fitted/wall_seconds")},
               "loads": {}}
    for k in ours:
        summary["loads"][k] = differences(ours[k][window], theirs[k][window])
    finest = None
    if reference:  # over the part of the window the reference covers
        finest, end = body_fitted_series(f"{reference}/body_fitted", t)
        both = window & (t <= end + 1e-9)
        summary["vs_reference"] = {"reference": os.path.abspath(reference), "window": [float(start), end], **{
            run: {k: differences(series[k][both], finest[k][both]) for k in series}
            for run, series in (("immersed", ours), ("body_fitted", theirs))}}
    with open(f"{out}/summary.json", "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")
    fig, axes = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    units = {"Fx": "N", "Fz": "N", "My": "N m"}
    still = min(np.searchsorted(t, 1.0), len(t) - 1)  # before the first wave: the buoyancy alone
    for ax, k in zip(axes, ours):
        # Fz less its still-water value (rho g V), so that the waves' swing shows.
        offset = theirs[k][still] if k == "Fz" else 0.0
        loaded = t > 0  # the first record comes before the first load
        ax.plot(t[loaded], theirs[k][loaded] - offset, "k-", lw=1, label="body-fitted (stock interFoam, no-slip wall)")
        ax.plot(t[loaded], ours[k][loaded] - offset, "r-", lw=1, label="immersed (armour coupling)")
        if finest is not None:
            shown = loaded & (t <= end + 1e-9)
            ax.plot(t[shown], finest[k][shown] - offset, "--", color="0.5", lw=1,
                    label="body-fitted on the reference's finer mesh")
        ax.axvline(start, color="grey", ls=":")
        s = summary["loads"][k]
        ax.set_ylabel(f"{k} less its still-water value [N]" if k == "Fz" else f"{k} [{units[k]}]")
        ax.set_title(f"{k}: rms difference {100 * s['rms_difference_over_changing_part']:.1f} % of the changing "
                     f"part, peak ratio {s['peak_ratio']:.3f}", fontsize=9)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[-1].set_xlabel("time [s]")
    fig.tight_layout()
    fig.savefig(f"{out}/body_fitted_loads.png", dpi=110)
    print(json.dumps(summary, indent=2))


if __name__ == "__main__":
    if len(sys.argv) in (4, 5) and sys.argv[1] == "--compare":
        compare(sys.argv[2], float(sys.argv[3]), sys.argv[4] if len(sys.argv) == 5 else None)
    elif len(sys.argv) == 4:
        prepare(sys.argv[1], sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
