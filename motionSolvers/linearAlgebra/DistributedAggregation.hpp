#pragma once
// The first level of smoothed aggregation for a scalar symmetric positive definite matrix K
// distributed over the ranks by rows (PETSc AIJ): rbm's aggregation of the serial cycle
// (SmoothedAggregation.hpp) made to work across ranks, and the two-level cycle built on it.
//
// Why: PETSc's GAMG coarsens K's first level by a maximal independent set at distance 2 over
// the ranks (MatCoarsen MIS-k), on a filtered copy of K's graph. On the hexahedral cube that
// transient is the peak of a rank's memory in a decomposed run (docs/parallel.md). Here each
// rank aggregates the rows it owns, on its diagonal block of K only (aggregateRows: a row and
// its strong neighbours, 3 × 3 × 3 rows on a hexahedral grid, as MIS-2 makes), in one pass over
// that block and with no communication; aggregates never cross ranks. The tentative
// prolongator T (1 where a row belongs to an aggregate) is then smoothed with the WHOLE K,
// P = (I − ω D⁻¹K) T, ω = 4 / (3 λ), λ the largest eigenvalue of D⁻¹K by power iteration, so
// P's rows at a rank's border reach the neighbour rank's aggregates as GAMG's do.
//
// The cycle (setUpAggregationCycle): PCMG with two levels, K on the fine one (PETSc's MatMult:
// the couplings across ranks included), Pᵀ K P on the coarse one (PETSc's Galerkin product);
// on the fine level Chebyshev smoothing of degree 2 on D⁻¹K over [0.1 λ, 1.1 λ] (GAMG's
// default smoother), the coarse level one GAMG cycle (a matrix about 27 times smaller, whose
// coarsening transient is as much smaller). On one rank P equals the serial aggregation's
// first interpolation (SmoothedAggregation.hpp) to rounding.

#include "PetscSupport.hpp"

#include <petscksp.h>

namespace rbm::motion {

struct DistributedProlongator {
    PetscMat interpolation;  // P: K's rows × the aggregates (each rank's after the lower ranks')
    double jacobiLambda = 0.0;  // the power iteration's estimate of λ(D⁻¹K), without margin
    PetscInt ownedAggregates = 0;
};

// P of the matrix k (AIJ, square, every diagonal entry positive; the same row and column
// layout). Throws std::runtime_error naming the row of a diagonal that is not positive.
// Collective on k's communicator.
DistributedProlongator distributedSmoothedProlongator(Mat k);

// Makes cycle's preconditioner the two-level cycle above for its operator k (cycle: a KSP whose
// operators are k and whose options prefix is set; its type is left to the caller). PETSc's
// options under that prefix still apply: -<prefix>mg_levels_1_ksp_max_it for the smoothing,
// -<prefix>mg_coarse_pc_type for the coarse cycle. Collective.
void setUpAggregationCycle(KSP cycle, Mat k);

} // namespace rbm::motion
