#include "CheckMeshQuality.hpp"

#include "ThreadCount.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rbm {

namespace {

// OpenFOAM's double-precision constants (primitives/Scalar/doubleScalar/doubleScalar.H).
constexpr double small = 1.0e-15;           // SMALL
constexpr double verySmall = 1.0e-300;      // VSMALL
constexpr double rootVerySmall = 1.0e-150;  // ROOTVSMALL
constexpr double veryGreat = 1.0e+300;      // VGREAT

// unitConversion.H: radToDeg(rad) = rad*180/pi, degToRad(deg) = deg*pi/180.
double radiansToDegrees(double radians) { return radians * 180.0 / std::numbers::pi; }
double degreesToRadians(double degrees) { return degrees * std::numbers::pi / 180.0; }

Vector3 componentMagnitudes(const Vector3& v) { return {std::abs(v.x), std::abs(v.y), std::abs(v.z)}; }

// VectorI.H normalised(): zero for a vector shorter than ROOTVSMALL.
Vector3 normalised(const Vector3& v)
{
    const double length = norm(v);
    return length < rootVerySmall ? Vector3{} : v / length;
}

// The normalisation distance shared by faceSkewness and boundaryFaceSkewness: "the
// approximate distance from the face centre to the edge of the face in the direction of
// the skewness", at least `floor`.
double skewnessNormalisation(std::span<const Label> facePoints, std::span<const Vector3> points,
                             const Vector3& faceCentre, const Vector3& skewDirection, double floor)
{
    double distance = floor;
    for (Label p : facePoints) distance = std::max(distance, std::abs(dot(skewDirection, points[p] - faceCentre)));
    return distance;
}

bool isType(const Patch& patch, const char* type) { return patch.type == type; }

} // namespace

int CheckMeshQuality::failedCheckCount() const
{
    int failed = 0;
    double largestOpenness = 0.0;
    for (int i = 0; i < 3; ++i) largestOpenness = std::max(largestOpenness, std::abs(boundaryOpenness[i]));
    if (largestOpenness > closedThreshold) ++failed;                                 // checkClosedBoundary
    if (openCellCount > 0 || highAspectRatioCellCount > 0) ++failed;                 // checkClosedCells
    if (faceCount > 0 && minFaceArea < verySmall) ++failed;                          // checkFaceAreas
    if (cellCount > 0 && minCellVolume < verySmall) ++failed;                        // checkCellVolumes
    if (nonOrthogonalityErrorCount > 0) ++failed;                                    // checkFaceOrthogonality
    if (incorrectlyOrientedPyramidCount > 0) ++failed;                               // checkFacePyramids
    if (severelySkewFaceCount > 0) ++failed;                                         // checkFaceSkewness
    return failed;
}

bool CheckMeshQuality::hasInvalidCells() const
{
    return openCellCount > 0 || zeroAreaFaceCount > 0 || nonPositiveVolumeCellCount > 0 ||
           nonOrthogonalityErrorCount > 0 || incorrectlyOrientedPyramidCount > 0;
}

double faceNonOrthogonalityCosine(const Vector3& ownerCentre, const Vector3& neighbourCentre, const Vector3& faceArea)
{
    // primitiveMeshTools::faceOrthogonality
    const Vector3 d = neighbourCentre - ownerCentre;
    return dot(d, faceArea) / (norm(d) * norm(faceArea) + rootVerySmall);
}

double faceSkewness(std::span<const Label> facePoints, std::span<const Vector3> points, const Vector3& faceCentre,
                    const Vector3& faceArea, const Vector3& ownerCentre, const Vector3& neighbourCentre)
{
    // primitiveMeshTools::faceSkewness
    const Vector3 ownerToFace = faceCentre - ownerCentre;
    const Vector3 d = neighbourCentre - ownerCentre;
    const Vector3 skew = ownerToFace - (dot(faceArea, ownerToFace) / (dot(faceArea, d) + rootVerySmall)) * d;
    const Vector3 skewDirection = skew / (norm(skew) + rootVerySmall);
    const double distance =
        skewnessNormalisation(facePoints, points, faceCentre, skewDirection, 0.2 * norm(d) + rootVerySmall);
    return norm(skew) / distance;
}

