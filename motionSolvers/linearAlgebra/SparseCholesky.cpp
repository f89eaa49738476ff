#include "SparseCholesky.hpp"

#include "ReadAhead.hpp"
#include "ThreadCount.hpp"
#include "VectorInstructions.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

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

// The upper triangle in compressed columns: entry (i, j), i ≤ j, is A(j, i) of row j
// (A is symmetric), sorted by row within each column.
void copyUpperTriangle(CholmodSession& session, int n, std::span<const int> rowOffsets, std::span<const int> columns,
                       std::span<const double> values)
{
    std::size_t upperCount = 0;
    for (int row = 0; row < n; ++row)
        for (int position = rowOffsets[row]; position < rowOffsets[row + 1]; ++position)
            if (columns[position] <= row) ++upperCount;
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
}

// CHOLMOD's supernodal factor of the session's matrix, checked positive definite and supernodal.
void factorise(CholmodSession& session, int n)
{
    // Always supernodal, so that there is one layout to copy (a small matrix CHOLMOD would
    // factorise simplicially costs a few microseconds either way).
    session.common()->supernodal = CHOLMOD_SUPERNODAL;
    {
        // Debian's CHOLMOD (SuiteSparse 5.12) asks for teams of CHOLMOD_OMP_NUM_THREADS,
        // compiled as 4, whatever OMP_NUM_THREADS says (ThreadCount.hpp has the figures).
        constexpr int cholmodTeamSize = 4;
        const LibraryTeamsWithinThreadCount withinThreadCount(cholmodTeamSize);
        session.factor_ = cholmod_analyze(session.matrix_, session.common());
        session.check("ordering (cholmod_analyze)");
        cholmod_factorize(session.matrix_, session.factor_, session.common());
        session.check("factorising (cholmod_factorize)");
    }
    if (session.common()->status == CHOLMOD_NOT_POSDEF || session.factor_->minor < static_cast<std::size_t>(n))
        throw std::runtime_error("sparse Cholesky: the matrix is not positive definite (column " +
                                 std::to_string(session.factor_->minor) + ")");
    if (!session.factor_->is_super)
        throw std::runtime_error("sparse Cholesky: CHOLMOD returned a simplicial factor where a supernodal one was asked for");
}

// rbm's supernodal layout of CHOLMOD's factor (see SparseCholesky's members).
struct FactorLayout {
    std::vector<int>& supernodeStart;
    std::vector<int>& belowStart;
    std::vector<int>& belowRow;
    std::vector<std::size_t>& valueStart;
};

// Fills the layout's starts and sizes belowRow; returns the number of entries rbm keeps.
std::size_t computeLayout(const cholmod_factor& factor, const FactorLayout& layout)
{
    const auto* super = static_cast<const int*>(factor.super);
    const auto* rowPointer = static_cast<const int*>(factor.pi);
    const std::size_t supernodes = factor.nsuper;
    layout.supernodeStart.assign(super, super + supernodes + 1);
    layout.belowStart.assign(supernodes + 1, 0);
    layout.valueStart.assign(supernodes + 1, 0);
    std::size_t belowTotal = 0, valueTotal = 0;
    for (std::size_t supernode = 0; supernode < supernodes; ++supernode) {
        const std::size_t width = static_cast<std::size_t>(super[supernode + 1] - super[supernode]);
        const std::size_t below = static_cast<std::size_t>(rowPointer[supernode + 1] - rowPointer[supernode]) - width;
        belowTotal += below;
        valueTotal += width * (width + 1) / 2 + below * width;
        layout.belowStart[supernode + 1] = static_cast<int>(belowTotal);
        layout.valueStart[supernode + 1] = valueTotal;
    }
    layout.belowRow.resize(belowTotal);
    return valueTotal;
}

