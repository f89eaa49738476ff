// Tests of the matrix-free coupled linearized solve (MatrixFreeLinearizedSystem,
// ReducedLinearizedOperator) and of Newton on the reduced nonlinear energy (ReducedNewtonSolver): the reduced gradient against finite differences and against the
// full linearized energy, and the solution against the assembled, directly factorised
// system, in 2D and 3D, with free, prescribed, sliding and mirror nodes.

#include "CoupledLinearizedSolver.hpp"
#include "CoupledNewtonSolver.hpp"
#include "GridCases.hpp"
#include "MatrixFreeLinearizedSystem.hpp"
#include "PetscTestEnvironment.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"
#include "ReducedLinearizedOperator.hpp"
#include "ReducedNewtonSolver.hpp"
#include "ThreadCount.hpp"
#include "LocalGlobalSolver.hpp"
#include "VectorInstructions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

static ::testing::Environment* const petscEnvironment =
    ::testing::AddGlobalTestEnvironment(new rbm::test::PetscTestEnvironment);

namespace rbm::motion {
namespace {

TEST(ReducedLinearizedOperator, GradientMatchesFiniteDifferencesOfTheReducedEnergy)
{
    for (int dimension : {2, 3}) {
        const GridCase c = gridCase(dimension, 4, true, 7);
        const RbmProblem& problem = *c.problem;
        const ReducedLinearizedOperator reduced(problem);
        const RbmEnergy energy(problem, RotationModel::smallAngle, c.prescribed);
        std::mt19937 random(3);
        std::uniform_real_distribution<double> value(-0.05, 0.05);
        std::vector<Vector3> displacement = c.prescribed;
        for (int node : problem.unknownNodes())
            displacement[node] = {value(random), value(random), dimension == 3 ? value(random) : 0.0};

        // E_reduced(u) = E(u, best ω(u)), evaluated through the full linearized energy.
        auto reducedEnergy = [&](const std::vector<Vector3>& u) {
            std::vector<Vector3> rotation(problem.nodeCount());
            reduced.bestRotations(u, rotation);
            std::vector<double> unknowns(problem.unknownCount());
            packUnknowns(problem, RbmState{u, rotation}, unknowns);
            return energy.value(unknowns);
        };
        std::vector<double> gradient(reduced.size());
        reduced.gradient(displacement, gradient);

        // The best rotations zero the rotation part of the full gradient, and the
        // displacement part equals the reduced gradient (envelope theorem).
        std::vector<Vector3> rotation(problem.nodeCount());
        reduced.bestRotations(displacement, rotation);
        std::vector<double> unknowns(problem.unknownCount()), fullGradient(problem.unknownCount());
        packUnknowns(problem, RbmState{displacement, rotation}, unknowns);
        energy.gradient(unknowns, fullGradient);
        const int bs = problem.blockSize();
        double largestRotationPart = 0.0, largestMismatch = 0.0, largestGradient = 0.0;
        for (int a = 0; a < problem.unknownNodeCount(); ++a) {
            const int node = problem.unknownNodes()[a];
            for (int q = dimension; q < bs; ++q) {
                double component = fullGradient[a * bs + q];
                // A mirror node's rotation is held to its normal (x): only that part must vanish.
                if (problem.rotatesAboutNormalOnly(node) && q != 3) component = 0.0;
                largestRotationPart = std::max(largestRotationPart, std::abs(component));
            }
            for (int q = 0; q < dimension; ++q) {
                largestMismatch = std::max(largestMismatch, std::abs(fullGradient[a * bs + q] - gradient[a * dimension + q]));
                largestGradient = std::max(largestGradient, std::abs(gradient[a * dimension + q]));
            }
            if (problem.rotatesAboutNormalOnly(node)) {
                EXPECT_EQ(rotation[node].y, 0.0);
                EXPECT_EQ(rotation[node].z, 0.0);
            }
        }
        EXPECT_GT(largestGradient, 1e-2) << dimension;
        EXPECT_LT(largestRotationPart, 1e-12 * largestGradient) << dimension;
        EXPECT_LT(largestMismatch, 1e-12 * largestGradient) << dimension;

        // Central differences are exact for a quadratic up to rounding.
        const double h = 1e-4;
        double largestError = 0.0;
        for (int a = 0; a < problem.unknownNodeCount(); a += 3) {
            for (int q = 0; q < dimension; ++q) {
                std::vector<Vector3> plus = displacement, minus = displacement;
                plus[problem.unknownNodes()[a]][q] += h;
                minus[problem.unknownNodes()[a]][q] -= h;
                const double difference = (reducedEnergy(plus) - reducedEnergy(minus)) / (2.0 * h);
                largestError = std::max(largestError, std::abs(difference - gradient[a * dimension + q]));
            }
        }
        EXPECT_LT(largestError, 1e-7 * largestGradient) << dimension;
    }
}

TEST(MatrixFreeLinearized, EqualsTheAssembledDirectSolution)
{
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, false}, {3, true}}) {
        const GridCase c = gridCase(dimension, dimension == 2 ? 12 : 6, mirror, 11);
        ASSERT_TRUE(c.problem->hasSlidingNodes());
        CoupledLinearizedSolver direct(*c.problem, {LinearSolverKind::direct, 1e-10});
        CoupledLinearizedSolver matrixFree(*c.problem, {LinearSolverKind::matrixFree, 1e-12});
        const RbmResult expected = direct.solve(c.prescribed);
        const RbmResult result = matrixFree.solve(c.prescribed);
        ASSERT_TRUE(expected.converged);
        ASSERT_TRUE(result.converged) << result.reason;
        EXPECT_GT(result.linearIterations, 2);
        EXPECT_LT(result.linearIterations, 60) << dimension << "D";
        // Within 1e-8 of the cell size (1/n) in displacement; rotations alike.
        EXPECT_GT(largestDifference(expected.displacement, std::vector<Vector3>(expected.displacement.size())), 1e-2);
        EXPECT_LT(largestDifference(result.displacement, expected.displacement), 1e-9) << dimension << "D" << mirror;
        EXPECT_LT(largestDifference(result.rotation, expected.rotation), 1e-8) << dimension << "D" << mirror;
        EXPECT_NEAR(result.energy, expected.energy, 1e-9 * expected.energy);
        // Sliding nodes stay on their planes exactly.
        for (int node = 0; node < c.problem->nodeCount(); ++node) {
            if (c.problem->kind(node) == NodeKind::sliding && c.points[node].x == 0.0) {
                EXPECT_NEAR(result.displacement[node].x, 0.01, 1e-15);
            }
        }
        // A warm start from the answer needs (almost) no iterations.
        const RbmResult again = matrixFree.solve(c.prescribed, &result);
        EXPECT_LE(again.linearIterations, 2);
        EXPECT_LT(largestDifference(again.displacement, expected.displacement), 1e-9);
    }
}

