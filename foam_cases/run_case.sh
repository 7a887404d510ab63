#!/usr/bin/env bash
# run_case.sh [--np N] [--plugin LIB] [--waves LIB] [--scene FILE] CASE_TEMPLATE OUTDIR
#
# Copies an interFoam case template to OUTDIR, fills its placeholders
# (@ARMOUR_PLUGIN@: the plugin's absolute path; @ARMOUR_WAVES@: the wave
# library's; @NP@: ranks; @ARMOUR_SCENE@ in constant/fvOptions: the armour
# scene --scene FILE, copied to OUTDIR/scene.toml), then runs
# blockMesh, setFields and interFoam (serial, or decomposePar + mpirun with
# --np N). Each tool logs to OUTDIR/log.<tool>. Any failure stops the script
# with the tool's FOAM FATAL line on stderr and exit status 1.
#
# The plugin is --plugin LIB, else $ARMOUR_FOAM_PLUGIN, else the first
# build*/coupling/openfoam/libarmourFoamCoupling.so of this checkout. It is
# needed only when the controlDict names @ARMOUR_PLUGIN@; likewise the wave
# library (--waves LIB, else $ARMOUR_WAVES_LIB, else the first
# build*/coupling/openfoam/waves/libarmourWaves.so) only for @ARMOUR_WAVES@.
set -euo pipefail

die() { echo "run_case: $*" >&2; exit 1; }

np=1
plugin="${ARMOUR_FOAM_PLUGIN:-}"
waves="${ARMOUR_WAVES_LIB:-}"
scene=""
while [ $# -gt 0 ]; do
    case "$1" in
        --np) [ $# -ge 2 ] || die "--np needs a number"; np="$2"; shift 2 ;;
        --plugin) [ $# -ge 2 ] || die "--plugin needs a path"; plugin="$2"; shift 2 ;;
        --waves) [ $# -ge 2 ] || die "--waves needs a path"; waves="$2"; shift 2 ;;
        --scene) [ $# -ge 2 ] || die "--scene needs a path"; scene="$2"; shift 2 ;;
        -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
        -*) die "unknown option $1" ;;
        *) break ;;
    esac
done
[ $# -eq 2 ] || die "usage: run_case.sh [--np N] [--plugin LIB] [--waves LIB] [--scene FILE] CASE_TEMPLATE OUTDIR"
template="$1"
out="$2"
[[ "$np" =~ ^[1-9][0-9]*$ ]] || die "--np must be a positive integer, got '$np'"
[ -f "$template/system/controlDict" ] || die "$template is not a case (no system/controlDict)"
# OpenFOAM's tools find their etc/ files only through WM_PROJECT_DIR (Debian's
# v1912: /usr/share/openfoam); checked before OUTDIR is made, with the tools.
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
[ -f "$WM_PROJECT_DIR/etc/controlDict" ] ||
    die "WM_PROJECT_DIR: $WM_PROJECT_DIR: not an OpenFOAM installation (no etc/controlDict); unset it to use /usr/share/openfoam"
for tool in blockMesh setFields interFoam; do
    command -v "$tool" > /dev/null || die "PATH: no $tool: install Debian's openfoam (docs/openfoam.md)"
done

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if grep -q '@ARMOUR_PLUGIN@' "$template/system/controlDict"; then
    if [ -z "$plugin" ]; then
        plugin="$(compgen -G "$root/build*/coupling/openfoam/libarmourFoamCoupling.so" | head -n1 || true)"
    fi
    { [ -n "$plugin" ] && [ -f "$plugin" ]; } || die "plugin libarmourFoamCoupling.so not found (build it, or pass --plugin)"
    plugin="$(cd "$(dirname "$plugin")" && pwd)/$(basename "$plugin")"
fi
if grep -q '@ARMOUR_WAVES@' "$template/system/controlDict"; then
    if [ -z "$waves" ]; then
        waves="$(compgen -G "$root/build*/coupling/openfoam/waves/libarmourWaves.so" | head -n1 || true)"
    fi
    { [ -n "$waves" ] && [ -f "$waves" ]; } || die "libarmourWaves.so not found (build it, or pass --waves)"
    waves="$(cd "$(dirname "$waves")" && pwd)/$(basename "$waves")"
fi

if [ -f "$template/constant/fvOptions" ] && grep -q '@ARMOUR_SCENE@' "$template/constant/fvOptions"; then
    { [ -n "$scene" ] && [ -f "$scene" ]; } || die "$template/constant/fvOptions needs an armour scene: pass --scene FILE"
fi

if [ -e "$out" ] && [ -n "$(ls -A "$out" 2>/dev/null)" ]; then
    die "$out exists and is not empty"
fi
mkdir -p "$out"
cp -r "$template"/. "$out"/
out="$(cd "$out" && pwd)"
sed -i -e "s|@ARMOUR_PLUGIN@|$plugin|g" -e "s|@ARMOUR_WAVES@|$waves|g" "$out/system/controlDict"
[ -f "$out/system/decomposeParDict" ] && sed -i "s|@NP@|$np|g" "$out/system/decomposeParDict"
if [ -n "$scene" ]; then
    cp "$scene" "$out/scene.toml"
    [ -f "$out/constant/fvOptions" ] && sed -i "s|@ARMOUR_SCENE@|$out/scene.toml|g" "$out/constant/fvOptions"
fi
for f in "$out"/0/*.orig; do
    [ -e "$f" ] && cp "$f" "${f%.orig}"
done

# run NAME CMD...: runs in the case, logs to log.NAME, and on failure
# surfaces the fatal line.
run() {
    local tool="$1" log="$out/log.$1"
    shift
    if ! (cd "$out" && "$@" > "$log" 2>&1); then
        local fatal
        fatal="$(grep -m1 -A4 'FOAM FATAL' "$log" | grep -v '^\s*$' | head -n5 | tr '\n' ' ' || true)"
        [ -n "$fatal" ] || fatal="$(tail -n 3 "$log" | tr '\n' ' ')"
        die "$tool failed (see $log): $fatal"
    fi
    # Some FOAM FATAL errors in parallel runs still exit 0 from mpirun.
    if grep -q 'FOAM FATAL' "$log"; then
        die "$tool reported: $(grep -m1 -A4 'FOAM FATAL' "$log" | tr '\n' ' ')"
    fi
}

run blockMesh blockMesh
run setFields setFields
if [ "$np" -eq 1 ]; then
    run interFoam interFoam
else
    run decomposePar decomposePar -force
    run interFoam mpirun --allow-run-as-root -np "$np" -x WM_PROJECT_DIR -x LD_LIBRARY_PATH interFoam -parallel
fi
echo "run_case: $out done"
