// MeshTopology (cell → faces / points, point → cells), the polyMesh ordering checker,
// the mesh generators and the cell-shape recognition with VTK node orderings.

#include "CellShape.hpp"
#include "InputError.hpp"
#include "MeshGenerators.hpp"
#include "MeshTopology.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

using namespace rbm;

namespace {

// A single cell from outward-oriented faces, all in one boundary patch "walls".
PolyMesh singleCell(std::vector<Vector3> points, const std::vector<std::vector<Label>>& faces)
{
    PolyMesh mesh;
    mesh.points = std::move(points);
    for (const auto& face : faces) {
        mesh.addFace(face);
        mesh.owner.push_back(0);
    }
    Patch walls;
    walls.name = "walls";
    walls.type = "wall";
    walls.startFace = 0;
    walls.faceCount = static_cast<Label>(faces.size());
    mesh.patches.push_back(walls);
    return mesh;
}

PolyMesh unitTetrahedron()
{
    return singleCell({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

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

bool hasMessageContaining(const std::vector<std::string>& messages, const std::string& text)
{
    return std::any_of(messages.begin(), messages.end(),
                       [&](const std::string& m) { return m.find(text) != std::string::npos; });
}

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

// ------------------------------------------------------------------------------------------
// Generators and topology

TEST(MeshGenerators, HexBoxHasTheCountsOfItsGrid)
{
    const PolyMesh mesh = makeHexBox(3, 2, 4, {0, 0, 0}, {3, 2, 4});
    EXPECT_EQ(mesh.pointCount(), 4 * 3 * 5);
    EXPECT_EQ(mesh.cellCount(), 24);
    // (nx-1) ny nz + nx (ny-1) nz + nx ny (nz-1) internal, 2 (ny nz + nx nz + nx ny) boundary faces.
    EXPECT_EQ(mesh.internalFaceCount(), 2 * 2 * 4 + 3 * 1 * 4 + 3 * 2 * 3);
    EXPECT_EQ(mesh.faceCount() - mesh.internalFaceCount(), 2 * (2 * 4 + 3 * 4 + 3 * 2));
    ASSERT_EQ(mesh.patches.size(), 6u);
    const std::vector<Label> expected{8, 8, 12, 12, 6, 6};
    for (std::size_t p = 0; p < 6; ++p) EXPECT_EQ(mesh.patches[p].faceCount, expected[p]) << mesh.patches[p].name;
    EXPECT_EQ(mesh.patches[0].name, "xMin");
    EXPECT_EQ(mesh.points.back(), (Vector3{3, 2, 4}));
}

TEST(MeshGenerators, HexBoxSidesWithTheSameNameShareOnePatch)
{
    const PolyMesh mesh = makeHexBox(2, 2, 2, {0, 0, 0}, {1, 1, 1},
                                     {BoxPatch{"walls", "wall"}, BoxPatch{"walls", "wall"}, BoxPatch{"inlet"},
                                      BoxPatch{"walls", "wall"}, BoxPatch{"walls", "wall"}, BoxPatch{"walls", "wall"}});
    ASSERT_EQ(mesh.patches.size(), 2u);
    EXPECT_EQ(mesh.patches[0].name, "walls");
    EXPECT_EQ(mesh.patches[0].type, "wall");
    EXPECT_EQ(mesh.patches[0].faceCount, 20);
    EXPECT_EQ(mesh.patches[1].name, "inlet");
    EXPECT_EQ(mesh.patches[1].faceCount, 4);
    EXPECT_TRUE(checkPolyMeshOrdering(mesh).empty());
}

TEST(MeshGenerators, EveryGeneratedMeshFollowsOpenFoamOrdering)
{
    std::vector<std::pair<std::string, PolyMesh>> meshes;
    meshes.emplace_back("hex box", makeHexBox(3, 4, 2, {-1, -2, 0}, {2, 2, 0.5}));
    for (auto kind : {PlanarCellKind::Quadrilaterals, PlanarCellKind::Triangles, PlanarCellKind::Mixed,
                      PlanarCellKind::Polygons}) {
        for (int axis = 0; axis < 3; ++axis) {
            for (bool separate : {false, true}) {
                meshes.emplace_back("extruded kind " + std::to_string(static_cast<int>(kind)) + " axis "
                                        + std::to_string(axis),
                                    makeExtruded2D(4, 3, {0, 0, -0.05}, {2, 1.5, 0.05}, kind, {axis, separate}));
            }
        }
        meshes.emplace_back("wedge on axis", makeWedge2D(4, 3, {0, 0, 0}, {1, 0.5, 0}, 5.0, kind));
        meshes.emplace_back("wedge off axis", makeWedge2D(4, 3, {0, 0.2, 0}, {1, 0.5, 0}, 10.0, kind));
    }
    for (const auto& [name, mesh] : meshes) {
        const auto problems = checkPolyMeshOrdering(mesh);
        EXPECT_TRUE(problems.empty()) << name << ": " << (problems.empty() ? "" : problems.front());
    }
}

TEST(MeshTopology, HexBoxCellsHaveSixFacesAndEightPoints)
{
    const PolyMesh mesh = makeHexBox(3, 3, 3, {0, 0, 0}, {1, 1, 1});
    const MeshTopology topology = buildMeshTopology(mesh);
    ASSERT_EQ(topology.cellCount, 27);
    EXPECT_EQ(topology.pointCount, 64);
    for (Label c = 0; c < topology.cellCount; ++c) {
        EXPECT_EQ(topology.facesOf(c).size(), 6u);
        EXPECT_EQ(topology.pointsOf(c).size(), 8u);
        EXPECT_TRUE(std::is_sorted(topology.pointsOf(c).begin(), topology.pointsOf(c).end()));
        EXPECT_TRUE(std::is_sorted(topology.facesOf(c).begin(), topology.facesOf(c).end()));
    }
    // Cell (1,1,1) = 13 has the points (i,j,k) with i,j,k in {1,2}: labels i + 4j + 16k.
    const std::vector<Label> expected{21, 22, 25, 26, 37, 38, 41, 42};
    EXPECT_TRUE(std::equal(topology.pointsOf(13).begin(), topology.pointsOf(13).end(), expected.begin(), expected.end()));
    // Corner point: one cell; interior point (1,1,1) = 21: eight cells.
    EXPECT_EQ(topology.cellsOf(0).size(), 1u);
    const std::vector<Label> aroundInterior{0, 1, 3, 4, 9, 10, 12, 13};
    EXPECT_TRUE(std::equal(topology.cellsOf(21).begin(), topology.cellsOf(21).end(), aroundInterior.begin(),
                           aroundInterior.end()));
    EXPECT_EQ(topology.pointCells.size(), 27u * 8u);
}

TEST(MeshTopology, TwoTetrahedraSharingAFace)
{
    // Cell 0 = (0,1,2,3), cell 1 = (0,1,2,4) on the other side of face (0,1,2).
    PolyMesh mesh;
    mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.3, 0.3, -1}};
    const std::vector<std::vector<Label>> faces{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {1, 0, 4}, {2, 1, 4}, {0, 2, 4}};
    const std::vector<Label> owners{0, 0, 0, 0, 1, 1, 1};
    for (std::size_t f = 0; f < faces.size(); ++f) {
        mesh.addFace(faces[f]);
        mesh.owner.push_back(owners[f]);
    }
    mesh.neighbour = {1};
    Patch walls;
    walls.name = "walls";
    walls.startFace = 1;
    walls.faceCount = 6;
    mesh.patches.push_back(walls);
    EXPECT_TRUE(checkPolyMeshOrdering(mesh).empty());

    const MeshTopology topology = buildMeshTopology(mesh);
    ASSERT_EQ(topology.cellCount, 2);
    const std::vector<Label> faces0{0, 1, 2, 3}, faces1{0, 4, 5, 6}, points1{0, 1, 2, 4}, cellsOf0{0, 1};
    EXPECT_TRUE(std::ranges::equal(topology.facesOf(0), faces0));
    EXPECT_TRUE(std::ranges::equal(topology.facesOf(1), faces1));
    EXPECT_TRUE(std::ranges::equal(topology.pointsOf(1), points1));
    EXPECT_TRUE(std::ranges::equal(topology.cellsOf(0), cellsOf0));
    EXPECT_EQ(topology.cellsOf(3).size(), 1u);
    EXPECT_EQ(topology.cellsOf(4).front(), 1);
}

TEST(MeshTopology, OutOfRangePointLabelIsAnInputError)
{
    PolyMesh mesh = unitTetrahedron();
    mesh.facePoints[2] = 7;
    EXPECT_THROW(buildMeshTopology(mesh), InputError);
}

// ------------------------------------------------------------------------------------------
// The ordering checker finds each kind of violation

TEST(PolyMeshOrdering, SwappedInternalFacesBreakUpperTriangularOrder)
{
    PolyMesh mesh = makeHexBox(2, 2, 1, {0, 0, 0}, {1, 1, 1});
    // Faces 0 (0→1) and 1 (0→2): swap the owner/neighbour lists and the points together.
    std::swap(mesh.neighbour[0], mesh.neighbour[1]);
    std::vector<Label> f0(mesh.face(0).begin(), mesh.face(0).end()), f1(mesh.face(1).begin(), mesh.face(1).end());
    std::copy(f1.begin(), f1.end(), mesh.facePoints.begin());
    std::copy(f0.begin(), f0.end(), mesh.facePoints.begin() + 4);
    const auto problems = checkPolyMeshOrdering(mesh);
    ASSERT_FALSE(problems.empty());
    EXPECT_TRUE(hasMessageContaining(problems, "upper-triangular")) << problems.front();
}

TEST(PolyMeshOrdering, OwnerAboveNeighbourIsReported)
{
    PolyMesh mesh = makeHexBox(2, 1, 1, {0, 0, 0}, {1, 1, 1});
    std::swap(mesh.owner[0], mesh.neighbour[0]);
    const auto problems = checkPolyMeshOrdering(mesh);
    EXPECT_TRUE(hasMessageContaining(problems, "face 0 has owner 1 and neighbour 0; expected owner < neighbour"));
}

TEST(PolyMeshOrdering, OneFlippedFaceMakesItsCellInconsistent)
{
    PolyMesh mesh = makeHexBox(2, 2, 2, {0, 0, 0}, {1, 1, 1});
    const Label f = mesh.patches[3].startFace;   // a yMax face
    std::reverse(mesh.facePoints.begin() + mesh.faceOffsets[f], mesh.facePoints.begin() + mesh.faceOffsets[f + 1]);
    const auto problems = checkPolyMeshOrdering(mesh);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_TRUE(hasMessageContaining(problems, "cell " + std::to_string(mesh.owner[f]) + " is not closed"));
}

TEST(PolyMeshOrdering, AllFacesReversedGiveNegativeVolumes)
{
    // Consistent but inward orientation: only the volume check can see it.
    PolyMesh mesh = makeHexBox(1, 1, 1, {0, 0, 0}, {1, 1, 1});
    for (Label f = 0; f < mesh.faceCount(); ++f) {
        std::reverse(mesh.facePoints.begin() + mesh.faceOffsets[f], mesh.facePoints.begin() + mesh.faceOffsets[f + 1]);
    }
    const auto problems = checkPolyMeshOrdering(mesh);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_TRUE(hasMessageContaining(problems, "cell 0 has volume -1")) << problems.front();
    EXPECT_TRUE(checkPolyMeshOrdering(mesh, {.checkCellVolumes = false}).empty());
}

TEST(PolyMeshOrdering, TheCheckHandsOverTheTopologyItBuilt)
{
    // A valid 3 x 2 x 2 box: no problem, and the topology of its 12 cells (6 faces, 8 points
    // each; corner point 0 in cell 0 only).
    const PolyMesh mesh = makeHexBox(3, 2, 2, {0, 0, 0}, {3, 2, 2});
    MeshTopology topology;
    EXPECT_TRUE(checkPolyMeshOrdering(mesh, {}, topology).empty());
    EXPECT_EQ(topology.cellCount, 12);
    EXPECT_EQ(topology.pointCount, 4 * 3 * 3);
    for (Label c = 0; c < topology.cellCount; ++c) {
        EXPECT_EQ(topology.facesOf(c).size(), 6u);
        EXPECT_EQ(topology.pointsOf(c).size(), 8u);
    }
    EXPECT_EQ(std::vector<Label>(topology.cellsOf(0).begin(), topology.cellsOf(0).end()), std::vector<Label>{0});
    const MeshTopology built = buildMeshTopology(mesh);
    EXPECT_EQ(topology.cellFaces, built.cellFaces);
    EXPECT_EQ(topology.cellPoints, built.cellPoints);
    EXPECT_EQ(topology.pointCells, built.pointCells);

    // Faces that break the rules: the problems, and the topology left alone.
    PolyMesh broken = mesh;
    std::swap(broken.owner[0], broken.neighbour[0]);
    MeshTopology untouched;
    EXPECT_FALSE(checkPolyMeshOrdering(broken, {}, untouched).empty());
    EXPECT_EQ(untouched.cellCount, 0);
    EXPECT_TRUE(untouched.cellFaces.empty());
}

TEST(PolyMeshOrdering, PatchesMustBeContiguousAndCoverTheBoundary)
{
    PolyMesh mesh = makeHexBox(1, 1, 1, {0, 0, 0}, {1, 1, 1});
    mesh.patches[2].startFace += 1;
    mesh.patches.pop_back();
    const auto problems = checkPolyMeshOrdering(mesh);
    EXPECT_TRUE(hasMessageContaining(problems, "patch 'yMin' starts at face 3; expected 2"));
    EXPECT_TRUE(hasMessageContaining(problems, "every boundary face must belong to exactly one patch"));
}

TEST(PolyMeshOrdering, ValidateTopologyThrowsAnInputErrorNamingTheFile)
{
    PolyMesh mesh = unitTetrahedron();
    mesh.facePoints[1] = mesh.facePoints[0];   // face 0 uses point 0 twice
    try {
        validateTopology(mesh, "constant/polyMesh/faces");
        FAIL() << "expected an InputError";
    } catch (const InputError& error) {
        EXPECT_EQ(error.file(), "constant/polyMesh/faces");
        EXPECT_NE(error.message().find("face 0 uses point 0 more than once"), std::string::npos) << error.what();
    }
    EXPECT_NO_THROW(validateTopology(unitTetrahedron()));
}

// ------------------------------------------------------------------------------------------
// Cell shapes and VTK orderings

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
