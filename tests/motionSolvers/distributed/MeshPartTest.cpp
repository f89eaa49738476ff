// One rank's part of a decomposed mesh (MeshPart, PointOwnership, NodeExchange) against the
// whole mesh: CTest runs this program under mpiexec with 1, 2, 3 and 4 ranks. Every rank
// builds the whole hexahedral box, takes its cells of a decomposition, and checks its part
// against what the whole mesh says: each point owned once, by the lowest rank holding it;
// rows one contiguous range per rank; every owned node's neighbourhood in the RBM graph
// the same as in the undecomposed graph; the ghost update and the reverse addition.
// Two decompositions: blocks (ranks meet along planes, edges and corners) and a scatter
// (cell (i, j, k) on rank (7i + 3j + 5k) mod ranks: parts in pieces, points held by up to
// 8 ranks none of which are face neighbours of each other).

#include "PetscTestEnvironment.hpp"

#include "CellNeighbourGraph.hpp"
#include "MeshGenerators.hpp"
#include "MeshPart.hpp"
#include "MeshTopology.hpp"
#include "NodeExchange.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <vector>

namespace {

using namespace rbm;
using namespace rbm::motion;

constexpr Label nx = 6, ny = 5, nz = 4;

int worldRank()
{
    int rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    return rank;
}

int worldSize()
{
    int size = 1;
    MPI_Comm_size(PETSC_COMM_WORLD, &size);
    return size;
}

// The box with its points moved off the lattice (so coordinates identify points).
PolyMesh wholeMesh()
{
    PolyMesh mesh = makeHexBox(nx, ny, nz, {0.0, 0.0, 0.0}, {1.2, 1.0, 0.8});
    for (Vector3& x : mesh.points) x = x + 0.01 * Vector3{std::sin(7 * x.y), std::cos(5 * x.z), std::sin(3 * x.x)};
    return mesh;
}

using Decomposition = std::function<int(Label i, Label j, Label k, int ranks)>;

int blocks(Label i, Label j, Label k, int ranks)
{
    if (ranks == 1) return 0;
    if (ranks == 2) return i + j < (nx + ny) / 2 ? 0 : 1;  // a staircase
    if (ranks == 3) return i < 2 ? 0 : (j < 3 ? 1 : 2);
    return (i < nx / 2 ? 0 : 1) + (j < ny / 2 ? 0 : 2) + 0 * k;  // quadrants: 4 ranks around an edge
}

int scattered(Label i, Label j, Label k, int ranks) { return static_cast<int>((7 * i + 3 * j + 5 * k) % ranks); }

struct Whole {
    PolyMesh mesh = wholeMesh();
    MeshTopology topology = buildMeshTopology(mesh);
    CellNeighbourGraph graph = buildCellNeighbourGraph(topology);
    std::vector<int> cellRanks;
    // Per point: the ranks with a cell around it.
    std::vector<std::set<int>> holders;

    explicit Whole(const Decomposition& decomposition)
    {
        const int ranks = worldSize();
        for (Label c = 0; c < topology.cellCount; ++c)
            cellRanks.push_back(decomposition(c % nx, (c / nx) % ny, c / (nx * ny), ranks));
        holders.resize(mesh.points.size());
        for (Label c = 0; c < topology.cellCount; ++c)
            for (Label p : topology.pointsOf(c)) holders[p].insert(cellRanks[c]);
    }

    // This rank's cells, its points in a scrambled local order (the part must not depend on it).
    LocalCells localCells(int rank) const
    {
        std::vector<Label> globalOfLocal;
        for (Label p = 0; p < mesh.pointCount(); ++p)
            if (holders[p].count(rank)) globalOfLocal.push_back(p);
        std::sort(globalOfLocal.begin(), globalOfLocal.end(),
                  [](Label a, Label b) { return (a * 7919) % 1009 < (b * 7919) % 1009 || ((a * 7919) % 1009 == (b * 7919) % 1009 && a < b); });
        std::vector<Label> localOfGlobal(mesh.points.size(), -1);
        LocalCells cells;
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
        // Processor boundary: the points of internal faces between cells of different ranks.
        cells.onProcessorBoundary.assign(cells.points.size(), 0);
        for (Label f = 0; f < mesh.internalFaceCount(); ++f) {
            if (cellRanks[mesh.owner[f]] == cellRanks[mesh.neighbour[f]]) continue;
            if (cellRanks[mesh.owner[f]] != rank && cellRanks[mesh.neighbour[f]] != rank) continue;
            for (Label p : mesh.face(f)) cells.onProcessorBoundary[localOfGlobal[p]] = 1;
        }
        return cells;
    }
};

// Per global point, the sum over ranks of `perRank` (one value per global point on each rank).
std::vector<int> sumOverRanks(std::vector<int> perRank)
{
    std::vector<int> sum(perRank.size());
    MPI_Allreduce(perRank.data(), sum.data(), static_cast<int>(perRank.size()), MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
    return sum;
}

void checkOwnershipAndRows(const Whole& whole, const MeshPart& part)
{
    const int rank = worldRank();
    const Label pointCount = whole.mesh.pointCount();
    EXPECT_EQ(part.globalNodeCount(), pointCount);
    std::vector<int> owned(pointCount, 0), rowOf(pointCount, 0);
    for (Label node = 0; node < part.nodeCount(); ++node) {
        const Label g = part.nodeGlobalIds()[node];
        const int lowestHolder = *whole.holders[g].begin();
        EXPECT_EQ(part.nodeOwnerRanks()[node], lowestHolder) << "global point " << g;
        EXPECT_EQ(part.owns(node), lowestHolder == rank) << "global point " << g;
        EXPECT_EQ(part.nodePoints()[node], whole.mesh.points[g]) << "global point " << g;
        if (part.owns(node)) {
            EXPECT_EQ(part.nodeRows()[node], part.firstOwnedRow() + node);
            owned[g] = 1;
            rowOf[g] = part.nodeRows()[node];
        }
    }
    const std::vector<int> owners = sumOverRanks(owned);
    const std::vector<int> rows = sumOverRanks(rowOf);
    EXPECT_TRUE(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; })) << "a point owned twice or never";
    std::vector<int> sortedRows = rows;
    std::sort(sortedRows.begin(), sortedRows.end());
    for (Label r = 0; r < pointCount; ++r) ASSERT_EQ(sortedRows[r], r) << "rows are not 0 … N−1";
    for (Label node = part.ownedNodeCount(); node < part.nodeCount(); ++node)
        EXPECT_EQ(part.nodeRows()[node], rows[part.nodeGlobalIds()[node]]) << "ghost of global point " << part.nodeGlobalIds()[node];
}

