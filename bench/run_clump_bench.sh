#!/usr/bin/env bash
# Clump error and build time against N (5...200), cube and dolos, both methods.
# Usage: bash bench/run_clump_bench.sh [OUT_DIR]   (default out/bench_clump)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/out/bench_clump}"
bash "$root/scripts/build.sh" bench_clump_convergence
"$root/build/bench/bench_clump_convergence" "$out"
# Debian's interpreter: python3-matplotlib is installed for it, not for other pythons on PATH.
/usr/bin/python3 "$root/bench/plot_clump_convergence.py" "$out"
