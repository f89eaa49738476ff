#include "CoupledLinearizedSolver.hpp"

#include "RbmEnergy.hpp"
#include "RigidMotionModes.hpp"

#include <algorithm>
#include <cmath>

namespace rbm::motion {

CoupledLinearizedSolver::CoupledLinearizedSolver(const RbmProblem& problem, CoupledLinearizedOptions options)
    : problem_(problem), options_(options)
{
    if (problem.unknownNodeCount() > 0 &&
        matrixFreeChosen(options.linearSolver, problem.dimension(), problem.unknownCount())) {
        matrixFree_ = std::make_unique<MatrixFreeLinearizedSystem>(problem, options.relativeTolerance);
        return;
    }
    const BlockPattern& pattern = problem.blockPattern();
    const int bs = problem.blockSize();
    system_ = std::make_unique<BlockSystemSolver>(pattern.rowOffsets, pattern.columns, bs,
                                                  MatrixSymmetry::symmetricPositiveDefinite, options.linearSolver,
                                                  problem.dimension(), options.relativeTolerance, "linearized");
    // The small-angle Hessian does not depend on the state nor on the prescribed values.
    const std::vector<Vector3> zero(problem.nodeCount());
    const RbmEnergy energy(problem, RotationModel::smallAngle, zero);
    std::vector<double> blocks(static_cast<std::size_t>(pattern.blockCount()) * bs * bs);
    const std::vector<double> origin(problem.unknownCount(), 0.0);
    energy.hessian(origin, blocks);
    problem.projectSlidingBlocks(blocks, bs);
    system_->setMatrix(blocks);
    if (!system_->isDirect()) system_->setNearNullSpace(rigidMotionModes(problem));
}

std::vector<double> CoupledLinearizedSolver::solveUnknowns(std::span<const Vector3> prescribedDisplacement,
                                                           const RbmState* initialGuess,
                                                           BlockSystemSolver::Report& report)
{
    if (matrixFree_) return matrixFree_->solveUnknowns(prescribedDisplacement, initialGuess, report);
    const RbmEnergy energy(problem_, RotationModel::smallAngle, prescribedDisplacement);
    // Start point z0: zero, except the normal offset c n of sliding nodes; E is quadratic,
    // so the minimiser over z0 + range(P) is z0 + δ with (P H P) δ = −P ∇E(z0).
    std::vector<double> start(problem_.unknownCount(), 0.0);
    problem_.slidingOffset(prescribedDisplacement, start);
    std::vector<double> rightHandSide(start.size());
    energy.gradient(start, rightHandSide);
    problem_.projectSliding(rightHandSide);
    for (double& value : rightHandSide) value = -value;

    std::vector<double> step(start.size(), 0.0);
    bool useGuess = false;
    if (initialGuess && !system_->isDirect()) {
        packUnknowns(problem_, *initialGuess, step);
        for (std::size_t k = 0; k < step.size(); ++k) step[k] -= start[k];
        problem_.projectSliding(step);
        useGuess = true;
    }
    report = system_->solve(rightHandSide, step, useGuess);
    problem_.projectSliding(step);  // exact constraint despite the solver's rounding
    // P∇E_lin(start + δ) = P∇E(start) + P H δ = M δ − rhs (M = P H P + s(I − P), Pδ = δ): one
    // block product instead of a second gradient evaluation, a noticeable share of a
    // linearized time step.
    std::vector<double> residual(step.size());
    system_->multiply(step, residual);
    double sum = 0.0;
    for (std::size_t k = 0; k < residual.size(); ++k) sum += (residual[k] - rightHandSide[k]) * (residual[k] - rightHandSide[k]);
    report.residualNorm = std::sqrt(sum);
    for (std::size_t k = 0; k < step.size(); ++k) start[k] += step[k];
    return start;
}

RbmResult CoupledLinearizedSolver::solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess)
{
    if (problem_.unknownNodeCount() == 0) return prescribedOnlyResult(problem_, prescribedDisplacement);
    BlockSystemSolver::Report report;
    const std::vector<double> unknowns = solveUnknowns(prescribedDisplacement, initialGuess, report);

    RbmResult result;
    static_cast<RbmState&>(result) = unpackUnknowns(problem_, prescribedDisplacement, unknowns);
    result.iterations = 1;
    result.linearIterations = report.iterations;
    result.converged = report.converged;
    result.reason = report.reason;

    result.residualNorm = report.residualNorm;
    if (result.residualNorm < 0.0) {
        const RbmEnergy linearized(problem_, RotationModel::smallAngle, prescribedDisplacement);
        std::vector<double> gradient(unknowns.size());
        linearized.gradient(unknowns, gradient);
        problem_.projectSliding(gradient);
        double sum = 0.0;
        for (double g : gradient) sum += g * g;
        result.residualNorm = std::sqrt(sum);
    }
    result.energy = RbmEnergy(problem_, RotationModel::exact, prescribedDisplacement).value(unknowns);
    return result;
}

} // namespace rbm::motion
