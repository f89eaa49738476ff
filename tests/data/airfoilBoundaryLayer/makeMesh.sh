#!/usr/bin/env bash
# Regenerates this fixture: a NACA4415 mesh with a structured boundary layer (hexahedra,
# first cell 4.5e-6 chord on a 0.008 surface spacing: checkMesh aspect ratio near 900)
# and prisms outside, one layer thick, stored binary and gzip-compressed.
# Needs gmsh and OpenFOAM v1912 (Debian packages gmsh, openfoam). Not run by the tests.
set -euo pipefail
cd "$(dirname "$0")"
set +u; source /usr/share/openfoam/etc/bashrc >/dev/null 2>&1 || true; set -u
work=$(mktemp -d)
python3 ../../../tutorials/naca4415/meshGeneration/naca4415Geo.py 0.008 2.0 4.5e-6 > "$work/mesh.geo"
gmsh -3 -format msh2 "$work/mesh.geo" -o "$work/mesh.msh" > "$work/log.gmsh"
rm -rf constant/polyMesh
gmshToFoam -case . "$work/mesh.msh" > "$work/log.gmshToFoam"
boundary=constant/polyMesh/boundary
foamDictionary $boundary -entry entry0/frontAndBack/type -set empty > /dev/null
foamDictionary $boundary -entry entry0/airfoil/type -set wall > /dev/null
for patch in frontAndBack farfield airfoil; do
  foamDictionary $boundary -entry entry0/$patch/physicalType -remove > /dev/null
done
foamFormatConvert -case . -constant -noZero > "$work/log.foamFormatConvert" 2>&1
rm -rf constant/polyMesh/sets constant/polyMesh/*Zones* "$work"
# OpenFOAM v1912 compresses only ascii output; it reads gzip-compressed binary files all the same.
gzip -9 constant/polyMesh/points constant/polyMesh/faces constant/polyMesh/owner constant/polyMesh/neighbour
checkMesh -case . -constant > log.checkMesh
