#!/usr/bin/env bash
# The choice of displacementLaplacian's diffusivity for constant/dynamicMeshDict.laplacian:
# moves the mesh of this case with OpenFOAM's moveDynamicMesh (the motion alone, OpenFOAM's
# checkMesh after every step) for each diffusivity below, up to the largest angle (t = 0.25)
# with deltaT 0.005 (50 steps; the mesh depends little on the step: each step solves for the
# total displacement), and prints a markdown table (about 10 min on a loaded 2-core machine).
#   ./diffusivities.sh [work folder]   (default ${TMPDIR:-/tmp}/naca4415PitchingFlow.diffusivities)
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
work=${1:-${TMPDIR:-/tmp}/naca4415PitchingFlow.diffusivities}
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
command -v moveDynamicMesh >/dev/null || { echo "diffusivities.sh: moveDynamicMesh not found (apt-get install openfoam)" >&2; exit 2; }
diffusivities=(
  "uniform"
  "inverseDistance (airfoil)"
  "quadratic inverseDistance (airfoil)"
  "exponential 1 inverseDistance (airfoil)"
  "exponential 2 inverseDistance (airfoil)"
  "exponential 5 inverseDistance (airfoil)"
)
rm -rf "$work"
mkdir -p "$work"
commit=$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)
echo "Measured $(date -u '+%Y-%m-%d %H:%M UTC') with \`tutorials/naca4415PitchingFlow/diffusivities.sh\` at commit $commit"
echo "(OpenFOAM v1912, moveDynamicMesh, t = 0 … 0.25, deltaT 0.005); α = angle of attack, 10° sin(2πt)."
echo
echo "| diffusivity | steps passing checkMesh (of 50) | first failing step | inverted cells (negative volume) there | most inverted cells in a step | worst max non-orthogonality before the first failure |"
echo "|---|---|---|---|---|---|"
i=0
for d in "${diffusivities[@]}"; do
  i=$((i+1))
  c=$work/$i
  mkdir -p "$c"
  cp -r "$here/0" "$here/constant" "$here/system" "$c/"
  cp "$here/constant/dynamicMeshDict.laplacian" "$c/constant/dynamicMeshDict"
  sed -i "s/^ *diffusivity .*/    diffusivity     $d;/" "$c/constant/dynamicMeshDict"
  sed -i 's/^deltaT .*/deltaT          0.005;/; s/^writeInterval .*/writeInterval   100000;/; s/^endTime .*/endTime         0.25;/' "$c/system/controlDict"
  moveDynamicMesh -case "$c" -noFunctionObjects > "$c/log.moveDynamicMesh" 2>&1
  status=$?
  awk -v d="$d" -v status="$status" '
    /^Time = /{t=$3; n++; cur=0}
    /non-orthogonality Max:/{if (bad == "" && $4+0 > no) no=$4+0}
    /Number of negative volume cells:/{cur=$NF+0; if (cur > inv) inv=cur}
    /^Mesh OK/{ok++}
    /Failed [0-9]+ mesh checks/{if (bad == "") {bad=t; badInv=cur}}
    END{
      pi=atan2(0,-1)
      where = (bad == "" ? "none" : sprintf("t = %s (α = %.1f°)", bad, 10*sin(2*pi*bad)))
      if (status != 0) where = where sprintf("; moveDynamicMesh stopped at t = %s (exit status %d)", t, status)
      printf "| `%s` | %d | %s | %s | %d | %.1f° |\n", d, ok, where, (bad == "" ? "—" : badInv), inv, no
    }' "$c/log.moveDynamicMesh"
done
