// The distributed smoothed aggregation (linearAlgebra/DistributedAggregation): CTest runs this
// program under mpiexec with 1 to 4 ranks. The matrix is the 27-point Laplacian of a hexahedral
// grid (TestCases.hpp's hexLaplacian), its rows split over the ranks in contiguous ranges.
// Expectations come from the serial aggregation (SmoothedAggregation.hpp) of the whole matrix on
// one rank, and from the definition P = (I − ω D⁻¹K) T evaluated here on the CSR.

#include "PetscTestEnvironment.hpp"

#include "DecomposedBox.hpp"
#include "DistributedAggregation.hpp"
#include "SmoothedAggregation.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rbm::motion {

namespace {

using rbm::test::multigridCases::hexLaplacian;
using rbm::test::multigridCases::Laplacian;

using rbm::test::worldRank;
using rbm::test::worldSize;

// The rows [first, end) of the CSR matrix on this rank of communicator (all rows on PETSC_COMM_SELF).
PetscMat distributed(const Laplacian& k, MPI_Comm communicator, int first, int end)
{
    PetscMat matrix;
    std::vector<PetscInt> inside, outside;
    for (int row = first; row < end; ++row) {
        int local = 0;
        for (int position = k.offsets[row]; position < k.offsets[row + 1]; ++position)
            local += k.columns[position] >= first && k.columns[position] < end;
        inside.push_back(local);
        outside.push_back(k.offsets[row + 1] - k.offsets[row] - local);
    }
    RBM_CHECK_PETSC(MatCreateAIJ(communicator, end - first, end - first, k.rows, k.rows, 0, inside.data(), 0,
                                 outside.data(), matrix.out()));
    for (int row = first; row < end; ++row) {
        const int count = k.offsets[row + 1] - k.offsets[row];
        RBM_CHECK_PETSC(MatSetValues(matrix, 1, &row, count, k.columns.data() + k.offsets[row], k.values.data() + k.offsets[row],
                                     INSERT_VALUES));
    }
    RBM_CHECK_PETSC(MatAssemblyBegin(matrix, MAT_FINAL_ASSEMBLY));
    RBM_CHECK_PETSC(MatAssemblyEnd(matrix, MAT_FINAL_ASSEMBLY));
    return matrix;
}

int firstRowOf(int rank, int rows) { return static_cast<int>(static_cast<long>(rows) * rank / worldSize()); }

PetscMat onThisRanksRows(const Laplacian& k)
{
    return distributed(k, PETSC_COMM_WORLD, firstRowOf(worldRank(), k.rows), firstRowOf(worldRank() + 1, k.rows));
}

PetscMat whole(const Laplacian& k) { return distributed(k, PETSC_COMM_SELF, 0, k.rows); }

TEST(DistributedAggregation, OnOneRankTheProlongatorIsTheSerialAggregations)
{
    const Laplacian k = hexLaplacian(10);  // 9³ rows
    const std::vector<AggregationLevel> serial = buildSmoothedAggregation(k.offsets, k.columns, k.values, 10);
    ASSERT_FALSE(serial.empty());
    const CompressedRows& expected = serial.front().interpolation;
    const PetscMat matrix = whole(k);
    const DistributedProlongator p = distributedSmoothedProlongator(matrix);
    PetscInt rows = 0, columns = 0;
    RBM_CHECK_PETSC(MatGetSize(p.interpolation, &rows, &columns));
    ASSERT_EQ(rows, k.rows);
    ASSERT_EQ(columns, serial.front().coarseOperator.rows());
    EXPECT_EQ(p.ownedAggregates, columns);
    for (PetscInt row = 0; row < rows; ++row) {
        PetscInt count = 0;
        const PetscInt* indices = nullptr;
        const PetscScalar* values = nullptr;
        RBM_CHECK_PETSC(MatGetRow(p.interpolation, row, &count, &indices, &values));
        // The product's pattern may hold explicit zeros where the serial one has none: compare
        // the nonzero entries by column.
        std::vector<double> got(static_cast<std::size_t>(columns), 0.0), want(got.size(), 0.0);
        for (PetscInt e = 0; e < count; ++e) got[indices[e]] = values[e];
        RBM_CHECK_PETSC(MatRestoreRow(p.interpolation, row, &count, &indices, &values));
        for (int e = expected.offsets[row]; e < expected.offsets[row + 1]; ++e) want[expected.columns[e]] = expected.values[e];
        for (PetscInt column = 0; column < columns; ++column)
            ASSERT_NEAR(got[column], want[column], 1e-13) << "row " << row << " column " << column;
    }
}

TEST(DistributedAggregation, AcrossRanksPIsTheSmoothedAggregationOfTheWholeK)
{
    const Laplacian k = hexLaplacian(13);  // 12³ rows
    const PetscMat matrix = onThisRanksRows(k);
    const DistributedProlongator p = distributedSmoothedProlongator(matrix);
    // λ by the same power iteration as on one rank: only the sums' order differs.
    const PetscMat single = whole(k);
    const double serialLambda = distributedSmoothedProlongator(single).jacobiLambda;
    EXPECT_NEAR(p.jacobiLambda, serialLambda, 1e-12 * serialLambda);

    PetscInt rows = 0, aggregates = 0;
    RBM_CHECK_PETSC(MatGetSize(p.interpolation, &rows, &aggregates));
    PetscInt total = 0;
    MPI_Allreduce(&p.ownedAggregates, &total, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
    EXPECT_EQ(total, aggregates);
    // Aggregates of a 3 × 3 × 3 neighbourhood: about 27 rows each, far more than 8.
    EXPECT_LT(8 * aggregates, rows);

    // T 1 = 1 (each row in one aggregate), so P 1 = 1 − ω D⁻¹ K 1, row by row from the CSR; and
    // each row's own aggregate is one of its rank's (aggregates never cross ranks): its column,
    // the largest entry of the row, lies in the rank's range.
    const double omega = 4.0 / (3.0 * 1.05 * p.jacobiLambda);
    PetscInt firstAggregate = 0, endAggregate = 0;
    RBM_CHECK_PETSC(MatGetOwnershipRangeColumn(p.interpolation, &firstAggregate, &endAggregate));
    const int first = firstRowOf(worldRank(), k.rows), end = firstRowOf(worldRank() + 1, k.rows);
    for (int row = first; row < end; ++row) {
        double rowSum = 0.0, diagonal = 0.0;
        for (int e = k.offsets[row]; e < k.offsets[row + 1]; ++e) {
            rowSum += k.values[e];
            if (k.columns[e] == row) diagonal = k.values[e];
        }
        PetscInt count = 0;
        const PetscInt* indices = nullptr;
        const PetscScalar* values = nullptr;
        RBM_CHECK_PETSC(MatGetRow(p.interpolation, row, &count, &indices, &values));
        double sum = 0.0, largest = -1.0;
        PetscInt largestColumn = -1;
        for (PetscInt e = 0; e < count; ++e) {
            sum += values[e];
            if (values[e] > largest) largest = values[e], largestColumn = indices[e];
        }
        RBM_CHECK_PETSC(MatRestoreRow(p.interpolation, row, &count, &indices, &values));
        EXPECT_NEAR(sum, 1.0 - omega * rowSum / diagonal, 1e-12) << "row " << row;
        EXPECT_GE(largestColumn, firstAggregate) << "row " << row;
        EXPECT_LT(largestColumn, endAggregate) << "row " << row;
    }
}

// PETSc's two-level multigrid on P and Pᵀ K P (Chebyshev smoothing of degree 2 with point Jacobi
// on the fine level, one GAMG cycle on the coarse): the levels as a PETSc preconditioner, to
// judge them independently of rbm's own cycle of a part (PartThreeVectorCycle).
void useTwoLevels(KSP solver, Mat k)
{
    const DistributedProlongator prolongator = distributedSmoothedProlongator(k);
    const PetscMat coarseOperator = galerkinOperator(k, prolongator.interpolation);
    PC preconditioner = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(solver, &preconditioner));
    RBM_CHECK_PETSC(PCSetType(preconditioner, PCMG));
    RBM_CHECK_PETSC(PCMGSetLevels(preconditioner, 2, nullptr));
    RBM_CHECK_PETSC(PCMGSetInterpolation(preconditioner, 1, prolongator.interpolation));
    RBM_CHECK_PETSC(PCMGSetGalerkin(preconditioner, PC_MG_GALERKIN_NONE));
    KSP smoother = nullptr;
    RBM_CHECK_PETSC(PCMGGetSmoother(preconditioner, 1, &smoother));
    RBM_CHECK_PETSC(KSPSetType(smoother, KSPCHEBYSHEV));
    RBM_CHECK_PETSC(KSPChebyshevSetEigenvalues(smoother, 1.1 * prolongator.jacobiLambda, 0.1 * prolongator.jacobiLambda));
    RBM_CHECK_PETSC(KSPSetTolerances(smoother, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 2));
    PC jacobi = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(smoother, &jacobi));
    RBM_CHECK_PETSC(PCSetType(jacobi, PCJACOBI));
    KSP coarse = nullptr;
    RBM_CHECK_PETSC(PCMGGetCoarseSolve(preconditioner, &coarse));
    RBM_CHECK_PETSC(KSPSetOperators(coarse, coarseOperator, coarseOperator));
    RBM_CHECK_PETSC(KSPSetType(coarse, KSPPREONLY));
    PC coarseCycle = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(coarse, &coarseCycle));
    RBM_CHECK_PETSC(PCSetType(coarseCycle, PCGAMG));
}

