// The cell-neighbour graph N(i) of docs/method.md §1: nodes sharing at least one cell.

#include "CellNeighbourGraph.hpp"
#include "MeshGenerators.hpp"
#include "MeshTopology.hpp"
#include "PseudoTwoDExtraction.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

using namespace rbm;

namespace {

// Sorted, no self, symmetric, offsets consistent: the invariants every graph must satisfy.
void expectWellFormed(const CellNeighbourGraph& graph)
{
    ASSERT_EQ(graph.offsets.front(), 0);
    ASSERT_EQ(static_cast<std::size_t>(graph.offsets.back()), graph.neighbours.size());
    for (Label i = 0; i < graph.nodeCount(); ++i) {
        const auto row = graph.neighboursOf(i);
        EXPECT_TRUE(std::adjacent_find(row.begin(), row.end(), std::greater_equal<>()) == row.end())
            << "row " << i << " is not strictly increasing";
        for (Label j : row) {
            EXPECT_NE(j, i);
            const auto back = graph.neighboursOf(j);
            EXPECT_TRUE(std::binary_search(back.begin(), back.end(), i)) << i << " -> " << j << " has no reverse";
        }
    }
}

std::vector<Label> row(const CellNeighbourGraph& graph, Label i)
{
    const auto r = graph.neighboursOf(i);
    return {r.begin(), r.end()};
}

// Quads of an nx × ny grid of nodes i + (nx+1) j.
void quadGrid(Label nx, Label ny, std::vector<Label>& offsets, std::vector<Label>& points)
{
    offsets = {0};
    points.clear();
    for (Label j = 0; j < ny; ++j) {
        for (Label i = 0; i < nx; ++i) {
            const Label p = i + (nx + 1) * j;
            points.insert(points.end(), {p, p + 1, p + nx + 2, p + nx + 1});
            offsets.push_back(static_cast<Label>(points.size()));
        }
    }
}

} // namespace

TEST(CellNeighbourGraph, StructuredQuadGridInteriorNodeHasEightNeighbours)
{
    std::vector<Label> offsets, points;
    quadGrid(4, 4, offsets, points);   // nodes i + 5 j
    const CellNeighbourGraph graph = buildCellNeighbourGraph(25, offsets, points);
    expectWellFormed(graph);
    EXPECT_EQ(row(graph, 12), (std::vector<Label>{6, 7, 8, 11, 13, 16, 17, 18}));   // node (2, 2)
    EXPECT_EQ(graph.neighboursOf(0).size(), 3u);                                      // corner
    EXPECT_EQ(graph.neighboursOf(2).size(), 5u);                                      // edge
    // Directed edge count: 2 × (horizontal 20 + vertical 20 + two diagonals per quad 32).
    EXPECT_EQ(graph.edgeCount(), 2 * (20 + 20 + 32));
}

TEST(CellNeighbourGraph, StructuredHexGridInteriorNodeHasTwentySixNeighbours)
{
    const PolyMesh mesh = makeHexBox(3, 3, 3, {0, 0, 0}, {1, 1, 1});
    const CellNeighbourGraph graph = buildCellNeighbourGraph(mesh);
    expectWellFormed(graph);
    ASSERT_EQ(graph.nodeCount(), 64);
    auto node = [](Label i, Label j, Label k) { return i + 4 * j + 16 * k; };
    EXPECT_EQ(graph.neighboursOf(node(1, 1, 1)).size(), 26u);
    EXPECT_EQ(graph.neighboursOf(node(2, 1, 2)).size(), 26u);
    EXPECT_EQ(graph.neighboursOf(node(1, 1, 0)).size(), 17u);   // on a face
    EXPECT_EQ(graph.neighboursOf(node(1, 0, 0)).size(), 11u);   // on an edge
    EXPECT_EQ(graph.neighboursOf(node(0, 0, 0)).size(), 7u);    // corner
    // Interior node: every node of the 3 × 3 × 3 block around it except itself.
    std::vector<Label> expected;
    for (Label k = 0; k < 3; ++k) {
        for (Label j = 0; j < 3; ++j) {
            for (Label i = 0; i < 3; ++i) {
                if (i != 1 || j != 1 || k != 1) expected.push_back(node(i, j, k));
            }
        }
    }
    EXPECT_EQ(row(graph, node(1, 1, 1)), expected);
}

