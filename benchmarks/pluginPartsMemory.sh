#!/usr/bin/env bash
# Peak memory per rank of the OpenFOAM plugin in a decomposed 3D run, distributed path (each
# rank solves its own part) against the gathered path (RBM_PLUGIN_GATHER=1: every rank holds
# the whole mesh), on one build: a unit cube of N³ hexahedra (blockMesh), its top (patch lid) turned 20°
# about the vertical centre line in one step, the bottom fixed, the four sides zeroGradient
# and floating (floatingPatches: sliding sides would leave the top's edges, which turn out of
# their planes, to crush the cells below them), decomposed by decomposePar (method simple,
# RANKS 1 1), `mpirun -np RANKS moveDynamicMesh -parallel` with /usr/bin/time -v around each
# rank. Measures, asserts nothing; prints the plugin's lines and one line per path and rank.
#   benchmarks/pluginPartsMemory.sh PLUGIN N [WORK_DIR [RANKS]]
# PLUGIN: the full path of librbmMotionSolver.so; RANKS: 2 by default.
set -euo pipefail
plugin="$1"
n="$2"
work="${3:-$(mktemp -d)}"
ranks="${4:-2}"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
mpiOptions=(-np "$ranks" --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpiOptions+=(--allow-run-as-root)
# The inputs of tests/data/decomposedTwist/np2 (its lid's condition, sides, controlDict) on the
# cube: one step, the lid's axis at the cube's centre, decomposePar's method simple.
source="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
fixture="$source/tests/data/decomposedTwist/np2"
cube="$source/tutorials/cube"
case="$work/cube$n-np$ranks"
rm -rf "$case"
mkdir -p "$case/system" "$case/constant" "$case/0"
sed -e 's/^deltaT .*/deltaT          1;/' -e 's/^writeFormat .*/writeFormat     binary;/' \
    "$fixture/system/controlDict" > "$case/system/controlDict"
sed -e 's/(0.025 0.04 0)/(0.5 0.5 0)/' "$fixture/0/pointDisplacement" > "$case/0/pointDisplacement"
sed -e "s#^motionSolverLibs.*#motionSolverLibs (\"$plugin\");#" "$fixture/constant/dynamicMeshDict" > "$case/constant/dynamicMeshDict"
echo 'rigidBodyMotionSolverCoeffs { floatingPatches (xMin xMax yMin yMax); }' >> "$case/constant/dynamicMeshDict"
sed -e "s/^numberOfSubdomains .*/numberOfSubdomains $ranks;/" -e 's/^method .*/method          simple;/' \
    -e "s/^coeffs .*/coeffs          { n ($ranks 1 1); delta 0.001; }/" \
    "$fixture/system/decomposeParDict" > "$case/system/decomposeParDict"
cp "$cube/system/fvSchemes" "$cube/system/fvSolution" "$case/system/"
cat > "$case/system/blockMeshDict" <<DICT
FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }
vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 1) (1 0 1) (1 1 1) (0 1 1));
blocks (hex (0 1 2 3 4 5 6 7) ($n $n $n) simpleGrading (1 1 1));
boundary
(
    bottom { type wall; faces ((0 3 2 1)); }
    lid { type wall; faces ((4 5 6 7)); }
    xMin { type patch; faces ((0 4 7 3)); }
    xMax { type patch; faces ((1 2 6 5)); }
    yMin { type patch; faces ((0 1 5 4)); }
    yMax { type patch; faces ((3 7 6 2)); }
);
DICT
(cd "$case" && blockMesh > log.blockMesh && decomposePar > log.decomposePar)

for path in distributed gathered; do
    rm -rf "$case"/processor*/1
    gather=0
    [ "$path" = gathered ] && gather=1
    (cd "$case" && RBM_PLUGIN_GATHER=$gather mpirun "${mpiOptions[@]}" -x WM_PROJECT_DIR -x RBM_PLUGIN_GATHER \
        sh -c "/usr/bin/time -v -o log.time.$path.\$OMPI_COMM_WORLD_RANK moveDynamicMesh -parallel" > "log.$path" 2>&1) ||
        { echo "$path: moveDynamicMesh failed, see $case/log.$path"; exit 1; }
    grep -h "rigidBodyMotionSolver" "$case/log.$path"
    for ((rank = 0; rank < ranks; ++rank)); do
        echo "$path rank $rank: $(grep -h 'Maximum resident' "$case/log.time.$path.$rank" | sed 's/.*: //') kB peak," \
             "$(grep -h 'Elapsed (wall' "$case/log.time.$path.$rank" | sed 's/.*: //') wall"
    done
done
