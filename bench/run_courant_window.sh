#!/usr/bin/env bash
# Which cells set the fluid step in waves on the armour, and what a separate
# free-surface limit saves (issue 16; docs/stability.md, Cost). A window of
# a coupled run is run twice from one of its checkpoints through `armour run
# --resume`, on copies of its folder: as the run ran (its maxCo and
# maxAlphaCo), and with every cell held to --max-courant but the free
# surface's cells (0.01 < alpha < 0.99) to --max-interface-courant
# (fluid.max_courant and fluid.max_interface_courant). Reported per row:
# fluid steps, CPU seconds (interFoam's ExecutionTime), the share of steps
# whose largest Courant number lies off the free surface (interface Courant
# < 0.9 x the largest); between the rows: the units' fluid loads at the
# records of the window (rms of the difference / rms of the load, largest
# difference in unit weights) and their poses at its end (largest difference
# in Dn; for units other than cubes, N and m). The second row may also change
# the pressure solver (p_rgh's GAMG tolerance, absolute, and relTol of its
# non-final correctors; the final's tolerance follows) and PIMPLE's momentum
# predictor (fluid.pressure_tolerance, pressure_relative_tolerance and
# momentum_predictor, which a resume may not change), and the free surface's
# advection: interIsoFoam's geometric isoAdvector (stock in v1912; no scene
# key holds it) instead of interFoam's MULES, with the isoAdvector settings
# of OpenFOAM's own wave tutorial. The rows run one after
# another in one call: compare their ratios. Writes OUT/summary.json (SI) and
# keeps each row's solver log (OUT/ROW.log.interFoam).
# Usage: bash bench/run_courant_window.sh RUN_DIR [--checkpoint T] [--seconds S]
#          [--max-courant C] [--max-interface-courant C] [--pressure-tolerance T]
#          [--pressure-rel-tol R] [--pressure-smoother S] [--pressure-coarsest N]
#          [--pressure-merge-levels L] [--momentum-predictor yes|no]
#          [--advection MULES|isoAdvector] [--np N] [--build DIR] [--out DIR]
#   RUN_DIR      an `armour run` output folder with checkpoints (serial or parallel)
#   --checkpoint the checkpoint's time in s, as its folder is named (default the latest)
#   --seconds    simulated seconds of the window (default 2)
#   --max-courant, --max-interface-courant  the second row's limits (default 1.0 and 0.5)
#   --pressure-tolerance, --pressure-rel-tol  the second row's p_rgh tolerance
#                and relTol (default: as the run's case has them; the template's
#                1e-7 and 0.01)
#   --pressure-smoother  the second row's p_rgh GAMG smoother (the templates' DIC;
#                GaussSeidel, symGaussSeidel, DICGaussSeidel, FDIC)
#   --pressure-coarsest  the second row's GAMG nCellsInCoarsestLevel (OpenFOAM's 10)
#   --pressure-merge-levels  the second row's GAMG mergeLevels (OpenFOAM's 1)
#   --momentum-predictor  the second row's PIMPLE momentumPredictor (default: as the run's)
#   --advection  the second row's free-surface advection (default MULES, the run's)
#   --np         ranks of both rows (default the checkpoint's)
#   --out        default ${TMPDIR:-/tmp}/armour-bench/courant_window
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=courant_window bench_targets="armour armourFoamCoupling armourWaves"
bench_options="checkpoint seconds max-courant max-interface-courant pressure-tolerance pressure-rel-tol
  pressure-smoother pressure-coarsest pressure-merge-levels momentum-predictor advection np"
opt_checkpoint="" opt_seconds=2 opt_max_courant=1.0 opt_max_interface_courant=0.5 opt_np=""
opt_pressure_tolerance="" opt_pressure_rel_tol="" opt_momentum_predictor="" opt_advection=MULES
opt_pressure_smoother="" opt_pressure_coarsest="" opt_pressure_merge_levels=""
# Every option checked before --out is made and the first row runs (bench_args
# calls this): OpenFOAM aborts on a name it does not know, after a row's minutes.
bench_check_options() {
  case "$opt_momentum_predictor" in "" | yes | no) ;; *) bench_fail "--momentum-predictor: yes or no (got $opt_momentum_predictor)" ;; esac
  case "$opt_advection" in
    MULES) ;;
    isoAdvector) command -v interIsoFoam >/dev/null || bench_fail "--advection isoAdvector: interIsoFoam not found (OpenFOAM v1912)" ;;
    *) bench_fail "--advection: MULES or isoAdvector (got $opt_advection)" ;;
  esac
  case "$opt_pressure_smoother" in
    "" | DIC | GaussSeidel | symGaussSeidel | DICGaussSeidel | FDIC) ;;
    *) bench_fail "--pressure-smoother: DIC, GaussSeidel, symGaussSeidel, DICGaussSeidel or FDIC (got $opt_pressure_smoother)" ;;
  esac
  for level in "coarsest:$opt_pressure_coarsest" "merge-levels:$opt_pressure_merge_levels"; do
    [[ "${level#*:}" =~ ^([1-9][0-9]*)?$ ]] || bench_fail "--pressure-${level%%:*}: a whole number >= 1 (got ${level#*:})"
  done
}
source "$root/bench/common.sh"
bench_window_args "$@"
start="$opt_checkpoint"
ranks=()
[ -z "$opt_np" ] || ranks=(--np "$opt_np")

