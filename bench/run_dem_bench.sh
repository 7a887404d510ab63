#!/usr/bin/env bash
# `armour run`'s LIGGGHTS driver against a bare LIGGGHTS script of the same
# scene (50, 100, 200 cubes of 20 spheres), in one run: loop-time ratio,
# sphere-steps per second, cost per unit-step. Writes OUT/summary.json and
# the runs' files, nothing in the source tree.
# Usage: bash bench/run_dem_bench.sh [--build DIR] [--out DIR] [--seconds S]
#   --build    default the repo's build/ (bash scripts/build.sh bench_dem_overhead)
#   --out      default ${TMPDIR:-/tmp}/armour-bench/dem
#   --seconds  simulated seconds per run, default 1.0
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=dem bench_targets=bench_dem_overhead bench_options="seconds"
source "$root/bench/common.sh"
bench_args "$@"
"$build/bench/bench_dem_overhead" "$out" "${opt_seconds:-1.0}"
