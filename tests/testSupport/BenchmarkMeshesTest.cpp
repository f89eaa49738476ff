// The benchmark's meshes (testSupport/BenchmarkMeshes.hpp): counts worked out by hand from the grid,
// OpenFOAM's ordering and orientation rules (checkPolyMeshOrdering), volumes against the
// box minus the hole, and the 2D extraction of the pseudo-3D meshes.

#include "BenchmarkMeshes.hpp"
#include "MeshGeometry.hpp"
#include "MeshTopology.hpp"
#include "PseudoTwoDExtraction.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>

namespace rbm {
namespace {

Label patchFaces(const PolyMesh& mesh, const std::string& name)
{
    const Label patch = mesh.findPatch(name);
    return patch < 0 ? -1 : mesh.patches[patch].faceCount;
}

double totalVolume(const PolyMesh& mesh)
{
    const MeshGeometry geometry = computeMeshGeometry(mesh);
    double minimum = geometry.cellVolumes.front();
    for (double volume : geometry.cellVolumes) minimum = std::min(minimum, volume);
    EXPECT_GT(minimum, 0.0);
    return std::accumulate(geometry.cellVolumes.begin(), geometry.cellVolumes.end(), 0.0);
}

// n = 8: the hole is the 2 × 2 (× 2) block of cells 3..4 and has one interior point (line).
TEST(BenchmarkMeshes, QuadrilateralBoxWithHoleHasTheCountsOfTheGrid)
{
    const PolyMesh mesh = makeBoxWithHole(8, HoleMeshCellKind::quadrilaterals);
    EXPECT_TRUE(checkPolyMeshOrdering(mesh).empty());
    EXPECT_EQ(mesh.cellCount(), 64 - 4);
    EXPECT_EQ(mesh.pointCount(), 2 * (81 - 1));
    EXPECT_EQ(patchFaces(mesh, "inner"), 4 * 2);
    EXPECT_EQ(patchFaces(mesh, "outer"), 4 * 8);
    EXPECT_EQ(patchFaces(mesh, "frontAndBack"), 2 * 60);
    EXPECT_EQ(mesh.patches[mesh.findPatch("frontAndBack")].type, "empty");
    // Internal faces: 2 × 8 × 7 grid lines inside the box, minus the 2 × 2 × 3 ones the hole removes.
    EXPECT_EQ(mesh.internalFaceCount(), 2 * 8 * 7 - 2 * 2 * 3);
    // (4 − 1/4) of area, one cell (2/8) thick.
    EXPECT_NEAR(totalVolume(mesh), 3.75 * 0.25, 1e-12);
}

TEST(BenchmarkMeshes, TriangleBoxWithHoleExtractsToTwoDimensions)
{
    const PolyMesh mesh = makeBoxWithHole(8, HoleMeshCellKind::triangles);
    EXPECT_TRUE(checkPolyMeshOrdering(mesh).empty());
    EXPECT_EQ(mesh.cellCount(), 2 * 60);
    EXPECT_EQ(patchFaces(mesh, "frontAndBack"), 2 * 120);
    EXPECT_NEAR(totalVolume(mesh), 3.75 * 0.25, 1e-12);
    const PseudoTwoDMesh twoD = extractPseudoTwoD(mesh);
    EXPECT_EQ(twoD.nodeCount(), 80);
    EXPECT_EQ(twoD.planar.cellCount(), 120);
    EXPECT_EQ(twoD.nodeCount(), static_cast<Label>(boxWithHoleNodeCount(8, HoleMeshCellKind::triangles)));
}

TEST(BenchmarkMeshes, HexahedralBoxWithHoleHasTheCountsOfTheGrid)
{
    const PolyMesh mesh = makeBoxWithHole(8, HoleMeshCellKind::hexahedra);
    EXPECT_TRUE(checkPolyMeshOrdering(mesh).empty());
    EXPECT_EQ(mesh.cellCount(), 512 - 8);
    EXPECT_EQ(mesh.pointCount(), 729 - 1);
    EXPECT_EQ(mesh.pointCount(), static_cast<Label>(boxWithHoleNodeCount(8, HoleMeshCellKind::hexahedra)));
    EXPECT_EQ(patchFaces(mesh, "inner"), 6 * 4);
    EXPECT_EQ(patchFaces(mesh, "outer"), 6 * 64);
    EXPECT_EQ(mesh.patches.size(), 2u);
    EXPECT_NEAR(totalVolume(mesh), 8.0 - 0.125, 1e-12);
}

// Kuhn's six tetrahedra per cube share their face diagonals with the neighbouring cubes, so the
// faces match up (every face at most twice, every cell closed) and the surface triangles are
// the cube faces cut in two.
TEST(BenchmarkMeshes, TetrahedralBoxWithHoleIsConforming)
{
    const PolyMesh mesh = makeBoxWithHole(8, HoleMeshCellKind::tetrahedra);
    EXPECT_TRUE(checkPolyMeshOrdering(mesh).empty());
    EXPECT_EQ(mesh.cellCount(), 6 * 504);
    EXPECT_EQ(mesh.pointCount(), 728);
    EXPECT_EQ(patchFaces(mesh, "inner"), 2 * 24);
    EXPECT_EQ(patchFaces(mesh, "outer"), 2 * 384);
    // Euler: faces = (4 × cells + boundary faces) / 2.
    EXPECT_EQ(mesh.faceCount(), (4 * 6 * 504 + 2 * 24 + 2 * 384) / 2);
    EXPECT_NEAR(totalVolume(mesh), 8.0 - 0.125, 1e-12);
}

TEST(BenchmarkMeshes, CellsPerSideGivesTheClosestNodeCount)
{
    // n = 96: 97² − 23² = 8880; n = 104: 105² − 25² = 10400; n = 112: 113² − 27² = 12040.
    EXPECT_EQ(boxWithHoleNodeCount(104, HoleMeshCellKind::quadrilaterals), 10400.0);
    EXPECT_EQ(boxWithHoleCellsPerSide(1e4, HoleMeshCellKind::quadrilaterals), 104);
    // 3D, n = 40: 41³ − 9³ = 68192; n = 48: 49³ − 11³ = 116318 (closer to 1e5 than 68192).
    EXPECT_EQ(boxWithHoleCellsPerSide(1e5, HoleMeshCellKind::tetrahedra), 48);
}

TEST(BenchmarkMeshes, CellsPerSideMustBeAMultipleOfEight)
{
    EXPECT_THROW(makeBoxWithHole(12, HoleMeshCellKind::hexahedra), std::invalid_argument);
    EXPECT_THROW(makeBoxWithHole(0, HoleMeshCellKind::quadrilaterals), std::invalid_argument);
}

TEST(BenchmarkMeshes, AssemblyRejectsAFaceSharedByThreeCells)
{
    // Three tetrahedra on the triangle 0 1 2.
    std::vector<Vector3> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 1, 1}};
    const std::vector<Label> offsets{0, 4, 8, 12};
    const std::vector<Label> cells{0, 1, 2, 3, 0, 1, 2, 4, 0, 1, 2, 5};
    std::vector<Patch> patches{{"walls", "wall", {}, 0, 0, {}}};
    EXPECT_THROW(assemblePolyMeshFromCells(points, offsets, cells, patches, [](const Vector3&) { return 0; }),
                 std::invalid_argument);
}

} // namespace
} // namespace rbm
