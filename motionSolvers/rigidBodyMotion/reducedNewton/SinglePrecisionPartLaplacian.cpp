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

// The ghost unknowns' values of `width` interleaved vectors x (width per owned unknown) from
// their owners, in ghostValues_ (width per ghost unknown, in the part's order), through a node
// array (the exchange's).
void SinglePrecisionPartLaplacian::fetchGhosts(const double* x, int width) const
{
    const std::vector<int>& nodes = problem_.unknownNodes();
    const int unknowns = problem_.unknownNodeCount();
    const std::size_t w = static_cast<std::size_t>(width);
    nodeValues_.resize(w * static_cast<std::size_t>(problem_.nodeCount()));
    ghostValues_.resize(w * static_cast<std::size_t>(unknowns - ownedUnknowns_));
    for (int a = 0; a < ownedUnknowns_; ++a)
        for (std::size_t c = 0; c < w; ++c) nodeValues_[w * static_cast<std::size_t>(nodes[a]) + c] = x[w * static_cast<std::size_t>(a) + c];
    problem_.nodeExchange()->updateGhosts(nodeValues_, width);
    for (int b = ownedUnknowns_; b < unknowns; ++b)
        for (std::size_t c = 0; c < w; ++c)
            ghostValues_[w * static_cast<std::size_t>(b - ownedUnknowns_) + c] = nodeValues_[w * static_cast<std::size_t>(nodes[b]) + c];
}

void SinglePrecisionPartLaplacian::multiply(Vec x, Vec y) const
{
    const BlockPattern& pattern = problem_.blockPattern();
    const double* in = nullptr;
    RBM_CHECK_PETSC(VecGetArrayRead(x, &in));
    fetchGhosts(in, 1);
    double* out = nullptr;
    RBM_CHECK_PETSC(VecGetArray(y, &out));
    const int* offsets = pattern.rowOffsets.data();
    const int* columns = pattern.columns.data();
    const float* values = values_.data();
    const double* ghosts = ghostValues_.data();
    for (int a = 0; a < ownedUnknowns_; ++a) {
        double sum = 0.0;
        for (int position = offsets[a]; position < offsets[a + 1]; ++position) {
            const int b = columns[position];
            sum += static_cast<double>(values[position]) * (b < ownedUnknowns_ ? in[b] : ghosts[b - ownedUnknowns_]);
        }
        out[a] = sum;
    }
    RBM_CHECK_PETSC(VecRestoreArray(y, &out));
    RBM_CHECK_PETSC(VecRestoreArrayRead(x, &in));
}

void SinglePrecisionPartLaplacian::multiplyThree(const double* x, double* y) const
{
    const BlockPattern& pattern = problem_.blockPattern();
    fetchGhosts(x, 3);
    const int* offsets = pattern.rowOffsets.data();
    const int* columns = pattern.columns.data();
    const float* values = values_.data();
    const double* ghosts = ghostValues_.data();
    for (int a = 0; a < ownedUnknowns_; ++a) {
        double s0 = 0.0, s1 = 0.0, s2 = 0.0;
        for (int position = offsets[a]; position < offsets[a + 1]; ++position) {
            const double value = values[position];
            const int b = columns[position];
            const double* xb = b < ownedUnknowns_ ? x + 3 * static_cast<std::size_t>(b)
                                                  : ghosts + 3 * static_cast<std::size_t>(b - ownedUnknowns_);
            s0 += value * xb[0], s1 += value * xb[1], s2 += value * xb[2];
        }
        double* out = y + 3 * static_cast<std::size_t>(a);
        out[0] = s0, out[1] = s1, out[2] = s2;
    }
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
