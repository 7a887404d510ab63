#!/usr/bin/env bash
# The released cube (scenes/released_cube.toml: a = 0.2 m, 4 cells across,
# density 1050, added_mass 0.5, heave only) started at three offsets in the
# grid: faces on cell faces, a quarter cell off, on cell centres (the
# centre moved by 0, 0.0125, 0.025 m along x, y and z), with the exact solid
# fractions and with the former sampled ramp. A position-independent mask
# makes the three sink alike. Prints and writes OUT/summary.json: the heave
# (m) after DURATION s per offset and mode.
# Usage: bash bench/run_released_offsets.sh [--build DIR] [--out DIR] [--duration S]
#   --build     default the repo's build/ (targets armour armourFoamCoupling)
#   --out       default ${TMPDIR:-/tmp}/armour-bench/released_offsets
#   --duration  simulated seconds per run (default 1.0)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=released_offsets bench_targets="armour armourFoamCoupling" bench_options="duration"
source "$root/bench/common.sh"
bench_args "$@"
duration="${opt_duration:-1.0}"
for mode in exact ramp; do
  for offset in 0 0.0125 0.025; do
    pos="[$offset,$offset,$(python3 -c "print(0.35 + $offset)")]"
    "$build/apps/armour" run "$root/scenes/released_cube.toml" --out "$out/${mode}_$offset" \
      --set "unit.0.density=1050" --set "fluid.added_mass=0.5" --set "run.duration=$duration" \
      --set "run.output_interval=0.05" --set "body.0.position=$pos" \
      --set "fluid.solid_fraction=\"$mode\"" >"$out/${mode}_$offset.log" 2>&1
  done
done
/usr/bin/python3 - "$out" "$duration" <<'PY'
import json, sys
from armour_results import read_bodies
out, duration = sys.argv[1], float(sys.argv[2])
rows = []
print(f"{'mask':>6s} {'offset m':>9s} {'heave m':>9s}")
for mode in ("exact", "ramp"):
    for offset in ("0", "0.0125", "0.025"):
        b = read_bodies(f"{out}/{mode}_{offset}")
        heave = float(b.position[-1, 0, 2] - b.position[0, 0, 2])
        rows.append({"solid_fraction": mode, "offset": float(offset), "time": float(b.time[-1]), "heave": heave})
        print(f"{mode:>6s} {offset:>9s} {heave:+9.4f}")
with open(f"{out}/summary.json", "w") as f:
    json.dump({"bench": "released_offsets", "duration": duration, "rows": rows,
               "si_units": {"offset": "m", "heave": "m", "time": "s"}}, f, indent=2)
PY
