#pragma once
// A sparse Cholesky factor P A Pᵀ = L Lᵀ of a symmetric positive definite matrix, computed
// once and then applied many times to a few right-hand sides at once (issue 12: the reduced
// Newton solver applies K⁻¹ of the constant weighted Laplacian 10–40 times per time step).
//
// Why not PETSc's MatMatSolve on its CHOLMOD factor: CHOLMOD keeps the factor supernodal, and
// its supernodal back-substitution calls BLAS (dtrsm/dgemm) once per supernode. A 2D mesh
// Laplacian has tens of thousands of supernodes of a few columns, so with 2–3 right-hand sides
// the BLAS calls' set-up, not the flops, dominates (perf on the 40k-node airfoil: 34 % of a
// pitching run in cholmod_super_*solve, most of it in OpenBLAS copy routines). Here CHOLMOD
// orders (AMD / METIS, its own choice of the best) and factorises supernodally (fast); the
// factor's columns are then copied into a plain compressed-column L without the supernodes'
// zero padding, and the triangular solves run as two tight loops over its entries with the
// right-hand sides interleaved (all components of a node side by side), so every entry of L is
// read once per solve for all components. (A supernodal sweep of rbm's own was measured
// slower: it reads the padding and the diagonal blocks' upper halves.)
//
// Built only where CHOLMOD's header was found (RBM_HAVE_CHOLMOD; Debian: libsuitesparse-dev,
// which petsc-dev depends on). Sequential: one process's matrix.

#include <cstddef>
#include <span>
#include <vector>

namespace rbm::motion {

class SparseCholesky {
public:
    // The matrix in compressed sparse rows over n rows, both triangles given (only the upper
    // triangle, column ≥ row, is read), any column order. Throws std::runtime_error naming the
    // failing step if CHOLMOD reports an error or the matrix is not positive definite.
    SparseCholesky(int n, std::span<const int> rowOffsets, std::span<const int> columns, std::span<const double> values);

    int size() const { return size_; }
    // Entries of L (diagonal included): the solve reads each once per sweep.
    std::size_t factorNonzeros() const { return rowIndex_.size(); }

    // X = A⁻¹ B for `count` (1 to 3) right-hand sides stored interleaved: B[k * count + c] is row k of
    // right-hand side c. b and x may be the same array.
    void solve(std::span<const double> b, std::span<double> x, int count) const;

    // Whether this build has CHOLMOD (otherwise the constructor throws).
    static bool available();

private:
    int size_ = 0;
    std::vector<int> permutation_;    // row k of the factored matrix is row permutation_[k] of A
    std::vector<int> columnStart_;    // L in compressed columns, the diagonal first in each column
    std::vector<int> rowIndex_;
    std::vector<double> value_;
    mutable std::vector<double> work_;
};

} // namespace rbm::motion
