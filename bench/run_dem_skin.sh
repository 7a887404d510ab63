#!/usr/bin/env bash
# The DEM's neighbour skin against its cost: LIGGGHTS rebuilds its neighbour
# lists whenever a sphere has moved half the skin, and a larger skin puts
# more pairs in them. The stability scene's 99 cubes (118-sphere clumps) are
# settled once by `armour run`; the LIGGGHTS set-up the adapter wrote for it
# (OUT/layer/settle/liggghts/input.liggghts: the loose pile before the
# settle) and for a dry hold of the settled layer (the layer at rest) are
# then replayed by the bare `liggghts` executable at each skin, under gravity
# alone, for the same steps: the pile falls and settles (units moving, as in
# waves), the layer stays still. Reports LIGGGHTS' own loop time and
# neighbour-list builds, and the cost against the adapter's skin
# (0.2 x the largest sphere radius, engines/liggghts_engine.cpp). Writes
# OUT/summary.json (SI: m, s) and prints a table. ~5 min on one core.
# Usage: bash bench/run_dem_skin.sh [--build DIR] [--out DIR] [--skins "0.0002 0.004 ..."] [--steps N]
#   --build   default the repo's build/ (bash scripts/build.sh armour)
#   --out     default ${TMPDIR:-/tmp}/armour-bench/dem_skin
#   --skins   m, default "0.0002 0.001 0.002 0.008", and always the adapter's own (0.0002: half the clump's
#             smallest sphere, the adapter's former skin)
#   --steps   DEM steps per replay, default 8000 (0.3 s)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=dem_skin bench_targets=armour bench_options="skins steps"
source "$root/bench/common.sh"
bench_args "$@"
skins="${opt_skins:-0.0002 0.001 0.002 0.008}"
steps="${opt_steps:-8000}"
command -v liggghts >/dev/null || bench_fail "needs the liggghts executable (Debian package liggghts)"

bench_settled_layer_dry
bench_held_layer_input

# The adapter's own skin is always among those replayed.
adapter_skin=$(sed -n 's/^variable skin string "\(.*\)"/\1/p' "$layer/settle/liggghts/input.liggghts")
skins=$(printf '%s\n' $skins "$adapter_skin" | sort -g -u)
rows=()
for phase in moving rest; do
  case $phase in
    moving) input="$layer/settle/liggghts/input.liggghts" ;;
    rest) input="$held_input" ;;
  esac
  for skin in $skins; do
    name="$phase-$skin"
    sed "s/^variable skin string .*/variable skin string \"$skin\"/" "$input" >"$out/$name.in"
    printf 'fix grav all gravity 9.81 vector 0.0 0.0 -1.0\nrun %s\n' "$steps" >>"$out/$name.in"
    liggghts -in "$out/$name.in" -log "$out/$name.log" -screen /dev/null
    rows+=("$phase $skin $out/$name.log")
  done
done

printf '%s\n' "${rows[@]}" | /usr/bin/python3 -c '
import json, re, sys
out, adapter, steps = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
rows = []
for line in sys.stdin:
    phase, skin, log = line.split()
    text = open(log).read()
    loop = float(re.findall(r"Loop time of ([0-9.eE+-]+)", text)[-1])
    builds = int(re.findall(r"Neighbor list builds = (\d+)", text)[-1])
    dangerous = int(re.findall(r"Dangerous builds = (\d+)", text)[-1])
    rows.append({"phase": phase, "skin": float(skin), "loop_seconds": loop, "neighbour_builds": builds,
                 "dangerous_builds": dangerous, "steps": steps})
print("%-7s %8s %10s %16s %10s %s" % ("phase", "skin [m]", "loop [s]", "builds (steps)", "dangerous", "cost / adapter skin"))
for r in rows:
    ref = next((q for q in rows if q["phase"] == r["phase"] and abs(q["skin"] - adapter) < 1e-12), None)
    r["cost_vs_adapter_skin"] = r["loop_seconds"] / ref["loop_seconds"] if ref else None
    print("%-7s %8g %10.2f %16s %10d %s" % (r["phase"], r["skin"], r["loop_seconds"],
          "%d (%d)" % (r["neighbour_builds"], steps), r["dangerous_builds"],
          "-" if ref is None else "%.2f" % r["cost_vs_adapter_skin"]))
doc = {"units": {"skin": "m", "loop_seconds": "s (LIGGGHTS loop time)"}, "adapter_skin": adapter,
       "phases": {"moving": "the loose pile before the settle, falling under gravity",
                  "rest": "the settled layer held dry"}, "rows": rows}
json.dump(doc, open(out + "/summary.json", "w"), indent=2)
' "$out" "$adapter_skin" "$steps"