// Written straight in the kept precision: no second copy of L at the peak (CHOLMOD's own
// factor is still alive here). With `scratch`, each supernode's block is copied there
// first: the single-precision entries are then written over CHOLMOD's own (below).
template <typename Entry>
void copyFactor(const cholmod_factor& factor, const FactorLayout& layout, Entry* values, std::vector<double>* scratch)
{
    const auto* super = static_cast<const int*>(factor.super);
    const auto* rowPointer = static_cast<const int*>(factor.pi);
    const auto* valuePointer = static_cast<const int*>(factor.px);
    const auto* rows = static_cast<const int*>(factor.s);
    const auto* factorValues = static_cast<const double*>(factor.x);
    const std::size_t supernodes = factor.nsuper;
    for (std::size_t supernode = 0; supernode < supernodes; ++supernode) {
        const int first = super[supernode];
        const int width = super[supernode + 1] - first;
        const int rowCount = rowPointer[supernode + 1] - rowPointer[supernode];
        const int* rowList = rows + rowPointer[supernode];
        // CHOLMOD's block: column-major, rowCount rows, its first `width` rows the
        // supernode's own columns.
        const double* block = factorValues + valuePointer[supernode];
        if (scratch) {
            scratch->assign(block, block + static_cast<std::size_t>(rowCount) * width);
            block = scratch->data();
        }
        auto entry = [&](int row, int column) { return block[static_cast<std::size_t>(column) * rowCount + row]; };
        Entry* out = values + layout.valueStart[supernode];
        for (int r = 0; r < width; ++r) {
            if (rowList[r] != first + r)
                throw std::runtime_error("sparse Cholesky: unexpected factor layout in supernode " +
                                         std::to_string(supernode));
            for (int c = 0; c < r; ++c) *out++ = static_cast<Entry>(entry(r, c));
            const double diagonal = entry(r, r);
            if (!(diagonal > 0.0))
                throw std::runtime_error("sparse Cholesky: the matrix is not positive definite (column " +
                                         std::to_string(first + r) + " of the factor)");
            *out++ = static_cast<Entry>(1.0 / diagonal);
        }
        int* belowOut = layout.belowRow.data() + layout.belowStart[supernode];
        for (int r = width; r < rowCount; ++r) *belowOut++ = rowList[r];
        for (int c = 0; c < width; ++c)
            for (int r = width; r < rowCount; ++r) *out++ = static_cast<Entry>(entry(r, c));
    }
}

// Whether CHOLMOD's supernode blocks lie back to back from the start of its real array.
bool blocksContiguous(const cholmod_factor& factor)
{
    const auto* super = static_cast<const int*>(factor.super);
    const auto* rowPointer = static_cast<const int*>(factor.pi);
    const auto* valuePointer = static_cast<const int*>(factor.px);
    const std::size_t supernodes = factor.nsuper;
    bool contiguous = factor.xtype == CHOLMOD_REAL && valuePointer[0] == 0;
    for (std::size_t supernode = 0; supernode < supernodes && contiguous; ++supernode)
        contiguous = valuePointer[supernode + 1] - valuePointer[supernode] ==
                     (rowPointer[supernode + 1] - rowPointer[supernode]) * (super[supernode + 1] - super[supernode]);
    return contiguous;
}

// The single-precision entries written over CHOLMOD's own array, which is taken from the
// factor and shrunk; returns it (SuiteSparse-allocated).
float* copyFactorInPlace(CholmodSession& session, const FactorLayout& layout, std::size_t valueTotal)
{
    std::vector<double> scratch;
    float* values = static_cast<float*>(session.factor_->x);
    copyFactor(*session.factor_, layout, values, &scratch);
    session.factor_->x = nullptr;  // rbm's now (CHOLMOD frees no null array)
    int shrunk = 0;
    void* kept = SuiteSparse_realloc(valueTotal, 2 * session.factor_->xsize, sizeof(float), values, &shrunk);
    return static_cast<float*>(kept);
}

} // namespace
#endif

