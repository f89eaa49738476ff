// Tests of ThreeVectorMultigrid (motionSolvers/linearAlgebra): one V-cycle of a multigrid hierarchy
// (rbm's smoothed aggregation, SmoothedAggregation.hpp, or PCGAMG's)
// applied to three interleaved right-hand sides, on the 27-point Laplacian of a hexahedral grid
// with 1/|d|² weights (the matrix reducedNewton's 3D preconditioner inverts). What a V-cycle must
// be as the preconditioner of CG: symmetric, positive definite, the three components
// independent of each other and treated alike, and a good approximation of K⁻¹ (few CG
// iterations, independent of the grid size).

#include "PetscTestEnvironment.hpp"
#include "ThreadCount.hpp"
#include "ThreeVectorMultigrid.hpp"
#include "VectorInstructions.hpp"

#include <gtest/gtest.h>

#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

static ::testing::Environment* const petscEnvironment =
    ::testing::AddGlobalTestEnvironment(new rbm::test::PetscTestEnvironment);

namespace rbm::motion {
namespace {

// K on the (n − 1)³ interior nodes of an n³-cell unit cube: neighbours = the 26 nodes sharing a
// cell, weight 1/|d|², K_ii = Σ_j w (boundary neighbours fixed), K_ij = −w. Rows sorted.
struct Laplacian {
    int rows = 0;
    std::vector<int> offsets{0}, columns;
    std::vector<double> values;

