#!/usr/bin/env bash
# The README's quick starts, timed: every command line of README.md between the
# markers <!-- quick-starts --> and <!-- end quick-starts --> that starts with
# build/apps/armour, run one after another exactly as written, except that its
# `--out out/NAME` becomes `--out OUT/NAME` (an earlier OUT/NAME is removed
# first). The clump cache is a fresh folder OUT/cache (ARMOUR_CACHE), so every
# clump is built as on a newcomer's first run. Writes OUT/summary.json (each
# quick start's command, exit status and wall seconds; SI units) and
# OUT/NAME.log, and prints a table. Exits 1 if a quick start failed.
# Usage: bash bench/run_quickstarts.sh [--build DIR] [--out DIR]
#   --build    default the repo's build/ (bash scripts/build.sh)
#   --out      default ${TMPDIR:-/tmp}/armour-bench/quickstarts
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench_name=quickstarts bench_targets="armour" bench_options=""
source "$root/bench/common.sh"
bench_args "$@"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
export ARMOUR_CACHE="$out/cache"
rm -rf "$ARMOUR_CACHE"
mkdir -p "$ARMOUR_CACHE"

mapfile -t commands < <(sed -n '/<!-- quick-starts -->/,/<!-- end quick-starts -->/p' "$root/README.md" |
  grep '^build/apps/armour ')
[ ${#commands[@]} -gt 0 ] || bench_fail "README.md: no quick-start command between the quick-starts markers"

results="$out/results.tsv"
: >"$results"
failed=0
for command in "${commands[@]}"; do
  name="$(sed -n 's/.*--out out\/\([A-Za-z0-9_.-]*\).*/\1/p' <<<"$command")"
  [ -n "$name" ] || bench_fail "README.md: a quick start without --out out/NAME: $command"
  # The README's own words, with build/apps/armour taken from --build and out/ from --out.
  line="${command/#build\/apps\/armour/$build/apps/armour}"
  line="${line/--out out\//--out $out/}"
  rm -rf "${out:?}/$name"
  echo "run_quickstarts: $name: $command" >&2
  start=$(date +%s.%N)
  status=0
  (cd "$root" && eval "$line") >"$out/$name.log" 2>&1 || status=$?
  wall=$(echo "$(date +%s.%N) - $start" | bc -l)
  [ "$status" = 0 ] || { failed=1; echo "run_quickstarts: $name failed (exit $status; see $out/$name.log)" >&2; }
  printf '%s\t%s\t%s\t%s\n' "$name" "$status" "$wall" "$command" >>"$results"
done

python3 - "$results" "$out/summary.json" "$(nproc)" "$(uptime)" <<'PY'
import json, sys
rows = [line.rstrip("\n").split("\t", 3) for line in open(sys.argv[1]) if line.strip()]
summary = {
    "quickstarts": [{"name": n, "command": c, "exit_status": int(s), "wall_seconds": float(w)}
                    for n, s, w, c in rows],
    "cores": int(sys.argv[3]),
    "uptime_at_end": sys.argv[4].strip(),
    "si_units": {"wall_seconds": "s"},
}
with open(sys.argv[2], "w") as f:
    json.dump(summary, f, indent=2)
print(f"{'quick start':<24} {'wall s':>8}  status")
for q in summary["quickstarts"]:
    print(f"{q['name']:<24} {q['wall_seconds']:8.1f}  {'ok' if q['exit_status'] == 0 else 'FAILED'}")
print(f"({summary['cores']} cores; load at the end: {summary['uptime_at_end'].split('load average:')[-1].strip()})")
PY
exit $failed