SparseCholesky::SparseCholesky(int n, std::span<const int> rowOffsets, std::span<const int> columns,
                               std::span<const double> values, FactorPrecision precision)
    : size_(n), precision_(precision)
{
#if !defined(RBM_HAVE_CHOLMOD)
    (void)rowOffsets;
    (void)columns;
    (void)values;
    (void)precision;
    throw std::runtime_error("sparse Cholesky: this build has no CHOLMOD (install libsuitesparse-dev and rebuild)");
#else
    if (n < 0 || rowOffsets.size() != static_cast<std::size_t>(n) + 1 || columns.size() != values.size() ||
        static_cast<std::size_t>(rowOffsets[n]) != columns.size())
        throw std::invalid_argument("sparse Cholesky: inconsistent compressed rows");
    CholmodSession session;
    copyUpperTriangle(session, n, rowOffsets, columns, values);
    factorise(session, n);
    const cholmod_factor& factor = *session.factor_;
    const auto* permutation = static_cast<const int*>(factor.Perm);
    const FactorLayout layout{supernodeStart_, belowStart_, belowRow_, valueStart_};
    const std::size_t valueTotal = computeLayout(factor, layout);
    if (precision_ == FactorPrecision::single) {
        // Over CHOLMOD's own array, which rbm then keeps (shrunk to the single-precision
        // entries): no second allocation of L's size. Supernode s's entries start at float
        // valueStart_[s] ≤ CHOLMOD's double valuePointer[s] (rbm stores the triangle, not the
        // square, of the diagonal block), so they never reach a later supernode's block; the
        // supernode's own block is read into scratch first. A second array would be fresh
        // pages of the factor's size, which the kernel zeroes, a large part of the set-up on
        // big 2D meshes (rbmBenchmark's quad2D case at 10⁶ nodes).
        if (blocksContiguous(factor) && valueTotal > 0) {
            singleValue_.reset(copyFactorInPlace(session, layout, valueTotal));
        } else {
            singleValue_.reset(static_cast<float*>(SuiteSparse_malloc(std::max<std::size_t>(valueTotal, 1), sizeof(float))));
            if (!singleValue_) throw std::runtime_error("sparse Cholesky: out of memory for the factor's entries");
            copyFactor(factor, layout, singleValue_.get(), nullptr);
        }
    } else {
        value_.resize(valueTotal);
        copyFactor(factor, layout, value_.data(), nullptr);
    }
    permutation_.assign(permutation, permutation + n);
#endif
}

void SparseCholesky::FreeEntries::operator()(float* entries) const
{
#if defined(RBM_HAVE_CHOLMOD)
    SuiteSparse_free(entries);
#else
    (void)entries;
#endif
}