TEST(MatrixFreeLinearized, ReportsTheResidualOfTheLinearizedGradient)
{
    // residualNorm = ‖P∇E_lin‖ at the result, whichever way it is computed: the assembled
    // path forms it as M δ − rhs, the matrix-free one from the reduced gradient. Checked
    // against RbmEnergy's own gradient on a solve stopped early (a residual well above rounding)
    // and on exact solves (rounding only, far below the right-hand side).
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, true}}) {
        const GridCase c = gridCase(dimension, dimension == 2 ? 12 : 6, mirror, 17);
        const RbmEnergy energy(*c.problem, RotationModel::smallAngle, c.prescribed);
        auto independent = [&](const RbmResult& result) {
            std::vector<double> unknowns(c.problem->unknownCount()), gradient(c.problem->unknownCount());
            packUnknowns(*c.problem, result, unknowns);
            energy.gradient(unknowns, gradient);
            c.problem->projectSliding(gradient);
            double sum = 0.0;
            for (double g : gradient) sum += g * g;
            return std::sqrt(sum);
        };
        const std::vector<Vector3> zero(c.points.size());
        RbmResult start;
        static_cast<RbmState&>(start) = RbmState{c.prescribed, zero};
        const double initial = independent(start);

        CoupledLinearizedSolver rough(*c.problem, {LinearSolverKind::matrixFree, 1e-2});
        const RbmResult early = rough.solve(c.prescribed);
        EXPECT_GT(early.residualNorm, 1e-6 * initial) << dimension;
        EXPECT_NEAR(early.residualNorm, independent(early), 1e-9 * initial) << dimension;

        for (const LinearSolverKind kind : {LinearSolverKind::direct, LinearSolverKind::matrixFree}) {
            CoupledLinearizedSolver solver(*c.problem, {kind, 1e-12});
            const RbmResult result = solver.solve(c.prescribed);
            EXPECT_GE(result.residualNorm, 0.0);
            EXPECT_LT(result.residualNorm, 1e-9 * initial) << dimension;
            EXPECT_LT(independent(result), 1e-9 * initial) << dimension;
        }
    }
}

TEST(MatrixFreeLinearized, ReproducesATranslationExactly)
{
    for (int dimension : {2, 3}) {
        GridCase c = gridCase(dimension, 5, false, 5);
        const Vector3 shift{0.02, -0.03, dimension == 3 ? 0.04 : 0.0};
        // Sliding planes get the normal part of the shift; everything prescribed moves by it.
        std::vector<Vector3> prescribed(c.points.size(), shift);
        CoupledLinearizedSolver matrixFree(*c.problem, {LinearSolverKind::matrixFree, 1e-13});
        const RbmResult result = matrixFree.solve(prescribed);
        ASSERT_TRUE(result.converged) << result.reason;
        double largest = 0.0;
        for (const Vector3& u : result.displacement) largest = std::max(largest, norm(u - shift));
        EXPECT_LT(largest, 1e-12) << dimension;
        double rotation = 0.0;
        for (const Vector3& omega : result.rotation) rotation = std::max(rotation, norm(omega));
        EXPECT_LT(rotation, 1e-11) << dimension;
    }
}

TEST(MatrixFreeLinearized, ResultsDoNotDependOnTheThreadCount)
{
    // 13³ nodes, 57 000 directed edges: above the threading threshold (ThreadCount.hpp).
    const GridCase c = gridCase(3, 12, true, 13);
    ASSERT_TRUE(worthThreading(c.problem->graph().neighbours.size()));
    const ReducedLinearizedOperator reduced(*c.problem);
    std::mt19937 random(5);
    std::uniform_real_distribution<double> value(-0.1, 0.1);
    std::vector<double> x(reduced.size());
    for (double& entry : x) entry = value(random);
    const int before = threadCount();
    std::vector<std::vector<double>> products, solutions;
    for (int threads : {1, 2, 3}) {
        setThreadCount(threads);
        std::vector<double> y(reduced.size());
        reduced.apply(x, y);
        products.push_back(y);
        CoupledLinearizedSolver solver(*c.problem, {LinearSolverKind::matrixFree, 1e-10});
        const RbmResult result = solver.solve(c.prescribed);
        std::vector<double> unknowns(c.problem->unknownCount());
        packUnknowns(*c.problem, result, unknowns);
        solutions.push_back(unknowns);
    }
    setThreadCount(before);
    EXPECT_EQ(products[1], products[0]);   // bit for bit
    EXPECT_EQ(products[2], products[0]);
    EXPECT_EQ(solutions[1], solutions[0]);
    EXPECT_EQ(solutions[2], solutions[0]);
}

TEST(MatrixFreeLinearized, IsTheAutomaticChoiceIn3DOnly)
{
    EXPECT_TRUE(matrixFreeChosen(LinearSolverKind::automatic, 3, 100 * directSolverRowLimit));
    EXPECT_TRUE(matrixFreeChosen(LinearSolverKind::automatic, 3, 60));
    EXPECT_FALSE(matrixFreeChosen(LinearSolverKind::automatic, 2, 100 * directSolverRowLimit));
    EXPECT_FALSE(matrixFreeChosen(LinearSolverKind::direct, 3, 600));
    EXPECT_FALSE(matrixFreeChosen(LinearSolverKind::iterative, 3, 100 * directSolverRowLimit));
    EXPECT_TRUE(matrixFreeChosen(LinearSolverKind::matrixFree, 2, 30));
}

} // namespace
} // namespace rbm::motion

