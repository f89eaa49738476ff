// Tests of ProjectedLaplacianFactor: with sliding nodes on tilted planes and on a line (3D),
// its solve is the exact inverse of P (K ⊗ I) P on the admissible subspace.
#include "ProjectedLaplacianFactor.hpp"

#include "TestCases.hpp"
#include "OrderedSums.hpp"
#include "ReducedLinearizedOperator.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace rbm::motion {
namespace {

// The grid of gridCase with oblique sliding planes on x = 0 and x = 1 and, in 3D, a third on
// y = 0: its nodes on x = 0 slide on the line where two planes meet.
RbmProblem obliqueSlidingProblem(int dimension)
{
    const GridCase grid = gridCase(dimension, 4, false, 5);
    std::vector<NodeConstraint> constraints = grid.problem->constraints();
    for (int node = 0; node < grid.problem->nodeCount(); ++node) {
        const Vector3& p = grid.points[node];
        const double height = dimension == 3 ? p.z : p.y;
        if (height == 0.0 || height == 1.0) continue;   // prescribed
        constraints[node] = {};
        if (p.x == 0.0) constraints[node] = {NodeKind::sliding, Vector3{-1.0, 0.3, dimension == 3 ? 0.2 : 0.0}};
        if (p.x == 1.0) constraints[node] = {NodeKind::sliding, Vector3{1.0, -0.2, dimension == 3 ? 0.1 : 0.0}};
        if (dimension == 3 && p.y == 0.0 && p.x > 0.0 && p.x < 1.0) constraints[node] = {NodeKind::sliding, Vector3{0.1, 1.0, 0.1}};
        if (dimension == 3 && p.y == 0.0 && p.x == 0.0) constraints[node].secondNormal = Vector3{0.1, 1.0, 0.1};
    }
    return RbmProblem(dimension, grid.points, grid.problem->sharedGraph(), std::move(constraints));
}

TEST(ProjectedLaplacianFactor, SolvesTheProjectedLaplacianOnObliquePlanesAndLines)
{
    for (int dimension : {2, 3}) {
        const RbmProblem problem = obliqueSlidingProblem(dimension);
        ASSERT_TRUE(problem.hasSlidingNodes());
        int lineNodes = 0;
        for (int node = 0; node < problem.nodeCount(); ++node) lineNodes += problem.slidesOnLine(node) ? 1 : 0;
        EXPECT_EQ(lineNodes, dimension == 3 ? 3 : 0);
        const std::vector<double> laplacian = coupledDisplacementLaplacian(problem);
        const ProjectedLaplacianFactor factor(problem, laplacian, FactorPrecision::double_);

        const int dim = dimension;
        std::vector<double> r(static_cast<std::size_t>(problem.unknownNodeCount()) * dim), z(r.size());
        std::mt19937 random(3);
        std::uniform_real_distribution<double> value(-1.0, 1.0);
        for (double& entry : r) entry = value(random);
        factor.solve(r, z);

        // z is admissible: the projection does not change it.
        std::vector<double> projected = z;
        problem.projectSliding(projected, dim);
        for (std::size_t k = 0; k < z.size(); ++k) EXPECT_NEAR(projected[k], z[k], 1e-13) << dimension << " " << k;
        // P (K ⊗ I) P z = P r.
        std::vector<double> residual = projectedLaplacianTimes(problem, laplacian, z);
        problem.projectSliding(r, dim);
        for (std::size_t k = 0; k < r.size(); ++k) residual[k] -= r[k];
        EXPECT_LT(euclideanNorm(residual), 1e-12 * euclideanNorm(r)) << dimension;
    }
}

} // namespace
} // namespace rbm::motion
