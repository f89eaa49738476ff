#include "NodeExchange.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace rbm::motion {

NodeExchange::NodeExchange(const MeshPart& part)
    : communicator_(part.communicator()), nodeCount_(part.nodeCount()), ownedNodeCount_(part.ownedNodeCount())
{
    int ranks = 1;
    RBM_CHECK_PETSC(MPI_Comm_size(communicator_, &ranks));
    // A ghost's root is its owner's node: its row − the owner's first row.
    std::vector<Label> firstRows(ranks);
    const Label first = part.firstOwnedRow();
    RBM_CHECK_PETSC(MPI_Allgather(&first, 1, MPI_INT, firstRows.data(), 1, MPI_INT, communicator_));
    for (Label node = part.ownedNodeCount(); node < part.nodeCount(); ++node) {
        const int owner = part.nodeOwnerRanks()[node];
        ghostRootRanks_.push_back(owner);
        ghostRootIndices_.push_back(part.nodeRows()[node] - firstRows[owner]);
    }
}

NodeExchange::~NodeExchange()
{
    for (auto& [size, forest] : starForests_) (void)PetscSFDestroy(&forest);
}

PetscSF NodeExchange::starForest(int blockSize) const
{
    auto found = starForests_.find(blockSize);
    if (found != starForests_.end()) return found->second;
    const auto ghosts = static_cast<PetscInt>(ghostRootRanks_.size());
    PetscInt* leaves = nullptr;
    PetscSFNode* roots = nullptr;
    RBM_CHECK_PETSC(PetscMalloc1(ghosts * blockSize, &leaves));
    RBM_CHECK_PETSC(PetscMalloc1(ghosts * blockSize, &roots));
    for (PetscInt k = 0; k < ghosts; ++k)
        for (int c = 0; c < blockSize; ++c) {
            leaves[k * blockSize + c] = (ownedNodeCount_ + k) * blockSize + c;
            roots[k * blockSize + c].rank = ghostRootRanks_[k];
            roots[k * blockSize + c].index = ghostRootIndices_[k] * blockSize + c;
        }
    PetscSF forest = nullptr;
    RBM_CHECK_PETSC(PetscSFCreate(communicator_, &forest));
    starForests_.emplace(blockSize, forest);  // destroyed with this object from here on
    RBM_CHECK_PETSC(PetscSFSetGraph(forest, ownedNodeCount_ * blockSize, ghosts * blockSize, leaves, PETSC_OWN_POINTER,
                                    roots, PETSC_OWN_POINTER));
    RBM_CHECK_PETSC(PetscSFSetUp(forest));
    return forest;
}

void NodeExchange::checkLength(std::span<double> values, int blockSize) const
{
    if (blockSize < 1 || values.size() != static_cast<std::size_t>(blockSize) * nodeCount_)
        throw std::invalid_argument("NodeExchange: " + std::to_string(values.size()) + " values for " +
                                    std::to_string(nodeCount_) + " nodes of block size " + std::to_string(blockSize));
}

// Roots and leaves live in the same array (owned entries first, ghosts after): the star
// forest reads the one and writes the other, which never overlap.
void NodeExchange::updateGhosts(std::span<double> values, int blockSize) const
{
    checkLength(values, blockSize);
    const PetscSF forest = starForest(blockSize);
    RBM_CHECK_PETSC(PetscSFBcastBegin(forest, MPI_DOUBLE, values.data(), values.data(), MPI_REPLACE));
    RBM_CHECK_PETSC(PetscSFBcastEnd(forest, MPI_DOUBLE, values.data(), values.data(), MPI_REPLACE));
}

void NodeExchange::addGhostsToOwners(std::span<double> values, int blockSize) const
{
    checkLength(values, blockSize);
    const PetscSF forest = starForest(blockSize);
    RBM_CHECK_PETSC(PetscSFReduceBegin(forest, MPI_DOUBLE, values.data(), values.data(), MPI_SUM));
    RBM_CHECK_PETSC(PetscSFReduceEnd(forest, MPI_DOUBLE, values.data(), values.data(), MPI_SUM));
}

} // namespace rbm::motion

namespace rbm::motion {

double NodeExchange::sum(double value) const
{
    double total = 0.0;
    RBM_CHECK_PETSC(MPI_Allreduce(&value, &total, 1, MPI_DOUBLE, MPI_SUM, communicator_));
    return total;
}

double NodeExchange::maximum(double value) const
{
    double largest = 0.0;
    RBM_CHECK_PETSC(MPI_Allreduce(&value, &largest, 1, MPI_DOUBLE, MPI_MAX, communicator_));
    return largest;
}

} // namespace rbm::motion
