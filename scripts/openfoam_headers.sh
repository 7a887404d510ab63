#!/usr/bin/env bash
# openfoam_headers.sh DEST
#
# Debian packages OpenFOAM v1912's libraries but none of its headers. This
# fetches Debian's own source package (so the headers match the binaries
# exactly), extracts only the libraries the armour plugin compiles against and
# builds their lnInclude/ folders the way wmake would, without wmake.
#
# Result: DEST/src/<lib>/lnInclude for OpenFOAM, OSspecific/POSIX,
# finiteVolume, meshTools, fvOptions; DEST/.done marks success, and a second
# run returns at once. The download is kept in DEST/download so a rebuild of
# DEST needs no network. Root is needed only when the source package has to
# be downloaded (deb-src entry, apt-get update).
set -euo pipefail

die() { echo "openfoam_headers: $*" >&2; exit 1; }

[ $# -eq 1 ] || die "usage: $0 DEST"
dest="$1"
mkdir -p "$dest" || die "cannot create $dest"
dest="$(cd "$dest" && pwd)"
[ -f "$dest/.done" ] && exit 0

# Two configures sharing one cache must not extract over each other.
exec 9>"$dest/.lock"
flock 9
[ -f "$dest/.done" ] && exit 0

libs=(OpenFOAM OSspecific/POSIX finiteVolume meshTools fvOptions)
download="$dest/download"
mkdir -p "$download"

orig() { compgen -G "$download/openfoam_*.orig.tar.*" | head -n1 || true; }

if [ -z "$(orig)" ]; then
    [ "$(id -u)" -eq 0 ] || die "the OpenFOAM source package is not in $download yet and fetching it needs root (apt-get source); run this script once as root"
    command -v dpkg-source >/dev/null || die "dpkg-dev is missing (apt-get install dpkg-dev)"

    # A deb-src entry for bookworm main, from the same archive and key as the
    # deb entry, unless some deb-src entry already exists.
    if ! grep -rqsE '^[[:space:]]*(deb-src[[:space:]]|Types:.*deb-src)' \
            /etc/apt/sources.list /etc/apt/sources.list.d/; then
        uri="" key=""
        for f in /etc/apt/sources.list.d/*.sources; do
            [ -f "$f" ] || continue
            # First deb822 stanza whose suites include plain "bookworm".
            read -r uri key < <(awk '
                /^[[:space:]]*$/ { if (ok && u != "") { print u, k; exit } ; u=""; k=""; ok=0; next }
                /^URIs:/        { u=$2 }
                /^Signed-By:/   { k=$2 }
                /^Suites:/      { for (i = 2; i <= NF; i++) if ($i == "bookworm") ok=1 }
                END             { if (ok && u != "") print u, k }' "$f") || true
            [ -n "$uri" ] && break
        done
        [ -n "$uri" ] || die "no deb822 'bookworm' entry found in /etc/apt/sources.list.d/ to copy for deb-src"
        {
            echo "# Added by armour-fsi scripts/openfoam_headers.sh: OpenFOAM headers come from the source package."
            echo "Types: deb-src"
            echo "URIs: $uri"
            echo "Suites: bookworm"
            echo "Components: main"
            [ -n "$key" ] && echo "Signed-By: $key"
        } > /etc/apt/sources.list.d/armour-deb-src.sources
    fi

    # Only the source indexes are missing: update just the deb-src files when
    # that works, which is much faster than a full update.
    srcs=(/etc/apt/sources.list.d/armour-deb-src.sources)
    if [ -f "${srcs[0]}" ] && apt-get update -qq -o Dir::Etc::sourcelist="${srcs[0]}" \
            -o Dir::Etc::sourceparts=- -o APT::Get::List-Cleanup=0 >/dev/null 2>&1 \
            && apt-cache showsrc openfoam >/dev/null 2>&1; then
        :
    else
        apt-get update -qq >/dev/null || die "apt-get update failed"
    fi
    (cd "$download" && apt-get source -qq --download-only openfoam >/dev/null 2>&1) \
        || die "apt-get source --download-only openfoam failed (deb-src entry or network?)"
    [ -n "$(orig)" ] || die "apt-get source produced no openfoam_*.orig.tar.* in $download"
fi

tarball="$(orig)"
top="$({ tar -tf "$tarball" 2>/dev/null || true; } | head -n1 | cut -d/ -f1)"
[ -n "$top" ] || die "cannot read $tarball"

rm -rf "$dest/src"
mkdir -p "$dest/src"
patterns=()
for lib in "${libs[@]}"; do patterns+=("$top/src/$lib/*"); done
tar -xf "$tarball" -C "$dest" --strip-components=1 --wildcards "${patterns[@]}" \
    || die "extracting ${libs[*]} from $tarball failed"

# Debian's patches are applied to the binaries, so apply those touching what
# we extracted (a header differing from the build would be a silent ABI trap).
debtar="$(compgen -G "$download/openfoam_*.debian.tar.*" | head -n1 || true)"
if [ -n "$debtar" ]; then
    tmp="$(mktemp -d)"
    tar -xf "$debtar" -C "$tmp"
    if [ -f "$tmp/debian/patches/series" ]; then
        while read -r p _; do
            case "$p" in ''|'#'*) continue ;; esac
            # Skip patches for files we did not extract; apply the rest strictly.
            if patch -d "$dest" -p1 --dry-run -s -f < "$tmp/debian/patches/$p" >/dev/null 2>&1; then
                patch -d "$dest" -p1 -s -f < "$tmp/debian/patches/$p" >/dev/null
            fi
        done < "$tmp/debian/patches/series"
    fi
    rm -rf "$tmp"
fi

# lnInclude: a flat folder of links to every source file of the library, as
# wmakeLnInclude makes it (same skipped folders). Relative links keep DEST movable.
for lib in "${libs[@]}"; do
    dir="$dest/src/$lib"
    [ -d "$dir" ] || die "$lib missing from $tarball"
    mkdir -p "$dir/lnInclude"
    (cd "$dir" && find . \( -name lnInclude -o -name Make -o -name config -o -name noLink \) -prune -o \
        -type f \( -name '*.C' -o -name '*.H' -o -name '*.c' -o -name '*.h' -o -name '*.type' \) -print0 |
        xargs -0 ln -sfr -t lnInclude) || die "building $lib/lnInclude failed"
done

touch "$dest/.done"
