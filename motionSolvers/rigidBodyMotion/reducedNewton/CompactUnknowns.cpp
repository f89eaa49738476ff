#include "CompactUnknowns.hpp"

namespace rbm::motion {

CompactUnknowns::CompactUnknowns(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement)
    : problem_(problem), size_(static_cast<std::size_t>(problem.unknownNodeCount()) * problem.dimension())
{
    if (!problem.hasSlidingNodes()) return;
    offset_.resize(size_);
    problem.slidingOffset(prescribedDisplacement, offset_, problem.dimension());
}

std::vector<double> CompactUnknowns::slidingOffset() const
{
    return offset_.empty() ? std::vector<double>(size_, 0.0) : offset_;
}

std::vector<double> CompactUnknowns::compact(std::span<const Vector3> displacement) const
{
    const int dim = problem_.dimension();
    const std::vector<int>& nodes = problem_.unknownNodes();
    std::vector<double> values(size_);
    for (int a = 0; a < problem_.unknownNodeCount(); ++a)
        for (int q = 0; q < dim; ++q) values[static_cast<std::size_t>(a) * dim + q] = displacement[nodes[a]][q];
    return values;
}

void CompactUnknowns::set(std::vector<Vector3>& target, std::span<const double> values) const
{
    const int dim = problem_.dimension();
    const std::vector<int>& nodes = problem_.unknownNodes();
    std::vector<double> tangential(size_);
    for (std::size_t k = 0; k < size_; ++k) tangential[k] = values[k] - offsetAt(k);
    problem_.projectSliding(tangential, dim);
    for (int a = 0; a < problem_.unknownNodeCount(); ++a) {
        Vector3 value{};
        for (int q = 0; q < dim; ++q)
            value[q] = offsetAt(static_cast<std::size_t>(a) * dim + q) + tangential[static_cast<std::size_t>(a) * dim + q];
        target[nodes[a]] = value;
    }
    problem_.updateGhostNodes(target);  // a part: the ghosts' values are their owners'
}

void CompactUnknowns::moveAlong(const std::vector<Vector3>& from, std::span<const double> direction, double lambda,
                                std::vector<Vector3>& trial) const
{
    const int dim = problem_.dimension();
    const std::vector<int>& nodes = problem_.unknownNodes();
    trial = from;
    for (int a = 0; a < problem_.unknownNodeCount(); ++a) {
        Vector3& value = trial[nodes[a]];
        for (int q = 0; q < dim; ++q) value[q] += lambda * direction[static_cast<std::size_t>(a) * dim + q];
        if (problem_.kind(nodes[a]) == NodeKind::sliding) {
            Vector3 c{};
            for (int q = 0; q < dim; ++q) c[q] = offsetAt(static_cast<std::size_t>(a) * dim + q);
            value -= problem_.slidingNormalPart(nodes[a], value - c);
        }
    }
    problem_.updateGhostNodes(trial);
}

} // namespace rbm::motion