namespace rbm::motion {
namespace {

// The method to round-off (displacementTolerance 0), for the tests of its exactness; the
// default stops within 1e-6 of each node's shortest edge.
ReducedNewtonOptions roundOffOptions()
{
    ReducedNewtonOptions options;
    options.displacementTolerance = 0.0;
    return options;
}

TEST(ReducedNewton, ReachesNewtonsMinimum)
{
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, false}, {3, true}}) {
        const GridCase c = gridCase(dimension, dimension == 2 ? 12 : 5, mirror, 13);
        const std::vector<Vector3> prescribed = largeTopMotion(c);
        CoupledNewtonSolver newton(*c.problem);
        ReducedNewtonSolver reduced(*c.problem, roundOffOptions());
        const RbmResult expected = newton.solve(prescribed);
        const RbmResult result = reduced.solve(prescribed);
        ASSERT_TRUE(expected.converged) << expected.reason;
        ASSERT_TRUE(result.converged) << result.reason;
        EXPECT_GT(expected.energy, 1e-3);
        EXPECT_NEAR(result.energy, expected.energy, 1e-10 * expected.energy) << dimension << "D mirror " << mirror;
        EXPECT_LT(largestDifference(result.displacement, expected.displacement), 1e-8) << dimension << "D mirror " << mirror;
        EXPECT_LT(result.residualNorm, 1e-6) << result.reason;
        for (int node = 0; node < c.problem->nodeCount(); ++node) {
            if (c.problem->kind(node) == NodeKind::sliding && c.points[node].x == 0.0) {
                EXPECT_NEAR(result.displacement[node].x, 0.01, 1e-15);
            }
        }

        // A time series of warm starts (the secant predictor from the third solve on) ends where a
        // cold solve of the last boundary does.
        ReducedNewtonSolver series(*c.problem, roundOffOptions());
        RbmResult state;
        for (int step = 1; step <= 4; ++step) {
            std::vector<Vector3> boundary = prescribed;
            for (Vector3& v : boundary) v = (step / 4.0) * v;
            const RbmResult next = series.solve(boundary, step == 1 ? nullptr : &state);
            ASSERT_TRUE(next.converged) << next.reason;
            state = next;
        }
        EXPECT_NEAR(state.energy, expected.energy, 1e-10 * expected.energy);
        EXPECT_LT(largestDifference(state.displacement, expected.displacement), 1e-8);
    }
}

// gridCase with its sliding sides free (no sliding node: K is solved as a scalar system).
GridCase withFreeSides(GridCase c)
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
std::pair<RbmResult, RbmResult> plainAndTurnedSolves(const RbmProblem& problem, ReducedNewtonOptions options,
                                                     const std::vector<Vector3>& prescribed)
{
    options.turnedStart = false;
    const RbmResult plain = ReducedNewtonSolver(problem, options).solve(prescribed);
    options.turnedStart = true;
    return {plain, ReducedNewtonSolver(problem, options).solve(prescribed)};
}

// Both converged to the same minimum (energy to 1e-10, every node to 1e-8), a non-trivial one.
void expectTheSameMinimum(const RbmResult& expected, const RbmResult& result)
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
BodyInBox bodyInBox(const GridCase& grid, int n, double degrees)
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

TEST(ReducedNewton, TurnedStartIsKeptOnlyWhereItsEnergyIsLower)
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

TEST(ReducedNewton, AWarmStartWithoutHistoryAlsoTriesTheTurnFromTheGuess)
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

TEST(ReducedNewton, AfterAColdSolveTheReferenceMeshIsTheResultBeforeIt)
{
    // No displacement is the exact minimum for a boundary at rest, so a cold solve's result
    // continues a chain from the reference mesh: the next warm start takes the secant predictor.
    // (a) Back to rest after 10°: the secant is exactly −1, the predictor exactly zero, and the
    // solve ends there without an iteration (outside a chain it started from the guess and
    // iterated). (b) A series 10° → 12° → 14° (the default tolerance): the second step's Newton
    // correction is a chain's, so the third step takes the subspace step along it: against the
    // same series without kept corrections (correctionMemory 0), both within 10 tolerances of the
    // minima, and fewer CG iterations at the third step.
    const int n = 16;
    const GridCase grid = gridCase(2, n, false, 29);
    const BodyInBox tenDegrees = bodyInBox(grid, n, 10.0);
    const RbmProblem problem(2, grid.points, grid.problem->graph(), tenDegrees.constraints, EdgeWeighting::inverseDistanceSquared);
    {
        ReducedNewtonSolver solver(problem, roundOffOptions());
        const RbmResult turned = solver.solve(tenDegrees.prescribed);
        ASSERT_TRUE(turned.converged) << turned.reason;
        const RbmResult atRest = solver.solve(std::vector<Vector3>(grid.points.size()), &turned);
        ASSERT_TRUE(atRest.converged) << atRest.reason;
        EXPECT_EQ(atRest.iterations, 0);
        EXPECT_EQ(atRest.linearIterations, 0);
        EXPECT_EQ(largestDifference(atRest.displacement, std::vector<Vector3>(grid.points.size())), 0.0);
    }
    std::vector<std::vector<RbmResult>> series;
    const std::vector<BodyInBox> steps{bodyInBox(grid, n, 10.0), bodyInBox(grid, n, 12.0), bodyInBox(grid, n, 14.0)};
    for (const int memory : {0, 3}) {
        ReducedNewtonOptions options;
        options.correctionMemory = memory;
        ReducedNewtonSolver solver(problem, options);
        std::vector<RbmResult>& results = series.emplace_back();
        for (std::size_t k = 0; k < steps.size(); ++k) {
            results.push_back(solver.solve(steps[k].prescribed, k == 0 ? nullptr : &results.back()));
            ASSERT_TRUE(results.back().converged) << "memory " << memory << ", step " << k + 1 << ": " << results.back().reason;
        }
    }
    // Both within 10 displacement tolerances of the grid's spacing of the minimum solved to round-off.
    const double bound = 10.0 * ReducedNewtonOptions{}.displacementTolerance / n;
    for (std::size_t k = 0; k < steps.size(); ++k) {
        const RbmResult exact = ReducedNewtonSolver(problem, roundOffOptions()).solve(steps[k].prescribed);
        ASSERT_TRUE(exact.converged) << exact.reason;
        for (const std::vector<RbmResult>& results : series)
            EXPECT_LT(largestDifference(results[k].displacement, exact.displacement), bound) << "step " << k + 1;
    }
    std::printf("body in a box, 10 -> 12 -> 14 deg: third step %d Newton / %d CG without kept corrections, %d / %d with\n",
                series[0][2].iterations, series[0][2].linearIterations, series[1][2].iterations,
                series[1][2].linearIterations);
    EXPECT_EQ(series[1][1].linearIterations, series[0][1].linearIterations);   // nothing kept yet
    EXPECT_LT(series[1][2].linearIterations, series[0][2].linearIterations);
}

