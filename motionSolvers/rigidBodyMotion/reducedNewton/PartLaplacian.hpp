#pragma once
// K⁻¹ of the reduced Newton method on one rank's part of a distributed 3D problem
// (RbmProblem::isPart; docs/parallel.md, "Distributed data"): the inverse of the projected
// vector Laplacian A = P (K ⊗ I) P + s (I − P) (RbmProblem::projectSlidingBlocks' operator,
// s = K_aa at a sliding node), applied to P r.
//
// Only the SCALAR K is assembled (one PETSc AIJ matrix over the ranks, each rank inserting the
// rows of its owned unknown nodes): the three components share it, and A differs from K ⊗ I
// only at the sliding nodes' projections, which are applied node by node. A vector matrix of
// K ⊗ I (block size 3) took 9 × the scalar's entries, about 2.9 kB per node in a hexahedral
// mesh, more than the rest of the part's problem, and its multigrid more again.
//
// The solve: CG on A (a shell: three products with K between projections) preconditioned by
// one multigrid cycle C of K per component between the same projections,
// M = P (C ⊗ I) P + (I − P)/s, to the relative tolerance, when asked to
// (`solveToTolerance`: -rbm_reduced_inner_solve, as for the serial multigrid); by default K⁻¹
// is M itself, one cycle per component: the Newton CG is flexible. On the 2.2·10⁵-cell cube
// on 2 ranks the step took 13 s with one cycle and 60 s solving to 10⁻⁴ (a loaded machine).
//
// C is by default rbm's two-level cycle over the ranks on the three components at once
// (PartThreeVectorCycle.hpp: aggregates of each rank's own rows, P smoothed with the whole K,
// Chebyshev smoothing with K in single precision, one GAMG cycle of Pᵀ K P per component); after
// its set-up PETSc's K is released, unless -rbm_reduced_inner_solve needs it for A. With
// -rbm_reduced_part_cycle gamg, or when a preconditioner is named for the cycle
// (-rbm_reduced_cycle_pc_type ...), C is PETSc's preconditioner of PETSc's K per component, GAMG
// unless named: GAMG's first coarsening (MIS-2 over the ranks) was the peak of a rank's memory.
// Measured on the 10⁶-cell cube turned 30° on 2 ranks, one thread each (docs/parallel.md):
// GAMG 1 254 MiB on the larger rank; rbm's cycle 1 034 MiB, and with the turned start 4 Newton
// iterations of 18 s of wall time where GAMG's took 5 of 28 s. With -rbm_reduced_part_cycle
// local it is block Jacobi over the ranks: rbm's own smoothed-aggregation cycle
// (ThreeVectorMultigrid, the serial 3D solver's) of the block of K that couples the rank's owned
// unknowns, the couplings to other ranks left out, and no matrix over the ranks is assembled: 17
// Newton iterations on the same cube (the weaker cycle makes the truncated Newton steps worse),
// and no scalar solve (so no turned start).
//
// Unknown rows: each rank's owned unknown nodes in their part order, after the lower ranks'
// (one contiguous range per rank); a ghost unknown's row comes from its owner through the
// node exchange. Setup and every apply are collective.
//
// PETSc options: prefix rbm_reduced_ for the CG on A (-rbm_reduced_ksp_monitor, ...),
// rbm_reduced_cycle_coarse_ for the coarse level of rbm's cycle, and rbm_reduced_cycle_ for
// PETSc's cycle (-rbm_reduced_cycle_pc_type hypre, ...).

#include "PetscSupport.hpp"
#include "RbmProblem.hpp"
#include "PartThreeVectorCycle.hpp"
#include "ThreeVectorMultigrid.hpp"

#include <memory>
#include <span>
#include <vector>

namespace rbm::motion {

class PartLaplacian {
public:
    // laplacian: K's scalar entries in the part problem's blockPattern() order
    // (coupledDisplacementLaplacian), copied (into PETSc's matrix or the local cycle's CSR): the
    // caller may release its array before setUp. Throws std::invalid_argument unless the problem
    // is a 3D part. Collective.
    PartLaplacian(const RbmProblem& problem, std::span<const double> laplacian, double relativeTolerance,
                  bool solveToTolerance);
    // Builds the cycle (its multigrid set-up) and the solver; collective, before the first apply. A
    // separate step so that the caller's copy of K is gone first: the cycle's set-up is a
    // transient peak of a rank's memory, and K's array (27 doubles a node) need not be alive in it.
    void setUp();
    ~PartLaplacian();
    PartLaplacian(const PartLaplacian&) = delete;
    PartLaplacian& operator=(const PartLaplacian&) = delete;

