// Tests of ThreeVectorMultigrid (motionSolvers/linearAlgebra): one V-cycle of a multigrid hierarchy
// (rbm's smoothed aggregation, SmoothedAggregation.hpp, or PCGAMG's)
// applied to three interleaved right-hand sides, on the 27-point Laplacian of a hexahedral grid
// with 1/|d|² weights (the matrix reducedNewton's 3D preconditioner inverts). What a V-cycle must
// be as the preconditioner of CG: symmetric, positive definite, the three components
// independent of each other and treated alike, and a good approximation of K⁻¹ (few CG
// iterations, independent of the grid size).

#include "PetscTestEnvironment.hpp"
#include "TestCases.hpp"
#include "ThreadCount.hpp"
#include "ThreeVectorMultigrid.hpp"
#include "VectorInstructions.hpp"

#include <gtest/gtest.h>

#include <petscsys.h>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace rbm::test::multigridCases;

namespace rbm::motion {

namespace {

double dot(const std::vector<double>& a, const std::vector<double>& b)
{
    double sum = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) sum += a[k] * b[k];
    return sum;
}

std::vector<double> randomVector(std::size_t size, unsigned seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    std::vector<double> v(size);
    for (double& x : v) x = value(random);
    return v;
}

// Preconditioned CG on all three components together (one dot product over all of them): the
// iterations to reduce ‖b − K x‖ by 1e-8, the residual checked with K itself.
int cgIterations(const Laplacian& K, ThreeVectorMultigrid* cycle, const std::vector<double>& b)
{
    std::vector<double> x(b.size(), 0.0), r = b, z(b.size()), p;
    if (cycle) cycle->apply(r, z);
    else z = r;
    p = z;
    double rz = dot(r, z);
    const double target = 1e-8 * std::sqrt(dot(b, b));
    for (int iteration = 1; iteration <= 2000; ++iteration) {
        const std::vector<double> q = K.times(p);
        const double alpha = rz / dot(p, q);
        for (std::size_t k = 0; k < x.size(); ++k) {
            x[k] += alpha * p[k];
            r[k] -= alpha * q[k];
        }
        std::vector<double> residual = K.times(x);
        for (std::size_t k = 0; k < x.size(); ++k) residual[k] = b[k] - residual[k];
        if (std::sqrt(dot(residual, residual)) <= target) return iteration;
        if (cycle) cycle->apply(r, z);
        else z = r;
        const double next = dot(r, z);
        for (std::size_t k = 0; k < x.size(); ++k) p[k] = z[k] + (next / rz) * p[k];
        rz = next;
    }
    return 2001;
}

TEST(ThreeVectorMultigrid, IsASymmetricPositiveDefiniteCycleWithIndependentComponents)
{
    const Laplacian K = hexLaplacian(14);  // 2 197 rows, 27-point stencil
    auto cycle = ThreeVectorMultigrid::build(K.offsets, K.columns, K.values, "cycletest");
    ASSERT_TRUE(cycle);
    ASSERT_GE(cycle->levelCount(), 2);
    EXPECT_EQ(cycle->rows(0), K.rows);
    const std::size_t size = 3 * static_cast<std::size_t>(K.rows);
    const std::vector<double> u = randomVector(size, 1), v = randomVector(size, 2);
    std::vector<double> mu(size), mv(size);
    cycle->apply(u, mu);
    cycle->apply(v, mv);
    // Symmetric: u·M⁻¹v = v·M⁻¹u (pre- and post-smoothing alike, restriction = Pᵀ).
    EXPECT_NEAR(dot(u, mv), dot(v, mu), 1e-12 * std::sqrt(dot(u, mu) * dot(v, mv)));
    // Positive definite, and close to K⁻¹: u·M⁻¹u / u·K⁻¹u is within [0.5, 2] for a good cycle;
    // here checked through the Rayleigh quotient of M⁻¹K on M⁻¹u: (M⁻¹u)ᵀK(M⁻¹u) / (M⁻¹u)ᵀu.
    EXPECT_GT(dot(u, mu), 0.0);
    const double rayleigh = dot(mu, K.times(mu)) / dot(mu, u);
    EXPECT_GT(rayleigh, 0.3);
    EXPECT_LT(rayleigh, 1.5);

    // Components independent and alike: the cycle of (a, b, c) is the cycles of (a, 0, 0), ...,
    // component by component, bit for bit, and a permutation of the components permutes the result.
    std::vector<double> permuted(size), permutedOut(size);
    for (int row = 0; row < K.rows; ++row)
        for (int c = 0; c < 3; ++c) permuted[3 * row + c] = u[3 * row + (c + 1) % 3];
    cycle->apply(permuted, permutedOut);
    for (int c = 0; c < 3; ++c) {
        std::vector<double> single(size, 0.0), singleOut(size);
        for (int row = 0; row < K.rows; ++row) single[3 * row + c] = u[3 * row + c];
        cycle->apply(single, singleOut);
        for (int row = 0; row < K.rows; ++row) {
            ASSERT_EQ(singleOut[3 * row + c], mu[3 * row + c]) << row << ' ' << c;
            ASSERT_EQ(singleOut[3 * row + (c + 1) % 3], 0.0);
            ASSERT_EQ(permutedOut[3 * row + c], mu[3 * row + (c + 1) % 3]);
        }
    }
}

TEST(ThreeVectorMultigrid, PreconditionsCGIndependentlyOfTheGridSize)
{
    // rbm's smoothed aggregation (the default) and PCGAMG's hierarchy (-…_cycle_hierarchy gamg).
    ASSERT_EQ(PetscOptionsSetValue(nullptr, "-rbm_cycletestgamg_cycle_hierarchy", "gamg"), 0);
    for (const char* name : {"cycletest", "cycletestgamg"}) {
        std::vector<int> iterations;
        for (int n : {10, 20, 30}) {  // 729, 6 859 and 24 389 rows
            const Laplacian K = hexLaplacian(n);
            auto cycle = ThreeVectorMultigrid::build(K.offsets, K.columns, K.values, name);
            ASSERT_TRUE(cycle);
            const std::vector<double> b = randomVector(3 * static_cast<std::size_t>(K.rows), 3);
            const int preconditioned = cgIterations(K, cycle.get(), b);
            const int plain = cgIterations(K, nullptr, b);
            EXPECT_LE(preconditioned, 20) << name << ' ' << n;
            EXPECT_GT(plain, 2 * preconditioned) << name << ' ' << n;
            iterations.push_back(preconditioned);
        }
        // Grid-independent, unlike plain CG (∝ n).
        EXPECT_LE(iterations[2], iterations[0] + 3) << name;
    }
    ASSERT_EQ(PetscOptionsClearValue(nullptr, "-rbm_cycletestgamg_cycle_hierarchy"), 0);
}

TEST(ThreeVectorMultigrid, IsTheSameForOneTwoAndThreeThreads)
{
    const Laplacian K = hexLaplacian(40);  // 59 319 rows: above the threading threshold
    ASSERT_TRUE(worthThreading(K.columns.size()));
    const std::vector<double> r = randomVector(3 * static_cast<std::size_t>(K.rows), 4);
    const int before = threadCount();
    std::vector<std::vector<double>> results;
    for (int threads : {1, 2, 3}) {
        setThreadCount(threads);
        auto cycle = ThreeVectorMultigrid::build(K.offsets, K.columns, K.values, "cycletest");
        ASSERT_TRUE(cycle);
        std::vector<double> z(r.size());
        cycle->apply(r, z);
        results.push_back(z);
    }
    setThreadCount(before);
    EXPECT_EQ(results[1], results[0]);
    EXPECT_EQ(results[2], results[0]);
}

TEST(ThreeVectorMultigrid, IsTheSameWithAndWithoutAvx)
{
    // The matrix products' AVX variant (one register per row's three values) against the
    // baseline scalar one: the same cycle bit for bit, on every level including the
    // single-precision finest one.
    const Laplacian K = hexLaplacian(12);
    const std::vector<double> r = randomVector(3 * static_cast<std::size_t>(K.rows), 6);
    std::vector<std::vector<double>> results;
    for (bool avx : {true, false}) {
        avxKernelsAllowed() = avx;
        auto cycle = ThreeVectorMultigrid::build(K.offsets, K.columns, K.values, "cycletest");
        ASSERT_TRUE(cycle);
        ASSERT_GT(cycle->levelCount(), 1);
        std::vector<double> z(r.size());
        cycle->apply(r, z);
        results.push_back(z);
    }
    avxKernelsAllowed() = true;
    EXPECT_EQ(results[1], results[0]);
    EXPECT_GT(*std::max_element(results[0].begin(), results[0].end()), 0.0);
}

TEST(ThreeVectorMultigrid, DeclinesAPreconditionerThatIsNotMultigrid)
{
    const Laplacian K = hexLaplacian(6);
    ASSERT_EQ(PetscOptionsSetValue(nullptr, "-rbm_cycletestjacobi_pc_type", "jacobi"), 0);
    EXPECT_FALSE(ThreeVectorMultigrid::build(K.offsets, K.columns, K.values, "cycletestjacobi"));
    ASSERT_EQ(PetscOptionsClearValue(nullptr, "-rbm_cycletestjacobi_pc_type"), 0);
}

} // namespace
} // namespace rbm::motion
