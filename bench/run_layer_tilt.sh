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
# hulls (Bullet). The damage analysis counts the units each run displaced
# (1 Dn from where they started), at the foot and resting on top of the
# layer. Run again with the same --out, it keeps the runs that finished.
# Writes OUT/summary.json (per unit model and angle: displaced per layer and
# their mean; angles in deg, times in s), OUT/layer_tilt.csv (one row per
# run), OUT/layer_tilt.png and the runs. About 1.5 minutes per layer and
# angle on 2 cores.
# Usage: bash bench/run_layer_tilt.sh --scenes 'SCENE...' [--angles 'DEG...'] [--duration S]
#          [--build DIR] [--out DIR]
#   --scenes    settled scenes, space-separated (required)
#   --angles    extra tilt down the face, deg (default '0 4 8 12 16')
#   --duration  s each layer is held (default 3)
#   --out       default ${TMPDIR:-/tmp}/armour-bench/layer_tilt
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=layer_tilt bench_targets=armour bench_options="scenes angles duration"
source "$root/bench/common.sh"
bench_check_options() {
  [ -n "${opt_scenes:-}" ] || bench_fail "--scenes: required (settled scenes, RUN/settle/scene.settled.toml)"
  local scene
  for scene in $opt_scenes; do
    [ -f "$scene" ] || bench_fail "--scenes: $scene: no such file"
  done
}
bench_args "$@"
angles="${opt_angles:-0 4 8 12 16}" duration="${opt_duration:-3}"
armour="$build/apps/armour"
k=0
for scene in $opt_scenes; do
  k=$((k + 1))
  layer="$out/layer_$k"
  mkdir -p "$layer"
  echo "$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")" >"$layer/scene.txt"
  /usr/bin/python3 "$root/studies/dry_scene.py" "$scene" "$layer/dry.toml" >/dev/null ||
    bench_fail "--scenes $scene: cannot make its dry scene"
  for angle in $angles; do
    gravity="$(awk -v t="$angle" 'BEGIN { r = t * atan2(0, -1) / 180; printf "[%.6f, 0.0, %.6f]", -9.81 * sin(r), -9.81 * cos(r) }')"
    for engine in liggghts bullet; do
      run="$layer/${engine}_$angle"
      [ ! -f "$run/summary.json" ] || continue
      rm -rf "$run"
      "$armour" run "$layer/dry.toml" --out "$run" --engine "$engine" --set analysis.kind=damage \
        --set "run.gravity=$gravity" --set "run.duration=$duration" --set run.output_interval=0.05 \
        >"$run.log" 2>&1 || bench_fail "armour run failed: $run.log"
    done
  done
done
/usr/bin/python3 - "$out" "$k" "$angles" <<'PY'
import csv, json, math, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from armour_results import read_summary
out, layers, angles = sys.argv[1], int(sys.argv[2]), [float(a) for a in sys.argv[3].split()]
models = {"liggghts": "clumps (LIGGGHTS)", "bullet": "exact hulls (Bullet)"}
rows, figures = [], {}
for engine in models:
    figures[engine] = []
    for angle in angles:
        counts = []
        for k in range(1, layers + 1):
            s = read_summary(f"{out}/layer_{k}/{engine}_{angle:g}")
            counts.append(s["units_displaced"])
            rows.append({"layer": k, "engine": engine, "extra_tilt_deg": angle, "units": s["units"],
                         "units_displaced": s["units_displaced"],
                         "units_displaced_on_top": s["units_displaced_on_top"],
                         "units_displaced_at_foot": s["units_displaced_at_foot"]})
        figures[engine].append({"extra_tilt_deg": angle, "units_displaced": counts,
                                "mean": sum(counts) / len(counts)})
        print(f"{models[engine]:22s} +{angle:4.1f} deg: displaced {counts}, mean {sum(counts) / len(counts):.1f}")
with open(f"{out}/layer_tilt.csv", "w", newline="") as handle:
    writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
json.dump({"units": "angles deg; counts of units", "layers": layers, "models": figures},
          open(f"{out}/summary.json", "w"), indent=2)
fig, ax = plt.subplots(figsize=(6, 4.2))
for (engine, label), marker in zip(models.items(), "os"):
    f = figures[engine]
    ax.plot(angles, [p["mean"] for p in f], marker + "-", label=f"{label}: mean of {layers}")
    for p in f:
        ax.plot([p["extra_tilt_deg"]] * len(p["units_displaced"]), p["units_displaced"], marker, ms=3,
                alpha=0.4, color=ax.lines[-1].get_color())
ax.set_xlabel("gravity turned down the face [deg] (face steepened by as much)")
ax.set_ylabel("units displaced (1 Dn) in the dry hold")
ax.grid(True, lw=0.3)
ax.legend(fontsize=8)
ax.set_title("one settled layer, held dry by each unit model", fontsize=10)
fig.tight_layout()
fig.savefig(f"{out}/layer_tilt.png", dpi=110)
PY
