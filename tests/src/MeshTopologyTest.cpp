// MeshTopology (cell → faces / points, point → cells), the polyMesh ordering checker,
// the mesh generators and the cell-shape recognition with VTK node orderings.

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

bool hasMessageContaining(const std::vector<std::string>& messages, const std::string& text)
{
    return std::any_of(messages.begin(), messages.end(),
                       [&](const std::string& m) { return m.find(text) != std::string::npos; });
}

} // namespace

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
