#include "OrderedSums.hpp"

#include <cmath>

namespace rbm::motion {

double dotProduct(std::span<const double> a, std::span<const double> b)
{
    double sum = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) sum += a[k] * b[k];
    return sum;
}

double euclideanNorm(std::span<const double> a) { return std::sqrt(dotProduct(a, a)); }

} // namespace rbm::motion
