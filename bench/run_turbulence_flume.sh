#!/usr/bin/env bash
# The turbulence option's effect on a regular wave travelling along the empty
# flume (scenes/wave_flume.toml: H = 0.06 m, T = 1.6 s, h = 0.4 m, 200 x 60
# cells): laminar, kOmegaSST with its default inflow turbulence
# (turbulence_intensity 1e-4) and with 100 times it (0.01), each with the
# gauge array near the wave maker (waves.gauge_x = 1.0 m) and far along
# (6.5 m). Writes OUT/turbulence_flume.csv (variant, gauge_x, incident height,
# the three gauge heights, reflection) and OUT/summary.json (the incident
# height at each array, its loss per metre between them, and for kOmegaSST
# the eddy viscosity in the water at the end, mean and largest, per variant).
# Six flume runs, ~1.5 min each on 2 cores. docs/turbulence.md shows the numbers.
# Usage: bash bench/run_turbulence_flume.sh [--build DIR] [--out DIR]
#   --build  default the repo's build/ (bash scripts/build.sh armour armourWaves)
#   --out    default ${TMPDIR:-/tmp}/armour-bench/turbulence_flume
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=turbulence_flume bench_targets="armour armourWaves" bench_options=""
source "$root/bench/common.sh"
bench_args "$@"
armour="$build/apps/armour"
for variant in laminar kOmegaSST kOmegaSST-I0.01; do
  model="${variant%-*}"
  sets=(--set "fluid.turbulence=\"$model\"")
  [ "$variant" = kOmegaSST-I0.01 ] && sets+=(--set fluid.turbulence_intensity=0.01)
  for gx in 1.0 6.5; do
    run="$out/${variant}_$gx"
    [ -f "$run/summary.json" ] && continue
    rm -rf "$run"
    "$armour" run "$root/scenes/wave_flume.toml" --out "$run" "${sets[@]}" --set "waves.gauge_x=$gx" \
      > "$run.log" 2>&1 || bench_fail "$variant, gauge_x $gx failed: see $run.log"
  done
done
python3 - "$out" <<'PY'
import json, os, re, sys
out = sys.argv[1]
rows, summary = [], {"si_units": {"heights": "m", "x": "m", "loss_per_m": "1/m", "nut": "m^2/s"},
                     "models": {}}

def cell_values(path):
    """The internalField of an ascii OpenFOAM volScalarField (uniform or a list)."""
    text = open(path).read()
    m = re.search(r"internalField\s+uniform\s+([-0-9.eE+]+)", text)
    if m:
        return None, float(m.group(1))
    m = re.search(r"internalField\s+nonuniform\s+List<scalar>\s*(\d+)\s*\(([^)]*)\)", text)
    return [float(v) for v in m.group(2).split()], None

def eddy_viscosity(case):
    """Mean and largest nut over the water's cells (alpha > 0.5) at the last written time."""
    last = max((d for d in os.listdir(case) if re.fullmatch(r"[0-9.]+", d) and d != "0"), key=float)
    alpha, _ = cell_values(f"{case}/{last}/alpha.water")
    nut, uniform = cell_values(f"{case}/{last}/nut")
    nut = nut or [uniform] * len(alpha)
    water = [v for a, v in zip(alpha, nut) if a > 0.5]
    return float(last), sum(water) / len(water), max(water)
for model in ("laminar", "kOmegaSST", "kOmegaSST-I0.01"):
    heights = {}
    for gx in ("1.0", "6.5"):
        w = json.load(open(f"{out}/{model}_{gx}/summary.json"))["waves"]
        heights[gx] = w["incident_height"]
        rows.append([model, gx, w["incident_height"], *w["gauge_heights"], w["reflection_coefficient"]])
    near, far = heights["1.0"], heights["6.5"]
    summary["models"][model] = {"incident_height_near": near, "incident_height_far": far,
                                "loss_per_m": (near - far) / near / 5.5}
    if model != "laminar":
        t, mean, top = eddy_viscosity(f"{out}/{model}_6.5/case")
        summary["models"][model].update({"nut_time": t, "nut_water_mean": mean, "nut_water_max": top})
# The wave's height (crest to trough) per period T = 1.6 s at each array's first gauge.
periods = {}
for model in ("laminar", "kOmegaSST", "kOmegaSST-I0.01"):
    for gx in ("1.0", "6.5"):
        rows_t = [[float(v) for v in line.split()]
                  for line in open(f"{out}/{model}_{gx}/case/postProcessing/gauges/0/surfaceElevation.dat")
                  if not line.startswith("#")]
        heights = []
        for k in range(20):
            eta = [r[1] for r in rows_t if 1.6 * k <= r[0] < 1.6 * (k + 1)]
            heights.append(max(eta) - min(eta))
        periods[f"{model}_{gx}"] = heights
with open(f"{out}/turbulence_flume_periods.csv", "w") as f:
    f.write("period_start_s," + ",".join(f"{name}_m" for name in periods) + "\n")
    for k in range(20):
        f.write(f"{1.6 * k:.1f}," + ",".join(f"{h[k]:.5f}" for h in periods.values()) + "\n")
with open(f"{out}/turbulence_flume.csv", "w") as f:
    f.write("variant,gauge_x_m,incident_height_m,gauge1_m,gauge2_m,gauge3_m,reflection\n")
    for r in rows:
        f.write(",".join(str(v) for v in r) + "\n")
json.dump(summary, open(f"{out}/summary.json", "w"), indent=2)
print(json.dumps(summary, indent=2))
PY