    std::vector<double> times(const std::vector<double>& x) const  // 3 interleaved vectors
    {
        std::vector<double> y(x.size(), 0.0);
        for (int row = 0; row < rows; ++row)
            for (int k = offsets[row]; k < offsets[row + 1]; ++k)
                for (int c = 0; c < 3; ++c) y[3 * row + c] += values[k] * x[3 * columns[k] + c];
        return y;
    }
};

Laplacian hexLaplacian(int n)
{
    Laplacian K;
    const int m = n - 1;
    K.rows = m * m * m;
    const double h = 1.0 / n;
    auto index = [m](int i, int j, int k) { return (i - 1) + m * ((j - 1) + m * (k - 1)); };
    for (int k = 1; k <= m; ++k)
        for (int j = 1; j <= m; ++j)
            for (int i = 1; i <= m; ++i) {
                double diagonal = 0.0;
                std::vector<std::pair<int, double>> row;
                for (int dk = -1; dk <= 1; ++dk)
                    for (int dj = -1; dj <= 1; ++dj)
                        for (int di = -1; di <= 1; ++di) {
                            if (di == 0 && dj == 0 && dk == 0) continue;
                            const double w = 1.0 / ((di * di + dj * dj + dk * dk) * h * h);
                            diagonal += w;
                            const int a = i + di, b = j + dj, c = k + dk;
                            if (a >= 1 && a <= m && b >= 1 && b <= m && c >= 1 && c <= m) row.emplace_back(index(a, b, c), -w);
                        }
                row.emplace_back(index(i, j, k), diagonal);
                std::sort(row.begin(), row.end());
                for (const auto& [column, value] : row) {
                    K.columns.push_back(column);
                    K.values.push_back(value);
                }
                K.offsets.push_back(static_cast<int>(K.columns.size()));
            }
    return K;
}

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

TEST(SmoothedAggregation, AggregatesAreConnectedNeighbourhoodsCoveringEveryRow)
{
    const Laplacian K = hexLaplacian(13);  // 12³ rows, 27-point stencil
    int count = 0;
    const std::vector<int> aggregate = aggregateRows(K.offsets, K.columns, K.values, count);
    ASSERT_EQ(static_cast<int>(aggregate.size()), K.rows);
    std::vector<std::vector<int>> members(static_cast<std::size_t>(count));
    for (int row = 0; row < K.rows; ++row) {
        ASSERT_GE(aggregate[row], 0);
        ASSERT_LT(aggregate[row], count);
        members[aggregate[row]].push_back(row);
    }
    std::size_t largest = 0;
    for (const std::vector<int>& rows : members) {
        ASSERT_FALSE(rows.empty());
        largest = std::max(largest, rows.size());
        // Connected: a search from its first row, through neighbours in the same aggregate,
        // reaches all of it.
        std::vector<int> reached{rows.front()}, stack{rows.front()};
        while (!stack.empty()) {
            const int row = stack.back();
            stack.pop_back();
            for (int k = K.offsets[row]; k < K.offsets[row + 1]; ++k) {
                const int column = K.columns[k];
                if (aggregate[column] == aggregate[row] &&
                    std::find(reached.begin(), reached.end(), column) == reached.end()) {
                    reached.push_back(column);
                    stack.push_back(column);
                }
            }
        }
        EXPECT_EQ(reached.size(), rows.size());
    }
    // A node and its whole neighbourhood: 3 × 3 × 3 rows inside the grid; 12³ rows make about
    // 4³ aggregates, and no more than an eighth of the rows.
    EXPECT_GE(largest, 27u);
    EXPECT_LE(count, K.rows / 8);
    EXPECT_GE(count, K.rows / 64);
}

TEST(SmoothedAggregation, CoarseOperatorIsTheGalerkinProductAndInterpolatesConstants)
{
    // Independently: Pᵀ A P by dense products, against PETSc's sparse one; the smoothed
    // prolongator interpolates the constant exactly on rows whose row sum is 0 (inside the
    // grid: (I − ω D⁻¹A) 1 = 1 there), and the coarse operator is symmetric, positive on its
    // diagonal.
    const Laplacian K = hexLaplacian(8);  // 343 rows
    const std::vector<AggregationLevel> levels = buildSmoothedAggregation(K.offsets, K.columns, K.values, 10);
    ASSERT_GE(levels.size(), 1u);
    const CompressedRows& p = levels[0].interpolation;
    const CompressedRows& coarse = levels[0].coarseOperator;
    const int n = K.rows, nc = coarse.rows();
    ASSERT_EQ(p.rows(), n);
    ASSERT_LT(nc, n / 4);
    int insideRows = 0;
    std::vector<double> denseA(static_cast<std::size_t>(n) * n, 0.0), denseP(static_cast<std::size_t>(n) * nc, 0.0);
    for (int row = 0; row < n; ++row) {
        double rowSum = 0.0, diagonal = 0.0;
        for (int k = K.offsets[row]; k < K.offsets[row + 1]; ++k) {
            denseA[static_cast<std::size_t>(row) * n + K.columns[k]] = K.values[k];
            rowSum += K.values[k];
            if (K.columns[k] == row) diagonal = K.values[k];
        }
        double interpolatedOne = 0.0;
        for (int k = p.offsets[row]; k < p.offsets[row + 1]; ++k) {
            denseP[static_cast<std::size_t>(row) * nc + p.columns[k]] = p.values[k];
            interpolatedOne += p.values[k];
        }
        if (std::abs(rowSum) < 1e-9 * diagonal) {
            EXPECT_NEAR(interpolatedOne, 1.0, 1e-12) << row;
            ++insideRows;
        }
    }
    EXPECT_EQ(insideRows, 5 * 5 * 5);  // the rows none of whose neighbours is on the boundary
    double largest = 0.0;
    std::vector<double> expected(static_cast<std::size_t>(nc) * nc, 0.0);
    for (int a = 0; a < nc; ++a)
        for (int b = 0; b < nc; ++b) {
            double sum = 0.0;
            for (int i = 0; i < n; ++i) {
                const double pia = denseP[static_cast<std::size_t>(i) * nc + a];
                if (pia == 0.0) continue;
                for (int j = 0; j < n; ++j) sum += pia * denseA[static_cast<std::size_t>(i) * n + j] * denseP[static_cast<std::size_t>(j) * nc + b];
            }
            expected[static_cast<std::size_t>(a) * nc + b] = sum;
            largest = std::max(largest, std::abs(sum));
        }
    std::vector<double> actual(static_cast<std::size_t>(nc) * nc, 0.0);
    for (int row = 0; row < nc; ++row)
        for (int k = coarse.offsets[row]; k < coarse.offsets[row + 1]; ++k)
            actual[static_cast<std::size_t>(row) * nc + coarse.columns[k]] = coarse.values[k];
    for (int a = 0; a < nc; ++a) {
        EXPECT_GT(actual[static_cast<std::size_t>(a) * nc + a], 0.0);
        for (int b = 0; b < nc; ++b) {
            EXPECT_NEAR(actual[static_cast<std::size_t>(a) * nc + b], expected[static_cast<std::size_t>(a) * nc + b], 1e-12 * largest);
            EXPECT_NEAR(actual[static_cast<std::size_t>(a) * nc + b], actual[static_cast<std::size_t>(b) * nc + a], 1e-12 * largest);
        }
    }
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