double boundaryFaceSkewness(std::span<const Label> facePoints, std::span<const Vector3> points, const Vector3& faceCentre,
                            const Vector3& faceArea, const Vector3& ownerCentre)
{
    // primitiveMeshTools::boundaryFaceSkewness: the neighbour is the owner mirrored in the face.
    const Vector3 ownerToFace = faceCentre - ownerCentre;
    const Vector3 normal = normalised(faceArea);
    const Vector3 d = normal * dot(normal, ownerToFace);
    const Vector3 skew = ownerToFace - (dot(faceArea, ownerToFace) / (dot(faceArea, d) + rootVerySmall)) * d;
    const Vector3 skewDirection = skew / (norm(skew) + rootVerySmall);
    const double distance =
        skewnessNormalisation(facePoints, points, faceCentre, skewDirection, 0.4 * norm(d) + rootVerySmall);
    return norm(skew) / distance;
}

void computeMeshDirections(const PolyMesh& mesh, std::span<const Vector3> faceAreas,
                           std::array<int, 3>& solutionDirections, std::array<int, 3>& geometricDirections)
{
    // polyMesh::calcDirections
    int emptyPatchCount = 0;
    int wedgePatchCount = 0;
    Vector3 emptyDirections;
    Vector3 wedgeDirections;
    for (const Patch& patch : mesh.patches) {
        if (patch.faceCount == 0) continue;
        if (isType(patch, "empty")) {
            ++emptyPatchCount;
            for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) {
                emptyDirections += componentMagnitudes(faceAreas[f]);
            }
        } else if (isType(patch, "wedge")) {
            // wedgePolyPatch::calcGeometry: n = average unit face normal; the centre normal
            // keeps the components beyond 0.5 in magnitude (shifted by 0.5), normalised.
            ++wedgePatchCount;
            Vector3 averageNormal;
            for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) {
                averageNormal += faceAreas[f] / (norm(faceAreas[f]) + verySmall);
            }
            averageNormal /= static_cast<double>(patch.faceCount);
            Vector3 centreNormal;
            for (int i = 0; i < 3; ++i) {
                const double sign = averageNormal[i] >= 0.0 ? 1.0 : -1.0;
                centreNormal[i] = sign * (std::max(std::abs(averageNormal[i]), 0.5) - 0.5);
            }
            centreNormal /= norm(centreNormal);
            wedgeDirections += componentMagnitudes(centreNormal);
        }
    }

    solutionDirections = {1, 1, 1};
    if (emptyPatchCount > 0) {
        emptyDirections /= norm(emptyDirections);
        for (int i = 0; i < 3; ++i) solutionDirections[i] = emptyDirections[i] > 1e-6 ? 0 : 1;
    }
    // "Knock out wedge directions": with wedges, geometricD is set from the wedges alone.
    geometricDirections = solutionDirections;
    if (wedgePatchCount > 0) {
        wedgeDirections /= norm(wedgeDirections);
        for (int i = 0; i < 3; ++i) geometricDirections[i] = wedgeDirections[i] > 1e-6 ? 0 : 1;
    }
}

