#include "NewtonCg.hpp"

#include "BacktrackingLineSearch.hpp"
#include "OrderedSums.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rbm::motion {

NewtonCg::NewtonCg(const RbmProblem& problem, ReducedEnergy& energy, LaplacianPreconditioner& preconditioner,
                   const RelativeDisplacement& relativeDisplacement, const NewtonCgOptions& options)
    : problem_(problem), energy_(energy), preconditioner_(preconditioner), relativeDisplacement_(relativeDisplacement), options_(options)
{
    if (problem.dimension() == 3) {
        // 3D: Eisenstat–Walker's exponent (1 + √5)/2 instead of 2 (PETSc's SNES default), and the
        // last step solved to 0.2 instead of 0.1 of the final tolerance. On large 3D meshes the
        // squared ratio oversolved every step: the gradient fell by far less than CG had been
        // asked for (the nonlinearity, not the linear solve, limited the step).
        forcingExponent_ = 0.5 * (1.0 + std::sqrt(5.0));
        finalForcingFactor_ = 0.2;
    }
}

void NewtonCg::startSolve(double gradientNorm)
{
    forcing_ = 0.1;
    previousGradientNorm_ = gradientNorm;
    firstNewtonIteration_ = 0;
    localGlobalSteps_ = 0;
}

void NewtonCg::updateForcing(int iteration, double gradientNorm, double finalTolerance)
{
    if (iteration > firstNewtonIteration_) {
        const double ratio = gradientNorm / previousGradientNorm_;
        const double safeguard = 0.9 * std::pow(forcing_, forcingExponent_);
        forcing_ = 0.9 * std::pow(ratio, forcingExponent_);
        if (safeguard > 0.1) forcing_ = std::max(forcing_, safeguard);
    }
    forcing_ = std::clamp(forcing_, finalForcingFactor_ * finalTolerance / gradientNorm, 0.5);
}

void NewtonCg::forceToFinalTolerance(double gradientNorm, double finalTolerance)
{
    forcing_ = std::min(forcing_, finalForcingFactor_ * finalTolerance / gradientNorm);
}

void NewtonCg::restartAfter(int iteration, double gradientNorm)
{
    previousGradientNorm_ = gradientNorm;
    firstNewtonIteration_ = iteration + 1;
}

NewtonCg::Outcome NewtonCg::step(ReducedIterate& point, const CompactUnknowns& unknowns,
                                 const std::vector<double>* firstPreconditioned, int iteration, int& linearIterations,
                                 bool monitor)
{
    std::vector<double>& g = point.gradient;
    std::vector<double>& step = step_;
    step.resize(g.size());
    energy_.prepareHessian(point.displacement, point.rotations);
    const int linearIterationsBefore = linearIterations;
    bool negativeCurvature = false;
    const bool directionFound = direction(g, forcing_, firstPreconditioned, step, linearIterations, negativeCurvature);
    releaseLinearWork();
    if (!directionFound) return Outcome::linearSolveFailed;
    double slope = problem_.compactDot(g, step);
    if (!(slope < 0.0)) {
        // Not a descent direction (rounding near a negative curvature): a local/global step.
        if (!preconditioner_.apply(g, step)) return Outcome::linearSolveFailed;
        for (double& value : step) value = -value;
        slope = problem_.compactDot(g, step);
        negativeCurvature = true;
    }
    if (negativeCurvature) ++localGlobalSteps_;
    trialGradient_.resize(g.size());

    // Where Ẽ no longer resolves the decrease, a step that lowers ‖P∇Ẽ‖ is taken.
    bool gradientKnown = false;  // trialGradient_ is the last trial point's
    double trialGradientNorm = point.gradientNorm;
    const LineSearchResult search = backtrackingLineSearch(
        point.energy, slope,
        [&](double lambda) {
            unknowns.moveAlong(point.displacement, step, lambda, trial_);
            gradientKnown = false;
            return energy_.fitAndEnergy(trial_, trialRotations_);
        },
        [&] {
            energy_.gradient(trial_, trialRotations_, trialGradient_);
            trialGradientNorm = problem_.compactNorm(trialGradient_);
            gradientKnown = true;
            return trialGradientNorm < point.gradientNorm;
        });
    if (!search.accepted) return Outcome::lineSearchFailed;
    if (!gradientKnown) {
        energy_.gradient(trial_, trialRotations_, trialGradient_);
        trialGradientNorm = problem_.compactNorm(trialGradient_);
    }
    if (monitor)
        std::printf("  reduced Newton %d: |P grad| %.6e -> %.6e, CG %d (forcing %.2e), step %.3g, energy %.12e%s\n",
                    iteration, point.gradientNorm, trialGradientNorm, linearIterations - linearIterationsBefore,
                    forcing_, search.lambda, search.energy, negativeCurvature ? ", negative curvature" : "");
    point.displacement.swap(trial_);
    point.rotations.swap(trialRotations_);
    g.swap(trialGradient_);
    point.energy = search.energy;
    previousGradientNorm_ = point.gradientNorm;
    point.gradientNorm = trialGradientNorm;
    releaseTrial();
    return Outcome::stepTaken;
}