TEST(ReducedNewton, ABoundaryBackAtRestStartsFromTheReferenceMeshAndTheChainGoesOn)
{
    // 10° → 5° → 0° → −5° along a chain: at 0° the body is back at rest, which the reference mesh
    // (no displacement) is its exact minimum, so the solve starts there and ends
    // without an iteration, at no displacement exactly (with the secant's start: 4 Newton steps).
    // The chain goes on: −5° reaches the cold solve's minimum (to round-off).
    const int n = 16;
    const GridCase grid = gridCase(2, n, false, 29);
    const std::vector<BodyInBox> bodies{bodyInBox(grid, n, 10.0), bodyInBox(grid, n, 5.0), bodyInBox(grid, n, 0.0),
                                        bodyInBox(grid, n, -5.0)};
    const RbmProblem problem(2, grid.points, grid.problem->graph(), bodies[0].constraints, EdgeWeighting::inverseDistanceSquared);
    ReducedNewtonSolver solver(problem, roundOffOptions());
    std::vector<RbmResult> results;
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        results.push_back(solver.solve(bodies[k].prescribed, k == 0 ? nullptr : &results.back()));
        ASSERT_TRUE(results.back().converged) << "step " << k + 1 << ": " << results.back().reason;
    }
    const std::vector<Vector3> rest(grid.points.size());
    EXPECT_EQ(results[2].iterations, 0);
    EXPECT_EQ(results[2].linearIterations, 0);
    EXPECT_EQ(largestDifference(results[2].displacement, rest), 0.0);
    const RbmResult cold = ReducedNewtonSolver(problem, roundOffOptions()).solve(bodies[3].prescribed);
    ASSERT_TRUE(cold.converged) << cold.reason;
    EXPECT_NEAR(results[3].energy, cold.energy, 1e-10 * cold.energy);
    EXPECT_LT(largestDifference(results[3].displacement, cold.displacement), 1e-8);
    // With the default tolerance, 6° → 4° → 2° → 0° → −2°: the step at rest keeps the secant's
    // miss as the chain's correction, and the step after it converges with the subspace step
    // along it alone (no CG iteration; with the rest start's own zero correction instead: 2).
    ReducedNewtonSolver loose(problem, ReducedNewtonOptions{});
    std::vector<RbmResult> series;
    for (const double degrees : {6.0, 4.0, 2.0, 0.0, -2.0}) {
        series.push_back(loose.solve(bodyInBox(grid, n, degrees).prescribed, series.empty() ? nullptr : &series.back()));
        ASSERT_TRUE(series.back().converged) << degrees << " deg: " << series.back().reason;
    }
    EXPECT_EQ(series[3].iterations, 0);
    EXPECT_EQ(largestDifference(series[3].displacement, rest), 0.0);
    EXPECT_EQ(series[4].linearIterations, 0);
    const RbmResult exact = ReducedNewtonSolver(problem, roundOffOptions()).solve(bodyInBox(grid, n, -2.0).prescribed);
    EXPECT_LT(largestDifference(series[4].displacement, exact.displacement), 10.0 * ReducedNewtonOptions{}.displacementTolerance / n);
}

TEST(ReducedNewton, AtABoundaryMetBeforeTheDisplacementTestComesBeforeTheSubspaceStep)
{
    // 2° → 4° → 6° → 4° (default tolerance): at the turning point the secant predictor is the
    // kept 4° result, which meets the boundary to rounding and is its minimum already. The
    // displacement test then comes first and ends the solve: no subspace step (with its three S
    // products) is tried, which -rbm_reduced_monitor shows, and the result is the kept one.
    const int n = 16;
    const GridCase grid = gridCase(2, n, false, 29);
    const RbmProblem problem(2, grid.points, grid.problem->graph(), bodyInBox(grid, n, 2.0).constraints,
                             EdgeWeighting::inverseDistanceSquared);
    // The solver reads -rbm_reduced_monitor when it is built; only the last solve's lines are kept.
    ASSERT_EQ(PetscOptionsSetValue(nullptr, "-rbm_reduced_monitor", nullptr), 0);
    ReducedNewtonSolver solver(problem, ReducedNewtonOptions{});
    ASSERT_EQ(PetscOptionsClearValue(nullptr, "-rbm_reduced_monitor"), 0);
    std::vector<RbmResult> series;
    std::string printed;
    for (const double degrees : {2.0, 4.0, 6.0, 4.0}) {
        const bool last = series.size() == 3;
        if (last) {
            std::fflush(stdout);
            ::testing::internal::CaptureStdout();
        }
        series.push_back(solver.solve(bodyInBox(grid, n, degrees).prescribed, series.empty() ? nullptr : &series.back()));
        if (last) {
            std::fflush(stdout);
            printed = ::testing::internal::GetCapturedStdout();
        }
        ASSERT_TRUE(series.back().converged) << degrees << " deg: " << series.back().reason;
    }
    EXPECT_NE(printed.find("displacement test at the reproduced boundary"), std::string::npos) << printed;
    EXPECT_EQ(printed.find("subspace"), std::string::npos) << printed;
    EXPECT_EQ(series[3].iterations, 0);
    EXPECT_EQ(series[3].linearIterations, 0);
    EXPECT_EQ(series[3].reason, "CONVERGED_DISPLACEMENT");
    EXPECT_LT(largestDifference(series[3].displacement, series[1].displacement), 1e-12);
}

