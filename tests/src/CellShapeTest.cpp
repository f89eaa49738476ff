// Tests of the cell shapes (src/CellShape): OpenFOAM's cell models recognised from the faces.

#include "CellShape.hpp"
#include "InputError.hpp"
#include "MeshGenerators.hpp"
#include "MeshTopology.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

using namespace rbm::test::topologyCases;

using namespace rbm;

namespace {

PolyMesh unitPyramid()
{
    return singleCell({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}},
                      {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
}

PolyMesh unitPrism()
{
    return singleCell({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}},
                      {{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}});
}

double tripleProduct(const Vector3& a, const Vector3& b, const Vector3& c) { return dot(a, cross(b, c)); }

// The edges of a cell as a sorted list of sorted point pairs (from its faces).
std::vector<std::pair<Label, Label>> cellEdges(const PolyMesh& mesh, const MeshTopology& topology, Label cell)
{
    std::vector<std::pair<Label, Label>> edges;
    for (Label f : topology.facesOf(cell)) {
        const auto face = mesh.face(f);
        for (std::size_t i = 0; i < face.size(); ++i) {
            const Label a = face[i], b = face[(i + 1) % face.size()];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
}

bool isEdge(const std::vector<std::pair<Label, Label>>& edges, Label a, Label b)
{
    return std::binary_search(edges.begin(), edges.end(), std::pair{std::min(a, b), std::max(a, b)});
}

} // namespace

TEST(CellShape, PolygonsByPointCount)
{
    EXPECT_EQ(polygonShape(3), PolygonShape::Triangle);
    EXPECT_EQ(polygonShape(4), PolygonShape::Quadrilateral);
    EXPECT_EQ(polygonShape(5), PolygonShape::Polygon);
    EXPECT_EQ(vtkPolygonType(3), VtkCellType::Triangle);
    EXPECT_EQ(vtkPolygonType(4), VtkCellType::Quad);
    EXPECT_EQ(vtkPolygonType(7), VtkCellType::Polygon);
    EXPECT_EQ(static_cast<int>(VtkCellType::Polyhedron), 42);   // VTK_POLYHEDRON
    EXPECT_EQ(polygonShapeName(PolygonShape::Quadrilateral), "quadrilateral");
}

TEST(CellShape, TetrahedronOrderingHasPositiveVolume)
{
    const PolyMesh mesh = unitTetrahedron();
    const MeshTopology topology = buildMeshTopology(mesh);
    EXPECT_EQ(cellShape(mesh, topology, 0), CellShape::Tetrahedron);
    std::vector<Label> nodes, faceStream;
    EXPECT_EQ(appendVtkCell(mesh, topology, 0, nodes, faceStream), VtkCellType::Tetra);
    ASSERT_EQ(nodes.size(), 4u);
    EXPECT_TRUE(faceStream.empty());
    // Base = first outward face (0,2,1) reversed, apex 3.
    EXPECT_EQ(nodes, (std::vector<Label>{0, 1, 2, 3}));
    const auto& x = mesh.points;
    EXPECT_DOUBLE_EQ(tripleProduct(x[nodes[1]] - x[nodes[0]], x[nodes[2]] - x[nodes[0]], x[nodes[3]] - x[nodes[0]]), 1.0);
}

TEST(CellShape, PyramidBaseNormalPointsToTheApex)
{
    const PolyMesh mesh = unitPyramid();
    const MeshTopology topology = buildMeshTopology(mesh);
    EXPECT_EQ(cellShape(mesh, topology, 0), CellShape::Pyramid);
    std::vector<Label> nodes, faceStream;
    EXPECT_EQ(appendVtkCell(mesh, topology, 0, nodes, faceStream), VtkCellType::Pyramid);
    EXPECT_EQ(nodes, (std::vector<Label>{0, 1, 2, 3, 4}));
    const auto& x = mesh.points;
    const Vector3 baseNormal = cross(x[nodes[2]] - x[nodes[0]], x[nodes[3]] - x[nodes[1]]);
    EXPECT_GT(dot(baseNormal, x[nodes[4]] - x[nodes[0]]), 0.0);
}

TEST(CellShape, PrismTriangleNormalPointsAwayFromTheOtherTriangle)
{
    const PolyMesh mesh = unitPrism();
    const MeshTopology topology = buildMeshTopology(mesh);
    EXPECT_EQ(cellShape(mesh, topology, 0), CellShape::Prism);
    std::vector<Label> nodes, faceStream;
    EXPECT_EQ(appendVtkCell(mesh, topology, 0, nodes, faceStream), VtkCellType::Wedge);
    // Base = outward bottom face (0,2,1); its top twins (3,5,4). vtkCellValidator accepts
    // exactly this orientation in VTK 9.1 (checked when this was written).
    EXPECT_EQ(nodes, (std::vector<Label>{0, 2, 1, 3, 5, 4}));
    const auto& x = mesh.points;
    const Vector3 normal = cross(x[nodes[1]] - x[nodes[0]], x[nodes[2]] - x[nodes[0]]);
    const Vector3 towardsTop = (x[nodes[3]] + x[nodes[4]] + x[nodes[5]] - x[nodes[0]] - x[nodes[1]] - x[nodes[2]]) / 3.0;
    EXPECT_LT(dot(normal, towardsTop), 0.0);
}

TEST(CellShape, HexahedronOrderingHasPositiveJacobianAtEveryCorner)
{
    // A box cell and the same cell in a mesh whose normal axis is x (different face order).
    for (const PolyMesh& mesh : {makeHexBox(1, 1, 1, {0, 0, 0}, {2, 3, 4}),
                                 makeExtruded2D(1, 1, {0, 0, 0}, {2, 3, 4}, PlanarCellKind::Quadrilaterals, {0, false})}) {
        const MeshTopology topology = buildMeshTopology(mesh);
        EXPECT_EQ(cellShape(mesh, topology, 0), CellShape::Hexahedron);
        std::vector<Label> nodes, faceStream;
        EXPECT_EQ(appendVtkCell(mesh, topology, 0, nodes, faceStream), VtkCellType::Hexahedron);
        ASSERT_EQ(nodes.size(), 8u);
        const auto& x = mesh.points;
        const auto edges = cellEdges(mesh, topology, 0);
        // VTK_HEXAHEDRON: 0-1-2-3 and 4-5-6-7 are loops joined by i–(i+4). The trilinear map's
        // Jacobian at corner 0 is det(x1-x0, x3-x0, x4-x0) = the cell volume 24 for a box.
        for (int i = 0; i < 4; ++i) {
            EXPECT_TRUE(isEdge(edges, nodes[i], nodes[(i + 1) % 4]));
            EXPECT_TRUE(isEdge(edges, nodes[4 + i], nodes[4 + (i + 1) % 4]));
            EXPECT_TRUE(isEdge(edges, nodes[i], nodes[i + 4]));
        }
        EXPECT_DOUBLE_EQ(tripleProduct(x[nodes[1]] - x[nodes[0]], x[nodes[3]] - x[nodes[0]], x[nodes[4]] - x[nodes[0]]),
                         24.0);
        // At corner 6 the parametric directions point to 6 from 7, 5 and 2.
        EXPECT_DOUBLE_EQ(tripleProduct(x[nodes[6]] - x[nodes[7]], x[nodes[6]] - x[nodes[5]], x[nodes[6]] - x[nodes[2]]),
                         24.0);
    }
}

TEST(CellShape, PolyhedronGetsAnOutwardFaceStream)
{
    // Two quads merged into a hexagon (two collinear edges), extruded: 8 faces, 12 points.
    const PolyMesh mesh = makeExtruded2D(2, 1, {0, 0, 0}, {2, 1, 1}, PlanarCellKind::Polygons);
    const MeshTopology topology = buildMeshTopology(mesh);
    ASSERT_EQ(topology.cellCount, 1);
    EXPECT_EQ(cellShape(mesh, topology, 0), CellShape::Polyhedron);
    std::vector<Label> nodes, stream;
    EXPECT_EQ(appendVtkCell(mesh, topology, 0, nodes, stream), VtkCellType::Polyhedron);
    EXPECT_EQ(nodes.size(), 12u);
    ASSERT_EQ(stream.front(), 8);
    // Volume from the outward face stream by the divergence theorem: the 2 × 1 × 1 box.
    double sixVolume = 0.0;
    std::size_t at = 1;
    for (Label f = 0; f < stream.front(); ++f) {
        const Label n = stream[at++];
        Vector3 centre, area;
        for (Label k = 0; k < n; ++k) {
            centre += mesh.points[stream[at + k]];
            area += cross(mesh.points[stream[at + k]], mesh.points[stream[at + (k + 1) % n]]);
        }
        sixVolume += dot(centre / static_cast<double>(n), area);
        at += static_cast<std::size_t>(n);
    }
    EXPECT_EQ(at, stream.size());
    EXPECT_NEAR(sixVolume / 6.0, 2.0, 1e-12);
}

TEST(CellShape, CountsThatMatchNoStandardShapeGivePolyhedra)
{
    // A unit cube whose top face is split into two triangles: 7 faces, 8 points.
    const PolyMesh split = singleCell({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
                                      {{0, 3, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}});
    EXPECT_TRUE(checkPolyMeshOrdering(split).empty());
    EXPECT_EQ(cellShape(split, buildMeshTopology(split), 0), CellShape::Polyhedron);
    // A square pyramid with its base split into two triangles: 6 triangles, 5 points.
    const PolyMesh splitPyramid = singleCell({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}},
                                             {{0, 3, 2}, {0, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
    EXPECT_TRUE(checkPolyMeshOrdering(splitPyramid).empty());
    EXPECT_EQ(cellShape(splitPyramid, buildMeshTopology(splitPyramid), 0), CellShape::Polyhedron);
}

TEST(CellShape, ExtrudedMixedMeshHasHexahedraAndPrisms)
{
    // 4 × 2 grid: quads for i < 2 (4 hexahedra), two triangles per cell elsewhere (8 prisms).
    const PolyMesh mesh = makeExtruded2D(4, 2, {0, 0, 0}, {4, 2, 1}, PlanarCellKind::Mixed);
    const MeshTopology topology = buildMeshTopology(mesh);
    const auto counts = countCellShapes(mesh, topology);
    EXPECT_EQ(counts[static_cast<int>(CellShape::Hexahedron)], 4);
    EXPECT_EQ(counts[static_cast<int>(CellShape::Prism)], 8);
    EXPECT_EQ(counts[static_cast<int>(CellShape::Polyhedron)], 0);
    // Every prism's VTK ordering: triangle normal away from the other triangle, i–(i+3) edges.
    for (Label c = 0; c < topology.cellCount; ++c) {
        std::vector<Label> nodes, stream;
        if (appendVtkCell(mesh, topology, c, nodes, stream) != VtkCellType::Wedge) continue;
        const auto& x = mesh.points;
        const auto edges = cellEdges(mesh, topology, c);
        for (int i = 0; i < 3; ++i) EXPECT_TRUE(isEdge(edges, nodes[i], nodes[i + 3]));
        const Vector3 normal = cross(x[nodes[1]] - x[nodes[0]], x[nodes[2]] - x[nodes[0]]);
        EXPECT_LT(dot(normal, x[nodes[3]] - x[nodes[0]]), 0.0);
        EXPECT_LT(dot(normal, x[nodes[4]] - x[nodes[1]]), 0.0);
    }
}

TEST(CellShape, WedgeCellsOnTheAxisArePrisms)
{
    // Cells touching the axis lose their axis face (collapsed): 2 triangles + 3 quads.
    const PolyMesh mesh = makeWedge2D(3, 2, {0, 0, 0}, {1, 1, 0}, 5.0);
    const MeshTopology topology = buildMeshTopology(mesh);
    const auto counts = countCellShapes(mesh, topology);
    EXPECT_EQ(counts[static_cast<int>(CellShape::Prism)], 3);
    EXPECT_EQ(counts[static_cast<int>(CellShape::Hexahedron)], 3);
    EXPECT_EQ(cellShapeName(CellShape::Prism), "prism");
}
