#pragma once
// K⁻¹, the preconditioner of the reduced Newton method's conjugate gradients: K is the coupled
// weighted graph Laplacian, the displacement block H_uu = K ⊗ I of the exact Hessian
// (ReducedEnergy.hpp). S ≤ K, and S = K on fields whose neighbourhoods do not turn, so K⁻¹
// is a good preconditioner of S; and K depends on neither the displacements nor the boundary
// values, so it is factorised (2D: Cholesky) or its multigrid set up ONCE, when the solver is
// built, and kept for every iteration, sub-step and time step.
//
// How K⁻¹ is applied:
//   - one rank, K factorised: rbm's supernodal Cholesky (SparseCholesky.hpp), or PETSc's
//     factorisation with every component in one back-substitution (MatMatSolve) when the
//     user chose PETSc's solver through the options; with sliding nodes, the projected
//     K ⊗ I in the sliding frames, factorised once the same way (ProjectedLaplacianFactor.hpp);
//   - 3D above directSolverRowLimit unknown nodes (one rank): ONE multigrid V-cycle applied to
//     the three components at once (ThreeVectorMultigrid.hpp, rbm's smoothed-aggregation
//     hierarchy of K); with sliding nodes, CG on the projected K ⊗ I preconditioned by that
//     cycle between projections, to the relative tolerance;
//   - one rank's part of a distributed 3D problem (RbmProblem::isPart): PartLaplacian, CG +
//     GAMG on the projected K ⊗ I assembled over the ranks, to the relative tolerance;
//   - otherwise PETSc's KSP on K (per component) or on the projected K ⊗ I (sliding nodes).
// The Newton CG is flexible (Polak–Ribière), so K⁻¹ needs not be an exact inverse.
//
// PETSc options (read here, once): K's solver reads rbm_reduced_ (e.g.
// -rbm_reduced_pc_factor_mat_solver_type mumps, -rbm_reduced_cycle_hierarchy gamg (then
// -rbm_reduced_pc_gamg_threshold 0.02 …), -rbm_reduced_cycle_degree 3); -rbm_reduced_inner_solve:
// K⁻¹ by CG + GAMG to the relative tolerance instead of one cycle.
//
// Vectors are compact: dimension() entries per unknown node.

#include "PetscSupport.hpp"
#include "ProjectedLaplacianFactor.hpp"
#include "RbmProblem.hpp"

#include <array>
#include <memory>
#include <span>
#include <vector>

namespace rbm::motion {

class PartLaplacian;
class SparseCholesky;
class ThreeVectorMultigrid;

class LaplacianPreconditioner {
public:
    // relativeTolerance: of K ⊗ I's iterative solves (3D with sliding nodes, 2D with K iterative).
    LaplacianPreconditioner(const RbmProblem& problem, LinearSolverKind linearSolver, double relativeTolerance);
    ~LaplacianPreconditioner();
    LaplacianPreconditioner(const LaplacianPreconditioner&) = delete;
    LaplacianPreconditioner& operator=(const LaplacianPreconditioner&) = delete;

    // z = P K⁻¹ P r (P: the problem's projection onto the sliding planes and the cyclic pairs);
    // false if an iterative solve failed.
    bool apply(std::span<const double> r, std::span<double> z);
    // s = K⁻¹ b for one scalar right-hand side (one value per unknown node): K's factor, or CG
    // preconditioned by the 3D cycle (or a part's cycle) to a loose tolerance. Only where
    // hasScalarSolve(); false if CG failed.
    bool solveScalar(std::span<const double> b, std::span<double> s);
    // No sliding nodes, and K factorised by rbm, its 3D multigrid cycle on one rank, or a part's
    // K⁻¹ (PartLaplacian::solveScalar: s on the ghost nodes too, from their owners).
    bool hasScalarSolve() const;
    // apply is one fixed linear map (a factorisation, or the 3D cycle without sliding nodes; not
    // an inner iteration whose result depends on its tolerance).
    bool isFixedLinearMap() const
    {
        return cholesky_ || projectedCholesky_ || (threeVectorCycle_ && !vectorSystem_ && problem_.dimension() == 3);
    }
    // K's entries in blockPattern() order; empty where one 3D cycle without sliding nodes is
    // K⁻¹, holds K's finest values in single precision and nothing else reads them (released,
    // 8 bytes a block: 210 MB at 10⁶ hexahedra). The paths that read them (sliding nodes, 2D
    // CG with the cycle) keep them.
    const std::vector<double>& laplacian() const { return laplacian_; }

private:
    // PETSc's defaults for K's solver where rbm's own factorisation is not used (CHOLMOD on
    // one rank, BoomerAMG for 2D on several).
    void choosePetscDefaults(int ranks, bool factorised);
    // K (or, with sliding nodes, the projected K ⊗ I) in PETSc's solver: the way not taken by
    // rbm's own factorisations and multigrid cycle.
    void buildPetscSystem(LinearSolverKind linearSolver, int ranks, bool innerSolve);
    // z = (P (K ⊗ I) P)⁻¹ P r by CG preconditioned by the cycle of the scalar K between
    // projections, to relativeTolerance. False if CG failed.
    bool projectedCycleSolve(std::span<const double> r, std::span<double> z, double relativeTolerance);

    // apply without the projection onto the cyclic pairs.
    bool applyInverse(std::span<const double> r, std::span<double> z);
    // q = K p, one value per unknown node: from laplacian_, or once it is released from the
    // edge weights and diagonal_, summed in the same order to the same bits.
    void laplacianTimes(std::span<const double> p, std::span<double> q) const;

    const RbmProblem& problem_;
    double relativeTolerance_;
    std::vector<double> pairProjected_;  // apply's projected right-hand side (cyclic pairs)
    std::vector<double> laplacian_;  // scalar K in blockPattern() order (see laplacian())
    std::vector<double> diagonal_;   // K's diagonal, once laplacian_ is released
    std::unique_ptr<BlockSystemSolver> system_;
    bool vectorSystem_ = false;            // sliding nodes: K ⊗ I projected, one system
    bool multipleRightHandSides_ = false;  // K factorised by PETSc on one rank: MatMatSolve on all components
    std::unique_ptr<SparseCholesky> cholesky_;  // K's factor, when one rank factorises the scalar K
    std::unique_ptr<ProjectedLaplacianFactor> projectedCholesky_;  // ... or, with sliding nodes, P (K ⊗ I) P
    bool laplacianByCycle_ = false;        // K iterative: K⁻¹ applied as one multigrid cycle (PCApply)
    // 3D, one rank: that cycle on the three components at once, set up in the constructor
    // instead of system_ (ThreeVectorMultigrid.hpp).
    std::unique_ptr<ThreeVectorMultigrid> threeVectorCycle_;
    std::unique_ptr<PartLaplacian> partLaplacian_;  // a part's K⁻¹
    bool anyRankHasSlidingNodes_ = false;            // of a part: over all ranks
    Mat factor_ = nullptr;                 // the factor inside system_'s PC (not owned)
    PetscMat components_, solutions_;      // dense m × dimension right-hand sides and solutions
    std::unique_ptr<InheritedOptions> laplacianOptions_;  // rbm's defaults for K's solver in PETSc (CHOLMOD, BoomerAMG)
    // Work arrays.
    std::vector<double> componentIn_, componentOut_, projected_;
    std::array<std::vector<double>, 4> cycleWork_;  // projectedCycleSolve's conjugate gradients
    std::vector<double> planarIn_, planarOut_;       // 2D vectors padded to the cycle's three components
};

} // namespace rbm::motion