TEST(ReducedNewton, AfterARestartTheSecondStepTakesASubspaceStepAlongTheFirstStepsCorrection)
{
    // A restart: a new solver warm-started from another's result at 10° (no history: outside a
    // chain), then 20° → 30° → 40°. Its second solve (30°) is a warm start outside a chain too
    // (one result kept): its turned start misses the minimum by nearly the field the first
    // solve's turned start missed by, so a Galerkin step along the first solve's Newton
    // correction comes first. The solve after it (the first of a chain) does not use it: the
    // secant predictor misses differently. Against the same restart without the subspace step
    // (correctionMemory 0): the same minima to round-off, fewer CG iterations at 30°, the same
    // iterations at 40°.
    const int n = 16;
    const GridCase grid = gridCase(2, n, false, 29);
    const std::vector<BodyInBox> bodies{bodyInBox(grid, n, 10.0), bodyInBox(grid, n, 20.0), bodyInBox(grid, n, 30.0),
                                        bodyInBox(grid, n, 40.0)};
    const RbmProblem problem(2, grid.points, grid.problem->graph(), bodies[0].constraints, EdgeWeighting::inverseDistanceSquared);
    const RbmResult before = ReducedNewtonSolver(problem, roundOffOptions()).solve(bodies[0].prescribed);
    ASSERT_TRUE(before.converged) << before.reason;
    std::vector<std::vector<RbmResult>> series;
    for (const int memory : {0, 3}) {
        ReducedNewtonOptions options = roundOffOptions();
        options.correctionMemory = memory;
        ReducedNewtonSolver restarted(problem, options);
        std::vector<RbmResult>& results = series.emplace_back();
        for (std::size_t k = 1; k < bodies.size(); ++k) {
            results.push_back(restarted.solve(bodies[k].prescribed, k == 1 ? &before : &results.back()));
            ASSERT_TRUE(results.back().converged) << "memory " << memory << ", " << 10 * (k + 1) << " deg: " << results.back().reason;
        }
    }
    for (std::size_t k = 0; k < series[0].size(); ++k) expectTheSameMinimum(series[0][k], series[1][k]);
    std::printf("body in a box, restart at 10 deg -> 20 -> 30 -> 40 deg: 30 deg %d Newton / %d CG without the subspace "
                "step, %d / %d with it; 40 deg %d / %d and %d / %d\n",
                series[0][1].iterations, series[0][1].linearIterations, series[1][1].iterations,
                series[1][1].linearIterations, series[0][2].iterations, series[0][2].linearIterations,
                series[1][2].iterations, series[1][2].linearIterations);
    EXPECT_LT(series[1][1].linearIterations, series[0][1].linearIterations);
    EXPECT_EQ(series[1][2].iterations, series[0][2].iterations);
    EXPECT_EQ(series[1][2].linearIterations, series[0][2].linearIterations);
}

TEST(ReducedNewton, In3DTheTurnedStartFollowsATwistToTheSameMinimum)
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

TEST(ReducedNewton, In3DTheTurnedStartOfARigidBoundaryMotionIsThatMotion)
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

TEST(ReducedNewton, In3DOnAGradedMeshTheCycleReachesTheFactorisedMinimumWithAndWithoutSymmetryPlanes)
{
    // A boundary-layer-like grid between two mirror planes (one layer of hexahedra, z = 0 and
    // z = 0.1, every node sliding on its plane), cells graded towards the wall x = 0 (first
    // cell 7.6e-4 of the box, aspect ratio up to ~160), the wall turned 5° about its centre, the
    // far side x = 1 fixed. With sliding nodes K ⊗ I is projected; where K is iterative its
    // inverse is CG preconditioned by the cycle of the scalar K between projections, to
    // laplacianRelativeTolerance. It must reach the minimum of the factorised path: to round-off
    // with displacementTolerance 0, and within the default tolerance's bound otherwise (one
    // cycle without the inner CG stopped 7.9e-4 chord away on the boundary-layer airfoil).
    // The same grid with its z planes free (no sliding node): K⁻¹ is one cycle, the default
    // 3D path, here on a graded mesh.
    const int nx = 40, ny = 20;
    const double ratio = 1.2;
    auto index = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
    std::vector<Vector3> points;
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i)
                points.push_back({(std::pow(ratio, i) - 1.0) / (std::pow(ratio, nx) - 1.0), double(j) / ny, 0.1 * k});
    const int nodeCount = static_cast<int>(points.size());
    std::vector<std::vector<int>> cells;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            std::vector<int>& cell = cells.emplace_back();
            for (int k = 0; k < 2; ++k)
                for (int dj = 0; dj < 2; ++dj)
                    for (int di = 0; di < 2; ++di) cell.push_back(index(i + di, j + dj, k));
        }
    const CellNeighbourGraph graph = graphOfCells(nodeCount, cells);
    for (const bool symmetryPlanes : {true, false}) {
        std::vector<NodeConstraint> constraints(nodeCount);
        std::vector<Vector3> prescribed(nodeCount);
        const double angle = 5.0 * 3.14159265358979 / 180.0;
        for (int node = 0; node < nodeCount; ++node) {
            const Vector3& p = points[node];
            if (p.x == 0.0 || p.x == 1.0) {
                constraints[node].kind = NodeKind::prescribed;
                if (p.x == 0.0) {
                    const double dy = p.y - 0.5;
                    prescribed[node] = {-std::sin(angle) * dy, std::cos(angle) * dy - dy, 0.0};
                }
            } else if (symmetryPlanes) {
                constraints[node] = {NodeKind::sliding, Vector3{0.0, 0.0, p.z == 0.0 ? -1.0 : 1.0}, true};
            }
        }
        const RbmProblem problem(3, points, graph, constraints,
                                 EdgeWeighting::inverseDistanceSquared);
        ASSERT_EQ(problem.hasSlidingNodes(), symmetryPlanes);
        for (const bool roundOff : {true, false}) {
            ReducedNewtonOptions directOptions = roundOff ? roundOffOptions() : ReducedNewtonOptions{};
            directOptions.linearSolver = LinearSolverKind::direct;
            ReducedNewtonOptions cycleOptions = directOptions;
            cycleOptions.linearSolver = LinearSolverKind::iterative;
            const RbmResult expected = ReducedNewtonSolver(problem, directOptions).solve(prescribed);
            const RbmResult result = ReducedNewtonSolver(problem, cycleOptions).solve(prescribed);
            ASSERT_TRUE(expected.converged) << expected.reason;
            ASSERT_TRUE(result.converged) << result.reason;
            double errorPerEdge = 0.0;
            for (int node = 0; node < nodeCount; ++node)
                errorPerEdge = std::max(errorPerEdge, norm(result.displacement[node] - expected.displacement[node]) /
                                                          problem.shortestNeighbourDistance(node));
            // Measured, symmetry planes: round-off, energies equal to 14 digits, 4 Newton steps both,
            // nodes within 5.4e-11 of their shortest edge; default tolerance, within 4.7e-7 of it.
            // Free planes: 1.6e-10 and 1.9e-6.
            if (roundOff) {
                EXPECT_NEAR(result.energy, expected.energy, 1e-10 * expected.energy);
                EXPECT_LT(errorPerEdge, 1e-6);
            } else {
                EXPECT_LT(errorPerEdge, 50.0 * ReducedNewtonOptions{}.displacementTolerance);
            }
        }
    }
}

