#include "SmoothedAggregation.hpp"

#include "PetscSupport.hpp"

#include <petscmat.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rbm::motion {

std::vector<int> aggregateRows(std::span<const int> rowOffsets, std::span<const int> columns,
                               std::span<const double> values, int& count)
{
    const int rows = static_cast<int>(rowOffsets.size()) - 1;
    std::vector<int> aggregate(static_cast<std::size_t>(rows), -1);
    count = 0;
    // Strong couplings only (|a_ij| ≥ θ √(a_ii a_jj)) form aggregates (phases 1 and 3; phase 2
    // joins the strongest neighbour as before). See the header for θ.
    std::vector<double> diagonal(static_cast<std::size_t>(rows), 0.0);
    for (int row = 0; row < rows; ++row)
        for (int k = rowOffsets[row]; k < rowOffsets[row + 1]; ++k)
            if (columns[k] == row) diagonal[row] = std::abs(values[k]);
    for (int row = 0; row < rows; ++row)  // a pattern without its diagonal: the row's sum
        if (diagonal[row] == 0.0)
            for (int k = rowOffsets[row]; k < rowOffsets[row + 1]; ++k) diagonal[row] += std::abs(values[k]);
    auto strong = [&](int row, int k) {
        const int column = columns[k];
        return column != row &&
               std::abs(values[k]) >= strongCouplingThreshold * std::sqrt(diagonal[row] * diagonal[column]);
    };
    // Phase 1: a row with no aggregated neighbour starts an aggregate of its neighbourhood.
    for (int row = 0; row < rows; ++row) {
        if (aggregate[row] >= 0) continue;
        bool free = true;
        for (int k = rowOffsets[row]; k < rowOffsets[row + 1] && free; ++k)
            free = !strong(row, k) || aggregate[columns[k]] < 0;
        if (!free) continue;
        aggregate[row] = count;
        for (int k = rowOffsets[row]; k < rowOffsets[row + 1]; ++k)
            if (strong(row, k)) aggregate[columns[k]] = count;
        ++count;
    }
    // Phase 2: the rows left join their strongest neighbour's aggregate of phase 1.
    const std::vector<int> firstPhase = aggregate;
    for (int row = 0; row < rows; ++row) {
        if (firstPhase[row] >= 0) continue;
        int best = -1;
        double strongest = -1.0;
        for (int k = rowOffsets[row]; k < rowOffsets[row + 1]; ++k) {
            const int column = columns[k];
            if (column == row || firstPhase[column] < 0) continue;
            if (std::abs(values[k]) > strongest) {
                strongest = std::abs(values[k]);
                best = firstPhase[column];
            }
        }
        aggregate[row] = best;
    }
    // Phase 3: rows with no aggregated neighbour start aggregates of their neighbours left.
    for (int row = 0; row < rows; ++row) {
        if (aggregate[row] >= 0) continue;
        aggregate[row] = count;
        for (int k = rowOffsets[row]; k < rowOffsets[row + 1]; ++k)
            if (strong(row, k) && aggregate[columns[k]] < 0) aggregate[columns[k]] = count;
        ++count;
    }
    return aggregate;
}

