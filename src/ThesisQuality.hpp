#pragma once
// The grid quality metrics of the thesis (§2.7; docs/method.md §7), each summarised
// by its mean, standard deviation, minimum and maximum (eqs 2.98a–d):
//
//  2D (a PlanarMesh, cells counter-clockwise):
//  - mean-ratio q of every triangle (eqs 2.93–2.97). With A_n the Jacobian at node n
//    (edges to the next two nodes, eq 2.93), W the equilateral triangle's (eq 2.94) and
//    S_n = A_n W^-1 (eq 2.95): q = (2/3) sum_n det(S_n) / |S_n|_F^2. That is the standard
//    mean ratio 2 det(S)/|S|_F^2 (|S_n|_F is the same at every node), equal to
//    4 sqrt(3) area / (sum of squared edge lengths): 1 for an equilateral triangle, 0 for
//    a degenerate one, negative for an inverted one. Note: eq 2.96 as printed,
//    mu_n = det(S_n) / (2 |S_n|_F^2), would give q = 1/2 for the ideal triangle, against the
//    text's statement that q_e = 2 mu-bar is normalised to 1; we follow the text.
//  - F_shape of every quadrilateral (eqs 2.99–2.101): with A_n the Jacobian at corner n
//    (edges to the next and to the previous corner) and S_n = A_n^T A_n,
//    F_shape = 8 / sum_n tr(S_n)/det(A_n): 1 for a square, 2ab/(a^2+b^2) for an a x b
//    rectangle, sin(angle) for a rhombus, negative when inverted, 0 when degenerate.
//  - non-orthogonality of every internal edge: the angle in degrees between the line from
//    the owner's centroid to the neighbour's and the edge normal (pointing from owner to
//    neighbour), 0..180; beyond 90 the centres are on the wrong sides.
//  - skewness of every internal edge: |c' - c_f| / |C_A C_B| with c' where the centre line
//    crosses the edge's line and c_f the edge midpoint.
//  - inverted cells: signed area <= 0 (inverted or degenerate).
//  3D (a PolyMesh with its MeshGeometry): non-orthogonality and skewness the same way over
//  internal faces (cell centres, face centres and area vectors as OpenFOAM computes them),
//  and inverted cells: cells with a face pyramid (apex at the cell centre) of volume <= 0.
//
// Cell centres in 2D are polygon area centroids (the centre of the extruded cell in a
// pseudo-3D mesh, so 2D and 3D figures agree on clean extrusions). Standard deviations
// are population ones (1/N, eq 2.98b). Statistics over zero items have count 0 and zeros.

#include "MeshGeometry.hpp"
#include "PlanarMesh.hpp"
#include "PolyMesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace rbm {

struct QualityStatistics {
    Label count = 0;
    double mean = 0.0;
    double standardDeviation = 0.0;   // population (1/N), eq 2.98b
    double min = 0.0;
    double max = 0.0;
};

// Single-pass mean / standard deviation (Welford) / min / max.
class StatisticsAccumulator {
public:
    void add(double value)
    {
        ++count_;
        const double delta = value - mean_;
        mean_ += delta / static_cast<double>(count_);
        sumSquaredDeviations_ += delta * (value - mean_);
        if (count_ == 1 || value < min_) min_ = value;
        if (count_ == 1 || value > max_) max_ = value;
    }
    QualityStatistics result() const;

private:
    Label count_ = 0;
    double mean_ = 0.0;
    double sumSquaredDeviations_ = 0.0;
    double min_ = 0.0;
    double max_ = 0.0;
};

struct ThesisQuality {
    int dimension = 3;                        // 2: PlanarMesh metrics; 3: PolyMesh metrics
    Label cellCount = 0;
    QualityStatistics triangleMeanRatio;      // q, 2D triangles (eqs 2.93–2.98)
    QualityStatistics quadrilateralShape;     // F_shape, 2D quadrilaterals (eqs 2.99–2.101)
    Label otherPolygonCount = 0;              // 2D cells with 5 or more nodes (no shape metric)
    QualityStatistics nonOrthogonality;       // degrees, internal edges (2D) / faces (3D)
    QualityStatistics skewness;               // internal edges / faces
    Label invertedCellCount = 0;
};

// Element metrics on the (x, y) components; nodes counter-clockwise.
double triangleMeanRatio(const Vector3& i, const Vector3& j, const Vector3& k);
double quadrilateralShape(const Vector3& i, const Vector3& j, const Vector3& k, const Vector3& m);

// Area centroid of a polygon on (x, y) (z of the result = mean z of the nodes); for a
// polygon of zero area, the node average. `signedArea` receives the shoelace area.
Vector3 polygonCentroid(std::span<const Label> polygon, std::span<const Vector3> positions, double& signedArea);
// The same signed area as polygonCentroid's, to the last bit, without the centroid.
double polygonSignedArea(std::span<const Label> polygon, std::span<const Vector3> positions);
// Twice the smallest signed area (on x, y) of the triangles (edge a→b, `centroid`) of a
// counter-clockwise polygon: ≤ 0 when the centroid is on or outside one of its edges, which
// InvertedCell.hpp counts as inverted (the pseudo-3D cell's side-face pyramids).
double smallestEdgeTriangle(std::span<const Label> polygon, std::span<const Vector3> positions, const Vector3& centroid);

// Angle in degrees between the centre line (from `ownerCentre` to `neighbourCentre`) and
// the normal `normal` (pointing from owner to neighbour).
double nonOrthogonalityAngle(const Vector3& ownerCentre, const Vector3& neighbourCentre, const Vector3& normal);
// |c' - c_f| / |d|: c' where the centre line crosses the plane (line in 2D) through
// `faceCentre` with normal `normal`.
double centreLineSkewness(const Vector3& ownerCentre, const Vector3& neighbourCentre, const Vector3& faceCentre,
                          const Vector3& normal);

// Per-cell work arrays kept between calls.
struct ThesisQualityWorkspace {
    std::vector<Vector3> cellCentres;            // 2D centroids
    std::vector<std::uint8_t> cellInverted;      // 3D flags
};

// 2D metrics with the nodes at `positions` (same count as mesh.points; mesh.points for the
// mesh as it is).
ThesisQuality computeThesisQuality2D(const PlanarMesh& mesh, std::span<const Vector3> positions,
                                     ThesisQualityWorkspace& workspace);
ThesisQuality computeThesisQuality2D(const PlanarMesh& mesh);

// 3D metrics for `points` whose geometry is `geometry`.
ThesisQuality computeThesisQuality3D(const PolyMesh& mesh, const MeshGeometry& geometry,
                                     ThesisQualityWorkspace& workspace);
ThesisQuality computeThesisQuality3D(const PolyMesh& mesh, const MeshGeometry& geometry);

} // namespace rbm
