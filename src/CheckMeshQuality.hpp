#pragma once
// The geometry measures OpenFOAM's checkMesh prints, with checkMesh's own definitions
// (OpenFOAM v1912: applications/utilities/mesh/manipulation/checkMesh/checkGeometry.C,
// src/OpenFOAM/meshes/primitiveMesh/primitiveMeshCheck/{primitiveMeshCheck,primitiveMeshTools}.C,
// src/OpenFOAM/meshes/polyMesh/polyMeshCheck/{polyMeshCheck,polyMeshTools}.C), so that a
// user reading rbm's report sees the numbers checkMesh would print on the same mesh.
//
// Definitions (d = neighbour centre - owner centre, S = face area vector):
//  - non-orthogonality of an internal face: acos(d.S / (|d||S| + ROOTVSMALL)) in degrees;
//    Max = the largest angle; average = acos(mean of the cosines over internal faces) — the
//    angle of the mean cosine, not the mean angle (polyMesh::checkFaceOrthogonality).
//    "Severely non-orthogonal": cosine below cos(70°) but above SMALL; "errors": cosine <= SMALL
//    (beyond 90°).
//  - skewness: internal faces |sv| / fd with sv = (C_f - C_o) - (S.(C_f - C_o) / (S.d + ROOTVSMALL)) d,
//    the distance from the face centre to where the centre line crosses the face plane, and
//    fd = max(0.2 |d|, largest projection of (face point - face centre) on sv's direction)
//    (primitiveMeshTools::faceSkewness); boundary faces use the mirror cell: d = n (n.(C_f - C_o)),
//    fd starting from 0.4 |d| (primitiveMeshTools::boundaryFaceSkewness). Max over all faces;
//    "severely skew" above 4.
//  - face pyramids: the pyramid of every face with apex at the owner centre must have volume
//    S.(C_f - C_o)/3 >= -SMALL, and with apex at the neighbour centre S.(C_n - C_f)/3 >= -SMALL
//    (primitiveMesh::checkFacePyramids with checkMesh's minPyrVol = -SMALL); the count is of
//    failing pyramids ("N faces are incorrectly oriented").
//  - aspect ratio (primitiveMeshTools::cellClosedness): with s = sum over the cell's faces of
//    the component-wise |S|, over the geometric (non-empty, non-wedge) directions only:
//    max(s_i) / (min(s_i) + ROOTVSMALL); in 3D also at least (s_x + s_y + s_z) / (6 V^(2/3)).
//  - geometric directions (polyMesh::calcDirections): a direction is empty when the sum of the
//    component-wise |S| over all faces of non-empty `empty` patches, normalised, exceeds 1e-6
//    there; wedge patches likewise with the component-wise |centre normal|.
//  - cell volumes: "Zero or negative" means below VSMALL (1e-300).

#include "MeshGeometry.hpp"
#include "PolyMesh.hpp"
#include "PseudoTwoDExtraction.hpp"

#include <array>
#include <optional>
#include <span>
#include <vector>

namespace rbm {

struct CheckMeshQuality {
    // checkMesh's thresholds (primitiveMeshCheck.C static data, checkGeometry.C arguments).
    static constexpr double closedThreshold = 1.0e-6;
    static constexpr double aspectThreshold = 1000.0;
    static constexpr double nonOrthogonalityThreshold = 70.0;   // degrees
    static constexpr double skewnessThreshold = 4.0;
    static constexpr double faceWeightThreshold = 0.05;         // -allGeometry
    static constexpr double volumeRatioThreshold = 0.01;        // -allGeometry

    // Mesh stats.
    Label pointCount = 0;
    Label faceCount = 0;
    Label internalFaceCount = 0;
    Label cellCount = 0;

    Vector3 boundingBoxMin;
    Vector3 boundingBoxMax;
    // 1 where the mesh extends in that direction, 0 where it is empty (checkMesh's "(1 1 0)");
    // geometric directions also exclude wedge directions.
    std::array<int, 3> solutionDirections{1, 1, 1};
    std::array<int, 3> geometricDirections{1, 1, 1};

    Vector3 boundaryOpenness;            // sum of boundary S / sum of boundary |S|
    double maxCellOpenness = 0.0;
    Label openCellCount = 0;             // openness > closedThreshold
    double maxAspectRatio = 0.0;
    Label highAspectRatioCellCount = 0;  // > aspectThreshold

    double minFaceArea = 0.0;
    double maxFaceArea = 0.0;
    Label zeroAreaFaceCount = 0;         // |S| < VSMALL

    double minCellVolume = 0.0;
    double maxCellVolume = 0.0;
    double totalVolume = 0.0;
    Label nonPositiveVolumeCellCount = 0;   // V < VSMALL

    double maxNonOrthogonality = 0.0;       // degrees, internal faces
    double averageNonOrthogonality = 0.0;   // degrees: acos(mean cosine)
    Label severelyNonOrthogonalFaceCount = 0;
    Label nonOrthogonalityErrorCount = 0;   // beyond 90 degrees

    Label incorrectlyOrientedPyramidCount = 0;

    double maxSkewness = 0.0;               // internal and boundary faces
    Label severelySkewFaceCount = 0;        // > skewnessThreshold

