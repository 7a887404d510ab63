#!/usr/bin/env bash
# Mesh convergence of the headline coupled figures, with the exact solid
# fractions (the default), at LEVELS cells across a unit (fluid.cell_size =
# a / n; blockMesh rounds the count per axis):
#   floating  scenes/floating_cube.toml: draft (m), against rho_u / rho_w a
#   dambreak  scenes/dambreak_two_cubes.toml: peak streamwise fluid force on
#             the first and second cube as the bore hits them, before the
#             first catches the second (N); run for DB_DURATION s (both peaks
#             come before 0.45 s), fluid step <= 2 ms at every level and
#             recorded every 2 ms, so the peak is sampled at each fluid step
#   platform  scenes/solitary_cubes_platform.toml, 3 s (the cubes lie on the
#             floor by 2.6 s): largest cube displacement (m) and the crest at
#             the gauge (m)
# The observed order p and the extrapolated value come from the three finest
# levels that ran (Richardson, unequal ratios); each level's error is taken
# against the extrapolated value. Runs whose summary.json exists are kept, so
# a second call with more levels only adds the missing runs.
# Writes OUT/<case>_<n>/ (the runs), OUT/mesh_convergence.{md,png} and
# OUT/summary.json (SI: m, N, s).
# Usage: bash bench/run_mesh_convergence.sh [--build DIR] [--out DIR] [--levels "3 4 6 8"]
#          [--cases "floating dambreak platform"] [--db-duration S] [--error E]
#   --build        default the repo's build/ (targets armour armourFoamCoupling armourWaves)
#   --out          default ${TMPDIR:-/tmp}/armour-bench/mesh_convergence
#   --levels       cells across a unit (default "3 4 6 8")
#   --cases        default "floating dambreak platform"
#   --db-duration  simulated seconds of the dam break (default 0.6)
#   --error        error the recommended resolution must stay within (default 0.05)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=mesh_convergence bench_targets="armour armourFoamCoupling armourWaves"
bench_options="levels cases db-duration error"
source "$root/bench/common.sh"
bench_args "$@"
levels="${opt_levels:-3 4 6 8}"
cases="${opt_cases:-floating dambreak platform}"
db_duration="${opt_db_duration:-0.6}"
error="${opt_error:-0.05}"

# scene, unit size (m) and extra --set options per case
scene_of() {
  case "$1" in
    floating) echo "floating_cube.toml 0.2" ;;
    dambreak) echo "dambreak_two_cubes.toml 0.08" ;;
    platform) echo "solitary_cubes_platform.toml 0.06" ;;
    *) bench_fail "--cases: $1: unknown (floating, dambreak, platform)" ;;
  esac
}
extra_of() {
  case "$1" in
    dambreak) echo "run.duration=$db_duration run.output_interval=0.002 fluid.max_time_step=0.002" ;;
    platform) echo "run.duration=3.0" ;;
    *) echo "" ;;
  esac
}

for n in $levels; do
  for c in $cases; do
    read -r scene size <<<"$(scene_of "$c")"
    run="$out/${c}_$n"
    [ -f "$run/summary.json" ] && continue
    rm -rf "$run" # a run stopped part-way (no summary): ours, started again
    cell="$(/usr/bin/python3 -c "print('%.10g' % ($size / $n))")"
    sets=(--set "fluid.cell_size=$cell")
    for s in $(extra_of "$c"); do sets+=(--set "$s"); done
    echo "$c at $n cells across (cell_size $cell m) ..."
    "$build/apps/armour" run "$root/scenes/$scene" --out "$run" "${sets[@]}" >"$run.log" 2>&1 ||
      echo "  failed: see $run.log"
  done
done
/usr/bin/python3 "$root/bench/plot_mesh_convergence.py" "$out" "$error"
