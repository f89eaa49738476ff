#include "BacktrackingLineSearch.hpp"

#include <algorithm>
#include <cmath>

namespace rbm::motion {

LineSearchResult backtrackingLineSearch(double energy, double slope, const std::function<double(double)>& energyAt,
                                        const std::function<bool()>& gradientDecreasesAt)
{
    constexpr int maximumAttempts = 40;
    constexpr double sufficientDecrease = 1e-4;  // Armijo's constant
    const double roundoff = 1e-13 * std::abs(energy) + 1e-300;
    LineSearchResult result;
    result.energy = energy;
    for (int attempt = 0; attempt < maximumAttempts; ++attempt) {
        const double lambda = result.lambda;
        const double trialEnergy = energyAt(lambda);
        result.energy = trialEnergy;
        if (std::isfinite(trialEnergy) && trialEnergy <= energy + sufficientDecrease * lambda * slope) {
            result.accepted = true;
        } else if (std::isfinite(trialEnergy) && trialEnergy <= energy + roundoff) {
            result.accepted = gradientDecreasesAt();
        }
        if (result.accepted) return result;
        // Minimiser of the quadratic through E(0), E'(0) and E(λ), kept in [0.1 λ, 0.5 λ].
        double next = 0.5 * lambda;
        if (std::isfinite(trialEnergy)) {
            const double curvature = trialEnergy - energy - slope * lambda;
            if (curvature > 0.0) next = -slope * lambda * lambda / (2.0 * curvature);
        }
        result.lambda = std::clamp(next, 0.1 * lambda, 0.5 * lambda);
    }
    return result;
}

} // namespace rbm::motion
