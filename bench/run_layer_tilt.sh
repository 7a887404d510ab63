#!/usr/bin/env bash
# A settled armour layer made steeper, dry, held by each unit model from the
# same poses: how many units each loses. Each SCENE is a settled scene
# (RUN/settle/scene.settled.toml) whose settle was Bullet's
# (fluid.settle_engine = "bullet": both unit models can then start from its
# poses, docs/stability.md); the script writes its dry scene
# (studies/dry_scene.py) and holds it for --duration s with gravity turned
# down the face by each of --angles degrees (the face then 33.7 deg + the
# angle steep for the stability scene's 1:1.5; its slope must rise towards
# +x, as that scene's does), once with clumps (LIGGGHTS) and once with exact
# hulls (Bullet). Each unit's move is read from the run's bodies.h5, first
# record to last: displaced at 1 Dn, moved at 0.25 Dn. (Not the damage
# analysis' count: in a dry run it counts from the moment the layer has
# settled, which a layer made steeper reaches late or never, so the two
# models would be counted from different moments.) Run again with the same
# options and --out, it keeps the runs that finished; other options there
# are refused. Writes OUT/summary.json (per unit model and angle: displaced,
# moved and the median move per layer, and their means; angles in deg, moves
# in Dn), OUT/layer_tilt.csv (one row per run), OUT/layer_tilt.png and the
# runs. About 2.3 minutes per layer and angle on 2 cores.
# Usage: bash bench/run_layer_tilt.sh --scenes 'SCENE...' [--angles 'DEG...'] [--duration S]
#          [--engines 'ENGINE...'] [--set 'KEY=VALUE...'] [--build DIR] [--out DIR]
#   --scenes    settled scenes, space-separated (required)
#   --angles    extra tilt down the face, deg (default '0 4 8 12 16')
#   --duration  s each layer is held (default 3)
#   --engines   the unit models held, of liggghts (clumps) and bullet (hulls)
#               (default both; one alone for a variant of it, e.g. scenes
#               whose [[unit]] sets edge_spheres)
#   --set       scene keys set in every run, both unit models (e.g.
#               'unit.0.method=inscribed unit.0.spheres=118': clumps held inside
#               the cube, which take a hull-settled layer's poses as they lie)
#   --out       default ${TMPDIR:-/tmp}/armour-bench/layer_tilt
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=layer_tilt bench_targets=armour bench_options="scenes angles duration engines set"
source "$root/bench/common.sh"
bench_check_options() {
  [ -n "${opt_scenes:-}" ] || bench_fail "--scenes: required (settled scenes, RUN/settle/scene.settled.toml)"
  local scene
  for scene in $opt_scenes; do
    [ -f "$scene" ] || bench_fail "--scenes: $scene: no such file"
  done
  local engine
  for engine in ${opt_engines-liggghts bullet}; do
    [[ " liggghts bullet " == *" $engine "* ]] || bench_fail "--engines: no engine '$engine' (liggghts, bullet)"
  done
  [ -n "${opt_engines-x}" ] || bench_fail "--engines: no engine named"
  bench_scene_sets
}
bench_args "$@"
angles="" duration="${opt_duration:-3}"
for angle in ${opt_angles:-0 4 8 12 16}; do
  angles+="$(awk -v a="$angle" 'BEGIN { printf "%g ", a + 0 }')" # one name per angle: 8.0 and 8 are 8
done
armour="$build/apps/armour"
engines="${opt_engines-liggghts bullet}"
# A folder resumed must hold a bench of the same layers and hold (its runs are kept as they are).
settings="duration=$duration set=${opt_set-} scenes="
for scene in $opt_scenes; do settings+="$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene") "; done
if [ -f "$out/settings.txt" ] && [ "$(cat "$out/settings.txt")" != "$settings" ]; then
  bench_fail "--out $out holds a bench of other layers, --duration or --set ($(cat "$out/settings.txt")): use a new --out"
