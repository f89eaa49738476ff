// Tests of smallestCellSizeRatio: the 1st percentile of the cells' size after over before.
#include "CellSizeRatio.hpp"

#include "MeshGenerators.hpp"
#include "PseudoTwoDExtraction.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbm {
namespace {

TEST(CellSizeRatio, ScalingTheMeshGivesTheScaleAndThePercentileIgnoresTheFewestCells)
{
    // 10 × 10 hexahedra in a box; x scaled by 0.5: every volume halves.
    const PolyMesh mesh = makeHexBox(10, 10, 1, {0, 0, 0}, {1, 1, 0.1});
    std::vector<Vector3> scaled(mesh.points);
    for (Vector3& p : scaled) p.x *= 0.5;
    EXPECT_NEAR(smallestCellSizeRatio(mesh, mesh.points, scaled), 0.5, 1e-12);

    // The planar form: 100 quadrilaterals, scaled the same way.
    const PolyMesh extruded = makeExtruded2D(10, 10, {0, 0, 0}, {1, 1, 0.1});
    const PseudoTwoDMesh twoD = extractPseudoTwoD(extruded);
    std::vector<Vector3> moved(twoD.planar.points);
    for (Vector3& p : moved) p.x *= 0.5;
    EXPECT_NEAR(smallestCellSizeRatio(twoD.planar, moved), 0.5, 1e-12);
    // The point at (0.1, 0.1) moved along the diagonal to (0.01, 0.01): cell (0, 0) keeps a
    // tenth of its area (shoelace: 0.001 of 0.01), cells (1, 0) and (0, 1) keep theirs (the
    // move is parallel to their diagonal through that point), cell (1, 1) grows. Sorted, the
    // ratios are 0.1, 1, 1, ...: the 1st percentile of 100 cells is the second, 1, not the one
    // cell the motion squeezed.
    moved = twoD.planar.points;
    auto movePoint = [&](Vector3 from, Vector3 to) {
        for (Vector3& p : moved)
            if (std::abs(p.x - from.x) < 1e-12 && std::abs(p.y - from.y) < 1e-12) p = {to.x, to.y, p.z};
    };
    movePoint({0.1, 0.1, 0}, {0.01, 0.01, 0});
    EXPECT_NEAR(smallestCellSizeRatio(twoD.planar, moved), 1.0, 1e-12);
    // A second cell squeezed the same way, at the opposite corner: now the second smallest is 0.1.
    movePoint({0.9, 0.9, 0}, {0.99, 0.99, 0});
    EXPECT_NEAR(smallestCellSizeRatio(twoD.planar, moved), 0.1, 1e-12);
}

} // namespace
} // namespace rbm
