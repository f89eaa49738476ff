#pragma once
// The cell-neighbour graph of the RBM method (docs/method.md §1): node j is a neighbour of
// node i when they share at least one cell. Stored in CSR form: the neighbours of node i
// are neighbours[offsets[i] .. offsets[i+1]), sorted ascending, never containing i itself.
// The relation is symmetric.

#include "PolyMesh.hpp"

#include <span>
#include <vector>

namespace rbm {

struct MeshTopology;
struct PlanarMesh;

struct CellNeighbourGraph {
    std::vector<Label> offsets{0};
    std::vector<Label> neighbours;

    Label nodeCount() const { return static_cast<Label>(offsets.size()) - 1; }
    Label edgeCount() const { return static_cast<Label>(neighbours.size()); }   // directed: each pair twice
    std::span<const Label> neighboursOf(Label node) const
    {
        return {neighbours.data() + offsets[node], static_cast<std::size_t>(offsets[node + 1] - offsets[node])};
    }
};

// Builds the graph from cells given as point lists in CSR form (cell c has points
// cellPoints[cellOffsets[c] .. cellOffsets[c+1])), over nodes 0 .. nodeCount-1.
CellNeighbourGraph buildCellNeighbourGraph(Label nodeCount, std::span<const Label> cellOffsets,
                                           std::span<const Label> cellPoints);

// The same graph over the points of a 3D mesh (cells from MeshTopology's cell → points lists).
CellNeighbourGraph buildCellNeighbourGraph(const MeshTopology& topology);
CellNeighbourGraph buildCellNeighbourGraph(const PolyMesh& mesh);
// Over the nodes of a 2D mesh (cells are its polygons).
CellNeighbourGraph buildCellNeighbourGraph(const PlanarMesh& mesh);

} // namespace rbm