namespace {

// checkMesh's costly per-face measures, by threads (each writes its own faces): the
// non-orthogonality cosine of every internal face and the skewness of every face.
void computeFaceMeasures(const PolyMesh& mesh, std::span<const Vector3> points, const MeshGeometry& geometry,
                         std::vector<double>& faceCosine, std::vector<double>& faceSkew)
{
    const Label faceCount = mesh.faceCount();
    const Label internalFaceCount = mesh.internalFaceCount();
    const std::span<const Vector3> faceCentres = geometry.faceCentres;
    const std::span<const Vector3> faceAreas = geometry.faceAreas;
    const std::span<const Vector3> cellCentres = geometry.cellCentres;
    const Label* owner = mesh.owner.data();
    const Label* neighbour = mesh.neighbour.data();
#pragma omp parallel for schedule(static) if (worthThreading(static_cast<std::size_t>(faceCount)))
    for (Label f = 0; f < faceCount; ++f) {
        const Vector3& S = faceAreas[f];
        const Vector3& fc = faceCentres[f];
        const Label own = owner[f];
        if (f < internalFaceCount) {
            const Label nei = neighbour[f];
            faceCosine[f] = faceNonOrthogonalityCosine(cellCentres[own], cellCentres[nei], S);
            faceSkew[f] = faceSkewness(mesh.face(f), points, fc, S, cellCentres[own], cellCentres[nei]);
        } else {
            faceSkew[f] = boundaryFaceSkewness(mesh.face(f), points, fc, S, cellCentres[own]);
        }
    }
}

// Overall domain bounding box (boundBox of all points).
void measureBoundingBox(std::span<const Vector3> points, CheckMeshQuality& q)
{
    if (points.empty()) return;
    q.boundingBoxMin = q.boundingBoxMax = points[0];
    for (const Vector3& p : points) {
        for (int i = 0; i < 3; ++i) {
            q.boundingBoxMin[i] = std::min(q.boundingBoxMin[i], p[i]);
            q.boundingBoxMax[i] = std::max(q.boundingBoxMax[i], p[i]);
        }
    }
}

// The face checks' sums, minima and counts, taken face by face in face order.
struct FaceChecks {
    const MeshGeometry& geometry;
    const Label* owner;
    const Label* neighbour;
    const std::vector<double>& faceCosine;
    const std::vector<double>& faceSkew;
    CheckMeshQuality& q;
    std::vector<Vector3>& sumClosed;
    std::vector<Vector3>& sumMagClosed;
    double severeCosine = std::cos(degreesToRadians(CheckMeshQuality::nonOrthogonalityThreshold));
    double minPyramidVolume = -small;   // checkGeometry.C: checkFacePyramids(true, -SMALL, ...)
    double minArea = std::numeric_limits<double>::max();
    double maxArea = -std::numeric_limits<double>::max();
    double minCosine = veryGreat;
    double sumCosine = 0.0;
    double maxSkew = 0.0;
    double minWeight = veryGreat;
    double sumWeight = 0.0;
    double minRatio = veryGreat;
    double sumRatio = 0.0;
    Vector3 boundarySum{};
    double boundaryMagnitudeSum = 0.0;

    // Face f: areas, the owner's closedness, the owner's pyramid, then the internal or boundary checks.
    void add(Label f)
    {
        const Vector3& S = geometry.faceAreas[f];
        const Vector3& fc = geometry.faceCentres[f];
        const Label own = owner[f];
        const Vector3 magS = componentMagnitudes(S);
        const double area = norm(S);

        // checkFaceAreas
        if (area < verySmall) ++q.zeroAreaFaceCount;
        minArea = std::min(minArea, area);
        maxArea = std::max(maxArea, area);

        // cellClosedness: sum of S (owner +, neighbour - below) and of component-wise |S|.
        sumClosed[own] += S;
        sumMagClosed[own] += magS;

        // checkFacePyramids, owner side: -pyramid(face, C_o).mag() = S.(C_f - C_o)/3.
        if ((1.0 / 3.0) * dot(S, fc - geometry.cellCentres[own]) < minPyramidVolume) ++q.incorrectlyOrientedPyramidCount;

        if (f < q.internalFaceCount) {
            addInternal(f, S, fc, own);
        } else {
            // checkClosedBoundary
            boundarySum += S;
            boundaryMagnitudeSum += area;

            const double skew = faceSkew[f];
            maxSkew = std::max(maxSkew, skew);
            if (skew > CheckMeshQuality::skewnessThreshold) ++q.severelySkewFaceCount;
        }
    }

