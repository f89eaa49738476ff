#pragma once
// The measure of the reduced Newton method's displacement test: the largest displacement of a
// node relative to its shortest edge. Mesh motion needs positions to a small fraction of the
// local cell, not the rounding level of the 1/|d|²-weighted gradient.

#include "RbmProblem.hpp"

#include <span>
#include <vector>

namespace rbm::motion {

class RelativeDisplacement {
public:
    // enabled false (no displacement test): largest() must not be called.
    RelativeDisplacement(const RbmProblem& problem, bool enabled);

    // max over unknown nodes of |v_node| / (the node's shortest edge), v compact.
    double largest(std::span<const double> v) const;

private:
    const RbmProblem& problem_;
    std::vector<double> inverseShortestEdge_;  // per unknown node
};

} // namespace rbm::motion
