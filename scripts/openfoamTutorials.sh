#!/usr/bin/env bash
# OpenFOAM's own moving-mesh tutorials as rbm's test suite (docs/openfoamTutorials.md).
# For each case: copies the tutorial from Debian's openfoam-examples, makes its mesh (the
# mesh steps of its Allrun only), and moves it with `moveDynamicMesh` (motion only, no flow)
# three times from the same mesh: with rbm's plugin (the user's switch: `motionSolverLibs`
# and `motionSolver` changed, everything else left in place), with the tutorial's own motion
# solver (its dynamicMeshDict as shipped), and held still (`staticFvMesh`, for the loop's own
# cost). Then checkMesh at every written time, and tests/openfoamTutorials/analyse.py
# measures steps, inverted cells, non-orthogonality, plane/axis deviations and the CPU per
# step, and compares each check with tests/openfoamTutorials/expectations.
#
#   scripts/openfoamTutorials.sh [--plugin PATH] [--work DIR] [--cases a,b,c] [--table FILE]
#                                [--emptyCoeffs] [--coeffs TEXT] [--keep]
#
#   --plugin PATH   librbmMotionSolver.so (default build/lib/librbmMotionSolver.so); `none`
#                   or a missing file: every case prints "skipped: ..." and the exit status is 0
#   --work DIR      scratch folder (default: a new mktemp -d, removed at the end unless --keep);
#                   each case works in DIR/<case>, which is emptied first
#   --cases a,b,c   among movingCone waveMakerFlap waveMakerPiston oscillatingBox sphereDrop
#                   (default: all)
#   --table FILE    writes the Markdown table; when FILE holds the markers
#                   `<!-- openfoamTutorials table begin -->` / `... end -->` (as
#                   docs/openfoamTutorials.md does) only the text between them is replaced
#   --emptyCoeffs   also appends `rigidBodyMotionSolverCoeffs { }` to the rbm case's
#                   dynamicMeshDict: only for plugins older than the one that accepts the
#                   other solvers' entries (the table says so); not the user's switch
#   --coeffs TEXT   appends `rigidBodyMotionSolverCoeffs { TEXT }` instead, to measure rbm's
#                   options on the cases (e.g. --coeffs "scaling similar;"); the table's
#                   header says so, and the expectations still apply to the defaults only
#   --openfoamDiffusivity TEXT  sets `diffusivity TEXT;` in OpenFOAM's own runs instead of the
#                   tutorial's (e.g. "uniform": how much its result owes to its tuned
#                   diffusivity); the table's header says so
#
# Exit status: 0 when every check the expectations file marks `pass` passed (a `knownMiss`
# that passes is reported loudly: "NOW PASSES, update expectations"); 1 when one failed;
# 2 on bad arguments. One run at a time (CPU per step is compared): OMP_NUM_THREADS=1.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
commandLine="scripts/openfoamTutorials.sh $*"
plugin=$root/build/lib/librbmMotionSolver.so
work=""
cases=movingCone,waveMakerFlap,waveMakerPiston,oscillatingBox,sphereDrop
table=""
emptyCoeffs=0
coeffs=""
openfoamDiffusivity=""
keep=0
while [[ $# -gt 0 ]]; do
  case $1 in
    --plugin) plugin=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --cases) cases=$2; shift 2 ;;
    --table) table=$2; shift 2 ;;
    --emptyCoeffs) emptyCoeffs=1; shift ;;
    --coeffs) coeffs=$2; shift 2 ;;
    --openfoamDiffusivity) openfoamDiffusivity=$2; shift 2 ;;
    --keep) keep=1; shift ;;
    -h|--help) sed -n '2,/^set -uo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "openfoamTutorials.sh: unknown argument '$1' (--help)" >&2; exit 2 ;;
  esac
done
IFS=, read -r -a caseList <<< "$cases"
allCases=" movingCone waveMakerFlap waveMakerPiston oscillatingBox sphereDrop "
for c in "${caseList[@]}"; do
  [[ $allCases == *" $c "* ]] || { echo "openfoamTutorials.sh: unknown case '$c' (known:$allCases)" >&2; exit 2; }
done
expectations=$root/tests/openfoamTutorials/expectations
examples=/usr/share/doc/openfoam-examples/examples

skipAll() {
  for c in "${caseList[@]}"; do echo "$c: skipped: $1"; done
  exit 0
}

# --- What is needed, or a visible skip ------------------------------------------------------
if [[ $plugin == none || ! -f $plugin ]]; then
  skipAll "OpenFOAM not installed (the plugin librbmMotionSolver.so was not built: '$plugin'; scripts/setup.sh installs libopenfoam and fetches its headers)"
