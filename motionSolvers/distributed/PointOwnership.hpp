#pragma once
// Which rank owns each point of a decomposed mesh, and the point's row in the distributed
// vectors (docs/parallel.md, "Distributed data").
//
// A point on a processor boundary is held by several ranks; it is owned by the lowest of
// them, every other point by its only holder. Rows are numbered by owner: rank 0's owned
// points first, each rank's in its local point order, so a rank's rows are one contiguous
// range (PETSc's layout).
//
// The holders of a shared point need not be face neighbours (four ranks around an edge,
// eight around a corner), so the owner is not found by talking to neighbours: a rendezvous
// does it. Global label g has a directory rank, g × ranks / (global point count); every holder
// tells the directory it holds g, the directory answers the lowest holder, and, once the
// owners have numbered their points, passes the owner's row on to the other holders. Two
// all-to-all exchanges of the processor-boundary points only.

#include "LocalCells.hpp"

#include <mpi.h>

#include <vector>

namespace rbm::motion {

struct PointOwnership {
    std::vector<int> ownerRanks;  // per local point
    std::vector<Label> rows;      // per local point: its row in the distributed numbering
    Label ownedCount = 0;         // points this rank owns
    Label firstOwnedRow = 0;      // the row of this rank's first owned point
    Label globalPointCount = 0;   // all ranks' owned points: the whole mesh's points

    bool owned(Label point, int rank) const { return ownerRanks[point] == rank; }
};

// Collective on `communicator`. Every holder of a shared point must flag it
// (LocalCells::onProcessorBoundary). Throws std::invalid_argument for a negative global label
// or arrays of the wrong size.
PointOwnership findPointOwnership(MPI_Comm communicator, const LocalCells& part);

} // namespace rbm::motion