namespace {

// The kernels below are inlined into both variants of the sweeps (sweepAvx, sweepBaseline), so
// each is compiled for that variant's instruction set.
#if defined(__GNUC__)
#define RBM_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define RBM_ALWAYS_INLINE inline
#endif

// For every component q < dim: out[q] = Σ_c a[c] b[q·stride + c], in four interleaved partial
// sums (independent chains the CPU overlaps) and all components in one pass over a. The order
// of each component's sum is fixed: its result does not depend on dim.
template <int dim, typename Entry>
RBM_ALWAYS_INLINE void dotProducts(const Entry* __restrict a, const double* __restrict b, std::size_t stride, int count,
                                   double* __restrict out)
{
    double sum[dim][4] = {};
    int c = 0;
    for (; c + 4 <= count; c += 4) {
        const double a0 = a[c], a1 = a[c + 1], a2 = a[c + 2], a3 = a[c + 3];
        for (int q = 0; q < dim; ++q) {
            const double* bq = b + q * stride + c;
            sum[q][0] += a0 * bq[0];
            sum[q][1] += a1 * bq[1];
            sum[q][2] += a2 * bq[2];
            sum[q][3] += a3 * bq[3];
        }
    }
    for (; c < count; ++c)
        for (int q = 0; q < dim; ++q) sum[q][0] += a[c] * b[q * stride + c];
    for (int q = 0; q < dim; ++q) out[q] = (sum[q][0] + sum[q][1]) + (sum[q][2] + sum[q][3]);
}

// For every component q < dim: b[q·stride + c] −= a[c] factor[q], c < count, in one pass over a.
template <int dim, typename Entry>
RBM_ALWAYS_INLINE void subtractMultiples(const Entry* __restrict a, const double* __restrict factor, double* __restrict b,
                                         std::size_t stride, int count)
{
    for (int c = 0; c < count; ++c) {
        const double entry = a[c];
        for (int q = 0; q < dim; ++q) b[q * stride + c] -= entry * factor[q];
    }
}

#if defined(__x86_64__)
// The products with the block B of the rows below a supernode (column-major, rows × columns),
// for single-precision entries in the sweeps' AVX variant. The generic code below goes column
// by column through a work vector (`gathered`), one load and one store of every row's partial
// sum per entry of B, which bounds the sweep at a small fraction of what the cache delivers
// even with the factor in cache. Here the partial sums stay in registers. The same operations
// in the same order, no FMA, so the same bits as the generic code
// (SparseCholesky.AvxAndBaselineSweepsAgreeBitForBit). Written with intrinsics because the
// compiler vectorised the plain loops across the wrong index. Not inlined (one call per
// supernode), so that only these functions need the AVX2 target.
//
// y_{row[t]} −= Σ_c B_tc x_c, x the supernode's values (component q at x[q·columns + c]):
// eight rows at a time, the columns in order, each row's sum formed as the generic code forms
// it (0 − B_t0 x_0 − B_t1 x_1 …, then added to y; the generic code's + and − swapped give the
// same rounding).
template <int dim>
[[gnu::target("avx2")]] void subtractBlockProductAvx(const float* __restrict block, int rows, int columns,
                                                     const double* __restrict x, const int* __restrict row,
                                                     double* __restrict y)
{
    int t = 0;
    for (; t + 8 <= rows; t += 8) {
        __m256d low[dim], high[dim];
        for (int q = 0; q < dim; ++q) low[q] = high[q] = _mm256_setzero_pd();
        const float* column = block + t;
        for (int c = 0; c < columns; ++c, column += rows) {
            const __m256d entryLow = _mm256_cvtps_pd(_mm_loadu_ps(column));
            const __m256d entryHigh = _mm256_cvtps_pd(_mm_loadu_ps(column + 4));
            for (int q = 0; q < dim; ++q) {
                const __m256d value = _mm256_broadcast_sd(x + q * columns + c);
                low[q] = _mm256_sub_pd(low[q], _mm256_mul_pd(entryLow, value));
                high[q] = _mm256_sub_pd(high[q], _mm256_mul_pd(entryHigh, value));
            }
        }
        alignas(32) double sum[dim][8];
        for (int q = 0; q < dim; ++q) {
            _mm256_store_pd(sum[q], low[q]);
            _mm256_store_pd(sum[q] + 4, high[q]);
        }
        for (int i = 0; i < 8; ++i) {
            double* yi = y + static_cast<std::size_t>(row[t + i]) * dim;
            for (int q = 0; q < dim; ++q) yi[q] += sum[q][i];
        }
    }
    for (; t < rows; ++t) {
        double sum[dim] = {};
        for (int c = 0; c < columns; ++c)
            for (int q = 0; q < dim; ++q) sum[q] -= static_cast<double>(block[static_cast<std::size_t>(c) * rows + t]) * x[q * columns + c];
        double* yi = y + static_cast<std::size_t>(row[t]) * dim;
        for (int q = 0; q < dim; ++q) yi[q] += sum[q];
    }
}

// x_c −= Σ_t B_tc g_t, g the rows' gathered values (component q at g[q·rows + t]): each
// column's sum as dotProducts forms it (four partial sums by t mod 4, the rest into the first,
// then (s0 + s1) + (s2 + s3)); four columns at a time share the loads of g.
template <int dim>
[[gnu::target("avx2")]] void subtractTransposedBlockProductAvx(const float* __restrict block, int rows, int columns,
                                                               const double* __restrict g, double* __restrict x)
{
    constexpr int group = 4;
    int c = 0;
    for (; c + group <= columns; c += group) {
        __m256d sum[group][dim];
        for (int k = 0; k < group; ++k)
            for (int q = 0; q < dim; ++q) sum[k][q] = _mm256_setzero_pd();
        const float* column = block + static_cast<std::size_t>(c) * rows;
        int t = 0;
        for (; t + 4 <= rows; t += 4) {
            __m256d values[dim];
            for (int q = 0; q < dim; ++q) values[q] = _mm256_loadu_pd(g + q * rows + t);
            for (int k = 0; k < group; ++k) {
                const __m256d entry = _mm256_cvtps_pd(_mm_loadu_ps(column + static_cast<std::size_t>(k) * rows + t));
                for (int q = 0; q < dim; ++q) sum[k][q] = _mm256_add_pd(sum[k][q], _mm256_mul_pd(entry, values[q]));
            }
        }
        for (int k = 0; k < group; ++k)
            for (int q = 0; q < dim; ++q) {
                alignas(32) double lanes[4];
                _mm256_store_pd(lanes, sum[k][q]);
                for (int rest = t; rest < rows; ++rest)
                    lanes[0] += static_cast<double>(column[static_cast<std::size_t>(k) * rows + rest]) * g[q * rows + rest];
                x[q * columns + c + k] -= (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
            }
    }
    for (; c < columns; ++c) {
        double sums[dim];
        dotProducts<dim>(block + static_cast<std::size_t>(c) * rows, g, static_cast<std::size_t>(rows), rows, sums);
        for (int q = 0; q < dim; ++q) x[q * columns + c] -= sums[q];
    }
}
constexpr bool haveAvxBlockKernels = true;
#else
constexpr bool haveAvxBlockKernels = false;  // declared only: never called on such machines
template <int dim>
void subtractBlockProductAvx(const float*, int, int, const double*, const int*, double*);
template <int dim>
void subtractTransposedBlockProductAvx(const float*, int, int, const double*, double*);
#endif

// How far ahead of the current supernode the sweeps request L's entries: about one supernode
// of the airfoil's factor. 1 to 4 KB do about equally well on the airfoil pitching series
// (rbmBenchmark --cases airfoil), 8 KB worse.
constexpr std::ptrdiff_t factorLookaheadBytes = 2048;

// The supernodal factor's index arrays (SparseCholesky's members), for the sweeps below.
struct SupernodalLayout {
    int supernodes;
    const int* supernodeStart;
    const int* belowStart;
    const int* belowRow;
    const std::size_t* valueStart;
};

// The two triangular sweeps over y (size × dim, interleaved) with L's entries `values`;
// `local` holds the widest supernode's columns, `gathered` the longest list of rows below a
// supernode, dim values each, one component after the other.
template <int dim, bool avx, typename Entry>
RBM_ALWAYS_INLINE void sweepSupernodes(const SupernodalLayout& factor, const Entry* values, double* y, double* local,
                                       double* gathered)
{
    constexpr bool avxBlocks = avx && haveAvxBlockKernels && std::is_same_v<Entry, float>;
    // L's entries are read once per sweep in address order (backwards in the second), a
    // supernode of the airfoil's factor about 2 KB: in a time step the factor comes from
    // memory, and the processor's own prefetching does not keep up with these short runs. So
    // the sweeps request the entries factorLookaheadBytes ahead (ReadAhead.hpp).
    auto byteOffset = [&](int supernode) {
        return static_cast<std::ptrdiff_t>(factor.valueStart[supernode] * sizeof(Entry));
    };
    ReadAhead forward(values, byteOffset(factor.supernodes), factorLookaheadBytes);
    // L y = P b, supernode by supernode.
    for (int s = 0; s < factor.supernodes; ++s) {
        forward.reach(byteOffset(s), byteOffset(s + 1));
        const int first = factor.supernodeStart[s], width = factor.supernodeStart[s + 1] - first;
        const int belowBegin = factor.belowStart[s], belowCount = factor.belowStart[s + 1] - belowBegin;
        const auto* entry = values + factor.valueStart[s];
        for (int r = 0; r < width; ++r)
            for (int q = 0; q < dim; ++q) local[q * width + r] = y[static_cast<std::size_t>(first + r) * dim + q];
        // The diagonal block: forward substitution, row by row.
        for (int r = 0; r < width; ++r) {
            double sums[dim];
            dotProducts<dim>(entry, local, width, r, sums);
            for (int q = 0; q < dim; ++q) local[q * width + r] = (local[q * width + r] - sums[q]) * entry[r];
            entry += r + 1;
        }
        for (int r = 0; r < width; ++r)
            for (int q = 0; q < dim; ++q) y[static_cast<std::size_t>(first + r) * dim + q] = local[q * width + r];
        // The rows below: the block (column-major) times the supernode's values, one contiguous
        // multiply-add per column into `gathered`, then one update per row.
        if constexpr (avxBlocks) {
            subtractBlockProductAvx<dim>(entry, belowCount, width, local, factor.belowRow + belowBegin, y);
            continue;
        }
        for (int k = 0; k < dim * belowCount; ++k) gathered[k] = 0.0;
        for (int c = 0; c < width; ++c, entry += belowCount) {
            double minus[dim];
            for (int q = 0; q < dim; ++q) minus[q] = -local[q * width + c];
            subtractMultiples<dim>(entry, minus, gathered, static_cast<std::size_t>(belowCount), belowCount);
        }
        for (int t = 0; t < belowCount; ++t) {
            double* yi = y + static_cast<std::size_t>(factor.belowRow[belowBegin + t]) * dim;
            for (int q = 0; q < dim; ++q) yi[q] -= gathered[q * belowCount + t];
        }
    }
    // Lᵀ z = y, supernodes backwards.
    ReadAhead backward(values, byteOffset(factor.supernodes), factorLookaheadBytes, true);
    for (int s = factor.supernodes - 1; s >= 0; --s) {
        backward.reach(byteOffset(s), byteOffset(s + 1));
        const int first = factor.supernodeStart[s], width = factor.supernodeStart[s + 1] - first;
        const int belowBegin = factor.belowStart[s], belowCount = factor.belowStart[s + 1] - belowBegin;
        for (int r = 0; r < width; ++r)
            for (int q = 0; q < dim; ++q) local[q * width + r] = y[static_cast<std::size_t>(first + r) * dim + q];
        // The rows below: their values gathered once, then one contiguous dot product per
        // column of the block.
        for (int t = 0; t < belowCount; ++t) {
            const double* yi = y + static_cast<std::size_t>(factor.belowRow[belowBegin + t]) * dim;
            for (int q = 0; q < dim; ++q) gathered[q * belowCount + t] = yi[q];
        }
        const auto* below = values + factor.valueStart[s] + static_cast<std::size_t>(width) * (width + 1) / 2;
        if constexpr (avxBlocks) {
            subtractTransposedBlockProductAvx<dim>(below, belowCount, width, gathered, local);
        } else {
            for (int c = 0; c < width; ++c, below += belowCount) {
                double sums[dim];
                dotProducts<dim>(below, gathered, static_cast<std::size_t>(belowCount), belowCount, sums);
                for (int q = 0; q < dim; ++q) local[q * width + c] -= sums[q];
            }
        }
        // The diagonal block transposed: back substitution, rows from the last, each row's
        // entries subtracted from the columns before it once its value is known.
        const auto* diagonalBlock = values + factor.valueStart[s];
        for (int r = width - 1; r >= 0; --r) {
            const auto* row = diagonalBlock + static_cast<std::size_t>(r) * (r + 1) / 2;
            double known[dim];
            for (int q = 0; q < dim; ++q) known[q] = local[q * width + r] *= row[r];
            subtractMultiples<dim>(row, known, local, width, r);
        }
        for (int r = 0; r < width; ++r)
            for (int q = 0; q < dim; ++q) y[static_cast<std::size_t>(first + r) * dim + q] = local[q * width + r];
    }
}

// Both sweeps for 1–3 right-hand sides with single or double entries; compiled twice below.
template <bool avx>
RBM_ALWAYS_INLINE void sweepAny(const SupernodalLayout& factor, const double* doubleValues, const float* singleValues,
                                int count, double* y, double* local, double* gathered)
{
    if (singleValues) {
        if (count == 1) sweepSupernodes<1, avx>(factor, singleValues, y, local, gathered);
        else if (count == 2) sweepSupernodes<2, avx>(factor, singleValues, y, local, gathered);
        else sweepSupernodes<3, avx>(factor, singleValues, y, local, gathered);
    } else {
        if (count == 1) sweepSupernodes<1, avx>(factor, doubleValues, y, local, gathered);
        else if (count == 2) sweepSupernodes<2, avx>(factor, doubleValues, y, local, gathered);
        else sweepSupernodes<3, avx>(factor, doubleValues, y, local, gathered);
    }
}

// The AVX2 and the baseline variant (src/VectorInstructions.hpp): four doubles per instruction
// instead of two halve the sweeps' arithmetic instructions. No FMA
// in either, so both give the same bits (SparseCholesky.AvxAndBaselineSweepsAgreeBitForBit).
#if defined(__x86_64__)
#define RBM_AVX2_TARGET [[gnu::target("avx2")]]
#else
#define RBM_AVX2_TARGET  // other processors: the same code twice (useAvxKernels() is false there)
#endif
RBM_AVX2_TARGET void sweepAvx(const SupernodalLayout& factor, const double* doubleValues, const float* singleValues,
                              int count, double* y, double* local, double* gathered)
{
    sweepAny<true>(factor, doubleValues, singleValues, count, y, local, gathered);
}
#undef RBM_AVX2_TARGET
void sweepBaseline(const SupernodalLayout& factor, const double* doubleValues, const float* singleValues, int count,
                   double* y, double* local, double* gathered)
{
    sweepAny<false>(factor, doubleValues, singleValues, count, y, local, gathered);
}

} // namespace

void SparseCholesky::solve(std::span<const double> b, std::span<double> x, int count) const
{
    const std::size_t total = static_cast<std::size_t>(size_) * count;
    if (count < 1 || count > 3 || b.size() != total || x.size() != total)
        throw std::invalid_argument("sparse Cholesky: solve with vectors of the wrong size");
    int widest = 0, longest = 0;
    for (std::size_t s = 0; s + 1 < supernodeStart_.size(); ++s) {
        widest = std::max(widest, supernodeStart_[s + 1] - supernodeStart_[s]);
        longest = std::max(longest, belowStart_[s + 1] - belowStart_[s]);
    }
    // y (permuted, interleaved), then per supernode its columns' values and the values of the
    // rows below it, deinterleaved.
    work_.resize(total + (static_cast<std::size_t>(widest) + static_cast<std::size_t>(longest)) * count);
    double* y = work_.data();
    double* local = y + total;
    double* gathered = local + static_cast<std::size_t>(widest) * count;
    for (int k = 0; k < size_; ++k)
        for (int c = 0; c < count; ++c) y[static_cast<std::size_t>(k) * count + c] = b[static_cast<std::size_t>(permutation_[k]) * count + c];
    const SupernodalLayout layout{supernodeCount(), supernodeStart_.data(), belowStart_.data(), belowRow_.data(),
                                  valueStart_.data()};
    const float* single = precision_ == FactorPrecision::single ? singleValue_.get() : nullptr;
    if (useAvxKernels()) sweepAvx(layout, value_.data(), single, count, y, local, gathered);
    else sweepBaseline(layout, value_.data(), single, count, y, local, gathered);
    for (int k = 0; k < size_; ++k)
        for (int c = 0; c < count; ++c) x[static_cast<std::size_t>(permutation_[k]) * count + c] = y[static_cast<std::size_t>(k) * count + c];
}

} // namespace rbm::motion
