#!/usr/bin/env bash
# The pull-out test of a settled armour layer (analysis kind "pull",
# docs/analysis.md): what holds each outer unit in its seat, apart from the
# waves. SCENE is a settled scene (an `armour run` folder's
# settle/scene.settled.toml); the script writes OUT/dry.toml (the scene
# without its [fluid], [waves], [[porous]], [[series]] and [[refine]] tables:
# the layer, its walls and materials, dry; a scene as `armour run` resolves
# it, one table header per line) and runs every round of units (each round's
# units >= 3 Dn apart) into OUT/round_K, --jobs at a time side by side, until
# a round finds no unit left (run again with the same options, it keeps the
# rounds that finished and runs the rest). Writes OUT/pull.csv (every
# pulled unit: its round, where it sits, the pull it held in its own weights
# m|g|), OUT/pull.png and OUT/summary.json (the median and quartiles of the
# resistance, in weights; units that never left count as --max; units the dry
# start moved from their seat before the pull are counted apart, as unseated).
# Usage: bash bench/run_pull_test.sh --scene SCENE [--engine E] [--rate R] [--max M]
#          [--angle DEG] [--jobs J] [--rounds N] [--sets 'KEY=VALUE ...'] [--build DIR] [--out DIR]
#   --scene   a settled scene (required)
#   --engine  liggghts (default) or bullet
#   --rate    the pull's growth, weights per second (default 0.5)
#   --max     the largest pull, weights (default 3)
#   --angle   deg from the face's outward normal toward down the face (default 0)
#   --jobs    rounds run side by side (default 2)
#   --rounds  run at most this many rounds (default: every round; a sample of the layer's units)
#   --sets    further scene overrides for every round, space-separated (e.g. 'material.0.friction=0.3')
#   --out     default ${TMPDIR:-/tmp}/armour-bench/pull_test
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=pull_test bench_targets=armour bench_options="scene engine rate max angle jobs rounds sets"
source "$root/bench/common.sh"
bench_args "$@"
[ -n "${opt_scene:-}" ] || bench_fail "--scene: required (a settled scene, RUN/settle/scene.settled.toml)"
[ -f "$opt_scene" ] || bench_fail "--scene $opt_scene: no such file"
engine="${opt_engine:-liggghts}" rate="${opt_rate:-0.5}" max="${opt_max:-3}" angle="${opt_angle:-0}"
jobs="${opt_jobs:-2}" rounds="${opt_rounds:-1000000}"
sets=()
read -ra kvs <<<"${opt_sets:-}"
for kv in "${kvs[@]}"; do sets+=(--set "$kv"); done
# A folder resumed must hold a test with the same options (its rounds are kept as they are).
# (`pull=seated`: the analysis that waits for each unit's seat; folders from before it are refused.)
settings="pull=seated scene=$(cd "$(dirname "$opt_scene")" && pwd)/$(basename "$opt_scene") engine=$engine rate=$rate max=$max angle=$angle sets=${opt_sets:-}"
if [ -f "$out/settings.txt" ] && [ "$(cat "$out/settings.txt")" != "$settings" ]; then
  bench_fail "--out $out holds a pull test with other options ($(cat "$out/settings.txt")): use a new --out"
fi
echo "$settings" >"$out/settings.txt"
armour="$build/apps/armour"

# The dry scene: every table the fluid needs is dropped, the rest kept as written.
/usr/bin/python3 "$root/studies/dry_scene.py" "$opt_scene" "$out/dry.toml" >/dev/null ||
  bench_fail "--scene $opt_scene: cannot make its dry scene"
# Each unit's pull waits for its seat (up to twice 5 (Dn/g)^1/2: 0.64 s for 4 cm cubes), rises to
# --max and holds it a second; the analysis ends the run there, so the spare 5 s cost nothing.
duration="$(awk -v m="$max" -v r="$rate" 'BEGIN { print m / r + 6 }')"

run_round() {
  # A round that finished before (its summary written) is kept: the script resumes a stopped test.
  [ ! -f "$out/round_$1/summary.json" ] || return 0
  "$armour" run "$out/dry.toml" --out "$out/round_$1" --engine "$engine" --set analysis.kind=pull \
    --set "analysis.pull_rate=$rate" --set "analysis.pull_max=$max" --set "analysis.pull_angle=$angle" \
    --set "analysis.pull_round=$1" --set "run.duration=$duration" --set run.output_interval=0.01 \
    --set run.checkpoint_interval=0 "${sets[@]}" \
    >"$out/round_$1.log" 2>&1 || bench_fail "round $1 failed: $out/round_$1.log"
}
round=0
while :; do
  pids=()
  for ((k = round; k < round + jobs && k < rounds; ++k)); do
    run_round "$k" &
    pids+=($!)
  done
  for p in "${pids[@]}"; do wait "$p" || exit 2; done
  last=$((round + jobs - 1))
  [ $((round + jobs)) -lt "$rounds" ] || break
  units="$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["pull_units"])' \
    "$out/round_$last/summary.json")"
  [ "$units" -gt 0 ] || break
  round=$((round + jobs))
