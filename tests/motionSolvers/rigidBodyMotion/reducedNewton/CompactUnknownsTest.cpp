#include "CompactUnknowns.hpp"

#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rbm::motion {
namespace {

TEST(CompactUnknowns, SetAndCompactAreInverseOnThePlanesAndMovingKeepsSlidingNodesOnThem)
{
    for (int dimension : {2, 3}) {
        const GridCase c = gridCase(dimension, 4, false, 1);
        const RbmProblem& problem = *c.problem;
        const CompactUnknowns unknowns(problem, c.prescribed);
        ASSERT_EQ(unknowns.size(), static_cast<std::size_t>(problem.unknownNodeCount()) * dimension);
        // Any compact values are put onto the planes; compact() of that gives them back.
        std::vector<double> values(unknowns.size());
        for (std::size_t k = 0; k < values.size(); ++k) values[k] = 0.01 * std::sin(1.0 + static_cast<double>(k));
        std::vector<Vector3> u = c.prescribed;
        unknowns.set(u, values);
        const std::vector<double> back = unknowns.compact(u);
        std::vector<Vector3> again = c.prescribed;
        unknowns.set(again, back);
        for (std::size_t node = 0; node < u.size(); ++node) EXPECT_EQ(again[node], u[node]);
        // Moving along any direction keeps u·n = c on every sliding node.
        std::vector<Vector3> trial;
        unknowns.moveAlong(u, values, 0.7, trial);
        for (int node : problem.unknownNodes()) {
            if (problem.kind(node) != NodeKind::sliding) continue;
            const Vector3& n = problem.slidingNormal(node);
            EXPECT_NEAR(dot(trial[node], n), dot(c.prescribed[node], n), 1e-15) << node;
            EXPECT_NEAR(dot(u[node], n), dot(c.prescribed[node], n), 1e-15) << node;
        }
    }
}

TEST(CompactUnknowns, WithoutSlidingNodesTheOffsetsAreZeroAndTheValuesPassUnchanged)
{
    // No sliding node: no offset array is held (a solve's 24 bytes a node), slidingOffset() is
    // zeros, and set() and compact() move the values across as they are, to the bit.
    const GridCase c = gridCase(3, 4, false, 1);
    std::vector<NodeConstraint> constraints = c.problem->constraints();
    for (NodeConstraint& constraint : constraints)
        if (constraint.kind == NodeKind::sliding) constraint = NodeConstraint{};
    const RbmProblem problem(3, c.points, c.problem->graph(), constraints);
    ASSERT_FALSE(problem.hasSlidingNodes());
    const CompactUnknowns unknowns(problem, c.prescribed);
    ASSERT_EQ(unknowns.size(), static_cast<std::size_t>(problem.unknownNodeCount()) * 3);
    EXPECT_EQ(unknowns.slidingOffset(), std::vector<double>(unknowns.size(), 0.0));
    std::vector<double> values(unknowns.size());
    for (std::size_t k = 0; k < values.size(); ++k) values[k] = 0.01 * std::sin(1.0 + static_cast<double>(k));
    std::vector<Vector3> u = c.prescribed;
    unknowns.set(u, values);
    EXPECT_EQ(unknowns.compact(u), values);
    const std::vector<int>& nodes = problem.unknownNodes();
    for (std::size_t a = 0; a < nodes.size(); ++a) EXPECT_EQ(u[nodes[a]].y, values[3 * a + 1]);
}

} // namespace
} // namespace rbm::motion
