#pragma once
// The decoupled RBM method (thesis §2.3.1, Algorithm 1): every unknown node i takes the
// rigid motion (u_i, R_i) that best fits its own stencil,
//     min F_i = 1/2 Σ_{j∈N(i)} w_ij |(p_j − p_i) − R_i (x_j − x_i)|²     (eq 2.2)
// with its neighbours held where they are. The thesis sweeps the nodes (Gauss–Seidel)
// until nothing moves; that needs thousands of sweeps (docs/method.md §3) and its result
// depends on the node order until it has converged. This solver computes the fixed point
// of those sweeps directly, so the result does not depend on the numbering:
//
//   nonlinear   The fixed-point conditions are ∂F_i/∂u_i = 0 and ∂F_i/∂R_i = 0 for all i.
//               With the rotations held, the first set is linear in the displacements:
//               K_dec u = b(R), K_dec the weighted graph Laplacian of the decoupled form
//               (K_ii = Σ_j w_ij, K_ij = −w_ij; symmetric since w_ij = w_ji), assembled and
//               factorised once. Alternating a per-node rotation fit (the closed form
//               docs/method.md §3 gives for the thesis' Newton iteration of eq 2.22) with one
//               Laplacian solve reaches the fixed point in tens of solves.
//   linearized  With small angles (eq 2.48, 2.92) the conditions of all nodes form one
//               linear, non-symmetric system in (u, θ) (block size 3 or 6): one solve.
//
// Sliding nodes: as everywhere, P K P + s (I − P) with projected right-hand sides.
// Options prefix: rbm_decoupled_ (also rbm_ and the global options).
// Result: residualNorm = the fixed-point residual (‖P(K_dec u − b(R))‖ after a final
// rotation fit, resp. ‖P(A z − b)‖ of the linearized system); energy = the COUPLED energy E
// at the result (larger than the coupled minimum: the two methods differ, thesis §3.1.2).

#include "LocalGlobalSolver.hpp"
#include "PetscSupport.hpp"
#include "RbmProblem.hpp"

#include <memory>

namespace rbm::motion {

enum class DecoupledModel { nonlinear, linearized };

struct DecoupledOptions {
    DecoupledModel model = DecoupledModel::nonlinear;
    LinearSolverKind linearSolver = LinearSolverKind::automatic;
    double linearRelativeTolerance = 1e-12;
    int maximumIterations = 5000;          // nonlinear: Laplacian solves
    double displacementTolerance = 1e-11;  // nonlinear: × shortest reference edge
    // nonlinear: Anderson acceleration depth. Off by default: the decoupled conditions can
    // have several fixed points where the boundary holds the mesh loosely (thesis §3.1.3),
    // and with nothing like an energy to guard the extrapolation, acceleration was seen to
    // land on a wrong one (the plain iteration found the rigid rotation there).
    int accelerationDepth = 0;
};

class DecoupledSolver : public RbmSolver {
public:
    explicit DecoupledSolver(const RbmProblem& problem, DecoupledOptions options = {});

    const RbmProblem& problem() const override { return problem_; }
    RbmResult solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess = nullptr) override;

private:
    RbmResult solveLinearized(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess);

    const RbmProblem& problem_;
    DecoupledOptions options_;
    std::unique_ptr<LaggedRotationIteration> iteration_;  // nonlinear
    std::unique_ptr<BlockSystemSolver> linearSystem_;     // linearized
    std::vector<double> linearBlocks_;                    // linearized matrix before projection
};

} // namespace rbm::motion
