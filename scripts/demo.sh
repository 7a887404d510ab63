#!/usr/bin/env bash
# The main job on the built-in default: clumps of a cube and a dolos with the
# fewest spheres meeting 1 % volume and 2 % Dn surface RMS, and their error table.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh" armour
"$root/build/apps/armour" demo --out "${1:-$root/out/demo}"
