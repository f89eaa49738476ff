#include "SinglePrecisionPartLaplacian.hpp"

#include "NodeExchange.hpp"

#include <algorithm>
#include <stdexcept>

namespace rbm::motion {

SinglePrecisionPartLaplacian::SinglePrecisionPartLaplacian(const RbmProblem& problem)
    : problem_(problem), ownedUnknowns_(problem.ownedUnknownCount())
{
    if (!problem.isPart()) throw std::invalid_argument("SinglePrecisionPartLaplacian: one rank's part is needed");
    diagonal_.resize(static_cast<std::size_t>(ownedUnknowns_));
    nodeValues_.assign(static_cast<std::size_t>(problem.nodeCount()), 0.0);
}

SinglePrecisionPartLaplacian::SinglePrecisionPartLaplacian(const RbmProblem& problem, std::span<const double> laplacian)
    : SinglePrecisionPartLaplacian(problem)
{
    const BlockPattern& pattern = problem.blockPattern();
    if (laplacian.size() != static_cast<std::size_t>(pattern.blockCount()))
        throw std::invalid_argument("SinglePrecisionPartLaplacian: one Laplacian entry per block of the pattern expected");
    const std::size_t ownedEntries = static_cast<std::size_t>(pattern.rowOffsets[ownedUnknowns_]);
    values_.assign(laplacian.begin(), laplacian.begin() + static_cast<std::ptrdiff_t>(ownedEntries));
    for (int a = 0; a < ownedUnknowns_; ++a) diagonal_[a] = laplacian[pattern.diagonal[a]];
    createShell();
}

SinglePrecisionPartLaplacian::SinglePrecisionPartLaplacian(const RbmProblem& problem, Mat laplacian,
                                                           std::span<const PetscInt> unknownRows)
    : SinglePrecisionPartLaplacian(problem)
{
    const BlockPattern& pattern = problem.blockPattern();
    if (unknownRows.size() != static_cast<std::size_t>(problem.unknownNodeCount()))
        throw std::invalid_argument("SinglePrecisionPartLaplacian: one global row per unknown node expected");
    values_.resize(static_cast<std::size_t>(pattern.rowOffsets[ownedUnknowns_]));
    for (int a = 0; a < ownedUnknowns_; ++a) {
        PetscInt count = 0;
        const PetscInt* columns = nullptr;
        const PetscScalar* values = nullptr;
        RBM_CHECK_PETSC(MatGetRow(laplacian, unknownRows[a], &count, &columns, &values));
        // PETSc's row is sorted by global column; the pattern's row is in the part's order.
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position) {
            const PetscInt column = unknownRows[pattern.columns[position]];
            const PetscInt* found = std::lower_bound(columns, columns + count, column);
            if (found == columns + count || *found != column)
                throw std::logic_error("SinglePrecisionPartLaplacian: K has no entry where the pattern has one");
            const double value = values[found - columns];
            values_[position] = static_cast<float>(value);
            if (position == pattern.diagonal[a]) diagonal_[a] = value;
        }
        RBM_CHECK_PETSC(MatRestoreRow(laplacian, unknownRows[a], &count, &columns, &values));
    }
    createShell();
}

void SinglePrecisionPartLaplacian::createShell()
{
    const MPI_Comm communicator = problem_.nodeExchange()->communicator();
    RBM_CHECK_PETSC(MatCreateShell(communicator, ownedUnknowns_, ownedUnknowns_, PETSC_DETERMINE, PETSC_DETERMINE, this,
                                   matrix_.out()));
    RBM_CHECK_PETSC(MatShellSetOperation(matrix_, MATOP_MULT, reinterpret_cast<void (*)(void)>(&shellMultiply)));
    RBM_CHECK_PETSC(MatShellSetOperation(matrix_, MATOP_GET_DIAGONAL, reinterpret_cast<void (*)(void)>(&shellDiagonal)));
    RBM_CHECK_PETSC(MatSetOption(matrix_, MAT_SYMMETRIC, PETSC_TRUE));
}

void SinglePrecisionPartLaplacian::multiply(Vec x, Vec y) const
{
    const BlockPattern& pattern = problem_.blockPattern();
    const std::vector<int>& nodes = problem_.unknownNodes();
    const double* in = nullptr;
    RBM_CHECK_PETSC(VecGetArrayRead(x, &in));
    for (int a = 0; a < ownedUnknowns_; ++a) nodeValues_[nodes[a]] = in[a];
    problem_.nodeExchange()->updateGhosts(nodeValues_, 1);
    double* out = nullptr;
    RBM_CHECK_PETSC(VecGetArray(y, &out));
    for (int a = 0; a < ownedUnknowns_; ++a) {
        double sum = 0.0;
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position) {
            const int b = pattern.columns[position];
            sum += static_cast<double>(values_[position]) * (b < ownedUnknowns_ ? in[b] : nodeValues_[nodes[b]]);
        }
        out[a] = sum;
    }
    RBM_CHECK_PETSC(VecRestoreArray(y, &out));
    RBM_CHECK_PETSC(VecRestoreArrayRead(x, &in));
}

PetscErrorCode SinglePrecisionPartLaplacian::shellMultiply(Mat matrix, Vec x, Vec y)
{
    try {
        void* context = nullptr;
        RBM_CHECK_PETSC(MatShellGetContext(matrix, &context));
        static_cast<const SinglePrecisionPartLaplacian*>(context)->multiply(x, y);
        return 0;
    } catch (const std::exception&) {
        return PETSC_ERR_LIB;
    }
}

PetscErrorCode SinglePrecisionPartLaplacian::shellDiagonal(Mat matrix, Vec diagonal)
{
    try {
        void* context = nullptr;
        RBM_CHECK_PETSC(MatShellGetContext(matrix, &context));
        const auto* self = static_cast<const SinglePrecisionPartLaplacian*>(context);
        double* out = nullptr;
        RBM_CHECK_PETSC(VecGetArray(diagonal, &out));
        for (int a = 0; a < self->ownedUnknowns_; ++a) out[a] = self->diagonal_[a];
        RBM_CHECK_PETSC(VecRestoreArray(diagonal, &out));
        return 0;
    } catch (const std::exception&) {
        return PETSC_ERR_LIB;
    }
}

} // namespace rbm::motion
