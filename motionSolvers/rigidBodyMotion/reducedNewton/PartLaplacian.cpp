#include "PartLaplacian.hpp"

#include "NodeExchange.hpp"

#include <stdexcept>

namespace rbm::motion {

PartLaplacian::PartLaplacian(const RbmProblem& problem, std::span<const double> laplacian, double relativeTolerance)
    : problem_(problem)
{
    if (!problem.isPart() || problem.dimension() != 3)
        throw std::invalid_argument("PartLaplacian: one rank's part of a 3D problem is needed");
    if (laplacian.size() != static_cast<std::size_t>(problem.blockPattern().blockCount()))
        throw std::invalid_argument("PartLaplacian: one Laplacian entry per block of the pattern expected");
    assemble(laplacian);
    const MPI_Comm communicator = problem.nodeExchange()->communicator();
    const PetscInt ownedRows = 3 * static_cast<PetscInt>(problem.ownedUnknownCount());
    RBM_CHECK_PETSC(VecCreateMPIWithArray(communicator, 3, ownedRows, PETSC_DECIDE, nullptr, rightHandSide_.out()));
    RBM_CHECK_PETSC(VecCreateMPIWithArray(communicator, 3, ownedRows, PETSC_DECIDE, nullptr, solution_.out()));
    RBM_CHECK_PETSC(KSPCreate(communicator, solver_.out()));
    RBM_CHECK_PETSC(KSPSetOperators(solver_, matrix_, matrix_));
    RBM_CHECK_PETSC(KSPSetType(solver_, KSPCG));
    PC preconditioner = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(solver_, &preconditioner));
    RBM_CHECK_PETSC(PCSetType(preconditioner, PCGAMG));
    RBM_CHECK_PETSC(KSPSetTolerances(solver_, relativeTolerance, 0.0, PETSC_DEFAULT, 1000));
    options_ = std::make_unique<InheritedOptions>("reduced");
    configureFromOptions(solver_, *options_);
    RBM_CHECK_PETSC(KSPSetUp(solver_));
}

PartLaplacian::~PartLaplacian() = default;

std::vector<PetscInt> PartLaplacian::unknownRows() const
{
    const NodeExchange& exchange = *problem_.nodeExchange();
    const int owned = problem_.ownedUnknownCount();
    PetscInt first = 0;
    const PetscInt count = owned;
    RBM_CHECK_PETSC(MPI_Exscan(&count, &first, 1, MPIU_INT, MPI_SUM, exchange.communicator()));
    int rank = 0;
    RBM_CHECK_PETSC(MPI_Comm_rank(exchange.communicator(), &rank));
    if (rank == 0) first = 0;  // MPI_Exscan leaves rank 0's result undefined
    // Through the node exchange as doubles (exact below 2⁵³): −1 at prescribed nodes.
    std::vector<double> nodeRows(static_cast<std::size_t>(problem_.nodeCount()), -1.0);
    for (int a = 0; a < owned; ++a) nodeRows[problem_.unknownNodes()[a]] = static_cast<double>(first + a);
    exchange.updateGhosts(nodeRows, 1);
    std::vector<PetscInt> rows(static_cast<std::size_t>(problem_.unknownNodeCount()));
    for (int a = 0; a < problem_.unknownNodeCount(); ++a) {
        rows[a] = static_cast<PetscInt>(nodeRows[problem_.unknownNodes()[a]]);
        if (rows[a] < 0)
            throw std::logic_error("PartLaplacian: a ghost unknown node is prescribed on its owner");
    }
    return rows;
}

void PartLaplacian::assemble(std::span<const double> laplacian)
{
    const BlockPattern& pattern = problem_.blockPattern();
    // K ⊗ I in 3 × 3 blocks, projected in place.
    std::vector<double> blocks(9 * static_cast<std::size_t>(pattern.blockCount()), 0.0);
    for (int position = 0; position < pattern.blockCount(); ++position)
        for (int q = 0; q < 3; ++q) blocks[9 * static_cast<std::size_t>(position) + 4 * q] = laplacian[position];
    problem_.projectSlidingBlocks(blocks, 3);
    const std::vector<PetscInt> rows = unknownRows();
    const int owned = problem_.ownedUnknownCount();
    // Preallocation by block row: columns on this rank (its owned range) and elsewhere.
    const PetscInt firstOwnedRow = owned > 0 ? rows[0] : 0;
    std::vector<PetscInt> diagonalBlocks(owned, 0), offDiagonalBlocks(owned, 0);
    for (int a = 0; a < owned; ++a)
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position) {
            const PetscInt column = rows[pattern.columns[position]];
            const bool local = column >= firstOwnedRow && column < firstOwnedRow + owned;
            (local ? diagonalBlocks : offDiagonalBlocks)[a] += 1;
        }
    const MPI_Comm communicator = problem_.nodeExchange()->communicator();
    RBM_CHECK_PETSC(MatCreate(communicator, matrix_.out()));
    RBM_CHECK_PETSC(MatSetSizes(matrix_, 3 * owned, 3 * owned, PETSC_DETERMINE, PETSC_DETERMINE));
    RBM_CHECK_PETSC(MatSetType(matrix_, MATAIJ));  // GAMG's format; block size 3 for its aggregates
    RBM_CHECK_PETSC(MatSetBlockSize(matrix_, 3));
    RBM_CHECK_PETSC(MatXAIJSetPreallocation(matrix_, 3, diagonalBlocks.data(), offDiagonalBlocks.data(), nullptr, nullptr));
    for (int a = 0; a < owned; ++a)
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position) {
            const PetscInt column = rows[pattern.columns[position]];
            RBM_CHECK_PETSC(MatSetValuesBlocked(matrix_, 1, &rows[a], 1, &column,
                                                blocks.data() + 9 * static_cast<std::size_t>(position), INSERT_VALUES));
        }
    RBM_CHECK_PETSC(MatAssemblyBegin(matrix_, MAT_FINAL_ASSEMBLY));
    RBM_CHECK_PETSC(MatAssemblyEnd(matrix_, MAT_FINAL_ASSEMBLY));
    RBM_CHECK_PETSC(MatSetOption(matrix_, MAT_SPD, PETSC_TRUE));
}

bool PartLaplacian::apply(std::span<const double> r, std::span<double> z)
{
    const std::size_t ownedEntries = 3 * static_cast<std::size_t>(problem_.ownedUnknownCount());
    if (r.size() != 3 * static_cast<std::size_t>(problem_.unknownNodeCount()) || z.size() != r.size())
        throw std::invalid_argument("PartLaplacian::apply: 3 entries per unknown node expected");
    projected_.assign(r.begin(), r.end());
    problem_.projectSliding(projected_, 3);
    std::fill(z.begin(), z.end(), 0.0);
    RBM_CHECK_PETSC(VecPlaceArray(rightHandSide_, projected_.data()));
    RBM_CHECK_PETSC(VecPlaceArray(solution_, z.data()));
    RBM_CHECK_PETSC(KSPSolve(solver_, rightHandSide_, solution_));
    RBM_CHECK_PETSC(VecResetArray(rightHandSide_));
    RBM_CHECK_PETSC(VecResetArray(solution_));
    std::fill(z.begin() + static_cast<std::ptrdiff_t>(ownedEntries), z.end(), 0.0);
    PetscInt iterations = 0;
    RBM_CHECK_PETSC(KSPGetIterationNumber(solver_, &iterations));
    lastIterations_ = static_cast<int>(iterations);
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    RBM_CHECK_PETSC(KSPGetConvergedReason(solver_, &reason));
    return reason > 0;
}

} // namespace rbm::motion
