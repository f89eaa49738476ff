#include "DistributedAggregation.hpp"

#include "SmoothedAggregation.hpp"

#include <cmath>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace rbm::motion {

namespace {

static_assert(sizeof(PetscInt) == sizeof(int), "PETSc's indices must be 32-bit ints to read its CSR arrays");

// Every owned row's aggregate, numbered on this rank from 0 (aggregateRows on the rank's
// diagonal block: its own rows and the couplings between them).
std::vector<int> ownedAggregates(Mat k, int& count)
{
    Mat block = nullptr;
    RBM_CHECK_PETSC(MatGetDiagonalBlock(k, &block));
    PetscInt rows = 0;
    const PetscInt* offsets = nullptr;
    const PetscInt* columns = nullptr;
    PetscBool done = PETSC_FALSE;
    RBM_CHECK_PETSC(MatGetRowIJ(block, 0, PETSC_FALSE, PETSC_FALSE, &rows, &offsets, &columns, &done));
    if (!done) throw std::runtime_error("distributed aggregation: K's diagonal block has no compressed rows");
    const PetscScalar* values = nullptr;
    RBM_CHECK_PETSC(MatSeqAIJGetArrayRead(block, &values));
    const std::size_t entries = static_cast<std::size_t>(offsets[rows]);
    std::vector<int> aggregate = aggregateRows({offsets, static_cast<std::size_t>(rows) + 1}, {columns, entries},
                                               {values, entries}, count);
    RBM_CHECK_PETSC(MatSeqAIJRestoreArrayRead(block, &values));
    RBM_CHECK_PETSC(MatRestoreRowIJ(block, 0, PETSC_FALSE, PETSC_FALSE, &rows, &offsets, &columns, &done));
    return aggregate;
}

// D⁻¹ of K; throws on every rank if any rank has a diagonal entry that is not positive (so that
// no rank is left waiting in a collective call).
PetscVec inverseDiagonal(Mat k)
{
    PetscVec inverse;
    RBM_CHECK_PETSC(MatCreateVecs(k, inverse.out(), nullptr));
    RBM_CHECK_PETSC(MatGetDiagonal(k, inverse));
    PetscInt first = 0, end = 0;
    RBM_CHECK_PETSC(VecGetOwnershipRange(inverse, &first, &end));
    PetscScalar* entries = nullptr;
    RBM_CHECK_PETSC(VecGetArray(inverse, &entries));
    PetscInt badRow = -1;
    for (PetscInt row = 0; row < end - first; ++row) {
        if (!(entries[row] > 0.0) && badRow < 0) badRow = first + row;
        entries[row] = entries[row] > 0.0 ? 1.0 / entries[row] : 0.0;
    }
    RBM_CHECK_PETSC(VecRestoreArray(inverse, &entries));
    PetscInt firstBadRow = 0;
    RBM_CHECK_PETSC(MPI_Allreduce(&badRow, &firstBadRow, 1, MPIU_INT, MPI_MAX, PetscObjectComm(reinterpret_cast<PetscObject>(k))));
    if (firstBadRow >= 0)
        throw std::runtime_error("distributed aggregation: K's row " + std::to_string(firstBadRow) +
                                 " has no positive diagonal");
    return inverse;
}

// The largest eigenvalue of D⁻¹K by power iteration from the serial aggregation's start (a fixed
// irregular vector by global row), so that one rank reproduces the serial λ.
double largestEigenvalueOfJacobi(Mat k, Vec inverse)
{
    constexpr int iterations = 15;  // as the serial aggregation
    PetscVec v, w;
    RBM_CHECK_PETSC(VecDuplicate(inverse, v.out()));
    RBM_CHECK_PETSC(VecDuplicate(inverse, w.out()));
    PetscInt first = 0, end = 0;
    RBM_CHECK_PETSC(VecGetOwnershipRange(v, &first, &end));
    PetscScalar* entries = nullptr;
    RBM_CHECK_PETSC(VecGetArray(v, &entries));
    for (PetscInt row = first; row < end; ++row)
        entries[row - first] = 1.0 + 0.5 * std::sin(static_cast<double>(row) * 0.6180339887498949 * 6.283185307179586);
    RBM_CHECK_PETSC(VecRestoreArray(v, &entries));
    PetscReal length = 0.0;
    RBM_CHECK_PETSC(VecNormalize(v, &length));
    double lambda = 1.0;
    for (int iteration = 0; iteration < iterations; ++iteration) {
        RBM_CHECK_PETSC(MatMult(k, v, w));
        RBM_CHECK_PETSC(VecPointwiseMult(w, w, inverse));
        PetscReal norm = 0.0;
        RBM_CHECK_PETSC(VecNorm(w, NORM_2, &norm));
        if (!(norm > 0.0)) break;
        lambda = norm;  // |D⁻¹K v| for |v| = 1
        RBM_CHECK_PETSC(VecScale(w, 1.0 / norm));
        RBM_CHECK_PETSC(VecSwap(v, w));
    }
    return lambda;
}

} // namespace

