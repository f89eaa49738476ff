#include "BlockRowLayout.hpp"

#include <petscis.h>
#include <petscmat.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace rbm::motion {

namespace {

MPI_Comm& currentSolverCommunicator()
{
    static MPI_Comm communicator = PETSC_COMM_SELF;
    return communicator;
}

using PetscScatter = PetscHandle<VecScatter, VecScatterDestroy>;
using PetscIs = PetscHandle<IS, ISDestroy>;
using PetscPartitioning = PetscHandle<MatPartitioning, MatPartitioningDestroy>;

} // namespace

MPI_Comm solverCommunicator() { return currentSolverCommunicator(); }

void setSolverCommunicator(MPI_Comm communicator) { currentSolverCommunicator() = communicator; }

struct BlockRowLayout::Gatherer {
    int blockSize = 0;
    PetscScatter scatter;
    PetscVec whole;  // sequential, PETSc order
};

BlockRowLayout::BlockRowLayout(MPI_Comm communicator, std::span<const int> rowOffsets, std::span<const int> columns)
    : communicator_(communicator)
{
    const int rows = static_cast<int>(rowOffsets.size()) - 1;
    if (rows < 0) throw std::invalid_argument("BlockRowLayout: empty row offsets");
    int rank = 0;
    MPI_Comm_size(communicator, &rankCount_);
    MPI_Comm_rank(communicator, &rank);
    petscRowOf_.resize(rows);
    std::iota(petscRowOf_.begin(), petscRowOf_.end(), 0);
    if (rankCount_ == 1) {
        ownedRows_ = petscRowOf_;
        naturalRowOf_ = petscRowOf_;
        return;
    }

    // The adjacency (pattern without the diagonal) of an even first split of the natural
    // rows, which MatPartitioning redistributes. MatCreateMPIAdj takes ownership of arrays
    // allocated with PetscMalloc.
    const int firstBegin = static_cast<int>(static_cast<long long>(rows) * rank / rankCount_);
    const int firstEnd = static_cast<int>(static_cast<long long>(rows) * (rank + 1) / rankCount_);
    const int localRows = firstEnd - firstBegin;
    PetscInt* offsets = nullptr;
    PetscInt* neighbours = nullptr;
    RBM_CHECK_PETSC(PetscMalloc1(localRows + 1, &offsets));
    int edgeCount = 0;
    for (int row = firstBegin; row < firstEnd; ++row)
        for (int position = rowOffsets[row]; position < rowOffsets[row + 1]; ++position)
            if (columns[position] != row) ++edgeCount;
    RBM_CHECK_PETSC(PetscMalloc1(std::max(edgeCount, 1), &neighbours));
    offsets[0] = 0;
    int edge = 0;
    for (int row = firstBegin; row < firstEnd; ++row) {
        for (int position = rowOffsets[row]; position < rowOffsets[row + 1]; ++position)
            if (columns[position] != row) neighbours[edge++] = columns[position];
        offsets[row - firstBegin + 1] = edge;
    }
    PetscMat adjacency;
    RBM_CHECK_PETSC(MatCreateMPIAdj(communicator, localRows, rows, offsets, neighbours, nullptr, adjacency.out()));

    PetscPartitioning partitioning;
    RBM_CHECK_PETSC(MatPartitioningCreate(communicator, partitioning.out()));
    RBM_CHECK_PETSC(MatPartitioningSetAdjacency(partitioning, adjacency));
#if defined(PETSC_HAVE_PTSCOTCH)
    RBM_CHECK_PETSC(MatPartitioningSetType(partitioning, MATPARTITIONINGPTSCOTCH));
#elif defined(PETSC_HAVE_PARMETIS)
    RBM_CHECK_PETSC(MatPartitioningSetType(partitioning, MATPARTITIONINGPARMETIS));
#else
    RBM_CHECK_PETSC(MatPartitioningSetType(partitioning, MATPARTITIONINGAVERAGE));
#endif
    RBM_CHECK_PETSC(PetscObjectSetOptionsPrefix(reinterpret_cast<PetscObject>(partitioning.get()), "rbm_"));  // -rbm_mat_partitioning_type
    RBM_CHECK_PETSC(MatPartitioningSetFromOptions(partitioning));
    PetscIs newRank;
    RBM_CHECK_PETSC(MatPartitioningApply(partitioning, newRank.out()));
    PetscIs newNumber;
    RBM_CHECK_PETSC(ISPartitioningToNumbering(newRank, newNumber.out()));
    std::vector<PetscInt> counts(rankCount_);
    RBM_CHECK_PETSC(ISPartitioningCount(newRank, rankCount_, counts.data()));
    PetscIs allNumbers;
    RBM_CHECK_PETSC(ISAllGather(newNumber, allNumbers.out()));
    {
        const PetscInt* numbers = nullptr;
        RBM_CHECK_PETSC(ISGetIndices(allNumbers, &numbers));
        for (int row = 0; row < rows; ++row) petscRowOf_[row] = static_cast<int>(numbers[row]);
        RBM_CHECK_PETSC(ISRestoreIndices(allNumbers, &numbers));
    }
    ownedBegin_ = 0;
    for (int r = 0; r < rank; ++r) ownedBegin_ += static_cast<int>(counts[r]);
    naturalRowOf_.assign(rows, -1);
    for (int row = 0; row < rows; ++row) naturalRowOf_[petscRowOf_[row]] = row;
    ownedRows_.assign(naturalRowOf_.begin() + ownedBegin_, naturalRowOf_.begin() + ownedBegin_ + counts[rank]);
}