done

/usr/bin/python3 - "$out" "$engine" "$rate" "$max" "$angle" "${opt_sets:-}" <<'PY'
import csv, glob, json, os, re, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from armour_results import write_rows
out, engine, rate, pull_max, angle = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
rows, first, wall = [], None, 0.0
for d in sorted(glob.glob(f"{out}/round_*/"), key=lambda p: int(re.search(r"round_(\d+)", p).group(1))):
    k = int(re.search(r"round_(\d+)", d).group(1))
    if not os.path.exists(os.path.join(d, "summary.json")):
        continue  # a round stopped before its end: rerun the script to finish it
    s = json.load(open(os.path.join(d, "summary.json")))
    first = first or s
    wall += s["wall_seconds"]
    with open(os.path.join(d, "pull.csv")) as f:
        for r in csv.DictReader(line for line in f if not line.startswith("#")):
            rows.append({"round": k, **r})
unseated = [r for r in rows if r.get("unseated") == "1"]
rows = [r for r in rows if r.get("unseated") != "1"]
if not rows and unseated:
    sys.exit(f"run_pull_test: {out}: every unit taken ({len(unseated)}) was moved by the dry start before the pull: is the scene a settled layer?")
if not rows:
    sys.exit(f"run_pull_test: {out}: no unit was pulled (no outer units on the slope's face?)")
held = sorted(float(r["resistance_weights"]) if r["resistance_weights"] else pull_max for r in rows)
q = lambda p: held[int(p * (len(held) - 1) + 0.5)] if held else None
write_rows(f"{out}/pull.csv", rows + unseated,
           "pull test: forces in the unit's own weight m|g| (-); s, y, n: on the slope face in Dn (-)")
summary = {"command": "bench/run_pull_test.sh", "engine": engine, "sets": sys.argv[6].split(), "pull_rate": rate, "pull_max": pull_max,
           "pull_angle_deg": angle, "units": len(rows), "rounds": len({r["round"] for r in rows + unseated}),
           "stayed": sum(1 for r in rows if r["stayed"] == "1"), "unseated": len(unseated),
           "resistance_median": q(0.5), "resistance_quartiles": [q(0.25), q(0.75)],
           "resistance_range": [held[0], held[-1]],
           "lone_unit_lift": first["pull_lone_unit_lift"], "lone_unit_slide": first["pull_lone_unit_slide"],
           "friction": first["pull_friction"], "wall_seconds_summed_over_rounds": wall,
           "si_units": {"forces": "unit weights m|g| (-)", "pull_rate": "1/s", "pull_angle_deg": "deg",
                        "wall_seconds_summed_over_rounds": "s", "positions": "Dn (-)"}}
json.dump(summary, open(f"{out}/summary.json", "w"), indent=2)
fig, ax = plt.subplots(figsize=(6.5, 4))
s = [float(r["s_over_Dn"]) for r in rows]
ax.scatter(s, [float(r["resistance_weights"]) if r["resistance_weights"] else pull_max for r in rows],
           c=["tab:red" if r["stayed"] == "1" else "tab:blue" for r in rows], s=18)
if first["pull_lone_unit_lift"] is not None:
    ax.axhline(first["pull_lone_unit_lift"], color="k", lw=0.8, ls="--", label="a unit held against sliding lifts off")
ax.axhline(pull_max, color="tab:red", lw=0.6, ls=":", label="the largest pull (red: held it)")
ax.set_xlabel("s: up the face from its toe [Dn]")
ax.set_ylabel("pull held [unit weights m|g|]")
ax.set_title(f"pull-out test, {engine}: {len(rows)} outer units, median {q(0.5):.2f}", fontsize=10)
ax.legend(fontsize=8)
ax.grid(True, lw=0.3)
fig.tight_layout()
fig.savefig(f"{out}/pull.png", dpi=110)
print(json.dumps({k: summary[k] for k in ("units", "stayed", "unseated", "resistance_median", "resistance_quartiles")}))
PY
