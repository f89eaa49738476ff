#include "RbmSolverSelection.hpp"

#include "CellNeighbourGraph.hpp"
#include "InputError.hpp"
#include "CoupledLinearizedSolver.hpp"
#include "CoupledNewtonSolver.hpp"
#include "DecoupledSolver.hpp"
#include "LocalGlobalThenNewton.hpp"
#include "ReducedNewtonSolver.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rbm::motion {

namespace {

std::unique_ptr<RbmSolver> makeDecoupledSolver(const RbmProblem& problem, const RigidBodyMotionOptions& options)
{
    DecoupledOptions decoupled;
    decoupled.model = options.formulation == RbmFormulation::linearized ? DecoupledModel::linearized
                                                                         : DecoupledModel::nonlinear;
    decoupled.linearSolver = options.linearSolver;
    if (options.relativeTolerance) decoupled.linearRelativeTolerance = *options.relativeTolerance;
    if (options.maxIterations) decoupled.maximumIterations = *options.maxIterations;
    decoupled.displacementTolerance = options.tolerance;
    return std::make_unique<DecoupledSolver>(problem, decoupled);
}

// The gradient a displacement error of `tolerance` × the cell size produces:
// tolerance × (mean w|d| over the edges) × √(unknown nodes), the scale of the Newton solvers'
// own default.
double newtonAbsoluteTolerance(const RbmProblem& problem, double tolerance)
{
    const CellNeighbourGraph& g = problem.graph();
    const auto& points = problem.referencePoints();
    double sum = 0.0;
    for (int i = 0; i < problem.nodeCount(); ++i)
        for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
            Vector3 d = points[g.neighbours[e]] - points[i];
            if (problem.dimension() == 2) d.z = 0.0;
            sum += problem.edgeWeights()[e] * norm(d);
        }
    const double mean = g.neighbours.empty() ? 1.0 : sum / static_cast<double>(g.neighbours.size());
    return tolerance * mean * std::sqrt(static_cast<double>(problem.unknownNodeCount()));
}

CoupledNewtonOptions newtonOptionsOf(const RbmProblem& problem, const RigidBodyMotionOptions& options)
{
    CoupledNewtonOptions newton;
    newton.linearSolver = options.linearSolver;
    if (options.relativeTolerance) {
        newton.relativeTolerance = *options.relativeTolerance;
        newton.linearRelativeTolerance = std::min(*options.relativeTolerance, newton.linearRelativeTolerance);
    }
    if (options.tolerance != RigidBodyMotionOptions{}.tolerance)
        newton.absoluteTolerance = newtonAbsoluteTolerance(problem, options.tolerance);
    return newton;
}

} // namespace

NeighbourhoodScaling effectiveScaling(const RigidBodyMotionOptions& options, int dimension)
{
    const bool reducedNewton = options.coupling == RbmCoupling::coupled &&
                               options.formulation == RbmFormulation::nonlinear &&
                               options.algorithm == RbmAlgorithm::reducedNewton;
    if (options.automaticScaling)
        return reducedNewton && dimension == 2 ? NeighbourhoodScaling{automaticScaleStiffness} : NeighbourhoodScaling{};
    if (!options.scaling.rigid() && dimension != 2)
        throw InputError(options.file, options.scalingLine,
                         "'scaling' other than rigid is implemented for planar (2D and pseudo-2D) cases only; "
                         "this case is 3D");
    return options.scaling;
}

double effectiveTransverseStiffness(const RigidBodyMotionOptions& options, int dimension)
{
    if (!options.automaticTransverseStiffness) return options.transverseStiffness;
    const bool reducedNewton = options.coupling == RbmCoupling::coupled &&
                               options.formulation == RbmFormulation::nonlinear &&
                               options.algorithm == RbmAlgorithm::reducedNewton;
    return reducedNewton && dimension == 2 ? automaticTransverseStiffness : 0.0;
}

std::unique_ptr<RbmSolver> makeRbmSolver(const RbmProblem& problem, const RigidBodyMotionOptions& options)
{
    if (options.coupling == RbmCoupling::decoupled) return makeDecoupledSolver(problem, options);
    if (options.formulation == RbmFormulation::linearized) {
        CoupledLinearizedOptions coupled;
        coupled.linearSolver = options.linearSolver;
        if (options.relativeTolerance) coupled.relativeTolerance = *options.relativeTolerance;
        return std::make_unique<CoupledLinearizedSolver>(problem, coupled);
    }
    CoupledNewtonOptions newton = newtonOptionsOf(problem, options);
    switch (options.algorithm) {
    case RbmAlgorithm::localGlobal: {
        LocalGlobalOptions localGlobal;
        localGlobal.linearSolver = options.linearSolver;
        if (options.relativeTolerance) localGlobal.linearRelativeTolerance = *options.relativeTolerance;
        localGlobal.maximumIterations = options.maxIterations.value_or(defaultLocalGlobalMaximumIterations);
        localGlobal.displacementTolerance = options.tolerance;
        return std::make_unique<LocalGlobalThenNewton>(problem, localGlobal, newton);
    }
    case RbmAlgorithm::reducedNewton: {
        ReducedNewtonOptions reduced;
        reduced.linearSolver = options.linearSolver;
        reduced.relativeTolerance = newton.relativeTolerance;
        reduced.absoluteTolerance = newton.absoluteTolerance;
        reduced.displacementTolerance = options.displacementTolerance;
        if (options.maxIterations) reduced.maximumIterations = *options.maxIterations;
        reduced.scaling = effectiveScaling(options, problem.dimension());
        reduced.transverseStiffness = problem.isPart() ? 0.0 : effectiveTransverseStiffness(options, problem.dimension());
        return std::make_unique<ReducedNewtonSolver>(problem, reduced);
    }
    case RbmAlgorithm::newton: break;
    }
    if (options.maxIterations) newton.maximumIterations = *options.maxIterations;
    return std::make_unique<CoupledNewtonSolver>(problem, newton);
}

std::string describeAutomaticScaling(const RigidBodyMotionOptions& options, int dimension)
{
    if (!options.automaticScaling) return {};
    const NeighbourhoodScaling scaling = effectiveScaling(options, dimension);
    std::ostringstream text;
    text << ", scaling auto = ";
    if (scaling.rigid()) text << "rigid";
    else text << scaling.stiffness;
    return text.str();
}

} // namespace rbm::motion
