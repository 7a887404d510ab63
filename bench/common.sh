# Sourced by every bench script: one way to take the build folder, the
# output folder and the script's own options. Benchmarks never write into the
# source tree: results go to --out (default ${TMPDIR:-/tmp}/armour-bench/NAME);
# figures that docs/ shows are copied there by hand.
#
# Usage, in a script (after `root=...`):
#   bench_name=clump                           # default output folder's name
#   bench_targets="bench_clump_convergence"    # CMake targets the bench runs
#   bench_options="seconds"                    # its own options: --seconds S sets $opt_seconds
#   source "$root/bench/common.sh"
#   bench_args "$@"                            # sets $build, $out (absolute, created) and $opt_*
# Options: --build DIR (default $ARMOUR_BUILD or the repo's build/, made by
# scripts/build.sh), --out DIR, -h/--help. The older form `script OUT_DIR
# [VALUE...]` still works: OUT_DIR, then the script's options in order.

# The chart scripts read results through analysis/armour_results.py.
export PYTHONPATH="$root/analysis${PYTHONPATH:+:$PYTHONPATH}"

# The build output of a CMake target, relative to the build folder.
bench_target_file() {
  case "$1" in
    armour) echo apps/armour ;;
    armourFoamCoupling) echo coupling/openfoam/libarmourFoamCoupling.so ;;
    armourWaves) echo coupling/openfoam/waves/libarmourWaves.so ;;
    *) echo "bench/$1" ;;
  esac
}

bench_usage() {
  # The script's header comment, without the shebang.
  sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"
}

bench_fail() {
  echo "$(basename "$0"): $*" >&2
  exit 2
}

# A bench's --set 'KEY=VALUE ...' as armour's options: sets=(--set KEY=VALUE ...).
# A word without '=' is refused here, before any run.
bench_scene_sets() {
  local settings=() setting
  read -ra settings <<<"${opt_set-}"
  sets=()
  for setting in "${settings[@]}"; do
    [[ "$setting" == *=* ]] || bench_fail "--set: '$setting' is not KEY=VALUE"
    sets+=(--set "$setting")
  done
}

