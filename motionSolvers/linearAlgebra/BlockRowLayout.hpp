#pragma once
// How the block rows of a coupled system are spread over the ranks of a communicator.
//
// Every rank holds the whole RBM problem (mesh, graph, weights: replicated) and computes
// with plain arrays in the problem's own unknown numbering ("natural" rows). The PETSc
// objects (matrix, vectors, KSP, SNES) are distributed: each rank owns a contiguous range
// of PETSc block rows and inserts only those rows of the matrix. Which natural rows a rank
// owns comes from PETSc's graph partitioner (MatPartitioning, PT-Scotch where PETSc has it)
// applied to the block sparsity pattern, so that ranks share few couplings; the PETSc
// numbering lists rank 0's rows first, then rank 1's, and so on.
//
// On a communicator of one rank (the default, PETSC_COMM_SELF) the layout is the
// identity and every method is a plain copy, so serial runs are unchanged.
//
// The communicator for new solvers is a process-wide setting, like OpenFOAM's parRun():
// rbmMoveMesh -parallel sets PETSC_COMM_WORLD; everything else stays serial.

#include "PetscSupport.hpp"

#include <mpi.h>

#include <span>
#include <vector>

namespace rbm::motion {

// The communicator over which solvers created from now on distribute their systems.
MPI_Comm solverCommunicator();
void setSolverCommunicator(MPI_Comm communicator);

class BlockRowLayout {
public:
    // rowOffsets/columns: block CSR over natural rows (as in BlockPattern). Collective on
    // the communicator; every rank must pass the same pattern.
    BlockRowLayout(MPI_Comm communicator, std::span<const int> rowOffsets, std::span<const int> columns);
    ~BlockRowLayout();
    BlockRowLayout(const BlockRowLayout&) = delete;
    BlockRowLayout& operator=(const BlockRowLayout&) = delete;

    MPI_Comm communicator() const { return communicator_; }
    bool isDistributed() const { return rankCount_ > 1; }
    int rowCount() const { return static_cast<int>(petscRowOf_.size()); }
    // This rank's PETSc block rows: [ownedBegin, ownedEnd).
    int ownedBegin() const { return ownedBegin_; }
    int ownedEnd() const { return ownedBegin_ + static_cast<int>(ownedRows_.size()); }
    int ownedRowCount() const { return static_cast<int>(ownedRows_.size()); }
    // PETSc block row of a natural row, and the natural rows this rank owns in PETSc order.
    int petscRow(int naturalRow) const { return petscRowOf_[naturalRow]; }
    const std::vector<int>& ownedRows() const { return ownedRows_; }

    // A vector of rowCount() blocks of blockSize entries, this rank holding its own rows.
    PetscVec createVector(int blockSize) const;
    // vector ← the owned rows of `natural` (all rowCount() blocks, natural order).
    void scatter(std::span<const double> natural, Vec vector, int blockSize) const;
    // natural ← the whole vector, on every rank (collective).
    void gather(Vec vector, std::span<double> natural, int blockSize) const;

private:
    MPI_Comm communicator_;
    int rankCount_ = 1;
    int ownedBegin_ = 0;
    std::vector<int> petscRowOf_;  // natural → PETSc block row
    std::vector<int> ownedRows_;   // natural rows owned here, in PETSc order
    std::vector<int> naturalRowOf_;  // PETSc block row → natural
    // Gathering to all ranks: one scatter and one sequential vector, made on first use per
    // block size (the solvers use one or two sizes).
    struct Gatherer;
    mutable std::vector<Gatherer> gatherers_;
};

} // namespace rbm::motion
