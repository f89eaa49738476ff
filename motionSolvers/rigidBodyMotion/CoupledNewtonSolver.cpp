#include "CoupledNewtonSolver.hpp"

#include "BacktrackingLineSearch.hpp"
#include "BlockRowLayout.hpp"

#include <limits>

#include "LocalGlobalSolver.hpp"
#include "RbmEnergy.hpp"
#include "RigidMotionModes.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>

namespace rbm::motion {

struct CoupledNewtonSolver::Context {
    const RbmProblem* problem = nullptr;
    std::unique_ptr<BlockRowLayout> layout;  // PETSc rows over the ranks (identity when serial)
    std::vector<double> whole;        // the unknowns gathered from a PETSc vector, natural order
    std::optional<RbmEnergy> energy;  // exact energy for the current prescribed displacements
    std::vector<double> blocks;       // Hessian values in pattern order
    std::vector<double> work;         // gradient scratch
    Mat jacobian = nullptr;
    int gaussNewtonSteps = 0;         // steps recomputed with the Gauss–Newton matrix
};

namespace {

using Context = CoupledNewtonSolver::Context;

PetscErrorCode reportException(const char* function, const std::exception& error)
{
    return petscErrorFromException(function, error);
}

// The whole unknown vector of x, natural order, on every rank (BlockRowLayout).
std::span<const double> gatherUnknowns(Context& context, Vec x)
{
    context.whole.resize(static_cast<std::size_t>(context.problem->unknownCount()));
    context.layout->gather(x, context.whole, context.problem->blockSize());
    return context.whole;
}

double energyAt(Context& context, Vec x)
{
    return context.energy->value(gatherUnknowns(context, x));
}

// F = P ∇E (the thesis' Eq1–Eq3 with the sliding constraints).
PetscErrorCode formGradient(SNES, Vec x, Vec f, void* data)
{
    try {
        auto& context = *static_cast<Context*>(data);
        const std::span<const double> unknowns = gatherUnknowns(context, x);
        context.work.resize(unknowns.size());
        context.energy->gradient(unknowns, context.work);
        context.problem->projectSliding(context.work);
        context.layout->scatter(context.work, f, context.problem->blockSize());
        return 0;
    } catch (const std::exception& error) {
        return reportException("formGradient", error);
    }
}

PetscErrorCode formEnergy(SNES, Vec x, PetscReal* energy, void* data)
{
    try {
        *energy = energyAt(*static_cast<Context*>(data), x);
        return 0;
    } catch (const std::exception& error) {
        return reportException("formEnergy", error);
    }
}

void assembleHessian(Context& context, Vec x, Mat matrix, bool includeCurvature)
{
    const RbmProblem& problem = *context.problem;
    context.energy->hessian(gatherUnknowns(context, x), context.blocks, includeCurvature);
    problem.projectSlidingBlocks(context.blocks, problem.blockSize());
    const BlockPattern& pattern = problem.blockPattern();
    setBlockMatrixValues(matrix, *context.layout, pattern.rowOffsets, pattern.columns, problem.blockSize(),
                         context.blocks);
}

PetscErrorCode formHessian(SNES, Vec x, Mat, Mat preconditioner, void* data)
{
    try {
        assembleHessian(*static_cast<Context*>(data), x, preconditioner, true);
        return 0;
    } catch (const std::exception& error) {
        return reportException("formHessian", error);
    }
}

// Armijo backtracking on the energy along the Newton step x_new = x − λ y
// (BacktrackingLineSearch.hpp; near the minimum a step that reduces ‖F‖). A step that is not a
// descent direction (exact Hessian indefinite) is recomputed with the Gauss–Newton matrix.
PetscErrorCode energyLineSearch(SNESLineSearch lineSearch, void* data)
{
    try {
        auto& context = *static_cast<Context*>(data);
        Vec x = nullptr, f = nullptr, y = nullptr, w = nullptr, g = nullptr;
        SNES snes = nullptr;
        RBM_CHECK_PETSC(SNESLineSearchGetVecs(lineSearch, &x, &f, &y, &w, &g));
        RBM_CHECK_PETSC(SNESLineSearchGetSNES(lineSearch, &snes));
        RBM_CHECK_PETSC(SNESLineSearchSetReason(lineSearch, SNES_LINESEARCH_SUCCEEDED));

        double fNorm = 0.0, yNorm = 0.0, slope = 0.0;
        RBM_CHECK_PETSC(VecNorm(f, NORM_2, &fNorm));
        RBM_CHECK_PETSC(VecNorm(y, NORM_2, &yNorm));
        RBM_CHECK_PETSC(VecDot(f, y, &slope));
        slope = -slope;  // dE/dλ along −y
        if (!(slope < -1e-12 * fNorm * yNorm)) {
            KSP ksp = nullptr;
            RBM_CHECK_PETSC(SNESGetKSP(snes, &ksp));
            assembleHessian(context, x, context.jacobian, false);
            RBM_CHECK_PETSC(KSPSolve(ksp, f, y));
            ++context.gaussNewtonSteps;
            RBM_CHECK_PETSC(VecNorm(y, NORM_2, &yNorm));
            RBM_CHECK_PETSC(VecDot(f, y, &slope));
            slope = -slope;
            if (!(slope < 0.0)) {
                RBM_CHECK_PETSC(SNESLineSearchSetReason(lineSearch, SNES_LINESEARCH_FAILED_USER));
                return 0;
            }
        }

        const double energy0 = energyAt(context, x);
        const LineSearchResult search = backtrackingLineSearch(
            energy0, slope,
            [&](double lambda) {
                RBM_CHECK_PETSC(VecWAXPY(w, -lambda, y, x));
                return energyAt(context, w);
            },
            [&] {
                double gNorm = 0.0;
                RBM_CHECK_PETSC(SNESComputeFunction(snes, w, g));
                RBM_CHECK_PETSC(VecNorm(g, NORM_2, &gNorm));
                return gNorm < fNorm;
            });
        if (!search.accepted) {
            RBM_CHECK_PETSC(SNESLineSearchSetReason(lineSearch, SNES_LINESEARCH_FAILED_REDUCT));
            return 0;
        }
        RBM_CHECK_PETSC(SNESComputeFunction(snes, w, f));
        RBM_CHECK_PETSC(VecCopy(w, x));
        double xNorm = 0.0;
        RBM_CHECK_PETSC(VecNorm(x, NORM_2, &xNorm));
        RBM_CHECK_PETSC(VecNorm(f, NORM_2, &fNorm));
        RBM_CHECK_PETSC(SNESLineSearchSetNorms(lineSearch, xNorm, fNorm, search.lambda * yNorm));
        return 0;
    } catch (const std::exception& error) {
        return reportException("energyLineSearch", error);
    }
}

// PETSc's default tests, and one more: ‖F‖ within roundoffFactor of the rounding error of
// the gradient itself (RbmEnergy::gradientRoundoffNorm) counts as converged. Without it,
// a boundary-layer mesh whose ‖F‖ stalls at that floor above the absolute tolerance costs
// two extra Newton iterations (two factorisations) that change nothing.
PetscErrorCode convergedOrAtRoundoff(SNES snes, PetscInt iteration, PetscReal xNorm, PetscReal stepNorm,
                                     PetscReal fNorm, SNESConvergedReason* reason, void* data)
{
    try {
        RBM_CHECK_PETSC(SNESConvergedDefault(snes, iteration, xNorm, stepNorm, fNorm, reason, nullptr));
        if (*reason != SNES_CONVERGED_ITERATING || iteration == 0) return 0;
        constexpr double roundoffFactor = 10.0;  // the estimate is itself ~6x above the floor seen on the airfoil
        auto& context = *static_cast<Context*>(data);
        Vec x = nullptr;
        RBM_CHECK_PETSC(SNESGetSolution(snes, &x));
        if (fNorm <= roundoffFactor * context.energy->gradientRoundoffNorm(gatherUnknowns(context, x)))
            *reason = SNES_CONVERGED_FNORM_ABS;
        return 0;
    } catch (const std::exception& error) {
        return reportException("convergedOrAtRoundoff", error);
    }
}

} // namespace

CoupledNewtonSolver::CoupledNewtonSolver(const RbmProblem& problem, CoupledNewtonOptions options)
    : problem_(problem), options_(options), petscOptions_("newton"), context_(std::make_unique<Context>())
{
    context_->problem = &problem;
    const BlockPattern& pattern = problem.blockPattern();
    context_->layout = std::make_unique<BlockRowLayout>(solverCommunicator(), pattern.rowOffsets, pattern.columns);
    const BlockRowLayout& layout = *context_->layout;
    const int bs = problem.blockSize();
    context_->blocks.assign(static_cast<std::size_t>(pattern.blockCount()) * bs * bs, 0.0);

    double absoluteTolerance = options.absoluteTolerance;
    if (absoluteTolerance < 0.0) {
        const CellNeighbourGraph& graph = problem.graph();
        double sum = 0.0;
        for (int i = 0; i < problem.nodeCount(); ++i) {
            for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
                Vector3 d = problem.referencePoints()[graph.neighbours[e]] - problem.referencePoints()[i];
                if (problem.dimension() == 2) d.z = 0.0;
                sum += problem.edgeWeights()[e] * norm(d);
            }
        }
        const double meanWeightedLength = graph.edgeCount() > 0 ? sum / graph.edgeCount() : 1.0;
        absoluteTolerance = 1e-11 * meanWeightedLength * std::sqrt(std::max(1, problem.unknownNodeCount()));
    }