TEST(CellNeighbourGraph, CubeSplitIntoSixTetrahedraCountedByHand)
{
    // Freudenthal split of the unit cube (vertex label x + 2y + 4z): six tetrahedra around
    // the diagonal 0–7. 0 and 7 touch all 7 other vertices; every other vertex lies in two
    // tetrahedra that share the diagonal and one cube edge, giving 4 neighbours. 19 edges:
    // 12 cube edges + 6 face diagonals + the body diagonal.
    const std::vector<Label> points{0, 1, 3, 7, 0, 1, 5, 7, 0, 2, 3, 7, 0, 2, 6, 7, 0, 4, 5, 7, 0, 4, 6, 7};
    const std::vector<Label> offsets{0, 4, 8, 12, 16, 20, 24};
    const CellNeighbourGraph graph = buildCellNeighbourGraph(8, offsets, points);
    expectWellFormed(graph);
    EXPECT_EQ(row(graph, 0), (std::vector<Label>{1, 2, 3, 4, 5, 6, 7}));
    EXPECT_EQ(row(graph, 7), (std::vector<Label>{0, 1, 2, 3, 4, 5, 6}));
    EXPECT_EQ(row(graph, 1), (std::vector<Label>{0, 3, 5, 7}));
    EXPECT_EQ(row(graph, 6), (std::vector<Label>{0, 2, 4, 7}));
    EXPECT_EQ(graph.edgeCount(), 2 * 19);
}

TEST(CellNeighbourGraph, TetrahedraSharingAFaceDoNotLinkTheirApexes)
{
    const std::vector<Label> points{0, 1, 2, 3, 0, 1, 2, 4};
    const std::vector<Label> offsets{0, 4, 8};
    const CellNeighbourGraph graph = buildCellNeighbourGraph(5, offsets, points);
    expectWellFormed(graph);
    EXPECT_EQ(row(graph, 0), (std::vector<Label>{1, 2, 3, 4}));
    EXPECT_EQ(row(graph, 3), (std::vector<Label>{0, 1, 2}));
    EXPECT_EQ(row(graph, 4), (std::vector<Label>{0, 1, 2}));
}

TEST(CellNeighbourGraph, IsolatedNodeHasNoNeighbours)
{
    const std::vector<Label> points{0, 1, 2};
    const std::vector<Label> offsets{0, 3};
    const CellNeighbourGraph graph = buildCellNeighbourGraph(4, offsets, points);
    expectWellFormed(graph);
    EXPECT_TRUE(graph.neighboursOf(3).empty());
    EXPECT_EQ(graph.nodeCount(), 4);
}

TEST(CellNeighbourGraph, PolyhedralAndMixedMeshesAreWellFormed)
{
    for (auto kind : {PlanarCellKind::Triangles, PlanarCellKind::Mixed, PlanarCellKind::Polygons}) {
        expectWellFormed(buildCellNeighbourGraph(makeExtruded2D(4, 3, {0, 0, 0}, {1, 1, 0.1}, kind)));
    }
    expectWellFormed(buildCellNeighbourGraph(makeWedge2D(4, 3, {0, 0, 0}, {1, 1, 0}, 5.0)));
}

TEST(CellNeighbourGraph, OneLayerExtrusionLinksTwinsAndBothPlanes)
{
    // A node of the 3D layer sees the front and back copies of its 2D neighbours and its own
    // twin: 2 × 8 + 1 = 17 for an interior node of a quad grid.
    const PolyMesh mesh = makeExtruded2D(4, 4, {0, 0, 0}, {1, 1, 0.1});
    const CellNeighbourGraph graph3D = buildCellNeighbourGraph(mesh);
    EXPECT_EQ(graph3D.neighboursOf(12).size(), 17u);
    const PseudoTwoDMesh flat = extractPseudoTwoD(mesh);
    const CellNeighbourGraph graph2D = buildCellNeighbourGraph(flat.planar);
    expectWellFormed(graph2D);
    EXPECT_EQ(row(graph2D, flat.nodeOfPoint[12]), (std::vector<Label>{6, 7, 8, 11, 13, 16, 17, 18}));
}

TEST(CellNeighbourGraph, TriangulatedGridInteriorNodeHasSixNeighbours)
{
    // Every quad cut along its (i,j)-(i+1,j+1) diagonal: the classic 6-regular interior.
    const PseudoTwoDMesh flat = extractPseudoTwoD(makeExtruded2D(4, 4, {0, 0, 0}, {1, 1, 0.1}, PlanarCellKind::Triangles));
    const CellNeighbourGraph graph = buildCellNeighbourGraph(flat.planar);
    EXPECT_EQ(row(graph, 12), (std::vector<Label>{6, 7, 11, 13, 17, 18}));
}

TEST(CellNeighbourGraph, RejectsLabelsOutsideTheNodeRange)
{
    const std::vector<Label> points{0, 1, 5};
    const std::vector<Label> offsets{0, 3};
    EXPECT_THROW(buildCellNeighbourGraph(4, offsets, points), std::invalid_argument);
    const std::vector<Label> badOffsets{0, 2};
    EXPECT_THROW(buildCellNeighbourGraph(6, badOffsets, points), std::invalid_argument);
}
