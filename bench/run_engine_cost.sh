#!/usr/bin/env bash
# Cost per unit-step of exact hulls (Bullet) against sphere clumps of 10 and 50
# spheres (LIGGGHTS), on the slope scenes, in one run; printed as ratios.
# Writes OUT/summary.json and the runs, nothing in the source tree.
# Usage: bash bench/run_engine_cost.sh [--build DIR] [--out DIR]
#   --build  default the repo's build/ (bash scripts/build.sh armour)
#   --out    default ${TMPDIR:-/tmp}/armour-bench/engine_cost
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=engine_cost bench_targets=armour bench_options=""
source "$root/bench/common.sh"
bench_args "$@"
armour="$build/apps/armour"
for scene in slope_cubes slope_dolosse; do
  "$armour" run "$root/scenes/$scene.toml" --out "$out/$scene/hulls" --set 'run.engine="bullet"' 2>/dev/null
  for n in 10 50; do
    "$armour" run "$root/scenes/$scene.toml" --out "$out/$scene/clumps$n" --set 'run.engine="liggghts"' \
      --set "unit.0.spheres=$n" 2>/dev/null
  done
done
/usr/bin/python3 - "$out" <<'PY'
import json, sys
from armour_results import read_summary
out = sys.argv[1]
rows = []
print(f"{'scene':15s} {'model':10s} {'s/unit-step':>12s} {'x hulls':>8s} {'dt [s]':>10s} {'wall s per sim s':>17s}")
for scene in ("slope_cubes", "slope_dolosse"):
    runs = {m: read_summary(f"{out}/{scene}/{m}") for m in ("hulls", "clumps10", "clumps50")}
    base = runs["hulls"]["seconds_per_unit_step"]
    for m, s in runs.items():
        ratio = s["seconds_per_unit_step"] / base
        print(f"{scene:15s} {m:10s} {s['seconds_per_unit_step']:12.3g} {ratio:8.2f} {s['dt']:10.3g} "
              f"{s['wall_seconds_per_simulated_second']:17.3g}")
        rows.append({"scene": scene, "model": m, "seconds_per_unit_step": s["seconds_per_unit_step"],
                     "ratio_to_hulls": ratio, "dt": s["dt"],
                     "wall_seconds_per_simulated_second": s["wall_seconds_per_simulated_second"]})
json.dump({"units": "s; ratios dimensionless", "rows": rows}, open(f"{out}/summary.json", "w"), indent=2)
PY
