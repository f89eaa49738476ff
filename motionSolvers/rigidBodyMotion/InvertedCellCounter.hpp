#pragma once
// The solver's own check of a displacement: how many cells it inverts (src/InvertedCell.hpp's
// predicate) and the worst cell quality, on the mesh the solve is done on (2D: the planar
// cells of a pseudo-3D mesh; 3D: the polyMesh). It decides the sub-step splits, the
// untangling and the step's report.
//
// A solve checks its last sub-step's result, then (unchanged unless untangled) the state it
// keeps: the last check without a cell list is remembered with its displacement, and the same
// bits give the same figures without a second pass over the mesh.

#include "MeshGeometry.hpp"
#include "PolyMesh.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "Vector3.hpp"

#include <span>
#include <vector>

namespace rbm::motion {

class InvertedCellCounter {
public:
    // 3D: `mesh` and its reference points `points0` (both must outlive the counter);
    // `twoD` non-null: the planar mesh is checked instead, displacements per planar node.
    InvertedCellCounter(const PolyMesh& mesh, const std::vector<Vector3>& points0, const PseudoTwoDMesh* twoD);

    // The number of inverted cells of the reference mesh moved by `nodeDisplacement`.
    // worstQuality (optional): the worst cell quality (2D: the thesis' mean ratio of
    // triangles / shape of quadrilaterals; 3D: the smallest face pyramid relative to the mean
    // V / faces, 1 for a cube, ≤ 0 when inverted). invertedCells (optional): their labels (2D:
    // planar cells).
    Label count(std::span<const Vector3> nodeDisplacement, double* worstQuality = nullptr,
                std::vector<Label>* invertedCells = nullptr);

    // Drops the remembered last check (its copy of the displacement, 24 bytes a node).
    void forgetLastCheck()
    {
        std::vector<Vector3>().swap(checkedDisplacement_);
        checkedInverted_ = -1;
    }

private:
    Label countPlanar(std::span<const Vector3> nodeDisplacement, bool wantWorst, double& worst,
                      std::vector<Label>* invertedCells);
    Label countPolyhedral(std::span<const Vector3> nodeDisplacement, bool wantWorst, double& worst,
                          std::vector<Label>* invertedCells);

    const PolyMesh& mesh_;
    const std::vector<Vector3>& points0_;
    const PseudoTwoDMesh* twoD_;
    // Workspace of one check.
    MeshGeometry geometry_;
    std::vector<Vector3> positions_;
    std::vector<double> smallestPyramid_;
    std::vector<int> faceCounts_;
    // The last check without a cell list.
    std::vector<Vector3> checkedDisplacement_;
    Label checkedInverted_ = -1;   // -1: none yet
    double checkedWorst_ = 0.0;
};

} // namespace rbm::motion
