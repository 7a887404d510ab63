#!/usr/bin/env bash
# The loads the coupling computes on a unit, against a reference without an
# immersed boundary: scenes/wave_load_cube.toml (a 0.1 m cube held 0.05 m
# above the bed of a wave flume, regular waves H 0.1 m, T 1.6 s) run twice on
# the same mesh and the same waves:
#   immersed     armour run: the cube is the coupling's mask (exact solid
#                fractions, penalty), its load the fluid's force density
#                summed over its cells (bodies.h5, external_force/torque);
#   body_fitted  stock interFoam: the same case with the cube's cells cut out
#                (topoSet + subsetMesh; its faces lie on cell faces) and its
#                faces a no-slip wall patch, forces and moments about the
#                cube's centre from OpenFOAM's forces function object.
# Compared over the window after the ramp (--from .. the end): for Fx, Fz and
# My the rms of the difference relative to the rms of the reference's changing
# part (its value less its mean over the window), and the peaks.
# Writes OUT/summary.json (SI: N, N m, s), OUT/body_fitted_loads.png, nothing
# in the source tree.
# With --reference DIR (the OUT of a finer run of this bench), both runs are
# also compared with that run's body-fitted loads (summary.json "vs_reference").
# Usage: bash bench/run_body_fitted_loads.sh [--build DIR] [--out DIR]
#            [--cells-across 2|4|8] [--duration S] [--from S] [--reference DIR]
#            [--only body_fitted] [--set KEY=VALUE]
#   --cells-across  cells across the cube: 4 is the scene's (Dn/4, 2.5 cm),
#                   2 and 8 scale the cells along each axis. Default 4.
#   --duration      simulated s, default the scene's 12
#   --from          start of the compared window, s, default 6
#   --set           one scene key for the immersed run only (e.g. fluid.penalty=1e4:
#                   the body-fitted run has no mask, so it does not change)
#   --only body_fitted  the stock run alone (a reference for coarser runs; the
#                   coupled run makes only its case, 0.02 s), no comparison
# Cost (2 shared cores, the other busy): ~14 min at 4 across (7 per run),
# ~2 min at 2; 8 across ~10x the cells and 2x the steps of 4.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=body_fitted_loads bench_targets="armour armourFoamCoupling armourWaves"
bench_options="cells-across duration from reference only set"
source "$root/bench/common.sh"
bench_args "$@"
across="${opt_cells_across:-4}"
duration="${opt_duration:-12}"
from="${opt_from:-6}"
reference="${opt_reference:-}"
only="${opt_only:-both}"
case "$only" in both | body_fitted) ;; *) bench_fail "--only: body_fitted (got $only)" ;; esac
[ -z "$reference" ] || [ -f "$reference/body_fitted/postProcessing/cubeLoads/0/force.dat" ] ||
  bench_fail "--reference $reference: no body-fitted loads there (an OUT of this bench)"
armour="$build/apps/armour"
export WM_PROJECT_DIR=/usr/share/openfoam
py=/usr/bin/python3
scene="$root/scenes/wave_load_cube.toml"
sets=(--set "run.duration=$([ "$only" = both ] && echo "$duration" || echo 0.02)")
case "$across" in # the scene's [240, 12, 24] fine cells scaled: the cube's faces stay on cell faces
  2) # 5 cm everywhere: the fine cell is the coarse one, so the refined box covers the flume
    sets+=(--set 'fluid.cells=[120,6,12]' --set 'fluid.refine_min=[0,0,0]' --set 'fluid.refine_max=[6,0.3,0.6]'
      --set 'fluid.coarse_cell_size=[0.1,0,0]') ;;
  4) ;;
  8) sets+=(--set 'fluid.cells=[480,24,48]') ;;
  *) bench_fail "--cells-across: 2, 4 or 8 (got $across)" ;;
esac
[ -z "${opt_set:-}" ] || sets+=(--set "$opt_set") # the immersed run's only: the stock run has no mask

# 1. The coupled run: its case folder is also the stock run's start.
rm -rf "$out/immersed" "$out/body_fitted"
start=$(date +%s.%N)
"$armour" run "$scene" --out "$out/immersed" "${sets[@]}" 2>"$out/immersed.log" ||
  { tail -n 3 "$out/immersed.log" >&2; exit 1; }
$py -c "import sys; print(float(sys.argv[1]) - float(sys.argv[2]))" "$(date +%s.%N)" "$start" \
  >"$out/immersed.wall_seconds"

# 2. The same case, stock: no plugin, the cube cut out of the mesh.
dir="$out/body_fitted"
mkdir -p "$dir"
cp -r "$out/immersed/case/system" "$out/immersed/case/constant" "$dir/"
mkdir "$dir/0" && cp "$out/immersed/case/0/"*.orig "$dir/0/"
rm -rf "$dir/constant/fvOptions" "$dir/constant/polyMesh"
$py "$root/bench/body_fitted_case.py" "$dir" "$out/immersed/scene.resolved.toml" "$duration"
foam() { # TOOL [ARGS...]: an OpenFOAM tool in the case, its log there; the log's end when it fails
  "$@" >"log.$1" 2>&1 || { echo "$(basename "$0"): $1 failed ($dir/log.$1):" >&2; tail -n 5 "log.$1" >&2; exit 1; }
}
(
  cd "$dir"
  foam blockMesh
  foam topoSet
  foam subsetMesh -overwrite fluid -patch cube
  for f in 0/*.orig; do cp "$f" "${f%.orig}"; done
  foam setFields
  start=$(date +%s.%N)
  foam interFoam
  $py -c "import sys; print(float(sys.argv[1]) - float(sys.argv[2]))" "$(date +%s.%N)" "$start" >wall_seconds
)

# 3. The comparison.
[ "$only" = both ] || exit 0
$py "$root/bench/body_fitted_case.py" --compare "$out" "$from" ${reference:+"$reference"}
