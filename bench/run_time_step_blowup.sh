#!/usr/bin/env bash
# Where the multisphere DEM time step blows up: scenes/drop_bounce.toml (a
# 20-sphere cube dropped 0.5 m flat, restitution 0.5) and the same drop onto
# a corner (turned 54.7 deg about (1, -1, 0): a body diagonal vertical; restitution 1: no damping), run at
# increasing multiples of the stability limit (engines/time_step.h) with
# run.force_time_step, frames (and energy samples) every 15 ms. A run is stable if its mechanical energy never rises
# above its start by more than 1 % of m g Dn. Writes OUT/blowup.json and
# prints a table.
# Usage: bash bench/run_time_step_blowup.sh [--build DIR] [--out DIR] [--multiples "0.2 1 2 ..."]
#   --build      default the repo's build/ (bash scripts/build.sh armour)
#   --out        default ${TMPDIR:-/tmp}/armour-bench/time_step
#   --multiples  default "0.2 0.5 1 1.5 2 3 4 6 8"
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=time_step bench_targets=armour bench_options="multiples"
source "$root/bench/common.sh"
bench_args "$@"
multiples="${opt_multiples:-0.2 0.5 1 1.5 2 3 4 6 8}"
armour="$build/apps/armour"
scene="$root/scenes/drop_bounce.toml"
declare -A variant_sets=(
  [flat]=""
  [corner]="--set body.0.orientation=[0.8881,0.3251,-0.3251,0.0] --set material.0.restitution=1.0"
)
rows=()
for variant in flat corner; do
  # The limit of this variant, from a default run's summary.
  # shellcheck disable=SC2086
  "$armour" run "$scene" ${variant_sets[$variant]} --set run.duration=0.01 --out "$out/$variant-limit" >/dev/null 2>&1
  limit=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['dt_limit'])" \
    "$out/$variant-limit/summary.json")
  for m in $multiples; do
    dt=$(/usr/bin/python3 -c "print($m * $limit)")
    dir="$out/$variant-x$m"
    # shellcheck disable=SC2086
    # Frames every 15 ms: above the largest step; energy is sampled there.
    if "$armour" run "$scene" ${variant_sets[$variant]} --set "run.time_step=$dt" --set run.force_time_step=true \
      --set run.output_interval=0.015 --out "$dir" >"$dir.log" 2>&1; then status=ok; else status=failed; fi
    rows+=("$variant $m $dt $limit $status $dir")
  done
done
printf '%s\n' "${rows[@]}" | /usr/bin/python3 -c '
import json, sys
rows = []
print("%-7s %6s %11s %8s %12s" % ("drop", "x limit", "dt [s]", "status", "gain/(m g Dn)"))
for line in sys.stdin:
    variant, m, dt, limit, status, d = line.split()
    gain = None
    try:
        s = json.load(open(d + "/summary.json"))
        gain = (s["energy_max"] - s["energy_initial"]) / s["energy_scale"]
    except (OSError, KeyError, ValueError):
        status = "failed"
    stable = status == "ok" and gain is not None and gain <= 0.01
    rows.append({"variant": variant, "multiple": float(m), "dt": float(dt), "dt_limit": float(limit),
                 "status": status, "energy_gain_normalised": gain, "stable": stable})
    print("%-7s %6s %11.3g %8s %12s" % (variant, m, float(dt), status if status != "ok" else ("stable" if stable else "GAIN"),
                                     "-" if gain is None else "%.4f" % gain))
doc = {"units": {"dt": "s", "energy_gain_normalised": "(E_max - E_0) / sum m g Dn"}, "rows": rows}
json.dump(doc, open(sys.argv[1] + "/blowup.json", "w"), indent=2)
json.dump(doc, open(sys.argv[1] + "/summary.json", "w"), indent=2)
' "$out"
