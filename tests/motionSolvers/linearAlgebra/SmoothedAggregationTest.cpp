// Tests of the smoothed aggregation (linearAlgebra/SmoothedAggregation) of the three-vector multigrid.

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
#include <tuple>
#include <vector>

using namespace rbm::test::multigridCases;

namespace rbm::motion {

namespace {

TEST(SmoothedAggregation, OnStretchedCellsAggregatesFollowTheStrongCouplingsOnly)
{
    // A 12 × 12 grid of cells of aspect ratio 100 (a boundary layer's): 1/|d|² weights give the
    // couplings along x 1e-4 of those along y; every row also holds 0.1 on its diagonal (a held
    // neighbour's share). |a_ij| / √(a_ii a_jj) is about 0.45 along y and 5e-5 along x, far
    // below the threshold 0.005: aggregates lie in single x columns (lines across the layers),
    // where aggregating whole neighbourhoods would mix both directions.
    constexpr int n = 12;
    auto index = [](int i, int j) { return j * n + i; };
    std::vector<int> offsets{0}, columns;
    std::vector<double> values;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            double diagonal = 0.1;
            const int diagonalPosition = static_cast<int>(columns.size());
            columns.push_back(index(i, j));
            values.push_back(0.0);
            for (const auto& [di, dj, weight] : {std::tuple{-1, 0, 1e-4}, std::tuple{1, 0, 1e-4}, std::tuple{0, -1, 1.0},
                                                 std::tuple{0, 1, 1.0}}) {
                if (i + di < 0 || i + di >= n || j + dj < 0 || j + dj >= n) continue;
                columns.push_back(index(i + di, j + dj));
                values.push_back(-weight);
                diagonal += weight;
            }
            values[diagonalPosition] = diagonal;
            offsets.push_back(static_cast<int>(columns.size()));
        }
    int count = 0;
    const std::vector<int> aggregate = aggregateRows(offsets, columns, values, count);
    std::vector<int> columnOf(static_cast<std::size_t>(count), -1);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            int& column = columnOf[aggregate[index(i, j)]];
            if (column < 0) column = i;
            EXPECT_EQ(column, i) << "an aggregate spans x columns " << column << " and " << i;
        }
    // In row order each column gets {0, 1}, {2, 3, 4}, {5, 6, 7}, {8, 9, 10} in phase 1 (a row and
    // its strong neighbours) and row 11 joins {8, 9, 10} in phase 2: 4 aggregates a column.
    EXPECT_EQ(count, 4 * n);
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

} // namespace
} // namespace rbm::motion
