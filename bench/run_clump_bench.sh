#!/usr/bin/env bash
# Clump error (volume, surface, inertia, topple angle), build time and the DEM
# time step each clump allows against N (5...200), cube and dolos, both methods.
# Writes OUT/clump_convergence.{json,png} and OUT/summary.json, nothing in the
# source tree (the figure in docs/images is copied there by hand).
# Usage: bash bench/run_clump_bench.sh [--build DIR] [--out DIR]
#   --build  default the repo's build/ (bash scripts/build.sh bench_clump_convergence)
#   --out    default ${TMPDIR:-/tmp}/armour-bench/clump
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=clump bench_targets=bench_clump_convergence bench_options=""
source "$root/bench/common.sh"
bench_args "$@"
"$build/bench/bench_clump_convergence" "$out"
# Debian's interpreter: python3-matplotlib is installed for it, not for other pythons on PATH.
/usr/bin/python3 "$root/bench/plot_clump_convergence.py" "$out"