# row NAME [--set KEY=VALUE ...]: the run resumed to $end (its own limits unless set).
row() {
  local name="$1"
  shift
  echo "courant_window: $name ($*) from t = $start s to $end s ..." >&2
  bench_resume_window "$run_dir" "$opt_checkpoint" "$end" "$out/$name" "${ranks[@]}" "$@" ||
    bench_fail "$name: armour run failed: $out/$name.log"
}

cut -d' ' -f1-3 /proc/loadavg >"$out/loadavg_before"
row as_run
# p_rgh's blocks in the case's fvSolution: the template's, and the one
# `armour run` appends for the fluid.pressure_* keys (with a p_rghFinal of its
# own, which the template's copies from p_rgh when it is read).
edits=()
[ -z "$opt_pressure_tolerance" ] ||
  edits+=(-e "/^    p_rgh\(Final\)\?\$/,/^    }/ s/^\( *tolerance *\)[^;]*;/\1$opt_pressure_tolerance;/")
[ -z "$opt_pressure_rel_tol" ] ||
  edits+=(-e "/^    p_rgh\$/,/^    }/ s/^\( *relTol *\)[^;]*;/\1$opt_pressure_rel_tol;/")
if [ ${#edits[@]} -gt 0 ]; then
  bench_case_edit="sed -i $(printf '%q ' "${edits[@]}") system/fvSolution"
fi
# GAMG's smoother and agglomeration for p_rgh and p_rghFinal, appended: OpenFOAM
# merges a repeated dictionary, the last setting of a key wins (p_rghFinal is
# named too: its $p_rgh was expanded where the template defines it).
gamg=""
[ -z "$opt_pressure_smoother" ] || gamg+="smoother $opt_pressure_smoother; "
[ -z "$opt_pressure_coarsest" ] || gamg+="nCellsInCoarsestLevel $opt_pressure_coarsest; "
[ -z "$opt_pressure_merge_levels" ] || gamg+="mergeLevels $opt_pressure_merge_levels; "
if [ -n "$gamg" ]; then
  bench_case_edit="${bench_case_edit:+$bench_case_edit && }printf 'solvers\\n{\\n    p_rgh\\n    {\\n        $gamg\\n    }\\n    p_rghFinal\\n    {\\n        $gamg\\n    }\\n}\\n' >> system/fvSolution"
fi
# A PIMPLE dictionary appended last wins (OpenFOAM merges a repeated one).
if [ -n "$opt_momentum_predictor" ]; then
  bench_case_edit="${bench_case_edit:+$bench_case_edit && }printf 'PIMPLE\\n{\\n    momentumPredictor $opt_momentum_predictor;\\n}\\n' >> system/fvSolution"
fi
# isoAdvector: interIsoFoam under interFoam's name, first on PATH for this row
# only (armour starts "interFoam"), and its tolerances appended to alpha.water's
# block (OpenFOAM merges a repeated dictionary; the MULES keys it ignores).
case "$opt_advection" in
  MULES) ;;
  isoAdvector)
    mkdir -p "$out/isoAdvector_bin"
    printf '#!/bin/sh\nexec interIsoFoam "$@"\n' >"$out/isoAdvector_bin/interFoam"
    chmod +x "$out/isoAdvector_bin/interFoam"
    PATH="$out/isoAdvector_bin:$PATH"
    bench_case_edit="${bench_case_edit:+$bench_case_edit && }printf 'solvers\\n{\\n    \"alpha.water.*\"\\n    {\\n        isoFaceTol 1e-10;\\n        surfCellTol 1e-6;\\n        nAlphaBounds 3;\\n        snapTol 1e-12;\\n        clip true;\\n    }\\n}\\n' >> system/fvSolution"
    ;;
esac
row split --set "fluid.max_courant=$opt_max_courant" --set "fluid.max_interface_courant=$opt_max_interface_courant"
bench_case_edit=""
cut -d' ' -f1-3 /proc/loadavg >"$out/loadavg_after"

/usr/bin/python3 - "$out" "$start" "$end" "$opt_checkpoint" <<'EOF'
import json, os, re, sys, tomllib
import h5py
import numpy as np

out, start, end, checkpoint = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]

