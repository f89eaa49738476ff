#include "LocalCells.hpp"

#include "MeshTopology.hpp"

#include <stdexcept>
#include <string>

namespace rbm::motion {

LocalCells localCellsOf(const PolyMesh& processorMesh, std::span<const Label> globalIds)
{
    if (globalIds.size() != processorMesh.points.size())
        throw std::invalid_argument("pointProcAddressing has " + std::to_string(globalIds.size()) +
                                    " labels for a mesh of " + std::to_string(processorMesh.points.size()) +
                                    " points (one per point expected)");
    LocalCells cells;
    cells.points = processorMesh.points;
    cells.globalIds.assign(globalIds.begin(), globalIds.end());
    const MeshTopology topology = buildMeshTopology(processorMesh);
    cells.cellOffsets = topology.cellPointOffsets;
    cells.cellPoints = topology.cellPoints;
    cells.onProcessorBoundary.assign(processorMesh.points.size(), 0);
    for (const Patch& patch : processorMesh.patches) {
        if (patch.type != "processor") continue;
        for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f)
            for (Label p : processorMesh.face(f)) cells.onProcessorBoundary[p] = 1;
    }
    return cells;
}

} // namespace rbm::motion
