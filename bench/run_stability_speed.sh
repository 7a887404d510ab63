#!/usr/bin/env bash
# Cost and accuracy of the stability scene's mesh (scenes/stability_cubes.toml,
# issues 16 and 34; docs/stability.md, Cost): the scene as shipped, on its
# refined mesh (the [[refine]] band and toe box: Dn/4 cells about the armour layer only,
# fluid_case/mesh_refinement.h), against the graded Dn/4 mesh it shipped before
# (one blockMesh block, Dn/4 in the whole box x > 1.15 m, z > 0.18 m:
# fluid.mesh = "graded", fluid.cells = [200, 25, 62]),
# both with --np 2, over the same waves from the same settled layer: the first
# row settles the layer (fluid.settle_time, timed apart), the second starts
# from its settled scene (OUT/refined/settle/scene.settled.toml). The rows run
# one after another in one call: compare them with each other only (the
# machine may be shared; the load average before and after is kept).
# Writes OUT/summary.json (SI):
#   wall_seconds_per_wave      per mesh: interFoam's wall seconds per simulated
#                              second once the waves are at the armour
#                              (--load-from on), x the scene's Tm0,2 at the toe
#   speedup                    graded / refined
#   incident_height_difference Hm0 of the incident wave at the toe (Mansard-Funke
#                              over the three gauges, from --waves-from on),
#                              refined / graded - 1
#   load_rms_difference        the units' fluid loads at the records from
#                              --load-from on: rms of the difference over the
#                              rms of the graded run's changing part (each
#                              unit's load less its mean over the window, so
#                              the buoyancy both share is left out)
#   load_intensity_difference  each unit's load intensity (the rms of its
#                              changing part over the window), unit by unit:
#                              rms of the difference over the rms of the graded
#                              run's; blind to when a wave breaks, which the
#                              time series above is not
#   load_floor                 with the row graded_again: the same figures
#                              between two runs of the graded mesh (the second
#                              with its interface Courant limit 1 % lower), the
#                              least any mesh can show against it
# Usage: bash bench/run_stability_speed.sh [--build DIR] [--out DIR] [--duration S]
#          [--load-from S] [--load-to S] [--waves-from S] [--cells NX,NY,NZ] [--band BELOW,ABOVE]
#          [--extra-rows LIST]
#   --duration    simulated seconds per run (default 6.5: full waves at the armour from ~4.5 s)
#   --load-from   s, start of the load and cost window (default 4.5)
#   --load-to     s, end of the load window (default the runs' end)
#   --waves-from  s, start of the gauges' window (default 2.5: the waves' front at the toe)
#   --cells       fluid.cells of both rows (default the scene's for the refined
#                 row and [200, 25, 62] for the graded one; NX, NY even)
#   --band        m, the refined row's band reach under and over the armour's
#                 face (default the scene's 0.06,0.16: 1.5 Dn under, 4 Dn over)
#   --extra-rows  comma-separated rows after the default two, each well over the
#                 default's 30 minutes on 2 cores: uniform (the fine cells in the
#                 whole flume, serial), graded_serial, refined_serial,
#                 graded_again (the floor of the load figures, ~15 minutes)
#   --build       default the repo's build/ (bash scripts/build.sh armour armourFoamCoupling armourWaves)
#   --out         default ${TMPDIR:-/tmp}/armour-bench/stability_speed
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=stability_speed bench_targets="armour armourFoamCoupling armourWaves"
bench_options="duration load-from load-to waves-from cells extra-rows band"
opt_duration=6.5 opt_load_from=4.5 opt_load_to="" opt_waves_from=2.5 opt_cells="" opt_band="" opt_extra_rows=""
source "$root/bench/common.sh"
bench_args "$@"
armour="$build/apps/armour"
scene="$root/scenes/stability_cubes.toml"
sets=(--set "run.duration=$opt_duration" --set waves.ramp_time=0.9 --set run.checkpoint_interval=0
  --set "fluid.write_interval=$opt_duration")
