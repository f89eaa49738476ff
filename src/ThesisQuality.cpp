#include "ThesisQuality.hpp"

#include "InvertedCell.hpp"
#include "ThreadCount.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rbm {

namespace {

constexpr double rootVerySmall = 1.0e-150;

// z-component of (a x b) on the (x, y) components.
double cross2(const Vector3& a, const Vector3& b) { return a.x * b.y - a.y * b.x; }
double normSquared2(const Vector3& a) { return a.x * a.x + a.y * a.y; }

// Eq 2.95: S = A W^-1 with W^-1 = (2/sqrt 3) [[sqrt3/2, -1/2], [0, 1]], A = [a b] (columns),
// then mu = det(S) / |S|_F^2 (eq 2.96 normalised so that the ideal triangle gives q = 1).
double nodeShapeMeasure(const Vector3& a, const Vector3& b)
{
    const double s = 2.0 / std::sqrt(3.0);
    // Columns of S: s*(sqrt3/2 a) = a and s*(-a/2 + b).
    const Vector3 column0 = a;
    const Vector3 column1{s * (-0.5 * a.x + b.x), s * (-0.5 * a.y + b.y), 0.0};
    const double determinant = cross2(column0, column1);
    const double frobeniusSquared = normSquared2(column0) + normSquared2(column1);
    return frobeniusSquared > 0.0 ? determinant / frobeniusSquared : 0.0;
}

} // namespace

QualityStatistics StatisticsAccumulator::result() const
{
    QualityStatistics s;
    s.count = count_;
    if (count_ == 0) return s;
    s.mean = mean_;
    s.standardDeviation = std::sqrt(std::max(0.0, sumSquaredDeviations_ / static_cast<double>(count_)));
    s.min = min_;
    s.max = max_;
    return s;
}

double triangleMeanRatio(const Vector3& i, const Vector3& j, const Vector3& k)
{
    // Eqs 2.93a–c: A_i = [x_j - x_i, x_k - x_i], A_j = [x_k - x_j, x_i - x_j], A_k = [x_i - x_k, x_j - x_k].
    const double mu = nodeShapeMeasure(j - i, k - i) + nodeShapeMeasure(k - j, i - j) + nodeShapeMeasure(i - k, j - k);
    // Eq 2.97: q = 2 * mean(mu).
    return 2.0 * mu / 3.0;
}

double quadrilateralShape(const Vector3& i, const Vector3& j, const Vector3& k, const Vector3& m)
{
    // Eqs 2.99a–d: at each corner, A_n = [edge to the next corner, edge to the previous one];
    // eq 2.100: tr(S_n) = tr(A_n^T A_n) = sum of the two squared edge lengths;
    // eq 2.101: F_shape = 8 / sum_n tr(S_n)/det(A_n).
    const Vector3* corners[4] = {&i, &j, &k, &m};
    double sum = 0.0;
    for (int n = 0; n < 4; ++n) {
        const Vector3& here = *corners[n];
        const Vector3 toNext = *corners[(n + 1) % 4] - here;
        const Vector3 toPrevious = *corners[(n + 3) % 4] - here;
        const double determinant = cross2(toNext, toPrevious);
        const double trace = normSquared2(toNext) + normSquared2(toPrevious);
        sum += trace / determinant;
    }
    // A degenerate corner (det = 0) makes the sum infinite: F_shape = 0, "degenerate".
    if (!std::isfinite(sum) || sum == 0.0) return 0.0;
    return 8.0 / sum;
}

Vector3 polygonCentroid(std::span<const Label> polygon, std::span<const Vector3> positions, double& signedArea)
{
    // Shoelace about the first node (better conditioned far from the origin): fan triangles
    // (p0, p_i, p_i+1), their signed areas weighting their centroids.
    const std::size_t n = polygon.size();
    const Vector3& origin = positions[polygon[0]];
    double twiceArea = 0.0;
    double weightedX = 0.0;
    double weightedY = 0.0;
    double sumZ = origin.z;
    Vector3 pointSum = origin;
    for (std::size_t a = 1; a < n; ++a) {
        sumZ += positions[polygon[a]].z;
        pointSum += positions[polygon[a]];
    }
    for (std::size_t a = 1; a + 1 < n; ++a) {
        const Vector3 u = positions[polygon[a]] - origin;
        const Vector3 v = positions[polygon[a + 1]] - origin;
        const double twiceTriangle = cross2(u, v);
        twiceArea += twiceTriangle;
        weightedX += twiceTriangle * (u.x + v.x);
        weightedY += twiceTriangle * (u.y + v.y);
    }
    signedArea = 0.5 * twiceArea;
    const double meanZ = sumZ / static_cast<double>(n);
    if (std::abs(twiceArea) <= rootVerySmall) {
        Vector3 average = pointSum / static_cast<double>(n);
        average.z = meanZ;
        return average;
    }
    // Triangle centroid relative to the origin = (u + v)/3.
    return {origin.x + weightedX / (3.0 * twiceArea), origin.y + weightedY / (3.0 * twiceArea), meanZ};
}

