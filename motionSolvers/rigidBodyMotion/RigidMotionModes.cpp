#include "RigidMotionModes.hpp"

#include <cmath>

namespace rbm::motion {

std::vector<std::vector<double>> rigidMotionModes(const RbmProblem& problem)
{
    const int dim = problem.dimension();
    const int bs = problem.blockSize();
    const std::size_t size = static_cast<std::size_t>(problem.unknownCount());
    const std::vector<int>& nodes = problem.unknownNodes();

    // Rotations about the centroid of the unknown nodes keep the entries of a size with the
    // translations' (a far-away origin would make the rotation modes huge).
    Vector3 centre;
    for (int node : nodes) centre += problem.referencePoints()[node];
    if (!nodes.empty()) centre /= static_cast<double>(nodes.size());

    std::vector<std::vector<double>> modes;
    auto addMode = [&](const Vector3& translation, const Vector3& rotation) {
        std::vector<double> mode(size, 0.0);
        for (std::size_t a = 0; a < nodes.size(); ++a) {
            Vector3 arm = problem.referencePoints()[nodes[a]] - centre;
            if (dim == 2) arm.z = 0.0;
            const Vector3 u = translation + cross(rotation, arm);
            double* block = mode.data() + a * bs;
            for (int k = 0; k < dim; ++k) block[k] = u[k];
            if (dim == 2) block[2] = rotation.z;
            else for (int k = 0; k < 3; ++k) block[3 + k] = rotation[k];
        }
        problem.projectSliding(mode);
        modes.push_back(std::move(mode));
    };
    const Vector3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int k = 0; k < dim; ++k) addMode(axes[k], {});
    if (dim == 2) addMode({}, axes[2]);
    else for (const Vector3& axis : axes) addMode({}, axis);

    // Modified Gram–Schmidt, twice for accuracy; a mode reduced below 1e-8 of its length is
    // (numerically) a combination of the others and dropped.
    std::vector<std::vector<double>> basis;
    for (std::vector<double>& mode : modes) {
        double original = 0.0;
        for (double value : mode) original += value * value;
        original = std::sqrt(original);
        if (!(original > 0.0)) continue;
        for (int pass = 0; pass < 2; ++pass) {
            for (const std::vector<double>& previous : basis) {
                double projection = 0.0;
                for (std::size_t k = 0; k < size; ++k) projection += mode[k] * previous[k];
                for (std::size_t k = 0; k < size; ++k) mode[k] -= projection * previous[k];
            }
        }
        double length = 0.0;
        for (double value : mode) length += value * value;
        length = std::sqrt(length);
        if (!(length > 1e-8 * original)) continue;
        for (double& value : mode) value /= length;
        basis.push_back(std::move(mode));
    }
    return basis;
}

} // namespace rbm::motion
