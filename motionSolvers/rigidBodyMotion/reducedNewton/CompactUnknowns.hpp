#pragma once
// The unknowns of one reduced Newton solve as compact vectors (dimension() entries per unknown
// node, in unknownNodes() order) and back. A sliding node's displacement is c n + (its part in
// the plane): c n, the sliding offset, is fixed by the solve's prescribed displacements, so
// moving along a compact direction keeps every sliding node exactly on its plane.

#include "RbmProblem.hpp"

#include <span>
#include <vector>

namespace rbm::motion {

class CompactUnknowns {
public:
    CompactUnknowns(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement);

    std::size_t size() const { return size_; }
    // The sliding offsets c n (compact; zero on free nodes): a copy, for a start's arithmetic.
    std::vector<double> slidingOffset() const;
    // The unknown nodes' displacements of a node array.
    std::vector<double> compact(std::span<const Vector3> displacement) const;
    // target's unknown nodes ← c n + P (values − c n): onto the sliding planes.
    void set(std::vector<Vector3>& target, std::span<const double> values) const;
    // trial ← from + λ direction, sliding nodes put back onto their planes exactly.
    void moveAlong(const std::vector<Vector3>& from, std::span<const double> direction, double lambda,
                   std::vector<Vector3>& trial) const;

private:
    double offsetAt(std::size_t k) const { return offset_.empty() ? 0.0 : offset_[k]; }

    const RbmProblem& problem_;
    std::size_t size_;
    // Empty where the problem has no sliding node (every offset zero): 24 bytes a node less
    // through the solve.
    std::vector<double> offset_;
};

} // namespace rbm::motion
