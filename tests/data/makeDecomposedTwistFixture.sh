#!/bin/bash
# Regenerates tests/data/decomposedTwist/np2 and np4 with OpenFOAM v1912: a column of 10 x 8 x 12
# hexahedra (two blocks of 5 x 8 x 12) whose bottom is fixed and whose top is two patches: the
# lid (x < 0.05) turns 20 degrees about its vertical centre line (angularOscillatingDisplacement,
# at its largest at t = 1: two steps of 0.5), the rest of the top and the four sides (xMin, xMax,
# yMin, yMax) are zeroGradient, so rbm slides them in their planes, and the column's vertical
# edges on the lines where two meet. decomposePar splits it (method manual) at x = 0.05, the
# lid's edge, with x < 0.05 on processor 1: the points of the lid's edge are owned by processor
# 0, which has no lid face, so only the exchange of patch membership makes them prescribed; for
# 4 processors each half is cut again along the staircase i + 2j + k = 14 (processors 2 and 3),
# through the sides and their edges, points held by up to four processors. Each case keeps its undecomposed constant/polyMesh and 0/pointDisplacement, so that
# the tests compare the decomposed run with the serial one. Not run by the tests (rbm never
# needs OpenFOAM); run it by hand after changing the case:
#     tests/data/makeDecomposedTwistFixture.sh
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
header() {   # $1 class, $2 object
    printf 'FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       %s;\n    object      %s;\n}\n' "$1" "$2"
}
for ranks in 2 4; do
    work="$(mktemp -d)"
    mkdir -p "$work/system" "$work/constant" "$work/0"
    { header dictionary controlDict; cat <<'DICT'
application     moveDynamicMesh;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         1;
deltaT          0.5;
writeControl    timeStep;
writeInterval   1;
writeFormat     ascii;
writePrecision  12;
writeCompression off;
timeFormat      general;
timePrecision   6;
DICT
    } > "$work/system/controlDict"
    { header dictionary blockMeshDict; cat <<'DICT'
scale 0.1;
vertices ((0 0 0) (1 0 0) (1 0.8 0) (0 0.8 0) (0 0 1.2) (1 0 1.2) (1 0.8 1.2) (0 0.8 1.2)
          (0.5 0 0) (0.5 0.8 0) (0.5 0 1.2) (0.5 0.8 1.2));
blocks
(
    hex (0 8 9 3 4 10 11 7) (5 8 12) simpleGrading (1 2 1)
    hex (8 1 2 9 10 5 6 11) (5 8 12) simpleGrading (1 2 1)
);
boundary
(
    bottom { type wall; faces ((0 3 9 8) (8 9 2 1)); }
    lid { type wall; faces ((4 10 11 7)); }
    top { type wall; faces ((10 5 6 11)); }
    xMin { type patch; faces ((0 4 7 3)); }
    xMax { type patch; faces ((1 2 6 5)); }
    yMin { type patch; faces ((0 8 10 4) (8 1 5 10)); }
    yMax { type patch; faces ((3 7 11 9) (9 11 6 2)); }
);
DICT
    } > "$work/system/blockMeshDict"
    { header dictionary decomposeParDict; cat <<DICT
numberOfSubdomains $ranks;
method          manual;
coeffs          { dataFile "cellDecomposition"; }
DICT
    } > "$work/system/decomposeParDict"
    { header dictionary dynamicMeshDict; cat <<'DICT'
dynamicFvMesh   dynamicMotionSolverFvMesh;
motionSolverLibs ("librbmMotionSolver.so");
motionSolver    rigidBodyMotionSolver;
DICT
    } > "$work/constant/dynamicMeshDict"
    { header pointVectorField pointDisplacement; cat <<'DICT'
dimensions      [0 1 0 0 0 0 0];
internalField   uniform (0 0 0);
boundaryField
{
    bottom { type fixedValue; value uniform (0 0 0); }
    lid
    {
        type            angularOscillatingDisplacement;
        axis            (0 0 1);
        origin          (0.025 0.04 0);
        angle0          0;
        amplitude       0.3490658503988659;
        omega           1.5707963267948966;
        value           uniform (0 0 0);
    }
    "(top|(x|y)M.*)" { type zeroGradient; }
}
DICT
    } > "$work/0/pointDisplacement"
    ( cd "$work" && blockMesh > log.blockMesh )
    python3 - "$work/constant/cellDecomposition" "$ranks" <<'PY'
import sys
path, ranks = sys.argv[1], int(sys.argv[2])
labels = []
for block in range(2):
    for k in range(12):
        for j in range(8):
            for i in range(5 * block, 5 * block + 5):
                r = int(i < 5)
                if ranks == 4:
                    r += 2 * int(i + 2 * j + k >= 14)
                labels.append(r)
with open(path, "w") as f:
    f.write("FoamFile\n{\n    version 2.0;\n    format ascii;\n    class labelList;\n    object cellDecomposition;\n}\n")
    f.write("%d\n(\n%s\n)\n" % (len(labels), "\n".join(map(str, labels))))
PY
    ( cd "$work" && decomposePar > log.decomposePar )
    out="$here/decomposedTwist/np$ranks"
    rm -rf "$out"
    mkdir -p "$out/constant"
    cp -r "$work/system" "$work/0" "$out/"
    cp -r "$work/constant/polyMesh" "$work/constant/dynamicMeshDict" "$out/constant/"
    for ((p = 0; p < ranks; ++p)); do
        mkdir -p "$out/processor$p/constant"
        cp -r "$work/processor$p/0" "$out/processor$p/"
        cp -r "$work/processor$p/constant/polyMesh" "$out/processor$p/constant/"
        rm -f "$out/processor$p/constant/polyMesh/"{cellProcAddressing,faceProcAddressing,boundaryProcAddressing}
    done
    rm -rf "$work"
    echo "wrote $out"
done
