#pragma once
// The coupled nonlinear RBM method (thesis §2.3.2, Algorithm 2): minimise the exact
// energy E over all unknowns at once with Newton's method (PETSc SNES) and the analytic
// Hessian (the thesis' Jacobian, eqs 2.30–2.47, in node-local variables).
//
// Start: the given initial guess (warm start from the previous time step), otherwise the
// coupled linearized solution; in both, every node's rotation is then replaced by the best
// fit of its own edges (the local step of LocalGlobalSolver). With the linearized rotations
// themselves Newton stopped, for a 120° rigid turn, at a stationary point with flipped node
// frames (E = 5.3 instead of 0; docs/method.md §2: the same happens from a zero start). At a true
// minimum every rotation equals its fit, so after convergence the fits are compared with
// the rotations and Newton is restarted from the fitted state when they differ.
//
// Globalisation: a line search on the energy itself (PETSc's shell line search with an
// Armijo backtracking on E). Where the exact Hessian is indefinite and its Newton step is
// not a descent direction, that step is recomputed with the Gauss–Newton matrix (the
// Hessian without the curvature term r·∂²(R d), positive definite).
// `-rbm_newton_snes_linesearch_type bt` etc. replace it.
//
// Sliding nodes: SNES works on the projected gradient P∇E and the Jacobian P H P + s (I−P)
// from a start that satisfies the constraints, so every step keeps them.
//
// Options prefix: rbm_newton_ (also rbm_ and the global options): -snes_monitor,
// -rbm_newton_snes_rtol, -rbm_newton_ksp_type, -rbm_newton_pc_type ...
//
// Result: iterations = Newton steps, linearIterations = Krylov iterations of the start and of
// the steps, residualNorm = ‖P∇E‖, energy = E, reason = SNES's converged reason.

#include "CoupledLinearizedSolver.hpp"
#include "PetscSupport.hpp"
#include "RbmProblem.hpp"

#include <memory>

namespace rbm::motion {

struct CoupledNewtonOptions {
    LinearSolverKind linearSolver = LinearSolverKind::automatic;
    int maximumIterations = 50;
    double relativeTolerance = 1e-10;  // on ‖P∇E‖ relative to the start
    // On ‖P∇E‖; a negative value means 1e-11 × (mean w |d|) × √(unknown nodes), about
    // 1e-11 of a cell per node.
    double absoluteTolerance = -1.0;
    double linearRelativeTolerance = 1e-10;  // Krylov tolerance when an iterative method is used
};

class CoupledNewtonSolver : public RbmSolver {
public:
    explicit CoupledNewtonSolver(const RbmProblem& problem, CoupledNewtonOptions options = {});
    ~CoupledNewtonSolver() override;

    const RbmProblem& problem() const override { return problem_; }
    RbmResult solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess = nullptr) override;

    struct Context;  // SNES callback data (defined in the .cpp)

private:
    const RbmProblem& problem_;
    CoupledNewtonOptions options_;
    InheritedOptions petscOptions_;
    std::unique_ptr<CoupledLinearizedSolver> linearized_;  // created on first use
    PetscSnes snes_;
    PetscMat jacobian_;
    PetscVec solution_;
    PetscVec residual_;
    std::unique_ptr<Context> context_;
};

} // namespace rbm::motion