TEST(ReducedNewton, In3DOneMultigridCycleAsKInverseReachesNewtonsMinimum)
{
    // linearSolver iterative: K⁻¹ is one V-cycle on the three components at once
    // (ThreeVectorMultigrid) without sliding nodes, and with mirror and sliding nodes CG on the
    // projected K ⊗ I preconditioned by that cycle between projections. Either way the minimum is Newton's on all unknowns (an independent
    // algorithm), to 12 digits of the energy.
    for (bool mirror : {false, true}) {
        const GridCase c = mirror ? gridCase(3, 8, true, 13) : withFreeSides(gridCase(3, 8, false, 13));
        ASSERT_EQ(c.problem->hasSlidingNodes(), mirror);
        const std::vector<Vector3> prescribed = largeTopMotion(c);
        CoupledNewtonSolver newton(*c.problem);
        const RbmResult expected = newton.solve(prescribed);
        ReducedNewtonOptions options = roundOffOptions();
        options.linearSolver = LinearSolverKind::iterative;
        ReducedNewtonSolver reduced(*c.problem, options);
        const RbmResult result = reduced.solve(prescribed);
        ASSERT_TRUE(expected.converged) << expected.reason;
        ASSERT_TRUE(result.converged) << result.reason;
        EXPECT_GT(expected.energy, 1e-3);
        EXPECT_NEAR(result.energy, expected.energy, 1e-12 * expected.energy) << "mirror " << mirror;
        EXPECT_LT(largestDifference(result.displacement, expected.displacement), 1e-8) << "mirror " << mirror;
        // One cycle is a good K⁻¹: CG iterations per Newton step stay few.
        EXPECT_LE(result.linearIterations, 20 * result.iterations) << result.linearIterations;
        for (int node = 0; node < c.problem->nodeCount(); ++node) {
            if (c.problem->kind(node) == NodeKind::sliding && c.points[node].x == 0.0) {
                EXPECT_NEAR(result.displacement[node].x, 0.01, 1e-15);
            }
        }
        // A warm start from the solution: nothing left to do.
        const RbmResult again = reduced.solve(prescribed, &result);
        ASSERT_TRUE(again.converged) << again.reason;
        EXPECT_NEAR(again.energy, expected.energy, 1e-12 * expected.energy);
        EXPECT_LE(again.iterations, 1);
    }
}

TEST(ReducedNewton, In3DTheMultigridCycleIsTheSameForOneTwoAndThreeThreads)
{
    const GridCase c = withFreeSides(gridCase(3, 12, false, 13));  // 13³ nodes, no sliding nodes
    ASSERT_TRUE(worthThreading(c.problem->graph().neighbours.size()));
    const std::vector<Vector3> prescribed = largeTopMotion(c);
    ReducedNewtonOptions options;
    options.linearSolver = LinearSolverKind::iterative;
    const int before = threadCount();
    std::vector<RbmResult> results;
    for (int threads : {1, 2, 3}) {
        setThreadCount(threads);
        ReducedNewtonSolver solver(*c.problem, options);
        results.push_back(solver.solve(prescribed));
        EXPECT_TRUE(results.back().converged) << results.back().reason;
    }
    setThreadCount(before);
    for (int k : {1, 2}) {
        EXPECT_EQ(results[k].displacement, results[0].displacement) << k;  // bit for bit
        EXPECT_EQ(results[k].energy, results[0].energy);
        EXPECT_EQ(results[k].linearIterations, results[0].linearIterations);
    }
}

TEST(ReducedNewton, MovesTheWholeMeshRigidlyWhenTheBoundaryMovesRigidly)
{
    // Every boundary node turned 120° (2D) / 100° about a skew axis (3D) and shifted: the exact
    // minimum is the rigid motion itself, E = 0.
    for (int dimension : {2, 3}) {
        GridCase c = gridCase(dimension, dimension == 2 ? 10 : 4, false, 3);
        std::vector<NodeConstraint> constraints(c.points.size());
        for (int node = 0; node < static_cast<int>(c.points.size()); ++node) {
            const Vector3& p = c.points[node];
            bool boundary = p.x == 0.0 || p.x == 1.0 || p.y == 0.0 || p.y == 1.0;
            if (dimension == 3) boundary = boundary || p.z == 0.0 || p.z == 1.0;
            if (boundary) constraints[node].kind = NodeKind::prescribed;
        }
        const RbmProblem problem(dimension, c.points, c.problem->graph(), constraints, EdgeWeighting::inverseDistanceSquared);
        const Matrix3 rotation = dimension == 2 ? planarRotation(120.0 * 3.14159265358979 / 180.0)
                                                : rotationFromVector(Vector3{0.6, -0.9, 1.2} * (100.0 * 3.14159265358979 / 180.0 / 1.6155));
        const Vector3 shift{0.3, -0.2, dimension == 3 ? 0.1 : 0.0};
        std::vector<Vector3> rigid(c.points.size());
        for (std::size_t node = 0; node < rigid.size(); ++node) {
            const Vector3 centred = c.points[node] - Vector3{0.5, 0.5, dimension == 3 ? 0.5 : 0.0};
            rigid[node] = rotation * centred - centred + shift;
        }
        for (LinearSolverKind kind : {LinearSolverKind::automatic, LinearSolverKind::iterative}) {
            ReducedNewtonOptions options = roundOffOptions();
            options.linearSolver = kind;  // 3D iterative: one multigrid cycle as K⁻¹
            ReducedNewtonSolver solver(problem, options);
            const RbmResult result = solver.solve(rigid);
            ASSERT_TRUE(result.converged) << result.reason;
            EXPECT_LT(largestDifference(result.displacement, rigid), 1e-10) << dimension;
            EXPECT_LT(result.energy, 1e-20) << dimension;
        }
    }
}

TEST(ReducedNewton, OwnFactorisationAndPetscsAgree)
{
    // K factorised by rbm (SparseCholesky, the default on one rank) or, when the user names the
    // package, through PETSc's KSP: the same minimum to rounding.
    const GridCase c = gridCase(2, 12, false, 17);
    const std::vector<Vector3> prescribed = largeTopMotion(c);
    ReducedNewtonSolver own(*c.problem, roundOffOptions());
    const RbmResult expected = own.solve(prescribed);
    ASSERT_TRUE(expected.converged) << expected.reason;
    ASSERT_EQ(PetscOptionsSetValue(nullptr, "-rbm_reduced_pc_factor_mat_solver_type", "petsc"), 0);
    RbmResult result;
    {
        ReducedNewtonSolver throughPetsc(*c.problem, roundOffOptions());
        result = throughPetsc.solve(prescribed);
    }
    ASSERT_EQ(PetscOptionsClearValue(nullptr, "-rbm_reduced_pc_factor_mat_solver_type"), 0);
    ASSERT_TRUE(result.converged) << result.reason;
    EXPECT_GT(expected.energy, 1e-3);
    EXPECT_NEAR(result.energy, expected.energy, 1e-10 * expected.energy);
    EXPECT_LT(largestDifference(result.displacement, expected.displacement), 1e-9);
    // Two different factorisations do not round alike: the option did switch the path.
    EXPECT_NE(result.displacement, expected.displacement);
}

