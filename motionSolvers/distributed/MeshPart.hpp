#pragma once
// One rank's part of a decomposed mesh with everything the distributed RBM solve needs
// locally (docs/parallel.md, "Distributed data"):
//
//   nodes    the points it owns first (rows firstOwnedRow … firstOwnedRow + ownedNodeCount − 1,
//            PointOwnership), then its ghosts: the points of its own cells that another rank
//            owns, then the points that only the halo cells bring;
//   cells    its own cells first (ownCellCount), then the halo: every cell of another rank
//            that holds one of the points this rank owns.
//
// With the halo, every owned node has all its cells, so its neighbourhood N(i) in the RBM's
// cell-neighbour graph is complete and its energy term, rotation fit and rows can be evaluated
// here. One layer suffices because a rank evaluates only its owned nodes' terms and adds what
// they contribute to ghost rows to the owners (NodeExchange). Ghost nodes' own neighbourhoods
// are incomplete and must not be evaluated.
//
// Setup is collective: PointOwnership's two rendezvous rounds and one all-to-all of the halo
// cells (their points' global labels, owners, rows and coordinates).

#include "LocalCells.hpp"
#include "PointOwnership.hpp"

#include <mpi.h>

#include <span>
#include <vector>

namespace rbm::motion {

class MeshPart {
public:
    MeshPart(MPI_Comm communicator, const LocalCells& part);

    MPI_Comm communicator() const { return communicator_; }
    int rank() const { return rank_; }

    Label ownedNodeCount() const { return ownedNodeCount_; }
    Label nodeCount() const { return static_cast<Label>(nodePoints_.size()); }
    Label ghostNodeCount() const { return nodeCount() - ownedNodeCount_; }
    Label globalNodeCount() const { return globalNodeCount_; }
    Label firstOwnedRow() const { return firstOwnedRow_; }
    bool owns(Label node) const { return node < ownedNodeCount_; }

    const std::vector<Vector3>& nodePoints() const { return nodePoints_; }
    const std::vector<Label>& nodeGlobalIds() const { return nodeGlobalIds_; }
    const std::vector<Label>& nodeRows() const { return nodeRows_; }
    const std::vector<int>& nodeOwnerRanks() const { return nodeOwnerRanks_; }
    // The node of every point of the LocalCells this part was built from.
    const std::vector<Label>& pointNodes() const { return pointNodes_; }

    Label cellCount() const { return cellCount_; }
    Label ownCellCount() const { return ownCellCount_; }
    // Cell c has the nodes cellNodes()[cellOffsets()[c] .. cellOffsets()[c+1]) (until releaseCells()).
    const std::vector<Label>& cellOffsets() const { return cellOffsets_; }
    const std::vector<Label>& cellNodes() const { return cellNodes_; }
    // Lets go of the cells' node lists (cellOffsets and cellNodes empty, cellCount kept) once
    // what needs them is built: the part's solver reads them only to build its neighbour graph,
    // and they would otherwise be alive in its GAMG set-up (about 36 bytes a cell).
    void releaseCells();
    std::span<const Label> nodesOf(Label cell) const
    {
        return {cellNodes_.data() + cellOffsets_[cell], static_cast<std::size_t>(cellOffsets_[cell + 1] - cellOffsets_[cell])};
    }

private:
    void numberLocalNodes(const LocalCells& part, const PointOwnership& ownership);
    void addHaloCells(const LocalCells& part, const PointOwnership& ownership);

    MPI_Comm communicator_;
    int rank_ = 0;
    Label ownedNodeCount_ = 0;
    Label globalNodeCount_ = 0;
    Label firstOwnedRow_ = 0;
    std::vector<Vector3> nodePoints_;
    std::vector<Label> nodeGlobalIds_;
    std::vector<Label> nodeRows_;
    std::vector<int> nodeOwnerRanks_;
    std::vector<Label> pointNodes_;
    Label ownCellCount_ = 0;
    Label cellCount_ = 0;
    std::vector<Label> cellOffsets_{0};
    std::vector<Label> cellNodes_;
};

} // namespace rbm::motion
