// SparseCholesky: rbm's back-substitution on CHOLMOD's factor (motionSolvers/linearAlgebra).
#include "SparseCholesky.hpp"
#include "ThreadCount.hpp"
#include "VectorInstructions.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <vector>

namespace rbm::motion {
namespace {

// A weighted graph Laplacian of an n×n grid with its 8 diagonal neighbours, plus a positive
// diagonal on the first row (a "prescribed boundary"): symmetric positive definite, with
// weights spread over six orders of magnitude as on a boundary-layer mesh.
struct Csr {
    int n = 0;
    std::vector<int> rowOffsets, columns;
    std::vector<double> values;
};

Csr gridLaplacian(int side)
{
    std::mt19937 random(4);
    std::uniform_real_distribution<double> exponent(0.0, 6.0);
    const int n = side * side;
    std::vector<std::vector<std::pair<int, double>>> rows(n);
    std::vector<double> diagonal(n, 0.0);
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j)
            for (int di = 0; di <= 1; ++di)
                for (int dj = -1; dj <= 1; ++dj) {
                    if (di == 0 && dj <= 0) continue;
                    const int i2 = i + di, j2 = j + dj;
                    if (i2 >= side || j2 < 0 || j2 >= side) continue;
                    const int a = i * side + j, b = i2 * side + j2;
                    const double w = std::pow(10.0, exponent(random));
                    rows[a].emplace_back(b, -w);
                    rows[b].emplace_back(a, -w);
                    diagonal[a] += w;
                    diagonal[b] += w;
                }
    for (int j = 0; j < side; ++j) diagonal[j] += 1.0;
    Csr matrix;
    matrix.n = n;
    matrix.rowOffsets.push_back(0);
    for (int a = 0; a < n; ++a) {
        rows[a].emplace_back(a, diagonal[a]);
        for (const auto& [column, value] : rows[a]) {
            matrix.columns.push_back(column);
            matrix.values.push_back(value);
        }
        matrix.rowOffsets.push_back(static_cast<int>(matrix.columns.size()));
    }
    return matrix;
}

std::vector<double> multiply(const Csr& a, const std::vector<double>& x, int count)
{
    std::vector<double> y(x.size(), 0.0);
    for (int row = 0; row < a.n; ++row)
        for (int p = a.rowOffsets[row]; p < a.rowOffsets[row + 1]; ++p)
            for (int c = 0; c < count; ++c) y[row * count + c] += a.values[p] * x[a.columns[p] * count + c];
    return y;
}

TEST(SparseCholesky, SolvesOneToThreeInterleavedRightHandSides)
{
    if (!SparseCholesky::available()) GTEST_SKIP() << "this build has no CHOLMOD";
  // 30×30 (CHOLMOD would factorise it simplicially unless told otherwise) and 150×150: both
  // with supernodes of one to hundreds of columns.
  for (int side : {30, 150}) {
    const Csr a = gridLaplacian(side);
    const SparseCholesky factor(a.n, a.rowOffsets, a.columns, a.values);
    EXPECT_EQ(factor.size(), a.n);
    EXPECT_EQ(factor.precision(), FactorPrecision::double_);
    EXPECT_GE(factor.factorNonzeros(), static_cast<std::size_t>(a.n));
    EXPECT_GT(factor.supernodeCount(), 1);
    EXPECT_LT(factor.supernodeCount(), a.n);  // some supernodes of several columns
    std::mt19937 random(7);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    std::vector<std::vector<double>> single(3, std::vector<double>(a.n));
    for (int count = 1; count <= 3; ++count) {
        // A known solution x: b = A x, then the solve must give x back.
        std::vector<double> expected(static_cast<std::size_t>(a.n) * count);
        for (double& v : expected) v = value(random);
        const std::vector<double> b = multiply(a, expected, count);
        std::vector<double> x(b.size());
        factor.solve(b, x, count);
        double largest = 0.0;
        for (std::size_t k = 0; k < x.size(); ++k) largest = std::max(largest, std::abs(x[k] - expected[k]));
        EXPECT_LT(largest, 1e-8) << count << " right-hand sides";
        // Interleaving changes nothing: each component equals its own one-column solve.
        for (int c = 0; c < count; ++c) {
            std::vector<double> column(a.n), solution(a.n);
            for (int k = 0; k < a.n; ++k) column[k] = b[k * count + c];
            factor.solve(column, solution, 1);
            for (int k = 0; k < a.n; ++k) ASSERT_EQ(solution[k], x[k * count + c]) << "component " << c;
        }
    }
    // In place.
    std::vector<double> inPlace(a.n, 1.0);
    std::vector<double> copy = inPlace, separate(a.n);
    factor.solve(copy, separate, 1);
    factor.solve(inPlace, inPlace, 1);
    EXPECT_EQ(inPlace, separate);
  }
}

TEST(SparseCholesky, SinglePrecisionFactorIsAPreconditionerCloseToTheInverse)
{
    if (!SparseCholesky::available()) GTEST_SKIP() << "this build has no CHOLMOD";
    // Entries of L rounded to float: the solve is exact for A + E with |E| ~ 2⁻²⁴ |L||Lᵀ|.
    // On this grid (weights over six orders, one weakly held row: κ(A) far above 1e8) that is
    // an error of a few per cent, concentrated in A's smoothest modes; yet M⁻¹A is close
    // enough to I that one step of iterative refinement x ← x + M⁻¹(b − A x) gains four
    // digits or more: a preconditioner as good as the exact inverse for CG.
    const Csr a = gridLaplacian(100);
    const SparseCholesky exact(a.n, a.rowOffsets, a.columns, a.values);
    const SparseCholesky single(a.n, a.rowOffsets, a.columns, a.values, FactorPrecision::single);
    EXPECT_EQ(single.precision(), FactorPrecision::single);
    EXPECT_EQ(single.factorNonzeros(), exact.factorNonzeros());
    std::mt19937 random(11);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    for (int count = 1; count <= 3; ++count) {
        std::vector<double> expected(static_cast<std::size_t>(a.n) * count);
        for (double& v : expected) v = value(random);
        const std::vector<double> b = multiply(a, expected, count);
        auto relativeError = [&](const std::vector<double>& x) {
            double error = 0.0, size = 0.0;
            for (std::size_t k = 0; k < x.size(); ++k) {
                error += (x[k] - expected[k]) * (x[k] - expected[k]);
                size += expected[k] * expected[k];
            }
            return std::sqrt(error / size);
        };
        std::vector<double> x(b.size());
        exact.solve(b, x, count);
        // Double precision: round-off times A's condition (far above 10⁶ here), whatever the
        // order of the sums (measured 0.9–1.1e-10).
        EXPECT_LT(relativeError(x), 1e-9);
        single.solve(b, x, count);
        const double first = relativeError(x);
        EXPECT_GT(first, 1e-12) << "the single-precision factor gave the exact answer: was it used?";
        EXPECT_LT(first, 0.1);
        const std::vector<double> ax = multiply(a, x, count);
        std::vector<double> residual(b.size()), correction(b.size());
        for (std::size_t k = 0; k < b.size(); ++k) residual[k] = b[k] - ax[k];
        single.solve(residual, correction, count);
        for (std::size_t k = 0; k < b.size(); ++k) x[k] += correction[k];
        EXPECT_LT(relativeError(x), 1e-4 * first) << count << " right-hand sides";
        std::printf("single-precision factor, %d right-hand sides: error %.3g, after one refinement %.3g\n", count,
                    first, relativeError(x));
    }
}

TEST(SparseCholesky, AvxAndBaselineSweepsAgreeBitForBit)
{
    if (!SparseCholesky::available()) GTEST_SKIP() << "this build has no CHOLMOD";
    // Neither variant fuses multiply-adds (src/VectorInstructions.hpp): the same bits, for both
    // precisions and 1–3 right-hand sides. (Where the CPU has no AVX2 both runs take the
    // baseline: the test then checks nothing new, and says so.)
    if (!useAvxKernels()) std::printf("this CPU has no AVX2: both solves take the baseline sweeps\n");
    const Csr a = gridLaplacian(120);
    for (FactorPrecision precision : {FactorPrecision::double_, FactorPrecision::single}) {
        const SparseCholesky factor(a.n, a.rowOffsets, a.columns, a.values, precision);
        std::mt19937 random(5);
        std::uniform_real_distribution<double> value(-1.0, 1.0);
        for (int count = 1; count <= 3; ++count) {
            std::vector<double> b(static_cast<std::size_t>(a.n) * count);
            for (double& v : b) v = value(random);
            std::vector<double> withAvx(b.size()), baseline(b.size());
            factor.solve(b, withAvx, count);
            avxKernelsAllowed() = false;
            factor.solve(b, baseline, count);
            avxKernelsAllowed() = true;
            EXPECT_EQ(withAvx, baseline) << count << " right-hand sides";
        }
    }
}

TEST(SparseCholesky, RefusesAnIndefiniteMatrixAndWrongSizes)
{
    if (!SparseCholesky::available()) GTEST_SKIP() << "this build has no CHOLMOD";
    Csr a = gridLaplacian(5);
    for (int p = a.rowOffsets[7]; p < a.rowOffsets[8]; ++p)
        if (a.columns[p] == 7) a.values[p] = -1.0;  // a negative diagonal entry
    try {
        const SparseCholesky factor(a.n, a.rowOffsets, a.columns, a.values);
        FAIL() << "an indefinite matrix was factorised";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("not positive definite"), std::string::npos) << error.what();
    }
    const Csr b = gridLaplacian(5);
    const SparseCholesky factor(b.n, b.rowOffsets, b.columns, b.values);
    std::vector<double> wrong(b.n * 4), out(b.n * 4);
    EXPECT_THROW(factor.solve(wrong, out, 4), std::invalid_argument);
    std::vector<double> shortVector(b.n - 1), result(b.n);
    EXPECT_THROW(factor.solve(shortVector, result, 1), std::invalid_argument);
}

