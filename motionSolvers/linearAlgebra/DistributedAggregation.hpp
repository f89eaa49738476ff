#pragma once
// The first level of smoothed aggregation for a scalar symmetric positive definite matrix K
// distributed over the ranks by rows (PETSc AIJ): rbm's aggregation of the serial cycle
// (SmoothedAggregation.hpp) made to work across ranks: the two levels of a decomposed run's cycle.
//
// Why: PETSc's GAMG coarsens K's first level by a maximal independent set at distance 2 over
// the ranks (MatCoarsen MIS-k), on a filtered copy of K's graph. On the hexahedral cube that
// transient was the peak of a rank's memory in a decomposed run (docs/parallel.md). Here each
// rank aggregates the rows it owns, on its diagonal block of K only (aggregateRows: a row and
// its strong neighbours, 3 × 3 × 3 rows on a hexahedral grid, as MIS-2 makes), in one pass over
// that block and with no communication; aggregates never cross ranks. The tentative
// prolongator T (1 where a row belongs to an aggregate) is then smoothed with the WHOLE K,
// P = (I − ω D⁻¹K) T, ω = 4 / (3 λ), λ the largest eigenvalue of D⁻¹K by power iteration, so
// P's rows at a rank's border reach the neighbour rank's aggregates as GAMG's do.
//
// The cycle on these two levels (PartThreeVectorCycle, on a part's three displacement components
// at once): K on the fine level, Pᵀ K P (galerkinOperator) on the coarse one, about 27 times
// smaller, whose own GAMG set-up is then as much smaller. On one rank P equals the serial
// aggregation's first interpolation (SmoothedAggregation.hpp) to rounding.

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

// The coarse operator Pᵀ K P (PETSc's product, its intermediate data released). Collective.
PetscMat galerkinOperator(Mat k, Mat interpolation);

} // namespace rbm::motion
