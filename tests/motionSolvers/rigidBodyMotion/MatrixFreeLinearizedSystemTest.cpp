// Tests of the matrix-free coupled linearized solve (MatrixFreeLinearizedSystem,
// ReducedLinearizedOperator): the reduced gradient against finite differences and against the
// full linearized energy, and the solution against the assembled, directly factorised
// system, in 2D and 3D, with free, prescribed, sliding and mirror nodes. (The reduced Newton
// method's tests are named after its parts: ReducedEnergyTest, WarmStartTest, …)

#include "CoupledLinearizedSolver.hpp"
#include "TestCases.hpp"
#include "LocalGlobalSolver.hpp"
#include "MatrixFreeLinearizedSystem.hpp"
#include "PetscTestEnvironment.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"
#include "ReducedLinearizedOperator.hpp"
#include "ThreadCount.hpp"
#include "VectorInstructions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace rbm::motion {

namespace {

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
