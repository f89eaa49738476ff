// The untangler on its own (src/Untangling.hpp, no PETSc): a 2 × 2 × 2 hex box whose centre
// point was pushed out of the box, with the centre free, on a line, or on a plane that misses
// the box (no valid position).

#include "MeshGenerators.hpp"
#include "Untangling.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace {

using namespace rbm;

struct CentreCase {
    PolyMesh mesh = makeHexBox(2, 2, 2, {0, 0, 0}, {2, 2, 2});
    SimplexDecomposition cells = decomposeCells(mesh);
    static constexpr Label centre = 13;  // point (1, 1, 1)
    std::vector<UntanglePointConstraint> constraints;
    CentreCase() : constraints(mesh.points.size(), UntanglePointConstraint{true, {}, {}})
    {
        constraints[centre].fixed = false;
    }
    // Cells with a non-positive simplex.
    std::vector<Label> inverted(std::span<const Vector3> positions) const
    {
        const std::vector<double> volumes = simplexVolumes(cells, positions);
        std::vector<Label> result;
        for (Label s = 0; s < cells.simplexCount(); ++s)
            if (!(volumes[s] > 0.0)) result.push_back(cells.simplexCell[s]);
        std::sort(result.begin(), result.end());
        result.erase(std::unique(result.begin(), result.end()), result.end());
        return result;
    }
    UntangleResult run(std::vector<Vector3>& positions) const
    {
        return untangle(cells, mesh.points, constraints, positions,
                        [this](std::span<const Vector3> at) { return inverted(at); });
    }
};

TEST(Untangling, EverySimplexOfAValidHexBoxIsPositive)
{
    const CentreCase c;
    ASSERT_EQ(c.mesh.points[CentreCase::centre], (Vector3{1, 1, 1}));
    // 8 cells × 6 faces × 4 edges tetrahedra, each 1/24 of its unit cube.
    const std::vector<double> volumes = simplexVolumes(c.cells, c.mesh.points);
    ASSERT_EQ(volumes.size(), 8u * 6u * 4u);
    for (double v : volumes) EXPECT_NEAR(v, 1.0 / 24.0, 1e-15);
}

TEST(Untangling, MovesAFreePointBackAndLeavesFixedPointsBitForBit)
{
    const CentreCase c;
    std::vector<Vector3> positions = c.mesh.points;
    positions[CentreCase::centre] = {2.6, 1.3, 0.9};
    ASSERT_EQ(c.inverted(positions).size(), 4u);  // the four cells at x > 1
    const UntangleResult result = c.run(positions);
    EXPECT_TRUE(result.untangled()) << result.describe(positions, c.cells);
    EXPECT_EQ(result.initialInverted, 4);
    EXPECT_EQ(result.movedPoints, 1);
    EXPECT_TRUE(c.inverted(positions).empty());
    for (Label p = 0; p < c.mesh.pointCount(); ++p)
        if (p != CentreCase::centre) {
            EXPECT_EQ(positions[p], c.mesh.points[p]) << p;
        }
    EXPECT_LT(positions[CentreCase::centre].x, 2.0);
}

TEST(Untangling, APointOnALineMovesAlongItOnly)
{
    CentreCase c;
    c.constraints[CentreCase::centre] = {false, {1, 0, 0}, {0, 1, 0}};  // the line x = y = 1
    std::vector<Vector3> positions = c.mesh.points;
    positions[CentreCase::centre] = {1.0, 1.0, 2.7};
    const UntangleResult result = c.run(positions);
    EXPECT_TRUE(result.untangled()) << result.describe(positions, c.cells);
    EXPECT_EQ(positions[CentreCase::centre].x, 1.0);
    EXPECT_EQ(positions[CentreCase::centre].y, 1.0);
    EXPECT_LT(positions[CentreCase::centre].z, 2.0);
    EXPECT_GT(positions[CentreCase::centre].z, 0.0);
}

TEST(Untangling, APlaneThatMissesTheValidRegionIsReported)
{
    // On the plane z = 2.7 no position is valid: the cells stay inverted, and the point could
    // move, so they are not "stuck" (all points fixed) either.
    CentreCase c;
    c.constraints[CentreCase::centre] = {false, {0, 0, 1}, {}};
    std::vector<Vector3> positions = c.mesh.points;
    positions[CentreCase::centre] = {1.2, 0.9, 2.7};
    const UntangleResult result = c.run(positions);
    EXPECT_FALSE(result.untangled());
    EXPECT_EQ(result.remainingCells.size(), 4u);  // the four upper cells
    EXPECT_TRUE(result.stuckCells.empty());
    EXPECT_EQ(positions[CentreCase::centre].z, 2.7);
    EXPECT_NE(result.describe(positions, c.cells).find("4 cell(s) stay inverted: cell 4 at ("), std::string::npos)
        << result.describe(positions, c.cells);
}

} // namespace
