#!/usr/bin/env bash
# The stiffening study of docs/motionSolver.md ("Default stiffening"):
# moves every tutorial, the thesis' squares with the solver's defaults and the boundary-layer
# airfoil fixture (4° and 10° about its trailing edge) with rbm under several `stiffening`
# settings, and optionally with OpenFOAM's displacementLaplacian under several diffusivities,
# and prints markdown tables: max non-orthogonality, max skewness (checkMesh definitions) and
# inverted cells, all measured by rbmCheckMesh (the worst over every written time for the
# pitching case, whose copy writes every step).
#
#   scripts/stiffeningStudy.sh [rbm|openfoam|all] [case ...]
#
# Cases: naca4415 naca4415Pitching squaresRotating squaresTranslated squaresFreeOuterBoundary
# cube wingBending squaresRotatingDefaults squaresTranslatedDefaults blAirfoil4 blAirfoil10
# (default: all). Settings: STIFFENING_SETTINGS (space-separated keys of `setting()` below;
# default: every key but auto, which is the default's spelling). OpenFOAM: DIFFUSIVITIES
# likewise; PITCHING_STEPS (default 40, one period of the motion: rbm solves each step on the
# initial mesh, so the second period repeats the first) limits the pitching case for both
# codes. RBM_BIN: folder of rbmMoveMesh and rbmCheckMesh (default build/bin). Each run works on a copy of the case's inputs (0/, constant/, system/)
# in a temporary folder (STUDY_DIR, default a new mktemp -d, deleted at the end unless
# KEEP_STUDY=1). One run at a time; OpenFOAM v1912 from Debian (/usr/share/openfoam).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=$(cd "${RBM_BIN:-$here/build/bin}" && pwd)
mode=${1:-rbm}
shift || true
allCases="naca4415 naca4415Pitching squaresRotating squaresTranslated squaresFreeOuterBoundary cube wingBending
          squaresRotatingDefaults squaresTranslatedDefaults blAirfoil4 blAirfoil10"
cases=${*:-$allCases}
work=${STUDY_DIR:-$(mktemp -d /tmp/stiffeningStudy.XXXXXX)}
mkdir -p "$work"
[[ ${KEEP_STUDY:-0} == 1 ]] || trap 'rm -rf "$work"' EXIT
pitchingSteps=${PITCHING_STEPS:-40}

# case → source folder, coefficient mode (shipped: the tutorial's own dynamicMeshDict
# coefficients; defaults: an empty coefficient dictionary), every non-empty patch, the
# prescribed patches whose displacement is not zero (the moving ones).
source_of() {
  case $1 in
    naca4415|naca4415Pitching|cube|wingBending) echo "tutorials/$1" ;;
    squaresRotating*) echo tutorials/squares/rotating ;;
    squaresTranslated*) echo tutorials/squares/translated ;;
    squaresFreeOuterBoundary) echo tutorials/squares/freeOuterBoundary ;;
    blAirfoil*) echo tests/data/airfoilBoundaryLayer ;;
  esac
}
coefficient_mode() { case $1 in *Defaults|blAirfoil*) echo defaults ;; *) echo shipped ;; esac; }
all_patches() {
  case $1 in
    naca4415*|blAirfoil*) echo "airfoil farfield" ;;
    squares*) echo "innerSquare outerSquare" ;;
    cube) echo "top bottom sides" ;;
    wingBending) echo "wing farfield symmetryPlane" ;;
  esac
}
moving_patches() {
  case $1 in
    naca4415*|blAirfoil*) echo airfoil ;;
    squares*) echo innerSquare ;;
    cube) echo "top sides" ;;
    wingBending) echo wing ;;
  esac
}
# The prescribed patches (fixed ones included), not the free or sliding ones.
prescribed_patches() {
  case $1 in
    squaresFreeOuterBoundary) echo innerSquare ;;
    wingBending) echo "wing farfield" ;;
    *) all_patches "$1" ;;
  esac
}

