#include "ReducedNewtonSolver.hpp"

#include "CoupledNewtonSolver.hpp"

#include "PetscTestEnvironment.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace rbm::motion {
namespace {

TEST(ReducedNewtonSolver, ReachesNewtonsMinimum)
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

TEST(ReducedNewtonSolver, MovesTheWholeMeshRigidlyWhenTheBoundaryMovesRigidly)
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

TEST(ReducedNewtonSolver, SimilarNeighbourhoodsReproduceASimilarityOfTheBoundary)
{
    // Every boundary node shrunk to 0.6 about (0.5, 0.5), turned 50° and shifted: with
    // `scaling similar` the energy of the similarity itself is zero (each neighbourhood is fitted
    // by 0.6 R exactly), so it is the minimum; the rigid energy must compress the cells and
    // ends elsewhere. With a finite scale stiffness a rigid boundary motion is still reproduced.
    const GridCase c = gridCase(2, 10, false, 3);
    std::vector<NodeConstraint> constraints(c.points.size());
    for (int node = 0; node < static_cast<int>(c.points.size()); ++node) {
        const Vector3& p = c.points[node];
        if (p.x == 0.0 || p.x == 1.0 || p.y == 0.0 || p.y == 1.0) constraints[node].kind = NodeKind::prescribed;
    }
    const RbmProblem problem(2, c.points, c.problem->graph(), constraints, EdgeWeighting::inverseDistanceSquared);
    auto boundaryMotion = [&](double factor, double degrees) {
        const Matrix3 rotation = planarRotation(degrees * 3.14159265358979 / 180.0);
        std::vector<Vector3> u(c.points.size());
        for (std::size_t node = 0; node < u.size(); ++node) {
            const Vector3 centred = c.points[node] - Vector3{0.5, 0.5, 0.0};
            u[node] = factor * (rotation * centred) - centred + Vector3{0.2, -0.1, 0.0};
        }
        return u;
    };
    const std::vector<Vector3> similarity = boundaryMotion(0.6, 50.0);
    ReducedNewtonOptions similar = roundOffOptions();
    similar.scaling.stiffness = 0.0;
    const RbmResult scaled = ReducedNewtonSolver(problem, similar).solve(similarity);
    ASSERT_TRUE(scaled.converged) << scaled.reason;
    EXPECT_LT(largestDifference(scaled.displacement, similarity), 1e-10);
    EXPECT_LT(scaled.energy, 1e-20);
    const RbmResult rigid = ReducedNewtonSolver(problem, roundOffOptions()).solve(similarity);
    ASSERT_TRUE(rigid.converged) << rigid.reason;
    EXPECT_GT(largestDifference(rigid.displacement, similarity), 1e-2);
    EXPECT_GT(rigid.energy, 1e-3);

    ReducedNewtonOptions stiffScale = roundOffOptions();
    stiffScale.scaling.stiffness = 1.0;
    const std::vector<Vector3> rigidMotion = boundaryMotion(1.0, 120.0);
    const RbmResult turned = ReducedNewtonSolver(problem, stiffScale).solve(rigidMotion);
    ASSERT_TRUE(turned.converged) << turned.reason;
    EXPECT_LT(largestDifference(turned.displacement, rigidMotion), 1e-10);
    // Between the two: a scale stiffness of 1 on the similarity ends between rigid and similar.
    const RbmResult between = ReducedNewtonSolver(problem, stiffScale).solve(similarity);
    ASSERT_TRUE(between.converged) << between.reason;
    const double offBetween = largestDifference(between.displacement, similarity);
    EXPECT_GT(offBetween, 1e-4);
    EXPECT_LT(offBetween, largestDifference(rigid.displacement, similarity));
}

} // namespace
} // namespace rbm::motion