refined_cells=() graded_cells=(--set 'fluid.cells=[200,25,62]')
# The refined row is the scene as shipped (its [[refine]] regions: Dn / 4 from
# 1.5 Dn under the armour's face to 4 Dn over it, and over the toe berm);
# --band moves the first region's reach.
if [ -n "$opt_band" ]; then
  IFS=, read -r band_below band_above <<<"$opt_band"
  [[ "$band_below" =~ ^[0-9.]+$ && "$band_above" =~ ^[0-9.]+$ ]] ||
    bench_fail "--band: two lengths in m, BELOW,ABOVE (got '$opt_band')"
  refined_cells=(--set "refine.0.below=$band_below" --set "refine.0.above=$band_above")
fi
if [ -n "$opt_cells" ]; then
  refined_cells+=(--set "fluid.cells=[$opt_cells]") graded_cells=(--set "fluid.cells=[$opt_cells]")
fi
graded=(--set fluid.mesh=graded "${graded_cells[@]}")
uniform=(--set "fluid.refine_min=[0.0, -0.124, 0.0]" --set "fluid.refine_max=[2.0, 0.124, 0.62]")
rows=(refined graded)
IFS=, read -r -a extra <<<"$opt_extra_rows"
for row in "${extra[@]}"; do
  case "$row" in
    uniform | graded_serial | refined_serial | graded_again) rows+=("$row") ;;
    *) bench_fail "--extra-rows: unknown row '$row' (uniform, graded_serial, refined_serial, graded_again)" ;;
  esac
done
# The load average around the rows that run now (kept from the call that ran
# them when a call only reads rows already run, e.g. with another --load-from).
settled="$out/refined/settle/scene.settled.toml" ran=0
for row in "${rows[@]}"; do
  run="$out/$row"
  [ -f "$run/summary.json" ] && continue
  [ $ran = 1 ] || cut -d' ' -f1-3 /proc/loadavg >"$out/loadavg_before"
  ran=1
  rm -rf "$run"
  echo "stability_speed: $row ..." >&2
  case "$row" in
    refined) cmd=("$armour" run "$scene" --np 2 "${refined_cells[@]}") ;;
    graded) cmd=("$armour" run "$settled" --np 2 "${graded[@]}") ;;
    graded_again) cmd=("$armour" run "$settled" --np 2 "${graded[@]}" --set fluid.max_interface_courant=0.495) ;;
    uniform) cmd=("$armour" run "$settled" "${graded[@]}" "${uniform[@]}") ;;
    graded_serial) cmd=("$armour" run "$settled" "${graded[@]}") ;;
    refined_serial) cmd=("$armour" run "$settled" "${refined_cells[@]}") ;;
  esac
  "${cmd[@]}" --out "$run" "${sets[@]}" >"$run.log" 2>&1 || bench_fail "$row: armour run failed: $run.log"
done
[ $ran = 0 ] || cut -d' ' -f1-3 /proc/loadavg >"$out/loadavg_after"
/usr/bin/python3 - "$out" "$opt_load_from" "${opt_load_to:-inf}" "$opt_waves_from" "${rows[*]}" <<'PY'
import json, os, re, sys
import h5py
import numpy as np
from armour_results import read_summary
from load_measures import intensity, intensity_difference, time_series_difference

out, load_from, load_to, waves_from = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
names = sys.argv[5].split()
# The scene's mean period at the toe (Tm0,2 of the incident wave over its long
# runs, docs/stability.md): a "wave" of the cost figures.
tm02 = 1.53
g, depth = 9.81, 0.40
load = [open(f"{out}/loadavg_{w}").read().split() for w in ("before", "after")]