TEST(ReducedNewton, DisplacementToleranceStopsEarlyWithinItsBound)
{
    // displacementTolerance ε: converged once |K⁻¹∇Ẽ| ≤ ε × the shortest edge at every node.
    // Against the fully converged solve (ε = 0), every node is off by well under 10 ε × its
    // shortest edge (K⁻¹ underestimates the Newton step by a few times, file comment), and the
    // solve took fewer CG iterations.
    for (int dimension : {2, 3}) {
        const GridCase c = gridCase(dimension, dimension == 2 ? 16 : 6, false, 21);
        const std::vector<Vector3> prescribed = largeTopMotion(c);
        ReducedNewtonSolver exact(*c.problem, roundOffOptions());
        const RbmResult reference = exact.solve(prescribed);
        ASSERT_TRUE(reference.converged) << reference.reason;
        const double shortestEdge = 1.0 / (dimension == 2 ? 16 : 6);  // the grid's spacing (jittered a little)
        for (double tolerance : {1e-3, 1e-5}) {
            ReducedNewtonOptions options;
            options.displacementTolerance = tolerance;
            ReducedNewtonSolver loose(*c.problem, options);
            const RbmResult result = loose.solve(prescribed);
            ASSERT_TRUE(result.converged) << result.reason;
            EXPECT_EQ(result.reason, "CONVERGED_DISPLACEMENT") << dimension << "D, " << tolerance;
            const double error = largestDifference(result.displacement, reference.displacement);
            EXPECT_LT(error, 10.0 * tolerance * shortestEdge) << dimension << "D, " << tolerance;
            EXPECT_LT(result.linearIterations, reference.linearIterations) << dimension << "D, " << tolerance;
        }
    }
}

TEST(ReducedNewton, CloseToTheMinimumOneNewtonStepPassesTheDisplacementTest)
{
    // A warm start a little off the minimum (every free node moved by up to 1e-4 of the grid's
    // spacing): the displacement test fails by 10-100 tolerances, far inside the region where
    // the step's nonlinearity (the square of the displacement) is below the tolerance. The one
    // Newton step then takes CG to the displacement target instead of stopping at the forcing
    // of 0.1, and the next test passes: one Newton step, not two. Within 10 ε of the exact
    // minimum, as DisplacementToleranceStopsEarlyWithinItsBound.
    for (int dimension : {2, 3}) {
        const GridCase c = gridCase(dimension, dimension == 2 ? 16 : 6, false, 21);
        const std::vector<Vector3> prescribed = largeTopMotion(c);
        const RbmResult reference = ReducedNewtonSolver(*c.problem, roundOffOptions()).solve(prescribed);
        ASSERT_TRUE(reference.converged) << reference.reason;
        const double spacing = 1.0 / (dimension == 2 ? 16 : 6);
        RbmResult guess = reference;
        for (int node = 0; node < c.problem->nodeCount(); ++node) {
            if (!c.problem->isUnknown(node)) continue;
            const double phase = 0.37 * node;
            guess.displacement[node] += 1e-4 * spacing * Vector3{std::sin(phase), std::cos(1.3 * phase),
                                                                 dimension == 3 ? std::sin(0.7 * phase) : 0.0};
        }
        constexpr double tolerance = 1e-6;
        ReducedNewtonOptions options;
        options.displacementTolerance = tolerance;
        ReducedNewtonSolver solver(*c.problem, options);
        const RbmResult result = solver.solve(prescribed, &guess);
        ASSERT_TRUE(result.converged) << result.reason;
        EXPECT_EQ(result.reason, "CONVERGED_DISPLACEMENT") << dimension << "D";
        EXPECT_EQ(result.iterations, 1) << dimension << "D: " << result.linearIterations << " CG iterations";
        EXPECT_LT(largestDifference(result.displacement, reference.displacement), 10.0 * tolerance * spacing) << dimension << "D";
        EXPECT_GT(largestDifference(guess.displacement, reference.displacement), 100.0 * tolerance * spacing) << dimension << "D";
    }
}

TEST(ReducedNewton, SubspaceOfPastCorrectionsSavesIterationsAndKeepsTheMinima)
{
    // A smooth series (the top's motion scaled by sin, warm-started from each result): from the
    // fourth step on, the first step of every solve is the Galerkin step in the span of the
    // last three Newton corrections (correctionMemory, the default). Solved to round-off, every
    // step ends where the series without it ends (the minima do not move); with the default
    // displacementTolerance, every node within 10 tolerances of the grid spacing of it, and
    // with fewer CG iterations: the secant predictor misses by nearly the same field each step.
    // Measured (10 steps): 2D 57 → 38 CG iterations, 3D 63 → 44 (to round-off 128 → 111 and
    // 167 → 140, where the last Newton steps' CG to the rounding level dominates).
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, true}}) {
        const GridCase c = gridCase(dimension, dimension == 2 ? 16 : 6, mirror, 31);
        const std::vector<Vector3> top = largeTopMotion(c);
        const double spacing = 1.0 / (dimension == 2 ? 16 : 6);
        for (const bool toRoundOff : {true, false}) {
            ReducedNewtonOptions without = toRoundOff ? roundOffOptions() : ReducedNewtonOptions{};
            ReducedNewtonOptions with = without;
            ASSERT_EQ(with.correctionMemory, 3);  // the default
            without.correctionMemory = 0;
            const double bound = toRoundOff ? 1e-8 : 10.0 * with.displacementTolerance * spacing;
            ReducedNewtonSolver plain(*c.problem, without), recycling(*c.problem, with);
            RbmResult plainState, recyclingState;
            int plainIterations = 0, recyclingIterations = 0;
            for (int step = 1; step <= 10; ++step) {
                std::vector<Vector3> boundary = top;
                for (Vector3& v : boundary) v = std::sin(0.15 * step) * v;
                const RbmResult a = plain.solve(boundary, step == 1 ? nullptr : &plainState);
                const RbmResult b = recycling.solve(boundary, step == 1 ? nullptr : &recyclingState);
                ASSERT_TRUE(a.converged) << a.reason;
                ASSERT_TRUE(b.converged) << b.reason;
                EXPECT_LT(largestDifference(b.displacement, a.displacement), bound)
                    << dimension << "D step " << step << (toRoundOff ? ", to round-off" : "");
                if (toRoundOff) {
                    EXPECT_NEAR(b.energy, a.energy, 1e-10 * a.energy) << dimension << "D step " << step;
                }
                plainIterations += a.linearIterations;
                recyclingIterations += b.linearIterations;
                plainState = a;
                recyclingState = b;
            }
            std::printf("%dD%s: CG iterations %d without, %d with the subspace step\n", dimension,
                        toRoundOff ? " to round-off" : "", plainIterations, recyclingIterations);
            if (!toRoundOff) {
                EXPECT_LT(recyclingIterations, 0.8 * plainIterations) << dimension << "D";
            }
        }
    }
}