def log_figures(row):
    text = open(os.path.join(out, row, "case", "log.interFoam")).read()
    co = [float(x) for x in re.findall(r"^Courant Number mean: \S+ max: (\S+)", text, re.M)]
    iface = [float(x) for x in re.findall(r"^Interface Courant Number mean: \S+ max: (\S+)", text, re.M)]
    cpu = [float(x) for x in re.findall(r"^ExecutionTime = (\S+) s", text, re.M)]
    steps = len(re.findall(r"^Time = ", text, re.M))
    # The first line pair is the start's report, before any step.
    pairs = list(zip(co[1:], iface[1:]))
    off = sum(1 for c, i in pairs if i < 0.9 * c)
    control = open(os.path.join(out, row, "case", "system", "controlDict")).read()
    limit = lambda key: float(re.search(r"^%s\s+([^;]+);" % key, control, re.M).group(1))
    solution = open(os.path.join(out, row, "case", "system", "fvSolution")).read()
    # OpenFOAM merges repeated dictionaries: the last p_rgh block that sets a
    # key (armour run appends one for fluid.pressure_*) is the one in force.
    p_rgh = "".join(re.findall(r"^    p_rgh\n    \{(.*?)^    \}", solution, re.M | re.S))
    setting = lambda key: float(re.findall(r"^\s*%s\s+([^;]+);" % key, p_rgh, re.M)[-1])
    # GAMG's keys, where a block sets them (several on one line when appended).
    gamg = lambda key, default: ([default] + re.findall(r"\b%s\s+([^;\s]+);" % key, p_rgh))[-1]
    predictor = re.findall(r"^\s*momentumPredictor\s+([^;]+);", solution, re.M)[-1]
    solver = re.search(r"^Exec\s*:\s*(\S+)", text, re.M)
    return {"solver": solver.group(1) if solver else None, "max_courant": limit("maxCo"), "max_interface_courant": limit("maxAlphaCo"),
            "pressure_tolerance": setting("tolerance"), "pressure_rel_tol": setting("relTol"),
            "pressure_smoother": gamg("smoother", None),
            "pressure_coarsest": int(gamg("nCellsInCoarsestLevel", 10)),
            "pressure_merge_levels": int(gamg("mergeLevels", 1)),
            "momentum_predictor": predictor in ("yes", "on", "true"), "steps": steps,
            "cpu_seconds": cpu[-1] if cpu else None,
            "steps_set_off_the_surface": off / max(len(pairs), 1),
            "courant_max_seen": max(co) if co else None, "interface_courant_max_seen": max(iface) if iface else None}

def bodies(row):
    with h5py.File(os.path.join(out, row, "bodies.h5"), "r") as f:
        t = f["time"][:]
        keep = t > start + 1e-9
        return t[keep], f["bodies/external_force"][:][keep], f["bodies/position"][:][keep]

rows = {row: log_figures(row) for row in ("as_run", "split")}
ta, fa, pa = bodies("as_run")
tb, fb, pb = bodies("split")
n = min(len(ta), len(tb))
with open(os.path.join(out, "as_run", "scene.resolved.toml"), "rb") as f:
    unit = tomllib.load(f)["unit"][0]
# Cubes: Dn is the edge; another shape's loads and poses are given in N and m.
dn = unit["size"] if unit["shape"] == "cube" else 1.0
weight = unit["density"] * unit["size"] ** 3 * 9.81 if unit["shape"] == "cube" else 1.0
diff = np.linalg.norm(fa[:n] - fb[:n], axis=2)
load = np.linalg.norm(fa[:n], axis=2)
summary = {
    "checkpoint": checkpoint, "window": [start, end], "rows": rows,
    "cpu_ratio": rows["split"]["cpu_seconds"] / rows["as_run"]["cpu_seconds"],
    "steps_ratio": rows["split"]["steps"] / rows["as_run"]["steps"],
    "records_compared": n,
    "record_time_shift": float(np.max(np.abs(ta[:n] - tb[:n]))) if n else None,
    "load_rms_difference_over_rms": float(np.sqrt((diff**2).mean()) / np.sqrt((load**2).mean())) if n else None,
    "load_max_difference_in_unit_weights": float(diff.max() / weight) if n else None,
    "largest_load_in_unit_weights": float(load.max() / weight) if n else None,
    "final_pose_max_difference_in_Dn": float(np.linalg.norm(pa[n - 1] - pb[n - 1], axis=1).max() / dn) if n else None,
    "si_units": {"window": "s", "cpu_seconds": "s", "record_time_shift": "s"},
}
with open(os.path.join(out, "summary.json.tmp"), "w") as f:
    json.dump(summary, f, indent=2)
os.replace(os.path.join(out, "summary.json.tmp"), os.path.join(out, "summary.json"))
print(json.dumps(summary, indent=2))
EOF
# The copies of the run go (each as large as the run); the solver logs stay.
for name in as_run split; do
  cp "$out/$name/case/log.interFoam" "$out/$name.log.interFoam"
  rm -rf "${out:?}/$name" "$out/$name.scene.toml"
done
