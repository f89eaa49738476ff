#include "LaplacianPreconditioner.hpp"

#include "CoupledNewtonSolver.hpp"

#include "TestCases.hpp"
#include "OrderedSums.hpp"
#include "PetscTestEnvironment.hpp"
#include "ThreadCount.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace rbm::motion {
namespace {

// ‖P K P z − P r‖ / ‖P r‖ for z = apply(r), r random.
double relativeResidual(const RbmProblem& problem, LaplacianPreconditioner& preconditioner)
{
    const int dim = problem.dimension();
    std::vector<double> r(static_cast<std::size_t>(problem.unknownNodeCount()) * dim), z(r.size());
    std::mt19937 random(2);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    for (double& entry : r) entry = value(random);
    EXPECT_TRUE(preconditioner.apply(r, z));
    std::vector<double> residual = projectedLaplacianTimes(problem, preconditioner.laplacian(), z);
    problem.projectSliding(r, dim);
    for (std::size_t k = 0; k < r.size(); ++k) residual[k] -= r[k];
    return euclideanNorm(residual) / euclideanNorm(r);
}

TEST(LaplacianPreconditioner, FactorisedIsTheProjectedInverseOfK)
{
    for (int dimension : {2, 3}) {
        const GridCase c = gridCase(dimension, 5, dimension == 3, 3);
        LaplacianPreconditioner preconditioner(*c.problem, LinearSolverKind::direct, 1e-4);
        EXPECT_FALSE(preconditioner.hasScalarSolve()) << "sliding nodes: one system for K ⊗ I";
        EXPECT_LT(relativeResidual(*c.problem, preconditioner), 1e-10) << dimension;
    }
}

TEST(LaplacianPreconditioner, IterativeIn3DSolvesToItsRelativeTolerance)
{
    const GridCase c = gridCase(3, 6, false, 5);
    LaplacianPreconditioner preconditioner(*c.problem, LinearSolverKind::iterative, 1e-6);
    EXPECT_FALSE(preconditioner.isFixedLinearMap()) << "with sliding nodes an inner CG, not one cycle";
    EXPECT_LT(relativeResidual(*c.problem, preconditioner), 1e-6);
}

TEST(LaplacianPreconditioner, In3DOnAGradedMeshTheCycleReachesTheFactorisedMinimumWithAndWithoutSymmetryPlanes)
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

TEST(LaplacianPreconditioner, In3DOneMultigridCycleAsKInverseReachesNewtonsMinimum)
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

TEST(LaplacianPreconditioner, In3DTheMultigridCycleIsTheSameForOneTwoAndThreeThreads)
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

TEST(LaplacianPreconditioner, OwnFactorisationAndPetscsAgree)
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

} // namespace
} // namespace rbm::motion
