#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang + AddressSanitizer) in build-fuzz/
# and runs every target for SECONDS (default 60): first on each regression
# input in tests/fuzz_inputs/TARGET/, then fuzzing from the shipped files
# (scenes/*.toml; scenes/*.stl and fuzz/seeds/*.stl). Exits non-zero on the
# first crash, uncaught exception or hang (> 10 s on one input), leaving the
# input in build-fuzz/crash-TARGET-*; see docs/fuzzing.md.
#   scripts/fuzz.sh 30            # CI: ctest runs it as fuzz_readers
#   ARMOUR_FUZZ_BUILD=/tmp/f scripts/fuzz.sh 600
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
build="${ARMOUR_FUZZ_BUILD:-$root/build-fuzz}"
jobs="$(nproc 2>/dev/null || echo 2)"

mkdir -p "$build"
{ cmake -S "$root/fuzz" -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ &&
    cmake --build "$build" -j "$jobs"; } > "$build/build.log" 2>&1 ||
  { tail -n 40 "$build/build.log"; echo "fuzz: the build failed (log: $build/build.log)" >&2; exit 1; }

# The targets write each input to a file named by their pid in the temp
# directory (fuzz/fuzz_input.h); give them one of ours, removed on exit.
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
export TMPDIR="$scratch"

seeds_of() {
  case "$1" in
    scene) ls "$root"/scenes/*.toml "$root"/fuzz/seeds/*.toml ;;
    stl) ls "$root"/scenes/*.stl "$root"/fuzz/seeds/*.stl ;;
    sweep) ls "$root"/studies/*.toml ;;
  esac
}

for target in scene stl sweep; do
  fuzzer="$build/fuzz_$target"
  [ -x "$fuzzer" ] || continue # fuzz_sweep: only with the sweep reader in the tree
  regressions=("$root/tests/fuzz_inputs/$target"/*)
  if [ -e "${regressions[0]}" ]; then
    "$fuzzer" -timeout=10 "${regressions[@]}" > "$build/regressions-$target.log" 2>&1 ||
      { tail -n 30 "$build/regressions-$target.log"; echo "fuzz: $target: a regression input fails again" >&2; exit 1; }
  fi
  # The corpus grows across runs in build-fuzz/corpus; the seeds are copied, never written.
  corpus="$build/corpus/$target" seeds="$build/seeds/$target"
  mkdir -p "$corpus" "$seeds"
  seeds_of "$target" | xargs -I{} cp {} "$seeds/"
  log="$build/fuzz-$target.log"
  if ! "$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$build/crash-$target-" "$corpus" "$seeds" > "$log" 2>&1; then
    tail -n 40 "$log"
    echo "fuzz: $target: crash or hang; the input is in $build/crash-$target-* (make it a regression input)" >&2
    exit 1
  fi
  runs="$(grep -m1 -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')"
  echo "fuzz: $target: $runs inputs in ${seconds} s, no crash, no hang ($(ls "$corpus" | wc -l) in the corpus)"
done
