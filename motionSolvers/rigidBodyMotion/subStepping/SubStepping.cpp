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

namespace {

// v in the plane of a 2D problem (z dropped), else v.
Vector3 inPlane(int dim, Vector3 v)
{
    if (dim == 2) v.z = 0.0;
    return v;
}

// The thesis' rule on a node's motion length: raises count to ⌊length / d_min⌋ + 1.
void applyThesisRule(const RbmProblem& problem, int node, double length, double& count)
{
    const double shortest = problem.shortestNeighbourDistance(node);
    if (length == 0.0 || !std::isfinite(shortest)) return;
    count = std::max(count, std::floor(length / shortest) + 1.0);
}

// A group's best rigid motion: centroid before and after, rotation and its angle.
struct GroupMotion {
    Vector3 centreFrom;
    Vector3 centreTo;
    Matrix3 rotation = Matrix3::identity();
    double angle = 0.0;
};

// Best rotation of the group (2D: atan2 of the summed cross and dot products; 3D: Kabsch).
void fitGroupRotation(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                      std::span<const int> members, GroupMotion& motion)
{
    const int dim = problem.dimension();
    const std::vector<Vector3>& reference = problem.referencePoints();
    if (dim == 2) {
        double crossSum = 0.0;
        double dotSum = 0.0;
        for (const int node : members) {
            const Vector3 a = inPlane(dim, reference[node]) - motion.centreFrom;
            const Vector3 b = inPlane(dim, reference[node] + prescribedDisplacement[node]) - motion.centreTo;
            crossSum += a.x * b.y - a.y * b.x;
            dotSum += a.x * b.x + a.y * b.y;
        }
        motion.angle = bestPlanarAngle(crossSum, dotSum);
        motion.rotation = planarRotation(motion.angle);
    } else {
        Matrix3 covariance;
        for (const int node : members) {
            const Vector3 a = reference[node] - motion.centreFrom;
            const Vector3 b = reference[node] + prescribedDisplacement[node] - motion.centreTo;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) covariance.m[r][c] += b[r] * a[c];
        }
        motion.rotation = bestRotation(covariance);
        motion.angle = norm(rotationVectorFromMatrix(motion.rotation));
    }
}

// The group's centroids and best rotation (the fit of §2.3 over the group).
GroupMotion bestGroupMotion(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                            std::span<const int> members)
{
    const int dim = problem.dimension();
    const std::vector<Vector3>& reference = problem.referencePoints();
    GroupMotion motion;
    for (const int node : members) {
        motion.centreFrom += inPlane(dim, reference[node]);
        motion.centreTo += inPlane(dim, reference[node] + prescribedDisplacement[node]);
    }
    motion.centreFrom /= static_cast<double>(members.size());
    motion.centreTo /= static_cast<double>(members.size());
    fitGroupRotation(problem, prescribedDisplacement, members, motion);
    return motion;
}

// |t - t_o| / gap of the group (see below; 0 where there is no finite positive gap).
double groupShear(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                  std::span<const int> groupOffsets, std::span<const int> groupNodes, int group,
                  const GroupMotion& motion)
{
    const int dim = problem.dimension();
    const std::vector<Vector3>& reference = problem.referencePoints();
    const int groupCount = static_cast<int>(groupOffsets.size()) - 1;
    const int begin = groupOffsets[group];
    const int end = groupOffsets[group + 1];
    // The translation turns the cells between this group and the others (fixed walls)
    // by about |t - t_o| / gap, gap the clearance between the group's bounding circle and
    // the nearest node of another group o, t_o that group's centroid translation: a
    // translation of the whole mesh costs nothing, one of a body against a fixed wall as
    // much as the shear it causes.
    double radius = 0.0;
    for (int k = begin; k < end; ++k)
        radius = std::max(radius, norm(inPlane(dim, reference[groupNodes[k]]) - motion.centreFrom));
    double gap = std::numeric_limits<double>::infinity();
    int nearest = -1;
    for (int other = 0; other < groupCount; ++other) {
        if (other == group) continue;
        for (int k = groupOffsets[other]; k < groupOffsets[other + 1]; ++k) {
            const double clearance = norm(inPlane(dim, reference[groupNodes[k]]) - motion.centreFrom) - radius;
            if (clearance < gap) {
                gap = clearance;
                nearest = other;
            }
        }
    }
    Vector3 otherTranslation;
    if (nearest >= 0) {
        for (int k = groupOffsets[nearest]; k < groupOffsets[nearest + 1]; ++k)
            otherTranslation += inPlane(dim, prescribedDisplacement[groupNodes[k]]);
        otherTranslation /= static_cast<double>(groupOffsets[nearest + 1] - groupOffsets[nearest]);
    }
    if (!(gap > 0.0)) gap = radius;  // nested bounding circles: the group's own size
    return gap > 0.0 && std::isfinite(gap) ? norm(motion.centreTo - motion.centreFrom - otherTranslation) / gap : 0.0;
}

// The thesis' rule on each member's non-rigid rest, parts below 1e-9 of the group's size and motion being rounding.
void applyRuleToNonRigidRest(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                             std::span<const int> members, const GroupMotion& motion, double& count)
{
    const int dim = problem.dimension();
    const std::vector<Vector3>& reference = problem.referencePoints();
    double size = 0.0;
    for (const int node : members)
        size = std::max(size, norm(inPlane(dim, reference[node]) - motion.centreFrom) +
                                  norm(inPlane(dim, prescribedDisplacement[node])));
    for (const int node : members) {
        const Vector3 rigid = motion.centreTo + motion.rotation * (inPlane(dim, reference[node]) - motion.centreFrom);
        const double rest = norm(inPlane(dim, reference[node] + prescribedDisplacement[node]) - rigid);
        if (rest > 1e-9 * size) applyThesisRule(problem, node, rest, count);
    }
}

} // namespace

int rotationAwareSubStepCount(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                              std::span<const int> groupOffsets, std::span<const int> groupNodes,
                              double maxAngleRadians)
{
    problem.checkNodeArray(prescribedDisplacement, "prescribed displacement");
    if (!(maxAngleRadians > 0.0)) throw std::invalid_argument("sub-steps: the angle per sub-step must be positive");
    const int dim = problem.dimension();
    double count = 1.0;
    // Sliding nodes: the normal component of their plane's motion (as in the thesis' rule).
    for (int node = 0; node < problem.nodeCount(); ++node) {
        if (problem.kind(node) != NodeKind::sliding) continue;
        const Vector3& normal = problem.slidingNormal(node);
        applyThesisRule(problem, node, std::abs(dot(inPlane(dim, prescribedDisplacement[node]), normal)), count);
    }
    const int groupCount = static_cast<int>(groupOffsets.size()) - 1;
    for (int group = 0; group < groupCount; ++group) {
        const int begin = groupOffsets[group];
        const int end = groupOffsets[group + 1];
        if (end == begin) continue;
        const std::span<const int> members = groupNodes.subspan(begin, end - begin);
        const GroupMotion motion = bestGroupMotion(problem, prescribedDisplacement, members);
        const double shear = groupShear(problem, prescribedDisplacement, groupOffsets, groupNodes, group, motion);
        // (1e-9: a rotation of exactly k·maxAngle, fitted to rounding, takes k sub-steps.)
        count = std::max(count, std::ceil((std::abs(motion.angle) + shear) / maxAngleRadians - 1e-9));
        applyRuleToNonRigidRest(problem, prescribedDisplacement, members, motion, count);
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
