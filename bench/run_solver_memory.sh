#!/usr/bin/env bash
# What keeping interFoam's freed memory in the heap saves (docs/openfoam.md,
# "The solver's memory"). A window of a coupled run is resumed from one of its
# checkpoints through `armour run --resume`, on copies of the run folder, in
# rows that alternate: glibc's defaults (ARMOUR_SOLVER_MALLOC=glibc) and
# armour's setting (MALLOC_MMAP_THRESHOLD_ and MALLOC_TRIM_THRESHOLD_ 4 GiB),
# --repeats times each, one after another in one call: compare their ratio.
# Per row: fluid steps and CPU seconds per step (interFoam's ExecutionTime
# from its 5th step on: the restart's reading and reconstructPar left out).
# The records of the two settings must be identical (the allocator does not
# change a number): checked on every unit's final pose. Writes
# OUT/summary.json (SI) and OUT/rows.csv.
# Usage: bash bench/run_solver_memory.sh RUN_DIR [--checkpoint T] [--seconds S]
#          [--np N] [--repeats R] [--build DIR] [--out DIR]
#   RUN_DIR      an `armour run` output folder with checkpoints
#   --checkpoint the checkpoint's time in s, as its folder is named (default the latest)
#   --seconds    simulated seconds of each row (default 0.25)
#   --np         ranks of every row (default 1)
#   --repeats    rows per setting (default 2)
#   --out        default ${TMPDIR:-/tmp}/armour-bench/solver_memory
# Example (the stability scene's Dn/4 run, docs/stability.md):
#   bash bench/run_solver_memory.sh /work/runs/dn4_long --seconds 0.25 --np 1
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=solver_memory bench_targets="armour armourFoamCoupling armourWaves"
bench_options="checkpoint seconds np repeats"
opt_checkpoint="" opt_seconds=0.25 opt_np=1 opt_repeats=2
source "$root/bench/common.sh"
bench_window_args "$@"

# row NAME SETTING: the run resumed to $end with SETTING (glibc or heap).
row() {
  echo "solver_memory: $1 ($2) from t = $opt_checkpoint s to $end s on $opt_np rank(s) ..." >&2
  (
    unset MALLOC_MMAP_THRESHOLD_ MALLOC_TRIM_THRESHOLD_ ARMOUR_SOLVER_MALLOC
    if [ "$2" = glibc ]; then export ARMOUR_SOLVER_MALLOC=glibc; fi
    bench_resume_window "$run_dir" "$opt_checkpoint" "$end" "$out/$1" --np "$opt_np"
  ) || bench_fail "$1: armour run failed: $out/$1.log"
}

cut -d' ' -f1-3 /proc/loadavg >"$out/loadavg_before"
rows=()
for i in $(seq 1 "$opt_repeats"); do
  row "glibc_$i" glibc
  row "heap_$i" heap
  rows+=("glibc_$i" "heap_$i")
done
cut -d' ' -f1-3 /proc/loadavg >"$out/loadavg_after"

/usr/bin/python3 - "$out" "$opt_checkpoint" "$end" "$opt_np" "${rows[@]}" <<'EOF'
import json, os, re, sys
import h5py
import numpy as np

out, start, end, np_ranks, rows = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]), sys.argv[5:]
figures, poses = {}, {}
for name in rows:
    log = open(os.path.join(out, name, "case", "log.interFoam")).read()
    cpu = [float(x) for x in re.findall(r"^ExecutionTime = (\S+) s", log, re.M)]
    if len(cpu) < 10:
        sys.exit(f"run_solver_memory.sh: {name}: only {len(cpu)} steps; lengthen --seconds")
    figures[name] = {"steps": len(cpu), "cpu_seconds_per_step": (cpu[-1] - cpu[4]) / (len(cpu) - 5)}
    with h5py.File(os.path.join(out, name, "bodies.h5"), "r") as f:
        poses[name] = np.concatenate([f["bodies"][k][-1].ravel() for k in ("position", "orientation")])
glibc = [figures[r]["cpu_seconds_per_step"] for r in rows if r.startswith("glibc")]
heap = [figures[r]["cpu_seconds_per_step"] for r in rows if r.startswith("heap")]
pairs = [h / g for g, h in zip(glibc, heap)]
reference = poses[rows[0]]
largest = max(float(np.max(np.abs(p - reference))) for p in poses.values())
with open(os.path.join(out, "rows.csv"), "w") as f:
    f.write("row,steps,cpu_seconds_per_step\n")
    for r in rows:
        f.write(f"{r},{figures[r]['steps']},{figures[r]['cpu_seconds_per_step']:.5f}\n")
summary = {
    "window_start_s": start, "window_end_s": end, "ranks": np_ranks,
    "glibc_cpu_seconds_per_step": glibc, "heap_cpu_seconds_per_step": heap,
    "heap_over_glibc": pairs, "heap_over_glibc_mean": float(np.mean(pairs)),
    "largest_pose_difference_between_rows": largest,
    "loadavg_before": open(os.path.join(out, "loadavg_before")).read().strip(),
    "loadavg_after": open(os.path.join(out, "loadavg_after")).read().strip(),
}
tmp = os.path.join(out, "summary.json.tmp")
with open(tmp, "w") as f:
    json.dump(summary, f, indent=2)
os.replace(tmp, os.path.join(out, "summary.json"))
for r in rows:
    print(f"{r:10s} {figures[r]['steps']:5d} steps, {figures[r]['cpu_seconds_per_step']:.4f} CPU s per step")
print(f"heap / glibc per pair: {', '.join(f'{p:.3f}' for p in pairs)} (mean {np.mean(pairs):.3f}); "
      f"final poses of the rows differ by up to {largest:.3g} (m, quaternion)")
if largest > 0.0:
    sys.exit("run_solver_memory.sh: the rows' records differ: the allocator changed a number")
EOF
for r in "${rows[@]}"; do rm -rf "${out:?}/$r" "$out/$r.scene.toml"; done