// CG iterations to 1e-8 with the two levels of k as preconditioner, and the error of the
// solution of K x = K 1 (x = 1) in the largest entry.
std::pair<int, double> solveWithTheCycle(Mat k)
{
    const MPI_Comm communicator = PetscObjectComm(reinterpret_cast<PetscObject>(k));
    PetscKsp solver;
    RBM_CHECK_PETSC(KSPCreate(communicator, solver.out()));
    RBM_CHECK_PETSC(KSPSetOperators(solver, k, k));
    RBM_CHECK_PETSC(KSPSetType(solver, KSPCG));
    RBM_CHECK_PETSC(KSPSetTolerances(solver, 1e-8, 0.0, PETSC_DEFAULT, 200));
    RBM_CHECK_PETSC(KSPSetOptionsPrefix(solver, "distributed_aggregation_test_"));
    useTwoLevels(solver, k);
    RBM_CHECK_PETSC(KSPSetUp(solver));
    PetscVec exact, rightHandSide, solution;
    RBM_CHECK_PETSC(MatCreateVecs(k, exact.out(), rightHandSide.out()));
    RBM_CHECK_PETSC(VecDuplicate(exact, solution.out()));
    RBM_CHECK_PETSC(VecSet(exact, 1.0));
    RBM_CHECK_PETSC(MatMult(k, exact, rightHandSide));
    RBM_CHECK_PETSC(KSPSolve(solver, rightHandSide, solution));
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    RBM_CHECK_PETSC(KSPGetConvergedReason(solver, &reason));
    EXPECT_GT(reason, 0);
    PetscInt iterations = 0;
    RBM_CHECK_PETSC(KSPGetIterationNumber(solver, &iterations));
    RBM_CHECK_PETSC(VecAXPY(solution, -1.0, exact));
    PetscReal error = 0.0;
    RBM_CHECK_PETSC(VecNorm(solution, NORM_INFINITY, &error));
    return {static_cast<int>(iterations), error};
}

