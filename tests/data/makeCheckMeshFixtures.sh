#!/bin/bash
# Regenerates the checkMesh agreement fixtures under tests/data/checkMesh/ with
# OpenFOAM v1912 (blockMesh, gmshToFoam, polyDualMesh, checkMesh) and gmsh 4.
# Committed output; the tests never run this script (rbm must not need OpenFOAM).
#
#   tests/data/makeCheckMeshFixtures.sh
#
# Every case gets:
#   constant/polyMesh/{points,faces,owner,neighbour,boundary}   ascii
#   checkMesh.log       plain `checkMesh`
#   checkMesh-all.log   `checkMesh -allGeometry -allTopology`
# and the moved case also <time>/polyMesh/points with logs for `checkMesh -time`.
#
# Cases (all small, < 3000 cells):
#   skewedHex   two distorted, graded hex blocks with an arc edge (3D hexahedra)
#   stretchedSkewed  thin sheared graded block: aspect ratio > 1000, skewness > 4
#   quad2D      one layer of distorted graded quads, empty front/back (2D quads)
#   prism2D     gmsh triangles around a hole, extruded one layer, empty front/back (2D triangles)
#   tet         gmsh tetrahedra in a box with a spherical hole (3D tetrahedra)
#   polyDual    polyDualMesh of a coarse tet mesh (3D polyhedra)
#   quad2DMoved quad2D plus a time folder 0.5 whose points invert two cells, and 0.25 whose
#               points make one cell a chevron: positive volume, its centroid across an edge
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
out=$here/checkMesh
# OpenFOAM's environment; its bashrc complains about missing helper scripts on Debian.
set +eu
# shellcheck disable=SC1091
source /usr/share/openfoam/etc/bashrc >/dev/null 2>&1
set -eu

work=${RBM_FIXTURE_WORK:-$(mktemp -d)}
[ -n "${RBM_FIXTURE_WORK:-}" ] || trap 'rm -rf "$work"' EXIT

controlDict() {
    mkdir -p "$1/system"
    cat > "$1/system/controlDict" <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application     checkMesh;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         1;
deltaT          1;
writeControl    timeStep;
writeInterval   1;
writeFormat     ascii;
writePrecision  17;
writeCompression off;
timeFormat      general;
timePrecision   6;
EOF
    # checkMesh and polyDualMesh build an fvMesh, which reads these two.
    cat > "$1/system/fvSchemes" <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }
ddtSchemes { default Euler; }
gradSchemes { default Gauss linear; }
divSchemes { default none; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
EOF
    cat > "$1/system/fvSolution" <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }
EOF
}

# Switches the patches named in $2.. of case $1 to type empty (gmshToFoam writes "patch").
makeEmpty() {
    local case=$1; shift
    for name in "$@"; do
        python3 - "$case/constant/polyMesh/boundary" "$name" <<'EOF'
import re, sys
path, name = sys.argv[1], sys.argv[2]
text = open(path).read()
pattern = re.compile(r'(\n\s*' + re.escape(name) + r'\s*\{[^}]*?type\s+)(\w+)(;)', re.S)
text, n = pattern.subn(r'\1empty\3', text)
if n != 1:
    sys.exit("patch %s not found in %s" % (name, path))
text = re.sub(r'(\n\s*' + re.escape(name) + r'\s*\{[^}]*?)\n\s*physicalType\s+\w+;', r'\1', text, flags=re.S)
open(path, 'w').write(text)
EOF
    done
}

runCheckMesh() {
    local case=$1; shift
    local suffix=$1; shift
    (cd "$case" && checkMesh "$@" > "checkMesh$suffix.log" 2>&1) || true
    (cd "$case" && checkMesh -allGeometry -allTopology "$@" > "checkMesh-all$suffix.log" 2>&1) || true
}

