#!/usr/bin/env bash
# The released cube (scenes/released_cube.toml: a = 0.2 m, 4 cells across,
# density 1050, added_mass 0.5, heave only) started at three offsets in the
# grid: faces on cell faces, a quarter cell off, on cell centres (the
# centre moved by 0, h/4 and h/2 along x, y and z, h the cell size: 0,
# 0.0125, 0.025 m at 4 across), with the exact solid fractions and with the
# former sampled ramp. A position-independent mask makes the three sink
# alike. With --across, the exact mask on finer meshes too: how the spread
# goes with the cells across the cube. Prints and writes OUT/summary.json:
# the heave (m) after DURATION s per offset, mode and cells across, and the
# spread of the three offsets ((max - min) / mean) per mesh.
# Usage: bash bench/run_released_offsets.sh [--build DIR] [--out DIR] [--duration S] [--across 'N ...']
#   --build     default the repo's build/ (targets armour armourFoamCoupling)
#   --out       default ${TMPDIR:-/tmp}/armour-bench/released_offsets
#   --duration  simulated seconds per run (default 1.0)
#   --across    cells across the cube for the exact mask, 0.2 m / N cells (default 4; the ramp runs at 4)
#               e.g. '4 6 8 12': 12 across is ~4 min a run on one core
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=released_offsets bench_targets="armour armourFoamCoupling" bench_options="duration across"
source "$root/bench/common.sh"
bench_args "$@"
duration="${opt_duration:-1.0}"
read -ra across <<<"${opt_across:-4}"
for n in "${across[@]}"; do
  [[ "$n" =~ ^[1-9][0-9]*$ ]] || bench_fail "--across $n: cells across must be a whole number >= 1"
done
run_one() { # mode, cells across, offset in cells
  local h o name
  h="$(python3 -c "print(0.2 / $2)")" o="$(python3 -c "print($3 * 0.2 / $2)")"
  name="${1}_$o"
  [ "$2" = 4 ] || name="${1}_${2}across_$3"
  "$build/apps/armour" run "$root/scenes/released_cube.toml" --out "$out/$name" \
    --set "unit.0.density=1050" --set "fluid.added_mass=0.5" --set "run.duration=$duration" \
    --set "run.output_interval=0.05" --set "body.0.position=[$o,$o,$(python3 -c "print(0.35 + $o)")]" \
    --set "fluid.cell_size=$h" --set "fluid.solid_fraction=\"$1\"" >"$out/$name.log" 2>&1
  echo "$1 $2 $3 $o $name" >>"$out/runs.txt"
}
: >"$out/runs.txt"
for f in 0 0.25 0.5; do run_one ramp 4 "$f"; done
for n in "${across[@]}"; do
  for f in 0 0.25 0.5; do run_one exact "$n" "$f"; done
done
/usr/bin/python3 - "$out" "$duration" <<'PY'
import json, sys
from armour_results import read_bodies
out, duration = sys.argv[1], float(sys.argv[2])
rows, spread = [], {}
print(f"{'mask':>6s} {'across':>6s} {'offset m':>9s} {'heave m':>9s}")
for line in open(f"{out}/runs.txt"):
    mode, across, cells, offset, name = line.split()
    b = read_bodies(f"{out}/{name}")
    heave = float(b.position[-1, 0, 2] - b.position[0, 0, 2])
    rows.append({"solid_fraction": mode, "cells_across": int(across), "offset_cells": float(cells),
                 "offset": float(offset), "time": float(b.time[-1]), "heave": heave})
    print(f"{mode:>6s} {across:>6s} {float(offset):9.4f} {heave:+9.4f}")
    spread.setdefault(f"{mode}_{across}", []).append(heave)
spread = {k: (max(h) - min(h)) / abs(sum(h) / len(h)) for k, h in spread.items()}
print("spread of the offsets ((max - min) / |mean|):", {k: round(v, 3) for k, v in spread.items()})
with open(f"{out}/summary.json", "w") as f:
    json.dump({"bench": "released_offsets", "duration": duration, "rows": rows, "spread": spread,
               "si_units": {"offset": "m", "heave": "m", "time": "s", "spread": "-"}}, f, indent=2)
PY
