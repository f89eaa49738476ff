#include "RelativeDisplacement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rbm::motion {

RelativeDisplacement::RelativeDisplacement(const RbmProblem& problem, bool enabled) : problem_(problem)
{
    const int dim = problem.dimension();
    const CellNeighbourGraph& graph = problem.graph();
    if (enabled) inverseShortestEdge_.assign(problem.unknownNodeCount(), 0.0);
    for (int a = 0; a < static_cast<int>(inverseShortestEdge_.size()); ++a) {
        const int i = problem.unknownNodes()[a];
        double shortest = std::numeric_limits<double>::infinity();
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            Vector3 d = problem.referencePoints()[graph.neighbours[e]] - problem.referencePoints()[i];
            if (dim == 2) d.z = 0.0;
            if (norm(d) > 0.0) shortest = std::min(shortest, norm(d));
        }
        inverseShortestEdge_[a] = std::isfinite(shortest) ? 1.0 / shortest : 0.0;
    }
}

double RelativeDisplacement::largest(std::span<const double> v) const
{
    const int dim = problem_.dimension();
    double largest = 0.0;
    for (int a = 0; a < problem_.ownedUnknownCount(); ++a) {  // a part: the largest over the ranks
        double squared = 0.0;
        for (int q = 0; q < dim; ++q) squared += v[static_cast<std::size_t>(a) * dim + q] * v[static_cast<std::size_t>(a) * dim + q];
        largest = std::max(largest, std::sqrt(squared) * inverseShortestEdge_[a]);
    }
    return problem_.maximumOverRanks(largest);
}

} // namespace rbm::motion
