#pragma once
// Modified Gram–Schmidt on a few long vectors (sums in index order: the same result for any
// thread count): a thin QR factorisation that leaves nearly dependent columns out.

#include <cstddef>
#include <vector>

namespace rbm::motion {

// An orthonormal basis of the columns' span, each kept column's coordinates in it (R's
// columns, r[i][i] the diagonal) and the kept columns' indices.
struct ThinQr {
    std::vector<std::vector<double>> basis, r;
    std::vector<std::size_t> kept;
};

// A column whose part outside the span of those before it is below 1e-6 of the longest column
// is left out (nearly dependent).
ThinQr orthonormalise(const std::vector<std::vector<double>>& columns);

} // namespace rbm::motion
