#pragma once
// The coupled nonlinear RBM method by Newton's method on the displacements alone, with every
// node's rotation eliminated by its best fit, and one Laplacian factorisation per run
// (`algorithm reducedNewton`, the default; issue 12).
//
// The exact energy (RbmEnergy.hpp)  E(u, R) = 1/2 Σ_i Σ_j w_ij |e_ij − R_i d_ij|²,
// e_ij = p_j − p_i, d_ij = x_j − x_i, holds R_i in the terms of node i alone. So
//
//     Ẽ(u) = min_R E(u, R) = E(u, R*(u)),   R*_i(u) = the best fit of node i's edges
//
// (the local step of LocalGlobalSolver: 2D atan2, 3D Kabsch) is a function of the
// displacements only, with the same minima as E: (u, R*(u)) minimises E iff u minimises Ẽ.
// Newton on Ẽ therefore never meets the stationary points with flipped node frames that
// Newton on (u, R) can stop at (CoupledNewtonSolver.hpp, DESIGN.md §1).
//
// Derivatives (envelope theorem, ∂E/∂R = 0 at R*):
//   ∇Ẽ = ∂E/∂u at R*, per unknown node k with d = x_j − x_k, t_j = [j unknown]:
//       g_k = Σ_j w [(1 + t_j)(u_k − u_j − d) + R_k d + t_j R_j d]   (= K u − b(R*));
//   ∇²Ẽ = S = H_uu − H_uδ H_δδ⁻¹ H_δu, the Schur complement of the exact Hessian in a
//       local rotation chart R_i ← exp([δ_i]×) R_i (at ∂E/∂δ = 0 it does not depend on the
//       chart). With q = R_i d_ij and e = e_ij:
//         H_uu = K ⊗ I, K the coupled weighted graph Laplacian (constant: E is quadratic in u);
//         H_δδ,i = Σ_j w [(q·e) I − (e qᵀ + q eᵀ)/2]   (block diagonal: δ_i only in node i's terms);
//         S v:  y_i = H_δδ,i⁻¹ Σ_j w q_ij × (v_j − v_i),
//               (S v)_k = (K v)_k + Σ_j w (y_k × R_k d + t_j y_j × R_j d).
//   At u = 0 (R* = I) S is the linearized method's reduced operator (ReducedLinearizedOperator).
//   A mirror node turns about its normal n only (δ = n φ); 2D rotations about z.
//
// Each Newton step solves S s = −∇Ẽ by preconditioned conjugate gradients, with K⁻¹ as the
// preconditioner (S ≤ K; S = K on fields whose neighbourhoods do not turn): K depends on
// neither the displacements nor the boundary values, so it is factorised (2D: Cholesky) or
// its multigrid set up ONCE, when the solver is built, and kept for every iteration, sub-step
// and time step. In 3D above 20 000 unknown nodes (one rank) K⁻¹ is ONE multigrid V-cycle
// applied to the three components at once (ThreeVectorMultigrid.hpp, rbm's smoothed-aggregation
// hierarchy of K); with sliding nodes, CG on the projected K ⊗ I preconditioned by that cycle
// between projections, to laplacianRelativeTolerance. S is applied from per-node data only
// (ReducedHessian3D.hpp); CG is flexible (Polak–Ribière), so the cycle needs not be an exact
// inverse. Inexact Newton (Eisenstat–Walker forcing) solves early steps loosely; a
// direction of negative curvature stops CG (Steihaug), and at the first CG iteration the step
// is then the preconditioned gradient −K⁻¹∇Ẽ, which is exactly a local/global step. A
// backtracking line search on Ẽ keeps every step a descent step.
//
// Start: cold, the harmonic interpolation K⁻¹ b(I) of the prescribed displacements or, where
// the boundary is one rigid body in a fixed frame (2D and 3D, one rank, no sliding nodes), the
// harmonic interpolation of the body's turn (every node turned by exp(s [ω]×) and shifted by
// s t, s = K⁻¹ b(1 on the body)), whichever has the lower energy; warm (the previous time
// step), the guess moved by a secant step and the harmonic increment of the boundary,
// K⁻¹ (b(new) − b(old)).
//
// Convergence: as CoupledNewtonSolver: ‖P∇Ẽ‖ below the absolute tolerance (1e-11 × mean w|d|
// × √unknown nodes by default), or 1e-10 × its start value, or 10 × the rounding level of the
// gradient (RbmEnergy::gradientRoundoffNorm). ∇_R E = 0 at R*, so ‖P∇Ẽ‖ is ‖P∇E‖.
//
// Determinism: every loop over nodes writes its own node's entries and every sum runs in node
// order, so the result is bit-identical for any thread count.
//
// PETSc options: -rbm_reduced_max_it N (Newton steps), -rbm_reduced_monitor (one line per step);
// the Laplacian's solver reads rbm_reduced_ (e.g. -rbm_reduced_pc_factor_mat_solver_type mumps,
// -rbm_reduced_cycle_hierarchy gamg (then -rbm_reduced_pc_gamg_threshold 0.02 …),
// -rbm_reduced_cycle_degree 3; -rbm_reduced_inner_solve: K⁻¹
// by CG + GAMG to laplacianRelativeTolerance instead of one cycle, the behaviour before).
// Result: iterations = Newton steps, linearIterations = CG iterations, residualNorm = ‖P∇E‖,
// energy = E.

