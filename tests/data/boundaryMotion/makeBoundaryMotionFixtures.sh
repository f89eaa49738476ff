#!/bin/bash
# Regenerates the OpenFOAM v1912 reference motions used by tests/motionSolvers/boundaryMotion/.
# Each case folder holds its inputs (system/, constant/, 0/) and the points OpenFOAM's
# moveDynamicMesh wrote at the times it ran; the test applies rbm's motion laws to
# constant/polyMesh/points and compares. Run from anywhere with OpenFOAM v1912 installed:
#   tests/data/boundaryMotion/makeBoundaryMotionFixtures.sh
set -eo pipefail
cd "$(dirname "$0")"
source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1 || true
set -u

header() { # class object location
cat <<HDR
FoamFile
{
    version     2.0;
    format      ascii;
    class       $1;
    location    "$3";
    object      $2;
}
HDR
}

newCase() { # case cellsPerDirection endTime deltaT
rm -rf "$1"
mkdir -p "$1/system" "$1/constant"
{ header dictionary blockMeshDict system; cat <<BM
// A cube, slightly sheared so that no coordinate is special; the bottom side (y min) is a
// planar parallelogram with outward normal along (0.1 -1 0.1), the front side (z min) is not planar.
vertices
(
    (0 0 0) (1 0.1 0) (1.1 1.2 0.1) (0.1 1 0)
    (0 0.1 1) (1 0.2 1) (1 1.1 1) (0.2 1 0.9)
);
blocks ( hex (0 1 2 3 4 5 6 7) ($2 $2 $2) simpleGrading (1 1 1) );
boundary
(
    left   { type patch; faces ((0 4 7 3)); }
    right  { type patch; faces ((1 2 6 5)); }
    bottom { type wall;  faces ((0 1 5 4)); }
    top    { type patch; faces ((3 7 6 2)); }
    front  { type patch; faces ((0 3 2 1)); }
    back   { type patch; faces ((4 5 6 7)); }
);
BM
} > "$1/system/blockMeshDict"
{ header dictionary controlDict system; cat <<CD
application     moveDynamicMesh;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         $3;
deltaT          $4;
writeControl    timeStep;
writeInterval   1;
purgeWrite      0;
writeFormat     ascii;
writePrecision  17;
writeCompression off;
timeFormat      general;
timePrecision   6;
runTimeModifiable false;
CD
} > "$1/system/controlDict"
{ header dictionary fvSchemes system; cat <<FS
ddtSchemes { default Euler; }
gradSchemes { default Gauss linear; }
divSchemes { default none; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
FS
} > "$1/system/fvSchemes"
{ header dictionary fvSolution system; cat <<FV
solvers
{
    "cellDisplacement.*" { solver PCG; preconditioner DIC; tolerance 1e-12; relTol 0; }
}
FV
} > "$1/system/fvSolution"
}

runCase() { # case [keepMesh]
(cd "$1" && blockMesh > log.blockMesh 2>&1 && moveDynamicMesh > log.moveDynamicMesh 2>&1) || { cat "$1/log.moveDynamicMesh"; exit 1; }
rm -f "$1"/log.*
# Solid-body cases need only the reference points.
if [ "${2:-}" != keepMesh ]; then
    find "$1/constant/polyMesh" -type f ! -name points -delete
fi
# Keep only the moved points of every time folder.
for t in "$1"/[0-9]*; do
    [ "$t" = "$1/0" ] && continue
    find "$t" -mindepth 1 ! -path "$t/polyMesh" ! -path "$t/polyMesh/points" -delete 2>/dev/null || true
done
}

solidBodyCase() { # case coefficients-text
newCase "$1" 2 1 0.25
{ header dictionary dynamicMeshDict constant; cat <<DM
dynamicFvMesh   dynamicMotionSolverFvMesh;
motionSolverLibs ("libfvMotionSolvers.so");
motionSolver    solidBody;
solidBodyCoeffs
{
$2
}
DM
} > "$1/constant/dynamicMeshDict"
}

solidBodyCase multiRotationTranslation '
    solidBodyMotionFunction multiMotion;
    multiMotionCoeffs
    {
        rotation
        {
            solidBodyMotionFunction rotatingMotion;
            rotatingMotionCoeffs { origin (0.5 0.5 0); axis (0 0 1); omega 1.5707963267948966; }
        }
        translation
        {
            solidBodyMotionFunction linearMotion;
            linearMotionCoeffs { velocity (1 0 0); }
        }
    }'
runCase multiRotationTranslation

solidBodyCase multiTranslationRotation '
    solidBodyMotionFunction multiMotion;
    multiMotionCoeffs
    {
        translation
        {
            solidBodyMotionFunction linearMotion;
            linearMotionCoeffs { velocity (1 0 0); }
        }
        rotation
        {
            solidBodyMotionFunction rotatingMotion;
            rotatingMotionCoeffs { origin (0.5 0.5 0); axis (0 0 1); omega 1.5707963267948966; }
        }
    }'
runCase multiTranslationRotation

solidBodyCase oscillatingRotation '
    solidBodyMotionFunction oscillatingRotatingMotion;
    oscillatingRotatingMotionCoeffs { origin (0.5 0.4 0.3); amplitude (10 20 30); omega 2; }'
runCase oscillatingRotation

solidBodyCase rotationPolynomialOmega '
    solidBodyMotionFunction rotatingMotion;
    origin (0.2 0.3 0.4);
    axis   (1 1 1);
    omega  polynomial ((1 0) (2 1));'
runCase rotationPolynomialOmega

solidBodyCase rotationTableOmega '
    solidBodyMotionFunction rotatingMotion;
    rotatingMotionCoeffs
    {
        origin (0 0 0);
        axis   (0 1 0);
        omega  table ((0 0) (0.5 2) (1 1));
    }'
runCase rotationTableOmega

solidBodyCase tabulated6DoF '
    solidBodyMotionFunction tabulated6DoFMotion;
    tabulated6DoFMotionCoeffs
    {
        CofG             (0.5 0.5 0.5);
        timeDataFileName "$FOAM_CASE/constant/6DoF.dat";
    }'
cat > tabulated6DoF/constant/6DoF.dat <<'DAT'
// time ((translation) (rotation in degrees)): not linear in time, so the Catmull-Rom
// interpolation of OpenFOAM's interpolateSplineXY differs from linear interpolation.
4
(
    (0    ((0 0 0)        (0 0 0)))
    (0.4  ((0.1 0.05 0)   (5 -10 15)))
    (0.7  ((0.3 0.1 0.2)  (20 5 -10)))
    (1.0  ((0.2 0.4 0.1)  (30 30 30)))
)
DAT
runCase tabulated6DoF

# Point-patch boundary conditions of pointDisplacement, moved by displacementLaplacian. The
# test compares the points that belong to one patch only (shared edge points take the value of
# whichever patch OpenFOAM evaluates last).
newCase pointPatchConditions 4 1 0.5
{ header dictionary dynamicMeshDict constant; cat <<DM
dynamicFvMesh   dynamicMotionSolverFvMesh;
motionSolverLibs ("libfvMotionSolvers.so");
motionSolver    displacementLaplacian;
displacementLaplacianCoeffs { diffusivity uniform; }
DM
} > pointPatchConditions/constant/dynamicMeshDict
mkdir -p pointPatchConditions/0
bottomValues=$(awk 'BEGIN { for (i = 0; i < 25; ++i) printf "(%g %g %g)\n", 0.01*i, -0.002*i*i, 0.003*(i%7) }')
{ header pointVectorField pointDisplacement 0; cat <<PD
dimensions      [0 1 0 0 0 0 0];
internalField   uniform (0 0 0);
boundaryField
{
    left
    {
        type            angularOscillatingDisplacement;
        axis            (0 0.2 1);
        origin          (0.5 0.5 0.5);
        angle0          0.1;
        amplitude       0.3;
        omega           3;
        value           uniform (0 0 0);
    }
    right
    {
        type            oscillatingDisplacement;
        amplitude       (0.1 0.2 0.05);
        omega           2;
        value           uniform (0 0 0);
    }
    top
    {
        type            uniformFixedValue;
        uniformValue    table ((0 (0 0 0)) (1 (0.1 0.2 0.3)));
    }
    bottom
    {
        // One distinct vector per patch point, in the patch's localPoints order.
        type            fixedValue;
        value           nonuniform List<vector> 25
(
$bottomValues
);
    }
    front
    {
        type            solidBodyMotionDisplacement;
        solidBodyMotionFunction rotatingMotion;
        rotatingMotionCoeffs { origin (0.5 0.5 0); axis (0 0 1); omega 0.5; }
        value           uniform (0 0 0);
    }
    back
    {
        type            fixedValue;
        value           uniform (0 0 0);
    }
}
PD
} > pointPatchConditions/0/pointDisplacement
runCase pointPatchConditions keepMesh
