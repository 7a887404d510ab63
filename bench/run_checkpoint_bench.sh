#!/usr/bin/env bash
# The cost of checkpoints on a coupled run: the still-water cube
# (scenes/still_water_cube.toml, 2250 cells, Bullet) run for --seconds of
# simulated time three times in one go, without checkpoints and with
# run.checkpoint_interval = 10 s and 1 s, and the wall time of each as a
# ratio to the run without. A checkpoint asks OpenFOAM for one extra write
# of the fields (binary, full precision), saves the engine and the coupler,
# and copies the time folder; a run with checkpoints also writes every
# field output binary and bodies.h5 uncompressed (docs/checkpoints.md).
# Writes OUT/summary.json (wall seconds and ratios, SI units) and the runs in OUT/<name>.
# Usage: bash bench/run_checkpoint_bench.sh [--build DIR] [--out DIR] [--seconds S]
#   --build    default the repo's build/ (bash scripts/build.sh armour armourFoamCoupling)
#   --out      default ${TMPDIR:-/tmp}/armour-bench/checkpoints
#   --seconds  simulated seconds per run (default 20; > 10 for a 10 s checkpoint)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=checkpoints bench_targets="armour armourFoamCoupling" bench_options="seconds"
opt_seconds=20
source "$root/bench/common.sh"
bench_args "$@"
armour="$build/apps/armour"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
scene="$root/scenes/still_water_cube.toml"
declare -A wall
for interval in 0 10 1; do
  name="every_${interval}s"
  [ "$interval" = 0 ] && name=none
  rm -rf "${out:?}/$name"
  echo "run_checkpoint_bench: $name" >&2
  start=$(date +%s.%N)
  "$armour" run "$scene" --out "$out/$name" --set "run.duration=$opt_seconds" --set run.output_interval=0.05 \
    --set "run.checkpoint_interval=$interval" >"$out/$name.log" 2>&1
  wall[$name]=$(echo "$(date +%s.%N) - $start" | bc -l)
done
python3 - "$out" "$opt_seconds" "${wall[none]}" "${wall[every_10s]}" "${wall[every_1s]}" <<'PY'
import json, sys
out, seconds, none, ten, one = sys.argv[1], float(sys.argv[2]), *map(float, sys.argv[3:])
summary = {"scene": "still_water_cube", "simulated_seconds": seconds,
           "wall_seconds": {"none": none, "every_10s": ten, "every_1s": one},
           "ratio_to_none": {"every_10s": ten / none, "every_1s": one / none},
           "si_units": {"wall_seconds": "s", "simulated_seconds": "s"}}
with open(f"{out}/summary.json", "w") as f:
    json.dump(summary, f, indent=2)
print(json.dumps(summary, indent=2))
PY