#include "PetscSupport.hpp"
#include "LaplacianPreconditioner.hpp"
#include "RbmEnergy.hpp"
#include "ReducedEnergy.hpp"
#include "RbmProblem.hpp"

#include <array>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace rbm::motion {

struct ReducedNewtonOptions {
    LinearSolverKind linearSolver = LinearSolverKind::automatic;  // of the Laplacian K
    int maximumIterations = 50;                                   // Newton steps
    double relativeTolerance = 1e-10;                             // on ‖P∇Ẽ‖ relative to the start
    double absoluteTolerance = -1.0;                              // < 0: CoupledNewtonOptions' default
    int maximumLinearIterations = 1000;                           // CG iterations per Newton step
    // When K ⊗ I is solved iteratively (3D with sliding nodes: CG + the cycle between
    // projections; -rbm_reduced_inner_solve: CG + GAMG): K⁻¹ is only the preconditioner of a
    // flexible CG, which needs no exact inverse.
    double laplacianRelativeTolerance = 1e-4;
    // Converged when no node's estimated remaining displacement, |K⁻¹ P∇Ẽ| at the node, exceeds
    // displacementTolerance × its shortest edge (≤ 0: off, only the gradient tests above, to
    // round-off). Mesh motion needs positions to a small fraction of the local cell, not the
    // rounding level of the 1/|d|²-weighted gradient: on the airfoil series the default saves
    // 27 % of the CG iterations (docs/motionSolver.md, "Reduced Newton"). The same default as
    // the dictionary's (RigidBodyMotionOptions).
    double displacementTolerance = 1e-6;
    // Cold starts where the boundary is one rigid body in a fixed frame (2D or 3D; K factorised
    // by rbm or the 3D multigrid cycle): also try the harmonic interpolation of the body's turn
    // (solve(); false: only the harmonic interpolation of the displacements, for tests).
    bool turnedStart = true;
    // Warm starts along a chain of own results: the Newton corrections of the last
    // correctionMemory steps (result − predictor) span the first step, a Galerkin step in that
    // subspace (solve(); 0: off; -rbm_reduced_correction_memory N). On the pitching airfoil each
    // correction lies within 1.5 % of the previous one's direction (Euclidean norm) and within
    // 0.1 % of the span of the last two.
    int correctionMemory = 3;
    // Warm starts: the harmonic correction of the predictor from the extensions of earlier
    // boundary changes where the new change is their combination (harmonicChangeFromBasis;
    // false: a back-substitution at every step, for tests; -rbm_reduced_harmonic_basis false).
    bool harmonicBasis = true;
};

class ReducedNewtonSolver : public RbmSolver {
public:
    explicit ReducedNewtonSolver(const RbmProblem& problem, ReducedNewtonOptions options = {});
    ~ReducedNewtonSolver() override;

    const RbmProblem& problem() const override { return problem_; }
    RbmResult solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess = nullptr) override;
    // The extensions of boundary changes kept (ReducedNewtonOptions::harmonicBasis), and the
    // warm starts that took their correction from them instead of a back-substitution.
    std::size_t harmonicBasisSize() const { return harmonicBasis_.size(); }
    int correctionsFromHarmonicBasis() const { return correctionsFromHarmonicBasis_; }