# setting key → the `stiffening` entry ("" : no entry, the solver's default).
setting() { # key case
  local all moving prescribed
  all=$(all_patches "$2"); moving=$(moving_patches "$2"); prescribed=$(prescribed_patches "$2")
  case $1 in
    default) echo "" ;;
    none) echo "stiffening none;" ;;
    auto) echo "stiffening auto;" ;;
    p0.8all) echo "stiffening power 0.8 inverseDistance ($all);" ;;
    p0.8prescribed) echo "stiffening power 0.8 inverseDistance ($prescribed);" ;;
    p0.8moving) echo "stiffening power 0.8 inverseDistance ($moving);" ;;
    p0.5all) echo "stiffening power 0.5 inverseDistance ($all);" ;;
    p0.6all) echo "stiffening power 0.6 inverseDistance ($all);" ;;
    p1all) echo "stiffening inverseDistance ($all);" ;;
    *) echo "unknown setting $1" >&2; exit 2 ;;
  esac
}
settings=${STIFFENING_SETTINGS:-default none p0.8all p0.8prescribed p0.8moving p0.6all p1all}

diffusivity() { # key case
  local all moving
  all=$(all_patches "$2"); moving=$(moving_patches "$2")
  case $1 in
    uniform) echo "uniform" ;;
    invDist) echo "inverseDistance ($moving)" ;;
    invDistAll) echo "inverseDistance ($all)" ;;
    quadInvDist) echo "quadratic inverseDistance ($moving)" ;;
    invFaceDist) echo "inverseFaceDistance ($moving)" ;;
    invFaceDistAll) echo "inverseFaceDistance ($all)" ;;
    quadInvFaceDist) echo "quadratic inverseFaceDistance ($moving)" ;;
    invVolume) echo "inverseVolume ($moving)" ;;
    *) echo "unknown diffusivity $1" >&2; exit 2 ;;
  esac
}
diffusivities=${DIFFUSIVITIES:-uniform invDist quadInvDist invFaceDist invFaceDistAll quadInvFaceDist}