    // Internal face f: the neighbour's pyramid, non-orthogonality, skewness, weight and volume ratio.
    void addInternal(Label f, const Vector3& S, const Vector3& fc, Label own)
    {
        const std::span<const Vector3> cellCentres = geometry.cellCentres;
        const Label nei = neighbour[f];
        if ((1.0 / 3.0) * dot(S, cellCentres[nei] - fc) < minPyramidVolume) ++q.incorrectlyOrientedPyramidCount;

        // polyMesh::checkFaceOrthogonality
        const double cosine = faceCosine[f];
        if (cosine < severeCosine) {
            if (cosine > small) {
                ++q.severelyNonOrthogonalFaceCount;
            } else {
                ++q.nonOrthogonalityErrorCount;
            }
        }
        minCosine = std::min(minCosine, cosine);
        sumCosine += cosine;

        // polyMesh::checkFaceSkewness
        const double skew = faceSkew[f];
        maxSkew = std::max(maxSkew, skew);
        if (skew > CheckMeshQuality::skewnessThreshold) ++q.severelySkewFaceCount;

        // polyMeshTools::faceWeights and volRatio
        const double ownerDistance = std::abs(dot(S, fc - cellCentres[own]));
        const double neighbourDistance = std::abs(dot(S, cellCentres[nei] - fc));
        const double weight =
            std::min(neighbourDistance, ownerDistance) / (neighbourDistance + ownerDistance + verySmall);
        minWeight = std::min(minWeight, weight);
        sumWeight += weight;
        if (weight < CheckMeshQuality::faceWeightThreshold) ++q.lowWeightFaceCount;

        const double ownerVolume = geometry.cellVolumes[own];
        const double neighbourVolume = geometry.cellVolumes[nei];
        const double ratio =
            std::min(ownerVolume, neighbourVolume) / (std::max(ownerVolume, neighbourVolume) + verySmall);
        minRatio = std::min(minRatio, ratio);
        sumRatio += ratio;
        if (ratio < CheckMeshQuality::volumeRatioThreshold) ++q.lowVolumeRatioFaceCount;
    }

    // The face figures of q from the sums and extremes.
    void store() const
    {
        if (q.faceCount > 0) {
            q.minFaceArea = minArea;
            q.maxFaceArea = maxArea;
        }
        q.boundaryOpenness = boundarySum / (boundaryMagnitudeSum + verySmall);
        q.maxSkewness = maxSkew;
        if (q.internalFaceCount > 0) {
            const double n = static_cast<double>(q.internalFaceCount);
            q.maxNonOrthogonality = radiansToDegrees(std::acos(std::clamp(minCosine, -1.0, 1.0)));
            q.averageNonOrthogonality = radiansToDegrees(std::acos(std::clamp(sumCosine / n, -1.0, 1.0)));
            q.minFaceWeight = minWeight;
            q.averageFaceWeight = sumWeight / n;
            q.minVolumeRatio = minRatio;
            q.averageVolumeRatio = sumRatio / n;
        }
    }
};

// cellClosedness' aspect ratio of a cell from its component-wise |S| sums and volume.
double cellAspectRatio(const Vector3& magClosed, const std::array<int, 3>& geometricDirections, int dimensions,
                       double cellVolume)
{
    double minComponent = veryGreat;
    double maxComponent = -veryGreat;
    for (int i = 0; i < 3; ++i) {
        if (geometricDirections[i] == 1) {
            minComponent = std::min(minComponent, magClosed[i]);
            maxComponent = std::max(maxComponent, magClosed[i]);
        }
    }
    double aspectRatio = maxComponent / (minComponent + rootVerySmall);
    if (dimensions == 3) {
        const double v = std::max(rootVerySmall, cellVolume);
        aspectRatio = std::max(aspectRatio,
                               1.0 / 6.0 * (magClosed.x + magClosed.y + magClosed.z) / std::pow(v, 2.0 / 3.0));
    }
    return aspectRatio;
}

// Per cell: openness, aspect ratio (cellClosedness with meshD = geometricD), volumes.
void checkCells(std::span<const double> cellVolumes, const std::vector<Vector3>& sumClosed,
                const std::vector<Vector3>& sumMagClosed, CheckMeshQuality& q)
{
    const int dimensions = q.geometricDimensionCount();
    double minVolume = std::numeric_limits<double>::max();
    double maxVolume = -std::numeric_limits<double>::max();
    double totalVolume = 0.0;
    double maxOpenness = 0.0;
    double maxAspect = -std::numeric_limits<double>::max();
    for (Label c = 0; c < q.cellCount; ++c) {
        const Vector3& closed = sumClosed[c];
        const Vector3& magClosed = sumMagClosed[c];
        double openness = 0.0;
        for (int i = 0; i < 3; ++i) openness = std::max(openness, std::abs(closed[i]) / (magClosed[i] + rootVerySmall));
        if (openness > CheckMeshQuality::closedThreshold) ++q.openCellCount;
        maxOpenness = std::max(maxOpenness, openness);

        const double aspectRatio = cellAspectRatio(magClosed, q.geometricDirections, dimensions, cellVolumes[c]);
        if (aspectRatio > CheckMeshQuality::aspectThreshold) ++q.highAspectRatioCellCount;
        maxAspect = std::max(maxAspect, aspectRatio);

        const double volume = cellVolumes[c];
        if (volume < verySmall) ++q.nonPositiveVolumeCellCount;
        minVolume = std::min(minVolume, volume);
        maxVolume = std::max(maxVolume, volume);
        totalVolume += volume;
    }
    if (q.cellCount > 0) {
        q.maxCellOpenness = maxOpenness;
        q.maxAspectRatio = maxAspect;
        q.minCellVolume = minVolume;
        q.maxCellVolume = maxVolume;
    }
    q.totalVolume = totalVolume;
}

} // namespace

