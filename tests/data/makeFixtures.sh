#!/bin/bash
# Regenerates the polyMesh format fixtures under tests/data/formats/ with OpenFOAM v1912.
# Not run by the tests (rbm never needs OpenFOAM); run it by hand after changing the mesh:
#     tests/data/makeFixtures.sh
#
# One small mesh (two blocks, 10 x 5 x 4 = 200 cells, 11 x 6 x 5 = 330 points) in every
# on-disk form the polyMesh reader must handle:
#   ascii/                  writeFormat ascii,  writeCompression off (faces as faceList)
#   binary/                 writeFormat binary, writeCompression off (faces as faceCompactList)
#   asciiGzip/              ascii,  every file .gz
#   binaryGzip/             binary, every file .gz
#   asciiFaceCompactList/   ascii, faces rewritten by hand as an ascii faceCompactList
#                           (OpenFOAM reads that form but never writes it in ascii)
#   binaryLabel64/          binary with 64-bit labels, arch "LSB;label=64;scalar=64",
#                           converted from binary/ (Debian's OpenFOAM is label=32)
# Every variant is produced from scratch by blockMesh + topoSet, so the binary variants
# hold bit-identical points and the ascii ones the same points rounded to writePrecision 6.
#
# Mesh (blockMeshDict below, scale 0.1):
#   block "left"  6 x 5 x 4 cells on [0,0.6] x [0,0.5] x [0,0.2]  -> cellZone left  (120 cells)
#   block "right" 4 x 5 x 4 cells on [0.6,1] x [0,0.5] x [0,0.2]  -> cellZone right  (80 cells)
#   y graded with simpleGrading 3 (last/first cell), so coordinates are not short decimals.
#   patches: inlet (patch, 20 faces), outlet (patch, inGroups farField openBoundaries, 20),
#            lowerWall (wall, inGroups movingWalls, 40), upperWall (wall, 40),
#            front/back (cyclic pair, 50 each: matchTolerance, transform, neighbourPatch)
#   faceZone interface: the 20 internal faces on x = 0.6, flipMap mixed (topoSet)
#   pointZone corner: 18 points (topoSet): the 3 x 2 x 2 in the box x < 0.25, y < 0.1, z < 0.06,
#            plus the cyclic partners (z = 0.2) of the 6 on z = 0, which topoSet adds to keep
#            point sets consistent across the front/back cyclic
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
out="$here/formats"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"   # Debian's OpenFOAM finds etc/ through it
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

writeControlDict() {   # $1 case, $2 ascii|binary, $3 on|off
    mkdir -p "$1/system"
    cat > "$1/system/controlDict" <<DICT
FoamFile
{
    version     2.0;
    format      ascii;
    class       dictionary;
    object      controlDict;
}
application     checkMesh;
startFrom       latestTime;
startTime       0;
stopAt          endTime;
endTime         1;
deltaT          1;
writeControl    timeStep;
writeInterval   1;
purgeWrite      0;
writeFormat     $2;
writePrecision  6;
writeCompression $3;
timeFormat      general;
timePrecision   6;
runTimeModifiable false;
DICT
}

