#include "SparseCholesky.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#if defined(RBM_HAVE_CHOLMOD)
#include <suitesparse/cholmod.h>
#endif

namespace rbm::motion {

bool SparseCholesky::available()
{
#if defined(RBM_HAVE_CHOLMOD)
    return true;
#else
    return false;
#endif
}

#if defined(RBM_HAVE_CHOLMOD)
namespace {

// cholmod_common with its start and finish (RAII); every CHOLMOD object below is freed in it.
class CholmodSession {
public:
    CholmodSession()
    {
        cholmod_start(&common_);
        common_.print = 0;       // errors are reported by status, not printed
        common_.error_handler = nullptr;
    }
    ~CholmodSession()
    {
        if (factor_) cholmod_free_factor(&factor_, &common_);
        if (matrix_) cholmod_free_sparse(&matrix_, &common_);
        cholmod_finish(&common_);
    }
    CholmodSession(const CholmodSession&) = delete;
    CholmodSession& operator=(const CholmodSession&) = delete;

    cholmod_common* common() { return &common_; }
    void check(const char* step) const
    {
        if (common_.status < CHOLMOD_OK)
            throw std::runtime_error(std::string("sparse Cholesky: ") + step + " failed (CHOLMOD status " +
                                     std::to_string(common_.status) + ")");
    }

