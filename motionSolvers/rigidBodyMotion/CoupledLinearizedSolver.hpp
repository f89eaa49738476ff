#pragma once
// The coupled linearized RBM method (thesis §2.4 for 2D, §2.5.1 for 3D): small-angle
// rotations R ≈ I + [θ]× make the coupled energy quadratic in the node-local unknowns, so
// its minimiser is one sparse symmetric positive definite solve H z = −∇E(0)
// (3 unknowns per node in 2D, 6 in 3D). H depends only on the reference mesh and the
// weights: it is assembled and factorised once, in the constructor, and reused by every
// solve(). Positions are x + u (node-local parameters need no cos/sin to recover them,
// docs/method.md §2). Sliding nodes: H ← P H P + s (I − P), right-hand side projected.
//
// Options prefix: rbm_linearized_ (also rbm_ and the global options), e.g.
// -rbm_linearized_ksp_type cg -rbm_linearized_pc_type gamg.
//
// Result: iterations = 1, linearIterations = Krylov iterations (0 for direct),
// residualNorm = ‖P ∇E_linearized‖ at the result, energy = the EXACT energy E there.

#include "MatrixFreeLinearizedSystem.hpp"
#include "PetscSupport.hpp"
#include "RbmProblem.hpp"

#include <memory>

namespace rbm::motion {

struct CoupledLinearizedOptions {
    LinearSolverKind linearSolver = LinearSolverKind::automatic;
    double relativeTolerance = 1e-10;  // Krylov tolerance when an iterative method is used
};

class CoupledLinearizedSolver : public RbmSolver {
public:
    explicit CoupledLinearizedSolver(const RbmProblem& problem, CoupledLinearizedOptions options = {});

    const RbmProblem& problem() const override { return problem_; }
    // initialGuess only seeds an iterative Krylov method; the result does not depend on it.
    RbmResult solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess = nullptr) override;

    // The linearized result as a compact unknown vector (for Newton's start).
    std::vector<double> solveUnknowns(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess,
                                      BlockSystemSolver::Report& report);

private:
    const RbmProblem& problem_;
    CoupledLinearizedOptions options_;
    std::unique_ptr<BlockSystemSolver> system_;              // assembled H (direct or CG + GAMG)
    std::unique_ptr<MatrixFreeLinearizedSystem> matrixFree_;  // or the reduced system, unassembled
};

} // namespace rbm::motion
