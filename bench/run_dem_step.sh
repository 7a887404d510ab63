#!/usr/bin/env bash
# The DEM's own time step as a lever on a coupled run's cost: the stability
# scene's cube clump (0.04 m, 118 spheres, softened concrete, its contact
# model) at multiples of its step limit (engines/time_step.h; the default
# step is 0.2 x the limit). What a coarser step costs in accuracy:
#   drops   one cube dropped flat and onto a corner at 1 m/s (the scene's
#           characteristic velocity, the impact the limit is sized for): the
#           rebound speed and the largest spin after impact, against the
#           finest step's;
#   hold    the stability scene's settled layer (99 units, settled at once:
#           Dn/2 cells for the short coupled start, which the settle does not use)
#           held dry: how far the units creep at each step;
# and what it saves: the hold's wall seconds per simulated second (the DEM's
# sub-steps are this cost inside every coupled step). Writes OUT/summary.json
# (SI: m, s, m/s, rad/s) and prints a table. ~10 min on one core.
# Usage: bash bench/run_dem_step.sh [--build DIR] [--out DIR] [--multiples "0.05 0.2 ..."]
#        [--hold-multiples "0.2 0.4 ..."] [--hold S]
#   --build           default the repo's build/ (bash scripts/build.sh armour)
#   --out             default ${TMPDIR:-/tmp}/armour-bench/dem_step
#   --multiples       the drops' multiples of the limit, default "0.05 0.1 0.2 0.4 0.6 0.8 1 1.5"
#                     (the first is the reference)
#   --hold-multiples  default "0.2 0.4 0.6 1"
#   --hold            seconds of simulated time each hold runs, default 5
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=dem_step bench_targets=armour bench_options="multiples hold-multiples hold"
source "$root/bench/common.sh"
bench_args "$@"
multiples="${opt_multiples:-0.05 0.1 0.2 0.4 0.6 0.8 1 1.5}"
hold_multiples="${opt_hold_multiples:-0.2 0.4 0.6 1}"
hold="${opt_hold:-5}"
armour="$build/apps/armour"
py=/usr/bin/python3

# The drop: the stability scene's unit and concrete (scenes/stability_cubes.toml),
# released 0.051 m above a rigid floor (1 m/s at impact).
cat >"$out/drop.toml" <<'EOF'
# One stability-scene cube dropped onto a floor at 1 m/s (bench/run_dem_step.sh). SI units.
name = "dem_step_drop"
[run]
engine = "liggghts"
duration = 0.4                   # s
output_interval = 0.001          # s: frames fine enough to catch the impact
time_step = 0.0                  # s; set by the bench
domain_min = [-0.5, -0.5, -0.1]  # m
domain_max = [0.5, 0.5, 0.5]     # m
[contact]
model = "hertz"
characteristic_velocity = 1.0    # m/s, as the stability scene
[analysis]
kind = "bounce"
[[material]]
name = "concrete"
youngs_modulus = 5e7             # Pa, softened as the stability scene
restitution = 0.3
friction = 0.6
[[unit]]
name = "cube"
shape = "cube"
size = 0.04                      # m
density = 2300.0                 # kg/m^3
tol_surface = 0.01               # 118 spheres, the stability scene's clump
material = "concrete"
[[wall]]
name = "floor"
type = "plane"
point = [0.0, 0.0, 0.0]          # m
normal = [0.0, 0.0, 1.0]
size = 1.0                       # m
material = "concrete"
[[body]]
unit = "cube"
position = [0.0, 0.0, 0.071]     # m: the bottom face 0.051 m above the floor
EOF
declare -A drop_sets=(
  [flat]=""
  # A body diagonal vertical (as bench/run_time_step_blowup.sh), the corner 0.051 m up.
  [corner]="--set body.0.orientation=[0.8881,0.3251,-0.3251,0.0] --set body.0.position=[0.0,0.0,0.0856]"
)

# The step limit of a scene, from a default run's summary.
limit_of() { "$py" -c "import json,sys; print(json.load(open(sys.argv[1]))['dt_limit'])" "$1/summary.json"; }

"$armour" run "$out/drop.toml" --set run.duration=0.001 --out "$out/drop-limit" >"$out/drop-limit.log" 2>&1
drop_limit=$(limit_of "$out/drop-limit")
rows=()
for variant in flat corner; do
  for m in $multiples; do
    dir="$out/drop-$variant-x$m"
    # shellcheck disable=SC2086
    "$armour" run "$out/drop.toml" ${drop_sets[$variant]} --set "run.time_step=$("$py" -c "print($m * $drop_limit)")" \
      --set run.force_time_step=true --out "$dir" >"$dir.log" 2>&1
    rows+=("drop $variant $m $dir")
  done
done

# The hold: settle the scene's layer at once, then hold its layer with the fluid's tables removed.
bench_settled_layer_dry
hold_limit=$(limit_of "$layer/settle")
for m in $hold_multiples; do
  dir="$out/hold-x$m"
  "$armour" run "$out/hold.toml" --set "run.duration=$hold" --set "run.time_step=$("$py" -c "print($m * $hold_limit)")" \
    --set run.force_time_step=true --set run.output_interval=0.05 --out "$dir" >"$dir.log" 2>&1
  rows+=("hold layer $m $dir")
done

printf '%s\n' "${rows[@]}" | "$py" "$root/bench/dem_step_table.py" "$out" "$drop_limit" "$hold_limit"
