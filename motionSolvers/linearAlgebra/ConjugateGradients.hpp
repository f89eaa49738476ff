#pragma once
// Preconditioned conjugate gradients on plain vectors, for the small inner solves of the
// reduced Newton method (an operator and a preconditioner given as callables, no PETSc
// objects). Sums in index order (OrderedSums.hpp): the same result for any thread count.

#include "OrderedSums.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace rbm::motion {

// Solves A x = b from x = 0 to ‖r‖ ≤ relativeTolerance ‖b‖: multiply(p, q) sets q = A p,
// precondition(r, z) sets z = M⁻¹ r. False on a direction of non-positive curvature, or when
// maximumIterations do not reach the tolerance. work: four vectors, resized here (kept by a
// caller that solves often, so that a solve allocates nothing).
template <typename Multiply, typename Precondition>
bool conjugateGradients(Multiply&& multiply, Precondition&& precondition, std::span<const double> b, std::span<double> x,
                        double relativeTolerance, int maximumIterations, std::array<std::vector<double>, 4>& work)
{
    const std::size_t size = b.size();
    auto& [r, z, p, q] = work;
    for (std::vector<double>* vector : {&r, &z, &p, &q}) vector->resize(size);
    std::copy(b.begin(), b.end(), r.begin());
    std::fill(x.begin(), x.end(), 0.0);
    const double target = relativeTolerance * euclideanNorm(r);
    precondition(std::span<const double>(r), std::span<double>(z));
    p = z;
    double rz = dotProduct(r, z);
    for (int iteration = 0;; ++iteration) {
        if (euclideanNorm(r) <= target) return true;
        if (iteration == maximumIterations) return false;
        multiply(std::span<const double>(p), std::span<double>(q));
        const double curvature = dotProduct(p, q);
        if (!(curvature > 0.0)) return false;
        const double alpha = rz / curvature;
        for (std::size_t k = 0; k < size; ++k) {
            x[k] += alpha * p[k];
            r[k] -= alpha * q[k];
        }
        precondition(std::span<const double>(r), std::span<double>(z));
        const double next = dotProduct(r, z);
        const double beta = next / rz;
        rz = next;
        for (std::size_t k = 0; k < size; ++k) p[k] = z[k] + beta * p[k];
    }
}

} // namespace rbm::motion
