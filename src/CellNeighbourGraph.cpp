#include "CellNeighbourGraph.hpp"

#include "MeshTopology.hpp"
#include "PlanarMesh.hpp"
#include "ThreadCount.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

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
    // (no set, no per-row allocation), then sorted. Threads build contiguous ranges of rows
    // into their own buffers, concatenated in row order: the graph does not depend on the
    // thread count.
    CellNeighbourGraph graph;
    graph.offsets.assign(static_cast<std::size_t>(nodeCount) + 1, 0);
    std::vector<std::vector<Label>> rangeNeighbours;
    std::vector<Label> rangeStart;
    const bool threaded = worthThreading(cellPoints.size());
#pragma omp parallel if (threaded)
    {
        int threads = 1, thread = 0;
#ifdef _OPENMP
        threads = omp_get_num_threads();
        thread = omp_get_thread_num();
#endif
#pragma omp single
        {
            rangeNeighbours.resize(static_cast<std::size_t>(threads));
            rangeStart.resize(static_cast<std::size_t>(threads) + 1);
            for (int t = 0; t <= threads; ++t)
                rangeStart[t] = static_cast<Label>(static_cast<long long>(nodeCount) * t / threads);
        }
        std::vector<Label>& neighbours = rangeNeighbours[thread];
        const Label first = rangeStart[thread];
        const Label end = rangeStart[thread + 1];
        neighbours.reserve(static_cast<std::size_t>(nodeCellOffsets[end] - nodeCellOffsets[first]) * 4);
        std::vector<Label> lastRow(static_cast<std::size_t>(nodeCount), -1);
        for (Label i = first; i < end; ++i) {
            const auto rowBegin = neighbours.size();
            lastRow[i] = i;   // never list i itself
            for (Label k = nodeCellOffsets[i]; k < nodeCellOffsets[i + 1]; ++k) {
                const Label c = nodeCells[k];
                for (Label j = cellOffsets[c]; j < cellOffsets[c + 1]; ++j) {
                    const Label p = cellPoints[j];
                    if (lastRow[p] != i) {
                        lastRow[p] = i;
                        neighbours.push_back(p);
                    }
                }
            }
            std::sort(neighbours.begin() + static_cast<std::ptrdiff_t>(rowBegin), neighbours.end());
            graph.offsets[i + 1] = static_cast<Label>(neighbours.size() - rowBegin);   // row length for now
        }
    }
    for (Label i = 0; i < nodeCount; ++i) graph.offsets[i + 1] += graph.offsets[i];
    graph.neighbours.resize(static_cast<std::size_t>(graph.offsets.back()));
#pragma omp parallel for schedule(static) if (threaded)
    for (std::size_t t = 0; t < rangeNeighbours.size(); ++t) {
        std::copy(rangeNeighbours[t].begin(), rangeNeighbours[t].end(),
                  graph.neighbours.begin() + graph.offsets[rangeStart[t]]);
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
