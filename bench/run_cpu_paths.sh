#!/usr/bin/env bash
# Why one command gives other counts on another machine: the C library's
# maths (exp, log, pow, sin, ...) picks its code by the processor's features,
# and its FMA code rounds some results to another last bit than its plain
# x86-64 code. The stability scene CI-sized (45 cubes of light concrete, so
# that units move once the waves reach them, 8 s of irregular waves) runs
# three times from the same build: twice as this processor is, once with
# AVX2 and FMA hidden from the C library (GLIBC_TUNABLES, glibc >= 2.33),
# as on a processor without them. Compares every record's poses with the
# first run's: when the runs first differ and how far apart they grow, in Dn.
# Writes OUT/summary.json (SI: s, m; differences also in Dn) and prints a
# table. ~10 min on 2 idle cores.
# Usage: bash bench/run_cpu_paths.sh [--build DIR] [--out DIR] [--duration S] [--density KG_M3]
#   --build     default the repo's build/ (bash scripts/build.sh armour)
#   --out       default ${TMPDIR:-/tmp}/armour-bench/cpu_paths
#   --duration  s of coupled time, default 8 (the waves reach the layer at ~4 s)
#   --density   kg/m^3 of the cubes, default 1300 (Delta 0.3: they move in the first waves)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=cpu_paths bench_targets=armour bench_options="duration density"
source "$root/bench/common.sh"
bench_args "$@"
duration="${opt_duration:-8}"
density="${opt_density:-1300}"
grep -qw fma /proc/cpuinfo || echo "run_cpu_paths: this processor has no FMA: the three runs should be one" >&2

scene_args=(--set pattern.0.rows=5 --set fluid.settle_stages=1 --set 'fluid.cells=[50,6,16]' --set fluid.penalty=200
  --set "run.duration=$duration" --set "unit.0.density=$density")
for name in as_is again no_fma; do
  rm -rf "${out:?}/$name"
  if [ $name = no_fma ]; then
    GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA "$build/apps/armour" run "$root/scenes/stability_cubes.toml" \
      --out "$out/$name" "${scene_args[@]}" >"$out/$name.log" 2>&1
  else
    "$build/apps/armour" run "$root/scenes/stability_cubes.toml" --out "$out/$name" "${scene_args[@]}" \
      >"$out/$name.log" 2>&1
  fi
done

/usr/bin/python3 - "$out" "$duration" "$density" <<'EOF'
import json, os, sys
import numpy as np
from armour_results import read_bodies, read_summary

out, duration, density = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
runs = {name: read_bodies(os.path.join(out, name)) for name in ("as_is", "again", "no_fma")}
dn = read_summary(os.path.join(out, "as_is"))["damage"]["Dn"]
ref = runs["as_is"]
rows = []
print("%-8s %18s %14s %14s %14s %10s" % ("run", "first differs at", "at 3.5 s [Dn]", "at 6 s [Dn]", "at end [Dn]",
                                         "displaced"))
for name in ("again", "no_fma"):
    b = runs[name]
    n = min(len(ref.time), len(b.time))
    gap = np.max(np.abs(b.position[:n] - ref.position[:n]), axis=(1, 2))
    first = float(ref.time[int(np.argmax(gap > 0))]) if (gap > 0).any() else None
    at = lambda t: float(gap[int(np.argmin(np.abs(ref.time[:n] - t)))] / dn)
    displaced = read_summary(os.path.join(out, name))["units_displaced"]
    rows.append({"run": name, "first_differing_record_time": first,
                 "largest_position_difference": {"3.5": at(3.5), "6": at(6.0), "end": float(gap[n - 1] / dn)},
                 "largest_position_difference_end_m": float(gap[n - 1]), "displaced": displaced})
    print("%-8s %18s %14.3g %14.3g %14.3g %10d" % (name, "never" if first is None else "%.2f s" % first,
          at(3.5), at(6.0), gap[n - 1] / dn, displaced))
doc = {"units": {"time": "s", "largest_position_difference": "Dn (each record's largest unit-centre "
                 "difference from the first run's)", "largest_position_difference_end_m": "m",
                 "duration": "s", "density": "kg/m^3", "Dn": "m"},
       "scene": "scenes/stability_cubes.toml, 5 rows (45 cubes) settled at once, cells [50, 6, 16]",
       "duration": duration, "density": density, "Dn": dn,
       "processor_has_fma": "fma" in open("/proc/cpuinfo").read().split(),
       "displaced_as_is": read_summary(os.path.join(out, "as_is"))["units_displaced"],
       "rows": rows}
json.dump(doc, open(os.path.join(out, "summary.json"), "w"), indent=2)
EOF