TEST(ReducedNewton, AfterATurningPointTheStartIsTheResultOfTheSameBoundary)
{
    // The top's motion scaled by sin(π k / 10), k = 1…7: a turning point at k = 5, and k = 6, 7
    // repeat the boundaries of k = 4, 3. At k = 7 the secant through the results of k = 6 (= 4)
    // and 5 would extrapolate by α = (s7 − s6)/(s6 − s5) = 2.9, clamped to 2, the wrong way; the
    // fit on the boundary over the kept results picks the result of k = 3 instead, and the
    // solve stops at the displacement test with no iteration.
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, true}}) {
        const GridCase c = gridCase(dimension, dimension == 2 ? 16 : 6, mirror, 41);
        const std::vector<Vector3> top = largeTopMotion(c);
        ReducedNewtonSolver solver(*c.problem);
        std::vector<RbmResult> results(8);
        for (int k = 1; k <= 7; ++k) {
            std::vector<Vector3> boundary = top;
            for (Vector3& v : boundary) v = std::sin(M_PI * k / 10.0) * v;
            results[k] = solver.solve(boundary, k == 1 ? nullptr : &results[k - 1]);
            ASSERT_TRUE(results[k].converged) << dimension << "D step " << k << ": " << results[k].reason;
        }
        EXPECT_EQ(results[7].iterations, 0) << dimension << "D";
        EXPECT_EQ(results[7].linearIterations, 0) << dimension << "D";
        EXPECT_LT(largestDifference(results[7].displacement, results[3].displacement), 1e-12) << dimension << "D";
        EXPECT_GT(largestDifference(results[7].displacement, results[6].displacement), 1e-3) << dimension << "D";
    }
}

TEST(ReducedNewton, ARigidBodysSeriesTakesThePredictorsHarmonicCorrectionFromFewExtensions)
{
    // The top turned by θ_k = θ sin(π k / 8) about its centre and shifted along x by
    // 0.1 sin(π k / 8), k = 1…12: every change of the prescribed displacement between steps is
    // (cos θ' − cos θ)(x − c) + (sin θ' − sin θ) ẑ × (x − c) + s e_x on the top and zero below,
    // a vector of one fixed three-dimensional space. So at most three extensions K⁻¹ B m are
    // kept, the later warm starts take their correction from them, and the series ends where
    // the same series with a back-substitution at every step ends (both to round-off). (Free
    // sides: with sliding nodes the boundary enters b through their offsets too, and no basis
    // is kept.)
    for (const int dimension : {2, 3}) {
        const GridCase c = withFreeSides(gridCase(dimension, dimension == 2 ? 14 : 5, false, 43));
        const double amplitude = (dimension == 2 ? 25.0 : 30.0) * 3.14159265358979 / 180.0;
        ReducedNewtonOptions withBasis;
        withBasis.displacementTolerance = 0.0;
        ReducedNewtonOptions withoutBasis = withBasis;
        withoutBasis.harmonicBasis = false;
        ReducedNewtonSolver fromBasis(*c.problem, withBasis), solving(*c.problem, withoutBasis);
        RbmResult last, lastSolved;
        const int steps = 12;
        for (int k = 1; k <= steps; ++k) {
            const double phase = std::sin(3.14159265358979 * k / 8.0);
            std::vector<Vector3> boundary = c.prescribed;
            for (int node = 0; node < c.problem->nodeCount(); ++node) {
                const Vector3& p = c.points[node];
                if ((dimension == 3 ? p.z : p.y) != 1.0) continue;
                const double angle = amplitude * phase;
                const double dx = p.x - 0.5, dy = dimension == 3 ? p.y - 0.5 : p.y - 1.0;
                boundary[node] = {std::cos(angle) * dx - std::sin(angle) * dy - dx + 0.1 * phase,
                                  std::sin(angle) * dx + std::cos(angle) * dy - dy, 0.0};
            }
            last = fromBasis.solve(boundary, k == 1 ? nullptr : &last);
            lastSolved = solving.solve(boundary, k == 1 ? nullptr : &lastSolved);
            ASSERT_TRUE(last.converged) << dimension << "D step " << k << ": " << last.reason;
            ASSERT_TRUE(lastSolved.converged) << dimension << "D step " << k << ": " << lastSolved.reason;
            EXPECT_LT(largestDifference(last.displacement, lastSolved.displacement), 1e-9) << dimension << "D step " << k;
            // The same start to rounding: the same iterations (a wrong combination would be
            // corrected by Newton, but not in the same steps).
            EXPECT_EQ(last.iterations, lastSolved.iterations) << dimension << "D step " << k;
            EXPECT_EQ(last.linearIterations, lastSolved.linearIterations) << dimension << "D step " << k;
        }
        EXPECT_LE(fromBasis.harmonicBasisSize(), 3u) << dimension << "D";
        EXPECT_GE(fromBasis.correctionsFromHarmonicBasis(), steps - 1 - 3) << dimension << "D";
        EXPECT_EQ(solving.harmonicBasisSize(), 0u) << dimension << "D";
        EXPECT_EQ(solving.correctionsFromHarmonicBasis(), 0) << dimension << "D";
        std::printf("%dD: %zu extensions kept, %d of %d warm starts took the correction from them\n", dimension,
                    fromBasis.harmonicBasisSize(), fromBasis.correctionsFromHarmonicBasis(), steps - 1);
    }
}

} // namespace
} // namespace rbm::motion