fi
plugin=$(cd "$(dirname "$plugin")" && pwd)/$(basename "$plugin")
for tool in moveDynamicMesh checkMesh blockMesh; do
  command -v $tool >/dev/null || skipAll "OpenFOAM not installed ($tool not found; apt-get install openfoam, done by scripts/setup.sh)"
done
if ! dpkg-query -W -f='${Status}' openfoam-examples 2>/dev/null | grep -q "install ok installed"; then
  if [[ $(id -u) == 0 ]]; then
    echo "openfoamTutorials: installing openfoam-examples"
    export DEBIAN_FRONTEND=noninteractive
    { apt-get update -qq && apt-get install -y -qq --no-install-recommends openfoam-examples; } >/dev/null 2>&1
  fi
fi
[[ -d $examples ]] || skipAll "OpenFOAM's tutorials not installed ($examples; apt-get install openfoam-examples, done by scripts/setup.sh)"

export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
if [[ -z $work ]]; then
  work=$(mktemp -d /tmp/openfoamTutorials.XXXXXX)
  [[ $keep == 1 ]] || trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work"
work=$(cd "$work" && pwd)

# --- The cases ----------------------------------------------------------------------------------
# source folder | kind (run: both solvers; refuse: rbm must stop naming a patch) | deltaT |
# steps | write every N steps | static-loop steps
caseSpec() {
  case $1 in
    movingCone)     echo "incompressible/pimpleFoam/laminar/movingCone run 5e-06 600 10 100" ;;
    waveMakerFlap)  echo "multiphase/interFoam/laminar/waves/waveMakerFlap run 0.005 50 2 20" ;;
    waveMakerPiston) echo "multiphase/interFoam/laminar/waves/waveMakerPiston run 0.005 20 2 20" ;;
    oscillatingBox) echo "multiphase/potentialFreeSurfaceDyMFoam/oscillatingBox run 0.001 1000 20 100" ;;
    sphereDrop)     echo "multiphase/compressibleInterDyMFoam/laminar/sphereDrop refuse 5e-05 5 1 0" ;;
  esac
}

# Mesh generation: the mesh steps of each tutorial's Allrun, nothing else (no setFields, no flow).
makeMesh() {
  case $1 in
    movingCone|waveMakerFlap|waveMakerPiston) blockMesh ;;
    oscillatingBox)
      blockMesh && topoSet && subsetMesh -overwrite c0 -patch floatingObject &&
        topoSet -dict system/topoSetDict-selectBottom && createPatch -overwrite ;;
    sphereDrop)
      blockMesh && topoSet && createPatch -overwrite && mergeOrSplitBaffles -overwrite &&
        (cd constant/polyMesh && ln -sf ../../include/meshModifiers .) ;;
  esac
}

# Changes for a motion-only run, made to every copy alike: a bounded number of steps at the
# tutorial's deltaT, writing every N steps; the waves' boundary condition library (interFoam
# links it, moveDynamicMesh does not).
setControl() { # dir deltaT steps writeEvery
  local endTime
  endTime=$(python3 -c "print(repr($2 * $3))")
  sed -i -E -e "s/^(endTime[[:space:]]+)[^;]*;/\1$endTime;/" -e "s/^(deltaT[[:space:]]+)[^;]*;/\1$2;/" \
            -e "s/^(writeControl[[:space:]]+)[^;]*;/\1timeStep;/" -e "s/^(writeInterval[[:space:]]+)[^;]*;/\1$4;/" \
            -e "s/^(stopAt[[:space:]]+)[^;]*;/\1endTime;/" -e "s/^(startFrom[[:space:]]+)[^;]*;/\1startTime;/" \
            "$1/system/controlDict"
  if [[ $(basename "$(dirname "$1")") == waveMaker* ]]; then
    sed -i -E '/^application/a libs            (waveModels);' "$1/system/controlDict"
  fi
}

# The user's switch to rbm: the library and the solver's name; nothing else touched.
switchToRbm() { # dir
  local dict=$1/constant/dynamicMeshDict
  if grep -qE '^[[:space:]]*motionSolverLibs' "$dict"; then
    sed -i -E "s|^([[:space:]]*motionSolverLibs[[:space:]]+).*|\1(\"$plugin\");|" "$dict"
  else
    echo "motionSolverLibs (\"$plugin\");" >> "$dict"
  fi
  sed -i -E "s/^([[:space:]]*(motionSolver|solver)[[:space:]]+)[A-Za-z0-9_]+;/\1rigidBodyMotionSolver;/" "$dict"
  if [[ -n $coeffs ]]; then echo "rigidBodyMotionSolverCoeffs { $coeffs }" >> "$dict"
  elif [[ $emptyCoeffs == 1 ]]; then echo 'rigidBodyMotionSolverCoeffs { }' >> "$dict"; fi
}

