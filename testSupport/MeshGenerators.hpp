#pragma once
// Programmatic meshes for tests and benchmarks, built the way blockMesh / extrudeMesh
// would write them: OpenFOAM face ordering (internal faces first, sorted by owner then
// neighbour; normals from owner to neighbour and out of the domain), contiguous patches.
// checkPolyMeshOrdering (MeshTopology.hpp) accepts every mesh made here.
//
// Structured grids number points and cells with i fastest (x, then y, then z), like
// blockMesh does for a single block; coordinates use exact end values (no rounding drift
// at the max side), so boundary points lie exactly on the box planes.

#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <array>
#include <string>

namespace rbm {

struct BoxPatch {
    std::string name;
    std::string type = "patch";
};

// Hexahedral box of nx × ny × nz cells spanning [min, max]. The six sides go to the patches
// named in `sides` (order: x-min, x-max, y-min, y-max, z-min, z-max); sides with the same
// name share one patch, in order of first appearance. Point (i, j, k) has label
// i + (nx+1)(j + (ny+1)k); cell (i, j, k) has label i + nx(j + ny k).
PolyMesh makeHexBox(Label nx, Label ny, Label nz, const Vector3& min, const Vector3& max,
                    const std::array<BoxPatch, 6>& sides = {BoxPatch{"xMin"}, BoxPatch{"xMax"}, BoxPatch{"yMin"},
                                                            BoxPatch{"yMax"}, BoxPatch{"zMin"}, BoxPatch{"zMax"}});

// The 2D cells of an nx × ny grid: Quadrilaterals; Triangles (every quad cut along its
// (i,j)-(i+1,j+1) diagonal); Mixed (quads for i < nx/2, triangles for the rest);
// Polygons (quads (2m, j) and (2m+1, j) merged into one six-point polygon with two
// collinear edges; nx must be even).
enum class PlanarCellKind { Quadrilaterals, Triangles, Mixed, Polygons };

struct ExtrusionOptions {
    // Axis of the plane normal: 0 = x, 1 = y, 2 = z. Local coordinates (u, v, w) map to 3D
    // cyclically so that (u, v, w) stays right-handed: z: (u, v, w); x: (w, u, v); y: (v, w, u).
    int normalAxis = 2;
    // One "frontAndBack" empty patch (blockMesh style) or two, "front" and "back".
    bool separateFrontAndBackPatches = false;
};

// OpenFOAM pseudo-3D case: one layer of cells between two empty planes. The 2D grid
// spans (u, v) in [min.x, max.x] × [min.y, max.y] and the layer w in [min.z, max.z]
// (local coordinates, see ExtrusionOptions::normalAxis). Quads give hexahedra, triangles
// prisms, polygons polyhedra. Patches, in this order: "left" (u = min.x), "right",
// "bottom" (v = min.y), "top", then the empty patch(es). Cells keep the 2D cell order;
// points on the front plane (w = min.z) come first, in 2D grid order, then the back plane.
PolyMesh makeExtruded2D(Label nx, Label ny, const Vector3& min, const Vector3& max,
                        PlanarCellKind kind = PlanarCellKind::Quadrilaterals, const ExtrusionOptions& options = {});

// OpenFOAM axisymmetric case: the 2D grid (u = axial x in [min.x, max.x], v = radius in
// [min.y, max.y]) rotated about the x axis to -angle/2 ("front" wedge patch) and +angle/2
// ("back" wedge patch): the point (u, v) at angle phi is (u, v cos phi, v sin phi).
// When min.y == 0 the points on the axis are shared by both planes, the side faces on
// the axis collapse away (cells there become prisms, as blockMesh makes them) and an
// empty "axis" patch with no faces is added. Patches: "left", "right", "bottom" (only when
// min.y > 0), "top", "front", "back", then "axis".
PolyMesh makeWedge2D(Label nx, Label ny, const Vector3& min, const Vector3& max, double wedgeAngleDegrees,
                     PlanarCellKind kind = PlanarCellKind::Quadrilaterals);

} // namespace rbm
