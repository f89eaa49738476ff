#include "Variants.hpp"

#include "CoupledLinearizedSolver.hpp"
#include "CoupledNewtonSolver.hpp"
#include "DecoupledSolver.hpp"
#include "LocalGlobalSolver.hpp"
#include "MemoryEstimate.hpp"
#include "ReducedNewtonSolver.hpp"

#include <stdexcept>

namespace rbm::benchmark {

namespace {

// "linearizedAssembled": the coupled linearized system assembled as before the matrix-free
// solve existed (direct in 2D and small 3D, CG + GAMG on the 6×6-block Hessian otherwise), for
// comparison with the automatic choice.
motion::LinearSolverKind assembledLinearSolver(const motion::RbmProblem& problem)
{
    return problem.dimension() == 2 || problem.unknownCount() <= motion::directSolverRowLimit
               ? motion::LinearSolverKind::direct
               : motion::LinearSolverKind::iterative;
}

} // namespace

const std::vector<std::string>& allVariants()
{
    static const std::vector<std::string> variants{"decoupled", "linearized", "newton", "localGlobal", "reducedNewton",
                                                   "decoupledLinearized", "linearizedAssembled",
                                                   "linearizedMatrixFree"};
    return variants;
}

bool isCoupledVariant(const std::string& variant)
{
    return variant == "linearized" || variant == "newton" || variant == "localGlobal" || variant == "reducedNewton" ||
           variant == "linearizedAssembled" || variant == "linearizedMatrixFree";
}


std::unique_ptr<motion::RbmSolver> makeSolver(const std::string& variant, const motion::RbmProblem& problem)
{
    if (variant == "decoupled" || variant == "decoupledLinearized") {
        motion::DecoupledOptions options;
        options.model = variant == "decoupled" ? motion::DecoupledModel::nonlinear : motion::DecoupledModel::linearized;
        // The core's default is 5000 fixed-point rounds; on the airfoil they did not converge in
        // 270 s. 200 (local/global's cap in RigidBodyMotionSolver) keeps large sizes affordable;
        // the report says whether the run converged.
        options.maximumIterations = 200;
        return std::make_unique<motion::DecoupledSolver>(problem, options);
    }
    if (variant == "linearized") return std::make_unique<motion::CoupledLinearizedSolver>(problem);
    if (variant == "linearizedMatrixFree")
        return std::make_unique<motion::CoupledLinearizedSolver>(
            problem, motion::CoupledLinearizedOptions{motion::LinearSolverKind::matrixFree});
    if (variant == "linearizedAssembled")
        return std::make_unique<motion::CoupledLinearizedSolver>(
            problem, motion::CoupledLinearizedOptions{assembledLinearSolver(problem)});
    if (variant == "newton") return std::make_unique<motion::CoupledNewtonSolver>(problem);
    if (variant == "reducedNewton") return std::make_unique<motion::ReducedNewtonSolver>(problem);
    if (variant == "localGlobal") {
        motion::LocalGlobalOptions options;
        options.maximumIterations = 200;  // RigidBodyMotionSolver's default before it hands over to Newton
        return std::make_unique<motion::LocalGlobalSolver>(problem, options);
    }
    std::string valid;
    for (const std::string& name : allVariants()) valid += " " + name;
    throw std::invalid_argument("unknown variant " + variant + ". Valid variants are:" + valid);
}

double estimatedMatrixBytes(const std::string& variant, const motion::RbmProblem& problem)
{
    const motion::SolveVariant solveVariant = variant == "decoupled"             ? motion::SolveVariant::decoupledNonlinear
                                              : variant == "decoupledLinearized" ? motion::SolveVariant::decoupledLinearized
                                              : variant == "linearized"          ? motion::SolveVariant::coupledLinearized
                                              : variant == "linearizedAssembled" ? motion::SolveVariant::coupledLinearized
                                              : variant == "linearizedMatrixFree" ? motion::SolveVariant::coupledLinearized
                                              : variant == "localGlobal"         ? motion::SolveVariant::coupledLocalGlobal
                                              : variant == "reducedNewton"       ? motion::SolveVariant::coupledReducedNewton
                                                                                 : motion::SolveVariant::coupledNewton;
    const motion::LinearSolverKind kind =
        variant == "linearizedAssembled"    ? assembledLinearSolver(problem)
        : variant == "linearizedMatrixFree" ? motion::LinearSolverKind::matrixFree
                                            : motion::LinearSolverKind::automatic;
    return motion::estimateSolveMemory(solveVariant, motion::solveSizeOf(problem), kind).bytes;
}

std::string solverCoefficients(const std::string& variant)
{
    if (variant == "linearized") return "coupling coupled; formulation linearized; subSteps 1;";
    if (variant == "linearizedAutoSubSteps") return "coupling coupled; formulation linearized;";
    if (variant == "newton") return "coupling coupled; formulation nonlinear; algorithm newton;";
    if (variant == "localGlobal") return "coupling coupled; formulation nonlinear; algorithm localGlobal;";
    if (variant == "reducedNewton") return "coupling coupled; formulation nonlinear; algorithm reducedNewton;";
    if (variant == "decoupled") return "coupling decoupled; formulation nonlinear; maxIterations 200;";
    if (variant == "decoupledLinearized") return "coupling decoupled; formulation linearized; subSteps 1;";
    if (variant == "linearizedAssembled") return "coupling coupled; formulation linearized; subSteps 1; linearSolver direct;";
    if (variant == "linearizedMatrixFree") return "coupling coupled; formulation linearized; subSteps 1; linearSolver matrixFree;";
    throw std::invalid_argument("no solver coefficients for variant " + variant);
}

} // namespace rbm::benchmark
