#include "ThreeVectorMultigrid.hpp"

#include "ChebyshevSmoothing.hpp"

#include "BlockRowLayout.hpp"
#include "PetscSupport.hpp"
#include "ThreadCount.hpp"
#include "VectorInstructions.hpp"

#include <petscksp.h>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rbm::motion {

namespace {

constexpr int coarsestRowLimit = 4000;
// rbm's own hierarchy stops at this many rows (its coarsest level is factorised densely: a few
// milliseconds here, against GAMG's 50 rows and one level more).
constexpr int aggregationCoarsestRows = 500;
constexpr int powerIterations = 10;

bool isType(PetscObject object, const char* type)
{
    PetscBool match = PETSC_FALSE;
    RBM_CHECK_PETSC(PetscObjectTypeCompare(object, type, &match));
    return match == PETSC_TRUE;
}

// Any sequential PETSc matrix as CSR (row by row: every type has MatGetRow).
void copyMatrix(Mat matrix, std::vector<int>& offsets, std::vector<int>& columns, std::vector<double>& values)
{
    PetscInt rows = 0, cols = 0;
    RBM_CHECK_PETSC(MatGetSize(matrix, &rows, &cols));
    offsets.assign(1, 0);
    offsets.reserve(static_cast<std::size_t>(rows) + 1);
    columns.clear();
    values.clear();
    for (PetscInt row = 0; row < rows; ++row) {
        PetscInt count = 0;
        const PetscInt* rowColumns = nullptr;
        const PetscScalar* rowValues = nullptr;
        RBM_CHECK_PETSC(MatGetRow(matrix, row, &count, &rowColumns, &rowValues));
        for (PetscInt k = 0; k < count; ++k) {
            columns.push_back(static_cast<int>(rowColumns[k]));
            values.push_back(rowValues[k]);
        }
        RBM_CHECK_PETSC(MatRestoreRow(matrix, row, &count, &rowColumns, &rowValues));
        offsets.push_back(static_cast<int>(columns.size()));
    }
}

} // namespace

std::unique_ptr<ThreeVectorMultigrid> ThreeVectorMultigrid::buildAggregation(std::span<const int> rowOffsets,
                                                                           std::span<const int> columns,
                                                                           std::span<const double> values)
{
    if (rowOffsets.size() < 2) return nullptr;
    try {
        return std::make_unique<ThreeVectorMultigrid>(
            rowOffsets, columns, values, buildSmoothedAggregation(rowOffsets, columns, values, aggregationCoarsestRows));
    } catch (const std::runtime_error&) {
        return nullptr;
    }
}

