#include "PartThreeVectorCycle.hpp"

#include "ChebyshevSmoothing.hpp"
#include "DistributedAggregation.hpp"

#include <stdexcept>

namespace rbm::motion {

PartThreeVectorCycle::PartThreeVectorCycle(const RbmProblem& problem, Mat laplacian, std::span<const PetscInt> unknownRows)
    : rows_(problem.ownedUnknownCount())
{
    DistributedProlongator prolongator = distributedSmoothedProlongator(laplacian);
    lambda_ = prolongator.jacobiLambda;
    interpolation_ = std::move(prolongator.interpolation);
    coarseOperator_ = galerkinOperator(laplacian, interpolation_);
    fine_ = std::make_unique<SinglePrecisionPartLaplacian>(problem, laplacian, unknownRows);
    inverseDiagonal_.resize(static_cast<std::size_t>(rows_));
    for (int a = 0; a < rows_; ++a) inverseDiagonal_[a] = 1.0 / fine_->diagonal()[a];
    const std::size_t entries = 3 * static_cast<std::size_t>(rows_);
    residual_.assign(entries, 0.0);
    direction_.assign(entries, 0.0);
    product_.assign(entries, 0.0);

    // The fine level's aggregation already follows the strong couplings only
    // (SmoothedAggregation.hpp); GAMG's on the coarse level drops the weak ones (createGamgCycle).
    coarseOptions_ = std::make_unique<InheritedOptions>("reduced_cycle_coarse");
    coarse_ = createGamgCycle(coarseOperator_, *coarseOptions_);
    RBM_CHECK_PETSC(MatCreateVecs(interpolation_, coarseRightHandSide_.out(), fineComponent_.out()));
    RBM_CHECK_PETSC(VecDuplicate(coarseRightHandSide_, coarseSolution_.out()));
}

PetscInt PartThreeVectorCycle::coarseRows() const
{
    PetscInt rows = 0, columns = 0;
    RBM_CHECK_PETSC(MatGetSize(coarseOperator_, &rows, &columns));
    return rows;
}

void PartThreeVectorCycle::smooth(double* x, const double* b, bool zeroGuess)
{
    constexpr int degree = 2;
    chebyshevSmooth(rows_, lambda_, degree, inverseDiagonal_.data(), b, x, zeroGuess, residual_.data(),
                    direction_.data(), product_.data(), 0 /* one thread: a rank is a core */,
                    [&](const double* in, double* out) { fine_->multiplyThree(in, out); });
}

// x += P (Pᵀ K P)⁻¹ Pᵀ (b − K x) by component, the residual in residual_.
void PartThreeVectorCycle::coarseCorrection(double* x)
{
    for (int c = 0; c < 3; ++c) {
        double* component = nullptr;
        RBM_CHECK_PETSC(VecGetArray(fineComponent_, &component));
        for (int row = 0; row < rows_; ++row) component[row] = residual_[3 * static_cast<std::size_t>(row) + c];
        RBM_CHECK_PETSC(VecRestoreArray(fineComponent_, &component));
        RBM_CHECK_PETSC(MatMultTranspose(interpolation_, fineComponent_, coarseRightHandSide_));
        RBM_CHECK_PETSC(KSPSolve(coarse_, coarseRightHandSide_, coarseSolution_));
        RBM_CHECK_PETSC(MatMult(interpolation_, coarseSolution_, fineComponent_));
        const double* correction = nullptr;
        RBM_CHECK_PETSC(VecGetArrayRead(fineComponent_, &correction));
        for (int row = 0; row < rows_; ++row) x[3 * static_cast<std::size_t>(row) + c] += correction[row];
        RBM_CHECK_PETSC(VecRestoreArrayRead(fineComponent_, &correction));
    }
}

void PartThreeVectorCycle::apply(std::span<const double> r, std::span<double> z)
{
    const std::size_t entries = 3 * static_cast<std::size_t>(rows_);
    if (r.size() != entries || z.size() != entries)
        throw std::invalid_argument("PartThreeVectorCycle::apply: 3 entries per owned unknown expected");
    smooth(z.data(), r.data(), true);
    fine_->multiplyThree(z.data(), residual_.data());
    for (std::size_t k = 0; k < entries; ++k) residual_[k] = r[k] - residual_[k];
    coarseCorrection(z.data());
    smooth(z.data(), r.data(), false);
}

} // namespace rbm::motion
