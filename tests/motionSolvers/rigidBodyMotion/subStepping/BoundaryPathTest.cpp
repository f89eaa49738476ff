// Tests of BoundaryPath: a rigidly moving group of prescribed nodes follows its rigid motion
// (a rotation is split into rotations, not chords); any other group follows straight lines.
#include "BoundaryPath.hpp"

#include "SubStepSplitting.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace rbm::motion {
namespace {

Vector3 rotatedAbout(const Vector3& p, const Vector3& centre, double angle)
{
    const double c = std::cos(angle), s = std::sin(angle);
    const Vector3 r = p - centre;
    return centre + Vector3{c * r.x - s * r.y, s * r.x + c * r.y, 0.0};
}

TEST(BoundaryPath, ARotatedGroupIsHalfRotatedHalfWayAndAStretchedOneMovesOnStraightLines)
{
    // Group 0: a square of side 1 about (0.5, 0.5) turned by 60° about its centre. Group 1:
    // two nodes pulled apart (not rigid).
    const double angle = std::numbers::pi / 3.0;
    const Vector3 centre{0.5, 0.5, 0.0};
    const std::vector<Vector3> reference{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {3, 0, 0}, {4, 0, 0}};
    const std::vector<int> offsets{0, 4, 6};
    const std::vector<int> nodes{0, 1, 2, 3, 4, 5};
    std::vector<Vector3> to(reference.size());
    for (int node = 0; node < 4; ++node) to[node] = rotatedAbout(reference[node], centre, angle) - reference[node];
    to[4] = {-0.5, 0.0, 0.0};
    to[5] = {0.5, 0.0, 0.0};
    const std::vector<Vector3> from(reference.size());

    const BoundaryPath path(2, reference, offsets, nodes, from, to);
    EXPECT_FALSE(path.allRigid());
    EXPECT_NEAR(path.largestRigidAngle(), angle, 1e-12);
    const std::vector<Vector3> half = path.at(0.5);
    for (int node = 0; node < 4; ++node) {
        const Vector3 expected = rotatedAbout(reference[node], centre, angle / 2.0) - reference[node];
        EXPECT_NEAR(norm(half[node] - expected), 0.0, 1e-12) << node;
        // Not the chord's midpoint: the corner is 1/√2 (1 − cos 30°) ≈ 0.095 from it.
        EXPECT_GT(norm(half[node] - 0.5 * to[node]), 0.09) << node;
    }
    EXPECT_NEAR(norm(half[4] - Vector3{-0.25, 0, 0}), 0.0, 1e-15);
    EXPECT_NEAR(norm(half[5] - Vector3{0.25, 0, 0}), 0.0, 1e-15);
    // The end of the path is the target, bit for bit.
    const std::vector<Vector3> end = path.at(1.0);
    for (std::size_t node = 0; node < to.size(); ++node) EXPECT_EQ(end[node], to[node]);
}

TEST(BoundaryPath, AGroupThatOnlyTranslatesIsRigidWithoutRotation)
{
    const std::vector<Vector3> reference{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const std::vector<int> offsets{0, 4};
    const std::vector<int> nodes{0, 1, 2, 3};
    const std::vector<Vector3> to(4, Vector3{0.1, -0.2, 0.3});
    const std::vector<Vector3> from(4);
    const BoundaryPath path(3, reference, offsets, nodes, from, to);
    EXPECT_TRUE(path.allRigid());
    EXPECT_NEAR(path.largestRigidAngle(), 0.0, 1e-12);
    for (const Vector3& u : path.at(0.25)) EXPECT_NEAR(norm(u - Vector3{0.025, -0.05, 0.075}), 0.0, 1e-14);
}

TEST(SubStepSplitting, SplitsUpToItsDepthThenGivesUpForTheRestOfTheSolve)
{
    SubStepSplitting splitting(2);
    EXPECT_TRUE(splitting.allows(0));
    EXPECT_TRUE(splitting.accept(0, false));   // valid: kept
    EXPECT_FALSE(splitting.accept(0, true));   // inverted at depth 0: split
    EXPECT_FALSE(splitting.accept(1, true));   // and at depth 1
    EXPECT_TRUE(splitting.allows(2));
    EXPECT_TRUE(splitting.accept(2, true));    // at the deepest level: kept, splitting given up
    EXPECT_FALSE(splitting.allows(0));
    EXPECT_EQ(splitting.describe(), " (2 sub-step splits) (a sub-step still inverted cells after 2 splits)");

    const SubStepSplitting fixed(0);   // `subSteps N`: never split
    EXPECT_FALSE(fixed.allows(0));
    EXPECT_EQ(fixed.describe(), "");
}

} // namespace
} // namespace rbm::motion