double polygonSignedArea(std::span<const Label> polygon, std::span<const Vector3> positions)
{
    // polygonCentroid's fan about the first node, its sum in its order.
    const Vector3& origin = positions[polygon[0]];
    double twiceArea = 0.0;
    for (std::size_t a = 1; a + 1 < polygon.size(); ++a) {
        const Vector3 u = positions[polygon[a]] - origin;
        const Vector3 v = positions[polygon[a + 1]] - origin;
        twiceArea += cross2(u, v);
    }
    return 0.5 * twiceArea;
}

double smallestEdgeTriangle(std::span<const Label> polygon, std::span<const Vector3> positions, const Vector3& centroid)
{
    double smallest = std::numeric_limits<double>::infinity();
    const std::size_t n = polygon.size();
    for (std::size_t a = 0; a < n; ++a) {
        const Vector3& from = positions[polygon[a]];
        const Vector3& to = positions[polygon[(a + 1) % n]];
        smallest = std::min(smallest, cross2(to - from, centroid - from));
    }
    return smallest;
}

double nonOrthogonalityAngle(const Vector3& ownerCentre, const Vector3& neighbourCentre, const Vector3& normal)
{
    const Vector3 d = neighbourCentre - ownerCentre;
    const double cosine = dot(d, normal) / (norm(d) * norm(normal) + rootVerySmall);
    return std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

double centreLineSkewness(const Vector3& ownerCentre, const Vector3& neighbourCentre, const Vector3& faceCentre,
                          const Vector3& normal)
{
    // The centre line C_A + t d meets the plane n.(x - c_f) = 0 at t = n.(c_f - C_A) / n.d;
    // the skewness vector c_f - c' is the same sv as OpenFOAM's faceSkewness.
    const Vector3 d = neighbourCentre - ownerCentre;
    const Vector3 ownerToFace = faceCentre - ownerCentre;
    const Vector3 skew = ownerToFace - (dot(normal, ownerToFace) / (dot(normal, d) + rootVerySmall)) * d;
    return norm(skew) / (norm(d) + rootVerySmall);
}

ThesisQuality computeThesisQuality2D(const PlanarMesh& mesh, std::span<const Vector3> positions,
                                     ThesisQualityWorkspace& workspace)
{
    if (positions.size() != mesh.points.size()) {
        throw std::invalid_argument("computeThesisQuality2D: " + std::to_string(positions.size()) +
                                    " positions given for a planar mesh of " + std::to_string(mesh.points.size()) +
                                    " nodes");
    }
    ThesisQuality quality;
    quality.dimension = 2;
    quality.cellCount = mesh.cellCount();

    // Per cell and per edge by threads (each writes its own slots), then the statistics in
    // cell and edge order: the same figures for any thread count.
    const Label cellCount = quality.cellCount;
    auto& centres = workspace.cellCentres;
    centres.resize(static_cast<std::size_t>(cellCount));
    std::vector<double> shapeValue(static_cast<std::size_t>(cellCount));
    std::vector<std::uint8_t> invertedCell(static_cast<std::size_t>(cellCount));
#pragma omp parallel for schedule(static) if (worthThreading(static_cast<std::size_t>(cellCount)))
    for (Label c = 0; c < cellCount; ++c) {
        const auto polygon = mesh.cell(c);
        double area = 0.0;
        centres[c] = polygonCentroid(polygon, positions, area);
        invertedCell[c] = isInvertedPolygon(area, smallestEdgeTriangle(polygon, positions, centres[c]));
        if (polygon.size() == 3) {
            shapeValue[c] = triangleMeanRatio(positions[polygon[0]], positions[polygon[1]], positions[polygon[2]]);
        } else if (polygon.size() == 4) {
            shapeValue[c] = quadrilateralShape(positions[polygon[0]], positions[polygon[1]], positions[polygon[2]],
                                               positions[polygon[3]]);
        }
    }
    StatisticsAccumulator meanRatio;
    StatisticsAccumulator shape;
    for (Label c = 0; c < cellCount; ++c) {
        const std::size_t size = mesh.cell(c).size();
        if (invertedCell[c]) ++quality.invertedCellCount;
        if (size == 3) {
            meanRatio.add(shapeValue[c]);
        } else if (size == 4) {
            shape.add(shapeValue[c]);
        } else {
            ++quality.otherPolygonCount;
        }
    }
    quality.triangleMeanRatio = meanRatio.result();
    quality.quadrilateralShape = shape.result();

    const Label edgeCount = mesh.internalEdgeCount();
    std::vector<double> angle(static_cast<std::size_t>(edgeCount)), skew(static_cast<std::size_t>(edgeCount));
#pragma omp parallel for schedule(static) if (worthThreading(static_cast<std::size_t>(edgeCount)))
    for (Label e = 0; e < edgeCount; ++e) {
        const auto [first, second] = mesh.edge(e);
        const Vector3& a = positions[first];
        const Vector3& b = positions[second];
        // The owner is on the left of a -> b: the normal (dy, -dx) points to the neighbour.
        const Vector3 normal{b.y - a.y, -(b.x - a.x), 0.0};
        Vector3 midpoint = 0.5 * (a + b);
        Vector3 ownerCentre = centres[mesh.edgeOwner[e]];
        Vector3 neighbourCentre = centres[mesh.edgeNeighbour[e]];
        // Planar metrics: ignore z (the plane coordinate).
        midpoint.z = ownerCentre.z = neighbourCentre.z = 0.0;
        angle[e] = nonOrthogonalityAngle(ownerCentre, neighbourCentre, normal);
        skew[e] = centreLineSkewness(ownerCentre, neighbourCentre, midpoint, normal);
    }
    StatisticsAccumulator nonOrthogonality;
    StatisticsAccumulator skewness;
    for (Label e = 0; e < edgeCount; ++e) {
        nonOrthogonality.add(angle[e]);
        skewness.add(skew[e]);
    }
    quality.nonOrthogonality = nonOrthogonality.result();
    quality.skewness = skewness.result();
    return quality;
}

ThesisQuality computeThesisQuality2D(const PlanarMesh& mesh)
{
    ThesisQualityWorkspace workspace;
    return computeThesisQuality2D(mesh, mesh.points, workspace);
}

ThesisQuality computeThesisQuality3D(const PolyMesh& mesh, const MeshGeometry& geometry,
                                     ThesisQualityWorkspace& workspace)
{
    const Label faceCount = mesh.faceCount();
    if (geometry.faceAreas.size() != static_cast<std::size_t>(faceCount)) {
        throw std::invalid_argument("computeThesisQuality3D: the geometry has " +
                                    std::to_string(geometry.faceAreas.size()) + " faces, the mesh " +
                                    std::to_string(faceCount));
    }
    ThesisQuality quality;
    quality.dimension = 3;
    quality.cellCount = static_cast<Label>(geometry.cellVolumes.size());

    auto& inverted = workspace.cellInverted;
    inverted.assign(static_cast<std::size_t>(quality.cellCount), 0);
    const auto& centres = geometry.cellCentres;

    const Label internalFaceCount = mesh.internalFaceCount();
    std::vector<double> angle(static_cast<std::size_t>(internalFaceCount)),
        skew(static_cast<std::size_t>(internalFaceCount));
#pragma omp parallel for schedule(static) if (worthThreading(static_cast<std::size_t>(internalFaceCount)))
    for (Label f = 0; f < internalFaceCount; ++f) {
        const Label own = mesh.owner[f];
        const Label nei = mesh.neighbour[f];
        angle[f] = nonOrthogonalityAngle(centres[own], centres[nei], geometry.faceAreas[f]);
        skew[f] = centreLineSkewness(centres[own], centres[nei], geometry.faceCentres[f], geometry.faceAreas[f]);
    }
    StatisticsAccumulator nonOrthogonality;
    StatisticsAccumulator skewness;
    for (Label f = 0; f < faceCount; ++f) {
        const Vector3& S = geometry.faceAreas[f];
        const Vector3& fc = geometry.faceCentres[f];
        const Label own = mesh.owner[f];
        // Face pyramids with apex at the cell centres (InvertedCell.hpp).
        if (isInvertedCell(1.0, tripleFacePyramid(S, fc, centres[own], true))) inverted[own] = 1;
        if (f < internalFaceCount) {
            const Label nei = mesh.neighbour[f];
            if (isInvertedCell(1.0, tripleFacePyramid(S, fc, centres[nei], false))) inverted[nei] = 1;
            nonOrthogonality.add(angle[f]);
            skewness.add(skew[f]);
        }
    }
    for (Label c = 0; c < quality.cellCount; ++c) {
        if (inverted[c] != 0 || isInvertedCell(geometry.cellVolumes[c], 1.0)) ++quality.invertedCellCount;
    }
    quality.nonOrthogonality = nonOrthogonality.result();
    quality.skewness = skewness.result();
    return quality;
}

ThesisQuality computeThesisQuality3D(const PolyMesh& mesh, const MeshGeometry& geometry)
{
    ThesisQualityWorkspace workspace;
    return computeThesisQuality3D(mesh, geometry, workspace);
}

} // namespace rbm
