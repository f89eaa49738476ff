#include "ConjugateGradients.hpp"

#include <gtest/gtest.h>

#include <array>
#include <span>
#include <vector>

using namespace rbm::motion;

namespace {

// A symmetric positive definite tridiagonal matrix (the 1-D Laplacian plus a diagonal shift).
constexpr std::size_t size = 6;
double entry(std::size_t i, std::size_t j)
{
    if (i == j) return 2.0 + 0.5 * static_cast<double>(i);
    return (i + 1 == j || j + 1 == i) ? -1.0 : 0.0;
}
void multiply(std::span<const double> p, std::span<double> q)
{
    for (std::size_t i = 0; i < size; ++i) {
        q[i] = 0.0;
        for (std::size_t j = 0; j < size; ++j) q[i] += entry(i, j) * p[j];
    }
}
void jacobi(std::span<const double> r, std::span<double> z)
{
    for (std::size_t i = 0; i < size; ++i) z[i] = r[i] / entry(i, i);
}

} // namespace

TEST(ConjugateGradients, MatchesTheDirectSolutionOfASmallSpdSystem)
{
    const std::vector<double> exact{1.0, -2.0, 0.5, 3.0, -1.0, 0.25};
    std::vector<double> b(size), x(size, 7.0);
    multiply(exact, b);
    std::array<std::vector<double>, 4> work;
    ASSERT_TRUE(conjugateGradients(multiply, jacobi, b, x, 1e-14, 50, work));
    for (std::size_t i = 0; i < size; ++i) EXPECT_NEAR(x[i], exact[i], 1e-12);
    // In exact arithmetic CG ends within `size` iterations: 1e-14 within a few more.
    EXPECT_TRUE(conjugateGradients(multiply, jacobi, b, x, 1e-14, static_cast<int>(size) + 3, work));
}

TEST(ConjugateGradients, FailsOnNegativeCurvatureAndOnTooFewIterations)
{
    std::vector<double> b{1.0, 0.0, 0.0, 0.0, 0.0, 1.0}, x(size);
    std::array<std::vector<double>, 4> work;
    auto negative = [](std::span<const double> p, std::span<double> q) {
        for (std::size_t i = 0; i < size; ++i) q[i] = -p[i];
    };
    auto identity = [](std::span<const double> r, std::span<double> z) { std::copy(r.begin(), r.end(), z.begin()); };
    EXPECT_FALSE(conjugateGradients(negative, identity, b, x, 1e-10, 50, work));
    EXPECT_FALSE(conjugateGradients(multiply, identity, b, x, 1e-14, 1, work));
}
