#include "InvertedCellCounter.hpp"

#include "InvertedCell.hpp"
#include "ThesisQuality.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace rbm::motion {

InvertedCellCounter::InvertedCellCounter(const PolyMesh& mesh, const std::vector<Vector3>& points0,
                                         const PseudoTwoDMesh* twoD)
    : mesh_(mesh), points0_(points0), twoD_(twoD)
{}

Label InvertedCellCounter::count(std::span<const Vector3> nodeDisplacement, double* worstQuality,
                                 std::vector<Label>* invertedCells)
{
    if (invertedCells) invertedCells->clear();
    const bool remember = invertedCells == nullptr;
    static_assert(sizeof(Vector3) == 3 * sizeof(double));
    if (remember && checkedInverted_ >= 0 && checkedDisplacement_.size() == nodeDisplacement.size() &&
        std::memcmp(nodeDisplacement.data(), checkedDisplacement_.data(), nodeDisplacement.size() * sizeof(Vector3)) == 0) {
        // The same bits: the same figures.
        if (worstQuality) *worstQuality = checkedWorst_;
        return checkedInverted_;
    }
    double worst = std::numeric_limits<double>::infinity();
    const bool wantWorst = worstQuality || remember;
    const Label inverted = twoD_ ? countPlanar(nodeDisplacement, wantWorst, worst, invertedCells)
                                 : countPolyhedral(nodeDisplacement, wantWorst, worst, invertedCells);
    worst = std::isfinite(worst) ? worst : 1.0;
    if (worstQuality) *worstQuality = worst;
    if (remember) {
        checkedDisplacement_.assign(nodeDisplacement.begin(), nodeDisplacement.end());
        checkedInverted_ = inverted;
        checkedWorst_ = worst;
    }
    return inverted;
}

Label InvertedCellCounter::countPlanar(std::span<const Vector3> nodeDisplacement, bool wantWorst, double& worst,
                                       std::vector<Label>* invertedCells)
{
    const PlanarMesh& planar = twoD_->planar;
    positions_.resize(planar.points.size());
    for (std::size_t node = 0; node < positions_.size(); ++node) {
        positions_[node] = planar.points[node];
        positions_[node].x += nodeDisplacement[node].x;
        positions_[node].y += nodeDisplacement[node].y;
    }
    Label inverted = 0;
    for (Label c = 0; c < planar.cellCount(); ++c) {
        const auto polygon = planar.cell(c);
        double area = 0.0;
        const Vector3 centroid = polygonCentroid(polygon, positions_, area);
        if (isInvertedPolygon(area, smallestEdgeTriangle(polygon, positions_, centroid))) {
            ++inverted;
            if (invertedCells) invertedCells->push_back(c);
        }
        if (!wantWorst) continue;
        if (polygon.size() == 3)
            worst = std::min(worst, triangleMeanRatio(positions_[polygon[0]], positions_[polygon[1]], positions_[polygon[2]]));
        else if (polygon.size() == 4)
            worst = std::min(worst, quadrilateralShape(positions_[polygon[0]], positions_[polygon[1]],
                                                       positions_[polygon[2]], positions_[polygon[3]]));
    }
    return inverted;
}

Label InvertedCellCounter::countPolyhedral(std::span<const Vector3> nodeDisplacement, bool wantWorst, double& worst,
                                           std::vector<Label>* invertedCells)
{
    positions_.resize(points0_.size());
    for (std::size_t p = 0; p < positions_.size(); ++p) positions_[p] = points0_[p] + nodeDisplacement[p];
    updateMeshGeometry(mesh_, positions_, geometry_);
    const std::size_t cellCount = geometry_.cellVolumes.size();
    smallestPyramid_.assign(cellCount, std::numeric_limits<double>::infinity());
    faceCounts_.assign(cellCount, 0);
    const auto& centres = geometry_.cellCentres;
    const Label internalFaces = mesh_.internalFaceCount();
    for (Label f = 0; f < mesh_.faceCount(); ++f) {
        const Vector3& area = geometry_.faceAreas[f];
        const Vector3& centre = geometry_.faceCentres[f];
        const Label own = mesh_.owner[f];
        smallestPyramid_[own] = std::min(smallestPyramid_[own], tripleFacePyramid(area, centre, centres[own], true) / 3.0);
        ++faceCounts_[own];
        if (f < internalFaces) {
            const Label nei = mesh_.neighbour[f];
            smallestPyramid_[nei] =
                std::min(smallestPyramid_[nei], tripleFacePyramid(area, centre, centres[nei], false) / 3.0);
            ++faceCounts_[nei];
        }
    }
    Label inverted = 0;
    for (std::size_t c = 0; c < cellCount; ++c) {
        const double volume = geometry_.cellVolumes[c];
        if (isInvertedCell(volume, smallestPyramid_[c])) {
            ++inverted;
            if (invertedCells) invertedCells->push_back(static_cast<Label>(c));
        }
        if (wantWorst && std::abs(volume) > 0.0)
            worst = std::min(worst, smallestPyramid_[c] * faceCounts_[c] / std::abs(volume));
    }
    // Not kept between checks: the 3D workspace (face centres and areas, cell centres and
    // volumes, positions) is about 215 bytes per cell, and the first check, of the initial
    // mesh, comes before the solve, whose peak it would raise. Allocating it again costs a
    // step about 1 % of its time.
    geometry_ = MeshGeometry{};
    positions_ = std::vector<Vector3>{};
    smallestPyramid_ = std::vector<double>{};
    faceCounts_ = std::vector<int>{};
    return inverted;
}

} // namespace rbm::motion
