#!/bin/bash
# Regenerates the committed malformed inputs of tests/apps/MalformedCaseTest.cpp. Not run by the
# tests; run it by hand after changing it (needs OpenFOAM v1912's blockMesh and python3):
#     tests/data/malformedCases/makeMalformedCases.sh
#
# base/: a valid rbmMoveMesh case, 3 x 2 cells x 1 layer on [0,3] x [0,2] x [0,0.1] by
#   blockMesh (24 points, 29 faces: 7 internal, then left 2, right 2, bottom 3, top 3,
#   frontAndBack 12; 6 cells), written ascii; the left side moves, the right is fixed, top and
#   bottom slide. One time step, 0 -> 0.1.
# <name>/: only the files that differ from base/, each spoilt in one way (see spoil() below);
#   the test copies base/, lays <name>/ over it (and removes the files listed in the test),
#   runs rbmMoveMesh and checks the message (file, line or entry, what was expected), the exit
#   status and that the case folder did not change.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
base="$here/base"
rm -rf "$base"
mkdir -p "$base/system" "$base/constant" "$base/0"

header() {   # $1 class, $2 location, $3 object
    cat <<DICT
FoamFile
{
    version     2.0;
    format      ascii;
    class       $1;
    location    "$2";
    object      $3;
}
DICT
}

{ header dictionary system controlDict; cat <<'DICT'
application     rbmMoveMesh;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         0.1;
deltaT          0.1;
writeControl    timeStep;
writeInterval   1;
writeFormat     ascii;
writePrecision  6;
writeCompression off;
timeFormat      general;
timePrecision   6;
DICT
} > "$base/system/controlDict"

{ header dictionary system blockMeshDict; cat <<'DICT'
scale 1;
vertices ((0 0 0) (3 0 0) (3 2 0) (0 2 0) (0 0 0.1) (3 0 0.1) (3 2 0.1) (0 2 0.1));
blocks (hex (0 1 2 3 4 5 6 7) (3 2 1) simpleGrading (1 1 1));
boundary
(
    left { type patch; faces ((0 4 7 3)); }
    right { type patch; faces ((1 2 6 5)); }
    bottom { type wall; faces ((0 1 5 4)); }
    top { type wall; faces ((3 7 6 2)); }
    frontAndBack { type empty; faces ((0 3 2 1) (4 5 6 7)); }
);
DICT
} > "$base/system/blockMeshDict"

{ header dictionary constant dynamicMeshDict; cat <<'DICT'
dynamicFvMesh   dynamicMotionSolverFvMesh;
motionSolver    rigidBodyMotionSolver;
rigidBodyMotionSolverCoeffs
{
    formulation     linearized;
}
DICT
} > "$base/constant/dynamicMeshDict"

{ header pointVectorField 0 pointDisplacement; cat <<'DICT'
dimensions      [0 1 0 0 0 0 0];
internalField   uniform (0 0 0);
boundaryField
{
    left
    {
        type            fixedValue;
        value           uniform (0.1 0 0);
    }
    right
    {
        type            fixedValue;
        value           uniform (0 0 0);
    }
    "(top|bottom)"
    {
        type            slip;
    }
    frontAndBack
    {
        type            empty;
    }
}
DICT
} > "$base/0/pointDisplacement"

blockMesh -case "$base" > /dev/null
rm -f "$base/constant/polyMesh/"*Zones "$base/constant/polyMesh/sets" 2>/dev/null || true

python3 - "$here" <<'PYTHON'
import gzip, os, re, shutil, struct, sys
here = sys.argv[1]
base = os.path.join(here, "base")

def read(path):
    with open(os.path.join(base, path)) as f:
        return f.read()

def write(case, path, text, binary=False):
    full = os.path.join(here, case, path)
    os.makedirs(os.path.dirname(full), exist_ok=True)
    with open(full, "wb" if binary else "w") as f:
        f.write(text)

