#!/usr/bin/env bash
# Unpacks the relocatable OpenFOAM 13 build (openfoam.org; docs/openfoam13.md) into
# third_party/OpenFOAM-13, against which CMake builds the second plugin,
# build/lib/librbmMotionSolverOF13.so. The tarball is not in the repository (64 MB); it is looked
# for, first found wins, in
#   1. $RBM_OPENFOAM13_TARBALL (the .tgz itself),
#   2.–3. where rbm's build machines keep it: a shared/openfoam-13 folder beside the main
#      checkout (found from a git worktree too), or at one fixed path (so that a fresh clone
#      anywhere on such a machine finds it).
# Not found: a message saying so and exit status 0: rbm and the v1912 plugin build without it
# and the OpenFOAM 13 plugin's tests report skipped. Idempotent: when
# third_party/OpenFOAM-13/etc/bashrc exists it does nothing.
#   scripts/unpackOpenFOAM13.sh [DESTINATION_PARENT]     (default third_party)
set -euo pipefail
cd "$(dirname "$0")/.."

parent="${1:-third_party}"
destination="$parent/OpenFOAM-13"
if [ -e "$destination/etc/bashrc" ]; then
  exit 0
fi

tarballName=openfoam-13-debian12-linux64GccDPInt32Opt.tgz
candidates=()
[ -n "${RBM_OPENFOAM13_TARBALL:-}" ] && candidates+=("$RBM_OPENFOAM13_TARBALL")
if commonDir="$(git rev-parse --path-format=absolute --git-common-dir 2>/dev/null)"; then
  candidates+=("$(dirname "$(dirname "$commonDir")")/shared/openfoam-13/$tarballName")
fi
candidates+=("/work/shared/openfoam-13/$tarballName")

tarball=""
for candidate in "${candidates[@]}"; do
  if [ -f "$candidate" ]; then
    tarball="$candidate"
    break
  fi
done
if [ -z "$tarball" ]; then
  echo "unpackOpenFOAM13: OpenFOAM 13 not found (looked for ${candidates[*]}); the OpenFOAM 13" \
       "plugin is not built and its tests report skipped (set RBM_OPENFOAM13_TARBALL to the .tgz)."
  exit 0
fi

# Unpacked into a temporary folder beside the destination and renamed into place, so an
# interrupted run leaves no half-unpacked tree that the idempotence check would take as done.
mkdir -p "$parent"
staging="$(mktemp -d "$parent/.OpenFOAM-13.XXXXXX")"
trap 'rm -rf "$staging"' EXIT
echo "unpackOpenFOAM13: unpacking $tarball"
tar -xzf "$tarball" -C "$staging" || { echo "unpackOpenFOAM13: error: unpacking $tarball failed" >&2; exit 1; }
if [ ! -e "$staging/OpenFOAM-13/etc/bashrc" ]; then
  echo "unpackOpenFOAM13: error: $tarball holds no OpenFOAM-13/etc/bashrc" >&2
  exit 1
fi
rm -rf "$destination"
mv "$staging/OpenFOAM-13" "$destination"
echo "unpackOpenFOAM13: OpenFOAM 13 in $destination"