def clock(case, t0, t1):
    """interFoam's (steps, wall s, CPU s, simulated s) from the first step at or after t0 to the last at or before t1."""
    text = open(f"{case}/log.interFoam").read()
    times = [float(t) for t in re.findall(r"^Time = ([0-9.eE+-]+)", text, re.M)]
    clocks = [tuple(map(float, p)) for p in
              re.findall(r"ExecutionTime = ([0-9.eE+-]+) s\s+ClockTime = ([0-9.eE+-]+) s", text)]
    pairs = [(t, c) for t, c in zip(times, clocks) if t <= t1 + 1e-9]
    first = next(i for i, (t, _) in enumerate(pairs) if t >= t0)
    (ta, (ca, wa)), (tb, (cb, wb)) = pairs[first], pairs[-1]
    return len(pairs) - 1 - first, wb - wa, cb - ca, tb - ta

def wavenumber(f):
    w, k = 2 * np.pi * f, (2 * np.pi * f) ** 2 / g
    for _ in range(50):
        k = w * w / (g * np.tanh(k * depth))
    return k

def gauge_data(name):
    rows = []
    for line in open(f"{out}/{name}/case/postProcessing/gauges/0/surfaceElevation.dat"):
        if line.strip() and not line.startswith("#"):
            rows.append([float(v) for v in line.split()])
    return np.array(rows)

# Every row's gauges and clock over the same windows: to the shortest row's end.
waves_to = min(gauge_data(name)[-1, 0] for name in names)

def incident_hm0(name, summary):
    """Mansard-Funke over the three gauges, from waves_from to waves_to: the
    incident and reflected Hm0 (m) in 0.5-2.5 fp, and each gauge's Hm0."""
    data = gauge_data(name)
    t, eta = data[:, 0], data[:, 1:4] - depth
    n = 256
    grid = np.linspace(waves_from, waves_to, n, endpoint=False)
    eta = np.array([np.interp(grid, t, e) for e in eta.T])
    eta -= eta.mean(axis=1, keepdims=True)
    spectra = np.fft.rfft(eta, axis=1)
    f = np.fft.rfftfreq(n, grid[1] - grid[0])
    x = np.array(summary["waves"]["gauge_x"])
    fp = 1 / 1.8
    m_in = m_re = 0.0
    for j in range(1, len(f)):
        if not 0.5 * fp <= f[j] <= 2.5 * fp:
            continue
        k = wavenumber(f[j])
        a = np.stack([np.exp(-1j * k * x), np.exp(1j * k * x)], axis=1)
        (ai, ar), *_ = np.linalg.lstsq(a, spectra[:, j], rcond=None)
        m_in += 2 * abs(ai) ** 2 / n**2
        m_re += 2 * abs(ar) ** 2 / n**2
    return 4 * np.sqrt(m_in), 4 * np.sqrt(m_re), [float(4 * e.std()) for e in eta]

def loads(name):
    with h5py.File(f"{out}/{name}/bodies.h5", "r") as h:
        t = h["time"][:]
        keep = (t >= load_from - 1e-9) & (t <= load_to + 1e-9)
        return t[keep], h["bodies/external_force"][:][keep]

weight = 2300 * 0.04**3 * 9.81

def load_differences(reference, other):
    """The units' loads of run `other` against run `reference` over the load window."""
    tr, fr = loads(reference)
    tn, fn = loads(other)
    n = min(len(tr), len(tn))
    fr, fn = fr[:n], fn[:n]
    diff = np.linalg.norm(fn - fr, axis=2)
    rms = lambda a: float(np.sqrt((a**2).mean()))
    return {
        "load_rms_difference": time_series_difference(fr, fn),
        "load_rms_difference_of_whole_load": rms(diff) / rms(np.linalg.norm(fr, axis=2)),
        "load_max_difference_in_unit_weights": float(diff.max() / weight),
        "load_intensity_difference": intensity_difference(fr, fn),
        "layer_load_intensity_ratio": rms(intensity(fn)) / rms(intensity(fr)),
        "records_compared": int(n), "record_time_shift": float(np.abs(tr[:n] - tn[:n]).max()),
        "load_window": [float(tr[0]), float(tr[n - 1])],
    }

