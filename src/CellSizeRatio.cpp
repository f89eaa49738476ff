#include "CellSizeRatio.hpp"

#include "MeshGeometry.hpp"

#include <algorithm>
#include <vector>

namespace rbm {

namespace {

double firstPercentile(std::vector<double>& ratios)
{
    if (ratios.empty()) return 0.0;
    const auto percentile = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 100);
    std::nth_element(ratios.begin(), percentile, ratios.end());
    return *percentile;
}

} // namespace

double smallestCellSizeRatio(const PlanarMesh& planar, std::span<const Vector3> movedPoints)
{
    std::vector<double> ratios;
    for (Label c = 0; c < planar.cellCount(); ++c) {
        const double before = planar.signedArea(c), after = planar.signedArea(c, movedPoints);
        if (before > 0.0 && after > 0.0) ratios.push_back(after / before);
    }
    return firstPercentile(ratios);
}

double smallestCellSizeRatio(const PolyMesh& mesh, std::span<const Vector3> pointsBefore,
                             std::span<const Vector3> pointsAfter)
{
    const MeshGeometry before = computeMeshGeometry(mesh, pointsBefore);
    const MeshGeometry after = computeMeshGeometry(mesh, pointsAfter);
    std::vector<double> ratios;
    for (std::size_t c = 0; c < before.cellVolumes.size(); ++c)
        if (before.cellVolumes[c] > 0.0 && after.cellVolumes[c] > 0.0)
            ratios.push_back(after.cellVolumes[c] / before.cellVolumes[c]);
    return firstPercentile(ratios);
}

} // namespace rbm
