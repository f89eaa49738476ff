#include "ReducedNewtonSolver.hpp"

#include "LocalGlobalSolver.hpp"
#include "NodeExchange.hpp"
#include "OrderedSums.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <cstdio>
#include <sstream>
#include <utility>

namespace rbm::motion {

namespace {

// CoupledNewtonSolver's default absolute tolerance on ‖P∇Ẽ‖: about 1e-11 of a cell per node.
double defaultAbsoluteTolerance(const RbmProblem& problem)
{
    const CellNeighbourGraph& graph = problem.graph();
    // A part: its owned nodes' edges, summed over the ranks.
    double sum = 0.0;
    for (int i = 0; i < problem.ownedNodeCount(); ++i)
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            Vector3 d = problem.referencePoints()[graph.neighbours[e]] - problem.referencePoints()[i];
            if (problem.dimension() == 2) d.z = 0.0;
            sum += problem.edgeWeights()[e] * norm(d);
        }
    sum = problem.sumOverRanks(sum);
    const double edges = problem.sumOverRanks(graph.offsets[problem.ownedNodeCount()]);
    const double unknownNodes = static_cast<double>(problem.totalUnknownNodeCount());
    const double meanWeightedLength = edges > 0 ? sum / edges : 1.0;
    return 1e-11 * meanWeightedLength * std::sqrt(std::max(1.0, unknownNodes));
}

} // namespace

ReducedNewtonSolver::ReducedNewtonSolver(const RbmProblem& problem, ReducedNewtonOptions options)
    : problem_(problem), options_(options),
      preconditioner_(problem, options.linearSolver, options.laplacianRelativeTolerance),
      reducedEnergy_(problem, options.scaling, options.transverseStiffness),
      relativeDisplacement_(problem, options.displacementTolerance > 0.0),
      warmStart_(problem, reducedEnergy_, preconditioner_, relativeDisplacement_,
                 {options.turnedStart, options.correctionMemory, options.harmonicBasis, options.displacementTolerance}),
      newtonCg_(problem, reducedEnergy_, preconditioner_, relativeDisplacement_,
                {options.maximumLinearIterations, options.displacementTolerance})
{
    absoluteTolerance_ = options.absoluteTolerance < 0.0 ? defaultAbsoluteTolerance(problem) : options.absoluteTolerance;
    // -rbm_reduced_max_it N (Newton steps) and -rbm_reduced_monitor (one line per step).
    PetscInt maximumIterations = options_.maximumIterations;
    RBM_CHECK_PETSC(PetscOptionsGetInt(nullptr, "rbm_reduced_", "-max_it", &maximumIterations, nullptr));
    options_.maximumIterations = static_cast<int>(maximumIterations);
    PetscBool monitor = PETSC_FALSE;
    RBM_CHECK_PETSC(PetscOptionsHasName(nullptr, "rbm_reduced_", "-monitor", &monitor));
    monitor_ = monitor == PETSC_TRUE;
    // A part's figures are the whole problem's (reduced over the ranks): rank 0 prints them.
    if (const NodeExchange* exchange = problem.nodeExchange(); monitor_ && exchange) {
        int rank = 0;
        RBM_CHECK_PETSC(MPI_Comm_rank(exchange->communicator(), &rank));
        monitor_ = rank == 0;
    }
}

ReducedNewtonSolver::~ReducedNewtonSolver() = default;

bool ReducedNewtonSolver::displacementTestPasses(const std::vector<double>& gradient, const char* where,
                                                 bool& laplacianFailed)
{
    estimatedCorrection_.resize(gradient.size());
    {
        // Local: not alive through the CG that may follow (the solve's peak).
        std::vector<double> negativeGradient(gradient.size());
        for (std::size_t k = 0; k < gradient.size(); ++k) negativeGradient[k] = -gradient[k];
        laplacianFailed = !preconditioner_.apply(negativeGradient, estimatedCorrection_);
    }
    if (laplacianFailed) return false;
    estimatedDisplacement_ = relativeDisplacement_.largest(estimatedCorrection_);
    if (monitor_)
        std::printf("  displacement test%s: K^-1(-grad) moves a node by %.3g of its shortest edge (tolerance %.3g)\n",
                    where, estimatedDisplacement_, options_.displacementTolerance);
    return estimatedDisplacement_ <= options_.displacementTolerance;
}

