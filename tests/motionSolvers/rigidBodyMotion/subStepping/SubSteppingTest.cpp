// Tests of the sub-steps (SubStepping): the automatic count, linearized and Newton steps in
// sub-steps.

#include "CoupledLinearizedSolver.hpp"
#include "CoupledNewtonSolver.hpp"
#include "DecoupledSolver.hpp"
#include "LocalGlobalSolver.hpp"
#include "PetscTestEnvironment.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"
#include "ReducedNewtonSolver.hpp"
#include "RigidMotionModes.hpp"
#include "SubStepping.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <numeric>
#include <ostream>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace rbm::motion::coreCases;

namespace rbm::motion {

namespace {

TEST(SubSteps, AutomaticCountMatchesAHandComputation)
{
    // A 4 × 3 grid with columns at x = 0, 1, 1.5, 3.5 and rows at y = 0, 2, 2.5.
    TestMesh mesh = structuredGrid(4, 3, 1, 1.0, {0.0, 0.0, 0.0});
    const double columns[4] = {0.0, 1.0, 1.5, 3.5};
    const double rows[3] = {0.0, 2.0, 2.5};
    for (std::size_t node = 0; node < mesh.points.size(); ++node)
        mesh.points[node] = {columns[mesh.gridIndex[node][0]], rows[mesh.gridIndex[node][1]], 0.0};
    std::vector<NodeConstraint> constraints = prescribeBoundary(mesh);
    const RbmProblem problem(2, mesh.points, mesh.graph, constraints, EdgeWeighting::uniform);
    auto nodeAt = [&](int i, int j) {
        for (std::size_t node = 0; node < mesh.points.size(); ++node)
            if (mesh.gridIndex[node][0] == i && mesh.gridIndex[node][1] == j) return static_cast<int>(node);
        return -1;
    };
    std::vector<Vector3> prescribed(mesh.points.size());
    EXPECT_EQ(automaticSubStepCount(problem, prescribed), 1);  // nothing moves
    // (3.5, 0): nearest neighbours (1.5, 0) and (3.5, 2) at 2; |u| = 5 → 5/2 = 2.5 → 3 steps.
    prescribed[nodeAt(3, 0)] = {3.0, 4.0, 0.0};
    EXPECT_EQ(automaticSubStepCount(problem, prescribed), 3);
    // (0, 2.5): nearest (0, 2) at 0.5; |u| = 0.5 → exactly one shortest distance → 2 steps.
    prescribed[nodeAt(0, 2)] = {0.3, 0.4, 0.0};
    EXPECT_EQ(automaticSubStepCount(problem, prescribed), 3);
    // (1.5, 0): nearest (1, 0) at 0.5; |u| = 2 → 4 → 5 steps, the largest.
    prescribed[nodeAt(2, 0)] = {1.2, -1.6, 0.0};
    EXPECT_EQ(automaticSubStepCount(problem, prescribed), 5);
    // A free node's entry does not count.
    prescribed[nodeAt(1, 1)] = {100.0, 0.0, 0.0};
    EXPECT_EQ(automaticSubStepCount(problem, prescribed), 5);
}

TEST(SubSteps, IncrementalLinearizedStepsConvergeToALargeRigidRotation)
{
    // Each increment turns the previous mesh by θ/n; the small-angle model errs by O((θ/n)²)
    // per increment, O(θ²/n) in total: the error must fall like 1/n.
    const double angle = degrees(60.0);
    const RigidCase c = rigidCase(2, angle, EdgeWeighting::inverseDistanceSquared);
    const BoundaryMotion turn = [&](double fraction) {
        RigidMotion partial = c.motion;
        partial.rotation = planarRotation(fraction * angle);
        partial.translation = fraction * c.motion.translation;
        return prescribedFrom(c.mesh, c.problem->constraints(), [&](const Vector3& x) { return partial.displacement(x); });
    };
    const RbmSolverFactory linearized = [](const RbmProblem& p) { return std::make_unique<CoupledLinearizedSolver>(p); };
    std::vector<double> errors;
    for (int count : {1, 10, 40}) {
        SubStepOptions options;
        options.count = count;
        const SubSteppedResult result = solveInSubSteps(*c.problem, turn, linearized, options);
        ASSERT_TRUE(result.converged) << result.reason;
        EXPECT_EQ(result.subStepCount, count);
        errors.push_back(maximumPositionError(c, result));
        // The rotations compose to the body's rotation.
        if (count == 40) {
            for (int node : c.problem->unknownNodes()) EXPECT_NEAR(result.rotation[node].z, angle, 0.02);
        }
    }
    EXPECT_GT(errors[0], 0.05 * c.meshSize);  // one linearized step cannot turn by 60°
    EXPECT_NEAR(errors[1] / errors[2], 4.0, 0.6);
    EXPECT_LT(errors[2], errors[0] / 20.0);
}

TEST(SubSteps, NewtonInSubStepsOnTheInitialMeshReachesTheDirectResult)
{
    // Continuation against the initial mesh: the result depends only on the final boundary.
    const SquaresCase c = squaresCase(21, 4, degrees(30.0));
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::inverseDistanceSquared);
    CoupledNewtonSolver newton(problem);
    const RbmResult direct = newton.solve(c.prescribed);
    SubStepOptions options;
    options.reference = SubStepReference::initialMesh;
    const SubSteppedResult stepped = solveInSubSteps(
        problem, c.prescribed, [](const RbmProblem& p) { return std::make_unique<CoupledNewtonSolver>(p); }, options);
    EXPECT_GT(stepped.subStepCount, 1);  // the rim moves by more than a cell
    ASSERT_TRUE(stepped.converged) << stepped.reason;
    EXPECT_NEAR(stepped.energy, direct.energy, 1e-9 * direct.energy);
    for (std::size_t node = 0; node < c.mesh.points.size(); ++node)
        ASSERT_LT(norm(stepped.displacement[node] - direct.displacement[node]), 1e-7);
}

} // namespace
} // namespace rbm::motion