    solution_ = layout.createVector(bs);
    residual_ = layout.createVector(bs);
    RBM_CHECK_PETSC(SNESCreate(layout.communicator(), snes_.out()));
    RBM_CHECK_PETSC(SNESSetType(snes_, SNESNEWTONLS));
    RBM_CHECK_PETSC(SNESSetFunction(snes_, residual_, formGradient, context_.get()));
    RBM_CHECK_PETSC(SNESSetObjective(snes_, formEnergy, context_.get()));
    RBM_CHECK_PETSC(SNESSetTolerances(snes_, absoluteTolerance, options.relativeTolerance, 1e-14,
                                      options.maximumIterations, 100000));
    RBM_CHECK_PETSC(SNESSetConvergenceTest(snes_, convergedOrAtRoundoff, context_.get(), nullptr));
    SNESLineSearch lineSearch = nullptr;
    RBM_CHECK_PETSC(SNESGetLineSearch(snes_, &lineSearch));
    RBM_CHECK_PETSC(SNESLineSearchSetType(lineSearch, SNESLINESEARCHSHELL));
    RBM_CHECK_PETSC(SNESLineSearchShellSetUserFunc(lineSearch, energyLineSearch, context_.get()));
    KSP ksp = nullptr;
    RBM_CHECK_PETSC(SNESGetKSP(snes_, &ksp));
    setDefaultLinearSolver(ksp, options.linearSolver, problem.dimension(), problem.unknownCount(),
                           MatrixSymmetry::symmetric, options.linearRelativeTolerance);
    configureFromOptions(snes_.get(), petscOptions_);
    jacobian_ = createBlockMatrix(ksp, layout, pattern.rowOffsets, pattern.columns, bs, MatrixSymmetry::symmetric,
                                  petscOptions_);
    context_->jacobian = jacobian_;
    setNearNullSpace(jacobian_, layout, bs, rigidMotionModes(problem));  // for GAMG; direct solvers ignore it
    RBM_CHECK_PETSC(SNESSetJacobian(snes_, jacobian_, jacobian_, formHessian, context_.get()));
}

