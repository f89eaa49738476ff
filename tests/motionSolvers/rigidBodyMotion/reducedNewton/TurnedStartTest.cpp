#include "TurnedStart.hpp"

#include "PetscTestEnvironment.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace rbm::motion {
namespace {

TEST(TurnedStart, TurnedStartIsKeptOnlyWhereItsEnergyIsLower)
{
    // The body in the box turned 30° (and shifted): the cold start then also tries the harmonic
    // interpolation of the turn (every node turned by s θ and shifted by s t, s harmonic, 1 on
    // the body, 0 on the outer boundary). On this even grid it starts higher than the
    // interpolated displacements (energy 31 against 16.5), so the plain start is kept: the same
    // steps and the same minimum as without the option. (On the boundary-layer airfoil the
    // turned start is the lower one by 30×:
    // RigidBodyMotionSolverTimeSteps.ColdAirfoilStepStartsFromTheTurnedInterpolation.)
    const int n = 16;
    const GridCase grid = gridCase(2, n, false, 29);
    const BodyInBox box = bodyInBox(grid, n, 30.0);
    const RbmProblem problem(2, grid.points, grid.problem->graph(), box.constraints, EdgeWeighting::inverseDistanceSquared);
    const auto [expected, result] = plainAndTurnedSolves(problem, roundOffOptions(), box.prescribed);
    expectTheSameMinimum(expected, result);
    EXPECT_EQ(result.iterations, expected.iterations);
    EXPECT_EQ(result.linearIterations, expected.linearIterations);
    EXPECT_EQ(result.displacement, expected.displacement);  // the same start, the same arithmetic
}

TEST(TurnedStart, AWarmStartWithoutHistoryAlsoTriesTheTurnFromTheGuess)
{
    // From the result at 15° to 30°, warm-started without a history for the secant (the second
    // step of a series, a restart): the start also tries the turn since the guess, interpolated
    // harmonically (the body's motion from 15° to 30° turned in from the guess's positions).
    // With and without, the same minimum as the cold solve at 30°, to round-off; the turned
    // start is kept only where its energy is lower, so it never takes more iterations here.
    const int n = 16;
    const GridCase grid = gridCase(2, n, false, 29);
    const BodyInBox first = bodyInBox(grid, n, 15.0), second = bodyInBox(grid, n, 30.0);
    const RbmProblem problem(2, grid.points, grid.problem->graph(), first.constraints, EdgeWeighting::inverseDistanceSquared);
    const RbmResult expected = ReducedNewtonSolver(problem, roundOffOptions()).solve(second.prescribed);
    std::vector<RbmResult> warm;
    for (const bool turned : {false, true}) {
        ReducedNewtonOptions options = roundOffOptions();
        options.turnedStart = turned;
        ReducedNewtonSolver solver(problem, options);
        const RbmResult guess = solver.solve(first.prescribed);
        ASSERT_TRUE(guess.converged) << guess.reason;
        warm.push_back(solver.solve(second.prescribed, &guess));
        expectTheSameMinimum(expected, warm.back());
    }
    std::printf("body in a box, 15 -> 30 deg warm: %d Newton / %d CG plain, %d / %d with the turned start\n",
                warm[0].iterations, warm[0].linearIterations, warm[1].iterations, warm[1].linearIterations);
    EXPECT_LE(warm[1].linearIterations, warm[0].linearIterations);
}

TEST(TurnedStart, In3DTheTurnedStartFollowsATwistToTheSameMinimum)
{
    // A hexahedral box, bottom fixed, top turned 40° about the vertical (one rigid body in a
    // fixed frame), sides free: the 3D turned start (Kabsch fit of the top's motion,
    // s harmonic, every node turned by exp(s [ω]×) about the top's centre and shifted by s t)
    // starts near the twisted minimum, so Newton needs no more steps, and ends at the same
    // minimum as the plain start, with K factorised (direct) and with K⁻¹ as one multigrid
    // cycle (iterative: s by CG to 1e-2, then Newton corrects).
    for (LinearSolverKind kind : {LinearSolverKind::direct, LinearSolverKind::iterative}) {
        const GridCase c = withFreeSides(gridCase(3, 8, false, 31));
        std::vector<Vector3> prescribed(c.points.size());
        const double angle = 40.0 * 3.14159265358979 / 180.0;
        for (int node = 0; node < c.problem->nodeCount(); ++node) {
            const Vector3& p = c.points[node];
            if (p.z != 1.0) continue;
            const double dx = p.x - 0.5, dy = p.y - 0.5;
            prescribed[node] = {std::cos(angle) * dx - std::sin(angle) * dy - dx, std::sin(angle) * dx + std::cos(angle) * dy - dy, 0.0};
        }
        ReducedNewtonOptions options = roundOffOptions();
        options.linearSolver = kind;
        const auto [expected, result] = plainAndTurnedSolves(*c.problem, options, prescribed);
        expectTheSameMinimum(expected, result);
        EXPECT_LE(result.iterations, expected.iterations);
        // The starts themselves (no Newton step): the turned one is far closer to the minimum.
        options.maximumIterations = 0;
        const auto [plainStartSolve, turnedStartSolve] = plainAndTurnedSolves(*c.problem, options, prescribed);
        const double plainStart = plainStartSolve.energy, turnedStart = turnedStartSolve.energy;
        // Measured: the energy above the minimum (88.71) at the plain start 94.6 (direct) and 124.9
        // (one cycle), at the turned start 11.3 for both.
        EXPECT_LT(turnedStart - expected.energy, 0.25 * (plainStart - expected.energy)) << static_cast<int>(kind);
    }
}

TEST(TurnedStart, In3DTheTurnedStartOfARigidBoundaryMotionIsThatMotion)
{
    // Every prescribed node (top and bottom) turned 70° about an oblique axis and shifted: s = 1
    // at every node (K 1 = b), so the turned start is the rigid motion itself and the solve
    // takes no Newton step; without the turned start the interpolated displacement vectors
    // shorten the edges and Newton has to find the rigid motion.
    const GridCase c = withFreeSides(gridCase(3, 6, false, 37));
    const Vector3 axis = Vector3{1.0, -2.0, 2.0} / 3.0;
    const double angle = 70.0 * 3.14159265358979 / 180.0;
    const Vector3 shift{0.3, -0.1, 0.2}, centre{0.5, 0.5, 0.5};
    auto rigid = [&](const Vector3& p) {
        const Vector3 r = p - centre;
        // Rodrigues, written out: r cos θ + (a × r) sin θ + a (a·r)(1 − cos θ).
        return r * std::cos(angle) + cross(axis, r) * std::sin(angle) + axis * (dot(axis, r) * (1.0 - std::cos(angle))) +
               centre + shift - p;
    };
    std::vector<Vector3> prescribed(c.points.size());
    for (int node = 0; node < c.problem->nodeCount(); ++node)
        if (!c.problem->isUnknown(node)) prescribed[node] = rigid(c.points[node]);
    ReducedNewtonOptions options;
    options.linearSolver = LinearSolverKind::direct;
    const auto [expected, result] = plainAndTurnedSolves(*c.problem, options, prescribed);
    ASSERT_TRUE(expected.converged) << expected.reason;
    ASSERT_TRUE(result.converged) << result.reason;
    EXPECT_GT(expected.iterations, 0);
    EXPECT_EQ(result.iterations, 0);
    double largestError = 0.0;
    for (int node = 0; node < c.problem->nodeCount(); ++node)
        largestError = std::max(largestError, norm(result.displacement[node] - rigid(c.points[node])));
    EXPECT_LT(largestError, 1e-5) << "cell size 1/6";
}

} // namespace
} // namespace rbm::motion
