#pragma once
// The RBM problem of one rank's part of a decomposed mesh (docs/parallel.md, "Distributed
// data"): the MeshPart's nodes (owned first, then ghosts) and its cells (own, then halo), whose
// cell-neighbour graph is complete around every owned node, the class of every node (ghosts
// included: a ghost's class is its owner's), and the part's node exchange.

#include "MeshPart.hpp"
#include "RbmProblem.hpp"

#include <vector>

namespace rbm::motion {

// Collective (it sets up the part's exchange). Throws std::invalid_argument as RbmProblem does
// and for constraints that are not one per node of the part.
RbmProblem partProblem(int dimension, const MeshPart& part, std::vector<NodeConstraint> constraints,
                       EdgeWeighting weighting = EdgeWeighting::inverseDistanceSquared);

} // namespace rbm::motion
