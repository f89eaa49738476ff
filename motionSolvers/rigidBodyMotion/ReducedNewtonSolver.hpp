#pragma once
// The coupled nonlinear RBM method by Newton's method on the displacements alone, with every
// node's rotation eliminated by its best fit, and one Laplacian factorisation per run
// (`algorithm reducedNewton`, the default; issue 12). The driver of the parts in
// reducedNewton/:
//
//   ReducedEnergy           Ẽ(u) = min_R E(u, R), its gradient and Hessian products S v;
//                           Newton on Ẽ never meets the stationary points with flipped node
//                           frames that Newton on (u, R) can stop at (CoupledNewtonSolver.hpp);
//   LaplacianPreconditioner K⁻¹, factorised (or its multigrid set up) once per run;
//   WarmStart               the start of each solve (cold: harmonic, or the body's turn; warm:
//                           the time-series predictor and its subspace step) and the history;
//   NewtonCg                forcing, CG on S s = −∇Ẽ preconditioned by K⁻¹, line search.
//
// Convergence: as CoupledNewtonSolver: ‖P∇Ẽ‖ below the absolute tolerance (1e-11 × mean w|d|
// × √unknown nodes by default), or 1e-10 × its start value, or 10 × the rounding level of the
// gradient (RbmEnergy::gradientRoundoffNorm); or, with the displacement test, when K⁻¹(−P∇Ẽ)
// moves no node by more than displacementTolerance of its shortest edge. ∇_R E = 0 at R*, so
// ‖P∇Ẽ‖ is ‖P∇E‖.
//
// Determinism: every loop over nodes writes its own node's entries and every sum runs in node
// order, so the result is bit-identical for any thread count.
//
// PETSc options, read when the solver is built: -rbm_reduced_max_it N (Newton steps),
// -rbm_reduced_monitor (one line per step); the parts' own (LaplacianPreconditioner.hpp,
// WarmStart.hpp).
// Result: iterations = Newton and subspace steps, linearIterations = CG iterations,
// residualNorm = ‖P∇E‖, energy = E.

#include "LaplacianPreconditioner.hpp"
#include "NewtonCg.hpp"
#include "RbmProblem.hpp"
#include "ReducedEnergy.hpp"
#include "ReducedIterate.hpp"
#include "RelativeDisplacement.hpp"
#include "WarmStart.hpp"

#include <optional>
#include <span>
#include <string>
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
    // rounding level of the 1/|d|²-weighted gradient, so this saves the last CG iterations
    // (docs/motionSolver.md, "Reduced Newton"). The same default as the dictionary's
    // (RigidBodyMotionOptions).
    double displacementTolerance = 1e-6;
    // Cold starts where the boundary is one rigid body in a fixed frame (2D or 3D; K factorised
    // by rbm or the 3D multigrid cycle): also try the harmonic interpolation of the body's turn
    // (TurnedStart.hpp; false: only the harmonic interpolation of the displacements, for tests).
    bool turnedStart = true;
    // Warm starts along a chain of own results: the Newton corrections of the last
    // correctionMemory steps (result − predictor) span the first step, a Galerkin step in that
    // subspace (WarmStart.hpp; 0: off; -rbm_reduced_correction_memory N). Along a smooth motion
    // the corrections of successive steps point almost the same way.
    int correctionMemory = 3;
    // Warm starts: the harmonic correction of the predictor from the extensions of earlier
    // boundary changes where the new change is their combination (HarmonicChangeBasis.hpp;
    // false: a back-substitution at every step, for tests; -rbm_reduced_harmonic_basis false).
    bool harmonicBasis = true;
    // Rigid neighbourhoods (the thesis' energy) or similarities (NeighbourhoodScaling.hpp).
    NeighbourhoodScaling scaling;
    // λ of the penalty on the displacement's variation across a translation
    // (TransverseGradientPenalty.hpp), on in the solves whose moving prescribed nodes all
    // translate by one vector towards fixed walls facing it, along it; 0: off.
    double transverseStiffness = 0.0;
};

class ReducedNewtonSolver : public RbmSolver {
public:
    explicit ReducedNewtonSolver(const RbmProblem& problem, ReducedNewtonOptions options = {});
    ~ReducedNewtonSolver() override;

    const RbmProblem& problem() const override { return problem_; }
    RbmResult solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess = nullptr) override;
    // The extensions of boundary changes kept (ReducedNewtonOptions::harmonicBasis), and the
    // warm starts that took their correction from them instead of a back-substitution.
    std::size_t harmonicBasisSize() const { return warmStart_.harmonicBasis().size(); }
    int correctionsFromHarmonicBasis() const { return warmStart_.harmonicBasis().correctionsFromBasis(); }

private:
    // The displacement test at P∇Ẽ = gradient: K⁻¹(−gradient) into estimatedCorrection_, its
    // largest relative displacement into estimatedDisplacement_, true when that is within the
    // tolerance; laplacianFailed when K⁻¹ failed. where: the monitor line's context.
    bool displacementTestPasses(const std::vector<double>& gradient, const char* where, bool& laplacianFailed);
    // Why a solve stops (converged or not).
    struct Stop {
        bool converged = false;
        std::string reason;
    };
    // The tests before an iteration, in order: a non-finite point, the gradient's tolerance,
    // its rounding level (returned in roundingLevel once computed), the iteration limit.
    std::optional<Stop> stopBefore(const ReducedIterate& point, double tolerance, int iteration,
                                   double& roundingLevel);
    // The displacement test before a Newton step; where it fails but the point is close to the
    // minimum, CG is told to go on to the final tolerance.
    std::optional<Stop> displacementTestBeforeStep(const ReducedIterate& point, double finalTolerance);
    // The result of a solve ending at point, with the reason and the count of local/global steps.
    RbmResult finishedResult(ReducedIterate point, RbmResult result, const std::string& reason) const;

    const RbmProblem& problem_;
    ReducedNewtonOptions options_;  // maximumIterations with -rbm_reduced_max_it read
    // K⁻¹ before the reduced energy: its set-up (a part's GAMG coarsening, the serial multigrid's
    // aggregation) is transient memory that the energy's per-node data then reuses instead of
    // adding to (the decomposed run's per-rank peak came in GAMG's set-up, with ReducedHessian3D
    // already allocated: docs/parallel.md, the measured table).
    LaplacianPreconditioner preconditioner_;
    ReducedEnergy reducedEnergy_;
    RelativeDisplacement relativeDisplacement_;
    WarmStart warmStart_;
    NewtonCg newtonCg_;
    double absoluteTolerance_ = 0.0;
    bool monitor_ = false;
    std::vector<double> estimatedCorrection_;  // the displacement test's K⁻¹(−∇Ẽ)
    double estimatedDisplacement_ = 0.0;
};

} // namespace rbm::motion
