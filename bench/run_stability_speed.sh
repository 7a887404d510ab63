#!/usr/bin/env bash
# Cost of a wave in the stability scene (scenes/stability_cubes.toml, issue
# 16; docs/stability.md): units, fluid cells, wall and CPU seconds per wave
# period (Tp) on the uniform mesh, on the scene's graded mesh (fine cells
# around the armour and the free-surface band, apps/flume_mesh.h) serial and
# with --np 2, and the shares of the solver's time spent in the DEM (the
# engine's sub-steps), the mask (solid fractions) and the loads, as the
# coupling plugin times them (summary.json: dem_seconds, mask_seconds,
# load_seconds; the rest is interFoam's own). The graded run settles the
# layer (fluid.settle_time, timed apart); the others start from its settled
# layer (OUT/graded/settle/scene.settled.toml), so every row couples the
# same units from the same poses. The waves ramp up over Tp / 2 so the timed
# span is mostly full waves. All rows run one after another in one call:
# compare their ratios (the machine is shared), and the load average before
# and after is printed. Writes OUT/summary.json.
# Usage: bash bench/run_stability_speed.sh [--build DIR] [--out DIR] [--duration S] [--cells NX,NY,NZ]
#   --duration  simulated seconds per run (default 5.4 = 3 Tp: full waves reach the armour after ~2 s)
#   --cells     fluid.cells, the fine cells (default the scene's 200,25,62: Dn / 4)
#   --build     default the repo's build/ (bash scripts/build.sh armour armourFoamCoupling armourWaves)
#   --out       default ${TMPDIR:-/tmp}/armour-bench/stability_speed
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=stability_speed bench_targets="armour armourFoamCoupling armourWaves" bench_options="duration cells"
opt_duration=5.4 opt_cells=""
source "$root/bench/common.sh"
bench_args "$@"
armour="$build/apps/armour"
scene="$root/scenes/stability_cubes.toml"
sets=(--set "run.duration=$opt_duration" --set waves.ramp_time=0.9)
[ -n "$opt_cells" ] && sets+=(--set "fluid.cells=[$opt_cells]")
# The refined box as the whole flume: the uniform mesh of the same fine cells.
uniform=(--set "fluid.refine_min=[0.0, -0.124, 0.0]" --set "fluid.refine_max=[2.0, 0.124, 0.62]")
cut -d' ' -f1-3 /proc/loadavg >"$out/loadavg_before"
# The graded run settles; the others start from its settled scene, which
# carries the scene's refined box (the uniform row overrides it).
settled="$out/graded/settle/scene.settled.toml"
for row in graded uniform graded_np2; do
  run="$out/$row"
  [ -f "$run/summary.json" ] && continue
  rm -rf "$run"
  case "$row" in
    graded) "$armour" run "$scene" --out "$run" "${sets[@]}" >"$run.log" 2>&1 ;;
    uniform) "$armour" run "$settled" --out "$run" "${sets[@]}" "${uniform[@]}" >"$run.log" 2>&1 ;;
    graded_np2) "$armour" run "$settled" --out "$run" --np 2 "${sets[@]}" >"$run.log" 2>&1 ;;
  esac
done
cut -d' ' -f1-3 /proc/loadavg >"$out/loadavg_after"
/usr/bin/python3 - "$out" <<'PY'
import json, re, sys
from armour_results import read_summary
out = sys.argv[1]
tp = 1.8  # s, the scene's waves.Tp
load = [open(f"{out}/loadavg_{w}").read().split() for w in ("before", "after")]

def step_clock(case):
    """interFoam's (CPU, wall) seconds from the first step's end to the last's: start-up left out."""
    pairs = re.findall(r"ExecutionTime = ([0-9.eE+-]+) s\s+ClockTime = ([0-9.eE+-]+) s",
                       open(f"{case}/log.interFoam").read())
    (c0, w0), (c1, w1) = [tuple(map(float, p)) for p in (pairs[0], pairs[-1])]
    return c1 - c0, w1 - w0, len(pairs) - 1

