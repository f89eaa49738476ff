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

int rotationAwareSubStepCount(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                              std::span<const int> groupOffsets, std::span<const int> groupNodes,
                              double maxAngleRadians)
{
    problem.checkNodeArray(prescribedDisplacement, "prescribed displacement");
    if (!(maxAngleRadians > 0.0)) throw std::invalid_argument("sub-steps: the angle per sub-step must be positive");
    const int dim = problem.dimension();
    auto flat = [dim](Vector3 v) {
        if (dim == 2) v.z = 0.0;
        return v;
    };
    const std::vector<Vector3>& reference = problem.referencePoints();
    double count = 1.0;
    auto thesisRule = [&](int node, double length) {
        const double shortest = problem.shortestNeighbourDistance(node);
        if (length == 0.0 || !std::isfinite(shortest)) return;
        count = std::max(count, std::floor(length / shortest) + 1.0);
    };
    // Sliding nodes: the normal component of their plane's motion (as in the thesis' rule).
    for (int node = 0; node < problem.nodeCount(); ++node) {
        if (problem.kind(node) != NodeKind::sliding) continue;
        const Vector3& normal = problem.slidingNormal(node);
        thesisRule(node, std::abs(dot(flat(prescribedDisplacement[node]), normal)));
    }
    const int groupCount = static_cast<int>(groupOffsets.size()) - 1;
    for (int group = 0; group < groupCount; ++group) {
        const int begin = groupOffsets[group];
        const int end = groupOffsets[group + 1];
        if (end == begin) continue;
        Vector3 centreFrom;
        Vector3 centreTo;
        for (int k = begin; k < end; ++k) {
            const int node = groupNodes[k];
            centreFrom += flat(reference[node]);
            centreTo += flat(reference[node] + prescribedDisplacement[node]);
        }
        centreFrom /= static_cast<double>(end - begin);
        centreTo /= static_cast<double>(end - begin);
        // Best rotation of the group (2D: atan2 of the summed cross and dot products; 3D: Kabsch).
        Matrix3 rotation = Matrix3::identity();
        double angle = 0.0;
        if (dim == 2) {
            double crossSum = 0.0;
            double dotSum = 0.0;
            for (int k = begin; k < end; ++k) {
                const int node = groupNodes[k];
                const Vector3 a = flat(reference[node]) - centreFrom;
                const Vector3 b = flat(reference[node] + prescribedDisplacement[node]) - centreTo;
                crossSum += a.x * b.y - a.y * b.x;
                dotSum += a.x * b.x + a.y * b.y;
            }
            angle = bestPlanarAngle(crossSum, dotSum);
            rotation = planarRotation(angle);
        } else {
            Matrix3 covariance;
            for (int k = begin; k < end; ++k) {
                const int node = groupNodes[k];
                const Vector3 a = reference[node] - centreFrom;
                const Vector3 b = reference[node] + prescribedDisplacement[node] - centreTo;
                for (int r = 0; r < 3; ++r)
                    for (int c = 0; c < 3; ++c) covariance.m[r][c] += b[r] * a[c];
            }
            rotation = bestRotation(covariance);
            angle = norm(rotationVectorFromMatrix(rotation));
        }
        // The translation turns the cells between this group and the others (fixed walls)
        // by about |t - t_o| / gap, gap the clearance between the group's bounding circle and
        // the nearest node of another group o, t_o that group's centroid translation: a
        // translation of the whole mesh costs nothing, one of a body against a fixed wall as
        // much as the shear it causes.
        double radius = 0.0;
        for (int k = begin; k < end; ++k) radius = std::max(radius, norm(flat(reference[groupNodes[k]]) - centreFrom));
        double gap = std::numeric_limits<double>::infinity();
        int nearest = -1;
        for (int other = 0; other < groupCount; ++other) {
            if (other == group) continue;
            for (int k = groupOffsets[other]; k < groupOffsets[other + 1]; ++k) {
                const double clearance = norm(flat(reference[groupNodes[k]]) - centreFrom) - radius;
                if (clearance < gap) {
                    gap = clearance;
                    nearest = other;
                }
            }
        }
        Vector3 otherTranslation;
        if (nearest >= 0) {
            for (int k = groupOffsets[nearest]; k < groupOffsets[nearest + 1]; ++k)
                otherTranslation += flat(prescribedDisplacement[groupNodes[k]]);
            otherTranslation /= static_cast<double>(groupOffsets[nearest + 1] - groupOffsets[nearest]);
        }
        if (!(gap > 0.0)) gap = radius;  // nested bounding circles: the group's own size
        const double shear =
            gap > 0.0 && std::isfinite(gap) ? norm(centreTo - centreFrom - otherTranslation) / gap : 0.0;
        // (1e-9: a rotation of exactly k·maxAngle, fitted to rounding, takes k sub-steps.)
        count = std::max(count, std::ceil((std::abs(angle) + shear) / maxAngleRadians - 1e-9));
        double size = 0.0;
        for (int k = begin; k < end; ++k) {
            const int node = groupNodes[k];
            size = std::max(size, norm(flat(reference[node]) - centreFrom) + norm(flat(prescribedDisplacement[node])));
        }
        for (int k = begin; k < end; ++k) {
            const int node = groupNodes[k];
            const Vector3 rigid = centreTo + rotation * (flat(reference[node]) - centreFrom);
            const double rest = norm(flat(reference[node] + prescribedDisplacement[node]) - rigid);
            if (rest > 1e-9 * size) thesisRule(node, rest);
        }
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
