#!/usr/bin/env bash
# Installs what is missing, then configures and builds armour-fsi in build/.
# Extra arguments are CMake targets (default: all).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
jobs="$(nproc 2>/dev/null || echo 2)"
if [ $# -eq 0 ]; then
  cmake --build "$root/build" -j "$jobs"
else
  for target in "$@"; do cmake --build "$root/build" -j "$jobs" --target "$target"; done
fi
