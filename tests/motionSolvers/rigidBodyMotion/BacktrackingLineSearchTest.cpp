#include "BacktrackingLineSearch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace rbm::motion;

namespace {
// E(λ) = (λ − minimiser)², E'(0) = −2 minimiser.
struct Quadratic {
    double minimiser;
    double operator()(double lambda) const { return (lambda - minimiser) * (lambda - minimiser); }
};
} // namespace

TEST(BacktrackingLineSearch, TakesTheFullStepWhenItDecreasesEnough)
{
    const Quadratic energy{0.8};
    int gradientQuestions = 0;
    const LineSearchResult result = backtrackingLineSearch(energy(0.0), -1.6, energy, [&] { return ++gradientQuestions, false; });
    EXPECT_TRUE(result.accepted);
    EXPECT_EQ(result.lambda, 1.0);
    EXPECT_EQ(result.energy, energy(1.0));
    EXPECT_EQ(gradientQuestions, 0);
}

TEST(BacktrackingLineSearch, OnAOneDimensionalQuadraticTheSecondTrialIsItsMinimiser)
{
    // The full step overshoots (E(1) > E(0)); the quadratic through E(0), E'(0) and E(1) is E itself.
    const Quadratic energy{0.3};
    int trials = 0;
    const LineSearchResult result = backtrackingLineSearch(
        energy(0.0), -0.6, [&](double lambda) { return ++trials, energy(lambda); }, [] { return false; });
    EXPECT_TRUE(result.accepted);
    EXPECT_NEAR(result.lambda, 0.3, 1e-15);
    EXPECT_NEAR(result.energy, 0.0, 1e-30);
    EXPECT_EQ(trials, 2);
}

TEST(BacktrackingLineSearch, ReductionsStayWithinATenthAndAHalf)
{
    // Far beyond the minimiser the quadratic's step would be tiny: λ shrinks by 10 at most.
    const Quadratic energy{1e-3};
    const LineSearchResult result = backtrackingLineSearch(energy(0.0), -2e-3, energy, [] { return false; });
    EXPECT_TRUE(result.accepted);
    EXPECT_NEAR(result.lambda, 1e-3, 1e-15);  // 1 → 0.1 → 0.01 → 0.001: each a tenth
}

TEST(BacktrackingLineSearch, WithinTheEnergysRoundingTheGradientDecides)
{
    // E flat to rounding: no Armijo decrease is visible, the step is taken where the gradient falls.
    const double energy = 1.0;
    auto flat = [&](double) { return energy * (1.0 + 1e-14); };
    const LineSearchResult taken = backtrackingLineSearch(energy, -1e-20, flat, [] { return true; });
    EXPECT_TRUE(taken.accepted);
    EXPECT_EQ(taken.lambda, 1.0);
    const LineSearchResult refused = backtrackingLineSearch(energy, -1e-20, flat, [] { return false; });
    EXPECT_FALSE(refused.accepted);
}

TEST(BacktrackingLineSearch, FailsWhereTheEnergyIsNotDefined)
{
    int trials = 0;
    const LineSearchResult result = backtrackingLineSearch(
        1.0, -1.0, [&](double) { return ++trials, std::numeric_limits<double>::quiet_NaN(); }, [] { return true; });
    EXPECT_FALSE(result.accepted);
    EXPECT_EQ(trials, 40);
    EXPECT_EQ(result.lambda, std::ldexp(1.0, -40));
}