private:
    // Projected conjugate gradients on S s = −g to ‖S s + g‖ ≤ forcing ‖g‖; see the file comment.
    // firstPreconditioned: K⁻¹(−g) when the caller has it (else computed here).
    bool newtonDirection(std::span<const double> g, double forcing, const std::vector<double>* firstPreconditioned,
                         std::span<double> step, int& iterations, bool& negativeCurvature);
    // Start for one rigid body in a fixed frame: see solve(). From the reference positions
    // (cold) or from base's displacements (a warm start without history: the body's motion
    // since base turned in). False where it does not apply.
    bool turnedHarmonicStart(std::span<const Vector3> prescribedDisplacement, std::vector<Vector3>& u,
                             std::span<const Vector3> base = {});
    // trial ← from + λ step (step compact), sliding nodes back onto their planes (solve()).
    using TrialMove = std::function<void(const std::vector<Vector3>& from, std::span<const double> step, double lambda)>;
    // Warm starts: one Galerkin step in the span of recentCorrections_ from u, taken when it
    // lowers Ẽ (Armijo); then u, rotations, energy and g are the new point's. Returns the
    // subspace's dimension, 0 when no step was taken.
    int subspaceStep(std::vector<Vector3>& u, std::vector<Matrix3>& rotations, double& energy, std::vector<double>& g,
                     const TrialMove& moveAlong, std::vector<Vector3>& trial, std::vector<Matrix3>& trialRotations,
                     bool monitor);
    // The warm start's harmonic correction K⁻¹ (b(new) − b(base)) without a back-substitution:
    // where the prescribed change (new − base on the prescribed nodes, into boundaryChange) is a
    // combination of the changes met before, the same combination of their extensions
    // (harmonicBasis_). On a rigid body's boundary every change lies in one small space (2D:
    // the body's points, their turn by 90° and the two translations, four vectors), so after
    // the first steps of a time series none needs a solve. False where not applicable or where
    // the change leaves the basis; then the caller solves and hands the result to
    // rememberHarmonicChange.
    bool harmonicChangeFromBasis(std::span<const Vector3> prescribed, std::span<const Vector3> base,
                                 std::vector<double>& boundaryChange, std::vector<double>& correction);
    void rememberHarmonicChange(std::vector<double> boundaryChange, std::span<const double> correction);
    // max over unknown nodes of |v_node| / (the node's shortest edge), v compact.
    double largestRelativeDisplacement(std::span<const double> v) const;

    const RbmProblem& problem_;
    ReducedNewtonOptions options_;
    ReducedEnergy reducedEnergy_;  // Ẽ, ∇Ẽ, S
    LaplacianPreconditioner preconditioner_;  // K⁻¹, factorised once
    double absoluteTolerance_ = 0.0;
    // Eisenstat–Walker forcing (solve): η = 0.9 (‖g‖/‖g_prev‖)^forcingExponent_, and the last
    // step to finalForcingFactor_ × the final tolerance (the constructor sets 3D's values).
    double forcingExponent_ = 2.0;
    double finalForcingFactor_ = 0.1;
    // The last results (node displacements, newest first), for the predictor of warm starts:
    // the secant from the first two, a fit on the boundary over all at a turning point.
    static constexpr std::size_t keptResults = 4;
    std::vector<std::vector<Vector3>> solutionHistory_;
    // At a turning point of the motion: the predictor G = u_0 + Σ_j c_j (u_0 − u_j) over
    // solutionHistory_ whose c fits the prescribed change on the prescribed nodes best (the
    // candidates in the .cpp), `secant` (c_1 alone) among them.
    std::vector<double> bestPredictorOnBoundary(std::span<const Vector3> prescribedDisplacement,
                                                std::vector<double> secant) const;
    // The last Newton corrections (result − predictor, compact), newest first, for the
    // subspace step of warm starts (ReducedNewtonOptions::correctionMemory).
    std::vector<std::vector<double>> recentCorrections_;
    bool correctionsFromChain_ = false;  // recentCorrections_ are a chain's (else one unchained solve's)
    // harmonicChangeFromBasis: orthonormal prescribed changes (dimension() entries per prescribed
    // node, in prescribedNodes_ order) and K⁻¹ B of each (compact); at most 12 (a 3D rigid motion's
    // space), kept only while one extension has at most maximumHarmonicBasisEntries entries.
    std::vector<int> prescribedNodes_;
    std::vector<std::vector<double>> boundaryBasis_, harmonicBasis_;
    static constexpr std::size_t maximumHarmonicBasisSize = 12;
    static constexpr std::size_t maximumHarmonicBasisEntries = 1 << 20;  // 8 MiB an extension, 96 MiB at most
    // A change counts as a combination when what is left outside the basis is below this share
    // of it (rounding of rotated coordinates is about 1e-13 of the change; the start only needs
    // to be close, Newton ends at the same minimum).
    static constexpr double harmonicBasisTolerance = 1e-9;
    // A change below this share of the displacements themselves is rounding: no correction.
    static constexpr double roundingChangeShare = 1e-12;
    int correctionsFromHarmonicBasis_ = 0;
    std::vector<double> inverseShortestEdge_;  // per unknown node, for displacementTolerance
    std::vector<int> boundaryNeighbours_;      // unknown nodes (compact) next to a prescribed one, then -1
    std::vector<double> cgResidual_, cgPreconditioned_, cgPreviousPreconditioned_, cgDirection_, cgProduct_;
};

} // namespace rbm::motion
