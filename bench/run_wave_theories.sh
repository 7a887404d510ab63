#!/usr/bin/env bash
# OpenFOAM's stock StokesV and cnoidal wave makers in the empty flume
# (scenes/wave_flume.toml, h = 0.4 m), each at a wave inside its validity:
# StokesV H = 0.06 m, T = 1.2 s (H/L0 = 0.027, Ur = 3.5, kh = 1.30), 32 s;
# cnoidal H = 0.06 m, T = 3.0 s (Ur = 31, kh = 0.44), 30 s. Prints each
# gauge's zero-crossing height and period against the target (the table of
# docs/waves.md) and writes OUT/summary.json (SI: m, s). ~100-120 s of CPU each.
# Usage: bash bench/run_wave_theories.sh [--build DIR] [--out DIR] [--theories "StokesV cnoidal"]
#   --build     default the repo's build/ (targets armour armourWaves)
#   --out       default ${TMPDIR:-/tmp}/armour-bench/wave_theories
#   --theories  which to run (default "StokesV cnoidal")
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=wave_theories bench_targets="armour armourWaves" bench_options="theories"
source "$root/bench/common.sh"
bench_args "$@"
theories="${opt_theories:-StokesV cnoidal}"
for theory in $theories; do
  case "$theory" in
    StokesV) sets=(--set waves.height=0.06 --set waves.period=1.2) ;;
    cnoidal) sets=(--set waves.height=0.06 --set waves.period=3.0 --set run.duration=30) ;;
    *) bench_fail "--theories: $theory is not StokesV or cnoidal" ;;
  esac
  "$build/apps/armour" run "$root/scenes/wave_flume.toml" --out "$out/$theory" "${sets[@]}" \
    --set "waves.theory=\"$theory\"" >"$out/$theory.log" 2>&1
done
/usr/bin/python3 - "$out" $theories <<'PY'
import json, os, sys
from armour_results import read_summary
out, theories = sys.argv[1], sys.argv[2:]
result = {"bench": "wave_theories", "runs": {}, "si_units": {"height": "m", "period": "s"}}
print("| theory | H, T target | gauge heights (zero crossing) | gauge periods | Kr |")
print("|---|---|---|---|---|")
for theory in theories:
    w = read_summary(f"{out}/{theory}")["waves"]
    H, T = w["target_height"], w["target_period"]
    hs = ", ".join(f"{h:.4f} ({100 * (h / H - 1):+.1f} %)" for h in w["gauge_heights"])
    ts = ", ".join(f"{t:.3f}" for t in w["gauge_periods"])
    print(f"| {theory} | {H} m, {T} s | {hs} | {ts} s | {100 * w['reflection_coefficient']:.1f} % |")
    result["runs"][theory] = {k: w[k] for k in ("theory", "target_height", "target_period", "gauge_heights",
                                                 "gauge_periods", "incident_height", "reflection_coefficient", "window")}
tmp = f"{out}/summary.json.tmp"
with open(tmp, "w") as f:
    json.dump(result, f, indent=2)
os.replace(tmp, f"{out}/summary.json")
PY
