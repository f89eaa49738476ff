#include "RelativeDisplacement.hpp"

#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace rbm::motion {
namespace {

TEST(RelativeDisplacement, IsTheLargestNodeDisplacementInUnitsOfItsShortestEdge)
{
    const GridCase c = gridCase(2, 4, false, 1);
    const RbmProblem& problem = *c.problem;
    const RelativeDisplacement measure(problem, true);
    std::vector<double> v(static_cast<std::size_t>(problem.unknownNodeCount()) * 2, 0.0);
    EXPECT_EQ(measure.largest(v), 0.0);
    // One node moved by (3, 4) × its shortest edge: 5.
    const int a = problem.unknownNodeCount() / 2, i = problem.unknownNodes()[a];
    const CellNeighbourGraph& graph = problem.graph();
    double shortest = 1e300;
    for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
        shortest = std::min(shortest, norm(problem.referencePoints()[graph.neighbours[e]] - problem.referencePoints()[i]));
    v[2 * a] = 3.0 * shortest;
    v[2 * a + 1] = 4.0 * shortest;
    EXPECT_NEAR(measure.largest(v), 5.0, 1e-14);
}

} // namespace
} // namespace rbm::motion