CheckMeshQuality computeCheckMeshQuality(const PolyMesh& mesh, std::span<const Vector3> points,
                                         const MeshGeometry& geometry, CheckMeshWorkspace& workspace)
{
    CheckMeshQuality q;
    q.pointCount = mesh.pointCount();
    q.faceCount = mesh.faceCount();
    q.internalFaceCount = mesh.internalFaceCount();
    q.cellCount = static_cast<Label>(geometry.cellVolumes.size());
    if (geometry.faceAreas.size() != static_cast<std::size_t>(q.faceCount) ||
        points.size() != mesh.points.size()) {
        throw std::invalid_argument("computeCheckMeshQuality: the geometry (" + std::to_string(geometry.faceAreas.size()) +
                                    " faces) or points (" + std::to_string(points.size()) +
                                    ") do not belong to this mesh");
    }
    measureBoundingBox(points, q);
    computeMeshDirections(mesh, geometry.faceAreas, q.solutionDirections, q.geometricDirections);

    auto& sumClosed = workspace.sumClosed;
    auto& sumMagClosed = workspace.sumMagClosed;
    sumClosed.assign(static_cast<std::size_t>(q.cellCount), Vector3{});
    sumMagClosed.assign(static_cast<std::size_t>(q.cellCount), Vector3{});

    // The costly per-face measures first, by threads (each writes its own faces); the sums,
    // minima and counts below then run in face order as before, whatever the thread count.
    std::vector<double> faceCosine(static_cast<std::size_t>(q.internalFaceCount));
    std::vector<double> faceSkew(static_cast<std::size_t>(q.faceCount));
    computeFaceMeasures(mesh, points, geometry, faceCosine, faceSkew);

    FaceChecks faces{geometry, mesh.owner.data(), mesh.neighbour.data(), faceCosine, faceSkew, q, sumClosed, sumMagClosed};
    for (Label f = 0; f < q.faceCount; ++f) faces.add(f);

    // Neighbour contributions in a second loop, as cellClosedness adds them: the same
    // summation order gives bit-identical aspect ratios.
    for (Label f = 0; f < q.internalFaceCount; ++f) {
        sumClosed[mesh.neighbour[f]] -= geometry.faceAreas[f];
        sumMagClosed[mesh.neighbour[f]] += componentMagnitudes(geometry.faceAreas[f]);
    }
    faces.store();
    checkCells(geometry.cellVolumes, sumClosed, sumMagClosed, q);
    return q;
}

namespace {

// The largest non-orthogonality (from the smallest cosine over the internal faces) and the
// largest skewness (over all faces, at least 0): min and max are exact, so the order of the
// faces does not matter.
CheckMeshExtremes extremesOfFaceMeasures(std::span<const double> internalFaceCosines, std::span<const double> faceSkewness)
{
    double minCosine = veryGreat;
    for (const double cosine : internalFaceCosines) minCosine = std::min(minCosine, cosine);
    double maxSkew = 0.0;
    for (const double skew : faceSkewness) maxSkew = std::max(maxSkew, skew);
    CheckMeshExtremes extremes;
    extremes.maxSkewness = maxSkew;
    if (!internalFaceCosines.empty())
        extremes.maxNonOrthogonality = radiansToDegrees(std::acos(std::clamp(minCosine, -1.0, 1.0)));
    return extremes;
}

} // namespace