CoupledNewtonSolver::~CoupledNewtonSolver() = default;

namespace {

// Warm start from the previous time step, with a linear predictor for the change of
// the boundary: guess + L⁻¹b(new) − L⁻¹b(old). Without it the boundary nodes jump
// by the whole increment while their neighbours stay, which on boundary-layer cells
// thinner than the increment is a tangled start and costs Newton tens of iterations.
std::vector<double> warmStart(const RbmProblem& problem, CoupledLinearizedSolver& linearized,
                              std::span<const Vector3> prescribedDisplacement, const RbmState& initialGuess,
                              const std::vector<double>& coldStart, int& linearIterations)
{
    BlockSystemSolver::Report report;
    std::vector<Vector3> previousBoundary(initialGuess.displacement.begin(), initialGuess.displacement.end());
    const std::vector<double> previousLinear = linearized.solveUnknowns(previousBoundary, nullptr, report);
    linearIterations += report.iterations;
    std::vector<double> warm(problem.unknownCount(), 0.0);
    packUnknowns(problem, initialGuess, warm);
    for (std::size_t k = 0; k < warm.size(); ++k) warm[k] += coldStart[k] - previousLinear[k];
    // Moved onto the sliding planes: u ← c n + P (u − c n).
    std::vector<double> offset(warm.size());
    problem.slidingOffset(prescribedDisplacement, offset);
    for (std::size_t k = 0; k < warm.size(); ++k) warm[k] -= offset[k];
    problem.projectSliding(warm);
    for (std::size_t k = 0; k < warm.size(); ++k) warm[k] += offset[k];
    return warm;
}

// The starts Newton may take: the cold (linearized) one, and the warm one if there is a guess.
std::vector<std::vector<double>> candidateStarts(const RbmProblem& problem, CoupledLinearizedSolver& linearized,
                                                 std::span<const Vector3> prescribedDisplacement,
                                                 const RbmState* initialGuess, int& linearIterations)
{
    BlockSystemSolver::Report report;
    std::vector<std::vector<double>> candidates;
    // Cold start: the linearized solution (one solve with the factorisation kept).
    std::vector<double> coldStart = linearized.solveUnknowns(prescribedDisplacement, nullptr, report);
    linearIterations += report.iterations;
    if (initialGuess) {
        std::vector<double> warm =
            warmStart(problem, linearized, prescribedDisplacement, *initialGuess, coldStart, linearIterations);
        // Whichever start has the lower energy (both with re-fitted rotations, below).
        candidates.push_back(std::move(coldStart));
        candidates.push_back(std::move(warm));
    } else {
        candidates.push_back(std::move(coldStart));
    }
    return candidates;
}

// Re-fits the rotations of unknowns to its displacements; returns the largest angle changed.
double refitRotations(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                      std::vector<double>& unknowns, std::vector<Matrix3>& fitted)
{
    const int dim = problem.dimension();
    const int bs = problem.blockSize();
    const RbmState state = unpackUnknowns(problem, prescribedDisplacement, unknowns);
    fitNodeRotations(problem, state.displacement, fitted);
    double largest = 0.0;
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        const int node = problem.unknownNodes()[a];
        const Vector3 parameters = rotationParameters(dim, fitted[node]);
        double* block = unknowns.data() + static_cast<std::size_t>(a) * bs + dim;
        const Matrix3 current = dim == 2 ? planarRotation(block[0]) : rotationFromVector({block[0], block[1], block[2]});
        const Matrix3 relative = fitted[node].transposed() * current;
        const double cosine = 0.5 * (relative.m[0][0] + relative.m[1][1] + relative.m[2][2] - 1.0);
        largest = std::max(largest, std::acos(std::clamp(cosine, -1.0, 1.0)));
        if (dim == 2) block[0] = parameters.z;
        else for (int k = 0; k < 3; ++k) block[k] = parameters[k];
    }
    return largest;
}

