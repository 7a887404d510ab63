#!/usr/bin/env bash
# Sphere clumps against exact shapes in a COUPLED scene: the solitary wave
# washing three light cubes off the platform (scenes/solitary_cubes_platform
# .toml), run with exact cubes (Bullet hulls, the reference) and with
# LIGGGHTS clumps of 8 and 27 optimised spheres, everything else equal:
#   - penalty 700 1/s for all (LIGGGHTS' soft contacts need <= 708 here, the
#     run's own warning; the scene's 1e3 would leave the clump runs unstable),
#   - the cubes placed 12 mm apart and 5 mm higher than in the scene (the
#     optimised 8-sphere clump's spheres protrude 4.4 mm past the faces)
#     and settled 0.3 s in the DEM under the still water by each engine,
#   - rolling friction 0.05 for the clumps (they rock on two spheres
#     otherwise, docs/dem.md).
# A fourth run, hulls_p1000, is the reference with penalty 1e3 instead of
# 700: the spread of the exact-shape result under a small change of a
# numerical setting, to read the clumps' differences against.
# Reports per model the wall time, the DEM's share, each cube's displacement,
# the time it starts to move (> 0.1 Dn) and the units displaced (> Dn), and
# against the hulls the difference of each cube's final position and largest
# displacement, in Dn. Writes OUT/summary.json,
# OUT/coupled_engines.png (accuracy against cost, and the cubes' x(t)),
# nothing in the source tree (docs/images figures are copied there by hand).
# Usage: bash bench/run_coupled_engines.sh [--build DIR] [--out DIR]
#   --build  default the repo's build/ (bash scripts/build.sh armour armourFoamCoupling armourWaves)
#   --out    default ${TMPDIR:-/tmp}/armour-bench/coupled_engines
# One run per model, one after the other (about 1.5 min each on 2 cores).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=coupled_engines bench_targets="armour armourFoamCoupling armourWaves" bench_options=""
source "$root/bench/common.sh"
bench_args "$@"
armour="$build/apps/armour"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
scene="$root/scenes/solitary_cubes_platform.toml"
common=(--set fluid.penalty=700 --set fluid.settle_time=0.3
        --set "body.0.position=[1.55, -0.036, 0.216]" --set "body.1.position=[1.55, 0.036, 0.216]"
        --set "body.2.position=[1.55, 0.0, 0.287]")
run_model() { # NAME ARGS...
  local name="$1"; shift
  echo "run_coupled_engines: $name" >&2
  "$armour" run "$scene" --out "$out/$name" "${common[@]}" "$@" 2>"$out/$name.log"
}
run_model hulls --set 'run.engine="bullet"'
run_model hulls_p1000 --set 'run.engine="bullet"' --set fluid.penalty=1e3
for n in 8 27; do
  run_model "clumps$n" --set 'run.engine="liggghts"' --set "unit.0.spheres=$n" --set 'unit.0.method="optimised"' \
    --set material.0.rolling_friction=0.05
done

/usr/bin/python3 - "$out" <<'PY'
import json, sys
from armour_results import read_bodies, read_summary
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

out = sys.argv[1]
models = ["hulls", "hulls_p1000", "clumps8", "clumps27"]
Dn = 0.06  # m, the scene's cube
runs = {}
for m in models:
    s = read_summary(f"{out}/{m}")
    b = read_bodies(f"{out}/{m}")
    t, p = b.time, b.position
    disp = np.linalg.norm(p - p[0], axis=2)
    onset = [float(t[np.argmax(disp[:, k] > 0.1 * Dn)]) if (disp[:, k] > 0.1 * Dn).any() else None
             for k in range(p.shape[1])]
    runs[m] = {"summary": s, "t": t, "p": p, "max_disp": disp.max(axis=0), "final": p[-1], "onset": onset,
               "displaced": int((disp.max(axis=0) > Dn).sum())}
ref = runs["hulls"]
rows = []
print(f"{'model':11s} {'wall s':>7s} {'DEM share':>9s} {'displaced':>9s} {'onset [s]':>17s} {'max disp per cube [m]':>22s} "
      f"{'final diff / Dn (max)':>22s} {'max-disp diff / Dn (max)':>25s}")
for m in models:
    r = runs[m]
    s = r["summary"]
    final_diff = np.linalg.norm(r["final"] - ref["final"], axis=1) / Dn
    disp_diff = np.abs(r["max_disp"] - ref["max_disp"]) / Dn
    row = {"model": m, "engine": s["engine"], "spheres": s.get("spheres_per_unit", {}).get("cube"),
           "wall_seconds": s["wall_seconds"], "dem_seconds": s.get("dem_seconds"),
           "dem_share_of_solver": s.get("dem_share_of_solver"),
           "units_displaced": r["displaced"], "onset_time_per_cube": r["onset"],
           "max_displacement_per_cube": r["max_disp"].tolist(),
           "final_position_per_cube": r["final"].tolist(),
           "final_position_difference_over_Dn": final_diff.tolist(),
           "max_displacement_difference_over_Dn": disp_diff.tolist()}
    rows.append(row)
    onsets = " ".join("-" if o is None else f"{o:.2f}" for o in r["onset"])
    print(f"{m:11s} {s['wall_seconds']:7.1f} {100 * (s.get('dem_share_of_solver') or 0):8.1f}% "
          f"{r['displaced']:6d}/{len(r['onset'])} {onsets:>17s} "
          f"{' '.join(f'{d:.3f}' for d in r['max_disp']):>22s} {final_diff.max():22.2f} {disp_diff.max():25.2f}")
json.dump({"scene": "scenes/solitary_cubes_platform.toml", "reference": "hulls (Bullet, exact cubes)",
           "Dn": Dn, "settings": {"penalty": 700, "settle_time": 0.3, "rolling_friction_clumps": 0.05},
           "si_units": {"wall_seconds": "s", "dem_seconds": "s", "onset_time": "s", "positions_and_displacements": "m",
                        "differences": "fractions of Dn"},
           "rows": rows}, open(f"{out}/summary.json", "w"), indent=2)

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
for row in rows:
    ax1.plot(row["wall_seconds"], max(row["final_position_difference_over_Dn"]), "o")
    ax1.annotate(row["model"], (row["wall_seconds"], max(row["final_position_difference_over_Dn"])),
                 textcoords="offset points", xytext=(5, 5))
ax1.set_xlabel("wall time of the coupled run [s]")
ax1.set_ylabel("largest final-position difference to hulls [Dn]")
ax1.set_title("accuracy against cost")
ax1.grid(True, alpha=0.3)
styles = {"hulls": "-", "hulls_p1000": "-.", "clumps8": "--", "clumps27": ":"}
for m in models:
    r = runs[m]
    for k in range(r["p"].shape[1]):
        ax2.plot(r["t"], r["p"][:, k, 0], styles[m], color=f"C{k}", label=f"{m} cube {k}")
ax2.set_xlabel("t [s]")
ax2.set_ylabel("x of the centre of mass [m]")
ax2.set_title("cubes washed off the platform")
ax2.legend(fontsize=6, ncol=4)
ax2.grid(True, alpha=0.3)
fig.tight_layout()
fig.savefig(f"{out}/coupled_engines.png", dpi=120)
PY