def body(text):
    """(header, list lines) of an ascii list file: the count line and what follows."""
    lines = text.split("\n")
    start = next(i for i, l in enumerate(lines) if re.fullmatch(r"\d+", l))
    return lines[:start], lines[start:]

for case in os.listdir(here):
    if case not in ("base", "makeMalformedCases.sh") and os.path.isdir(os.path.join(here, case)):
        shutil.rmtree(os.path.join(here, case))

points, faces, owner, neighbour, boundary = (read("constant/polyMesh/" + n)
                                             for n in ("points", "faces", "owner", "neighbour", "boundary"))
pm = "constant/polyMesh/"

# --- polyMesh -----------------------------------------------------------------------------
h, b = body(points)
write("truncatedPoints", pm + "points", "\n".join(h + b[:14]) + "\n")                 # cut inside the list
write("pointCountLargerThanData", pm + "points", "\n".join(h + ["25"] + b[1:]))
write("pointCountSmallerThanData", pm + "points", "\n".join(h + ["23"] + b[1:]))
write("faceCountOf2To31", pm + "faces", faces.replace("\n29\n(", "\n2147483648\n(", 1))
write("faceWithTwoPoints", pm + "faces", faces.replace("4(1 5 17 13)", "2(1 5)", 1))
write("pointLabelOutOfRange", pm + "faces", faces.replace("4(1 5 17 13)", "4(1 5 24 13)", 1))
write("neighbourLongerThanTheInternalFaces", pm + "neighbour", neighbour.replace("7(1 3 2 4 5 4 5)", "8(1 3 2 4 5 4 5 5)", 1))
# A faceZones file whose second face label is past the 29 faces.
write("faceZoneLabelOutOfRange", pm + "faceZones", open(os.path.join(base, pm + "boundary")).read().split("FoamFile")[0]
      + "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       regIOobject;\n"
      + "    location    \"constant/polyMesh\";\n    object      faceZones;\n}\n\n1\n(\nmiddle\n{\n"
      + "    type faceZone;\nfaceLabels      List<label> 2(0 29);\nflipMap         List<bool> 2(0 0);\n}\n)\n")
write("ownerShorterThanFaces", pm + "owner", owner.replace("\n29\n(", "\n28\n(", 1).replace("\n5\n)", "\n)", 1))
# Internal faces 0 (owner 0, neighbour 1) and 1 (owner 0, neighbour 3) swapped, in all three files.
# (owner stays 0, 0; the short neighbour list is written on one line.)
hf, bf = body(faces)
bf[2], bf[3] = bf[3], bf[2]
write("notUpperTriangular", pm + "faces", "\n".join(hf + bf))
write("notUpperTriangular", pm + "neighbour", neighbour.replace("7(1 3 2 4 5 4 5)", "7(3 1 2 4 5 4 5)", 1))
# A boundary face of "left" with one corner moved to another point: its cell is no longer closed.
write("meshNotClosed", pm + "faces", faces.replace("4(0 12 16 4)", "4(0 12 17 4)", 1))
write("patchesOverlap", pm + "boundary", boundary.replace("startFace       9;", "startFace       8;", 1))
write("patchesLeaveAGap", pm + "boundary", boundary.replace("startFace       9;", "startFace       10;", 1))
write("patchRunsPastTheLastFace", pm + "boundary", boundary.replace("nFaces          12;", "nFaces          13;", 1))
write("nanCoordinate", pm + "points", points.replace("(1 0 0)", "(1 nan 0)", 1))
write("infiniteCoordinate", pm + "points", points.replace("(1 0 0)", "(1 0 inf)", 1))
# Binary points whose header says 32-bit scalars: 24 points of 3 doubles are 576 bytes where
# the header promises 288.
coordinates = [tuple(float(x) for x in l.strip("()").split()) for l in b[2:2 + 24]]
data = b"".join(struct.pack("<3d", *c) for c in coordinates)
binaryHeader = "\n".join(h).replace("format      ascii;", "format      binary;")
binaryHeader = binaryHeader.replace("class       vectorField;",
                                    "arch        \"LSB;label=32;scalar=32\";\n    class       vectorField;")
