#pragma once
// Every quality figure rbm reports for a mesh, in one struct: mesh statistics and cell
// types, checkMesh's geometry measures (CheckMeshQuality.hpp) and the thesis' metrics
// (ThesisQuality.hpp). For a pseudo-3D mesh (one layer between empty or wedge planes) the
// thesis metrics are the 2D ones, on the extracted planar mesh (PseudoTwoDExtraction.hpp);
// otherwise the 3D ones.
//
// QualityEvaluator keeps everything that does not change when points move (topology, cell
// types, the 2D extraction) and the work arrays, so evaluating the quality of a moved mesh
// every time step allocates only the report itself.
//
// Formatting: formatQualityReport gives a checkMesh-like text report; qualityReportJson
// the same numbers as one JSON object (non-finite numbers as null).

#include "CheckMeshQuality.hpp"
#include "MeshGeometry.hpp"
#include "MeshTopology.hpp"
#include "PolyMesh.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "ThesisQuality.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace rbm {

struct QualityReport {
    // Mesh stats, as checkMesh prints them.
    Label pointCount = 0;
    Label faceCount = 0;
    Label internalFaceCount = 0;
    Label cellCount = 0;
    double facesPerCell = 0.0;   // (faces + internal faces) / cells
    Label patchCount = 0;
    Label pointZoneCount = 0;
    Label faceZoneCount = 0;
    Label cellZoneCount = 0;
    // Cells of each shape, indexed by CellShape (tetrahedron, pyramid, prism, hexahedron,
    // polyhedron).
    std::array<Label, 5> cellShapeCounts{};

    PseudoTwoDKind pseudoTwoD = PseudoTwoDKind::None;
    // Why a mesh with empty or wedge patches is measured in 3D (extraction failed); empty otherwise.
    std::string twoDExtractionProblem;

    CheckMeshQuality checkMesh;
    ThesisQuality thesis;

    // Inverted cells (src/InvertedCell.hpp; 2D: area <= 0 or the centroid across an edge; 3D:
    // a face pyramid or the volume <= 0).
    Label invertedCellCount() const { return thesis.invertedCellCount; }
    // Valid: no inverted cell and none of checkMesh's errors (non-positive volumes, wrong
    // face pyramids, open cells, zero-area faces, faces beyond 90° non-orthogonality).
    // checkMesh's warnings (aspect ratio > 1000, skewness > 4) do not make a mesh invalid.
    bool isValid() const { return thesis.invertedCellCount == 0 && !checkMesh.hasInvalidCells(); }
};

// The four figures a time step's log line and the inverted-cell policy need (rbmMoveMesh's
// time loop, the OpenFOAM plugin; motionSolvers/StepAssessment.hpp), each equal to the same
// figure of the full report: to the last bit, except the two checkMesh extremes of a pseudo-2D
// mesh that is still an extrusion (to rounding), which come from closed forms on the 2D mesh
// (computeExtrusionCheckMeshExtremes) and agree to rounding (about 1e-14 relative):
struct StepQuality {
    double maxNonOrthogonality = 0.0;   // report.checkMesh.maxNonOrthogonality
    double maxSkewness = 0.0;           // report.checkMesh.maxSkewness
    // Worst cell: 2D (thesis metrics on the extracted plane) the smallest mean-ratio q of the
    // triangles and F_shape of the quadrilaterals (NaN without either); 3D the smallest
    // face-pyramid ratio n_faces · min_f V_f / |V_cell| with V_f = S_f · (C_f − C)/3 (S_f
    // outward; 1 for a cube, ≤ 0 for an inverted cell, 0 for a cell of zero volume).
    double worstCellQuality = 0.0;
    Label invertedCellCount = 0;        // report.invertedCellCount()
};

class QualityEvaluator {
public:
    // Prepares the evaluation of `mesh` (its topology; the points may later move). The mesh
    // must outlive the evaluator.
    explicit QualityEvaluator(const PolyMesh& mesh);
    // The same with the mesh's topology built already (buildMeshTopology(mesh)) and, for a
    // pseudo-3D mesh, its extracted 2D mesh (extractPseudoTwoD(mesh), e.g. the motion
    // solver's), which must outlive the evaluator; nullptr: extracted here as above.
    QualityEvaluator(const PolyMesh& mesh, MeshTopology topology, const PseudoTwoDMesh* twoD);

