#include "MeshGeometry.hpp"

#include "ThreadCount.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rbm {

namespace {

// OpenFOAM's double-precision constants (src/OpenFOAM/primitives/Scalar/doubleScalar).
constexpr double rootVerySmall = 1.0e-150;   // ROOTVSMALL
constexpr double verySmall = 1.0e-300;       // VSMALL

} // namespace

void computeFaceCentresAndAreas(const PolyMesh& mesh, std::span<const Vector3> points,
                                std::vector<Vector3>& faceCentres, std::vector<Vector3>& faceAreas)
{
    if (points.size() != mesh.points.size()) {
        throw std::invalid_argument("computeFaceCentresAndAreas: " + std::to_string(points.size()) +
                                    " points given for a mesh of " + std::to_string(mesh.points.size()));
    }
    const Label faceCount = mesh.faceCount();
    faceCentres.resize(static_cast<std::size_t>(faceCount));
    faceAreas.resize(static_cast<std::size_t>(faceCount));

    // Every face on its own: threads write only their own faces.
#pragma omp parallel for schedule(static) if (worthThreading(static_cast<std::size_t>(faceCount)))
    for (Label f = 0; f < faceCount; ++f) {
        const auto face = mesh.face(f);
        const std::size_t n = face.size();

        // primitiveMeshTools::makeFaceCentresAndAreas: a triangle is computed directly
        // "for efficiency and to avoid round-off error-related problems".
        if (n == 3) {
            const Vector3& p0 = points[face[0]];
            const Vector3& p1 = points[face[1]];
            const Vector3& p2 = points[face[2]];
            faceCentres[f] = (1.0 / 3.0) * (p0 + p1 + p2);
            faceAreas[f] = 0.5 * cross(p1 - p0, p2 - p0);
            continue;
        }

        Vector3 pointAverage = points[face[0]];
        for (std::size_t i = 1; i < n; ++i) pointAverage += points[face[i]];
        pointAverage /= static_cast<double>(n);

        Vector3 sumN;
        double sumA = 0.0;
        Vector3 sumAc;
        for (std::size_t i = 0; i < n; ++i) {
            const Vector3& thisPoint = points[face[i]];
            const Vector3& nextPoint = points[face[i + 1 == n ? 0 : i + 1]];
            const Vector3 c = thisPoint + nextPoint + pointAverage;           // 3 x triangle centroid
            const Vector3 normal = cross(nextPoint - thisPoint, pointAverage - thisPoint);   // 2 x area vector
            const double a = norm(normal);
            sumN += normal;
            sumA += a;
            sumAc += a * c;
        }

        if (sumA < rootVerySmall) {
            // "This is to deal with zero-area faces."
            faceCentres[f] = pointAverage;
            faceAreas[f] = Vector3{};
        } else {
            faceCentres[f] = (1.0 / 3.0) * sumAc / sumA;
            faceAreas[f] = 0.5 * sumN;
        }
    }
}

void computeCellCentresAndVolumes(const PolyMesh& mesh, Label cellCount, std::span<const Vector3> faceCentres,
                                  std::span<const Vector3> faceAreas, std::vector<Vector3>& estimatedCellCentres,
                                  std::vector<Vector3>& cellCentres, std::vector<double>& cellVolumes)
{
    const std::size_t cells = static_cast<std::size_t>(cellCount);
    estimatedCellCentres.assign(cells, Vector3{});
    cellCentres.assign(cells, Vector3{});
    // cellVolumes first counts the faces of every cell, then accumulates 3 x pyramid volumes.
    cellVolumes.assign(cells, 0.0);

    const Label faceCount = mesh.faceCount();
    const Label internalFaceCount = mesh.internalFaceCount();
    const Label* owner = mesh.owner.data();
    const Label* neighbour = mesh.neighbour.data();

    // primitiveMeshTools::makeCellCentresAndVols: "first estimate the approximate cell
    // centre as the average of face centres".
    for (Label f = 0; f < faceCount; ++f) {
        estimatedCellCentres[owner[f]] += faceCentres[f];
        cellVolumes[owner[f]] += 1.0;
    }
    for (Label f = 0; f < internalFaceCount; ++f) {
        estimatedCellCentres[neighbour[f]] += faceCentres[f];
        cellVolumes[neighbour[f]] += 1.0;
    }
    for (std::size_t c = 0; c < cells; ++c) {
        estimatedCellCentres[c] /= cellVolumes[c];
        cellVolumes[c] = 0.0;
    }

    for (Label f = 0; f < faceCount; ++f) {
        const Vector3& fc = faceCentres[f];
        const Vector3& fA = faceAreas[f];
        const Label own = owner[f];
        // 3 x face-pyramid volume and the pyramid centroid.
        const double pyramid3Volume = dot(fA, fc - estimatedCellCentres[own]);
        const Vector3 pyramidCentre = (3.0 / 4.0) * fc + (1.0 / 4.0) * estimatedCellCentres[own];
        cellCentres[own] += pyramid3Volume * pyramidCentre;
        cellVolumes[own] += pyramid3Volume;
    }
    for (Label f = 0; f < internalFaceCount; ++f) {
        const Vector3& fc = faceCentres[f];
        const Vector3& fA = faceAreas[f];
        const Label nei = neighbour[f];
        const double pyramid3Volume = dot(fA, estimatedCellCentres[nei] - fc);
        const Vector3 pyramidCentre = (3.0 / 4.0) * fc + (1.0 / 4.0) * estimatedCellCentres[nei];
        cellCentres[nei] += pyramid3Volume * pyramidCentre;
        cellVolumes[nei] += pyramid3Volume;
    }

    for (std::size_t c = 0; c < cells; ++c) {
        if (std::abs(cellVolumes[c]) > verySmall) {
            cellCentres[c] /= cellVolumes[c];
        } else {
            cellCentres[c] = estimatedCellCentres[c];
        }
        cellVolumes[c] *= (1.0 / 3.0);
    }
}

void updateMeshGeometry(const PolyMesh& mesh, std::span<const Vector3> points, MeshGeometry& geometry)
{
    computeFaceCentresAndAreas(mesh, points, geometry.faceCentres, geometry.faceAreas);
    computeCellCentresAndVolumes(mesh, mesh.cellCount(), geometry.faceCentres, geometry.faceAreas,
                                 geometry.estimatedCellCentres, geometry.cellCentres, geometry.cellVolumes);
}

MeshGeometry computeMeshGeometry(const PolyMesh& mesh, std::span<const Vector3> points)
{
    MeshGeometry geometry;
    updateMeshGeometry(mesh, points, geometry);
    return geometry;
}

} // namespace rbm