// Rotations re-fitted to each candidate's displacements; Newton starts from the lowest energy.
std::vector<double> lowestEnergyStart(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                                      const RbmEnergy& energyOf, std::vector<std::vector<double>>& candidates,
                                      std::vector<Matrix3>& fitted)
{
    double lowestEnergy = std::numeric_limits<double>::infinity();
    std::vector<double> start;
    for (std::vector<double>& candidate : candidates) {
        refitRotations(problem, prescribedDisplacement, candidate, fitted);
        const double energy = energyOf.value(candidate);
        if (start.empty() || energy < lowestEnergy) {  // the first even when no energy is finite
            lowestEnergy = energy;
            start = candidate;
        }
    }
    return start;
}

// What the restarted Newton solve ended with.
struct NewtonOutcome {
    SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
    int restarts = 0;
};

// Newton from start, restarted from the re-fitted state while it converges to rotations that
// differ from their fits (at most maximumRestarts times); the solution is left in unknowns.
NewtonOutcome solveWithRestarts(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                                SNES snes, Vec solution, Context& context, std::vector<double> start,
                                std::vector<Matrix3>& fitted, std::vector<double>& unknowns, RbmResult& result)
{
    const int bs = problem.blockSize();
    constexpr int maximumRestarts = 3;
    NewtonOutcome outcome;
    for (;;) {
        context.layout->scatter(start, solution, bs);
        RBM_CHECK_PETSC(SNESSolve(snes, nullptr, solution));
        PetscInt iterations = 0, linearIterations = 0;
        RBM_CHECK_PETSC(SNESGetIterationNumber(snes, &iterations));
        RBM_CHECK_PETSC(SNESGetLinearSolveIterations(snes, &linearIterations));
        RBM_CHECK_PETSC(SNESGetConvergedReason(snes, &outcome.reason));
        result.iterations += static_cast<int>(iterations);
        result.linearIterations += static_cast<int>(linearIterations);
        context.layout->gather(solution, unknowns, bs);
        if (outcome.reason <= 0 || outcome.restarts == maximumRestarts) break;
        start = unknowns;
        if (refitRotations(problem, prescribedDisplacement, start, fitted) < 1e-6) break;
        ++outcome.restarts;
    }
    return outcome;
}

} // namespace

