#include "CellNeighbourGraph.hpp"

#include "MeshTopology.hpp"
#include "PlanarMesh.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace rbm {

CellNeighbourGraph buildCellNeighbourGraph(Label nodeCount, std::span<const Label> cellOffsets,
                                           std::span<const Label> cellPoints)
{
    if (nodeCount < 0 || cellOffsets.empty() || cellOffsets.front() != 0
        || static_cast<std::size_t>(cellOffsets.back()) != cellPoints.size()) {
        throw std::invalid_argument("buildCellNeighbourGraph: cell offsets must start at 0 and end at the number of "
                                    "cell points");
    }
    const Label cellCount = static_cast<Label>(cellOffsets.size()) - 1;
    for (Label c = 0; c < cellCount; ++c) {
        if (cellOffsets[c + 1] < cellOffsets[c]) {
            throw std::invalid_argument("buildCellNeighbourGraph: offsets of cell " + std::to_string(c) + " decrease");
        }
    }
    for (Label p : cellPoints) {
        if (p < 0 || p >= nodeCount) {
            throw std::invalid_argument("buildCellNeighbourGraph: node label " + std::to_string(p)
                                        + " outside [0, " + std::to_string(nodeCount) + ")");
        }
    }

    // node → cells by counting sort.
    std::vector<Label> nodeCellOffsets(static_cast<std::size_t>(nodeCount) + 1, 0);
    for (Label p : cellPoints) ++nodeCellOffsets[p + 1];
    for (Label n = 0; n < nodeCount; ++n) nodeCellOffsets[n + 1] += nodeCellOffsets[n];
    std::vector<Label> nodeCells(cellPoints.size());
    {
        std::vector<Label> cursor(nodeCellOffsets.begin(), nodeCellOffsets.end() - 1);
        for (Label c = 0; c < cellCount; ++c) {
            for (Label i = cellOffsets[c]; i < cellOffsets[c + 1]; ++i) nodeCells[cursor[cellPoints[i]]++] = c;
        }
    }

    // Row i: the union of the points of i's cells, deduplicated with a per-node stamp
    // (no set, no per-row allocation), then sorted.
    CellNeighbourGraph graph;
    graph.offsets.reserve(static_cast<std::size_t>(nodeCount) + 1);
    graph.neighbours.reserve(cellPoints.size() * 4);
    std::vector<Label> lastRow(static_cast<std::size_t>(nodeCount), -1);
    for (Label i = 0; i < nodeCount; ++i) {
        const auto rowBegin = graph.neighbours.size();
        lastRow[i] = i;   // never list i itself
        for (Label k = nodeCellOffsets[i]; k < nodeCellOffsets[i + 1]; ++k) {
            const Label c = nodeCells[k];
            for (Label j = cellOffsets[c]; j < cellOffsets[c + 1]; ++j) {
                const Label p = cellPoints[j];
                if (lastRow[p] != i) {
                    lastRow[p] = i;
                    graph.neighbours.push_back(p);
                }
            }
        }
        std::sort(graph.neighbours.begin() + static_cast<std::ptrdiff_t>(rowBegin), graph.neighbours.end());
        graph.offsets.push_back(static_cast<Label>(graph.neighbours.size()));
    }
    return graph;
}

CellNeighbourGraph buildCellNeighbourGraph(const MeshTopology& topology)
{
    return buildCellNeighbourGraph(topology.pointCount, topology.cellPointOffsets, topology.cellPoints);
}

CellNeighbourGraph buildCellNeighbourGraph(const PolyMesh& mesh)
{
    return buildCellNeighbourGraph(buildMeshTopology(mesh));
}

CellNeighbourGraph buildCellNeighbourGraph(const PlanarMesh& mesh)
{
    return buildCellNeighbourGraph(mesh.nodeCount(), mesh.cellOffsets, mesh.cellPoints);
}

} // namespace rbm
