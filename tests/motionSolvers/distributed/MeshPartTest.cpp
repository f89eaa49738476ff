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

#include "DecomposedBox.hpp"
#include "DecomposedCase.hpp"
#include "PolyMeshReader.hpp"
#include "MeshPart.hpp"
#include "NodeExchange.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <vector>

namespace {

using namespace rbm;
using namespace rbm::motion;
using rbm::test::DecomposedBox;
using rbm::test::worldRank;
using rbm::test::worldSize;
using Whole = DecomposedBox;

constexpr Label nx = 6, ny = 5, nz = 4;

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

void checkDecomposition(const rbm::test::BoxDecomposition& decomposition)
{
    const Whole whole(nx, ny, nz, decomposition);
    const MeshPart part(PETSC_COMM_WORLD, whole.localCells(worldRank()));
    checkOwnershipAndRows(whole, part);
    checkNeighbourhoods(whole, part);
    checkExchange(part);
}

TEST(MeshPart, BlocksMatchTheWholeMesh) { checkDecomposition(rbm::test::blockDecomposition(nx, ny)); }

TEST(MeshPart, ScatteredCellsMatchTheWholeMesh) { checkDecomposition(rbm::test::scatteredDecomposition); }

TEST(MeshPart, PointsSharedByFourRanksAroundAnEdgeHaveTheLowestOwner)
{
    if (worldSize() != 4) GTEST_SKIP() << "needs 4 ranks";
    const Whole whole(nx, ny, nz, rbm::test::blockDecomposition(nx, ny));
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

// decomposePar's own split of a 6 × 5 × 4 box into 4 (tests/data/decomposed): each rank reads
// its processor folder (its processor patches and pointProcAddressing, localCellsOf), and the
// parts match the undecomposed mesh as above. Processors 0 and 3 share only the middle edge.
TEST(MeshPart, DecomposeParsProcessorFoldersMatchTheWholeMesh)
{
    if (worldSize() != 4) GTEST_SKIP() << "needs 4 ranks (the fixture has 4 processors)";
    const std::filesystem::path fixture = std::filesystem::path(RBM_TEST_DATA_DIR) / "decomposed";
    const PolyMesh whole = io::readPolyMesh(fixture / "constant" / "polyMesh");
    const CellNeighbourGraph wholeGraph = buildCellNeighbourGraph(whole);
    const io::ProcessorMesh processor = io::readProcessorMesh(fixture, worldRank());
    MeshPart part(PETSC_COMM_WORLD, localCellsOf(processor.mesh, processor.pointProcAddressing));
    EXPECT_EQ(part.globalNodeCount(), whole.pointCount());
    const CellNeighbourGraph graph = buildCellNeighbourGraph(part.nodeCount(), part.cellOffsets(), part.cellNodes());
    // Once the graph is built the cells' node lists may go (the part's solver lets them go); the count stays.
    const Label cells = part.cellCount();
    part.releaseCells();
    EXPECT_EQ(part.cellCount(), cells);
    EXPECT_TRUE(part.cellNodes().empty());
    EXPECT_EQ(part.cellOffsets(), std::vector<Label>{0});
    std::vector<int> owned(whole.pointCount(), 0);
    for (Label node = 0; node < part.ownedNodeCount(); ++node) {
        const Label g = part.nodeGlobalIds()[node];
        owned[g] = 1;
        EXPECT_EQ(part.nodePoints()[node], whole.points[g]);
        std::vector<Label> local;
        for (Label j : graph.neighboursOf(node)) local.push_back(part.nodeGlobalIds()[j]);
        std::sort(local.begin(), local.end());
        const auto expected = wholeGraph.neighboursOf(g);
        EXPECT_EQ(local, std::vector<Label>(expected.begin(), expected.end())) << "global point " << g;
    }
    const std::vector<int> owners = sumOverRanks(owned);
    EXPECT_TRUE(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; })) << "a point owned twice or never";
}

} // namespace