# Keeps only the polyMesh files and logs: checkMesh writes sets, VTK files and more.
cleanCase() {
    local case=$1
    rm -rf "$case/constant/polyMesh/sets" "$case/postProcessing" "$case/VTK" "$case"/*/polyMesh/sets
    find "$case" -name '*.vtk' -delete
    find "$case" -name '*.msh' -delete
    find "$case" -name '*.obj' -delete   # polyDualMesh's feature files
    find "$case" -name 'cellLevel' -o -name 'pointLevel' | xargs -r rm -f
}

installCase() {
    local name=$1
    rm -rf "${out:?}/$name"
    mkdir -p "$out"
    cp -r "$work/$name" "$out/$name"
    cleanCase "$out/$name"
    rm -rf "$out/$name/system/blockMeshDict.bak"
}

# ---------------------------------------------------------------------------
# skewedHex: two blocks, non-parallel faces, edge grading, one arc edge.
case=$work/skewedHex
controlDict "$case"
cat > "$case/system/blockMeshDict" <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }
convertToMeters 1;
vertices
(
    (0 0 0)          // 0
    (2 0 0.1)        // 1
    (2.3 1.2 0)      // 2
    (-0.2 1 0.2)     // 3
    (0.1 0.2 1)      // 4
    (2.2 -0.1 1.1)   // 5
    (2 1.4 1.3)      // 6
    (0 1.1 0.9)      // 7
    (3.5 -0.3 0.2)   // 8
    (3.9 1.6 -0.1)   // 9
    (3.4 -0.2 1.4)   // 10
    (4.2 1.5 1.2)    // 11
);
blocks
(
    hex (0 1 2 3 4 5 6 7) (12 9 7) edgeGrading (4 4 4 4  0.5 0.5 0.5 0.5  1 2 2 1)
    hex (1 8 9 2 5 10 11 6) (8 9 7) edgeGrading (0.3 0.3 0.3 0.3  0.5 0.8 0.8 0.5  2 1.2 1.2 2)
);
edges
(
    arc 0 1 (1 -0.3 0)
    arc 9 11 (4.4 1.6 0.5)
);
boundary
(
    inlet  { type patch; faces ( (0 4 7 3) ); }
    outlet { type patch; faces ( (8 9 11 10) ); }
    walls
    {
        type wall;
        faces
        (
            (0 3 2 1) (1 2 9 8)
            (4 5 6 7) (5 10 11 6)
            (0 1 5 4) (1 8 10 5)
            (3 7 6 2) (2 6 11 9)
        );
    }
);
mergePatchPairs ();
EOF
(cd "$case" && blockMesh > log.blockMesh 2>&1)
runCheckMesh "$case" ""
installCase skewedHex

# ---------------------------------------------------------------------------
# stretchedSkewed: a thin, strongly sheared block with a two-way grading: aspect ratio
# above 1000, faces beyond 70 degrees non-orthogonality and skewness above 4 (checkMesh's
# warnings: "Failed 2 mesh checks" on a mesh with no inverted cell).
case=$work/stretchedSkewed
controlDict "$case"
cat > "$case/system/blockMeshDict" <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }
convertToMeters 1;
vertices
(
    (0 0 0) (1 0 0) (9 1 0) (8 1 0)
    (0 0 0.0001) (1 0 0.0001) (9 1 0.0001) (8 1 0.0001)
);
blocks
(
    hex (0 1 2 3 4 5 6 7) (6 40 1) simpleGrading (1 ((0.5 0.5 0.02) (0.5 0.5 50)) 1)
);
edges ();
boundary
(
    walls { type wall; faces ( (0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2) (0 3 2 1) (4 5 6 7) ); }
);
mergePatchPairs ();
EOF
(cd "$case" && blockMesh > log.blockMesh 2>&1)
runCheckMesh "$case" ""
installCase stretchedSkewed

# ---------------------------------------------------------------------------
# quad2D: one layer, empty front and back, distorted and graded quads.
case=$work/quad2D
controlDict "$case"
cat > "$case/system/blockMeshDict" <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }
convertToMeters 1;
vertices
(
    (0 0 0) (3 0.4 0) (3.4 2.2 0) (0.3 1.8 0)
    (0 0 0.1) (3 0.4 0.1) (3.4 2.2 0.1) (0.3 1.8 0.1)
    (5 0.1 0) (5.2 2.5 0) (5 0.1 0.1) (5.2 2.5 0.1)
);
blocks
(
    hex (0 1 2 3 4 5 6 7) (24 16 1) simpleGrading (3 0.25 1)
    hex (1 8 9 2 5 10 11 6) (12 16 1) edgeGrading (0.5 0.5 0.5 0.5  0.25 0.25 0.25 0.25  1 1 1 1)
);
edges
(
    arc 3 2 (1.8 2.4 0)
    arc 7 6 (1.8 2.4 0.1)
);
boundary
(
    inlet  { type patch; faces ( (0 4 7 3) ); }
    outlet { type patch; faces ( (8 9 11 10) ); }
    walls  { type wall; faces ( (0 1 5 4) (1 8 10 5) (3 7 6 2) (2 6 11 9) ); }
    frontAndBack { type empty; faces ( (0 3 2 1) (1 2 9 8) (4 5 6 7) (5 10 11 6) ); }
);
mergePatchPairs ();
EOF
(cd "$case" && blockMesh > log.blockMesh 2>&1)
runCheckMesh "$case" ""
installCase quad2D

# quad2DMoved: the same mesh with a time folder whose points fold two cells over.
cp -r "$work/quad2D" "$work/quad2DMoved"
case=$work/quad2DMoved
mkdir -p "$case/0.5/polyMesh"
python3 - "$case/constant/polyMesh/points" "$case/0.5/polyMesh/points" <<'EOF'
import re, sys
src, dst = sys.argv[1], sys.argv[2]
body = open(src).read().split('}', 1)[1]
pts = [tuple(map(float, m.groups())) for m in
       re.finditer(r'\(([-+0-9.eE]+) ([-+0-9.eE]+) ([-+0-9.eE]+)\)', body)]
# On each plane, push the interior point nearest (1.5, 1.0) by 0.6 in +x, past its
# right-hand neighbours, so the quads on one side fold over (negative volumes).
for z in (0.0, 0.1):
    i = min((i for i, p in enumerate(pts) if abs(p[2] - z) < 1e-9),
            key=lambda i: (pts[i][0] - 1.5) ** 2 + (pts[i][1] - 1.0) ** 2)
    x, y, zz = pts[i]
    pts[i] = (x + 0.6, y, zz)
with open(dst, 'w') as f:
    f.write('FoamFile\n{\n    version     2.0;\n    format      ascii;\n'
            '    class       vectorField;\n    location    "0.5/polyMesh";\n'
            '    object      points;\n}\n\n')
    f.write('%d\n(\n' % len(pts))
    for p in pts:
        f.write('(%.17g %.17g %.17g)\n' % p)
    f.write(')\n')
EOF
runCheckMesh "$case" "-0.5" -time 0.5
# 0.25: on each plane the interior point nearest (1.5, 1.0) moved 85 % of the way to the
# opposite corner of its cell on the lower left: that cell becomes a chevron whose area stays
# positive but whose centroid lies beyond its reflex corner (its face pyramids turn over).
mkdir -p "$case/0.25/polyMesh"
python3 - "$case/constant/polyMesh" "$case/0.25/polyMesh/points" <<'EOF'
import re, sys
mesh, dst = sys.argv[1], sys.argv[2]
body = open(mesh + '/points').read().split('}', 1)[1]
pts = [tuple(map(float, m.groups())) for m in
       re.finditer(r'\(([-+0-9.eE]+) ([-+0-9.eE]+) ([-+0-9.eE]+)\)', body)]
faces = [list(map(int, m.group(1).split())) for m in
         re.finditer(r'4\(([0-9 ]+)\)', open(mesh + '/faces').read().split('}', 1)[1])]
for z in (0.0, 0.1):
    i = min((i for i, p in enumerate(pts) if abs(p[2] - z) < 1e-9),
            key=lambda i: (pts[i][0] - 1.5) ** 2 + (pts[i][1] - 1.0) ** 2)
    # The quads of this plane holding i; the corner opposite i lowest on the left.
    quads = [f for f in faces if i in f and all(abs(pts[k][2] - z) < 1e-9 for k in f)]
    q = min((f[(f.index(i) + 2) % 4] for f in quads), key=lambda k: pts[k][0] + pts[k][1])
    x, y, zz = pts[i]
    pts[i] = (x + 0.85 * (pts[q][0] - x), y + 0.85 * (pts[q][1] - y), zz)
with open(dst, 'w') as f:
    f.write('FoamFile\n{\n    version     2.0;\n    format      ascii;\n'
            '    class       vectorField;\n    location    "0.25/polyMesh";\n'
            '    object      points;\n}\n\n')
    f.write('%d\n(\n' % len(pts))
    for p in pts:
        f.write('(%.17g %.17g %.17g)\n' % p)
    f.write(')\n')
EOF
runCheckMesh "$case" "-0.25" -time 0.25
installCase quad2DMoved
rm -f "$out/quad2DMoved/checkMesh.log" "$out/quad2DMoved/checkMesh-all.log"

# ---------------------------------------------------------------------------
# prism2D: gmsh triangles in a plate with a hole, extruded one layer.
case=$work/prism2D
controlDict "$case"
cat > "$case/prism2D.geo" <<'EOF'
lc = 0.12;
Point(1) = {0, 0, 0, lc};
Point(2) = {2.5, 0, 0, lc};
Point(3) = {2.5, 1.5, 0, lc};
Point(4) = {0, 1.5, 0, lc};
Point(5) = {0.9, 0.7, 0, lc/3};
Point(6) = {1.2, 0.7, 0, lc/3};
Point(7) = {0.6, 0.7, 0, lc/3};
Point(8) = {0.9, 1.0, 0, lc/3};
Point(9) = {0.9, 0.4, 0, lc/3};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Circle(5) = {6, 5, 8};
Circle(6) = {8, 5, 7};
Circle(7) = {7, 5, 9};
Circle(8) = {9, 5, 6};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
out[] = Extrude {0, 0, 0.1} { Surface{1}; Layers{1}; Recombine; };
Physical Surface("frontAndBack") = {1, out[0]};
Physical Surface("inlet") = {out[5]};
Physical Surface("outlet") = {out[3]};
Physical Surface("walls") = {out[2], out[4], out[6], out[7], out[8], out[9]};
Physical Volume("fluid") = {out[1]};
Mesh.MshFileVersion = 2.2;
EOF
(cd "$case" && gmsh -3 -format msh2 prism2D.geo -o prism2D.msh > log.gmsh 2>&1 && gmshToFoam prism2D.msh > log.gmshToFoam 2>&1)
makeEmpty "$case" frontAndBack
runCheckMesh "$case" ""
installCase prism2D

# ---------------------------------------------------------------------------
# tet: gmsh tetrahedra in a box with a spherical hole.
case=$work/tet
controlDict "$case"
cat > "$case/tet.geo" <<'EOF'
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1.2, 1};
Sphere(2) = {0.8, 0.6, 0.5, 0.3};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Mesh.CharacteristicLengthMax = 0.22;
Mesh.CharacteristicLengthMin = 0.06;
Mesh.Optimize = 0;
s() = Boundary{ Volume{3}; };
Physical Surface("walls") = {s()};
Physical Volume("fluid") = {3};
Mesh.MshFileVersion = 2.2;
EOF
(cd "$case" && gmsh -3 -format msh2 tet.geo -o tet.msh > log.gmsh 2>&1 && gmshToFoam tet.msh > log.gmshToFoam 2>&1)
runCheckMesh "$case" ""
installCase tet

# ---------------------------------------------------------------------------
# polyDual: the dual of a coarse tet mesh: general polyhedra.
case=$work/polyDual
controlDict "$case"
cat > "$case/coarse.geo" <<'EOF'
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1.5, 1, 0.8};
Mesh.CharacteristicLengthMax = 0.2;
Mesh.CharacteristicLengthMin = 0.2;
s() = Boundary{ Volume{1}; };
Physical Surface("walls") = {s()};
Physical Volume("fluid") = {1};
Mesh.MshFileVersion = 2.2;
EOF
(cd "$case" && gmsh -3 -format msh2 coarse.geo -o coarse.msh > log.gmsh 2>&1 && gmshToFoam coarse.msh > log.gmshToFoam 2>&1)
(cd "$case" && polyDualMesh 80 -overwrite > log.polyDualMesh 2>&1)
runCheckMesh "$case" ""
installCase polyDual

# The generator logs are kept for provenance; geometry inputs too.
du -sh "$out"
