#pragma once
// One Newton step of the reduced method: S s = −∇Ẽ solved by preconditioned conjugate
// gradients with K⁻¹ as the preconditioner (LaplacianPreconditioner.hpp), then a backtracking
// line search on Ẽ (BacktrackingLineSearch.hpp) that keeps every step a descent step.
//
// Inexact Newton: Eisenstat–Walker's forcing (choice 2) solves early steps loosely. The CG is
// flexible (Polak–Ribière) so that an iterative K⁻¹ is allowed too. A direction of negative
// curvature stops CG (Steihaug); at the first CG iteration the step is then the preconditioned
// gradient −K⁻¹∇Ẽ, which is exactly a local/global step (LocalGlobalSolver.hpp). With the
// displacement test on, CG also stops once K⁻¹ of its residual (the gradient the step leaves,
// to first order) moves no node by more than half the displacement tolerance.

#include "CompactUnknowns.hpp"
#include "LaplacianPreconditioner.hpp"
#include "ReducedEnergy.hpp"
#include "ReducedIterate.hpp"
#include "RelativeDisplacement.hpp"

#include <span>
#include <vector>

namespace rbm::motion {

struct NewtonCgOptions {
    int maximumLinearIterations = 1000;  // CG iterations per Newton step
    double displacementTolerance = 1e-6;  // CG's displacement target is half of it (≤ 0: none)
};

class NewtonCg {
public:
    NewtonCg(const RbmProblem& problem, ReducedEnergy& energy, LaplacianPreconditioner& preconditioner,
             const RelativeDisplacement& relativeDisplacement, const NewtonCgOptions& options);

    // At the start of a solve, ‖P∇Ẽ‖ there.
    void startSolve(double gradientNorm);
    // The forcing η of Newton iteration `iteration` at ‖P∇Ẽ‖ = gradientNorm: η = 0.9
    // (‖g‖/‖g_prev‖)^exponent, safeguarded, at most 0.5, and no tighter than the final
    // tolerance (finalTolerance, the larger of the gradient's tolerance and its rounding level)
    // needs.
    void updateForcing(int iteration, double gradientNorm, double finalTolerance);
    // Close to the minimum: the step to the final tolerance (the displacement target then ends
    // CG, not the forcing).
    void forceToFinalTolerance(double gradientNorm, double finalTolerance);
    // A step was taken outside Newton (the warm start's subspace step) at `iteration`: the
    // forcing's ratio starts afresh after it.
    void restartAfter(int iteration, double gradientNorm);

    enum class Outcome { stepTaken, linearSolveFailed, lineSearchFailed };
    // One Newton step from point (moved to the new point when taken). firstPreconditioned:
    // K⁻¹(−∇Ẽ) where the caller has it (the displacement test's), else computed here.
    // linearIterations: CG iterations added.
    Outcome step(ReducedIterate& point, const CompactUnknowns& unknowns, const std::vector<double>* firstPreconditioned,
                 int iteration, int& linearIterations, bool monitor);
    // Steps of this solve that met negative curvature (local/global steps).
    int localGlobalSteps() const { return localGlobalSteps_; }
    // At the end of a solve: frees the work arrays (about 260 bytes a node in 3D), which the
    // solver would otherwise hold through the quality check and the writing of every step;
    // the next solve allocates them again.
    void releaseWork();

private:
    // The two phases of a Newton step never need each other's arrays: CG's vectors are dead once
    // the step is known, and the line search's trial point (after the swap, the previous
    // iterate) is dead until the next line search. Each phase frees its own at its end, so the
    // solve's peak holds one phase's arrays, not both (120 bytes a node less in 3D, at the
    // price of allocating them again at each Newton step: page faults, not arithmetic).
    void releaseLinearWork();
    void releaseTrial();

    // Projected CG on S s = −g to ‖S s + g‖ ≤ forcing ‖g‖ (see the file comment).
    bool direction(std::span<const double> g, double forcing, const std::vector<double>* firstPreconditioned,
                   std::span<double> step, int& iterations, bool& negativeCurvature);

    const RbmProblem& problem_;  // its reductions (a part's over the ranks)
    ReducedEnergy& energy_;
    LaplacianPreconditioner& preconditioner_;
    const RelativeDisplacement& relativeDisplacement_;
    NewtonCgOptions options_;
    // Eisenstat–Walker's exponent and the final step's share of the final tolerance (by dimension).
    double forcingExponent_ = 2.0;
    double finalForcingFactor_ = 0.1;
    // This solve's forcing state.
    double forcing_ = 0.1;
    double previousGradientNorm_ = 0.0;
    int firstNewtonIteration_ = 0;
    int localGlobalSteps_ = 0;
    // Work arrays.
    std::vector<double> step_, trialGradient_;
    std::vector<Vector3> trial_;
    std::vector<Matrix3> trialRotations_;
    std::vector<double> cgResidual_, cgPreconditioned_, cgPreviousPreconditioned_, cgDirection_, cgProduct_;
};

} // namespace rbm::motion
