#!/bin/bash
# Regenerates tests/data/decomposed/ with OpenFOAM v1912: a box of 6 x 5 x 4 hexahedra
# (y graded, so coordinates are not short decimals) split by decomposePar into 4 processors,
# method simple (2 2 1): the four parts meet around a vertical edge, so points there are held
# by four processors. Kept: constant/polyMesh (the whole mesh) and every
# processorN/constant/polyMesh with its pointProcAddressing, faceProcAddressing,
# cellProcAddressing and boundaryProcAddressing. Not run by the tests (rbm never needs
# OpenFOAM); run it by hand after changing the mesh:
#     tests/data/makeDecomposedFixture.sh
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
out="$here/decomposed"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
header() {   # $1 object
    printf 'FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       dictionary;\n    object      %s;\n}\n' "$1"
}
mkdir -p "$work/system" "$work/constant"
{ header controlDict; cat <<'DICT'
application     moveMesh;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         1;
deltaT          1;
writeControl    timeStep;
writeInterval   1;
writeFormat     ascii;
writePrecision  10;
writeCompression off;
timeFormat      general;
DICT
} > "$work/system/controlDict"
{ header blockMeshDict; cat <<'DICT'
scale 0.1;
vertices ((0 0 0) (1.2 0 0) (1.2 1 0) (0 1 0) (0 0 0.8) (1.2 0 0.8) (1.2 1 0.8) (0 1 0.8));
blocks (hex (0 1 2 3 4 5 6 7) (6 5 4) simpleGrading (1 3 1));
boundary
(
    bottom { type wall; faces ((0 3 2 1)); }
    top { type wall; faces ((4 5 6 7)); }
    sides { type patch; faces ((0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2)); }
);
DICT
} > "$work/system/blockMeshDict"
{ header decomposeParDict; cat <<'DICT'
numberOfSubdomains 4;
method          simple;
coeffs { n (2 2 1); }
DICT
} > "$work/system/decomposeParDict"
( cd "$work" && blockMesh > log.blockMesh && decomposePar > log.decomposePar )
rm -rf "$out"
mkdir -p "$out/constant"
cp -r "$work/constant/polyMesh" "$out/constant/"
for p in 0 1 2 3; do
    mkdir -p "$out/processor$p/constant"
    cp -r "$work/processor$p/constant/polyMesh" "$out/processor$p/constant/"
done
cp -r "$work/system" "$out/"
echo "wrote $out"
