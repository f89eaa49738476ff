#include "GramSchmidt.hpp"

#include "OrderedSums.hpp"

#include <algorithm>

namespace rbm::motion {

ThinQr orthonormalise(const std::vector<std::vector<double>>& columns)
{
    double longest = 0.0;
    for (const std::vector<double>& column : columns) longest = std::max(longest, euclideanNorm(column));
    ThinQr qr;
    for (std::size_t j = 0; j < columns.size(); ++j) {
        std::vector<double> v = columns[j];
        std::vector<double> coordinates(qr.basis.size() + 1, 0.0);
        for (std::size_t i = 0; i < qr.basis.size(); ++i) {
            coordinates[i] = dotProduct(qr.basis[i], v);
            for (std::size_t k = 0; k < v.size(); ++k) v[k] -= coordinates[i] * qr.basis[i][k];
        }
        const double remaining = euclideanNorm(v);
        if (!(remaining > 1e-6 * longest)) continue;
        coordinates.back() = remaining;
        for (double& value : v) value /= remaining;
        qr.basis.push_back(std::move(v));
        qr.r.push_back(std::move(coordinates));
        qr.kept.push_back(j);
    }
    return qr;
}

} // namespace rbm::motion
