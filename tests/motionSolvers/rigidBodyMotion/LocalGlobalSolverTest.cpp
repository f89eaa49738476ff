// Tests of the local/global solver (LocalGlobalSolver): Anderson acceleration.

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

TEST(LocalGlobal, AndersonAccelerationReachesTheSameMinimumInFewerIterations)
{
    // The loosely held case of §3.1.3, where the plain alternation crawls.
    const SquaresCase c = squaresCase(11, 2, degrees(45.0));
    std::vector<NodeConstraint> constraints = c.constraints;
    for (std::size_t node = 0; node < constraints.size(); ++node)
        if (norm(c.prescribed[node]) == 0.0) constraints[node].kind = NodeKind::free;
    // Pull one outer corner so the answer is not a rigid motion.
    std::vector<Vector3> prescribed = c.prescribed;
    constraints[0].kind = NodeKind::prescribed;
    prescribed[0] = {-5.0, 3.0, 0.0};
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, constraints, EdgeWeighting::uniform);
    LocalGlobalOptions plainOptions;
    plainOptions.accelerationDepth = 0;
    LocalGlobalSolver plain(problem, plainOptions);
    LocalGlobalSolver accelerated(problem);
    const RbmResult slow = plain.solve(prescribed);
    const RbmResult fast = accelerated.solve(prescribed);
    ASSERT_TRUE(slow.converged) << slow.reason;
    ASSERT_TRUE(fast.converged) << fast.reason;
    EXPECT_GT(slow.energy, 1e-3);
    EXPECT_NEAR(fast.energy, slow.energy, 1e-8 * slow.energy);
    EXPECT_LT(fast.iterations * 5, slow.iterations) << fast.reason << " vs " << slow.reason;
}

} // namespace
} // namespace rbm::motion