writeFvDicts() {   # $1 case: the minimal fvSchemes/fvSolution checkMesh insists on
    for name in fvSchemes fvSolution; do
        cat > "$1/system/$name" <<DICT
FoamFile
{
    version     2.0;
    format      ascii;
    class       dictionary;
    object      $name;
}
DICT
    done
    cat >> "$1/system/fvSchemes" <<'DICT'
ddtSchemes { default steadyState; }
gradSchemes { default Gauss linear; }
divSchemes { default none; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
DICT
}

writeMeshDicts() {   # $1 case
    cat > "$1/system/blockMeshDict" <<'DICT'
FoamFile
{
    version     2.0;
    format      ascii;
    class       dictionary;
    object      blockMeshDict;
}
scale 0.1;
vertices
(
    (0 0 0)  (6 0 0)  (10 0 0)
    (0 5 0)  (6 5 0)  (10 5 0)
    (0 0 2)  (6 0 2)  (10 0 2)
    (0 5 2)  (6 5 2)  (10 5 2)
);
blocks
(
    hex (0 1 4 3 6 7 10 9) left  (6 5 4) simpleGrading (1 3 1)
    hex (1 2 5 4 7 8 11 10) right (4 5 4) simpleGrading (1 3 1)
);
edges ();
boundary
(
    inlet     { type patch; faces ((0 6 9 3)); }
    outlet    { type patch; inGroups (farField openBoundaries); faces ((2 5 11 8)); }
    lowerWall { type wall; inGroups (movingWalls); faces ((0 1 7 6) (1 2 8 7)); }
    upperWall { type wall; faces ((3 9 10 4) (4 10 11 5)); }
    front     { type cyclic; neighbourPatch back;  faces ((0 3 4 1) (1 4 5 2)); }
    back      { type cyclic; neighbourPatch front; faces ((6 7 10 9) (7 8 11 10)); }
);
mergePatchPairs ();
DICT
    cat > "$1/system/topoSetDict" <<'DICT'
FoamFile
{
    version     2.0;
    format      ascii;
    class       dictionary;
    object      topoSetDict;
}
actions
(
    // Internal faces on the block interface x = 0.6.
    { name interfaceFaces; type faceSet; action new; source boxToFace; box (0.59 -1 -1) (0.61 1 1); }
    // Orientation cells: left below y = 0.25 and right above, so the flipMap is mixed.
    { name orientCells; type cellSet; action new; source boxToCell; box (-1 -1 -1) (0.6 0.25 1); }
    { name orientCells; type cellSet; action add; source boxToCell; box (0.6 0.25 -1) (2 2 2); }
    { name interface; type faceZoneSet; action new; source setsToFaceZone; faceSet interfaceFaces; cellSet orientCells; }
    // Points near the origin corner.
    { name cornerPoints; type pointSet; action new; source boxToPoint; box (-1 -1 -1) (0.25 0.1 0.06); }
    { name corner; type pointZoneSet; action new; source setToPointZone; set cornerPoints; }
);
DICT
}

makeVariant() {   # $1 name, $2 ascii|binary, $3 on|off
    local case="$work/$1"
    writeControlDict "$case" "$2" "$3"
    writeFvDicts "$case"
    writeMeshDicts "$case"
    blockMesh -case "$case" > "$work/$1.blockMesh.log" 2>&1
    topoSet -case "$case" > "$work/$1.topoSet.log" 2>&1
    rm -rf "$case/constant/polyMesh/sets"
    rm -f "$case/system/blockMeshDict" "$case/system/topoSetDict"
    checkMesh -case "$case" > "$work/$1.checkMesh.log" 2>&1 || { cat "$work/$1.checkMesh.log"; exit 1; }
    rm -rf "${out:?}/$1"
    mkdir -p "$out"
    cp -r "$case" "$out/$1"
}

makeVariant ascii ascii off
makeVariant binary binary off
makeVariant asciiGzip ascii on
makeVariant binaryGzip binary on

# ascii faceCompactList: same mesh, faces as "N+1(offsets) M(point labels)".
rm -rf "$out/asciiFaceCompactList"
cp -r "$out/ascii" "$out/asciiFaceCompactList"
python3 - "$out/ascii/constant/polyMesh/faces" "$out/asciiFaceCompactList/constant/polyMesh/faces" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
header_end = text.index("// * * *")
header = text[:header_end].replace("class       faceList;", "class       faceCompactList;")
body = text[header_end:]
start = body.index("\n\n\n") + 3
faces = re.findall(r"\d+\(([\d ]+)\)", body[start:])
offsets, labels = [0], []
for f in faces:
    labels += f.split()
    offsets.append(len(labels))
rule = body[:start]
out = header + rule
out += "%d\n(\n%s\n)\n\n" % (len(offsets), "\n".join(map(str, offsets)))
out += "%d\n(\n%s\n)\n\n" % (len(labels), "\n".join(labels))
out += "\n// ************************************************************************* //\n"
open(sys.argv[2], "w").write(out)
PY
checkMesh -case "$out/asciiFaceCompactList" > "$work/asciiFaceCompactList.checkMesh.log" 2>&1 \
    || { cat "$work/asciiFaceCompactList.checkMesh.log"; exit 1; }

# 64-bit labels: every binary label list widened from int32 to int64, arch changed.
rm -rf "$out/binaryLabel64"
cp -r "$out/binary" "$out/binaryLabel64"
python3 - "$out/binaryLabel64/constant/polyMesh" <<'PY'
import os, re, struct, sys
folder = sys.argv[1]
def widen(data, start, count):
    """Rewrites the binary block of `count` int32 at data[start:] as int64; returns (bytes, end)."""
    values = struct.unpack_from("<%di" % count, data, start)
    return struct.pack("<%dq" % count, *values), start + 4 * count
for name in ["faces", "owner", "neighbour", "cellZones", "faceZones", "pointZones"]:
    path = os.path.join(folder, name)
    data = open(path, "rb").read()
    data = data.replace(b'arch        "LSB;label=32;scalar=64";', b'arch        "LSB;label=64;scalar=64";')
    # Binary label lists: "<count>\n(" + raw bytes + ")". In zone files only List<label>
    # (cellLabels, faceLabels, pointLabels) are label lists; flipMap is List<bool>, written as ascii.
    out, pos = b"", 0
    pattern = re.compile(rb"(?:^|\n)(\d+)\n\(" if name in ("faces", "owner", "neighbour")
                         else rb"(?:cellLabels|faceLabels|pointLabels)\s+List<label>\s+(\d+)\n?\(")
    while True:
        m = pattern.search(data, pos)
        if not m:
            break
        count = int(m.group(1))
        start = m.end()
        out += data[pos:start]
        block, end = widen(data, start, count)
        assert data[end:end + 1] == b")", (path, count)
        out += block
        pos = end
    out += data[pos:]
    open(path, "wb").write(out)
PY
# points and boundary hold no binary labels; mark their arch too, as a label=64 OpenFOAM would.
sed -i 's/label=32;scalar=64/label=64;scalar=64/' "$out/binaryLabel64/constant/polyMesh/points" \
    "$out/binaryLabel64/constant/polyMesh/boundary"
du -sh "$out"
