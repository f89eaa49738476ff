#pragma once
// Recognition of the standard cell shapes and their VTK node orderings.
//
// 3D: a cell is a tetrahedron, pyramid, prism (wedge) or hexahedron when its faces and
// points have the counts of that shape (4 triangles and 4 points; 4 triangles + 1 quad
// and 5 points; 2 triangles + 3 quads and 6 points; 6 quads and 8 points) AND its edges
// connect them the way the shape requires (the ordered VTK node list can be built).
// Anything else, including degenerate or split-face variants, is a polyhedron. This is
// OpenFOAM's cellModel matching done by counting plus a structural check.
//
// 2D: a polygon with 3 points is a triangle, with 4 a quadrilateral, else a polygon.
//
// VTK orderings (VTK 9 conventions, each checked with vtkCellValidator):
//  - VTK_TETRA (0,1,2,3): (p1-p0) x (p2-p0) points towards p3 (positive volume);
//  - VTK_PYRAMID (0,1,2,3 | 4): the base's right-hand normal points towards the apex 4;
//  - VTK_WEDGE (0,1,2 | 3,4,5): the triangle (0,1,2)'s right-hand normal points away from
//    the triangle (3,4,5); point i+3 is joined to point i by an edge;
//  - VTK_HEXAHEDRON (0,1,2,3 | 4,5,6,7): the base's right-hand normal points towards the
//    opposite face; point i+4 is joined to point i by an edge;
//  - VTK_POLYHEDRON: the cell's unique points, plus a face stream
//    [faceCount, n0, p.., n1, p.., ...] with every face oriented outward.

#include "MeshTopology.hpp"
#include "PolyMesh.hpp"

#include <cstdint>
#include <string_view>
#include <vector>

namespace rbm {

enum class CellShape : std::uint8_t { Tetrahedron, Pyramid, Prism, Hexahedron, Polyhedron };
enum class PolygonShape : std::uint8_t { Triangle, Quadrilateral, Polygon };

// The numeric values are VTK's vtkCellType constants, so writers can use them directly.
enum class VtkCellType : std::uint8_t {
    Triangle = 5,
    Polygon = 7,
    Quad = 9,
    Tetra = 10,
    Hexahedron = 12,
    Wedge = 13,
    Pyramid = 14,
    Polyhedron = 42,
};

std::string_view cellShapeName(CellShape shape);       // "tetrahedron", "pyramid", "prism", ...
std::string_view polygonShapeName(PolygonShape shape);  // "triangle", "quadrilateral", "polygon"

PolygonShape polygonShape(std::size_t pointCount);
VtkCellType vtkPolygonType(std::size_t pointCount);     // VTK_TRIANGLE, VTK_QUAD or VTK_POLYGON

// Shape of one cell of a 3D mesh.
CellShape cellShape(const PolyMesh& mesh, const MeshTopology& topology, Label cell);

// Appends the VTK description of `cell` and returns its VTK type. For the four standard
// shapes, `connectivity` receives the ordered node list and `faceStream` is untouched.
// For a polyhedron, `connectivity` receives the cell's unique points (ascending) and
// `faceStream` its faces: the face count, then for each face its point count and its
// points, oriented outward. The buffers are only appended to, so one pair serves a whole mesh.
VtkCellType appendVtkCell(const PolyMesh& mesh, const MeshTopology& topology, Label cell,
                          std::vector<Label>& connectivity, std::vector<Label>& faceStream);

// Number of cells of each shape, indexed by CellShape.
std::vector<Label> countCellShapes(const PolyMesh& mesh, const MeshTopology& topology);

} // namespace rbm
