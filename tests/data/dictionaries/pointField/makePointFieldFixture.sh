#!/bin/bash
# Regenerates the pointVectorField fixtures of tests/io/PointVectorFieldTest.cpp with OpenFOAM
# v1912. Not run by the tests (rbm never needs OpenFOAM); run it by hand:
#     tests/data/dictionaries/pointField/makePointFieldFixture.sh
#
# Mesh: blockMesh, one block of 4 x 2 x 1 cells on [0,2] x [0,1] x [0,0.1] (30 points).
#   patches: inlet (patch), outlet (patch), lowerWall (wall, inGroups movingWalls wall),
#            upperWall (wall, inGroups wall), frontAndBack (empty)
# 0/pointDisplacement mixes every way an entry can apply (see the file): regular
# expressions, groups, names, and a nonuniform value on upperWall (10 points).
# moveMesh (displacementLaplacian) then writes 1/pointDisplacement with one explicit entry
# per patch: what OpenFOAM itself resolved. The run is done twice:
#   ascii/    writeFormat ascii  (0/, 1/ and constant/polyMesh kept)
#   binary/   writeFormat binary (only 1/pointDisplacement kept: binary internalField)
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

makeCase() {   # $1 case folder, $2 ascii|binary
    local c="$1"
    mkdir -p "$c/system" "$c/constant" "$c/0"
    cat > "$c/system/controlDict" <<DICT
FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application moveMesh; startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1;
writeControl timeStep; writeInterval 1; writeFormat $2; writePrecision 6; writeCompression off;
timeFormat general; timePrecision 6;
DICT
    cat > "$c/system/blockMeshDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }
scale 1;
vertices ( (0 0 0) (2 0 0) (2 1 0) (0 1 0) (0 0 0.1) (2 0 0.1) (2 1 0.1) (0 1 0.1) );
blocks ( hex (0 1 2 3 4 5 6 7) (4 2 1) simpleGrading (1 1 1) );
boundary
(
    inlet { type patch; faces ((0 4 7 3)); }
    outlet { type patch; faces ((2 6 5 1)); }
    lowerWall { type wall; inGroups (movingWalls); faces ((1 5 4 0)); }
    upperWall { type wall; faces ((3 7 6 2)); }
    frontAndBack { type empty; faces ((0 3 2 1) (4 5 6 7)); }
);
DICT
    cat > "$c/system/fvSchemes" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }
ddtSchemes { default Euler; } gradSchemes { default Gauss linear; } divSchemes { default none; }
laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
DICT
    cat > "$c/system/fvSolution" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }
solvers { "cellDisplacement.*" { solver PCG; preconditioner DIC; tolerance 1e-12; relTol 0; } }
DICT
    cat > "$c/constant/dynamicMeshDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object dynamicMeshDict; }
dynamicFvMesh dynamicMotionSolverFvMesh;
motionSolverLibs ("libfvMotionSolvers.so");
motionSolver displacementLaplacian;
displacementLaplacianCoeffs { diffusivity uniform; }
DICT
    cat > "$c/0/pointDisplacement" <<'DICT'
FoamFile
{
    version     2.0;
    format      ascii;
    class       pointVectorField;
    object      pointDisplacement;
}

dimensions      [0 1 0 0 0 0 0];

internalField   uniform (0 0 0);

boundaryField
{
    // Every patch matches this expression; it applies only where nothing else does.
    ".*"
    {
        type            fixedValue;
        value           uniform (9 9 9);
    }
    // Group of lowerWall and upperWall: groups come before expressions.
    wall
    {
        type            fixedValue;
        value           uniform (1 0 0);
    }
    // Second group of lowerWall: the later group entry wins.
    movingWalls
    {
        type            fixedValue;
        value           uniform (2 0 0);
    }
    // The later expression wins over ".*" for inlet; outlet has its own entry below.
    "(inlet|outlet)"
    {
        type            fixedValue;
        value           uniform (3 0 0);
    }
    outlet
    {
        type            fixedValue;
        value           uniform (4 0 0);
    }
    // The patch name wins over the groups; one value per patch point, in OpenFOAM's order.
    upperWall
    {
        type            fixedValue;
        value           nonuniform List<vector> 10
        (
            (0.5 0 0) (0.51 0 0) (0.52 0 0) (0.53 0 0) (0.54 0 0)
            (0.55 0 0) (0.56 0 0) (0.57 0 0) (0.58 0 0) (0.59 0 0)
        );
    }
    // frontAndBack (empty) has no entry: it is empty.
}
DICT
    (cd "$c" && blockMesh > log.blockMesh 2>&1 && moveMesh > log.moveMesh 2>&1)
}

makeCase "$work/ascii" ascii
makeCase "$work/binary" binary

rm -rf "$here/ascii" "$here/binary"
mkdir -p "$here/ascii/constant" "$here/ascii/0" "$here/ascii/1" "$here/binary/1"
cp -r "$work/ascii/constant/polyMesh" "$here/ascii/constant/"
cp "$work/ascii/0/pointDisplacement" "$here/ascii/0/"
cp "$work/ascii/1/pointDisplacement" "$here/ascii/1/"
cp "$work/binary/1/pointDisplacement" "$here/binary/1/"
echo "fixtures written to $here"