    // -allGeometry measures (polyMeshTools::faceWeights, volRatio), internal faces.
    double minFaceWeight = 0.0;             // min(d_o, d_n)/(d_o + d_n) with d = |S.(C_f - C)|
    double averageFaceWeight = 0.0;
    Label lowWeightFaceCount = 0;           // internal faces below faceWeightThreshold
    double minVolumeRatio = 0.0;            // min(V_o, V_n)/max(V_o, V_n)
    double averageVolumeRatio = 0.0;
    Label lowVolumeRatioFaceCount = 0;      // internal faces below volumeRatioThreshold

    int geometricDimensionCount() const { return geometricDirections[0] + geometricDirections[1] + geometricDirections[2]; }
    int solutionDimensionCount() const { return solutionDirections[0] + solutionDirections[1] + solutionDirections[2]; }

    // The number of plain checkMesh geometry checks that fail ("Failed N mesh checks."):
    // closed boundary, closed cells (open cells or aspect ratio above 1000), face areas,
    // cell volumes, non-orthogonality errors (> 90°), face pyramids, skewness (> 4).
    // checkMesh's 2D edge-alignment check is not among them: rbm keeps the out-of-plane
    // coordinates of a 2D case unchanged, so a motion cannot misalign those edges.
    int failedCheckCount() const;
    // Failures that make the mesh unusable (as opposed to checkMesh's warnings about
    // aspect ratio and skewness): open cells, zero areas, non-positive volumes, faces
    // beyond 90° non-orthogonality, inverted face pyramids.
    bool hasInvalidCells() const;
};

// Geometric / solution directions of polyMesh::calcDirections from the `empty` and
// `wedge` patches (see the header comment).
void computeMeshDirections(const PolyMesh& mesh, std::span<const Vector3> faceAreas,
                           std::array<int, 3>& solutionDirections, std::array<int, 3>& geometricDirections);

// Per-cell work arrays, kept between calls so repeated evaluation allocates nothing.
struct CheckMeshWorkspace {
    std::vector<Vector3> sumClosed;
    std::vector<Vector3> sumMagClosed;
};

// All measures for `points` (mesh.points or moved positions) whose geometry is `geometry`.
CheckMeshQuality computeCheckMeshQuality(const PolyMesh& mesh, std::span<const Vector3> points,
                                         const MeshGeometry& geometry, CheckMeshWorkspace& workspace);
CheckMeshQuality computeCheckMeshQuality(const PolyMesh& mesh, const MeshGeometry& geometry);

// Only the two extremes a time step's log line prints (StepAssessment.hpp), equal to the last
// bit to computeCheckMeshQuality's maxNonOrthogonality and maxSkewness, at a third of its cost:
// none of the other measures, no work arrays allocated (`workspace` keeps them between calls).
struct CheckMeshExtremes {
    double maxNonOrthogonality = 0.0;   // degrees, internal faces; 0 without internal faces
    double maxSkewness = 0.0;           // internal and boundary faces
};
struct CheckMeshExtremesWorkspace {
    std::vector<double> faceCosine;
    std::vector<double> faceSkew;
};
CheckMeshExtremes computeCheckMeshExtremes(const PolyMesh& mesh, std::span<const Vector3> points,
                                           const MeshGeometry& geometry, CheckMeshExtremesWorkspace& workspace);

// The same two extremes for a one-layer extrusion between two `empty` planes (twoD.kind
// Empty) whose points at `points` are still an extrusion to rounding (1e-12): every front point
// and its twin with the same in-plane coordinates, each plane at one out-of-plane coordinate,
// the back one beyond the front one, and every cell of positive area. Then each 3D cell is a prism, its
// centre the polygon's centroid at mid-thickness, each side face a rectangle with its centre
// at the edge's midpoint and its area vector the edge's normal times the thickness: closed
// forms from the 2D positions instead of OpenFOAM's triangle and pyramid decompositions of
// every face and cell (the same values to rounding: 1e-12 relative on the checkMesh fixtures),
// and the empty faces' skewness its exact value 0 (the cell centre lies on their normal
// through their centre). The per-face formulas are those above. About a fifth of
// computeCheckMeshExtremes' cost with updateMeshGeometry; std::nullopt where the conditions
// do not hold (then computeCheckMeshExtremes). `workspace` keeps the work arrays.
struct ExtrusionExtremesWorkspace {
    std::vector<Vector3> planarPositions;   // per 2D node, in the plane's frame
    std::vector<Vector3> cellCentres;       // per cell, in the plane's frame (z = 0)
    std::vector<double> edgeCosine;
    std::vector<double> edgeSkew;
};
std::optional<CheckMeshExtremes> computeExtrusionCheckMeshExtremes(const PolyMesh& mesh, const PseudoTwoDMesh& twoD,
                                                                   std::span<const Vector3> points,
                                                                   ExtrusionExtremesWorkspace& workspace);

// The per-face measures, for tests and for locating bad faces.
double faceNonOrthogonalityCosine(const Vector3& ownerCentre, const Vector3& neighbourCentre, const Vector3& faceArea);
double faceSkewness(std::span<const Label> facePoints, std::span<const Vector3> points, const Vector3& faceCentre,
                    const Vector3& faceArea, const Vector3& ownerCentre, const Vector3& neighbourCentre);
double boundaryFaceSkewness(std::span<const Label> facePoints, std::span<const Vector3> points, const Vector3& faceCentre,
                            const Vector3& faceArea, const Vector3& ownerCentre);

} // namespace rbm
