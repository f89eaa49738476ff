#pragma once
// A hexahedral box decomposed over the ranks of PETSC_COMM_WORLD without files, as
// decomposePar would split it: every rank builds the whole box, assigns the cells to ranks and
// takes its own as LocalCells (its points in a scrambled local order, the points of faces
// between ranks flagged). The tests of the distributed parts compare each rank's part with the
// whole box.

#include "CellNeighbourGraph.hpp"
#include "LocalCells.hpp"
#include "MeshGenerators.hpp"
#include "MeshTopology.hpp"

#include <mpi.h>
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <vector>

namespace rbm::test {

inline int worldRank()
{
    int rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    return rank;
}

inline int worldSize()
{
    int size = 1;
    MPI_Comm_size(PETSC_COMM_WORLD, &size);
    return size;
}

// Which rank cell (i, j, k) of an nx × ny × nz box goes to.
using BoxDecomposition = std::function<int(Label i, Label j, Label k, int ranks)>;

// Blocks: ranks meet along planes, edges and corners (2: a staircase; 4: quadrants around a
// vertical edge).
inline BoxDecomposition blockDecomposition(Label nx, Label ny)
{
    return [nx, ny](Label i, Label j, Label, int ranks) {
        if (ranks == 1) return 0;
        if (ranks == 2) return i + j < (nx + ny) / 2 ? 0 : 1;
        if (ranks == 3) return i < 2 ? 0 : (j < 3 ? 1 : 2);
        return (i < nx / 2 ? 0 : 1) + (j < ny / 2 ? 0 : 2);
    };
}

// Scattered: cell (i, j, k) on rank (7i + 3j + 5k) mod ranks: parts in pieces, points held by
// up to 8 ranks, most of them not face neighbours of each other.
inline int scatteredDecomposition(Label i, Label j, Label k, int ranks)
{
    return static_cast<int>((7 * i + 3 * j + 5 * k) % ranks);
}

// The top layer of cells on the last rank, the rest in slabs along x over the others: the last
// rank then owns no unknown node (its own points are the top's, prescribed in the tests, and
// the layer below, which lower ranks hold too).
inline BoxDecomposition topLayerDecomposition(Label nx, Label nz)
{
    return [nx, nz](Label i, Label, Label k, int ranks) {
        if (ranks == 1) return 0;
        return k == nz - 1 ? ranks - 1 : static_cast<int>(i * (ranks - 1) / nx);
    };
}

struct DecomposedBox {
    Label nx, ny, nz;
    PolyMesh mesh;
    MeshTopology topology;
    CellNeighbourGraph graph;
    std::vector<int> cellRanks;
    std::vector<std::set<int>> holders;  // per point: the ranks with a cell around it

    // The box [0, 1.2] × [0, 1] × [0, 0.8] with its points moved off the lattice (so that
    // coordinates identify points), cells on ranks by `decomposition` over PETSC_COMM_WORLD.
    DecomposedBox(Label nx_, Label ny_, Label nz_, const BoxDecomposition& decomposition)
        : nx(nx_), ny(ny_), nz(nz_), mesh(makeHexBox(nx, ny, nz, {0.0, 0.0, 0.0}, {1.2, 1.0, 0.8}))
    {
        for (Vector3& x : mesh.points) x = x + 0.01 * Vector3{std::sin(7 * x.y), std::cos(5 * x.z), std::sin(3 * x.x)};
        topology = buildMeshTopology(mesh);
        graph = buildCellNeighbourGraph(topology);
        const int ranks = worldSize();
        for (Label c = 0; c < topology.cellCount; ++c)
            cellRanks.push_back(decomposition(c % nx, (c / nx) % ny, c / (nx * ny), ranks));
        holders.resize(mesh.points.size());
        for (Label c = 0; c < topology.cellCount; ++c)
            for (Label p : topology.pointsOf(c)) holders[p].insert(cellRanks[c]);
    }

    motion::LocalCells localCells(int rank) const
    {
        std::vector<Label> globalOfLocal;
        for (Label p = 0; p < mesh.pointCount(); ++p)
            if (holders[p].count(rank)) globalOfLocal.push_back(p);
        const auto scrambled = [](Label a) { return (a * 7919) % 1009; };
        std::sort(globalOfLocal.begin(), globalOfLocal.end(), [&](Label a, Label b) {
            return scrambled(a) != scrambled(b) ? scrambled(a) < scrambled(b) : a < b;
        });
        std::vector<Label> localOfGlobal(mesh.points.size(), -1);
        motion::LocalCells cells;
        for (Label g : globalOfLocal) {
            localOfGlobal[g] = cells.pointCount();
            cells.points.push_back(mesh.points[g]);
            cells.globalIds.push_back(g);
        }
        for (Label c = 0; c < topology.cellCount; ++c) {
            if (cellRanks[c] != rank) continue;
            for (Label p : topology.pointsOf(c)) cells.cellPoints.push_back(localOfGlobal[p]);
            cells.cellOffsets.push_back(static_cast<Label>(cells.cellPoints.size()));
        }
        cells.onProcessorBoundary.assign(cells.points.size(), 0);
        for (Label f = 0; f < mesh.internalFaceCount(); ++f) {
            const int a = cellRanks[mesh.owner[f]], b = cellRanks[mesh.neighbour[f]];
            if (a == b || (a != rank && b != rank)) continue;
            for (Label p : mesh.face(f)) cells.onProcessorBoundary[localOfGlobal[p]] = 1;
        }
        return cells;
    }
};

} // namespace rbm::test