copyCase() { # from to
  rm -rf "$2" && mkdir -p "$2" && cp -a "$1/constant" "$1/system" "$1/0" "$2/"
}

# moveDynamicMesh, then checkMesh of every written time, then the measurements.
runMotion() { # dir mode(run|baseline) classifyField
  local dir=$1 rc
  (cd "$dir" && timeout 600 moveDynamicMesh -noFunctionObjects > log.moveDynamicMesh 2>&1)
  rc=$?
  echo "rc=$rc" > "$dir/result"
  if [[ $2 == run ]]; then
    (cd "$dir" && timeout 600 checkMesh -noFunctionObjects -noZero > log.checkMesh 2>&1)
    python3 "$root/tests/openfoamTutorials/analyse.py" run "$dir" "$3" >> "$dir/result"
  else
    python3 "$root/tests/openfoamTutorials/analyse.py" baseline "$dir" >> "$dir/result"
  fi
}

runCase() { # name
  local name=$1 spec src kind dt steps every staticSteps dir
  spec=$(caseSpec "$name")
  read -r src kind dt steps every staticSteps <<< "$spec"
  dir=$work/$name
  rm -rf "$dir" && mkdir -p "$dir"
  cp -a "$examples/$src" "$dir/tutorial"
  find "$dir/tutorial" -name '*.gz' -exec gunzip -f {} +
  {
    echo "kind=$kind"; echo "source=$src"; echo "planned=$steps"; echo "deltaT=$dt"; echo "writeEvery=$every"
  } > "$dir/meta"
  (cd "$dir/tutorial" && makeMesh "$name") > "$dir/log.mesh" 2>&1 || {
    echo "meshError=1" >> "$dir/meta"; return; }
  if [[ -d $dir/tutorial/0.orig ]]; then rm -rf "$dir/tutorial/0" && cp -a "$dir/tutorial/0.orig" "$dir/tutorial/0"; fi
  setControl "$dir/tutorial" "$dt" "$steps" "$every"
  grep -ao 'nCells:[0-9]*' "$dir/tutorial/constant/polyMesh/owner" | head -n 1 | sed 's/nCells:/cells=/' >> "$dir/meta"

  copyCase "$dir/tutorial" "$dir/rbm"
  if [[ -d $root/tests/openfoamTutorials/$name ]]; then
    cp -a "$root/tests/openfoamTutorials/$name/." "$dir/rbm/0/"
  fi
  switchToRbm "$dir/rbm"
  runMotion "$dir/rbm" run "$dir/rbm/0/pointDisplacement"

  if [[ $kind == run ]]; then
    copyCase "$dir/tutorial" "$dir/openfoam"
    if [[ -n $openfoamDiffusivity ]]; then
      sed -i -E "s/^([[:space:]]*diffusivity[[:space:]]+).*;/\1$openfoamDiffusivity;/" "$dir/openfoam/constant/dynamicMeshDict"
    fi
    runMotion "$dir/openfoam" run "$dir/rbm/0/pointDisplacement"
    copyCase "$dir/tutorial" "$dir/static"
    setControl "$dir/static" "$dt" "$staticSteps" 100000000
    sed -i -E 's/^([[:space:]]*dynamicFvMesh[[:space:]]+)[A-Za-z]+;/\1staticFvMesh;/' "$dir/static/constant/dynamicMeshDict"
    runMotion "$dir/static" baseline ""
  fi
}

start=$(date +%s)
for c in "${caseList[@]}"; do
  caseStart=$(date +%s)
  runCase "$c"
  echo "wallSeconds=$(( $(date +%s) - caseStart ))" >> "$work/$c/meta"
done
total=$(( $(date +%s) - start ))

commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
if [[ -n $(git -C "$root" status --porcelain 2>/dev/null) ]]; then commit="$commit + uncommitted changes"; fi
cpu=$(lscpu 2>/dev/null | sed -n 's/^Model name:[[:space:]]*//p' | head -n 1)
cores=$(lscpu 2>/dev/null | sed -n "s/^CPU(s):[[:space:]]*//p" | head -n 1)
pluginStamp="$(basename "$plugin") $(date -u -r "$plugin" '+%Y-%m-%d %H:%M:%S UTC'), sha256 $(sha256sum "$plugin" | cut -c1-12)"
python3 "$root/tests/openfoamTutorials/analyse.py" report "$work" "$cases" "$expectations" "${table:--}" \
  "$commit" "$(date -u '+%Y-%m-%d %H:%M UTC')" "$cpu, $cores cores, load $(cut -d' ' -f1-3 /proc/loadavg)" \
  "$commandLine" "$total" "$pluginStamp" "$emptyCoeffs" "$coeffs" "$openfoamDiffusivity"
