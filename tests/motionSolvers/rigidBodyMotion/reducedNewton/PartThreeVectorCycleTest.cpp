// The parts' three-vector multigrid cycle (PartThreeVectorCycle): CTest runs this program under
// mpiexec with 1 to 4 ranks, on the decomposed box of PartLaplacianTest. Its accuracy as K⁻¹ is
// PartLaplacianTest's (CG with it against the whole factorisation); here its properties as an
// operator: the same fixed linear map on each of the three components, symmetric (the Newton CG
// it preconditions needs a symmetric positive definite one), and a multigrid (one cycle removes
// most of the error of K x = b).

#include "PetscTestEnvironment.hpp"

#include "BoxConstraints.hpp"
#include "DecomposedBox.hpp"
#include "MeshPart.hpp"
#include "NodeExchange.hpp"
#include "PartLaplacian.hpp"
#include "PartProblem.hpp"
#include "PartThreeVectorCycle.hpp"
#include "ReducedLinearizedOperator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

using namespace rbm;
using namespace rbm::motion;
using rbm::test::DecomposedBox;

constexpr Label nx = 9, ny = 8, nz = 7;

struct PartCase {
    DecomposedBox box{nx, ny, nz, rbm::test::scatteredDecomposition};
    MeshPart part{PETSC_COMM_WORLD, box.localCells(rbm::test::worldRank())};
    RbmProblem problem;
    PetscMat laplacian;
    std::vector<PetscInt> rows;

    PartCase() : problem(makeProblem())
    {
        // K over the ranks as PartLaplacian assembles it: rows numbered by owner.
        const std::vector<double> k = coupledDisplacementLaplacian(problem);
        const BlockPattern& pattern = problem.blockPattern();
        const int owned = problem.ownedUnknownCount();
        PetscInt first = 0;
        const PetscInt count = owned;
        MPI_Exscan(&count, &first, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
        if (rbm::test::worldRank() == 0) first = 0;
        std::vector<double> nodeRows(static_cast<std::size_t>(problem.nodeCount()), -1.0);
        for (int a = 0; a < owned; ++a) nodeRows[problem.unknownNodes()[a]] = static_cast<double>(first + a);
        problem.nodeExchange()->updateGhosts(nodeRows, 1);
        for (int a = 0; a < problem.unknownNodeCount(); ++a) rows.push_back(static_cast<PetscInt>(nodeRows[problem.unknownNodes()[a]]));
        RBM_CHECK_PETSC(MatCreateAIJ(PETSC_COMM_WORLD, owned, owned, PETSC_DETERMINE, PETSC_DETERMINE, 27, nullptr, 27, nullptr,
                                     laplacian.out()));
        for (int a = 0; a < owned; ++a)
            for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
                RBM_CHECK_PETSC(MatSetValue(laplacian, rows[a], rows[pattern.columns[position]], k[position], INSERT_VALUES));
        RBM_CHECK_PETSC(MatAssemblyBegin(laplacian, MAT_FINAL_ASSEMBLY));
        RBM_CHECK_PETSC(MatAssemblyEnd(laplacian, MAT_FINAL_ASSEMBLY));
    }

    RbmProblem makeProblem() const
    {
        return partProblem(3, part, rbm::test::partConstraints(part, rbm::test::boxConstraints(box, Vector3{1.0, 0.2, 0.0})));
    }

    // Three smooth and rough fields at the owned unknowns, by position (the same on any ranks).
    std::vector<double> field(int variant) const
    {
        std::vector<double> values;
        for (int a = 0; a < problem.ownedUnknownCount(); ++a) {
            const Vector3& x = problem.referencePoints()[problem.unknownNodes()[a]];
            values.push_back(std::sin(3 * x.x + variant) * x.z);
            values.push_back(std::cos(7 * x.y * (variant + 1)) - x.x);
            values.push_back((variant + 1) * x.x * x.y + std::sin(11 * x.z));
        }
        return values;
    }
};

// A smooth field (the lowest modes of the box): what point smoothing alone barely reduces.
std::vector<double> smoothField(const RbmProblem& problem)
{
    std::vector<double> values;
    for (int a = 0; a < problem.ownedUnknownCount(); ++a) {
        const Vector3& x = problem.referencePoints()[problem.unknownNodes()[a]];
        const double mode = std::sin(M_PI * x.z / 0.8) * (1.0 + 0.3 * x.x) * (1.0 - 0.2 * x.y);
        values.push_back(mode);
        values.push_back(0.5 * mode);
        values.push_back(-mode);
    }
    return values;
}

double dot(const std::vector<double>& a, const std::vector<double>& b)
{
    double local = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) local += a[k] * b[k];
    double total = 0.0;
    MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    return total;
}

TEST(PartThreeVectorCycle, IsOneSymmetricLinearMapOnEachComponent)
{
    PartCase c;
    PartThreeVectorCycle cycle(c.problem, c.laplacian, c.rows);
    const std::vector<double> u = c.field(0), v = c.field(1);
    std::vector<double> cu(u.size()), cv(v.size());
    cycle.apply(u, cu);
    cycle.apply(v, cv);
    // Symmetric: (u, C v) = (v, C u), to the rounding of the products.
    const double uCv = dot(u, cv), vCu = dot(v, cu);
    EXPECT_NEAR(uCv, vCu, 1e-10 * std::sqrt(dot(u, cu) * dot(v, cv)));
    EXPECT_GT(dot(u, cu), 0.0);
    // Each component alone: the second of u put in the first place, the others zero.
    std::vector<double> alone(u.size(), 0.0), result(u.size());
    for (std::size_t a = 0; 3 * a < u.size(); ++a) alone[3 * a] = u[3 * a + 1];
    cycle.apply(alone, result);
    for (std::size_t a = 0; 3 * a < u.size(); ++a) {
        EXPECT_EQ(result[3 * a], cu[3 * a + 1]) << "row " << a;
        EXPECT_EQ(result[3 * a + 1], 0.0);
        EXPECT_EQ(result[3 * a + 2], 0.0);
    }
}

TEST(PartThreeVectorCycle, OneCycleRemovesMostOfTheError)
{
    // K x = b with x smooth and known: after one cycle from zero the error's K-norm is a fraction
    // of x's, where point smoothing alone (the cycle without its coarse level) leaves most of it.
    PartCase c;
    PartThreeVectorCycle cycle(c.problem, c.laplacian, c.rows);
    const std::vector<double> x = smoothField(c.problem);
    std::vector<double> b(x.size()), z(x.size()), error(x.size()), kError(x.size());
    cycle.fineLevel().multiplyThree(x.data(), b.data());
    cycle.apply(b, z);
    for (std::size_t k = 0; k < x.size(); ++k) error[k] = x[k] - z[k];
    cycle.fineLevel().multiplyThree(error.data(), kError.data());
    const double before = dot(x, b), after = dot(error, kError);
    // Measured on 2 ranks: 0.0037 with the coarse level, 0.41 without.
    EXPECT_LT(after, 0.05 * before) << "K-norm² of the error " << after << " against " << before;
    EXPECT_GT(cycle.coarseRows(), 0);
}

} // namespace