fi
echo "$settings" >"$out/settings.txt"
k=0
for scene in $opt_scenes; do
  k=$((k + 1))
  layer="$out/layer_$k"
  mkdir -p "$layer"
  /usr/bin/python3 "$root/studies/dry_scene.py" "$scene" "$layer/dry.toml" >/dev/null ||
    bench_fail "--scenes $scene: cannot make its dry scene"
  for angle in $angles; do
    gravity="$(awk -v t="$angle" 'BEGIN { r = t * atan2(0, -1) / 180; printf "[%.6f, 0.0, %.6f]", -9.81 * sin(r), -9.81 * cos(r) }')"
    for engine in $engines; do
      run="$layer/${engine}_$angle"
      [ ! -f "$run/summary.json" ] || continue
      rm -rf "$run"
      "$armour" run "$layer/dry.toml" --out "$run" --engine "$engine" --set analysis.kind=damage \
        --set "run.gravity=$gravity" --set "run.duration=$duration" --set run.output_interval=0.05 \
        "${sets[@]}" >"$run.log" 2>&1 || bench_fail "armour run failed: $run.log"
    done
  done
done
/usr/bin/python3 - "$out" "$k" "$angles" "$engines" <<'PY'
import json, sys
import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from armour_results import read_summary, write_rows
out, layers, angles = sys.argv[1], int(sys.argv[2]), [float(a) for a in sys.argv[3].split()]
models = {engine: label for engine, label in (("liggghts", "clumps (LIGGGHTS)"), ("bullet", "exact hulls (Bullet)"))
          if engine in sys.argv[4].split()}
rows, figures = [], {}
for engine in models:
    figures[engine] = []
    for angle in angles:
        point = {"extra_tilt_deg": angle, "units_displaced": [], "units_moved": [], "median_move_over_Dn": []}
        for k in range(1, layers + 1):
            run = f"{out}/layer_{k}/{engine}_{angle:g}"
            Dn = read_summary(run)["damage"]["Dn"]
            with h5py.File(f"{run}/bodies.h5", "r") as f:
                position = f["bodies/position"][:]
            move = np.linalg.norm(position[-1] - position[0], axis=1) / Dn  # first record to last
            figures_of_run = {"units_displaced": int((move >= 1.0).sum()), "units_moved": int((move >= 0.25).sum()),
                              "median_move_over_Dn": float(np.median(move))}
            for key, value in figures_of_run.items():
                point[key].append(value)
            rows.append({"layer": k, "engine": engine, "extra_tilt_deg": angle, "units": len(move), **figures_of_run})
        for key in ("units_displaced", "units_moved", "median_move_over_Dn"):
            point["mean_" + key] = sum(point[key]) / layers
        figures[engine].append(point)
        print(f"{models[engine]:22s} +{angle:4.1f} deg: displaced {point['units_displaced']} (mean "
              f"{point['mean_units_displaced']:.1f}), moved 0.25 Dn {point['units_moved']}, median move "
              f"{', '.join(f'{m:.2f}' for m in point['median_move_over_Dn'])} Dn")
write_rows(f"{out}/layer_tilt.csv", rows)
json.dump({"units": "angles deg; moves in Dn; counts of units, from the first record to the last",
           "layers": layers, "models": figures}, open(f"{out}/summary.json", "w"), indent=2)
fig, ax = plt.subplots(figsize=(6, 4.2))
for (engine, label), marker in zip(models.items(), "os"):
    f = figures[engine]
    ax.plot(angles, [p["mean_units_displaced"] for p in f], marker + "-", label=f"{label}: mean of {layers}")
    for p in f:
        ax.plot([p["extra_tilt_deg"]] * layers, p["units_displaced"], marker, ms=3, alpha=0.4,
                color=ax.lines[-1].get_color())
ax.set_xlabel("gravity turned down the face [deg] (face steepened by as much)")
ax.set_ylabel("units displaced (1 Dn, first record to last)")
ax.grid(True, lw=0.3)
ax.legend(fontsize=8)
ax.set_title("one settled layer, held dry by each unit model", fontsize=10)
fig.tight_layout()
fig.savefig(f"{out}/layer_tilt.png", dpi=110)
PY
