#!/usr/bin/env bash
# Buoyancy of a submerged cube against its position and orientation in the
# grid, the former sampled ramp against the exact solid fractions, at 3, 4, 6
# and 12 cells across (mean, min, max over random poses). Writes
# OUT/buoyancy_positions.{json,png} and OUT/summary.json (docs/images/
# buoyancy_positions.png is a copy).
# Usage: bash bench/run_buoyancy_positions.sh [--build DIR] [--out DIR] [--poses N]
#   --build  default the repo's build/ (target bench_buoyancy_positions)
#   --out    default ${TMPDIR:-/tmp}/armour-bench/buoyancy_positions
#   --poses  random poses per resolution (default 200)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=buoyancy_positions bench_targets=bench_buoyancy_positions bench_options="poses"
source "$root/bench/common.sh"
bench_args "$@"
"$build/bench/bench_buoyancy_positions" "$out" "${opt_poses:-200}"
# Debian's interpreter: python3-matplotlib is installed for it.
/usr/bin/python3 "$root/bench/plot_buoyancy_positions.py" "$out"
