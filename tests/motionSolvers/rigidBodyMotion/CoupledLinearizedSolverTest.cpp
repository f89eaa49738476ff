// Tests of the coupled linearized solver (CoupledLinearizedSolver): a translation exact, the error
// of a small rotation shrinking with the square of its angle.

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

TEST(CoupledLinearized, ReproducesATranslationExactly)
{
    // Without rotation the small-angle model is exact: every free node translates. (A direct
    // solve, so that only the model is tested: the 3D default, matrix-free CG, stops at its
    // Krylov tolerance, 1e-10; MatrixFreeLinearizedTest checks it with a tighter one.)
    for (int dimension : {2, 3}) {
        const RigidCase c = rigidCase(dimension, 0.0, EdgeWeighting::inverseDistanceSquared);
        CoupledLinearizedSolver solver(*c.problem, {LinearSolverKind::direct});
        const RbmResult result = solver.solve(c.prescribed);
        EXPECT_TRUE(result.converged) << result.reason;
        EXPECT_LT(maximumPositionError(c, result), 1e-12);
        EXPECT_LT(result.energy, 1e-24);
    }
}

TEST(CoupledLinearized, ErrorOfASmallRotationShrinksWithTheSquareOfTheAngle)
{
    // The small-angle model errs by O(θ²) (eq 2.48: cos θ ≈ 1 drops θ²/2).
    for (int dimension : {2, 3}) {
        const RigidCase small = rigidCase(dimension, degrees(1.0), EdgeWeighting::uniform);
        const RigidCase half = rigidCase(dimension, degrees(0.5), EdgeWeighting::uniform);
        CoupledLinearizedSolver solverSmall(*small.problem);
        CoupledLinearizedSolver solverHalf(*half.problem);
        const double errorSmall = maximumPositionError(small, solverSmall.solve(small.prescribed));
        const double errorHalf = maximumPositionError(half, solverHalf.solve(half.prescribed));
        EXPECT_GT(errorSmall, 1e-6);
        EXPECT_NEAR(errorSmall / errorHalf, 4.0, 0.1) << dimension << "D";
    }
}

} // namespace
} // namespace rbm::motion