bench_args() {
  build="${ARMOUR_BUILD:-$root/build}"
  out="${TMPDIR:-/tmp}/armour-bench/$bench_name"
  local positional=() name
  while [ $# -gt 0 ]; do
    case "$1" in
      -h | --help) bench_usage; exit 0 ;;
      --build | --out)
        [ $# -ge 2 ] || bench_fail "$1: needs a folder"
        if [ "$1" = --build ]; then build="$2"; else out="$2"; fi
        shift 2 ;;
      --build=*) build="${1#--build=}"; shift ;;
      --out=*) out="${1#--out=}"; shift ;;
      --*)
        name="${1#--}"; name="${name%%=*}"
        case " $bench_options " in
          *" $name "*) ;;
          *) bench_fail "$1: unknown option (see --help)" ;;
        esac
        if [[ "$1" == *=* ]]; then
          printf -v "opt_${name//-/_}" '%s' "${1#*=}"; shift
        else
          [ $# -ge 2 ] || bench_fail "$1: needs a value"
          printf -v "opt_${name//-/_}" '%s' "$2"; shift 2
        fi ;;
      *) positional+=("$1"); shift ;;
    esac
  done
  # The older positional form: OUT_DIR, then the options in order.
  if [ ${#positional[@]} -gt 0 ]; then
    out="${positional[0]}"
    local i=1
    for name in $bench_options; do
      [ $i -lt ${#positional[@]} ] || break
      printf -v "opt_${name//-/_}" '%s' "${positional[$i]}"
      i=$((i + 1))
    done
    [ $i -ge ${#positional[@]} ] || bench_fail "${positional[$i]}: unexpected argument (see --help)"
  fi
  [ -d "$build" ] || bench_fail "--build $build: no build folder; make it with: bash scripts/build.sh $bench_targets"
  build="$(cd "$build" && pwd)"
  local target
  for target in $bench_targets; do
    [ -e "$build/$(bench_target_file "$target")" ] ||
      bench_fail "$build/$(bench_target_file "$target") missing; build it with: bash scripts/build.sh $bench_targets (or pass --build DIR)"
  done
  # A script's own option checks (bench_check_options, where it defines one) run
  # before --out is made: a refused option leaves nothing behind.
  ! declare -F bench_check_options >/dev/null || bench_check_options
  mkdir -p "$out"
  out="$(cd "$out" && pwd)"
}

# bench_resume_window RUN_DIR CHECKPOINT END DIR [armour run options...]: a
# copy of the run folder RUN_DIR in DIR (inside --out), resumed from its
# checkpoint CHECKPOINT (a folder name under RUN_DIR/checkpoints; the copy's
# later ones dropped) to END s through `armour run --resume` with the run's
# resolved scene (the fluid written at END only); armour's output in DIR.log.
# $bench_case_edit, when set, runs (eval) in the copy's case folder before the
# resume: a resume keeps the case's system/ files, so a window can try a solver
# setting no scene key holds. Returns armour's status.
bench_resume_window() {
  local run_dir="$1" checkpoint="$2" end="$3" dir="$4" c
  shift 4
  # Called where `set -e` does not hold (`row || bench_fail`): each step returns on failure.
  rm -rf "$dir" || return
  cp -r "$run_dir" "$dir" || return
  for c in "$dir"/checkpoints/*; do
    if awk -v a="$(basename "$c")" -v b="$checkpoint" 'BEGIN { exit !(a + 0 > b + 0) }'; then
      rm -rf "$c" || return
    fi
  done
  cp "$run_dir/scene.resolved.toml" "$dir.scene.toml" || return
  if [ -n "${bench_case_edit:-}" ]; then
    (cd "$dir/case" && eval "$bench_case_edit") || return
  fi
  "$build/apps/armour" run "$dir.scene.toml" --out "$dir" --set "run.duration=$end" \
    --set "fluid.write_interval=$end" --resume "$@" >"$dir.log" 2>&1
}

# bench_window_args RUN_DIR [options...], for the benches that resume windows
# of a run: RUN_DIR (an `armour run` output folder with checkpoints) first,
# then bench_args' options. Sets $run_dir (absolute), $opt_checkpoint (its
# default: the latest) and $end (the checkpoint's time + $opt_seconds, s).
bench_window_args() {
  case "${1:-}" in
    -h | --help) bench_usage; exit 0 ;;
    "" | -*) bench_fail "RUN_DIR: give an armour run output folder first (see --help)" ;;
  esac
  run_dir="$1"
  shift
  bench_args "$@"
  [ -d "$run_dir" ] || bench_fail "$run_dir: no such folder"
  run_dir="$(cd "$run_dir" && pwd)"
  [ -f "$run_dir/scene.resolved.toml" ] && [ -d "$run_dir/checkpoints" ] ||
    bench_fail "$run_dir: not an armour run output folder with checkpoints"
  [ -n "$opt_checkpoint" ] ||
    opt_checkpoint="$(ls "$run_dir/checkpoints" 2>/dev/null | { grep -v '^\.' || true; } | sort -g | tail -1)"
  [ -f "$run_dir/checkpoints/$opt_checkpoint/checkpoint.json" ] ||
    bench_fail "--checkpoint $opt_checkpoint: no checkpoint in $run_dir/checkpoints"
  end="$(awk -v a="$opt_checkpoint" -v b="$opt_seconds" 'BEGIN { printf "%.10g", a + b }')"
}

# The stability scene's layer, settled once into $layer = $out/layer (Dn/2
# cells for the short coupled start; the settle is the DEM's alone), and its
# settled scene with the fluid's tables removed, $out/hold.toml: a dry hold of
# the layer. Settled at once (fluid.settle_stages = 1, not the scene's 11
# stages): one LIGGGHTS set-up, $layer/settle/liggghts/, that the DEM benches
# replay, and the layer their kept figures were measured on. Sets $layer for
# the caller.
bench_settled_layer_dry() {
  layer="$out/layer"
  if [ ! -f "$layer/settle/scene.settled.toml" ]; then
    "$build/apps/armour" run "$root/scenes/stability_cubes.toml" --out "$layer" --set 'fluid.cells=[100,12,31]' \
      --set fluid.settle_stages=1 --set run.duration=0.05 >"$layer.log" 2>&1
  fi
  awk '/^\[/ { skip = ($0 ~ /^\[fluid\]|^\[waves\]|^\[\[porous\]\]|^\[\[series\]\]|^\[\[refine\]\]|^\[analysis\]/) } !skip' \
    "$layer/settle/scene.settled.toml" >"$out/hold.toml"
}

# After bench_settled_layer_dry: the LIGGGHTS set-up the adapter writes for a
# dry hold of the settled layer (its bodies at rest), from a 0.05 s hold run
# made once in $out/hold. Sets $held_input for the caller.
bench_held_layer_input() {
  held_input="$out/hold/liggghts/input.liggghts"
  [ -f "$held_input" ] ||
    "$build/apps/armour" run "$out/hold.toml" --set run.duration=0.05 --out "$out/hold" >"$out/hold.log" 2>&1
}