std::unique_ptr<ThreeVectorMultigrid> ThreeVectorMultigrid::build(std::span<const int> rowOffsets,
                                                                std::span<const int> columns,
                                                                std::span<const double> values,
                                                                std::string_view solverName)
{
    PetscMPIInt ranks = 1;
    RBM_CHECK_PETSC(MPI_Comm_size(solverCommunicator(), &ranks));
    if (ranks != 1) return nullptr;
    static_assert(sizeof(PetscInt) == sizeof(int), "PETSc's indices must be 32-bit ints to wrap the CSR arrays");
    const InheritedOptions options(solverName);
    PetscKsp ksp;
    RBM_CHECK_PETSC(KSPCreate(PETSC_COMM_SELF, ksp.out()));
    RBM_CHECK_PETSC(KSPSetType(ksp, KSPCG));
    PC pc = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(ksp, &pc));
    RBM_CHECK_PETSC(PCSetType(pc, PCGAMG));
    configureFromOptions(ksp.get(), options);
    const PetscObject pcObject = reinterpret_cast<PetscObject>(pc);
    if (!isType(pcObject, PCGAMG) && !isType(pcObject, PCMG)) return nullptr;
    // The hierarchy: rbm's smoothed aggregation (SmoothedAggregation.hpp) unless
    // -rbm_<solverName>_cycle_hierarchy gamg asks for PCGAMG's (then GAMG's options apply).
    char hierarchy[16] = "aggregation";
    RBM_CHECK_PETSC(PetscOptionsGetString(nullptr, options.prefix().c_str(), "-cycle_hierarchy", hierarchy,
                                          sizeof(hierarchy), nullptr));
    PetscInt degree = 2;
    RBM_CHECK_PETSC(PetscOptionsGetInt(nullptr, options.prefix().c_str(), "-cycle_degree", &degree, nullptr));
    const std::string hierarchyName = hierarchy;
    if (hierarchyName != "gamg" && hierarchyName != "aggregation")
        throw std::invalid_argument("-" + options.prefix() + "cycle_hierarchy " + hierarchyName +
                                    ": expected aggregation or gamg");
    if (hierarchyName == "aggregation" && isType(pcObject, PCGAMG)) {
        try {
            auto cycle = std::make_unique<ThreeVectorMultigrid>(
                rowOffsets, columns, values, buildSmoothedAggregation(rowOffsets, columns, values, aggregationCoarsestRows));
            cycle->degree_ = std::max<int>(1, static_cast<int>(degree));
            return cycle;
        } catch (const std::runtime_error&) {
            return nullptr;
        }
    }
    const PetscInt rows = static_cast<PetscInt>(rowOffsets.size()) - 1;
    PetscMat matrix;
    // PETSc only reads the arrays (no MatSetValues on this matrix).
    RBM_CHECK_PETSC(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, rows, rows, const_cast<PetscInt*>(rowOffsets.data()),
                                              const_cast<PetscInt*>(columns.data()),
                                              const_cast<PetscScalar*>(values.data()), matrix.out()));
    RBM_CHECK_PETSC(MatSetOption(matrix, MAT_SYMMETRIC, PETSC_TRUE));
    RBM_CHECK_PETSC(MatSetOption(matrix, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
    RBM_CHECK_PETSC(MatSetOption(matrix, MAT_SPD, PETSC_TRUE));
    RBM_CHECK_PETSC(KSPSetOperators(ksp, matrix, matrix));
    RBM_CHECK_PETSC(KSPSetUp(ksp));
    RBM_CHECK_PETSC(PCSetUp(pc));
    try {
        auto cycle = std::make_unique<ThreeVectorMultigrid>(pc, rowOffsets, columns, values);
        cycle->degree_ = std::max<int>(1, static_cast<int>(degree));
        return cycle;
    } catch (const std::runtime_error&) {
        return nullptr;
    }
}

ThreeVectorMultigrid::ThreeVectorMultigrid(PC pc, std::span<const int> rowOffsets, std::span<const int> columns,
                                           std::span<const double> values)
{
    const PetscObject object = reinterpret_cast<PetscObject>(pc);
    if (!isType(object, PCGAMG) && !isType(object, PCMG))
        throw std::runtime_error("ThreeVectorMultigrid: the preconditioner is not multigrid");
    PetscMPIInt ranks = 1;
    RBM_CHECK_PETSC(MPI_Comm_size(PetscObjectComm(object), &ranks));
    if (ranks != 1) throw std::runtime_error("ThreeVectorMultigrid: one rank only");
    PetscInt petscLevels = 0;
    RBM_CHECK_PETSC(PCMGGetLevels(pc, &petscLevels));
    if (petscLevels < 1) throw std::runtime_error("ThreeVectorMultigrid: no levels");
    std::vector<AggregationLevel> coarser(static_cast<std::size_t>(petscLevels - 1));
    for (int index = 0; index + 1 < petscLevels; ++index) {
        const PetscInt petscLevel = petscLevels - 1 - index;  // PETSc: 0 = coarsest
        Mat interpolation = nullptr;
        RBM_CHECK_PETSC(PCMGGetInterpolation(pc, petscLevel, &interpolation));
        copyMatrix(interpolation, coarser[index].interpolation.offsets, coarser[index].interpolation.columns,
                   coarser[index].interpolation.values);
        KSP smoother = nullptr;
        Mat operatorMatrix = nullptr;
        RBM_CHECK_PETSC(PCMGGetSmoother(pc, petscLevel - 1, &smoother));
        RBM_CHECK_PETSC(KSPGetOperators(smoother, &operatorMatrix, nullptr));
        copyMatrix(operatorMatrix, coarser[index].coarseOperator.offsets, coarser[index].coarseOperator.columns,
                   coarser[index].coarseOperator.values);
    }
    setUp(rowOffsets, columns, values, std::move(coarser));
}

ThreeVectorMultigrid::ThreeVectorMultigrid(std::span<const int> rowOffsets, std::span<const int> columns,
                                           std::span<const double> values, std::vector<AggregationLevel> coarser)
{
    setUp(rowOffsets, columns, values, std::move(coarser));
}

void ThreeVectorMultigrid::setUp(std::span<const int> rowOffsets, std::span<const int> columns,
                                 std::span<const double> values, std::vector<AggregationLevel> coarser)
{
    const int levelTotal = static_cast<int>(coarser.size()) + 1;
    levels_.resize(static_cast<std::size_t>(levelTotal));
    for (int index = 0; index < levelTotal; ++index) {
        Level& level = levels_[index];
        if (index == 0) {
            level.rows = static_cast<int>(rowOffsets.size()) - 1;
            level.offsets = rowOffsets.data();
            level.columns = columns.data();
            level.values = values.data();
        } else {
            level.owned = std::move(coarser[index - 1].coarseOperator);
            level.rows = level.owned.rows();
            level.offsets = level.owned.offsets.data();
            level.columns = level.owned.columns.data();
            level.values = level.owned.values.data();
        }
        if (index + 1 < levelTotal) {
            Csr& p = level.interpolation;
            p = std::move(coarser[index].interpolation);
            if (p.rows() != level.rows) throw std::runtime_error("ThreeVectorMultigrid: interpolation does not match");
            const int coarseRows = coarser[index].coarseOperator.rows();
            for (int column : p.columns)
                if (column < 0 || column >= coarseRows) throw std::runtime_error("ThreeVectorMultigrid: interpolation does not match");
            // Its transpose, rows in order (restriction gathers).
            Csr& r = level.restriction;
            r.offsets.assign(static_cast<std::size_t>(coarseRows) + 1, 0);
            for (int column : p.columns) ++r.offsets[column + 1];
            for (int row = 0; row < coarseRows; ++row) r.offsets[row + 1] += r.offsets[row];
            r.columns.resize(p.columns.size());
            r.values.resize(p.values.size());
            std::vector<int> next(r.offsets.begin(), r.offsets.end() - 1);
            for (int row = 0; row < level.rows; ++row)
                for (int k = p.offsets[row]; k < p.offsets[row + 1]; ++k) {
                    const int position = next[p.columns[k]]++;
                    r.columns[position] = row;
                    r.values[position] = p.values[k];
                }
        }
        const std::size_t size = static_cast<std::size_t>(level.rows) * 3;
        if (index > 0 || levelTotal == 1) {
            level.rhs.assign(size, 0.0);
            level.solution.assign(size, 0.0);
            level.b = level.rhs.data();
            level.x = level.solution.data();
        }
        level.inverseDiagonal.assign(static_cast<std::size_t>(level.rows), 0.0);
        for (int row = 0; row < level.rows; ++row)
            for (int k = level.offsets[row]; k < level.offsets[row + 1]; ++k)
                if (level.columns[k] == row) level.inverseDiagonal[row] = level.values[k] > 0.0 ? 1.0 / level.values[k] : 0.0;
    }
    for (int index = 1; index < levelTotal; ++index)
        if (static_cast<int>(levels_[index - 1].restriction.offsets.size()) - 1 != levels_[index].rows)
            throw std::runtime_error("ThreeVectorMultigrid: level sizes do not match");

    // Coarsest level: dense Cholesky.
    Level& coarsest = levels_.back();
    const int nc = coarsest.rows;
    if (nc > coarsestRowLimit) throw std::runtime_error("ThreeVectorMultigrid: the coarsest level is too large");
    coarseFactor_.assign(static_cast<std::size_t>(nc) * nc, 0.0);
    for (int row = 0; row < nc; ++row)
        for (int k = coarsest.offsets[row]; k < coarsest.offsets[row + 1]; ++k)
            coarseFactor_[static_cast<std::size_t>(row) * nc + coarsest.columns[k]] = coarsest.values[k];
    for (int j = 0; j < nc; ++j) {
        double* rowJ = coarseFactor_.data() + static_cast<std::size_t>(j) * nc;
        double diagonal = rowJ[j];
        for (int k = 0; k < j; ++k) diagonal -= rowJ[k] * rowJ[k];
        if (!(diagonal > 0.0)) throw std::runtime_error("ThreeVectorMultigrid: the coarsest operator is not positive definite");
        rowJ[j] = std::sqrt(diagonal);
        for (int i = j + 1; i < nc; ++i) {
            double* rowI = coarseFactor_.data() + static_cast<std::size_t>(i) * nc;
            double sum = rowI[j];
            for (int k = 0; k < j; ++k) sum -= rowI[k] * rowJ[k];
            rowI[j] = sum / rowJ[j];
        }
    }
    const std::size_t finest = static_cast<std::size_t>(levels_.front().rows) * 3;
    residual_.assign(finest, 0.0);
    direction_.assign(finest, 0.0);
    product_.assign(finest, 0.0);
    // The finest operator read in single precision (8 instead of 12 bytes an entry, the product
    // being bound by reading it): a faster cycle for a single-precision copy of the finest
    // entries (counted in MemoryEstimate.cpp). A preconditioner of a flexible CG needs no
    // more; the operator stays symmetric.
    if (levels_.size() > 1) {
        Level& fine = levels_.front();
        fine.singleValues.assign(fine.values, fine.values + fine.offsets[fine.rows]);
    }
    for (std::size_t index = 0; index + 1 < levels_.size(); ++index) estimateLambda(levels_[index]);
    // From here on the products read the single-precision copy only (readsFinestValues).
    if (!levels_.front().singleValues.empty()) levels_.front().values = nullptr;
}

double ThreeVectorMultigrid::bytes() const
{
    double total = 8.0 * static_cast<double>(coarseFactor_.size() + residual_.size() + direction_.size() + product_.size());
    for (const Level& level : levels_) {
        for (const Csr* csr : {&level.owned, &level.interpolation, &level.restriction})
            total += 4.0 * static_cast<double>(csr->offsets.size() + csr->columns.size()) + 8.0 * static_cast<double>(csr->values.size());
        total += 8.0 * static_cast<double>(level.inverseDiagonal.size() + level.rhs.size() + level.solution.size()) +
                 4.0 * static_cast<double>(level.singleValues.size());
    }
    return total;
}

namespace {

// y = A x on rows [begin, end), three interleaved vectors; the matrix values in single (single ≠
// nullptr) or double precision.
template <typename Value>
void multiplyRows(int begin, int end, const int* offsets, const int* columns, const Value* values, const double* x,
                  double* y)
{
    for (int row = begin; row < end; ++row) {
        double s0 = 0.0, s1 = 0.0, s2 = 0.0;
        for (int k = offsets[row]; k < offsets[row + 1]; ++k) {
            const double a = static_cast<double>(values[k]);
            const double* xc = x + 3 * static_cast<std::size_t>(columns[k]);
            s0 += a * xc[0];
            s1 += a * xc[1];
            s2 += a * xc[2];
        }
        double* yr = y + 3 * static_cast<std::size_t>(row);
        yr[0] = s0, yr[1] = s1, yr[2] = s2;
    }
}

#if defined(__x86_64__)
// The same with AVX2: a column's three values in one register (a masked load, which does not read
// past the vector's end), one multiply and one add per entry instead of three each. No FMA, so
// every lane rounds as the scalar code does and the result is the same bit for bit. The gain is
// small, since the product is bound by reading the matrix; it shows in the reduced Newton
// solve of rbmBenchmark's twist3D case.
template <typename Value>
[[gnu::target("avx2")]] void multiplyRowsAvx(int begin, int end, const int* offsets, const int* columns,
                                             const Value* values, const double* x, double* y)
{
    const __m256i firstThree = _mm256_set_epi64x(0, -1, -1, -1);
    for (int row = begin; row < end; ++row) {
        __m256d sum = _mm256_setzero_pd();
        for (int k = offsets[row]; k < offsets[row + 1]; ++k) {
            const __m256d a = _mm256_set1_pd(static_cast<double>(values[k]));
            const __m256d xc = _mm256_maskload_pd(x + 3 * static_cast<std::size_t>(columns[k]), firstThree);
            sum = _mm256_add_pd(sum, _mm256_mul_pd(a, xc));
        }
        _mm256_maskstore_pd(y + 3 * static_cast<std::size_t>(row), firstThree, sum);
    }
}
#else
// Other processors: the baseline (useAvxKernels() is false there).
template <typename Value>
void multiplyRowsAvx(int begin, int end, const int* offsets, const int* columns, const Value* values, const double* x,
                     double* y)
{
    multiplyRows(begin, end, offsets, columns, values, x, y);
}
#endif

} // namespace

void ThreeVectorMultigrid::multiply(const Level& level, const double* x, double* y) const
{
    const int rows = level.rows;
    const int* offsets = level.offsets;
    const int* columns = level.columns;
    const double* values = level.values;
    const float* single = level.singleValues.empty() ? nullptr : level.singleValues.data();
    const bool avx = useAvxKernels();
    // Contiguous row ranges, one per thread: every row is its own sum, the same for any thread count.
    forEachThreadRange(rows, worthThreading(static_cast<std::size_t>(offsets[rows])), [&](int begin, int end) {
        if (avx && single) multiplyRowsAvx(begin, end, offsets, columns, single, x, y);
        else if (avx) multiplyRowsAvx(begin, end, offsets, columns, values, x, y);
        else if (single) multiplyRows(begin, end, offsets, columns, single, x, y);
        else multiplyRows(begin, end, offsets, columns, values, x, y);
    });
}

// λ_max(D⁻¹A) by power iteration on three start vectors (deterministic), the largest ratio.
void ThreeVectorMultigrid::estimateLambda(Level& level)
{
    const std::size_t size = static_cast<std::size_t>(level.rows) * 3;
    std::vector<double> finestStart;  // the finest of several levels has no solution vector of its own
    if (level.solution.empty()) finestStart.resize(size);
    std::vector<double>& v = level.solution.empty() ? finestStart : level.solution;
    std::vector<double>& w = residual_;
    for (std::size_t k = 0; k < size; ++k) {
        // A fixed, irregular start (golden-ratio sequence): no eigenvector is missed by symmetry.
        const double phase = static_cast<double>(k) * 0.6180339887498949;
        v[k] = 0.5 + (phase - std::floor(phase));
    }
    double estimate = 0.0;
    for (int iteration = 0; iteration < powerIterations; ++iteration) {
        multiply(level, v.data(), w.data());
        double norms[3] = {}, products[3] = {};
        for (int row = 0; row < level.rows; ++row)
            for (int c = 0; c < 3; ++c) {
                const std::size_t k = 3 * static_cast<std::size_t>(row) + c;
                w[k] *= level.inverseDiagonal[row];
                norms[c] += w[k] * w[k];
                products[c] += v[k] * v[k];
            }
        estimate = 0.0;
        for (int c = 0; c < 3; ++c) estimate = std::max(estimate, std::sqrt(norms[c] / std::max(products[c], 1e-300)));
        for (int c = 0; c < 3; ++c) {
            const double scale = norms[c] > 0.0 ? 1.0 / std::sqrt(norms[c]) : 0.0;
            for (int row = 0; row < level.rows; ++row) v[3 * static_cast<std::size_t>(row) + c] = w[3 * static_cast<std::size_t>(row) + c] * scale;
        }
    }
    level.lambdaMax = estimate > 0.0 ? estimate : 1.0;
    std::fill(v.begin(), v.end(), 0.0);
}

// Chebyshev on D⁻¹A over [0.1 λ, 1.1 λ] from level.solution (zero if zeroGuess) for level.rhs.
void ThreeVectorMultigrid::smooth(Level& level, bool zeroGuess)
{
    chebyshevSmooth(level.rows, level.lambdaMax, degree_, level.inverseDiagonal.data(), level.b, level.x, zeroGuess,
                    residual_.data(), direction_.data(), product_.data(), static_cast<std::size_t>(level.offsets[level.rows]),
                    [&](const double* in, double* out) { multiply(level, in, out); });
}

void ThreeVectorMultigrid::coarseSolve(Level& level)
{
    const int nc = level.rows;
    for (int c = 0; c < 3; ++c) {
        // L y = b, Lᵀ x = y
        std::vector<double>& x = level.solution;
        for (int i = 0; i < nc; ++i) {
            const double* rowI = coarseFactor_.data() + static_cast<std::size_t>(i) * nc;
            double sum = level.rhs[3 * static_cast<std::size_t>(i) + c];
            for (int k = 0; k < i; ++k) sum -= rowI[k] * x[3 * static_cast<std::size_t>(k) + c];
            x[3 * static_cast<std::size_t>(i) + c] = sum / rowI[i];
        }
        for (int i = nc - 1; i >= 0; --i) {
            double sum = x[3 * static_cast<std::size_t>(i) + c];
            for (int k = i + 1; k < nc; ++k) sum -= coarseFactor_[static_cast<std::size_t>(k) * nc + i] * x[3 * static_cast<std::size_t>(k) + c];
            x[3 * static_cast<std::size_t>(i) + c] = sum / coarseFactor_[static_cast<std::size_t>(i) * nc + i];
        }
    }
}

void ThreeVectorMultigrid::cycle(int index)
{
    Level& level = levels_[index];
    if (index + 1 == static_cast<int>(levels_.size())) {
        coarseSolve(level);
        return;
    }
    Level& coarse = levels_[index + 1];
    smooth(level, true);
    // residual b − A x into level.residual, restricted into coarse.rhs
    double* residual = residual_.data();
    multiply(level, level.x, residual);
    const int rows = level.rows;
    const bool threads = worthThreading(static_cast<std::size_t>(level.offsets[rows]));
#pragma omp parallel for schedule(static) if (threads)
    for (int row = 0; row < rows; ++row)
        for (int c = 0; c < 3; ++c) {
            const std::size_t k = 3 * static_cast<std::size_t>(row) + c;
            residual[k] = level.b[k] - residual[k];
        }
    const Csr& restriction = level.restriction;
#pragma omp parallel for schedule(static) if (threads)
    for (int row = 0; row < coarse.rows; ++row) {
        double s0 = 0.0, s1 = 0.0, s2 = 0.0;
        for (int k = restriction.offsets[row]; k < restriction.offsets[row + 1]; ++k) {
            const double a = restriction.values[k];
            const double* rc = residual + 3 * static_cast<std::size_t>(restriction.columns[k]);
            s0 += a * rc[0], s1 += a * rc[1], s2 += a * rc[2];
        }
        double* out = coarse.rhs.data() + 3 * static_cast<std::size_t>(row);
        out[0] = s0, out[1] = s1, out[2] = s2;
    }
    cycle(index + 1);
    // x += P e
    const Csr& interpolation = level.interpolation;
#pragma omp parallel for schedule(static) if (threads)
    for (int row = 0; row < rows; ++row) {
        double s0 = 0.0, s1 = 0.0, s2 = 0.0;
        for (int k = interpolation.offsets[row]; k < interpolation.offsets[row + 1]; ++k) {
            const double a = interpolation.values[k];
            const double* ec = coarse.solution.data() + 3 * static_cast<std::size_t>(interpolation.columns[k]);
            s0 += a * ec[0], s1 += a * ec[1], s2 += a * ec[2];
        }
        double* x = level.x + 3 * static_cast<std::size_t>(row);
        x[0] += s0, x[1] += s1, x[2] += s2;
    }
    smooth(level, false);
}

void ThreeVectorMultigrid::apply(std::span<const double> r, std::span<double> z)
{
    Level& finest = levels_.front();
    const std::size_t size = static_cast<std::size_t>(finest.rows) * 3;
    if (r.size() != size || z.size() != size) throw std::invalid_argument("ThreeVectorMultigrid::apply: sizes do not match");
    if (finest.rhs.empty()) {
        if (r.data() < z.data() + z.size() && z.data() < r.data() + r.size())
            throw std::invalid_argument("ThreeVectorMultigrid::apply: r and z overlap");
        finest.b = r.data();
        finest.x = z.data();
        cycle(0);
        finest.b = nullptr;
        finest.x = nullptr;
        return;
    }
    std::copy(r.begin(), r.end(), finest.rhs.begin());
    cycle(0);
    std::copy(finest.solution.begin(), finest.solution.end(), z.begin());
}

} // namespace rbm::motion
