// Tests of the tests' mesh generators (testSupport/MeshGenerators).

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