write("binaryArchMismatch", pm + "points", (binaryHeader + "\n24\n(").encode() + data + b")\n", binary=True)
# An ascii list under a header that says binary.
write("asciiFileSaysBinary", pm + "points", points.replace("format      ascii;", "format      binary;", 1))
# points.gz (the plain points file removed by the test) with the deflate data damaged.
packed = bytearray(gzip.compress(points.encode(), mtime=0))
for i in range(20, 40):
    packed[i] ^= 0x5A
write("corruptGzip", pm + "points.gz", bytes(packed), binary=True)

# --- dictionaries ---------------------------------------------------------------------------
control = open(os.path.join(base, "system/controlDict")).read()
write("dictionarySyntaxError", "system/controlDict", control.replace("endTime         0.1;", "endTime         0.1", 1))
write("unclosedBrace", "constant/dynamicMeshDict", open(os.path.join(base, "constant/dynamicMeshDict")).read().replace("    formulation     linearized;\n}", "    formulation     linearized;\n", 1))
write("includeLoop", "system/controlDict", control.replace("application", "#include \"controlDict\"\napplication", 1))
write("missingInclude", "system/controlDict", control.replace("application", "#include \"commonSettings\"\napplication", 1))
write("negativeDeltaT", "system/controlDict", control.replace("deltaT          0.1;", "deltaT          -0.1;", 1))
write("endTimeBeforeStartTime", "system/controlDict", control.replace("endTime         0.1;", "endTime         -1;", 1))
dynamic = open(os.path.join(base, "constant/dynamicMeshDict")).read()
write("nestedThousandsDeep", "constant/dynamicMeshDict", dynamic + "deep\n" + "{ a\n" * 3000 + "}\n" * 3000)
write("misspeltSolverName", "constant/dynamicMeshDict", dynamic.replace("motionSolver    rigidBodyMotionSolver;", "motionSolver    rigidBodyMotionSolvr;", 1))
write("misspeltKeyword", "constant/dynamicMeshDict", dynamic.replace("formulation     linearized;", "formulaton      linearized;", 1))

# --- pointDisplacement ------------------------------------------------------------------------
field = open(os.path.join(base, "0/pointDisplacement")).read()
right = "    right\n    {\n        type            fixedValue;\n        value           uniform (0 0 0);\n    }\n"
write("missingPatch", "0/pointDisplacement", field.replace(right, "", 1))
write("unknownPatch", "0/pointDisplacement", field.replace(right, right + "    wing\n    {\n        type            fixedValue;\n        value           uniform (0 0 0);\n    }\n", 1))
write("unknownType", "0/pointDisplacement", field.replace("type            fixedValue;\n        value           uniform (0 0 0);", "type            movingWallDisplacement;\n        value           uniform (0 0 0);", 1))
write("nonuniformListOfTheWrongLength", "0/pointDisplacement", field.replace(
    "value           uniform (0.1 0 0);", "value           nonuniform List<vector> 5((0.1 0 0) (0.1 0 0) (0.1 0 0) (0.1 0 0) (0.1 0 0));", 1))
# top is a symmetryPlane patch (its points slide on y = 2), but pointDisplacement moves it.
write("patchBothMovingAndSliding", pm + "boundary", re.sub(r"(    top\n    \{\n        type            )wall;\n        inGroups        1\(wall\);",
                                                          r"\1symmetryPlane;\n        inGroups        1(symmetryPlane);", boundary, count=1))
write("patchBothMovingAndSliding", "0/pointDisplacement", field.replace(
    "    \"(top|bottom)\"\n    {\n        type            slip;\n    }\n",
    "    top\n    {\n        type            fixedValue;\n        value           uniform (0.05 0 0);\n    }\n    bottom\n    {\n        type            slip;\n    }\n", 1))
PYTHON
echo "written: $(ls "$here" | grep -v makeMalformedCases.sh | tr '\n' ' ')"
