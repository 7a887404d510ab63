#!/usr/bin/env bash
# Slide angle (friction 0.5 and 0.3) and topple angle (friction 1.2) of the
# shipped tilt scene against the tilt rate, for exact hulls (Bullet) and the
# scene's 20-sphere clump (LIGGGHTS), with atan(mu) and 45 deg as references.
# Output samples every 0.25 deg of tilt at every rate. Writes OUT/summary.json
# (angles in deg, rates in deg/s), OUT/tilt_rate.png and the runs; nothing in
# the source tree.
# Usage: bash bench/run_tilt_rate.sh [--build DIR] [--out DIR]
#   --build  default the repo's build/ (bash scripts/build.sh armour)
#   --out    default ${TMPDIR:-/tmp}/armour-bench/tilt_rate
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=tilt_rate bench_targets=armour bench_options=""
source "$root/bench/common.sh"
bench_args "$@"
armour="$build/apps/armour"
rates="2.5 5 10 20"
for engine in bullet liggghts; do
  for mu in 0.3 0.5 1.2; do
    for rate in $rates; do
      run="$out/runs/${engine}_mu${mu}_rate${rate}"
      rm -rf "$run"
      "$armour" run "$root/scenes/tilt_cube.toml" --out "$run" --set "run.engine=\"$engine\"" \
        --set "material.0.friction=$mu" --set "analysis.tilt_rate=$rate" \
        --set "run.duration=$(awk "BEGIN { print 60.0 / $rate }")" \
        --set "run.output_interval=$(awk "BEGIN { print 0.25 / $rate }")" 2>/dev/null
    done
  done
done
/usr/bin/python3 - "$out" "$rates" <<'PY'
import json, math, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from armour_results import read_summary
out, rates = sys.argv[1], [float(r) for r in sys.argv[2].split()]
rows = []
fig, (slide, topple) = plt.subplots(1, 2, figsize=(11, 4.3))
for engine, colour in (("bullet", "black"), ("liggghts", "tab:blue")):
    for mu, marker in ((0.3, "v"), (0.5, "o"), (1.2, "s")):
        xs, ys = [], []
        for rate in rates:
            s = read_summary(f"{out}/runs/{engine}_mu{mu}_rate{rate:g}")
            key = "topple_angle_deg" if mu > 1 else "slide_angle_deg"
            rows.append({"engine": engine, "mu": mu, "tilt_rate": rate, "slide_angle_deg": s["slide_angle_deg"],
                         "topple_angle_deg": s["topple_angle_deg"]})
            print(f"{engine:8s} mu {mu:3.1f} rate {rate:4.1f} deg/s: slide {s['slide_angle_deg']} "
                  f"topple {s['topple_angle_deg']} deg")
            if s[key] is not None:
                xs.append(rate)
                ys.append(s[key] - (45.0 if mu > 1 else math.degrees(math.atan(mu))))
        ax = topple if mu > 1 else slide
        ax.plot(xs, ys, marker + "-", color=colour, label=f"{engine}, mu {mu:g}")
for ax, what, tol in ((slide, "slide angle - atan(mu)", 0.5), (topple, "topple angle - 45", 1.0)):
    ax.axhspan(-tol, tol, color="tab:green", alpha=0.12, label=f"±{tol:g} deg")
    ax.set_xscale("log")
    ax.set_xlabel("tilt rate [deg/s]")
    ax.set_ylabel(f"{what} [deg]")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
fig.suptitle("scenes/tilt_cube.toml: exact hulls and the 20-sphere clump against the tilt rate", fontsize=10)
fig.tight_layout()
fig.savefig(f"{out}/tilt_rate.png", dpi=110)
json.dump({"units": "angles deg, tilt_rate deg/s", "rows": rows}, open(f"{out}/summary.json", "w"), indent=2)
PY