namespace {

// The largest eigenvalue of D⁻¹A (A symmetric positive definite: real, positive) by power
// iteration from a fixed irregular start, with a 5 % margin: an underestimate would make the
// prolongator's Jacobi smoothing amplify the top of the spectrum instead of damping it.
double largestEigenvalueOfJacobi(std::span<const int> offsets, std::span<const int> columns,
                                 std::span<const double> values, std::span<const double> inverseDiagonal)
{
    constexpr int iterations = 15;
    const std::size_t rows = inverseDiagonal.size();
    std::vector<double> v(rows), w(rows);
    double length = 0.0;
    for (std::size_t k = 0; k < rows; ++k) {
        v[k] = 1.0 + 0.5 * std::sin(static_cast<double>(k) * 0.6180339887498949 * 6.283185307179586);
        length += v[k] * v[k];
    }
    for (double& entry : v) entry /= std::sqrt(length);
    double lambda = 1.0;
    for (int iteration = 0; iteration < iterations; ++iteration) {
        double norm = 0.0;
        for (std::size_t row = 0; row < rows; ++row) {
            double sum = 0.0;
            for (int k = offsets[row]; k < offsets[row + 1]; ++k) sum += values[k] * v[columns[k]];
            w[row] = inverseDiagonal[row] * sum;
            norm += w[row] * w[row];
        }
        norm = std::sqrt(norm);
        if (!(norm > 0.0)) break;
        lambda = norm;  // |D⁻¹A v| for |v| = 1
        for (std::size_t row = 0; row < rows; ++row) v[row] = w[row] / norm;
    }
    return 1.05 * lambda;
}

// P = (I − ω D⁻¹A) T, T the aggregation (T(i, aggregate(i)) = 1), columns sorted in each row.
CompressedRows smoothedProlongator(std::span<const int> offsets, std::span<const int> columns,
                                   std::span<const double> values, const std::vector<int>& aggregate)
{
    const int rows = static_cast<int>(offsets.size()) - 1;
    std::vector<double> inverseDiagonal(static_cast<std::size_t>(rows), 0.0);
    for (int row = 0; row < rows; ++row) {
        for (int k = offsets[row]; k < offsets[row + 1]; ++k)
            if (columns[k] == row) inverseDiagonal[row] = values[k] > 0.0 ? 1.0 / values[k] : 0.0;
        if (!(inverseDiagonal[row] > 0.0))
            throw std::runtime_error("smoothed aggregation: row " + std::to_string(row) + " has no positive diagonal");
    }
    const double omega = 4.0 / (3.0 * largestEigenvalueOfJacobi(offsets, columns, values, inverseDiagonal));
    CompressedRows p;
    p.offsets.reserve(static_cast<std::size_t>(rows) + 1);
    p.columns.reserve(columns.size() / 2);
    p.values.reserve(columns.size() / 2);
    std::vector<std::pair<int, double>> entries;
    for (int row = 0; row < rows; ++row) {
        entries.clear();
        entries.emplace_back(aggregate[row], 1.0);
        const double scale = omega * inverseDiagonal[row];
        for (int k = offsets[row]; k < offsets[row + 1]; ++k) {
            const int target = aggregate[columns[k]];
            auto found = std::find_if(entries.begin(), entries.end(), [&](const auto& entry) { return entry.first == target; });
            if (found == entries.end()) entries.emplace_back(target, -scale * values[k]);
            else found->second -= scale * values[k];
        }
        std::sort(entries.begin(), entries.end());
        for (const auto& [column, value] : entries) {
            p.columns.push_back(column);
            p.values.push_back(value);
        }
        p.offsets.push_back(static_cast<int>(p.columns.size()));
    }
    return p;
}

// Pᵀ A P by PETSc (the matrices wrap the arrays; the product is copied out).
CompressedRows galerkinProduct(std::span<const int> offsets, std::span<const int> columns, std::span<const double> values,
                               const CompressedRows& p, int coarseRows)
{
    static_assert(sizeof(PetscInt) == sizeof(int), "PETSc's indices must be 32-bit ints to wrap the CSR arrays");
    const PetscInt rows = static_cast<PetscInt>(offsets.size()) - 1;
    PetscMat a, prolongator, product;
    RBM_CHECK_PETSC(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, rows, rows, const_cast<PetscInt*>(offsets.data()),
                                              const_cast<PetscInt*>(columns.data()),
                                              const_cast<PetscScalar*>(values.data()), a.out()));
    RBM_CHECK_PETSC(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, rows, coarseRows, const_cast<PetscInt*>(p.offsets.data()),
                                              const_cast<PetscInt*>(p.columns.data()),
                                              const_cast<PetscScalar*>(p.values.data()), prolongator.out()));
    RBM_CHECK_PETSC(MatPtAP(a, prolongator, MAT_INITIAL_MATRIX, PETSC_DEFAULT, product.out()));
    const PetscInt* rowStart = nullptr;
    const PetscInt* columnIndex = nullptr;
    PetscInt count = 0;
    PetscBool done = PETSC_FALSE;
    RBM_CHECK_PETSC(MatGetRowIJ(product, 0, PETSC_FALSE, PETSC_FALSE, &count, &rowStart, &columnIndex, &done));
    if (!done || count != coarseRows) throw std::runtime_error("smoothed aggregation: PETSc's product has no compressed rows");
    const PetscScalar* entries = nullptr;
    RBM_CHECK_PETSC(MatSeqAIJGetArrayRead(product, &entries));
    CompressedRows c;
    c.offsets.assign(rowStart, rowStart + coarseRows + 1);
    c.columns.assign(columnIndex, columnIndex + rowStart[coarseRows]);
    c.values.assign(entries, entries + rowStart[coarseRows]);
    RBM_CHECK_PETSC(MatSeqAIJRestoreArrayRead(product, &entries));
    RBM_CHECK_PETSC(MatRestoreRowIJ(product, 0, PETSC_FALSE, PETSC_FALSE, &count, &rowStart, &columnIndex, &done));
    return c;
}

} // namespace

std::vector<AggregationLevel> buildSmoothedAggregation(std::span<const int> rowOffsets, std::span<const int> columns,
                                                       std::span<const double> values, int coarsestRows)
{
    std::vector<AggregationLevel> levels;
    std::span<const int> offsets = rowOffsets, indices = columns;
    std::span<const double> entries = values;
    while (static_cast<int>(offsets.size()) - 1 > coarsestRows) {
        const int rows = static_cast<int>(offsets.size()) - 1;
        int count = 0;
        const std::vector<int> aggregate = aggregateRows(offsets, indices, entries, count);
        if (2 * count > rows) break;  // no real coarsening left (e.g. rows without neighbours)
        AggregationLevel level;
        level.interpolation = smoothedProlongator(offsets, indices, entries, aggregate);
        level.coarseOperator = galerkinProduct(offsets, indices, entries, level.interpolation, count);
        levels.push_back(std::move(level));
        const CompressedRows& coarse = levels.back().coarseOperator;
        offsets = coarse.offsets;
        indices = coarse.columns;
        entries = coarse.values;
    }
    return levels;
}

} // namespace rbm::motion
