#pragma once
// The line search of rbm's Newton methods (CoupledNewtonSolver, ReducedNewtonSolver):
// backtracking from the full step λ = 1 until the energy falls by the Armijo condition
// E(λ) ≤ E(0) + 10⁻⁴ λ E'(0), each new λ the minimiser of the quadratic through E(0), E'(0)
// and E(λ), kept in [0.1 λ, 0.5 λ]. Near the minimum the energy stops resolving its own
// decrease (its rounding, ~10⁻¹³ E, exceeds 10⁻⁴ λ E'(0)); there a step that does not raise
// the energy beyond that rounding and lowers the gradient's norm is taken instead, so that
// Newton can still reach the gradient's tolerances.

#include <functional>

namespace rbm::motion {

struct LineSearchResult {
    bool accepted = false;  // false: 40 reductions of λ found no acceptable step
    double lambda = 1.0;    // the step length taken (the last tried when not accepted)
    double energy = 0.0;    // E(λ)
};

// energy = E(0), slope = E'(0) < 0 along the direction. energyAt(λ) moves the trial point to
// λ along the direction and returns E there (non-finite where E is not defined);
// gradientDecreasesAt() tells whether the gradient's norm at the last trial point is below
// the one at λ = 0 (only asked in the rounding band above).
LineSearchResult backtrackingLineSearch(double energy, double slope, const std::function<double(double)>& energyAt,
                                        const std::function<bool()>& gradientDecreasesAt);

} // namespace rbm::motion
