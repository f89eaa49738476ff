#pragma once
// One rank's part of a decomposed mesh as the distributed solver takes it: the rank's own
// points and cells (cells as point lists), each point's label in the whole mesh, and which
// points lie on faces shared with another rank. Built from a processor's polyMesh
// (decomposePar's processorN/, whose processor patches hold the shared faces and whose
// pointProcAddressing holds the global labels) or from OpenFOAM's local mesh in the plugin.
// Nothing here is communicated: MeshPart does that.

#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <span>
#include <vector>

namespace rbm::motion {

struct LocalCells {
    std::vector<Vector3> points;
    // Per point: its label in the undecomposed mesh (0 … global point count − 1).
    std::vector<Label> globalIds;
    // Cell c has the points cellPoints[cellOffsets[c] .. cellOffsets[c+1]) (local labels).
    std::vector<Label> cellOffsets{0};
    std::vector<Label> cellPoints;
    // Per point: 1 when it lies on a face shared with another rank (a processor patch). Every
    // point that another rank also holds is such a point: the cells around a point are
    // connected through their faces.
    std::vector<char> onProcessorBoundary;

    Label pointCount() const { return static_cast<Label>(points.size()); }
    Label cellCount() const { return static_cast<Label>(cellOffsets.size()) - 1; }
};

// The part of a processor's polyMesh: its cells from the faces, the points of its patches of
// type "processor" flagged, `globalIds` its pointProcAddressing (one per point). Throws
// std::invalid_argument when the sizes do not match.
LocalCells localCellsOf(const PolyMesh& processorMesh, std::span<const Label> globalIds);

} // namespace rbm::motion