RbmResult ReducedNewtonSolver::solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess)
{
    problem_.checkNodeArray(prescribedDisplacement, "prescribed displacement");
    if (problem_.totalUnknownNodeCount() == 0) return prescribedOnlyResult(problem_, prescribedDisplacement);
    const bool displacementTest = options_.displacementTolerance > 0.0;
    if (options_.transverseStiffness > 0.0)
        reducedEnergy_.setTranslation(
            TransverseGradientPenalty::translationTowardsFixedWalls(problem_, prescribedDisplacement));
    const CompactUnknowns unknowns(problem_, prescribedDisplacement);
    WarmStart::Start start = warmStart_.start(prescribedDisplacement, initialGuess, unknowns);
    // Moved, not copied: record() below reads the start's predictor only, and a copy would keep
    // a second iterate (displacements, rotations, gradient: 120 bytes a node) through the solve.
    ReducedIterate point = std::move(start.point);
    const double tolerance = std::max(absoluteTolerance_, options_.relativeTolerance * point.gradientNorm);
    newtonCg_.startSolve(point.gradientNorm);
    RbmResult result;
    result.converged = false;
    std::string reason = start.failure;
    bool subspaceStepDue = start.subspaceStepDue;
    const bool finite = std::isfinite(point.energy) && std::isfinite(point.gradientNorm);
    bool laplacianFailed = false;
    // Where the boundary is reproduced, the displacement test first: the subspace step's
    // products (the Hessian's data, S products, a fit and a gradient) would end "not taken"
    // there. Where the test fails, its K⁻¹ is one back-substitution (or cycle) more.
    if (start.boundaryReproduced && subspaceStepDue && displacementTest && reason.empty() && finite &&
        point.gradientNorm > tolerance && displacementTestPasses(point.gradient, " at the reproduced boundary", laplacianFailed)) {
        result.converged = true;
        reason = "CONVERGED_DISPLACEMENT";
    }
    for (int iteration = 0; start.failure.empty() && !result.converged; ++iteration) {
        double roundingLevel = 0.0;
        if (const std::optional<Stop> stop = stopBefore(point, tolerance, iteration, roundingLevel)) {
            result.converged = stop->converged;
            reason = stop->reason;
            break;
        }
        const double finalTolerance = std::max(tolerance, roundingLevel);
        newtonCg_.updateForcing(iteration, point.gradientNorm, finalTolerance);
        // First, the warm start's subspace step; then the tests and Newton from the new point.
        // Before the displacement test, whose K⁻¹(−∇Ẽ) would be thrown away: a step smaller
        // than that test's tolerance is not taken.
        if (std::exchange(subspaceStepDue, false) && warmStart_.subspaceStep(point, unknowns, monitor_) > 0) {
            ++result.iterations;
            newtonCg_.restartAfter(iteration, point.gradientNorm);
            continue;
        }
        const std::vector<double>* firstPreconditioned = nullptr;
        if (displacementTest) {
            if (const std::optional<Stop> stop = displacementTestBeforeStep(point, finalTolerance)) {
                result.converged = stop->converged;
                reason = stop->reason;
                break;
            }
            firstPreconditioned = &estimatedCorrection_;
        }
        const NewtonCg::Outcome outcome =
            newtonCg_.step(point, unknowns, firstPreconditioned, iteration, result.linearIterations, monitor_);
        if (outcome != NewtonCg::Outcome::stepTaken) {
            reason = outcome == NewtonCg::Outcome::linearSolveFailed ? "DIVERGED_LINEAR_SOLVE (Laplacian)"
                                                                     : "DIVERGED_LINE_SEARCH";
            break;
        }
        ++result.iterations;
    }
    // The work arrays go between solves (the caller's quality check and output come next), and
    // before record(), whose copies of the result would otherwise add to them at the solve's peak.
    newtonCg_.releaseWork();
    reducedEnergy_.releaseHessian();
    std::vector<double>().swap(estimatedCorrection_);
    warmStart_.record(start, point.displacement, result.converged, initialGuess != nullptr, unknowns);
    return finishedResult(std::move(point), std::move(result), reason);
}

