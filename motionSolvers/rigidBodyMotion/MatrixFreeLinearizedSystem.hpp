#pragma once
// The coupled linearized RBM system solved without assembling it (`linearSolver
// matrixFree`, and the automatic choice for large 3D problems on one rank): conjugate
// gradients on the reduced system S u = −∇E_reduced (ReducedLinearizedOperator.hpp, the
// rotations eliminated node by node), S applied by a PETSc shell matrix, preconditioned by
// one V-cycle of algebraic multigrid on the scalar displacement Laplacian H_uu for all
// displacement components at once (ThreeVectorMultigrid, rbm's smoothed aggregation; with
// -rbm_linearized_mf_pc_type … PETSc's preconditioner, one application per component).
//
// Why: the assembled 3D Hessian holds 36 values per graph edge (hexahedral meshes: 27 blocks
// per row, 7.8 KB per node, 20 KB with multigrid's copies), 20 GiB for 10^6 cells. The shell
// keeps the problem's weights and the scalar Laplacian, about 1 KB per node with multigrid.
// The Laplacian's AMG set-up is kept for every solve of the same problem (time steps of a
// linearized run without sub-steps).
//
// Options: the Krylov method reads rbm_linearized_ (and the inherited global ones, see
// InheritedOptions), e.g. -rbm_linearized_ksp_monitor; the Laplacian's preconditioner reads
// rbm_linearized_mf_, e.g. -rbm_linearized_mf_pc_type hypre. One rank only: the shell
// works on whole arrays.

#include "PetscSupport.hpp"
#include "ReducedLinearizedOperator.hpp"
#include "ThreeVectorMultigrid.hpp"

#include <memory>
#include <span>
#include <vector>

namespace rbm::motion {

using PetscPc = PetscHandle<PC, PCDestroy>;

// Whether the coupled linearized solver works matrix-free: asked for (`matrixFree`), or
// `automatic` for any 3D problem on one MPI rank: in 3D it takes several times less CPU and
// memory than MUMPS or CG + GAMG on the assembled 6×6 blocks, from about a thousand cells up
// (docs/motionSolver.md, "Linear solvers, measured"; rbmBenchmark --cases twist3D --variants
// linearized,linearizedAssembled).
bool matrixFreeChosen(LinearSolverKind kind, int dimension, int unknownCount);

class MatrixFreeLinearizedSystem {
public:
    // Builds the Laplacian and its multigrid hierarchy. Throws std::invalid_argument when
    // the solver communicator has more than one rank.
    MatrixFreeLinearizedSystem(const RbmProblem& problem, double relativeTolerance);
    MatrixFreeLinearizedSystem(const MatrixFreeLinearizedSystem&) = delete;
    MatrixFreeLinearizedSystem& operator=(const MatrixFreeLinearizedSystem&) = delete;

    const ReducedLinearizedOperator& reducedOperator() const { return operator_; }

    // The minimiser of the linearized energy for the prescribed displacements as a compact
    // unknown vector (u and rotations, RbmProblem's block layout), as CoupledLinearizedSolver
    // returns it. initialGuess (optional) seeds CG with its displacements.
    std::vector<double> solveUnknowns(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess,
                                      BlockSystemSolver::Report& report);

    // y = P S P x (P: the sliding projection); the shell's multiplication.
    void multiply(std::span<const double> x, std::span<double> y) const;
    // y = P B P x, B: one multigrid cycle of the Laplacian on every component; the shell's preconditioner.
    void precondition(Vec x, Vec y);

private:
    void projectSliding(Vec vector) const;  // P on a displacement vector, in place

    const RbmProblem& problem_;
    ReducedLinearizedOperator operator_;
    InheritedOptions options_;
    std::vector<double> laplacianValues_;          // H_uu in the block pattern (the cycle references it)
    std::unique_ptr<ThreeVectorMultigrid> cycle_;  // rbm's cycle of H_uu (else PETSc's PC below)
    std::vector<double> cycleIn_, cycleOut_;       // the cycle's three-component vectors
    PetscMat laplacian_;
    PetscPc laplacianPreconditioner_;
    PetscMat shell_;
    PetscKsp ksp_;
    PetscVec rightHandSide_, solution_;
    PetscVec componentIn_, componentOut_, projected_;
    mutable std::vector<double> projectedInput_;
};

} // namespace rbm::motion