    // The report for the mesh with its points at `points` (mesh.points or moved positions).
    QualityReport evaluate(std::span<const Vector3> points);
    QualityReport evaluate() { return evaluate(mesh_.points); }
    // Only the figures of StepQuality, at about half the cost of evaluate() (a pseudo-2D mesh
    // still an extrusion: about a fifth). geometryAt(points) is then that of `points`.
    StepQuality evaluateStep(std::span<const Vector3> points);

    // Built again here after releaseWorkspaces() (about 0.13 s at 10⁶ hexahedra).
    const MeshTopology& topology() const;
    // The topology with at least each cell's faces (facesOf; the point lists may be empty): all
    // a 3D step's quality reads. After releaseWorkspaces() only that part is built again, in about
    // a fifth of the whole topology's time.
    const MeshTopology& cellFaceTopology() const;
    // The extracted 2D mesh of a pseudo-3D mesh (nullptr otherwise, or when the extraction failed).
    const PseudoTwoDMesh* twoDMesh() const { return twoD_; }

    // The geometry of the points of the last evaluate() or evaluateStep(), which must be
    // `points`: computed here when evaluateStep() did without it (an extrusion).
    const MeshGeometry& geometryAt(std::span<const Vector3> points);
    // The geometry computed by the last evaluate() (or evaluateStep() on its 3D path).
    const MeshGeometry& geometry() const { return geometry_; }
    // The per-face measures behind the last evaluateStep()'s two checkMesh extremes on its 3D
    // path (not an extrusion's closed forms): faceCosine per internal face, faceSkew per face,
    // a boundary face's with checkMesh's mirror cell. A part of a decomposed mesh
    // (motionSolvers/distributed/PartQuality) needs them without its processor faces, which are
    // boundary faces here but internal faces of the whole mesh.
    const CheckMeshExtremesWorkspace& stepFaceMeasures() const { return extremesWorkspace_; }
    bool isTwoD() const { return twoD_ != nullptr; }
    // Gives back the per-face and per-cell work arrays (the geometry among them; the next
    // geometryAt() computes it again) and the topology (topology() builds it again). Between
    // the time steps of a run they would sit beside the motion solver's own arrays: 230 MB and
    // 100 MB at 10⁶ hexahedra, which would raise the peak of a large 3D run. A pseudo-2D mesh's
    // step evaluation does not read the topology.
    void releaseWorkspaces();

private:
    const PolyMesh& mesh_;
    // Rebuilt on demand once released (topology(), cellFaceTopology()): a cache of the mesh's,
    // hence mutable.
    enum class TopologyHeld { whole, cellFacesOnly, none };
    mutable MeshTopology topology_;
    mutable TopologyHeld topologyHeld_ = TopologyHeld::whole;
    std::array<Label, 5> cellShapeCounts_{};   // counted at the first evaluate() (evaluateStep needs none)
    bool haveCellShapeCounts_ = false;
    PseudoTwoDKind pseudoTwoD_ = PseudoTwoDKind::None;
    std::string twoDExtractionProblem_;
    std::unique_ptr<PseudoTwoDMesh> ownTwoD_;
    const PseudoTwoDMesh* twoD_ = nullptr;     // ownTwoD_ or the one given
    MeshGeometry geometry_;
    CheckMeshWorkspace checkMeshWorkspace_;
    ThesisQualityWorkspace thesisWorkspace_;
    std::vector<Vector3> nodePositions_;
    CheckMeshExtremesWorkspace extremesWorkspace_;
    ExtrusionExtremesWorkspace extrusionWorkspace_;
    bool geometryStale_ = false;                // geometry_ is not that of the last evaluateStep's points
    std::vector<double> cellValues_;            // evaluateStep: per cell q / F_shape, or pyramid ratio
    std::vector<std::uint8_t> cellInverted_;    // evaluateStep: per cell
};

// One-off evaluation of `mesh` at its own points.
QualityReport computeQualityReport(const PolyMesh& mesh);

// checkMesh-like readable report (mesh stats, cell types, 2D/3D, checkMesh's measures with
// its OK/*** verdicts, the thesis metrics table, inverted cells, "Mesh OK." or "Failed N
// mesh checks.").
std::string formatQualityReport(const QualityReport& report);

// The same figures as one JSON object (see the keys in QualityReport.cpp).
std::string qualityReportJson(const QualityReport& report);

} // namespace rbm
