#pragma once
// One multigrid V-cycle of a scalar symmetric positive definite matrix A applied to THREE
// right-hand sides at once (the x, y and z components of a displacement field), on one rank.
//
// The hierarchy (coarse operators and interpolations) is rbm's smoothed aggregation
// (SmoothedAggregation.hpp; the default of build()) or taken from a set-up PCMG / PCGAMG and
// copied; the finest operator is the caller's CSR (its pattern referenced, its values copied in
// single precision). The cycle itself is
// rbm's: per level Chebyshev smoothing of degree 2 on D⁻¹A over [0.1 λ, 1.1 λ] (PETSc's default
// multigrid smoother; λ estimated by power iteration), pre- and post-smoothing alike, so the
// cycle is a symmetric positive definite operator; the coarsest level is solved by a dense
// Cholesky factorisation. Why not PCApply three times: on the 27-point hexahedral Laplacian a
// V-cycle is bound by reading the matrix (12 bytes per entry for a few flops); here each pass
// over a level's matrix serves three vectors (interleaved, 24 contiguous bytes per column
// index), and the pre-smoothing starts from zero (no product), so a cycle on three vectors reads
// the finest matrix 4 times instead of 3 × 5 times, at 8 bytes an entry (single precision).
//
// Determinism: every loop writes its own row; restriction is a product with the stored
// transpose of the interpolation (rows gathered, not scattered); sums run in CSR order.

#include "SmoothedAggregation.hpp"

#include <petscpc.h>

#include <memory>
#include <span>
#include <string_view>
#include <vector>

namespace rbm::motion {

class ThreeVectorMultigrid {
public:
    // The cycle of the CSR matrix: by default on rbm's smoothed-aggregation hierarchy
    // (SmoothedAggregation.hpp, coarsest level at most 500 rows); with
    // -rbm_<solverName>_cycle_hierarchy gamg on the hierarchy PCGAMG sets up on PETSC_COMM_SELF
    // (PETSc's matrix wrapping the caller's arrays, no copy; GAMG's defaults, then the options
    // under rbm_<solverName>_, e.g. -rbm_reduced_pc_gamg_threshold; PETSc's objects released
    // before returning). nullptr when the options choose a preconditioner that is not multigrid,
    // on more than one rank, or where the hierarchy cannot be built. rbm's own aggregation
    // (SmoothedAggregation.hpp) is the default because on hexahedral meshes its set-up costs
    // about half of GAMG's (whose time goes to its graph and the coarsening on the squared
    // graph) for about the same CG iterations; GAMG without squaring the graph
    // (-pc_gamg_square_graph 0), or with misk distance-2 or hem coarsening, is slower still
    // (docs/motionSolver.md, "Reduced Newton", "The preconditioner K⁻¹"; rbmBenchmark's
    // twist3D case).
    static std::unique_ptr<ThreeVectorMultigrid> build(std::span<const int> rowOffsets, std::span<const int> columns,
                                                       std::span<const double> values, std::string_view solverName);
    // rbm's smoothed-aggregation cycle of the CSR matrix whatever the options and the ranks (one
    // rank's own block of a distributed matrix); nullptr for no rows or where the hierarchy
    // cannot be built. The arrays must outlive it as for build().
    static std::unique_ptr<ThreeVectorMultigrid> buildAggregation(std::span<const int> rowOffsets,
                                                                  std::span<const int> columns,
                                                                  std::span<const double> values);

    // pc: a set-up PC of type mg or gamg on PETSC_COMM_SELF whose finest operator equals the CSR
    // matrix (rowOffsets, columns, values), rows in the same order. Throws std::runtime_error if
    // the hierarchy cannot be used (another PC type, more than one rank, a coarsest level of more
    // than 4 000 rows).
    ThreeVectorMultigrid(PC pc, std::span<const int> rowOffsets, std::span<const int> columns,
                         std::span<const double> values);

    // The finest operator the caller's CSR, the coarser levels given, finest first
    // (SmoothedAggregation.hpp). Throws std::runtime_error as the constructor above.
    ThreeVectorMultigrid(std::span<const int> rowOffsets, std::span<const int> columns, std::span<const double> values,
                         std::vector<AggregationLevel> coarser);

    // z = M⁻¹ r, interleaved vectors (3 values per row); r and z must not overlap (the finest
    // level works in them directly).
    void apply(std::span<const double> r, std::span<double> z);

    // Whether apply() reads the caller's finest values: not once they are held in single
    // precision (more than one level), and the caller may then release them.
    bool readsFinestValues() const { return levels_.front().values != nullptr; }

    int levelCount() const { return static_cast<int>(levels_.size()); }
    int rows(int level) const { return levels_[level].rows; }
    // Bytes held (copies of the coarse levels, transfers, work vectors).
    double bytes() const;

private:
    using Csr = CompressedRows;
    struct Level {
        int rows = 0;
        const int* offsets = nullptr;  // the operator (the caller's on the finest level)
        const int* columns = nullptr;
        const double* values = nullptr;
        Csr owned;                     // the operator's storage on coarse levels
        std::vector<float> singleValues;  // the finest operator's values in single precision (read in products)
        std::vector<double> inverseDiagonal;
        double lambdaMax = 1.0;        // of D⁻¹A
        Csr interpolation;             // from the next coarser level to this one (rows × coarser rows)
        Csr restriction;               // its transpose
        std::vector<double> rhs, solution;  // interleaved, 3 per row; none on the finest of several levels
        // What the cycle reads and writes: rhs and solution, or on the finest of several levels
        // apply's r and z (two vectors of the finest size fewer, 48 bytes a row).
        const double* b = nullptr;
        double* x = nullptr;
    };

    void setUp(std::span<const int> rowOffsets, std::span<const int> columns, std::span<const double> values,
               std::vector<AggregationLevel> coarser);
    void multiply(const Level& level, const double* x, double* y) const;  // y = A x (3 vectors)
    void smooth(Level& level, bool zeroGuess);
    void cycle(int index);
    void coarseSolve(Level& level);
    void estimateLambda(Level& level);

    std::vector<Level> levels_;   // 0 = finest
    int degree_ = 2;              // of the Chebyshev smoother (-rbm_<solverName>_cycle_degree)
    std::vector<double> coarseFactor_;  // dense Cholesky factor of the coarsest operator (lower, row-major)
    // Work shared by the levels (one level is smoothed at a time), sized for the finest.
    std::vector<double> residual_, direction_, product_;
};

} // namespace rbm::motion