rows = []
print(f"{'mesh':>10s} {'ranks':>5s} {'units':>5s} {'cells':>7s} {'sim s':>5s} {'steps':>5s} {'wall s/step':>11s} "
      f"{'CPU s/step':>10s} {'steps/Tp':>8s} {'wall s/Tp':>9s} {'CPU s/Tp':>8s} {'DEM':>6s} {'mask':>6s} "
      f"{'loads':>6s} {'fluid':>6s}")
for name, np in (("uniform", 1), ("graded", 1), ("graded_np2", 2)):
    s = read_summary(f"{out}/{name}")
    f = s["fluid"]
    solver = f["solver_seconds"]
    share = {k: s.get(f"{k}_seconds", 0.0) / solver for k in ("dem", "mask", "load")}
    cpu, wall, steps = step_clock(f"{out}/{name}/case")
    steps_per_wave = f["steps"] * tp / s["simulated_seconds"]
    row = {"mesh": name.split("_")[0], "ranks": np, "units": s["units"], "cells": f["cells_total"],
           "cells_along": f["cells"], "fine_cell_size": f["cell_size"], "largest_cell_size": f["largest_cell_size"],
           "simulated_seconds": s["simulated_seconds"], "steps": f["steps"],
           "wall_seconds": s["wall_seconds"], "solver_seconds": solver,
           "wall_seconds_per_step": wall / steps, "cpu_seconds_per_step": cpu / steps,
           "steps_per_wave": steps_per_wave, "wall_seconds_per_wave": wall / steps * steps_per_wave,
           "cpu_seconds_per_wave": cpu / steps * steps_per_wave,
           "dem_share": share["dem"], "mask_share": share["mask"], "load_share": share["load"],
           "fluid_share": 1.0 - sum(share.values()), "engine_dt": s.get("dt")}
    rows.append(row)
    print(f"{row['mesh']:>10s} {np:5d} {row['units']:5d} {row['cells']:7d} {row['simulated_seconds']:5.2f} "
          f"{row['steps']:5d} {row['wall_seconds_per_step']:11.3f} {row['cpu_seconds_per_step']:10.3f} "
          f"{steps_per_wave:8.0f} {row['wall_seconds_per_wave']:9.0f} {row['cpu_seconds_per_wave']:8.0f} "
          + " ".join(f"{100 * row[k + '_share']:5.1f}%" for k in ("dem", "mask", "load", "fluid")))
settle = json.load(open(f"{out}/graded/settle/summary.json"))
graded_ratio = rows[0]["wall_seconds_per_wave"] / rows[1]["wall_seconds_per_wave"]
np2_ratio = rows[1]["wall_seconds_per_wave"] / rows[2]["wall_seconds_per_wave"]
print(f"graded: {graded_ratio:.2f} x the uniform mesh's speed ({rows[1]['cells'] / rows[0]['cells']:.2f} x the "
      f"cells); --np 2: {np2_ratio:.2f} x the serial graded speed; settle (DEM only, once): "
      f"{settle['wall_seconds']:.1f} s wall for {settle['simulated_seconds']:.2f} s; load average before "
      f"{' '.join(load[0])}, after {' '.join(load[1])}")
print("steps/Tp is this run's (a short run: partly the ramp); in full waves the Courant number sets the step. "
      "Target: <= 30 wall s per wave for a 100-unit layer on 2 cores")
json.dump({"scene": "scenes/stability_cubes.toml", "Tp": tp, "target_wall_seconds_per_wave": 30,
           "rows": rows, "graded_speed_ratio": graded_ratio, "np2_speed_ratio": np2_ratio,
           "settle_wall_seconds": settle["wall_seconds"], "loadavg_before": load[0], "loadavg_after": load[1],
           "frozen_units": "none: every unit is coupled (the DEM is ~2 % of the cost: freezing gains nothing)",
           "si_units": {"wall_seconds": "s", "Tp": "s", "fine_cell_size": "m", "largest_cell_size": "m"}},
          open(f"{out}/summary.json", "w"), indent=2)
PY
