#!/usr/bin/env bash
# Regenerates the benchmark airfoil mesh: NACA4415 (chord 1) in a circular far field of 20
# chords, a structured boundary layer of hexahedra around the airfoil and prisms outside, one
# layer thick (OpenFOAM's pseudo-3D form), stored binary and gzip-compressed (OpenFOAM v1912
# reads it as it is). Defaults: surface spacing 0.003, far-field spacing 1.0, first cell
# 2.0e-6 chord: 40 640 nodes per plane, 54 131 cells, checkMesh aspect ratio 976,
# non-orthogonality 69 degrees, "Mesh OK" (see log.checkMesh).
# Needs gmsh and OpenFOAM v1912 (Debian packages gmsh, openfoam). Not run by the tests.
# Usage: makeMesh.sh [surfaceSize farfieldSize firstLayerHeight]
set -euo pipefail
cd "$(dirname "$0")"
surfaceSize=${1:-0.003}
farfieldSize=${2:-1.0}
firstLayer=${3:-2.0e-6}
set +u; source /usr/share/openfoam/etc/bashrc >/dev/null 2>&1 || true; set -u
work=$(mktemp -d)
python3 ../../tutorials/naca4415/meshGeneration/naca4415Geo.py "$surfaceSize" "$farfieldSize" "$firstLayer" > "$work/mesh.geo"
# Two fan elements at the trailing edge: with gmsh 4.8.4's default (5) a first layer this thin
# gives collapsed fan cells there (duplicate points, zero-area faces).
gmsh -3 -format msh2 -setnumber Mesh.BoundaryLayerFanElements 2 "$work/mesh.geo" -o "$work/mesh.msh" > "$work/log.gmsh"
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