rows, by_name = [], {}
print(f"{'mesh':>15s} {'cells':>7s} {'steps':>5s} {'wall s/step':>11s} {'wall s/sim s':>12s} {'wall s/wave':>11s} "
      f"{'Hm0 inc':>8s} {'gauge Hm0 (m)':>22s}")
for name in names:
    s = read_summary(f"{out}/{name}")
    f = s["fluid"]
    steps, wall, cpu, simulated = clock(f"{out}/{name}/case", load_from, waves_to)
    hi, hr, gauges = incident_hm0(name, s)
    row = {"row": name, "mesh": f.get("mesh", "graded"), "ranks": f["np"], "units": s["units"],
           "cells": f["cells_total"], "block_cells": f["cells"], "fine_cell_size": f["cell_size"],
           "steps_in_window": steps, "window": [load_from, load_from + simulated],
           "wall_seconds_per_step": wall / steps, "cpu_seconds_per_step": cpu / steps,
           "wall_seconds_per_simulated_second": wall / simulated, "wall_seconds_per_wave": wall / simulated * tm02,
           "incident_hm0": hi, "reflected_hm0": hr, "gauge_hm0": gauges, "gauge_x": s["waves"]["gauge_x"],
           "wall_seconds": s["wall_seconds"], "dem_share": s.get("dem_seconds", 0.0) / f["solver_seconds"]}
    rows.append(row)
    by_name[name] = row
    print(f"{name:>15s} {row['cells']:7d} {steps:5d} {row['wall_seconds_per_step']:11.3f} "
          f"{row['wall_seconds_per_simulated_second']:12.1f} {row['wall_seconds_per_wave']:11.1f} {hi:8.4f} "
          + " ".join(f"{h:.4f}" for h in gauges))
ref, new = by_name["graded"], by_name["refined"]
loads_compared = load_differences("graded", "refined")
summary = {
    "scene": "scenes/stability_cubes.toml",
    "wall_seconds_per_wave": {r["row"]: r["wall_seconds_per_wave"] for r in rows},
    "speedup": ref["wall_seconds_per_wave"] / new["wall_seconds_per_wave"],
    "incident_height_difference": new["incident_hm0"] / ref["incident_hm0"] - 1.0,
    **loads_compared,
    "waves_window": [waves_from, float(waves_to)],
    "cell_ratio": new["cells"] / ref["cells"],
    "wave_period": tm02, "rows": rows,
    "settle_wall_seconds": json.load(open(f"{out}/refined/settle/summary.json"))["wall_seconds"],
    "loadavg_before": load[0], "loadavg_after": load[1],
    "si_units": {"wall_seconds": "s", "wave_period": "s", "heights": "m", "fine_cell_size": "m",
                 "window": "s", "load_window": "s", "record_time_shift": "s"},
}
if "graded_again" in by_name:
    summary["load_floor"] = load_differences("graded", "graded_again")
window = "{:.2f}-{:.2f} s".format(*summary["load_window"])
print(f"speedup {summary['speedup']:.2f} ({new['cells']} against {ref['cells']} cells); incident Hm0 "
      f"{100 * summary['incident_height_difference']:+.2f} %; loads {100 * summary['load_rms_difference']:.1f} % rms "
      f"of their changing part, intensities {100 * summary['load_intensity_difference']:.1f} % "
      f"({summary['records_compared']} records, {window}); load average before {' '.join(load[0])}, "
      f"after {' '.join(load[1])}")
if "load_floor" in summary:
    floor = summary["load_floor"]
    print(f"floor (graded_again against graded): loads {100 * floor['load_rms_difference']:.1f} %, "
          f"intensities {100 * floor['load_intensity_difference']:.1f} %")
with open(f"{out}/summary.json.tmp", "w") as f:
    json.dump(summary, f, indent=2)
os.replace(f"{out}/summary.json.tmp", f"{out}/summary.json")
PY