// Debian's CHOLMOD asks for a team of 4 threads in every large supernode of its factorisation,
// whatever OMP_NUM_THREADS says; with rbm at 2 threads on a 2-core machine that team cost more
// than it saved (ThreadCount.hpp). The factorisation must not start threads beyond rbm's count:
// OpenMP keeps a team's threads for the next region, so this process' thread count after a
// region of 2 threads must be the same after the factorisation.
TEST(SparseCholesky, TheFactorisationStaysWithinRbmsThreadCount)
{
    if (!SparseCholesky::available()) GTEST_SKIP() << "this build has no CHOLMOD";
#ifndef _OPENMP
    GTEST_SKIP() << "built without OpenMP";
#else
    auto threadsOfThisProcess = [] {
        std::size_t count = 0;
        for ([[maybe_unused]] const auto& task : std::filesystem::directory_iterator("/proc/self/task")) ++count;
        return count;
    };
    const int before = threadCount();
    setThreadCount(2);
    int teamSize = 0;
#pragma omp parallel
    {
#pragma omp single
        teamSize = omp_get_num_threads();
    }
    ASSERT_EQ(teamSize, 2);
    const std::size_t threadsBefore = threadsOfThisProcess();
    const Csr a = gridLaplacian(120);   // supernodes far above CHOLMOD's threshold of 1024 entries
    const SparseCholesky factor(a.n, a.rowOffsets, a.columns, a.values);
    EXPECT_EQ(threadsOfThisProcess(), threadsBefore) << "CHOLMOD started threads beyond rbm's 2";
    // The same factor as with CHOLMOD's own team: a solve against a known solution.
    std::vector<double> expected(a.n), rightHandSide, solution(a.n);
    for (int i = 0; i < a.n; ++i) expected[i] = std::sin(0.01 * i);
    rightHandSide = multiply(a, expected, 1);
    factor.solve(rightHandSide, solution, 1);
    for (int i = 0; i < a.n; ++i) ASSERT_NEAR(solution[i], expected[i], 1e-8) << i;
    // With 4 threads allowed, CHOLMOD's team is its own again.
    setThreadCount(4);
    int teamOfFour = 0;
    {
        const LibraryTeamsWithinThreadCount withinThreadCount(4);
#pragma omp parallel num_threads(4)
        {
#pragma omp single
            teamOfFour = omp_get_num_threads();
        }
    }
    EXPECT_EQ(teamOfFour, 4);
    setThreadCount(before);
#endif
}

} // namespace
} // namespace rbm::motion
