#!/usr/bin/env bash
# The wall time of one mask update (the solid fractions of every unit in the
# fluid cells), the former ramp against the exact fractions, units at rest
# and moving, on the mesh and units of scenes/bench_tank_cubes.toml, and the
# ramp for 100 cubes in 1e5 cells. The tests check the same cases by counts
# (cells visited, bodies recomputed); this gives the time. Prints a table
# and writes OUT/mask_cost.json.
# Usage: bash bench/run_mask_bench.sh [--build DIR] [--out DIR] [--repeats N]
#   --build    default the repo's build/ (target bench_mask_cost)
#   --out      default ${TMPDIR:-/tmp}/armour-bench/mask_cost
#   --repeats  updates timed per row (default 20)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=mask_cost bench_targets=bench_mask_cost bench_options="repeats"
source "$root/bench/common.sh"
bench_args "$@"
"$build/bench/bench_mask_cost" "$out" "${opt_repeats:-20}"