    cholmod_sparse* matrix_ = nullptr;
    cholmod_factor* factor_ = nullptr;

private:
    cholmod_common common_{};
};

} // namespace
#endif

SparseCholesky::SparseCholesky(int n, std::span<const int> rowOffsets, std::span<const int> columns,
                               std::span<const double> values)
    : size_(n)
{
#if !defined(RBM_HAVE_CHOLMOD)
    (void)rowOffsets;
    (void)columns;
    (void)values;
    throw std::runtime_error("sparse Cholesky: this build has no CHOLMOD (install libsuitesparse-dev and rebuild)");
#else
    if (n < 0 || rowOffsets.size() != static_cast<std::size_t>(n) + 1 || columns.size() != values.size() ||
        static_cast<std::size_t>(rowOffsets[n]) != columns.size())
        throw std::invalid_argument("sparse Cholesky: inconsistent compressed rows");
    // The upper triangle in compressed columns: entry (i, j), i ≤ j, is A(j, i) of row j
    // (A is symmetric), sorted by row within each column.
    std::size_t upperCount = 0;
    for (int row = 0; row < n; ++row)
        for (int position = rowOffsets[row]; position < rowOffsets[row + 1]; ++position)
            if (columns[position] <= row) ++upperCount;
    CholmodSession session;
    session.matrix_ = cholmod_allocate_sparse(n, n, upperCount, 1, 1, 1, CHOLMOD_REAL, session.common());
    session.check("allocating the matrix");
    auto* start = static_cast<int*>(session.matrix_->p);
    auto* index = static_cast<int*>(session.matrix_->i);
    auto* entry = static_cast<double*>(session.matrix_->x);
    std::vector<std::pair<int, double>> column;
    std::size_t next = 0;
    for (int j = 0; j < n; ++j) {
        start[j] = static_cast<int>(next);
        column.clear();
        for (int position = rowOffsets[j]; position < rowOffsets[j + 1]; ++position)
            if (columns[position] <= j) column.emplace_back(columns[position], values[position]);
        std::sort(column.begin(), column.end());
        for (const auto& [i, value] : column) {
            index[next] = i;
            entry[next] = value;
            ++next;
        }
    }
    start[n] = static_cast<int>(next);

    session.factor_ = cholmod_analyze(session.matrix_, session.common());
    session.check("ordering (cholmod_analyze)");
    cholmod_factorize(session.matrix_, session.factor_, session.common());
    session.check("factorising (cholmod_factorize)");
    if (session.common()->status == CHOLMOD_NOT_POSDEF || session.factor_->minor < static_cast<std::size_t>(n))
        throw std::runtime_error("sparse Cholesky: the matrix is not positive definite (column " +
                                 std::to_string(session.factor_->minor) + ")");
    // The supernodal factor pads its supernodes with explicit zeros (relaxed amalgamation: 25 %
    // of the entries of the airfoil's factor); the solve need not read them. Its columns are
    // copied straight into compressed columns (CHOLMOD's own conversion to a simplicial factor
    // would allocate and fill a third copy of L: 0.8 GB and a quarter of the set-up at 10⁶
    // 2D nodes). A small matrix factorised simplicially (L D Lᵀ) is converted to L Lᵀ first.
    if (!session.factor_->is_super) {
        cholmod_change_factor(CHOLMOD_REAL, 1, 0, 1, 1, session.factor_, session.common());
        session.check("converting the factor (cholmod_change_factor)");
    }
    const cholmod_factor& factor = *session.factor_;
    const auto* permutation = static_cast<const int*>(factor.Perm);
    columnStart_.assign(n + 1, 0);
    rowIndex_.clear();
    value_.clear();
    auto keep = [&](int row, double value, bool diagonal) {
        if (value != 0.0 || diagonal) {
            rowIndex_.push_back(row);
            value_.push_back(value);
        }
    };
    if (factor.is_super) {
        const auto* super = static_cast<const int*>(factor.super);
        const auto* rowPointer = static_cast<const int*>(factor.pi);
        const auto* valuePointer = static_cast<const int*>(factor.px);
        const auto* rows = static_cast<const int*>(factor.s);
        const auto* values = static_cast<const double*>(factor.x);
        const std::size_t estimate = static_cast<std::size_t>(session.common()->lnz);
        rowIndex_.reserve(estimate);
        value_.reserve(estimate);
        for (std::size_t supernode = 0; supernode < factor.nsuper; ++supernode) {
            const int k1 = super[supernode], k2 = super[supernode + 1];
            const int rowCount = rowPointer[supernode + 1] - rowPointer[supernode];
            // Column k1 + c: the rows from c on (its diagonal first), column-major in the block.
            for (int c = 0; c < k2 - k1; ++c) {
                const double* column = values + valuePointer[supernode] + static_cast<std::size_t>(c) * rowCount;
                for (int r = c; r < rowCount; ++r) keep(rows[rowPointer[supernode] + r], column[r], r == c);
                columnStart_[k1 + c + 1] = static_cast<int>(rowIndex_.size());
            }
        }
    } else {
        const auto* factorStart = static_cast<const int*>(factor.p);
        const auto* factorIndex = static_cast<const int*>(factor.i);
        const auto* factorValue = static_cast<const double*>(factor.x);
        rowIndex_.reserve(n > 0 ? static_cast<std::size_t>(factorStart[n]) : 0);
        value_.reserve(rowIndex_.capacity());
        for (int j = 0; j < n; ++j) {
            for (int p = factorStart[j]; p < factorStart[j + 1]; ++p) keep(factorIndex[p], factorValue[p], p == factorStart[j]);
            columnStart_[j + 1] = static_cast<int>(rowIndex_.size());
        }
    }
    permutation_.assign(permutation, permutation + n);
    // A small matrix may be factorised simplicially as L D Lᵀ, which does not fail on an
    // indefinite matrix; its L Lᵀ form then has a diagonal entry that is not positive.
    for (int j = 0; j < n; ++j) {
        if (columnStart_[j] >= columnStart_[j + 1] || rowIndex_[columnStart_[j]] != j)
            throw std::runtime_error("sparse Cholesky: unexpected factor layout in column " + std::to_string(j));
        if (!(value_[columnStart_[j]] > 0.0))
            throw std::runtime_error("sparse Cholesky: the matrix is not positive definite (column " +
                                     std::to_string(j) + " of the factor)");
    }
#endif
}

void SparseCholesky::solve(std::span<const double> b, std::span<double> x, int count) const
{
    const std::size_t total = static_cast<std::size_t>(size_) * count;
    if (count < 1 || count > 3 || b.size() != total || x.size() != total)
        throw std::invalid_argument("sparse Cholesky: solve with vectors of the wrong size");
    work_.resize(total);
    double* y = work_.data();
    for (int k = 0; k < size_; ++k)
        for (int c = 0; c < count; ++c) y[static_cast<std::size_t>(k) * count + c] = b[static_cast<std::size_t>(permutation_[k]) * count + c];
    const int* start = columnStart_.data();
    const int* index = rowIndex_.data();
    const double* value = value_.data();
    auto sweep = [&](auto components) {
        constexpr int dim = decltype(components)::value;
        // L y = P b, column by column (scatter).
        for (int j = 0; j < size_; ++j) {
            double* yj = y + static_cast<std::size_t>(j) * dim;
            const double inverse = 1.0 / value[start[j]];
            double v[dim];
            for (int c = 0; c < dim; ++c) v[c] = yj[c] *= inverse;
            for (int p = start[j] + 1; p < start[j + 1]; ++p) {
                double* yi = y + static_cast<std::size_t>(index[p]) * dim;
                for (int c = 0; c < dim; ++c) yi[c] -= value[p] * v[c];
            }
        }
        // Lᵀ z = y, backwards (gather).
        for (int j = size_ - 1; j >= 0; --j) {
            double v[dim];
            double* yj = y + static_cast<std::size_t>(j) * dim;
            for (int c = 0; c < dim; ++c) v[c] = yj[c];
            for (int p = start[j] + 1; p < start[j + 1]; ++p) {
                const double* yi = y + static_cast<std::size_t>(index[p]) * dim;
                for (int c = 0; c < dim; ++c) v[c] -= value[p] * yi[c];
            }
            const double inverse = 1.0 / value[start[j]];
            for (int c = 0; c < dim; ++c) yj[c] = v[c] * inverse;
        }
    };
    switch (count) {
    case 1: sweep(std::integral_constant<int, 1>{}); break;
    case 2: sweep(std::integral_constant<int, 2>{}); break;
    case 3: sweep(std::integral_constant<int, 3>{}); break;
    default: break;
    }
    for (int k = 0; k < size_; ++k)
        for (int c = 0; c < count; ++c) x[static_cast<std::size_t>(permutation_[k]) * count + c] = y[static_cast<std::size_t>(k) * count + c];
}

} // namespace rbm::motion
