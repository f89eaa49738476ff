#pragma once
// Problems and checks shared by the reduced Newton method's tests: options to round-off, the
// grid cases with free sides, one rigid body in a fixed box, and the comparison of minima.

#include "GridCases.hpp"
#include "ReducedNewtonSolver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

namespace rbm::motion {

// The method to round-off (displacementTolerance 0), for the tests of its exactness; the
// default stops within 1e-6 of each node's shortest edge.
inline ReducedNewtonOptions roundOffOptions()
{
    ReducedNewtonOptions options;
    options.displacementTolerance = 0.0;
    return options;
}

// gridCase with its sliding sides free (no sliding node: K is solved as a scalar system).
inline GridCase withFreeSides(GridCase c)
{
    std::vector<NodeConstraint> constraints(c.points.size());
    for (int node = 0; node < c.problem->nodeCount(); ++node)
        if (c.problem->kind(node) == NodeKind::prescribed) constraints[node].kind = NodeKind::prescribed;
        else c.prescribed[node] = Vector3{};
    c.problem = std::make_unique<RbmProblem>(c.dimension, c.points, c.problem->graph(), constraints,
                                             EdgeWeighting::inverseDistanceSquared);
    return c;
}

// The same boundary solved without and with the turned cold start (options otherwise alike):
// {plain, turned}.
inline std::pair<RbmResult, RbmResult> plainAndTurnedSolves(const RbmProblem& problem, ReducedNewtonOptions options,
                                                     const std::vector<Vector3>& prescribed)
{
    options.turnedStart = false;
    const RbmResult plain = ReducedNewtonSolver(problem, options).solve(prescribed);
    options.turnedStart = true;
    return {plain, ReducedNewtonSolver(problem, options).solve(prescribed)};
}

// Both converged to the same minimum (energy to 1e-10, every node to 1e-8), a non-trivial one.
inline void expectTheSameMinimum(const RbmResult& expected, const RbmResult& result)
{
    ASSERT_TRUE(expected.converged) << expected.reason;
    ASSERT_TRUE(result.converged) << result.reason;
    EXPECT_GT(expected.energy, 1e-3);
    EXPECT_NEAR(result.energy, expected.energy, 1e-10 * expected.energy);
    EXPECT_LT(largestDifference(result.displacement, expected.displacement), 1e-8);
}

// One rigid body in a fixed frame: the nodes of the grid's central square (a body) turned by
// `degrees` about its centre and shifted, the outer boundary fixed, the nodes between free.
// Returns the problem's constraints and the prescribed displacement.
struct BodyInBox {
    std::vector<NodeConstraint> constraints;
    std::vector<Vector3> prescribed;
};
inline BodyInBox bodyInBox(const GridCase& grid, int n, double degrees)
{
    BodyInBox box{std::vector<NodeConstraint>(grid.points.size()), std::vector<Vector3>(grid.points.size())};
    const double angle = degrees * 3.14159265358979 / 180.0;
    for (std::size_t node = 0; node < grid.points.size(); ++node) {
        const int i = static_cast<int>(node) % (n + 1), j = static_cast<int>(node) / (n + 1);
        const bool outer = i == 0 || j == 0 || i == n || j == n;
        const bool body = i >= 6 && i <= 10 && j >= 6 && j <= 10;
        if (!outer && !body) continue;
        box.constraints[node].kind = NodeKind::prescribed;
        if (body) {
            const double dx = grid.points[node].x - 0.5, dy = grid.points[node].y - 0.5;
            box.prescribed[node] = {std::cos(angle) * dx - std::sin(angle) * dy - dx + 0.001 * degrees,
                                    std::sin(angle) * dx + std::cos(angle) * dy - dy - 0.02 * degrees / 30.0, 0.0};
        }
    }
    return box;
}

} // namespace rbm::motion