# A fresh copy of the case's inputs in $work/<case>.
prepare() { # case
  local name=$1 source dir
  source=$here/$(source_of "$name")
  dir=$work/$name
  rm -rf "$dir"
  mkdir -p "$dir"
  cp -r "$source/constant" "$source/system" "$dir/"
  rm -rf "$dir/constant/dynamicMeshDict"
  if [[ $name == blAirfoil* ]]; then
    local angle=${name#blAirfoil}
    mkdir -p "$dir/0"
    cat > "$dir/0/pointDisplacement" <<EOF
FoamFile { version 2.0; format ascii; class pointVectorField; object pointDisplacement; }
dimensions [0 1 0 0 0 0 0];
internalField uniform (0 0 0);
boundaryField
{
    airfoil
    {
        type solidBodyMotionDisplacement;
        solidBodyMotionFunction rotatingMotion;
        rotatingMotionCoeffs { origin (1 0 0); axis (0 0 1); omega $(python3 -c "import math; print(repr(math.radians($angle)))"); }
        value uniform (0 0 0);
    }
    farfield { type fixedValue; value uniform (0 0 0); }
    frontAndBack { type empty; }
}
EOF
  else
    cp -r "$source/0" "$dir/"
  fi
  if [[ $name == naca4415Pitching ]]; then
    sed -i -e 's/^writeInterval .*/writeInterval   1;/' \
      -e "s/^endTime .*/endTime         $(python3 -c "print($pitchingSteps * 0.025)");/" "$dir/system/controlDict"
  fi
  echo "$dir"
}

# The rbm coefficient dictionary: the shipped one's entries (or none) plus `extra`.
write_rbm_dict() { # case dir extra
  local coefficients=""
  if [[ $(coefficient_mode "$1") == shipped ]]; then
    coefficients=$(sed -n '/^rigidBodyMotionSolverCoeffs/,/^}/p' "$here/$(source_of "$1")/constant/dynamicMeshDict" |
                   sed -e '1,2d' -e '$d' | sed -e 's://.*$::' -e '/^ *$/d' -e '/stiffening/d')
  fi
  cat > "$2/constant/dynamicMeshDict" <<EOF
FoamFile { version 2.0; format ascii; class dictionary; object dynamicMeshDict; }
dynamicFvMesh dynamicMotionSolverFvMesh;
motionSolver rigidBodyMotionSolver;
rigidBodyMotionSolverCoeffs
{
$coefficients
    $3
}
EOF
}

write_openfoam_dict() { # dir diffusivity
  cat > "$1/constant/dynamicMeshDict" <<EOF
FoamFile { version 2.0; format ascii; class dictionary; object dynamicMeshDict; }
dynamicFvMesh dynamicMotionSolverFvMesh;
motionSolverLibs ("libfvMotionSolvers.so");
motionSolver displacementLaplacian;
displacementLaplacianCoeffs { diffusivity $2; }
EOF
}

# The worst figures over every time folder: "maxNO maxSkew inverted".
measure() { # dir
  local worstNo=0 worstSkew=0 worstInverted=0 t json
  for t in $(ls "$1" | grep -E '^[0-9.e+-]+$' | grep -v '^0$' | sort -g); do
    json=$("$bin/rbmCheckMesh" -case "$1" -time "$t" -json || true)
    read -r no skew inverted < <(echo "$json" | jq -r '"\(.checkMesh.maxNonOrthogonality) \(.checkMesh.maxSkewness) \(.invertedCells)"')
    worstNo=$(awk -v a="$worstNo" -v b="$no" 'BEGIN { print (b > a ? b : a) }')
    worstSkew=$(awk -v a="$worstSkew" -v b="$skew" 'BEGIN { print (b > a ? b : a) }')
    worstInverted=$(( inverted > worstInverted ? inverted : worstInverted ))
  done
  printf '%.2f° | %.3f | %d' "$worstNo" "$worstSkew" "$worstInverted"
}

run_rbm() { # case setting
  local dir status=ok
  dir=$(prepare "$1")
  write_rbm_dict "$1" "$dir" "$(setting "$2" "$1")"
  "$bin/rbmMoveMesh" -case "$dir" -noVTK > "$dir/log.rbmMoveMesh" 2>&1 || status="exit $?"
  echo "| $1 | rbm \`$(setting "$2" "$1" | sed 's/^$/(default: no entry)/')\` | $(measure "$dir") | $status |"
}

run_openfoam() { # case diffusivity
  local dir status=ok
  dir=$(prepare "$1")
  write_openfoam_dict "$dir" "$(diffusivity "$2" "$1")"
  ( set +u; source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1; moveMesh -case "$dir" > "$dir/log.moveMesh" 2>&1 ) ||
    status="exit $?"
  echo "| $1 | OpenFOAM \`diffusivity $(diffusivity "$2" "$1")\` | $(measure "$dir") | $status |"
}

echo "Measured $(date -u '+%Y-%m-%d %H:%M UTC'), commit $(git -C "$here" rev-parse --short HEAD)$(git -C "$here" diff --quiet HEAD -- motionSolvers apps || echo ' + uncommitted changes'), $(uname -n), $(nproc --all) cores; pitching: $pitchingSteps steps"
echo
echo "| case | method | max non-orthogonality | max skewness | inverted cells | run |"
echo "|---|---|---|---|---|---|"
for c in $cases; do
  if [[ $mode == rbm || $mode == all ]]; then
    done_settings="|"
    for s in $settings; do
      # A setting that spells the same entry as an earlier one for this case is not run again.
      [[ $s == default || $done_settings != *"|$(setting "$s" "$c")|"* ]] || continue
      done_settings+="$(setting "$s" "$c")|"
      run_rbm "$c" "$s"
    done
  fi
  if [[ $mode == openfoam || $mode == all ]]; then
    for d in $diffusivities; do run_openfoam "$c" "$d"; done
  fi
done
