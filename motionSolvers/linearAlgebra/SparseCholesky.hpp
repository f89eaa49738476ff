#pragma once
// A sparse Cholesky factor P A Pᵀ = L Lᵀ of a symmetric positive definite matrix, computed
// once and then applied many times to a few right-hand sides at once (issue 12: the reduced
// Newton solver applies K⁻¹ of the constant weighted Laplacian 10–40 times per time step).
//
// Why not PETSc's MatMatSolve on its CHOLMOD factor: CHOLMOD's supernodal back-substitution
// calls BLAS (dtrsm/dgemm) once per supernode. A 2D mesh Laplacian has thousands of supernodes
// of a few to a few dozen columns, so with 2–3 right-hand sides the BLAS calls' set-up, not the
// flops, dominates (profiled on the airfoil pitching series: cholmod_super_*solve's time
// goes mostly to OpenBLAS copy routines). Here CHOLMOD orders (AMD / METIS,
// its own choice of the best) and factorises supernodally (fast); rbm then keeps each
// supernode as a packed lower-triangular diagonal block and a column-major block of the rows
// below it, with one row list per supernode, and sweeps them itself: forward, one contiguous
// multiply-add per column of the block into a dense work vector and then one update per row
// below; backward, one gather per row below and then one contiguous dot product per column —
// instead of one indirect load and store per entry of L. On the airfoil 97 % of L's entries
// sit in supernodes of 8 columns or more. The right-hand sides are interleaved (all components
// of a node side by side) in the caller's vectors and deinterleaved per supernode, so every
// entry of L is read once per solve for all components. The sweeps are then bound by reading
// L from memory, which is why the entries are kept in single precision (below).
// On CPUs with AVX2 the products with the blocks below the supernodes keep eight rows' (forward)
// or four columns' (backward) partial sums in registers instead of the work vector, with the
// same operations in the same order (the same bits), so that a factor in cache is swept at
// nearly the cache's speed. In a time step the factor comes from memory, and the sweeps
// request its entries 2 KB ahead (ReadAhead.hpp). What both give a back-substitution is
// measured on the airfoil pitching series (rbmBenchmark --cases airfoil; docs/motionSolver.md,
// "Reduced Newton", "The preconditioner K⁻¹").

// Built only where CHOLMOD's header was found (RBM_HAVE_CHOLMOD; Debian: libsuitesparse-dev,
// which petsc-dev depends on). Sequential: one process's matrix.

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace rbm::motion {

// How the factor's entries are kept. The sweeps stream every entry of L from memory once per
// solve and are bound by that traffic (perf: the loads of L's entries are the hot
// instructions), so single precision halves a solve's time. The arithmetic stays in double;
// each entry is then off by at most 2⁻²⁴ relatively, i.e. the factor of a matrix within that
// relative distance of A entrywise: a preconditioner as good as the exact one (reduced Newton
// takes the same CG iterations), not an exact inverse.
enum class FactorPrecision { double_, single };

class SparseCholesky {
public:
    // The matrix in compressed sparse rows over n rows, both triangles given (only the upper
    // triangle, column ≥ row, is read), any column order. Throws std::runtime_error naming the
    // failing step if CHOLMOD reports an error or the matrix is not positive definite.
    SparseCholesky(int n, std::span<const int> rowOffsets, std::span<const int> columns, std::span<const double> values,
                   FactorPrecision precision = FactorPrecision::double_);

    int size() const { return size_; }
    // Entries of L as stored (diagonal included, the supernodes' explicit zeros too): the solve
    // reads each once per sweep.
    std::size_t factorNonzeros() const { return valueStart_.empty() ? 0 : valueStart_.back(); }
    FactorPrecision precision() const { return precision_; }
    int supernodeCount() const { return static_cast<int>(supernodeStart_.size()) - 1; }

    // X = A⁻¹ B for `count` (1 to 3) right-hand sides stored interleaved: B[k * count + c] is row k of
    // right-hand side c. b and x may be the same array.
    void solve(std::span<const double> b, std::span<double> x, int count) const;

    // Whether this build has CHOLMOD (otherwise the constructor throws).
    static bool available();

private:
    int size_ = 0;
    std::vector<int> permutation_;    // row k of the factored matrix is row permutation_[k] of A
    // Supernode s holds the columns [supernodeStart_[s], supernodeStart_[s + 1]) of L (width w).
    // Its entries, from valueStart_[s] on: the w × w diagonal block's lower triangle, packed
    // by rows with each diagonal entry stored as its reciprocal, then the block of the rows
    // below it, column-major (belowRow_[belowStart_[s] + t] is row t's index in L).
    std::vector<int> supernodeStart_;
    std::vector<int> belowStart_;
    std::vector<int> belowRow_;
    std::vector<std::size_t> valueStart_;
    std::vector<double> value_;        // FactorPrecision::double_
    // FactorPrecision::single: CHOLMOD's own array of L's entries, rewritten in place and kept
    // (constructor), so freed as SuiteSparse allocated it.
    struct FreeEntries {
        void operator()(float* entries) const;
    };
    std::unique_ptr<float[], FreeEntries> singleValue_;
    FactorPrecision precision_ = FactorPrecision::double_;
    mutable std::vector<double> work_;
};

} // namespace rbm::motion
