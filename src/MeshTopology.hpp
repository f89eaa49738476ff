#pragma once
// Cell-based connectivity derived from the face-based PolyMesh: the faces and the
// (unique) points of every cell, and the cells around every point, all in CSR form.
// Built in one pass over the faces (plus a counting sort), without vector<vector>.
//
// Also the checker of OpenFOAM's polyMesh rules (docs/method.md §9), used by tests and by
// readers that want to reject a broken mesh with a clear message:
//  - faces have at least 3 distinct, valid point labels;
//  - internal faces come first, owner < neighbour, sorted by owner then neighbour
//    (upper-triangular order);
//  - patches are contiguous, start after the internal faces and cover every boundary face;
//  - every cell is closed and consistently oriented: with owner faces taken as they are
//    and neighbour faces reversed (outward orientation), every cell edge is used exactly
//    once in each direction;
//  - optionally, every cell has a positive volume with that orientation (normals point
//    from owner to neighbour and out of the domain).

#include "PolyMesh.hpp"

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace rbm {

struct MeshTopology {
    Label pointCount = 0;
    Label cellCount = 0;

    // Faces of cell c: cellFaces[cellFaceOffsets[c] .. cellFaceOffsets[c+1]), ascending face labels.
    std::vector<Label> cellFaceOffsets{0};
    std::vector<Label> cellFaces;
    // Points of cell c, each once: cellPoints[cellPointOffsets[c] .. cellPointOffsets[c+1]), ascending.
    std::vector<Label> cellPointOffsets{0};
    std::vector<Label> cellPoints;
    // Cells around point p: pointCells[pointCellOffsets[p] .. pointCellOffsets[p+1]), ascending.
    std::vector<Label> pointCellOffsets{0};
    std::vector<Label> pointCells;

    std::span<const Label> facesOf(Label cell) const
    {
        return {cellFaces.data() + cellFaceOffsets[cell],
                static_cast<std::size_t>(cellFaceOffsets[cell + 1] - cellFaceOffsets[cell])};
    }
    std::span<const Label> pointsOf(Label cell) const
    {
        return {cellPoints.data() + cellPointOffsets[cell],
                static_cast<std::size_t>(cellPointOffsets[cell + 1] - cellPointOffsets[cell])};
    }
    std::span<const Label> cellsOf(Label point) const
    {
        return {pointCells.data() + pointCellOffsets[point],
                static_cast<std::size_t>(pointCellOffsets[point + 1] - pointCellOffsets[point])};
    }
};

// Builds the cell → faces, cell → points and point → cells maps. Throws rbm::InputError
// (file "") when a face, owner or neighbour label is out of range, since nothing
// downstream could work on such a mesh.
MeshTopology buildMeshTopology(const PolyMesh& mesh);
// Only the first part of it: the counts and each cell's faces (cellFaceOffsets, cellFaces); the
// point lists stay empty. A few passes over the faces, about a fifth of the whole topology's
// time: what a per-step quality check of a 3D mesh reads (QualityEvaluator).
MeshTopology buildCellFaceTopology(const PolyMesh& mesh);

// Appends the points of face `face` oriented outward from `cell` (as stored when `cell`
// owns the face, reversed when it is the neighbour) to `out`.
void appendOutwardFace(const PolyMesh& mesh, Label face, Label cell, std::vector<Label>& out);

struct TopologyCheckOptions {
    bool checkCellVolumes = true;    // reject cells whose outward-oriented volume is not positive
    std::size_t maxMessages = 20;    // further problems are only counted
};

// Every violation of the rules listed at the top of this file, one sentence each naming
// the face, cell or patch; empty when the mesh is valid.
std::vector<std::string> checkPolyMeshOrdering(const PolyMesh& mesh, const TopologyCheckOptions& options = {});
// The same; when the faces, their owners and the patches pass (the cells are checked on the
// mesh's topology), `topology` receives that topology, buildMeshTopology(mesh), for the caller
// to keep; otherwise it is left as it was.
std::vector<std::string> checkPolyMeshOrdering(const PolyMesh& mesh, const TopologyCheckOptions& options,
                                               MeshTopology& topology);

// Throws rbm::InputError(file, 0, ...) listing the problems checkPolyMeshOrdering finds.
void validateTopology(const PolyMesh& mesh, const std::string& file = {}, const TopologyCheckOptions& options = {});

} // namespace rbm