DistributedProlongator distributedSmoothedProlongator(Mat k)
{
    const MPI_Comm communicator = PetscObjectComm(reinterpret_cast<PetscObject>(k));
    PetscInt firstRow = 0, endRow = 0;
    RBM_CHECK_PETSC(MatGetOwnershipRange(k, &firstRow, &endRow));
    int count = 0;
    const std::vector<int> aggregate = ownedAggregates(k, count);
    PetscInt firstAggregate = 0;
    const PetscInt owned = count;
    RBM_CHECK_PETSC(MPI_Exscan(&owned, &firstAggregate, 1, MPIU_INT, MPI_SUM, communicator));
    int rank = 0;
    RBM_CHECK_PETSC(MPI_Comm_rank(communicator, &rank));
    if (rank == 0) firstAggregate = 0;  // MPI_Exscan leaves rank 0's result undefined

    DistributedProlongator result;
    result.ownedAggregates = owned;
    const PetscVec inverse = inverseDiagonal(k);
    result.jacobiLambda = largestEigenvalueOfJacobi(k, inverse);
    // The serial aggregation's ω: 4 / (3 λ) with λ given a 5 % margin (an underestimate would make
    // the smoothing amplify the top of the spectrum instead of damping it).
    const double omega = 4.0 / (3.0 * 1.05 * result.jacobiLambda);

    PetscMat tentative;
    RBM_CHECK_PETSC(MatCreateAIJ(communicator, endRow - firstRow, owned, PETSC_DETERMINE, PETSC_DETERMINE, 1, nullptr,
                                 0, nullptr, tentative.out()));
    for (PetscInt row = firstRow; row < endRow; ++row) {
        const PetscInt column = firstAggregate + aggregate[row - firstRow];
        RBM_CHECK_PETSC(MatSetValue(tentative, row, column, 1.0, INSERT_VALUES));
    }
    RBM_CHECK_PETSC(MatAssemblyBegin(tentative, MAT_FINAL_ASSEMBLY));
    RBM_CHECK_PETSC(MatAssemblyEnd(tentative, MAT_FINAL_ASSEMBLY));
    // P = T − ω D⁻¹ (K T): K T holds T's pattern (K's diagonal is in every row).
    RBM_CHECK_PETSC(MatMatMult(k, tentative, MAT_INITIAL_MATRIX, PETSC_DEFAULT, result.interpolation.out()));
    // PETSc keeps the product's intermediate data (for a product again with new values) unless told.
    RBM_CHECK_PETSC(MatProductClear(result.interpolation));
    RBM_CHECK_PETSC(MatDiagonalScale(result.interpolation, inverse, nullptr));
    RBM_CHECK_PETSC(MatAYPX(result.interpolation, -omega, tentative, SUBSET_NONZERO_PATTERN));
    return result;
}

PetscMat galerkinOperator(Mat k, Mat interpolation)
{
    // Formed once, PETSc's intermediate data of the product dropped: kept (for a product again
    // with new values, as PCMG's own Galerkin option does) they held Pᵀ explicitly and P's rows
    // from other ranks, about 80 MB a rank on the 10⁶-cell cube on 2 ranks through every solve.
    PetscMat coarse;
    RBM_CHECK_PETSC(MatPtAP(k, interpolation, MAT_INITIAL_MATRIX, PETSC_DEFAULT, coarse.out()));
    RBM_CHECK_PETSC(MatProductClear(coarse));
    return coarse;
}

} // namespace rbm::motion
