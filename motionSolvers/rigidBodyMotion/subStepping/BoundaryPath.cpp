#include "BoundaryPath.hpp"

#include "LocalGlobalSolver.hpp"  // bestRotation, bestPlanarAngle
#include "RbmEnergy.hpp"          // planarRotation, rotationFromVector

#include <algorithm>
#include <cmath>

namespace rbm::motion {

BoundaryPath::BoundaryPath(int dimension, const std::vector<Vector3>& reference, const std::vector<int>& groupOffsets,
                           const std::vector<int>& groupNodes, std::span<const Vector3> from, std::span<const Vector3> to)
    : dimension_(dimension), reference_(reference), groupOffsets_(groupOffsets), groupNodes_(groupNodes),
      from_(from), to_(to)
{
    const int groupCount = static_cast<int>(groupOffsets.size()) - 1;
    motions_.resize(groupCount);
    for (int group = 0; group < groupCount; ++group) fit(group);
}

std::vector<Vector3> BoundaryPath::at(double fraction) const
{
    if (fraction >= 1.0) return {to_.begin(), to_.end()};
    std::vector<Vector3> values(to_.size());
    for (std::size_t node = 0; node < values.size(); ++node)
        values[node] = fromOf(static_cast<int>(node)) + fraction * (to_[node] - fromOf(static_cast<int>(node)));
    for (std::size_t group = 0; group < motions_.size(); ++group) {
        const GroupMotion& motion = motions_[group];
        if (!motion.rigid) continue;
        const Matrix3 rotation = dimension_ == 2 ? planarRotation(fraction * motion.rotation.z)
                                                : rotationFromVector(fraction * motion.rotation);
        for (int k = groupOffsets_[group]; k < groupOffsets_[group + 1]; ++k) {
            const int node = groupNodes_[k];
            const Vector3 start = position(node, from_);
            Vector3 value = motion.centre + fraction * motion.translation + rotation * (start - motion.centre) -
                            flat(reference_[node]);
            if (dimension_ == 2) value.z = 0.0;
            values[node] = value;
        }
    }
    return values;
}

bool BoundaryPath::allRigid() const
{
    return std::all_of(motions_.begin(), motions_.end(), [](const GroupMotion& m) { return m.rigid; });
}

double BoundaryPath::largestRigidAngle() const
{
    double largest = 0.0;
    for (const GroupMotion& motion : motions_)
        if (motion.rigid) largest = std::max(largest, norm(motion.rotation));
    return largest;
}

Vector3 BoundaryPath::flat(Vector3 v) const
{
    if (dimension_ == 2) v.z = 0.0;
    return v;
}

Vector3 BoundaryPath::position(int node, std::span<const Vector3> displacement) const
{
    return flat(reference_[node] + (displacement.empty() ? Vector3{} : displacement[node]));
}

void BoundaryPath::fit(int group)
{
    const int begin = groupOffsets_[group];
    const int end = groupOffsets_[group + 1];
    if (end == begin) {
        motions_[group].rigid = true;
        return;
    }
    Vector3 centreFrom;
    Vector3 centreTo;
    for (int k = begin; k < end; ++k) {
        centreFrom += position(groupNodes_[k], from_);
        centreTo += position(groupNodes_[k], to_);
    }
    centreFrom /= static_cast<double>(end - begin);
    centreTo /= static_cast<double>(end - begin);
    Matrix3 rotation = Matrix3::identity();
    Vector3 parameters;
    double radius = 0.0;
    double largestMove = 0.0;
    if (dimension_ == 2) {
        double crossSum = 0.0;
        double dotSum = 0.0;
        for (int k = begin; k < end; ++k) {
            const Vector3 a = position(groupNodes_[k], from_) - centreFrom;
            const Vector3 b = position(groupNodes_[k], to_) - centreTo;
            crossSum += a.x * b.y - a.y * b.x;
            dotSum += a.x * b.x + a.y * b.y;
        }
        parameters.z = bestPlanarAngle(crossSum, dotSum);
        rotation = planarRotation(parameters.z);
    } else {
        Matrix3 covariance;
        for (int k = begin; k < end; ++k) {
            const Vector3 a = position(groupNodes_[k], from_) - centreFrom;
            const Vector3 b = position(groupNodes_[k], to_) - centreTo;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) covariance.m[r][c] += b[r] * a[c];
        }
        rotation = bestRotation(covariance);
        parameters = rotationVectorFromMatrix(rotation);
        rotation = rotationFromVector(parameters);
    }
    double misfit = 0.0;
    for (int k = begin; k < end; ++k) {
        const int node = groupNodes_[k];
        const Vector3 a = position(node, from_) - centreFrom;
        const Vector3 b = position(node, to_);
        radius = std::max(radius, norm(a));
        largestMove = std::max(largestMove, norm(to_[node] - fromOf(node)));
        misfit = std::max(misfit, norm(centreTo + rotation * a - b));
    }
    GroupMotion& motion = motions_[group];
    motion.rigid = misfit <= 1e-9 * (radius + largestMove) && std::isfinite(misfit);
    motion.centre = centreFrom;
    motion.translation = centreTo - centreFrom;
    motion.rotation = parameters;
}

} // namespace rbm::motion