    // z = A⁻¹ P r on the owned rows (3 per unknown node; ghost rows of z zero, of r ignored);
    // false if CG did not converge.
    bool apply(std::span<const double> r, std::span<double> z);
    // s = K⁻¹ b for one scalar right-hand side, b on the owned unknown nodes (ghost rows
    // ignored), s on every unknown node (the ghosts' from their owners): CG on K preconditioned by
    // the cycle, to relativeTolerance of b, at most maximumIterations. The turned start's
    // harmonic share (TurnedStart.hpp). False if CG did not converge; collective.
    bool solveScalar(std::span<const double> b, std::span<double> s, double relativeTolerance, int maximumIterations);
    // Whether solveScalar can: not with -rbm_reduced_part_cycle local (its cycle is per rank).
    bool hasScalarSolve() const { return !useLocalCycle_; }
    // CG iterations of the last apply (0 when K⁻¹ is one cycle).
    int lastIterations() const { return lastIterations_; }

private:
    // Each unknown node's global row (−1 for prescribed nodes), ghosts' from their owners.
    std::vector<PetscInt> unknownRows() const;
    void assemble(std::span<const double> laplacian);
    void slidingScales(std::span<const double> laplacian);
    // The cycle C: rbm's two-level aggregation over the ranks (the default, -rbm_reduced_part_cycle
    // aggregation), PETSc's GAMG of the whole K (gamg) or rbm's smoothed aggregation of the rank's
    // own block of K (local).
    void setUpLocalCycle(std::span<const double> laplacian);
    void setUpCycle();
    void setUpSolver();  // the CG on A (or preonly), with innerSolve_ and relativeTolerance_
    // P on 3 entries per owned unknown node.
    void project(double* values) const;
    // A in (cycle false: the shell's product) or M in (cycle true: the preconditioner).
    void betweenProjections(Vec in, Vec out, bool cycle) const;
    static PetscErrorCode shellMultiply(Mat matrix, Vec x, Vec y);
    static PetscErrorCode shellPrecondition(PC preconditioner, Vec r, Vec z);
    static PetscErrorCode shellScalarCycle(PC preconditioner, Vec r, Vec z);  // rbm's cycle on one vector
    // The per-component products: out_q = K in_q (cycle false) or C in_q (cycle true).
    void componentwise(Vec in, Vec out, bool cycle) const;

    const RbmProblem& problem_;
    int ownedUnknowns_ = 0;
    std::vector<double> slidingScale_;  // per owned unknown: K_aa (s), used at sliding nodes
    bool innerSolve_ = true;
    double relativeTolerance_ = 0.0;
    bool setUp_ = false;
    PetscMat stiffness_;   // scalar K, owned unknown rows (released after rbm's cycle's set-up unless A needs it)
    std::unique_ptr<PartThreeVectorCycle> threeVectorCycle_;  // rbm's cycle, the default
    PetscMat operator_;    // A, a shell on 3 rows per owned unknown
    PetscKsp cycle_;       // PETSc's cycle of K (preonly + GAMG or the named preconditioner)
    // -rbm_reduced_part_cycle local: of K's block of the owned unknowns (its CSR, which the cycle reads).
    std::vector<int> localOffsets_, localColumns_;
    std::vector<double> localValues_;
    std::unique_ptr<ThreeVectorMultigrid> localCycle_;
    bool useLocalCycle_ = false;
    bool useAggregationCycle_ = false;  // -rbm_reduced_part_cycle aggregation (DistributedAggregation.hpp)
    PetscKsp solver_;      // CG on A preconditioned by M (preonly: M alone)
    PetscVec componentIn_, componentOut_;  // one component, owned unknown rows
    mutable PetscVec projected_;            // P x (product) or P r (preconditioner)
    PetscVec rightHandSide_, solution_;
    PetscKsp scalarSolver_;  // CG on K with the cycle (solveScalar), made at its first use
    std::unique_ptr<InheritedOptions> options_, cycleOptions_;
    std::vector<double> projectedRightHandSide_;
    int lastIterations_ = 0;
};

} // namespace rbm::motion
