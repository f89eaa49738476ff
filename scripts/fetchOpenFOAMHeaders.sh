#!/usr/bin/env bash
# Fetches OpenFOAM v1912's headers for building the plugin (openfoam/) against Debian's
# OpenFOAM libraries. Debian 12 ships the libraries (libopenfoam) but no headers package; the
# headers are in Debian's source package. This script
#   1. adds a deb-src line for bookworm main (/etc/apt/sources.list.d/rbm-openfoam-src.sources)
#      when apt has none, and runs `apt-get update` for it,
#   2. downloads the source package (`apt-get source --download-only openfoam`, about 45 MB),
#   3. unpacks the `src/` folders the plugin needs into third_party/openfoam-1912/src,
#   4. makes one flat lnInclude/ folder of symlinks to every *.H and *.C of them (what
#      wmake's per-library lnInclude folders give OpenFOAM's includes).
# Idempotent: when third_party/openfoam-1912/lnInclude/fvCFD.H exists it does nothing.
# Fails loudly (exit status 1, a message saying what to do) when the source is unavailable.
#   scripts/fetchOpenFOAMHeaders.sh [DESTINATION]     (default third_party/openfoam-1912)
set -euo pipefail
cd "$(dirname "$0")/.."

destination="${1:-third_party/openfoam-1912}"
marker="$destination/lnInclude/fvCFD.H"
if [ -e "$marker" ]; then
  exit 0
fi

fail() {
  echo "fetchOpenFOAMHeaders: error: $*" >&2
  echo "fetchOpenFOAMHeaders: the OpenFOAM plugin needs OpenFOAM v1912's headers from Debian's source" \
       "package 'openfoam' (bookworm main). Check the network and apt's sources, or configure with" \
       "-DRBM_BUILD_OPENFOAM_PLUGIN=OFF to build rbm without the plugin." >&2
  exit 1
}

# The library folders the plugin's includes reach (motionSolver, displacementMotionSolver,
# pointPatchFields, pointConstraints, globalMeshData, twoDPointCorrector, fvMesh).
libraries=(OpenFOAM OSspecific/POSIX finiteVolume meshTools dynamicMesh fvMotionSolver)

if ! apt-get indextargets --format '$(CREATED_BY) $(SITE)' 2>/dev/null | grep -q '^Sources '; then
  [ "$(id -u)" -eq 0 ] || fail "apt has no deb-src line and adding one needs root"
  echo "fetchOpenFOAMHeaders: adding a deb-src line for bookworm main"
  cat > /etc/apt/sources.list.d/rbm-openfoam-src.sources <<'EOF'
# Added by rbm's scripts/fetchOpenFOAMHeaders.sh: OpenFOAM's headers come from its source package.
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
  apt-get update -qq || fail "apt-get update failed"
fi

download="$(mktemp -d "${TMPDIR:-/tmp}/rbm-openfoam-src.XXXXXX")"
chmod 755 "$download"   # apt's _apt user downloads into it
trap 'rm -rf "$download"' EXIT
echo "fetchOpenFOAMHeaders: downloading Debian's openfoam source package"
fetchSource() { (cd "$download" && apt-get source --download-only -qq -o APT::Sandbox::User=root openfoam >/dev/null); }
# A deb-src line whose index apt never downloaded: update once and try again.
fetchSource || { [ "$(id -u)" -eq 0 ] && apt-get update -qq && fetchSource; } ||
  fail "apt-get source --download-only openfoam failed"
shopt -s nullglob
tarballs=("$download"/openfoam_*.orig.tar.*)
[ ${#tarballs[@]} -eq 1 ] || fail "expected one openfoam_*.orig.tar.* in the source package, found ${#tarballs[@]}"

# Unpack into a temporary folder next to the destination, renamed into place at the end, so an
# interrupted run leaves no half-unpacked tree that the idempotence check would take as done.
mkdir -p "$(dirname "$destination")"
staging="$(mktemp -d "$(dirname "$destination")/.openfoam-1912.XXXXXX")"
trap 'rm -rf "$download" "$staging"' EXIT
# One pass over the archive (xz): members matched by pattern, whatever the top folder's name.
members=()
for library in "${libraries[@]}"; do members+=("*/src/$library/*"); done
tar -xf "${tarballs[0]}" -C "$staging" --strip-components=1 --wildcards "${members[@]}" ||
  fail "unpacking ${tarballs[0]} failed"

mkdir -p "$staging/lnInclude"
for library in "${libraries[@]}"; do
  # One flat folder: the first file of a name wins (names are unique across these libraries
  # except for a few test and tutorial sources that the plugin does not include).
  find "$staging/src/$library" \( -name '*.H' -o -name '*.C' \) -type f -print0 |
    while IFS= read -r -d '' file; do
      link="$staging/lnInclude/$(basename "$file")"
      [ -e "$link" ] || ln -s "../src/${file#"$staging/src/"}" "$link"
    done
done
[ -e "$staging/lnInclude/fvCFD.H" ] || fail "the unpacked source has no fvCFD.H"
rm -rf "$destination"
mv "$staging" "$destination"
echo "fetchOpenFOAMHeaders: OpenFOAM v1912 headers in $destination/lnInclude"