BlockRowLayout::~BlockRowLayout() = default;

PetscVec BlockRowLayout::createVector(int blockSize) const
{
    PetscVec vector;
    RBM_CHECK_PETSC(VecCreate(communicator_, vector.out()));
    RBM_CHECK_PETSC(VecSetSizes(vector, ownedRowCount() * blockSize, rowCount() * blockSize));
    RBM_CHECK_PETSC(VecSetBlockSize(vector, blockSize));
    RBM_CHECK_PETSC(VecSetType(vector, isDistributed() ? VECMPI : VECSEQ));
    return vector;
}

void BlockRowLayout::scatter(std::span<const double> natural, Vec vector, int blockSize) const
{
    if (natural.size() != static_cast<std::size_t>(rowCount()) * blockSize)
        throw std::invalid_argument("BlockRowLayout::scatter: the array does not match the layout");
    PetscScalar* local = nullptr;
    RBM_CHECK_PETSC(VecGetArray(vector, &local));
    for (std::size_t k = 0; k < ownedRows_.size(); ++k)
        std::copy_n(natural.data() + static_cast<std::size_t>(ownedRows_[k]) * blockSize, blockSize,
                    local + k * blockSize);
    RBM_CHECK_PETSC(VecRestoreArray(vector, &local));
}

void BlockRowLayout::gather(Vec vector, std::span<double> natural, int blockSize) const
{
    if (natural.size() != static_cast<std::size_t>(rowCount()) * blockSize)
        throw std::invalid_argument("BlockRowLayout::gather: the array does not match the layout");
    const PetscScalar* values = nullptr;
    if (!isDistributed()) {
        RBM_CHECK_PETSC(VecGetArrayRead(vector, &values));
        std::copy_n(values, natural.size(), natural.data());
        RBM_CHECK_PETSC(VecRestoreArrayRead(vector, &values));
        return;
    }
    auto found = std::find_if(gatherers_.begin(), gatherers_.end(),
                              [blockSize](const Gatherer& g) { return g.blockSize == blockSize; });
    if (found == gatherers_.end()) {
        Gatherer gatherer;
        gatherer.blockSize = blockSize;
        RBM_CHECK_PETSC(VecScatterCreateToAll(vector, gatherer.scatter.out(), gatherer.whole.out()));
        gatherers_.push_back(std::move(gatherer));
        found = gatherers_.end() - 1;
    }
    RBM_CHECK_PETSC(VecScatterBegin(found->scatter, vector, found->whole, INSERT_VALUES, SCATTER_FORWARD));
    RBM_CHECK_PETSC(VecScatterEnd(found->scatter, vector, found->whole, INSERT_VALUES, SCATTER_FORWARD));
    RBM_CHECK_PETSC(VecGetArrayRead(found->whole, &values));
    for (int row = 0; row < rowCount(); ++row)
        std::copy_n(values + static_cast<std::size_t>(row) * blockSize, blockSize,
                    natural.data() + static_cast<std::size_t>(naturalRowOf_[row]) * blockSize);
    RBM_CHECK_PETSC(VecRestoreArrayRead(found->whole, &values));
}

} // namespace rbm::motion
