#!/usr/bin/env bash
# Coupling overhead: scenes/bench_tank_cubes.toml (cubes in a tank of still
# water, LIGGGHTS) with 10 and 100 units, coupled, against the same case with
# fluid.frozen = true (units held, mask imposed once, no load integration, no
# engine advance). Prints the coupled/frozen interFoam CPU time per fluid step
# (its ExecutionTime from the first step to the last: start-up left out)
# (target: overhead <= 10 %) and the share of the solver's time spent in the
# engine's sub-steps (dem_seconds, timed by the plugin). Writes
# OUT/summary.json (nothing in the source tree). Each pair runs REPEATS times
# (default 3), coupled and frozen alternating, and the fastest run of each
# counts: on a shared machine noise only ever adds time, so the minimum is the
# estimate least polluted by it.
# Usage: bash bench/run_coupled_bench.sh [--build DIR] [--out DIR]
#   --build  default the repo's build/ (bash scripts/build.sh armour armourFoamCoupling)
#   --out    default ${TMPDIR:-/tmp}/armour-bench/coupled
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=coupled bench_targets="armour armourFoamCoupling" bench_options=""
source "$root/bench/common.sh"
bench_args "$@"
armour="$build/apps/armour"
repeats="${REPEATS:-3}"
for n in 10 100; do
  for r in $(seq 1 "$repeats"); do
    for mode in coupled frozen; do
      frozen=false; [ "$mode" = frozen ] && frozen=true
      "$armour" run "$root/scenes/bench_tank_cubes.toml" --out "$out/n${n}_${mode}_$r" \
        --set "drop.0.count=$n" --set "fluid.frozen=$frozen" 2>"$out/n${n}_${mode}_$r.log"
    done
  done
done
/usr/bin/python3 - "$out" "$repeats" <<'PY'
import json, sys
from armour_results import read_summary
out, repeats = sys.argv[1], int(sys.argv[2])
def fastest(n, mode):
    runs = [read_summary(f"{out}/n{n}_{mode}_{r}") for r in range(1, repeats + 1)]
    return min(runs, key=lambda s: s["fluid"]["cpu_seconds_per_step"])
rows = []
print(f"{'units':>5s} {'coupled s/step':>14s} {'frozen s/step':>13s} {'ratio':>6s} {'DEM s':>7s} "
      f"{'DEM share':>9s} {'loads+mask s':>12s} {'steps c/f':>9s}")
for n in (10, 100):
    c, f = fastest(n, "coupled"), fastest(n, "frozen")
    sc, sf = c["fluid"]["cpu_seconds_per_step"], f["fluid"]["cpu_seconds_per_step"]
    row = {"units": n, "coupled_seconds_per_step": sc, "frozen_seconds_per_step": sf,
           "ratio": sc / sf, "overhead_percent": 100 * (sc / sf - 1),
           "coupled_solver_seconds": c["fluid"]["solver_seconds"], "frozen_solver_seconds": f["fluid"]["solver_seconds"],
           "coupled_steps": c["fluid"]["steps"], "frozen_steps": f["fluid"]["steps"],
           "dem_seconds": c.get("dem_seconds"), "dem_share_of_solver": c.get("dem_share_of_solver"),
           "load_seconds": c.get("load_seconds"), "mask_seconds": c.get("mask_seconds"), "engine_dt": c["dt"]}
    rows.append(row)
    print(f"{n:5d} {sc:14.4g} {sf:13.4g} {row['ratio']:6.3f} {row['dem_seconds']:7.3g} "
          f"{100 * row['dem_share_of_solver']:8.1f}% {row['load_seconds'] + row['mask_seconds']:12.3g} "
          f"{row['coupled_steps']:4d}/{row['frozen_steps']:d}")
json.dump({"scene": "scenes/bench_tank_cubes.toml", "target_overhead_percent": 10, "repeats": repeats,
           "estimate": "fastest of the repeats, per mode", "rows": rows},
          open(f"{out}/summary.json", "w"), indent=2)
PY
