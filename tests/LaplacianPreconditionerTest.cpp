#include "LaplacianPreconditioner.hpp"

#include "GridCases.hpp"
#include "OrderedSums.hpp"
#include "PetscTestEnvironment.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

static ::testing::Environment* const petscEnvironment =
    ::testing::AddGlobalTestEnvironment(new rbm::test::PetscTestEnvironment);

namespace rbm::motion {
namespace {

// P (K ⊗ I) P z, compact.
std::vector<double> projectedLaplacianTimes(const RbmProblem& problem, const std::vector<double>& laplacian,
                                            std::vector<double> z)
{
    const int dim = problem.dimension();
    const BlockPattern& pattern = problem.blockPattern();
    problem.projectSliding(z, dim);
    std::vector<double> y(z.size(), 0.0);
    for (int a = 0; a < problem.unknownNodeCount(); ++a)
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
            for (int q = 0; q < dim; ++q)
                y[static_cast<std::size_t>(a) * dim + q] +=
                    laplacian[position] * z[static_cast<std::size_t>(pattern.columns[position]) * dim + q];
    problem.projectSliding(y, dim);
    return y;
}

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

} // namespace
} // namespace rbm::motion
