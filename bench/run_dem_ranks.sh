#!/usr/bin/env bash
# One DEM split over the ranks against one DEM per rank: in a parallel coupled
# run every rank advances its own serial LIGGGHTS replica of the whole layer
# (engines/liggghts_engine.cpp), so the DEM's time does not shrink with the
# ranks. Would LIGGGHTS' own domain decomposition, one run over 2 ranks, take
# less wall time a step? The stability scene's 99 cubes (118-sphere clumps)
# are settled once by `armour run` (as bench/run_dem_skin.sh); the LIGGGHTS
# set-up the adapter wrote for the loose pile (units moving, as in waves) and
# for a dry hold of the settled layer (at rest) are replayed by the bare
# `liggghts` executable under gravity for the same steps: on 1 rank, and on 2
# ranks with the box cut across the flume's width (y = 0: half the layer's
# five units across on each rank) and across its height (z = 0.31 m). LIGGGHTS
# 3.8 has no load balancing and its box spans the flume, so a cut along x
# (at x = 1.0 m) would leave every unit on one rank. Reports LIGGGHTS' loop
# time (s) and its pair / neigh / comm / other parts, the atoms per rank, and each
# row's speed-up over 1 rank. Writes OUT/summary.json (SI: s) and prints a
# table. Needs 2 free cores: timings on a busy machine measure the machine.
# ~6 min on two cores (the settle), the replays ~1 min.
# Usage: bash bench/run_dem_ranks.sh [--build DIR] [--out DIR] [--steps N]
#   --build   default the repo's build/ (bash scripts/build.sh armour)
#   --out     default ${TMPDIR:-/tmp}/armour-bench/dem_ranks
#   --steps   DEM steps per replay, default 4000 (0.15 s)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=dem_ranks bench_targets=armour bench_options="steps"
source "$root/bench/common.sh"
bench_args "$@"
steps="${opt_steps:-4000}"
command -v liggghts >/dev/null || bench_fail "needs the liggghts executable (Debian package liggghts)"
command -v mpirun >/dev/null || bench_fail "needs mpirun (Debian package openmpi-bin)"
[ "$(nproc)" -ge 2 ] || bench_fail "needs 2 cores; this machine has $(nproc)"

bench_settled_layer_dry
bench_held_layer_input

# The adapter's box with the processor grid left to the command line.
sed 's/^processors .*/processors      ${px} ${py} ${pz}/' "$root/liggghts_inputs/domain.in" >"$out/domain_ranks.in"
rows=()
for phase in moving rest; do
  case $phase in
    moving) input="$layer/settle/liggghts/input.liggghts" ;;
    rest) input="$held_input" ;;
  esac
  sed "s#^include .*/domain.in\$#include $out/domain_ranks.in#" "$input" >"$out/$phase.in"
  grep -q "domain_ranks.in" "$out/$phase.in" || bench_fail "$input: no domain.in include to replace"
  printf 'fix grav all gravity 9.81 vector 0.0 0.0 -1.0\nrun %s\n' "$steps" >>"$out/$phase.in"
  for grid in "1 1 1" "1 2 1" "1 1 2"; do
    read -r px py pz <<<"$grid"
    ranks=$((px * py * pz))
    name="$phase-$px$py$pz"
    launch=()
    [ "$ranks" -eq 1 ] || launch=(mpirun --allow-run-as-root -np "$ranks")
    "${launch[@]}" liggghts -var px "$px" -var py "$py" -var pz "$pz" -in "$out/$phase.in" \
      -log "$out/$name.log" -screen /dev/null >"$out/$name.out" 2>&1 ||
      bench_fail "liggghts on $ranks rank(s) failed: $out/$name.log"
    rows+=("$phase $px $py $pz $out/$name.log")
  done
done

printf '%s\n' "${rows[@]}" | /usr/bin/python3 -c '
import json, re, sys
out, steps = sys.argv[1], int(sys.argv[2])
rows = []
for line in sys.stdin:
    phase, px, py, pz, log = line.split()
    text = open(log).read()
    part = lambda name: float(re.findall(name + r"\s+time \(%\) = ([0-9.eE+-]+)", text)[-1])
    nlocal = re.findall(r"Nlocal:\s+([0-9.eE+-]+) ave ([0-9.eE+-]+) max", text)[-1]
    rows.append({"phase": phase, "grid": [int(px), int(py), int(pz)], "ranks": int(px) * int(py) * int(pz),
                 "loop_seconds": float(re.findall(r"Loop time of ([0-9.eE+-]+)", text)[-1]),
                 "pair_seconds": part("Pair"), "neigh_seconds": part("Neigh"), "comm_seconds": part("Comm"), "other_seconds": part("Other"),
                 "atoms_per_rank_max": float(nlocal[1]), "atoms_per_rank_mean": float(nlocal[0]), "steps": steps})
print("%-7s %6s %10s %9s %9s %9s %9s %15s %s" % ("phase", "grid", "loop [s]", "pair [s]", "neigh [s]", "comm [s]", "other [s]",
                                             "atoms/rank max", "speed-up over 1 rank"))
for r in rows:
    serial = next(q for q in rows if q["phase"] == r["phase"] and q["ranks"] == 1)
    r["speedup_over_one_rank"] = serial["loop_seconds"] / r["loop_seconds"]
    print("%-7s %6s %10.2f %9.2f %9.2f %9.2f %9.2f %15d %.2f" % (r["phase"], "x".join(map(str, r["grid"])),
          r["loop_seconds"], r["pair_seconds"], r["neigh_seconds"], r["comm_seconds"], r["other_seconds"], r["atoms_per_rank_max"],
          r["speedup_over_one_rank"]))
doc = {"units": {"loop_seconds": "s (LIGGGHTS loop time, wall)", "pair_seconds": "s", "neigh_seconds": "s", "comm_seconds": "s",
                 "other_seconds": "s (fixes: the multisphere integration, the walls)"},
       "phases": {"moving": "the loose pile before the settle, falling under gravity",
                  "rest": "the settled layer held dry"},
       "grids": "LIGGGHTS processors px x py x pz; 1x2x1 cuts the box at y = 0, 1x1x2 at mid-height",
       "best_speedup_over_one_rank": {p: max(r["speedup_over_one_rank"] for r in rows if r["phase"] == p)
                                      for p in ("moving", "rest")},
       "rows": rows}
json.dump(doc, open(out + "/summary.json", "w"), indent=2)
' "$out" "$steps"
