#pragma once
// What every front door of rbm does after a motion solve (rbmMoveMesh's time loop, the
// OpenFOAM plugin's solve()): check that the displacement is finite, evaluate the moved
// mesh's quality (checkMesh's measures and the thesis' metrics, QualityReport.hpp), fill the
// step's log record (io::StepLogRecord: one readable line, one JSON line) and decide whether
// the step is valid: converged, finite, and no inverted cell. An invalid step stops the run
// unless the user asked to go on (rbmMoveMesh's -writeInvalid, the plugin's `writeInvalid`
// coefficient); invalidStepCause/invalidStepAdvice give the words for it, the same in both.
//
// Worst quality (the log line's "worst quality"): 2D meshes (pseudo-3D, solved on one plane)
// the smallest mean-ratio q of the triangles / F_shape of the quadrilaterals; 3D meshes the
// smallest face-pyramid ratio n_faces · min_f V_f / |V_cell| (1 for a cube or a regular
// tetrahedron, ≤ 0 for an inverted cell), the same figure as MotionSolveReport::worstQuality.

#include "MeshTopology.hpp"
#include "MotionSolver.hpp"
#include "PolyMesh.hpp"
#include "QualityReport.hpp"
#include "RunLog.hpp"
#include "Vector3.hpp"

#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace rbm::motion {

// 3D cell quality from the face pyramids with apex at the cell centre, V_f = S_f · (C_f − C)/3
// with S_f outward (the pyramids of the thesis' 3D inverted-cell test, ThesisQuality.hpp):
// ratio = n_faces · min_f V_f / |V_cell|, the smallest pyramid relative to the mean one.
struct PyramidQuality {
    double ratio = 0.0;
    bool inverted = false;   // a pyramid or the volume <= 0, as ThesisQuality counts
};
PyramidQuality cellPyramidQuality(const PolyMesh& mesh, const MeshTopology& topology, const MeshGeometry& geometry,
                                  Label cell);

struct StepVerdict {
    bool finite = true;         // no NaN or infinite displacement, a finite residual
    bool valid = true;          // finite, converged and no inverted cell
    std::string nonFiniteText;  // what was not finite (empty when finite)
};

class StepAssessor {
public:
    // The mesh (its topology; the points move) must outlive the assessor.
    explicit StepAssessor(const PolyMesh& mesh);
    // With the mesh's topology and 2D mesh built already (QualityEvaluator's second constructor).
    StepAssessor(const PolyMesh& mesh, MeshTopology topology, const PseudoTwoDMesh* twoD);
    ~StepAssessor();
    StepAssessor(const StepAssessor&) = delete;
    StepAssessor& operator=(const StepAssessor&) = delete;

    // Quality of the mesh with its points at `points`; geometry() is then theirs.
    QualityReport evaluate(std::span<const Vector3> points);
    // Only the log line's figures (worst quality, max non-orthogonality and skewness, inverted
    // cells), each equal to the full report's (QualityReport.hpp, StepQuality), at about half
    // the cost; geometryAt(points) is then that of `points`. What assess() evaluates.
    StepQuality evaluateStep(std::span<const Vector3> points) { return evaluator_.evaluateStep(points); }
    // The geometry of `points`, the points of the last evaluate() or evaluateStep().
    const MeshGeometry& geometryAt(std::span<const Vector3> points) { return evaluator_.geometryAt(points); }
    const MeshTopology& topology() const { return evaluator_.topology(); }
    // At least each cell's faces (QualityEvaluator::cellFaceTopology): what cellPyramidQuality reads.
    const MeshTopology& cellFaceTopology() const { return evaluator_.cellFaceTopology(); }
    // The extracted 2D mesh of a pseudo-3D mesh, nullptr otherwise (QualityEvaluator::twoDMesh).
    const PseudoTwoDMesh* twoDMesh() const { return evaluator_.twoDMesh(); }
    // The log line's worst quality of the report evaluate() returned last.
    double worstCellQuality(const QualityReport& report) const;
    // Between time steps: the evaluator's work arrays given back (QualityEvaluator::releaseWorkspaces).
    void releaseWorkspaces() { evaluator_.releaseWorkspaces(); }

    // Checks one solve: `displacement` and `points` are the solver's pointDisplacement() and
    // curPoints(). Fills the solve's and the quality's figures of `record` (not step, time,
    // timeName, wallSeconds, written); a solve with non-finite values counts as not converged
    // and its reason says what was not finite.
    StepVerdict assess(const MotionSolveReport& solve, std::span<const Vector3> displacement,
                       std::span<const Vector3> points, io::StepLogRecord& record);

private:
    const PolyMesh& mesh_;
    QualityEvaluator evaluator_;
};

// StepAssessor::assess's two halves, for a front door that evaluates the quality itself (one
// rank's part of a decomposed mesh: PartQuality, reduced over the ranks).
// The solve's figures into `record` and the verdict's finiteness: `nonFiniteText` says which
// displacements were not finite (empty when all were); a non-finite residual fails too.
StepVerdict recordSolve(const MotionSolveReport& solve, std::string nonFiniteText, io::StepLogRecord& record);
// The quality figures into `record` (NaN and no inverted cell when `quality` is null: a
// non-finite step is not evaluated), then the verdict's validity.
void recordQuality(const StepQuality* quality, StepVerdict& verdict, io::StepLogRecord& record);

// Why a step is invalid, one sentence without a full stop: "the moved mesh has 3 inverted
// cells", "... and the solve did not converge (reason)", "the motion solver did not converge
// (reason)" or "the motion solver produced <nonFiniteText> (solver's reason: ...)".
std::string invalidStepCause(const StepVerdict& verdict, const io::StepLogRecord& record);
// What may help, ending with how to go on anyway (`goOnAnyway`, e.g. "-writeInvalid writes
// the step anyway to look at it"); a non-finite step has no way to go on.
// `solverAdvice` (MotionSolver::invertedStepAdvice) replaces the general advice for inverted cells.
std::string invalidStepAdvice(const StepVerdict& verdict, const io::StepLogRecord& record, std::string_view goOnAnyway,
                              std::string_view solverAdvice = {});

} // namespace rbm::motion
