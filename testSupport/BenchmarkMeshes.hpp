#pragma once
// Meshes for the performance benchmark (benchmarks/RbmBenchmark.cpp): boxes with a box-shaped
// hole whose boundary is turned while the outer boundary stays fixed, in 2D (one layer of
// hexahedra or prisms between two empty planes, OpenFOAM's pseudo-3D form) and in 3D
// (hexahedra, or tetrahedra made by cutting every hexahedron into six).
//
// Every mesh follows OpenFOAM's polyMesh rules (checkPolyMeshOrdering in MeshTopology.hpp
// accepts it): internal faces first, owner < neighbour, sorted by owner then neighbour;
// face normals from owner to neighbour and out of the domain; patches contiguous.
//
// Geometry: the outer box is [-1, 1]^d, the hole [-1/4, 1/4]^d (in 2D, x and y only); n
// cells per side, n a multiple of 8 so that the hole's sides lie on grid lines. Points are
// numbered with x fastest, then y, then z (2D: the front plane z = 0 first, then the back
// plane z = 2/n); points inside the hole are left out.
//
// Patches, in this order: "inner" (type wall: the hole's surface), "outer" (type patch),
// and in 2D "frontAndBack" (type empty).

#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace rbm {

enum class HoleMeshCellKind {
    quadrilaterals,  // 2D: hexahedra after extrusion
    triangles,       // 2D: every grid square cut along its (i, j)-(i+1, j+1) diagonal; prisms after extrusion
    hexahedra,       // 3D
    tetrahedra,      // 3D: every grid cube cut into six tetrahedra around its (i, j, k)-(i+1, j+1, k+1)
                     // diagonal (Kuhn's subdivision: neighbouring cubes cut their shared face alike)
};

// True for quadrilaterals and triangles.
bool isPlanarCellKind(HoleMeshCellKind kind);

// The box-with-hole mesh with n cells per side (n ≥ 8, a multiple of 8; std::invalid_argument
// otherwise).
PolyMesh makeBoxWithHole(Label cellsPerSide, HoleMeshCellKind kind);

// Nodes of the RBM problem of makeBoxWithHole(n, kind): the points of one plane in 2D, all
// points in 3D.
double boxWithHoleNodeCount(Label cellsPerSide, HoleMeshCellKind kind);

// The multiple of 8 whose box-with-hole mesh has the node count closest to targetNodes.
Label boxWithHoleCellsPerSide(double targetNodes, HoleMeshCellKind kind);

// Builds a polyMesh from cells given by their points, the way a mesh generator's output is
// converted: faces shared by two cells become internal faces, the others boundary faces that
// `patchOfBoundaryFace` (called with the face centre) sorts into `patches` (names and types;
// startFace and faceCount are filled in). Cell c has points cellPoints[cellOffsets[c] ..
// cellOffsets[c+1]) in OpenFOAM's model order for its shape, chosen by the point count:
// 4 tetrahedron, 6 prism (triangle 0 1 2, then the opposite triangle 3 4 5), 8 hexahedron
// (bottom 0 1 2 3 as a loop, then the top 4 5 6 7 above them). Each face is oriented out of
// its owner from the geometry (cells must be convex). Throws std::invalid_argument for other
// point counts, a face shared by more than two cells, or a patch index out of range.
PolyMesh assemblePolyMeshFromCells(std::vector<Vector3> points, std::span<const Label> cellOffsets,
                                   std::span<const Label> cellPoints, std::vector<Patch> patches,
                                   const std::function<Label(const Vector3& faceCentre)>& patchOfBoundaryFace);

} // namespace rbm
