#pragma once
// The multigrid cycle of a decomposed run's K⁻¹ (PartLaplacian), applied to the three
// displacement components at once: rbm's two-level smoothed aggregation over the ranks
// (DistributedAggregation.hpp), with the fine level in single precision on the part's own
// pattern (SinglePrecisionPartLaplacian.hpp).
//
// Why three at once: the cycle is bound by reading the fine K (27 entries a row for a few flops
// each). PETSc's multigrid takes one vector: three cycles, each with Chebyshev smoothing of
// degree 2 before and after and a residual, read K 15 times for one Newton-CG iteration. Here
// each pass serves three interleaved vectors and the pre-smoothing starts from zero (no product),
// so K is read 4 times, as in the serial 3D cycle (ThreeVectorMultigrid.hpp): on the 2·10⁵-cell
// cube on 2 ranks K's products were a quarter of a rank's time with PETSc's cycle.
//
// The cycle: Chebyshev smoothing of degree 2 on D⁻¹K over [0.1 λ, 1.1 λ] (GAMG's default
// smoother, ThreeVectorMultigrid's formulas), the residual restricted by Pᵀ, one GAMG cycle of
// Pᵀ K P per component (PETSc, options prefix rbm_reduced_cycle_coarse_, couplings below 0.01 of
// the diagonal's scale dropped from its graph by default), the correction interpolated by P,
// the same smoothing after. Pre- and post-smoothing alike: a symmetric operator.

#include "PetscSupport.hpp"
#include "SinglePrecisionPartLaplacian.hpp"

#include <memory>
#include <span>
#include <vector>

namespace rbm::motion {

class PartThreeVectorCycle {
public:
    // laplacian: PETSc's K of the part problem's owned unknown rows, assembled with unknownRows
    // (every unknown node's global row, ghosts included), read here only: P, Pᵀ K P and then the
    // single-precision copy of the fine level, made after the products' transient. The caller may
    // release it afterwards. Collective.
    PartThreeVectorCycle(const RbmProblem& problem, Mat laplacian, std::span<const PetscInt> unknownRows);
    PartThreeVectorCycle(const PartThreeVectorCycle&) = delete;
    PartThreeVectorCycle& operator=(const PartThreeVectorCycle&) = delete;

    // z = C r, 3 interleaved values per owned unknown (r and z must not overlap). Collective.
    void apply(std::span<const double> r, std::span<double> z);
    // λ of D⁻¹K (the smoothing's bounds) and the coarse level's rows over all ranks.
    double jacobiLambda() const { return lambda_; }
    PetscInt coarseRows() const;
    const SinglePrecisionPartLaplacian& fineLevel() const { return *fine_; }

private:
    void smooth(double* x, const double* b, bool zeroGuess);
    void coarseCorrection(double* x);

    std::unique_ptr<SinglePrecisionPartLaplacian> fine_;
    int rows_ = 0;
    double lambda_ = 1.0;
    std::vector<double> inverseDiagonal_;
    PetscMat interpolation_, coarseOperator_;
    PetscKsp coarse_;
    std::unique_ptr<InheritedOptions> coarseOptions_;
    PetscVec fineComponent_, coarseRightHandSide_, coarseSolution_;
    std::vector<double> residual_, direction_, product_;  // 3 per owned unknown
};

} // namespace rbm::motion