bool NewtonCg::direction(std::span<const double> g, double forcing, const std::vector<double>* firstPreconditioned,
                         std::span<double> step, int& iterations, bool& negativeCurvature)
{
    // Flexible (Polak–Ribière) preconditioned CG, so that an iterative K⁻¹ is allowed too.
    const std::size_t size = g.size();
    // Work vectors of this call (releaseLinearWork frees them once the step is known).
    std::vector<double>& r = cgResidual_;
    std::vector<double>& z = cgPreconditioned_;
    std::vector<double>& previousZ = cgPreviousPreconditioned_;
    std::vector<double>& p = cgDirection_;
    std::vector<double>& sp = cgProduct_;
    for (std::vector<double>* work : {&r, &z, &previousZ, &p, &sp}) work->resize(size);
    for (std::size_t k = 0; k < size; ++k) r[k] = -g[k];
    std::fill(step.begin(), step.end(), 0.0);
    const double target = forcing * problem_.compactNorm(g);
    if (firstPreconditioned) z = *firstPreconditioned;
    else if (!preconditioner_.apply(r, z)) return false;
    p = z;
    // The step is good enough once K⁻¹ of its residual, the gradient it leaves to first order,
    // is half the displacement tolerance: the next Newton iteration then stops.
    const double displacementTarget = 0.5 * options_.displacementTolerance;
    double rz = problem_.compactDot(r, z);
    negativeCurvature = false;
    for (int iteration = 0; iteration < options_.maximumLinearIterations; ++iteration) {
        energy_.applyHessian(p, sp);
        const double curvature = problem_.compactDot(p, sp);
        if (!(curvature > 0.0)) {
            // Steihaug: stop at a direction of negative curvature. With nothing yet, the
            // preconditioned gradient −K⁻¹∇Ẽ (a local/global step).
            negativeCurvature = true;
            if (iteration == 0) std::copy(z.begin(), z.end(), step.begin());
            return true;
        }
        const double alpha = rz / curvature;
        for (std::size_t k = 0; k < size; ++k) {
            step[k] += alpha * p[k];
            r[k] -= alpha * sp[k];
        }
        ++iterations;
        if (problem_.compactNorm(r) <= target) return true;
        previousZ.swap(z);
        if (!preconditioner_.apply(r, z)) return false;
        if (displacementTarget > 0.0 && relativeDisplacement_.largest(z) <= displacementTarget) return true;
        double numerator = 0.0;
        for (std::size_t k = 0; k < size; ++k) numerator += r[k] * (z[k] - previousZ[k]);
        const double beta = std::max(0.0, numerator / rz);
        rz = problem_.compactDot(r, z);
        for (std::size_t k = 0; k < size; ++k) p[k] = z[k] + beta * p[k];
    }
    return true;  // the iteration limit: the step so far still is a descent direction
}

void NewtonCg::releaseWork()
{
    std::vector<double>().swap(step_);
    releaseLinearWork();
    releaseTrial();
}

void NewtonCg::releaseLinearWork()
{
    for (std::vector<double>* work : {&cgResidual_, &cgPreconditioned_, &cgPreviousPreconditioned_, &cgDirection_, &cgProduct_})
        std::vector<double>().swap(*work);
}

void NewtonCg::releaseTrial()
{
    std::vector<double>().swap(trialGradient_);
    std::vector<Vector3>().swap(trial_);
    std::vector<Matrix3>().swap(trialRotations_);
}

} // namespace rbm::motion