CheckMeshExtremes computeCheckMeshExtremes(const PolyMesh& mesh, std::span<const Vector3> points,
                                           const MeshGeometry& geometry, CheckMeshExtremesWorkspace& workspace)
{
    const Label faceCount = mesh.faceCount();
    const Label internalFaceCount = mesh.internalFaceCount();
    if (geometry.faceAreas.size() != static_cast<std::size_t>(faceCount) || points.size() != mesh.points.size()) {
        throw std::invalid_argument("computeCheckMeshExtremes: the geometry (" + std::to_string(geometry.faceAreas.size()) +
                                    " faces) or points (" + std::to_string(points.size()) +
                                    ") do not belong to this mesh");
    }
    // The per-face measures of computeCheckMeshQuality, by threads; then its minimum and
    // maximum in face order: the same figures, whatever the thread count.
    auto& faceCosine = workspace.faceCosine;
    auto& faceSkew = workspace.faceSkew;
    faceCosine.resize(static_cast<std::size_t>(internalFaceCount));
    faceSkew.resize(static_cast<std::size_t>(faceCount));
    computeFaceMeasures(mesh, points, geometry, faceCosine, faceSkew);
    return extremesOfFaceMeasures(faceCosine, faceSkew);
}

namespace {

// The front-plane positions of the 2D nodes in the plane's frame (z = 0) and the planes'
// distance; false when the points are no longer an extrusion to rounding.
bool projectExtrusion(const PseudoTwoDMesh& twoD, std::span<const Vector3> points, std::vector<Vector3>& positions,
                      double& thickness)
{
    const PlaneFrame& frame = twoD.frame;
    const Label nodes = twoD.planar.nodeCount();
    // Still an extrusion to rounding? Both planes' coordinates of every node, within
    // extrusionTolerance of the thickness (out of plane) or of the coordinates' size (in plane):
    // a body turned about the plane's normal moves its points out of plane by the rounding of
    // its rotation (0.1 + 2e-17 on the benchmark's airfoil).
    constexpr double extrusionTolerance = 1e-12;
    positions.resize(static_cast<std::size_t>(nodes));
    const double frontPlane = frame.toLocal(points[twoD.frontPointOfNode[0]]).z;
    const double backPlane = frame.toLocal(points[twoD.backPointOfNode[0]]).z;
    thickness = backPlane - frontPlane;
    const double outOfPlane = extrusionTolerance * thickness;
    bool extrusion = thickness > 0.0;
#pragma omp parallel for schedule(static) reduction(&& : extrusion) if (worthThreading(static_cast<std::size_t>(nodes)))
    for (Label n = 0; n < nodes; ++n) {
        const Vector3 front = frame.toLocal(points[twoD.frontPointOfNode[n]]);
        const Vector3 back = frame.toLocal(points[twoD.backPointOfNode[n]]);
        const double inPlane = extrusionTolerance * (std::abs(front.x) + std::abs(front.y) + thickness);
        extrusion = extrusion && std::abs(front.x - back.x) <= inPlane && std::abs(front.y - back.y) <= inPlane &&
                    std::abs(front.z - frontPlane) <= outOfPlane && std::abs(back.z - backPlane) <= outOfPlane;
        positions[n] = {front.x, front.y, 0.0};
    }
    return extrusion;
}

// Cell centres: the polygon's centroid (shoelace, about its first vertex) at mid-thickness;
// false when a polygon's area is not positive.
bool planarCellCentres(const PlanarMesh& planar, std::span<const Vector3> positions, std::vector<Vector3>& cellCentres)
{
    const Label cellCount = planar.cellCount();
    cellCentres.resize(static_cast<std::size_t>(cellCount));
    bool positive = true;
#pragma omp parallel for schedule(static) reduction(&& : positive) if (worthThreading(static_cast<std::size_t>(cellCount)))
    for (Label c = 0; c < cellCount; ++c) {
        const auto polygon = planar.cell(c);
        const Vector3& origin = positions[polygon[0]];
        double twiceArea = 0.0, sumX = 0.0, sumY = 0.0;
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
            const Vector3 a = positions[polygon[k]] - origin;
            const Vector3 b = positions[polygon[k + 1]] - origin;
            const double cross = a.x * b.y - a.y * b.x;
            twiceArea += cross;
            sumX += cross * (a.x + b.x);
            sumY += cross * (a.y + b.y);
        }
        positive = positive && twiceArea > 0.0;
        const double scale = twiceArea > 0.0 ? 1.0 / (3.0 * twiceArea) : 0.0;
        cellCentres[c] = {origin.x + sumX * scale, origin.y + sumY * scale, 0.0};
    }
    return positive;
}