TEST(DistributedAggregation, TheTwoLevelsConvergeAsFastOnEveryRankCountAsOnOne)
{
    // The coarse level couples the ranks: block Jacobi over ranks would need more iterations as
    // they grow. Against the same cycle of the whole matrix on one rank, and
    // against CG with the point Jacobi preconditioner (no multigrid) on the same matrix.
    const Laplacian k = hexLaplacian(25);  // 24³ rows
    const PetscMat matrix = onThisRanksRows(k);
    const auto [iterations, error] = solveWithTheCycle(matrix);
    const PetscMat single = whole(k);
    const auto [singleIterations, singleError] = solveWithTheCycle(single);
    EXPECT_LT(error, 1e-6);
    EXPECT_LT(singleError, 1e-6);
    EXPECT_LE(iterations, singleIterations + 2);

    PetscKsp jacobi;
    RBM_CHECK_PETSC(KSPCreate(PETSC_COMM_SELF, jacobi.out()));
    RBM_CHECK_PETSC(KSPSetOperators(jacobi, single, single));
    RBM_CHECK_PETSC(KSPSetType(jacobi, KSPCG));
    RBM_CHECK_PETSC(KSPSetTolerances(jacobi, 1e-8, 0.0, PETSC_DEFAULT, 1000));
    PC pc = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(jacobi, &pc));
    RBM_CHECK_PETSC(PCSetType(pc, PCJACOBI));
    PetscVec right, x;
    RBM_CHECK_PETSC(MatCreateVecs(single, x.out(), right.out()));
    RBM_CHECK_PETSC(VecSet(x, 1.0));
    RBM_CHECK_PETSC(MatMult(single, x, right));
    RBM_CHECK_PETSC(KSPSolve(jacobi, right, x));
    PetscInt jacobiIterations = 0;
    RBM_CHECK_PETSC(KSPGetIterationNumber(jacobi, &jacobiIterations));
    EXPECT_LT(3 * iterations, jacobiIterations) << "multigrid: " << iterations << ", point Jacobi: " << jacobiIterations;
}

TEST(DistributedAggregation, ANonPositiveDiagonalIsNamedOnEveryRank)
{
    Laplacian k = hexLaplacian(6);
    const int badRow = k.rows / 2;
    for (int e = k.offsets[badRow]; e < k.offsets[badRow + 1]; ++e)
        if (k.columns[e] == badRow) k.values[e] = 0.0;
    const PetscMat matrix = onThisRanksRows(k);
    try {
        (void)distributedSmoothedProlongator(matrix);
        FAIL() << "no error";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("row " + std::to_string(badRow)), std::string::npos) << error.what();
    }
}

} // namespace

} // namespace rbm::motion
