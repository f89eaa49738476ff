#pragma once
// The two data movements of the distributed solve over a MeshPart's nodes, on arrays with
// `blockSize` doubles per node (owned nodes first, then ghosts, as the part numbers them):
//
//   updateGhosts       every ghost gets its owner's values (before an evaluation reads the
//                      neighbours of the owned nodes);
//   addGhostsToOwners  every owner adds what its ghost copies hold (after an evaluation has
//                      scattered the owned nodes' terms onto their neighbours, ghosts included).
//
// Both go through a PETSc star forest (PetscSF): the owned nodes' values are its roots, the
// ghosts' its leaves, one forest per block size (built at first use) on plain doubles: MPI
// reduces only predefined types, so a block type could be broadcast but not added. Traffic is
// the ghost values only, never the whole vector.

#include "MeshPart.hpp"
#include "PetscSupport.hpp"

#include <petscsf.h>

#include <map>
#include <vector>
#include <span>

namespace rbm::motion {

class NodeExchange {
public:
    explicit NodeExchange(const MeshPart& part);
    ~NodeExchange();
    NodeExchange(const NodeExchange&) = delete;
    NodeExchange& operator=(const NodeExchange&) = delete;

    MPI_Comm communicator() const { return communicator_; }

    // values: blockSize × part.nodeCount() entries. Collective.
    void updateGhosts(std::span<double> values, int blockSize) const;
    // Adds the ghosts' values to their owners' (the ghosts' entries are left as they were).
    void addGhostsToOwners(std::span<double> values, int blockSize) const;
    // The sum and the largest of one value per rank (collective).
    double sum(double value) const;
    double maximum(double value) const;

private:
    PetscSF starForest(int blockSize) const;
    void checkLength(std::span<double> values, int blockSize) const;

    MPI_Comm communicator_;
    Label nodeCount_ = 0;
    Label ownedNodeCount_ = 0;
    std::vector<Label> ghostRootRanks_, ghostRootIndices_;  // per ghost: its owner and the owner's node
    mutable std::map<int, PetscSF> starForests_;            // per block size
};

} // namespace rbm::motion
