#!/usr/bin/env bash
# Where a cube leaves its neighbour, for each unit model, over many seats.
# The shipped cube-on-a-cube tilt (scenes/tilt_cube_pair.toml: a free 0.04 m
# cube on a held one, gravity turning about +y at 5 deg/s, friction 0.6) with
# the free cube placed at x = 0, 3, ..., 18 mm and y = 0, 5, 10 mm off its
# neighbour's centre (21 seats), for exact hulls (Bullet) and sphere clumps of
# 47, 64, 118 (the scene's), 200 and 500 spheres, and the scene's 118 with
# 1, 3 or 7 of them spread along every edge, and the scene's body of 110 with
# 7 along every edge (202 spheres; unit.edge_spheres, LIGGGHTS). Each run reports
# the tilt at which the cube leaves its seat (leave_angle_deg, docs/analysis.md)
# and how (slid or toppled). An exact cube leaves at the smaller of the slide,
# atan(0.6) = 30.96 deg, and its tip over the downhill edge,
# atan((a/2 - x) / (a/2)); so the error of each model is its leave angle less
# that, seat by seat. Writes OUT/summary.json (per model: the error's mean,
# rms and worst in deg, over all seats and over those it came to rest on,
# the seats it never rested on (left_before_resting) and those whose way out
# differs from the exact cube's, the DEM's step and its wall seconds per
# simulated second over all runs, whose ratios alone are figures on a shared
# machine), OUT/seats.csv (one row per run),
# OUT/cube_on_cube.png and the runs. About 15 minutes on 2 cores (clumps of
# 200 and 500 spheres are built once, then cached).
# Usage: bash bench/run_cube_on_cube.sh [--build DIR] [--out DIR] [--models 'NAME ...'] [--set 'KEY=VALUE ...']
#   --build   default the repo's build/ (bash scripts/build.sh armour)
#   --out     default ${TMPDIR:-/tmp}/armour-bench/cube_on_cube
#   --models  the models to run, of hulls clump_47 clump_64 clump_118 clump_200
#             clump_500 clump_118_edges_1 clump_118_edges_3 clump_118_edges_7
#             clump_202_edges_7
#             (default all)
#   --set     scene keys set in every run, one suspect at a time (e.g.
#             material.0.youngs_modulus=5e8: the contact 10 x stiffer)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=cube_on_cube bench_targets=armour bench_options="models set"
# name|spheres|armour run options choosing the model
all_models=(
  "hulls|0|--engine bullet"
  "clump_47|47|--set unit.0.tol_surface=0.02"
  "clump_64|64|--set unit.0.tol_surface=0.015"
  "clump_118|118|"
  "clump_200|200|--set unit.0.spheres=200"
  "clump_500|500|--set unit.0.spheres=500"
  "clump_118_edges_1|118|--set unit.0.spheres=118 --set unit.0.edge_spheres=1"
  "clump_118_edges_3|118|--set unit.0.spheres=118 --set unit.0.edge_spheres=3"
  "clump_118_edges_7|118|--set unit.0.spheres=118 --set unit.0.edge_spheres=7"
  "clump_202_edges_7|202|--set unit.0.spheres=202 --set unit.0.edge_spheres=7"
)
# The models and settings asked for, checked before --out is made (common.sh).
bench_check_options() {
  local names=() name model
  read -ra names <<<"${opt_models-}"
  [ -z "${opt_models+x}" ] || [ ${#names[@]} -gt 0 ] || bench_fail "--models: no model named"
  models=()
  for model in "${all_models[@]}"; do
    name="${model%%|*}"
    if [ -z "${opt_models+x}" ] || [[ " ${names[*]} " == *" $name "* ]]; then models+=("$model"); fi
  done
  for name in "${names[@]}"; do
    [[ " ${all_models[*]} " == *" $name|"* ]] || bench_fail "--models: no model '$name'"
  done
  bench_scene_sets
}
source "$root/bench/common.sh"
bench_args "$@"
armour="$build/apps/armour"
for model in "${models[@]}"; do
  IFS='|' read -r name spheres options <<<"$model"
  for x in 0.0 0.003 0.006 0.009 0.012 0.015 0.018; do
    for y in 0.0 0.005 0.01; do
      run="$out/runs/$name/x${x}_y$y"
      rm -rf "$run"
      mkdir -p "$(dirname "$run")"
      # shellcheck disable=SC2086 # the model's options are words
      "$armour" run "$root/scenes/tilt_cube_pair.toml" --out "$run" $options "${sets[@]}" \
        --set "body.0.position=[$x, $y, 0.065]" >"$run.log" 2>&1 ||
        bench_fail "armour run failed: $run.log"
    done
  done
done
BENCH_SET="${opt_set-}" /usr/bin/python3 - "$out" "${models[@]}" <<'PY'
import json, math, os, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from armour_results import read_summary, write_rows
out, models = sys.argv[1], [m.split("|") for m in sys.argv[2:]]
a, mu = 0.04, 0.6  # the scene's cube edge (m) and friction
slide = math.degrees(math.atan(mu))

def exact(x):
    tip = math.degrees(math.atan((a / 2 - x) / (a / 2)))
    return (tip, "toppled") if tip < slide else (slide, "slid")


def spread(errors):
    n = len(errors)
    if not n:
        return {"mean_error_deg": None, "rms_error_deg": None, "worst_error_deg": None}
    return {"mean_error_deg": sum(errors) / n, "rms_error_deg": math.sqrt(sum(e * e for e in errors) / n),
            "worst_error_deg": max(errors, key=abs)}


rows, figures = [], {}
for name, spheres, _ in models:
    errors, rested, differ, unrested, wall, simulated, dt = [], [], 0, 0, 0.0, 0.0, None
    for x in (0.0, 0.003, 0.006, 0.009, 0.012, 0.015, 0.018):
        for y in (0.0, 0.005, 0.01):
            s = read_summary(f"{out}/runs/{name}/x{x}_y{y}")
            reference, way = exact(x)
            left, by = s["leave_angle_deg"], s["left_by"]
            if left is None:
                raise SystemExit(f"{name} x={x} y={y}: the cube stayed on its seat to the end of the tilt")
            errors.append(left - reference)
            if s["left_before_resting"]:
                unrested += 1
            else:
                rested.append(left - reference)
            differ += by != way
            wall += s["wall_seconds"]
            simulated += s["simulated_seconds"]
            dt = s["dt"]
            rows.append({"model": name, "spheres": int(spheres), "x_m": x, "y_m": y, "leave_angle_deg": left,
                         "left_by": by, "left_before_resting": s["left_before_resting"], "exact_deg": reference,
                         "exact_by": way, "error_deg": left - reference})
    figures[name] = {"spheres": int(spheres), "seats": len(errors), **spread(errors),
                     "seats_rested_on": {"seats": len(rested), **spread(rested)},
                     "seats_never_rested_on": unrested, "seats_left_another_way": differ, "dt": dt,
                     "wall_seconds_per_simulated_second": wall / simulated}
    f, r = figures[name], figures[name]["seats_rested_on"]
    print(f"{name:10s} error mean {f['mean_error_deg']:+5.1f} rms {f['rms_error_deg']:4.1f} worst "
          f"{f['worst_error_deg']:+5.1f} deg (on the {r['seats']} seats it rested on: mean {r['mean_error_deg']:+5.1f}, "
          f"rms {r['rms_error_deg']:4.1f}); never rested on {unrested}, another way out at {differ} of "
          f"{len(errors)}; dt {dt:.3g} s, {f['wall_seconds_per_simulated_second']:.3g} wall s per simulated s")
write_rows(f"{out}/seats.csv", rows)
json.dump({"units": "angles deg, positions m, dt s, wall_seconds_per_simulated_second s/s",
           "set": os.environ["BENCH_SET"].split(),
           "reference": "an exact cube leaves at min(atan(0.6), atan((a/2 - x) / (a/2)))",
           "models": figures}, open(f"{out}/summary.json", "w"), indent=2)

fig, (angles, cost) = plt.subplots(1, 2, figsize=(11, 4.3))
xs = [i * 0.0005 for i in range(37)]
angles.plot([1000 * x for x in xs], [exact(x)[0] for x in xs], "k-", lw=2, label="exact cube")
for k, ((name, _, _), marker) in enumerate(zip(models, "s^ovDP<>Xh")):
    mine = [r for r in rows if r["model"] == name]
    # Side by side at each x, so that the models' points do not hide each other.
    angles.plot([1000 * r["x_m"] + 0.2 * (k - (len(models) - 1) / 2) for r in mine],
                [r["leave_angle_deg"] for r in mine], marker, ms=4, alpha=0.75,
                label=name.replace("_", " ").replace("clump ", "clump of ")
                .replace(" edges ", " spheres, edge spheres ")
                + ("" if name == "hulls" or "edges" in name else " spheres"))
    f = figures[name]
    cost.plot(f["wall_seconds_per_simulated_second"], f["rms_error_deg"], marker, ms=7,
              label=name.replace("_", " "))
angles.set_xlabel("free cube's centre off its neighbour's, downhill x [mm]")
angles.set_ylabel("tilt at which it leaves its seat [deg]")
angles.legend(fontsize=7)
angles.grid(True, lw=0.3)
cost.set_xscale("log")
cost.set_xlabel("wall seconds per simulated second (one run, shared machine: ratios only)")
cost.set_ylabel("rms error of the leave angle over 21 seats [deg]")
cost.grid(True, which="both", lw=0.3)
cost.legend(fontsize=7)
fig.suptitle("scenes/tilt_cube_pair.toml: where a cube leaves its neighbour, y = 0, 5, 10 mm"
             + "".join(f", {setting}" for setting in os.environ["BENCH_SET"].split()), fontsize=10)
fig.tight_layout()
fig.savefig(f"{out}/cube_on_cube.png", dpi=110)
PY
