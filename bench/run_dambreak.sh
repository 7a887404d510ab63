#!/usr/bin/env bash
# The dam-break reference case (scenes/dambreak_two_cubes.toml, 1.5 s, 4 cells
# across a cube), with the exact solid fractions (the default) and, for
# comparison, the former sampled ramp. Prints the per-cube table of
# docs/openfoam.md (first / second cube in the flow) and writes
# OUT/summary.json with both runs' rows (SI: s, m, m/s, N).
# Usage: bash bench/run_dambreak.sh [--build DIR] [--out DIR] [--modes "exact ramp"]
#   --build  default the repo's build/ (targets armour armourFoamCoupling)
#   --out    default ${TMPDIR:-/tmp}/armour-bench/dambreak
#   --modes  fluid.solid_fraction values to run (default "exact ramp")
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=dambreak bench_targets="armour armourFoamCoupling" bench_options="modes"
source "$root/bench/common.sh"
bench_args "$@"
modes="${opt_modes:-exact ramp}"
for mode in $modes; do
  "$build/apps/armour" run "$root/scenes/dambreak_two_cubes.toml" --out "$out/$mode" \
    --set "fluid.solid_fraction=\"$mode\"" >"$out/$mode.log" 2>&1
done
/usr/bin/python3 - "$out" $modes <<'PY'
import json, sys
from armour_results import read_summary
out, modes = sys.argv[1], sys.argv[2:]
result = {"bench": "dambreak", "runs": {}, "si_units": {"time": "s", "length": "m", "speed": "m/s", "force": "N"}}
for mode in modes:
    s = read_summary(f"{out}/{mode}")
    units = {u["body"]: u for u in s["per_unit"]}
    first, second = units[s["first_body"]], units[s["second_body"]]
    rows = [("starts downstream (+x > 5 % Dn)", "first_move_time", "{:.3f} s"),
            ("max displacement", "max_displacement", "{:.3f} m"),
            ("final x displacement", "final_displacement_x", "{:+.3f} m"),
            ("max speed", "max_speed", "{:.2f} m/s"),
            ("peak streamwise fluid force", "peak_force_x", "{:.2f} N")]
    print(f"\nsolid_fraction = {mode} ({s['simulated_seconds']:.2f} s simulated, {s['wall_seconds']:.0f} s wall)")
    print("| | first (x0 = %.2f m) | second (x0 = %.2f m) |" % (first["initial_position"][0], second["initial_position"][0]))
    print("|---|---|---|")
    for label, key, fmt in rows:
        f = lambda u: fmt.format(u[key]) if u[key] is not None else "never"
        print(f"| {label} | {f(first)} | {f(second)} |")
    print(f"| `force_difference` | **{s['force_difference']:+.2f} N** | |")
    result["runs"][mode] = {"first": first, "second": second, "force_difference": s["force_difference"],
                            "wall_seconds": s["wall_seconds"]}
with open(f"{out}/summary.json", "w") as f:
    json.dump(result, f, indent=2)
PY
