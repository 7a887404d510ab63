#!/usr/bin/env bash
# `armour run`'s LIGGGHTS driver against a bare LIGGGHTS script of the same
# scene (50, 100, 200 cubes of 20 spheres), in one run: loop-time ratio,
# sphere-steps per second, cost per unit-step.
# Usage: bash bench/run_dem_bench.sh [OUT_DIR] [simulated seconds, default 1.0]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/out/bench_dem}"
bash "$root/scripts/build.sh" bench_dem_overhead
"$root/build/bench/bench_dem_overhead" "$out" "${2:-1.0}"
