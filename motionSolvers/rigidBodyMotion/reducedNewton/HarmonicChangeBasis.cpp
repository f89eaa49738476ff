#include "HarmonicChangeBasis.hpp"

#include "OrderedSums.hpp"

#include <cmath>

namespace rbm::motion {

bool HarmonicChangeBasis::correctionFromBasis(std::span<const Vector3> prescribed, std::span<const Vector3> base,
                                              std::vector<double>& boundaryChange, std::vector<double>& correction)
{
    boundaryChange.clear();
    // Only where K⁻¹ is one fixed linear map (a factorisation, or the 3D cycle without sliding
    // nodes, not an inner iteration) and the boundary enters b linearly (no sliding offsets:
    // sliding planes through the nodes' reference positions, as both front doors give them),
    // and where the kept extensions stay small against the problem (12 of them).
    const int dim = problem_.dimension();
    const std::size_t size = static_cast<std::size_t>(problem_.unknownNodeCount()) * dim;
    const bool linear = preconditioner_.isFixedLinearMap();
    if (!enabled_ || !linear || size > maximumHarmonicBasisEntries) return false;
    if (problem_.hasSlidingNodes()) {
        std::vector<double> offset(size);
        for (const std::span<const Vector3> values : {prescribed, base}) {
            problem_.slidingOffset(values, offset, dim);
            for (double value : offset)
                if (value != 0.0) return false;
        }
    }
    if (prescribedNodes_.empty())
        for (int node = 0; node < problem_.nodeCount(); ++node)
            if (!problem_.isUnknown(node)) prescribedNodes_.push_back(node);
    boundaryChange.resize(prescribedNodes_.size() * dim);
    double scale = 0.0;  // |new| + |base| on the prescribed nodes
    {
        double newSquared = 0.0, baseSquared = 0.0;
        for (std::size_t p = 0; p < prescribedNodes_.size(); ++p)
            for (int q = 0; q < dim; ++q) {
                const double value = prescribed[prescribedNodes_[p]][q], guess = base[prescribedNodes_[p]][q];
                boundaryChange[p * dim + q] = value - guess;
                newSquared += value * value;
                baseSquared += guess * guess;
            }
        scale = std::sqrt(newSquared) + std::sqrt(baseSquared);
    }
    // A change at the rounding level of the displacements (the predictor at a reversal of the
    // motion reproduces an earlier boundary): no correction, and no noise kept as a direction.
    const double changeNorm = euclideanNorm(boundaryChange);
    if (changeNorm <= roundingChangeShare * scale) {
        correction.assign(size, 0.0);
        ++correctionsFromBasis_;
        return true;
    }
    // The change's coordinates in the orthonormal basis of the changes met before, and what is
    // left outside it (two Gram–Schmidt passes: the part left can be small against the change).
    std::vector<double> left = boundaryChange;
    std::vector<double> coordinates(boundaryBasis_.size(), 0.0);
    for (int pass = 0; pass < 2; ++pass)
        for (std::size_t i = 0; i < boundaryBasis_.size(); ++i) {
            const double c = dotProduct(boundaryBasis_[i], left);
            coordinates[i] += c;
            for (std::size_t k = 0; k < left.size(); ++k) left[k] -= c * boundaryBasis_[i][k];
        }
    if (euclideanNorm(left) > harmonicBasisTolerance * changeNorm) return false;
    correction.assign(size, 0.0);
    for (std::size_t i = 0; i < boundaryBasis_.size(); ++i)
        for (std::size_t k = 0; k < size; ++k) correction[k] += coordinates[i] * harmonicBasis_[i][k];
    ++correctionsFromBasis_;
    return true;
}

void HarmonicChangeBasis::remember(std::vector<double> boundaryChange, std::span<const double> correction)
{
    if (boundaryChange.empty() || boundaryBasis_.size() >= maximumHarmonicBasisSize) return;
    // The part of the change outside the basis, normed, and K⁻¹ B of it: the same combination
    // of `correction` (K⁻¹ B of the whole change) and the kept extensions.
    std::vector<double> extension(correction.begin(), correction.end());
    for (int pass = 0; pass < 2; ++pass)
        for (std::size_t i = 0; i < boundaryBasis_.size(); ++i) {
            const double c = dotProduct(boundaryBasis_[i], boundaryChange);
            for (std::size_t k = 0; k < boundaryChange.size(); ++k) boundaryChange[k] -= c * boundaryBasis_[i][k];
            for (std::size_t k = 0; k < extension.size(); ++k) extension[k] -= c * harmonicBasis_[i][k];
        }
    const double leftNorm = euclideanNorm(boundaryChange);
    if (!(leftNorm > 0.0)) return;
    for (double& value : boundaryChange) value /= leftNorm;
    for (double& value : extension) value /= leftNorm;
    boundaryBasis_.push_back(std::move(boundaryChange));
    harmonicBasis_.push_back(std::move(extension));
}

} // namespace rbm::motion