// checkMesh's extremes over the side faces, one per 2D edge, by threads.
CheckMeshExtremes sideFaceExtremes(const PlanarMesh& planar, std::span<const Vector3> positions,
                                   std::span<const Vector3> cellCentres, double thickness,
                                   std::vector<double>& edgeCosine, std::vector<double>& edgeSkew)
{
    // Side faces, one per 2D edge: centre at the edge's midpoint, area (dy, −dx) × thickness
    // (the edge runs counter-clockwise around its owner, whose side the normal leaves). Every
    // vector the measures take lies in the plane (centres all at mid-thickness), so they are
    // evaluated in the plane's frame, with z = 0: the same values (the frame is orthonormal),
    // and a face's four corners project onto its edge's two ends (the skewness' normalisation
    // takes |direction · (corner − centre)| with an in-plane direction).
    const Label edgeCount = planar.edgeCount();
    const Label internalEdges = planar.internalEdgeCount();
    edgeCosine.resize(static_cast<std::size_t>(internalEdges));
    edgeSkew.resize(static_cast<std::size_t>(edgeCount));
#pragma omp parallel for schedule(static) if (worthThreading(static_cast<std::size_t>(edgeCount)))
    for (Label e = 0; e < edgeCount; ++e) {
        const std::span<const Label> ends(planar.edgePoints.data() + 2 * static_cast<std::size_t>(e), 2);
        const Vector3& p0 = positions[ends[0]];
        const Vector3& p1 = positions[ends[1]];
        const Vector3 faceCentre{0.5 * (p0.x + p1.x), 0.5 * (p0.y + p1.y), 0.0};
        const Vector3 faceArea{(p1.y - p0.y) * thickness, (p0.x - p1.x) * thickness, 0.0};
        const Vector3& ownerCentre = cellCentres[planar.edgeOwner[e]];
        if (e < internalEdges) {
            const Vector3& neighbourCentre = cellCentres[planar.edgeNeighbour[e]];
            edgeCosine[e] = faceNonOrthogonalityCosine(ownerCentre, neighbourCentre, faceArea);
            edgeSkew[e] = faceSkewness(ends, positions, faceCentre, faceArea, ownerCentre, neighbourCentre);
        } else {
            edgeSkew[e] = boundaryFaceSkewness(ends, positions, faceCentre, faceArea, ownerCentre);
        }
    }
    return extremesOfFaceMeasures(edgeCosine, edgeSkew);  // the empty faces' skewness 0 adds nothing
}

} // namespace

std::optional<CheckMeshExtremes> computeExtrusionCheckMeshExtremes(const PolyMesh& mesh, const PseudoTwoDMesh& twoD,
                                                                   std::span<const Vector3> points,
                                                                   ExtrusionExtremesWorkspace& workspace)
{
    if (twoD.kind != PseudoTwoDKind::Empty || points.size() != mesh.points.size()) return std::nullopt;
    if (twoD.planar.nodeCount() == 0) return std::nullopt;
    double thickness = 0.0;
    if (!projectExtrusion(twoD, points, workspace.planarPositions, thickness)) return std::nullopt;
    if (!planarCellCentres(twoD.planar, workspace.planarPositions, workspace.cellCentres)) {
        return std::nullopt;  // an inverted cell: OpenFOAM's decompositions decide
    }
    return sideFaceExtremes(twoD.planar, workspace.planarPositions, workspace.cellCentres, thickness,
                            workspace.edgeCosine, workspace.edgeSkew);
}

CheckMeshQuality computeCheckMeshQuality(const PolyMesh& mesh, const MeshGeometry& geometry)
{
    CheckMeshWorkspace workspace;
    return computeCheckMeshQuality(mesh, mesh.points, geometry, workspace);
}

} // namespace rbm
