#!/usr/bin/env bash
# Density-ratio stability of the coupling from real coupled runs:
# scenes/released_cube.toml (a cube released from rest in still water,
# free_body, heave only, 16 x 16 x 18 cells) for rho_unit/rho_water in RATIOS,
# with plain explicit coupling (fluid.added_mass = 0) and the stabilised
# scheme (fluid.added_mass = CA, default 0.5). A run fails when the solver
# stops (exit status, no summary), a value is NaN, the cube leaves the mesh
# box, or its acceleration carries a step-to-step oscillation that grows
# (largest |a_{n+1} - 2 a_n + a_{n-1}| / 4 of the last third above 3 x that of
# the first third and above 0.2 g; a light cube reaching the surface wobbles
# less), judged while the cube is still one cell below the surface (breaching
# it shakes a light cube without any instability). A run that passes but
# keeps a sawtooth above 0.2 g is "marginal". Writes OUT/density_ratio.png
# and OUT/summary.json, nothing in the source tree (docs/images figures are
# copied there by hand).
# ANALYSE_ONLY=1 re-reads the runs already in OUT.
# Usage: bash bench/run_density_ratio.sh [--build DIR] [--out DIR] [--added-mass CA]
#   --build       default the repo's build/ (bash scripts/build.sh armour armourFoamCoupling)
#   --out         default ${TMPDIR:-/tmp}/armour-bench/density_ratio
#   --added-mass  C_a of the stabilised runs, default 0.5
#   RATIOS="0.1 0.2 ..." overrides the ratios.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=density_ratio bench_targets="armour armourFoamCoupling" bench_options="added-mass"
source "$root/bench/common.sh"
bench_args "$@"
ca="${opt_added_mass:-0.5}"
ratios="${RATIOS:-0.1 0.2 0.3 0.5 0.8 1.2 2.0}"
armour="$build/apps/armour"
for r in $ratios; do
  [ -n "${ANALYSE_ONLY:-}" ] && break
  for c in 0 "$ca"; do
    d="$out/r${r}_ca${c}"
    rho=$(/usr/bin/python3 -c "print(1000.0 * $r)")
    status=0
    "$armour" run "$root/scenes/released_cube.toml" --out "$d" --set "unit.0.density=$rho" \
      --set "fluid.added_mass=$c" >"$out/r${r}_ca${c}.log" 2>&1 || status=$?
    echo "$status" >"$d.exit_status" # beside the run: its folder holds armour's files only
    echo "ratio $r C_a $c: exit $status"
  done
done
/usr/bin/python3 - "$out" "$ca" "$ratios" <<'PY'
import json, math, os, sys
from armour_results import read_bodies
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

out, ca, ratios = sys.argv[1], sys.argv[2], [float(r) for r in sys.argv[3].split()]
g, z_floor, z_top, z_water, half = 9.81, 0.0, 0.9, 0.7, 0.1
rows = []
for r in ratios:
    for c in ("0", ca):
        d = f"{out}/r{r:g}_ca{c}"
        if not os.path.isdir(d):
            d = f"{out}/r{[s for s in sys.argv[3].split() if float(s) == r][0]}_ca{c}"
        row = {"ratio": r, "added_mass": float(c), "exit_status": int(open(f"{d}.exit_status").read())}
        why = []
        if row["exit_status"] != 0 or not os.path.exists(f"{d}/summary.json"):
            why.append("solver stopped (exit %d)" % row["exit_status"])
        if os.path.exists(f"{d}/bodies.h5"):
            b = read_bodies(d)
            t, z, v = b.time, b.position[:, 0, 2], b.velocity[:, 0, 2]
            if not (np.all(np.isfinite(z)) and np.all(np.isfinite(v))):
                why.append("NaN")
            ok = np.isfinite(z) & np.isfinite(v)
            t, z, v = t[ok], z[ok], v[ok]
            if len(t) > 1 and (z.max() + half > z_top or z.min() - half < z_floor):
                why.append("left the mesh")
            sub = np.nonzero(z + half > z_water - 0.05)[0]  # first record within a cell of the surface
            m = sub[0] if len(sub) else len(t)
            if len(t) > 6 and m > 6:
                a = np.diff(v[:m]) / np.diff(t[:m])
                osc = np.abs(a[2:] - 2 * a[1:-1] + a[:-2]) / 4
                n = len(osc) // 3
                first, last = osc[:n].max(), osc[-n:].max()
                row.update(oscillation_first_third=float(first), oscillation_last_third=float(last),
                           max_abs_acceleration=float(np.abs(a).max()), records=int(len(t)),
                           z_change=float(z[-1] - z[0]))
                if last > 3 * first and last > 0.2 * g:
                    why.append("growing oscillation")
                row["marginal"] = bool(not why and last > 0.2 * g)
        else:
            why.append("no record")
        row["stable"] = not why
        row["failure"] = ", ".join(why)
        rows.append(row)
        state = ("marginal (sawtooth %.2g m/s^2, not growing)" % row["oscillation_last_third"]
                 if row.get("marginal") else "stable")
        print(f"ratio {r:4g}  C_a {c:>4s}: {state if not why else 'FAILED: ' + row['failure']}")

def boundary(c):
    un = [x["ratio"] for x in rows if x["added_mass"] == float(c) and not x["stable"]]
    st = [x["ratio"] for x in rows if x["added_mass"] == float(c) and x["stable"]]
    return {"largest_failing_ratio": max(un) if un else None,
            "smallest_stable_ratio_above_it": min([s for s in st if not un or s > max(un)], default=None)}
summary = {"scene": "scenes/released_cube.toml", "ratios": ratios, "stabilised_added_mass": float(ca),
           "criterion": "exit status / NaN / leaves the mesh / step-to-step oscillation growing 3x and above 0.2 g",
           "runs": rows, "measured_boundary": {"plain": boundary("0"), "stabilised": boundary(ca)},
           # docs/coupling.md, AddedMass.FailureBoundaryTable (run_added_mass_problem, C_a,true = 0.5)
           "model_problem_boundary_plain": 0.5}
json.dump(summary, open(f"{out}/summary.json", "w"), indent=2)

fig, ax = plt.subplots(figsize=(8, 3.2))
for y, c, label in ((1, "0", "plain explicit (C_a = 0)"), (0, ca, f"stabilised (C_a = {ca})")):
    for x in rows:
        if x["added_mass"] == float(c):
            ax.plot(x["ratio"], y, "o" if x["stable"] else "x", ms=10,
                    color=("tab:orange" if x.get("marginal") else "tab:green") if x["stable"] else "tab:red")
ax.axvline(0.5, color="k", ls="--", lw=1)
ax.text(0.51, 0.5, "model problem boundary\n(run_added_mass_problem,\nC_a,true = 0.5)", fontsize=8, va="center")
ax.set_xscale("log")
ax.set_xticks(ratios)
ax.set_xticklabels([f"{r:g}" for r in ratios])
ax.set_yticks([0, 1])
ax.set_yticklabels([f"C_a = {ca}", "C_a = 0"])
ax.set_ylim(-0.5, 1.5)
ax.set_xlabel("rho_unit / rho_water")
ax.set_title("released cube, coupled interFoam runs: o stable (orange: marginal), x failed")
fig.tight_layout()
fig.savefig(f"{out}/density_ratio.png", dpi=110)
print(json.dumps(summary["measured_boundary"]))
PY
