// Tests of CurvedPatchProjection through the solver: the points of a curved zeroGradient patch
// slide along it and stay on its surface, where the tangent plane alone leaves it by s²/2R.
#include "CurvedPatchProjection.hpp"

#include "MeshGenerators.hpp"
#include "PetscTestEnvironment.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace rbm::motion {
namespace {

// A quarter annulus, radii 1 (xMin) and 2 (xMax), 6 cells across, 48 around, two layers in z:
// the hex box's x → radius 1 + x, y → angle y π/2.
PolyMesh quarterAnnulus()
{
    PolyMesh mesh = makeHexBox(6, 48, 2, {0, 0, 0}, {1, 1, 0.2});
    for (Vector3& p : mesh.points) {
        const double radius = 1.0 + p.x, angle = p.y * std::numbers::pi / 2.0;
        p = {radius * std::cos(angle), radius * std::sin(angle), p.z};
    }
    return mesh;
}

TEST(CurvedPatchProjection, PointsSlidingOnACurvedZeroGradientPatchStayOnItsSurface)
{
    // The inner arc turns 20° about the z axis; every other patch is zeroGradient (slides).
    const PolyMesh mesh = quarterAnnulus();
    const io::Dictionary field = io::Dictionary::parseText(R"(
        boundaryField
        {
            xMin { type fixedValue; value uniform (0 0 0); }
            ".*" { type zeroGradient; }
        })", "0/pointDisplacement");
    auto solver = rbm::test::makeSolver(mesh, "", &field);
    const double turn = 20.0 * std::numbers::pi / 180.0;
    const Label inner = mesh.findPatch("xMin");
    std::vector<Vector3> turned;
    for (Label p : patchMeshPoints(mesh, inner)) {
        const Vector3& x = mesh.points[p];
        turned.push_back(Vector3{std::cos(turn) * x.x - std::sin(turn) * x.y, std::sin(turn) * x.x + std::cos(turn) * x.y,
                                 x.z} -
                         x);
    }
    solver->setPatchDisplacement("xMin", turned);
    const MotionSolveReport report = solver->solve();
    ASSERT_TRUE(report.converged) << report.reason;
    EXPECT_EQ(report.invertedCellCount, 0);
    EXPECT_TRUE(report.warnings.empty());

    // The outer arc's facets are chords of the circle r = 2 across 1.875°: on them a point is
    // within the sagitta 2 (1 − cos(π/192)) = 2.7e-4 of the circle.
    const std::vector<Vector3> points = solver->curPoints();
    double largestOff = 0.0, largestSlide = 0.0, largestOffPlane = 0.0;
    for (Label p : patchMeshPoints(mesh, mesh.findPatch("xMax"))) {
        const Vector3& x0 = mesh.points[p];
        if (std::abs(x0.x) < 1e-12 || std::abs(x0.y) < 1e-12) continue;   // also on yMin, yMax
        largestOff = std::max(largestOff, std::abs(std::hypot(points[p].x, points[p].y) - 2.0));
        largestSlide = std::max(largestSlide, norm(points[p] - x0));
        // Where the arc meets zMin and zMax (z = 0, 0.2), its points stay on those planes too.
        if (x0.z < 1e-12 || x0.z > 0.2 - 1e-12) largestOffPlane = std::max(largestOffPlane, std::abs(points[p].z - x0.z));
    }
    EXPECT_GT(largestSlide, 0.1);        // they do slide along the arc
    EXPECT_LT(largestOff, 2.8e-4);       // and stay on its surface, in the middle layer and on its edges
    EXPECT_LT(largestOffPlane, 1e-12);
    // The tangent plane alone would leave the circle by √(R² + s²) − R for a slide s: 0.01 here.
    EXPECT_GT(std::hypot(2.0, largestSlide) - 2.0, 0.005);
}

} // namespace
} // namespace rbm::motion
