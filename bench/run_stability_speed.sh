#!/usr/bin/env bash
# Cost of a wave in the stability scene (scenes/stability_cubes.toml, issue
# 16; docs/stability.md): units, fluid cells, wall seconds per wave period
# (Tp) serial and with --np 2, and the shares of the solver's time spent in
# the DEM (the engine's sub-steps), the mask (solid fractions) and the loads,
# as the coupling plugin times them (summary.json: dem_seconds, mask_seconds,
# load_seconds; the rest is interFoam's own). The serial run settles the
# layer first (fluid.settle_time, timed apart); the --np 2 run starts from
# its settled layer (OUT/serial/settle/scene.settled.toml), so both couple
# the same units from the same poses. The waves ramp up over Tp / 2 so the
# timed span is mostly full waves. Prints the table, the load average before
# and after (the machine is shared: compare the two runs' ratio, not the
# absolute seconds), and writes OUT/summary.json.
# Usage: bash bench/run_stability_speed.sh [--build DIR] [--out DIR] [--duration S] [--cells NX,NY,NZ]
#   --duration  simulated seconds per run (default 2.7 = 1.5 Tp; 0.3 still gives the costs per step)
#   --cells     fluid.cells (default the scene's 200,25,62: Dn / 4)
#   --build     default the repo's build/ (bash scripts/build.sh armour armourFoamCoupling armourWaves)
#   --out       default ${TMPDIR:-/tmp}/armour-bench/stability_speed
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=stability_speed bench_targets="armour armourFoamCoupling armourWaves" bench_options="duration cells"
opt_duration=2.7 opt_cells=""
source "$root/bench/common.sh"
bench_args "$@"
armour="$build/apps/armour"
scene="$root/scenes/stability_cubes.toml"
sets=(--set "run.duration=$opt_duration" --set waves.ramp_time=0.9)
[ -n "$opt_cells" ] && sets+=(--set "fluid.cells=[$opt_cells]")
cut -d' ' -f1-3 /proc/loadavg >"$out/loadavg_before"
for np in 1 2; do
  run="$out/np$np"
  [ -f "$run/summary.json" ] && continue
  rm -rf "$run"
  if [ "$np" = 1 ]; then
    "$armour" run "$scene" --out "$run" "${sets[@]}" >"$run.log" 2>&1
  else
    "$armour" run "$out/np1/settle/scene.settled.toml" --out "$run" --np 2 "${sets[@]}" >"$run.log" 2>&1
  fi
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
print(f"{'ranks':>5s} {'units':>5s} {'cells':>7s} {'sim s':>5s} {'steps':>5s} {'wall s/step':>11s} "
      f"{'CPU s/step':>10s} {'steps/Tp':>8s} {'wall s/Tp':>9s} {'DEM':>6s} {'mask':>6s} {'loads':>6s} {'fluid':>6s}")
for np in (1, 2):
    s = read_summary(f"{out}/np{np}")
    f = s["fluid"]
    solver = f["solver_seconds"]
    share = {k: s.get(f"{k}_seconds", 0.0) / solver for k in ("dem", "mask", "load")}
    cpu, wall, steps = step_clock(f"{out}/np{np}/case")
    steps_per_wave = f["steps"] * tp / s["simulated_seconds"]
    row = {"ranks": np, "units": s["units"], "cells": f["cells_total"],
           "simulated_seconds": s["simulated_seconds"], "steps": f["steps"],
           "wall_seconds": s["wall_seconds"], "solver_seconds": solver,
           "wall_seconds_per_step": wall / steps, "cpu_seconds_per_step": cpu / steps,
           "steps_per_wave": steps_per_wave, "wall_seconds_per_wave": wall / steps * steps_per_wave,
           "dem_share": share["dem"], "mask_share": share["mask"], "load_share": share["load"],
           "fluid_share": 1.0 - sum(share.values()), "engine_dt": s.get("dt")}
    rows.append(row)
    print(f"{np:5d} {row['units']:5d} {row['cells']:7d} {row['simulated_seconds']:5.2f} {row['steps']:5d} "
          f"{row['wall_seconds_per_step']:11.3f} {row['cpu_seconds_per_step']:10.3f} {steps_per_wave:8.0f} "
          f"{row['wall_seconds_per_wave']:9.0f} "
          + " ".join(f"{100 * row[k + '_share']:5.1f}%" for k in ("dem", "mask", "load", "fluid")))
settle = json.load(open(f"{out}/np1/settle/summary.json"))
speedup = rows[0]["wall_seconds_per_wave"] / rows[1]["wall_seconds_per_wave"]
print(f"--np 2: {speedup:.2f} x the serial speed; settle (DEM only, once): {settle['wall_seconds']:.1f} s wall for "
      f"{settle['simulated_seconds']:.2f} s; load average before {' '.join(load[0])}, after {' '.join(load[1])}")
print("steps/Tp is this run's (a short run: mostly the ramp, steps at max_time_step); in full waves the "
      "Courant number shortens the step. Target: <= 30 wall s per wave for a 100-unit layer on 2 cores")
json.dump({"scene": "scenes/stability_cubes.toml", "Tp": tp, "target_wall_seconds_per_wave": 30,
           "rows": rows, "np2_speed_ratio": speedup, "settle_wall_seconds": settle["wall_seconds"],
           "loadavg_before": load[0], "loadavg_after": load[1],
           "frozen_units": "none: every unit is coupled (no per-unit freezing below still water yet)",
           "si_units": {"wall_seconds": "s", "Tp": "s"}},
          open(f"{out}/summary.json", "w"), indent=2)
PY