void checkNeighbourhoods(const Whole& whole, const MeshPart& part)
{
    const CellNeighbourGraph graph = buildCellNeighbourGraph(part.nodeCount(), part.cellOffsets(), part.cellNodes());
    for (Label node = 0; node < part.ownedNodeCount(); ++node) {
        std::vector<Label> local;
        for (Label j : graph.neighboursOf(node)) local.push_back(part.nodeGlobalIds()[j]);
        std::sort(local.begin(), local.end());
        const auto expected = whole.graph.neighboursOf(part.nodeGlobalIds()[node]);
        EXPECT_EQ(local, std::vector<Label>(expected.begin(), expected.end())) << "global point " << part.nodeGlobalIds()[node];
    }
    // Own cells are exactly this rank's; each halo cell holds an owned node.
    Label ownCells = 0;
    for (int r : whole.cellRanks) ownCells += r == worldRank() ? 1 : 0;
    EXPECT_EQ(part.ownCellCount(), ownCells);
    for (Label c = part.ownCellCount(); c < part.cellCount(); ++c) {
        const auto nodes = part.nodesOf(c);
        EXPECT_TRUE(std::any_of(nodes.begin(), nodes.end(), [&](Label n) { return part.owns(n); })) << "halo cell " << c;
    }
}

void checkExchange(const MeshPart& part)
{
    const NodeExchange exchange(part);
    const Label nodes = part.nodeCount();
    // Ghost update, block size 3: owners hold f(g), ghosts NaN before.
    std::vector<double> values(3 * nodes, std::nan(""));
    for (Label n = 0; n < part.ownedNodeCount(); ++n)
        for (int c = 0; c < 3; ++c) values[3 * n + c] = 10.0 * part.nodeGlobalIds()[n] + c;
    exchange.updateGhosts(values, 3);
    for (Label n = 0; n < nodes; ++n)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(values[3 * n + c], 10.0 * part.nodeGlobalIds()[n] + c) << "node " << n;
    // Reverse addition, block size 1: every copy adds 1, so an owner ends with its copies' count.
    std::vector<int> held(part.globalNodeCount(), 0);
    for (Label g : part.nodeGlobalIds()) held[g] = 1;
    const std::vector<int> copies = sumOverRanks(held);
    std::vector<double> ones(nodes, 1.0);
    exchange.addGhostsToOwners(ones, 1);
    for (Label n = 0; n < part.ownedNodeCount(); ++n)
        EXPECT_EQ(ones[n], copies[part.nodeGlobalIds()[n]]) << "global point " << part.nodeGlobalIds()[n];
    for (Label n = part.ownedNodeCount(); n < nodes; ++n) EXPECT_EQ(ones[n], 1.0);
    EXPECT_THROW(exchange.updateGhosts(std::span<double>(values).first(3), 3), std::invalid_argument);
}

void checkDecomposition(const Decomposition& decomposition)
{
    const Whole whole(decomposition);
    const MeshPart part(PETSC_COMM_WORLD, whole.localCells(worldRank()));
    checkOwnershipAndRows(whole, part);
    checkNeighbourhoods(whole, part);
    checkExchange(part);
}

TEST(MeshPart, BlocksMatchTheWholeMesh) { checkDecomposition(blocks); }

TEST(MeshPart, ScatteredCellsMatchTheWholeMesh) { checkDecomposition(scattered); }

TEST(MeshPart, PointsSharedByFourRanksAroundAnEdgeHaveTheLowestOwner)
{
    if (worldSize() != 4) GTEST_SKIP() << "needs 4 ranks";
    const Whole whole(blocks);
    const MeshPart part(PETSC_COMM_WORLD, whole.localCells(worldRank()));
    // The vertical line x = nx/2, y = ny/2 is held by all four quadrants and owned by rank 0.
    Label sharedByFour = 0;
    for (Label node = 0; node < part.nodeCount(); ++node)
        if (whole.holders[part.nodeGlobalIds()[node]].size() == 4) {
            ++sharedByFour;
            EXPECT_EQ(part.nodeOwnerRanks()[node], 0);
        }
    EXPECT_EQ(sharedByFour, nz + 1);
}

} // namespace