RbmResult CoupledNewtonSolver::solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess)
{
    problem_.checkNodeArray(prescribedDisplacement, "prescribed displacement");
    if (problem_.unknownNodeCount() == 0) return prescribedOnlyResult(problem_, prescribedDisplacement);
    RbmResult result;
    if (!linearized_) {
        CoupledLinearizedOptions linearOptions;
        linearOptions.linearSolver = options_.linearSolver;
        linearized_ = std::make_unique<CoupledLinearizedSolver>(problem_, linearOptions);
    }
    std::vector<std::vector<double>> candidates =
        candidateStarts(problem_, *linearized_, prescribedDisplacement, initialGuess, result.linearIterations);

    context_->energy.emplace(problem_, RotationModel::exact, prescribedDisplacement);
    context_->gaussNewtonSteps = 0;

    // Rotations are re-fitted to the displacements (the local step of LocalGlobalSolver)
    // before Newton starts and after it stops: at a minimum of E every node's rotation is
    // the best fit of its own edges, so a converged state whose rotations differ from
    // their fits is a saddle point with flipped node frames (docs/method.md §2); Newton is
    // restarted from the re-fitted state (at most maximumRestarts times).
    std::vector<Matrix3> fitted;
    std::vector<double> start =
        lowestEnergyStart(problem_, prescribedDisplacement, *context_->energy, candidates, fitted);
    std::vector<double> unknowns(problem_.unknownCount());
    const NewtonOutcome outcome = solveWithRestarts(problem_, prescribedDisplacement, snes_, solution_, *context_,
                                                    std::move(start), fitted, unknowns, result);

    static_cast<RbmState&>(result) = unpackUnknowns(problem_, prescribedDisplacement, unknowns);
    result.converged = outcome.reason > 0;
    result.reason = convergedReasonText(outcome.reason);
    if (context_->gaussNewtonSteps > 0)
        result.reason += " (" + std::to_string(context_->gaussNewtonSteps) + " Gauss-Newton steps)";
    if (outcome.restarts > 0)
        result.reason += " (" + std::to_string(outcome.restarts) + " restarts from re-fitted rotations)";
    result.energy = context_->energy->value(unknowns);
    result.residualNorm = context_->energy->projectedGradientNorm(unknowns);
    return result;
}

} // namespace rbm::motion
