#include "PartProblem.hpp"

#include "CellNeighbourGraph.hpp"
#include "NodeExchange.hpp"

#include <memory>
#include <stdexcept>
#include <string>

namespace rbm::motion {

RbmProblem partProblem(int dimension, const MeshPart& part, std::vector<NodeConstraint> constraints,
                       EdgeWeighting weighting)
{
    if (static_cast<Label>(constraints.size()) != part.nodeCount())
        throw std::invalid_argument("part problem: " + std::to_string(constraints.size()) + " node classes for " +
                                    std::to_string(part.nodeCount()) + " nodes");
    auto graph = std::make_shared<const CellNeighbourGraph>(
        buildCellNeighbourGraph(part.nodeCount(), part.cellOffsets(), part.cellNodes()));
    ProblemPart problemPart{part.ownedNodeCount(), std::make_shared<const NodeExchange>(part)};
    return RbmProblem(dimension, part.nodePoints(), std::move(graph), std::move(constraints), weighting,
                      std::move(problemPart));
}

} // namespace rbm::motion