std::optional<ReducedNewtonSolver::Stop> ReducedNewtonSolver::stopBefore(const ReducedIterate& point, double tolerance,
                                                                         int iteration, double& roundingLevel)
{
    constexpr double roundoffFactor = 10.0;  // as CoupledNewtonSolver's convergence test
    if (!(std::isfinite(point.energy) && std::isfinite(point.gradientNorm))) return Stop{false, "DIVERGED_FNORM_NAN"};
    if (point.gradientNorm <= tolerance)
        return Stop{true, point.gradientNorm <= absoluteTolerance_ ? "CONVERGED_FNORM_ABS" : "CONVERGED_FNORM_RELATIVE"};
    roundingLevel = roundoffFactor * reducedEnergy_.gradientRoundoffNorm(point.displacement);
    if (point.gradientNorm <= roundingLevel) return Stop{true, "CONVERGED_FNORM_ABS (rounding level)"};
    if (iteration >= options_.maximumIterations) return Stop{false, "DIVERGED_MAX_IT"};
    return std::nullopt;
}

std::optional<ReducedNewtonSolver::Stop> ReducedNewtonSolver::displacementTestBeforeStep(const ReducedIterate& point,
                                                                                       double finalTolerance)
{
    // The displacement test: K⁻¹(−∇Ẽ), the local/global estimate of the remaining
    // displacement (S ≤ K: it underestimates the Newton step), small against every node's
    // shortest edge. It is CG's first preconditioned residual too, so the test costs
    // nothing when it fails.
    bool laplacianFailed = false;
    if (displacementTestPasses(point.gradient, "", laplacianFailed)) return Stop{true, "CONVERGED_DISPLACEMENT"};
    if (laplacianFailed) return Stop{false, "DIVERGED_LINEAR_SOLVE (Laplacian)"};
    // Close to the minimum the step's own nonlinearity is of the order of the squared
    // displacement (relative to the edges): with D² ≤ 10 ε it is a fraction of ε, and the
    // gradient after the step is CG's residual. So CG goes on to the displacement target
    // that makes the next test pass instead of stopping at the forcing and leaving a
    // Newton step more (CloseToTheMinimumOneNewtonStepPassesTheDisplacementTest).
    if (estimatedDisplacement_ * estimatedDisplacement_ <= 10.0 * options_.displacementTolerance)
        newtonCg_.forceToFinalTolerance(point.gradientNorm, finalTolerance);
    return std::nullopt;
}

RbmResult ReducedNewtonSolver::finishedResult(ReducedIterate point, RbmResult result, const std::string& reason) const
{
    const int n = problem_.nodeCount();
    result.displacement = std::move(point.displacement);
    // Every iterate lies on u_b = q u_a up to the rounding of its steps; the result exactly.
    problem_.enforceCoupledPairs(result.displacement);
    result.rotation.assign(n, Vector3{});
    if (point.rotations.size() == static_cast<std::size_t>(n))
        for (int node : problem_.unknownNodes())
            result.rotation[node] = rotationParameters(problem_.dimension(), point.rotations[node]);
    // E(u, R*(u)) = Ẽ(u), and ‖P∇E‖ = ‖P∇Ẽ‖ since ∇_R E = 0 at the best fit (ReducedEnergy.hpp):
    // the values of the last iterate, without a second evaluation.
    result.energy = point.energy;
    result.residualNorm = point.gradientNorm;
    std::ostringstream text;
    text << reason;
    const int localGlobalSteps = newtonCg_.localGlobalSteps();
    if (localGlobalSteps > 0) text << " (" << localGlobalSteps << " local/global steps at negative curvature)";
    result.reason = text.str();
    return result;
}

} // namespace rbm::motion
