#pragma once
// The quality figures of a whole decomposed mesh (the log line's StepQuality: worst cell
// quality, max non-orthogonality, max skewness, inverted cells), evaluated by every rank on
// its processor mesh (decomposePar's processorN/constant/polyMesh, one rank per processor) and
// reduced over the ranks, so that every rank holds the same figures as a serial evaluation of
// the undecomposed mesh (QualityEvaluator::evaluateStep, what StepAssessor prints).
//
// The cell figures are local: every cell belongs to one rank. The face figures are not: a
// face on a `processor` patch is a boundary face of the processor mesh but an internal face of
// the whole mesh, whose non-orthogonality and skewness (CheckMeshQuality.hpp) take the cell
// centres on both sides. The matching patch on the neighbour rank lists the same faces in the
// same order (reversed), so each evaluation sends the centres of the patch faces' cells across
// every processor patch, from the higher rank to the lower, which measures those faces:
// measured once, with its own face geometry and the neighbour's centre. Both figures are the
// same whichever side measures (the face's area vector and the centre-to-centre vector both
// change sign, and skewness depends on neither sign), so the lower rank need not be the side of
// the whole mesh's owner cell. The skewness checkMesh gives a boundary face (with a mirror
// cell) is left out for processor faces.
//
// 3D parts only, like the rest of the distributed solve: a pseudo-2D part's evaluation takes
// closed forms on its 2D mesh without per-face measures.

#include "PolyMesh.hpp"
#include "QualityReport.hpp"
#include "Vector3.hpp"

#include <mpi.h>

#include <optional>

#include <span>
#include <vector>

namespace rbm::motion {

class PartQuality {
public:
    // Collective on `communicator`, whose rank r holds processor r: every processor patch of
    // `processorMesh` must have myProcNo r and a neighbProcNo of another rank, and its face
    // count must equal that of the neighbour's matching patch. Throws std::invalid_argument on
    // every rank when one rank's part breaks this or is pseudo-2D. The mesh (its topology; the
    // points move) must outlive this object.
    PartQuality(const PolyMesh& processorMesh, MPI_Comm communicator);

    // The whole mesh's figures with this part's points at `points` (one per point of the
    // processor mesh), the same on every rank. Collective.
    StepQuality evaluateStep(std::span<const Vector3> points);

    // Between time steps: the evaluator given back, its work arrays and its topology (the
    // next evaluateStep builds it again, O(cells)): the first solve's GAMG set-up is a rank's
    // memory peak, and the topology, about 90 bytes a point, need not be alive in it.
    void releaseWorkspaces();

private:
    // One processor patch: its faces [startFace, startFace + faceCount) and the rank across it.
    struct ProcessorPatch {
        Label startFace = 0;
        Label faceCount = 0;
        int neighbourRank = 0;
        int tag = 0;             // the patch's ordinal among this rank's patches to the same neighbour
        Label firstCentre = 0;   // its faces' slots in centresAcross_
    };

    // The extremes of this part's own faces: internal faces and the patches that are not processor patches.
    double ownFacesMaxSkewness() const;
    // Receives (lower rank) or sends (higher rank) the cell centres across every processor patch.
    void exchangeCellCentres(const MeshGeometry& geometry);
    // The processor faces this rank measures, folded into `quality`.
    void addProcessorFaces(std::span<const Vector3> points, const MeshGeometry& geometry, StepQuality& quality) const;

    const PolyMesh& mesh_;
    MPI_Comm communicator_;
    int rank_ = 0;
    std::optional<QualityEvaluator> evaluator_;  // empty after releaseWorkspaces()
    std::vector<ProcessorPatch> processorPatches_;
    // Per processor face, patch by patch: towards a lower rank the centre of this rank's cell
    // (sent), towards a higher rank that of the neighbour's cell (received).
    std::vector<Vector3> centresAcross_;
};

} // namespace rbm::motion
