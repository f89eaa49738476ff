#pragma once
// Dot products and Euclidean norms of plain vectors, summed in index order: the same result
// for any thread count (the solvers' determinism rests on it), at the price of a serial sum.

#include <span>

namespace rbm::motion {

// Σ_k a_k b_k in index order; a and b of the same size.
double dotProduct(std::span<const double> a, std::span<const double> b);

// √(a·a), with dotProduct's order.
double euclideanNorm(std::span<const double> a);

} // namespace rbm::motion
