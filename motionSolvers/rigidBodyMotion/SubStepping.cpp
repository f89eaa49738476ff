#include "SubStepping.hpp"

#include "LocalGlobalSolver.hpp"
#include "RbmEnergy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rbm::motion {

int automaticSubStepCount(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement)
{
    problem.checkNodeArray(prescribedDisplacement, "prescribed displacement");
    double count = 1.0;
    for (int node = 0; node < problem.nodeCount(); ++node) {
        const NodeKind kind = problem.kind(node);
        if (kind == NodeKind::free) continue;
        Vector3 displacement = prescribedDisplacement[node];
        if (problem.dimension() == 2) displacement.z = 0.0;
        if (kind == NodeKind::sliding) displacement = problem.slidingNormalPart(node, displacement);
        const double length = norm(displacement);
        const double shortest = problem.shortestNeighbourDistance(node);
        if (length == 0.0 || !std::isfinite(shortest)) continue;
        // Smallest n with length / n < shortest.
        count = std::max(count, std::floor(length / shortest) + 1.0);
    }
    if (!(count < static_cast<double>(std::numeric_limits<int>::max())))
        throw std::invalid_argument("sub-steps: the prescribed displacement is too large for its mesh");
    return static_cast<int>(count);
}

SubSteppedResult solveInSubSteps(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                                 const RbmSolverFactory& makeSolver, SubStepOptions options)
{
    problem.checkNodeArray(prescribedDisplacement, "prescribed displacement");
    const std::vector<Vector3> total(prescribedDisplacement.begin(), prescribedDisplacement.end());
    const BoundaryMotion linear = [&total](double fraction) {
        std::vector<Vector3> values(total.size());
        for (std::size_t node = 0; node < total.size(); ++node) values[node] = fraction * total[node];
        return values;
    };
    return solveInSubSteps(problem, linear, makeSolver, options);
}

SubSteppedResult solveInSubSteps(const RbmProblem& problem, const BoundaryMotion& boundaryMotion,
                                 const RbmSolverFactory& makeSolver, SubStepOptions options)
{
    const std::vector<Vector3> final = boundaryMotion(1.0);
    problem.checkNodeArray(final, "prescribed displacement");
    if (options.count < 0) throw std::invalid_argument("sub-steps: the number of sub-steps must not be negative");
    const int count = options.count > 0 ? options.count : automaticSubStepCount(problem, final);
    const int n = problem.nodeCount();
    const int dim = problem.dimension();

    SubSteppedResult result;
    result.subStepCount = count;
    result.converged = true;
    auto accumulate = [&result](const RbmResult& step) {
        result.iterations += step.iterations;
        result.linearIterations += step.linearIterations;
        result.converged = result.converged && step.converged;
        result.residualNorm = step.residualNorm;
        result.reason = step.reason;
    };
    auto motionAt = [&](int step) { return step == count ? final : boundaryMotion(static_cast<double>(step) / count); };

    if (options.reference == SubStepReference::initialMesh) {
        const std::unique_ptr<RbmSolver> solver = makeSolver(problem);
        RbmResult previous;
        for (int step = 1; step <= count; ++step) {
            RbmResult current = solver->solve(motionAt(step), step > 1 ? &previous : nullptr);
            accumulate(current);
            previous = std::move(current);
        }
        result.displacement = std::move(previous.displacement);
        result.rotation = std::move(previous.rotation);
        result.energy = previous.energy;
    } else {
        std::vector<Vector3> displacement(n);
        std::vector<Matrix3> rotation(n, Matrix3::identity());
        std::vector<double> planarAngle(n, 0.0);  // 2D: angles add up, no wrapping
        std::vector<Vector3> reached(n);          // boundary displacement after the previous increment
        std::vector<Vector3> points = problem.referencePoints();
        for (int step = 1; step <= count; ++step) {
            const std::vector<Vector3> target = motionAt(step);
            std::vector<Vector3> increment(n);
            for (int node = 0; node < n; ++node) increment[node] = target[node] - reached[node];
            const RbmProblem stepProblem = step == 1 ? problem : problem.withReferencePoints(points);
            RbmResult current;
            {
                const std::unique_ptr<RbmSolver> solver = makeSolver(stepProblem);
                current = solver->solve(increment);
            }
            accumulate(current);
            for (int node = 0; node < n; ++node) {
                displacement[node] += current.displacement[node];
                if (!problem.isUnknown(node)) continue;
                if (dim == 2) {
                    planarAngle[node] += current.rotation[node].z;
                } else {
                    rotation[node] = rotationFromVector(current.rotation[node]) * rotation[node];
                }
            }
            for (int node = 0; node < n; ++node) {
                points[node] = problem.referencePoints()[node] + displacement[node];
                if (dim == 2) points[node].z = problem.referencePoints()[node].z;
            }
            reached = target;
        }
        result.displacement = std::move(displacement);
        result.rotation.assign(n, Vector3{});
        for (int node : problem.unknownNodes())
            result.rotation[node] = dim == 2 ? Vector3{0.0, 0.0, planarAngle[node]} : rotationParameters(3, rotation[node]);
        std::vector<double> unknowns(problem.unknownCount());
        packUnknowns(problem, result, unknowns);
        result.energy = RbmEnergy(problem, RotationModel::exact, final).value(unknowns);
    }
    result.reason += " (" + std::to_string(count) + " sub-steps)";
    return result;
}

} // namespace rbm::motion
