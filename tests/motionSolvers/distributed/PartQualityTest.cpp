// The whole mesh's quality figures from its processor meshes (PartQuality) against the serial
// evaluation of the undecomposed mesh (StepAssessor::evaluateStep, what rbmMoveMesh prints):
// CTest runs this program under mpiexec with 1, 2, 3 and 4 ranks. Each rank takes processor
// <rank> of a split of the whole mesh, moves its points with the whole mesh's moved points
// (through pointProcAddressing) and must report, like every other rank, the serial figures.
//
// Splits: a 6 × 5 × 4 box split in memory as decomposePar would (ProcessorMeshSplit.hpp) into
// slabs along x and into scattered cells (most internal faces between two ranks, the whole
// mesh's owner cell on the higher rank for about half of them), on any rank count; and
// decomposePar's own split of a 6 × 5 × 4 box into 4 (tests/data/decomposed), on 4 ranks (on
// 1 rank its undecomposed mesh is the part).
//
// The motions shear the cells on both sides of a plane x = const that lies between two ranks:
// turned, the worst non-orthogonality is that of a face between two ranks; slid, the worst
// skewness (both checked here, and that the ranks' own faces alone would give other figures),
// so the figures cannot match without the exchange of the cell centres across the processor
// patches. Turned with one point of the plane pushed through a cell, cells on two ranks or
// more are inverted and the count is their sum.

#include "PetscTestEnvironment.hpp"

#include "CheckMeshQuality.hpp"
#include "DecomposedBox.hpp"
#include "DecomposedCase.hpp"
#include "MeshGeometry.hpp"
#include "PartQuality.hpp"
#include "PolyMeshReader.hpp"
#include "ProcessorMeshSplit.hpp"
#include "StepAssessment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

namespace {

using namespace rbm;
using rbm::test::worldRank;
using rbm::test::worldSize;

constexpr Label nx = 6, ny = 5, nz = 4;
constexpr double boxCell = 0.2;   // DecomposedBox: [0, 1.2] × [0, 1] × [0, 0.8] in 6 × 5 × 4 cells

// Where the motions act: the plane x = x between two ranks, cells of width h across it, in a
// domain from zMin to zMax.
struct ShearPlane {
    double x, h, zMin, zMax;
};

// How close p lies to the plane x = plane.x + layer · h: 1 on it, below 3e-4 one cell off.
double nearLayer(const Vector3& p, const ShearPlane& plane, int layer)
{
    const double s = (p.x - plane.x - layer * plane.h) / (0.35 * plane.h);
    return std::exp(-s * s);
}

// Turning: the plane's points move along x by a sine of y (slope up to 0.7, period 4 h), which
// turns the faces in the plane against the line through their two cells' centres, which stays
// along x (the worst non-orthogonality: 23° on the box, 30° on decomposePar's graded one). The
// faces across the plane's edges see that line turn by about half as much.
Vector3 turningShear(const Vector3& p, const ShearPlane& plane)
{
    const double period = 4.0 * plane.h, slope = 0.7;
    const double k = 2.0 * std::numbers::pi / period;
    return nearLayer(p, plane, 0) * Vector3{slope / k * std::sin(k * p.y), 0.0, 0.0};
}

// Sliding: the plane's points move along z, up to 0.4 h midway between the z boundaries (none
// on them, which stay flat), and the points one cell beyond the plane half as far: the faces in
// the plane move off the line through their two cells' centres, which move 1/2 and 3/4 as far
// (skewness 0.30 on the box, 0.29 on decomposePar's); the faces one and two cells off the
// plane far less. Not mirror
// images across the plane, so a face's neighbour centre is not its owner centre mirrored (the
// skewness checkMesh gives a boundary face).
Vector3 slidingShear(const Vector3& p, const ShearPlane& plane)
{
    const double slide = 0.4 * plane.h * std::sin(std::numbers::pi * (p.z - plane.zMin) / (plane.zMax - plane.zMin));
    return (nearLayer(p, plane, 0) + 0.5 * nearLayer(p, plane, 1)) * Vector3{0.0, 0.0, slide};
}

using Motion = Vector3 (*)(const Vector3&, const ShearPlane&);

std::vector<Vector3> movedPoints(const PolyMesh& whole, Motion motion, const ShearPlane& plane)
{
    std::vector<Vector3> moved = whole.points;
    for (Vector3& p : moved) p = p + motion(p, plane);
    return moved;
}

// Pushes the point of the whole mesh nearest to `near` by 1.6 h along each axis: past the far
// corner of the cell beyond it, whose faces through the point turn inside out (their
// projections fold over).
void pushThroughACell(std::vector<Vector3>& moved, const PolyMesh& whole, const Vector3& near, double h)
{
    Label nearest = 0;
    for (Label p = 1; p < whole.pointCount(); ++p)
        if (norm(whole.points[p] - near) < norm(whole.points[nearest] - near)) nearest = p;
    moved[nearest] = moved[nearest] + 1.6 * h * Vector3{1.0, 1.0, 1.0};
}

Label serialInvertedCells(const PolyMesh& whole, std::span<const Vector3> points)
{
    return motion::StepAssessor(whole).evaluateStep(points).invertedCellCount;
}

std::vector<Vector3> processorPoints(const std::vector<Vector3>& wholePoints, const io::ProcessorMesh& part)
{
    std::vector<Vector3> points;
    for (Label g : part.pointProcAddressing) points.push_back(wholePoints[g]);
    return points;
}

// The faces of the whole mesh with the largest non-orthogonality and skewness, from the
// per-face measures of CheckMeshQuality.hpp.
struct WorstFaces {
    Label nonOrthogonal = -1;
    Label skew = -1;
};
WorstFaces worstFacesOf(const PolyMesh& whole, std::span<const Vector3> points)
{
    const MeshGeometry geometry = computeMeshGeometry(whole, points);
    WorstFaces worst;
    double smallestCosine = 2.0, largestSkewness = -1.0;
    for (Label f = 0; f < whole.faceCount(); ++f) {
        const Vector3& ownerCentre = geometry.cellCentres[whole.owner[f]];
        double skewness = 0.0;
        if (f < whole.internalFaceCount()) {
            const Vector3& neighbourCentre = geometry.cellCentres[whole.neighbour[f]];
            const double cosine = faceNonOrthogonalityCosine(ownerCentre, neighbourCentre, geometry.faceAreas[f]);
            if (cosine < smallestCosine) smallestCosine = cosine, worst.nonOrthogonal = f;
            skewness = faceSkewness(whole.face(f), points, geometry.faceCentres[f], geometry.faceAreas[f], ownerCentre,
                                    neighbourCentre);
        } else {
            skewness = boundaryFaceSkewness(whole.face(f), points, geometry.faceCentres[f], geometry.faceAreas[f], ownerCentre);
        }
        if (skewness > largestSkewness) largestSkewness = skewness, worst.skew = f;
    }
    return worst;
}

bool betweenTwoRanks(const PolyMesh& whole, std::span<const int> cellProcessors, Label face)
{
    return face < whole.internalFaceCount() && cellProcessors[whole.owner[face]] != cellProcessors[whole.neighbour[face]];
}

// What the ranks would report from their processor meshes alone (no exchange): each its own
// serial figures, the largest over the ranks.
StepQuality largestOfTheRanksAlone(const PolyMesh& processorMesh, std::span<const Vector3> points)
{
    QualityEvaluator alone(processorMesh);
    const StepQuality own = alone.evaluateStep(points);
    StepQuality largest;
    MPI_Allreduce(&own.maxNonOrthogonality, &largest.maxNonOrthogonality, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
    MPI_Allreduce(&own.maxSkewness, &largest.maxSkewness, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
    return largest;
}

// How many ranks hold inverted cells of the whole mesh (each its own, counted on its processor mesh).
int ranksWithInvertedCells(const PolyMesh& processorMesh, std::span<const Vector3> points)
{
    QualityEvaluator alone(processorMesh);
    const int holds = alone.evaluateStep(points).invertedCellCount > 0 ? 1 : 0;
    int ranks = 0;
    MPI_Allreduce(&holds, &ranks, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
    return ranks;
}

void expectNear(double part, double serial, const char* what)
{
    EXPECT_NEAR(part, serial, 1e-12 * std::abs(serial)) << what << " on rank " << worldRank();
}

// Which figure of a motion the faces between ranks must give.
enum class WorstBetweenRanks { NonOrthogonality, Skewness, Neither };

// Every rank's figures equal the serial evaluation of the whole mesh at `wholePoints`. With
// more than one rank, the face with the worst figure `between` lies between two ranks, and
// the ranks' own faces alone would give another figure.
void checkPartAgainstWholeMesh(const std::string& name, const PolyMesh& whole, std::span<const int> cellProcessors,
                               const io::ProcessorMesh& part, const std::vector<Vector3>& wholePoints,
                               WorstBetweenRanks between)
{
    motion::StepAssessor serialAssessor(whole);
    const StepQuality serial = serialAssessor.evaluateStep(wholePoints);
    const std::vector<Vector3> points = processorPoints(wholePoints, part);
    motion::PartQuality partQuality(part.mesh, PETSC_COMM_WORLD);
    const StepQuality reduced = partQuality.evaluateStep(points);

    expectNear(reduced.worstCellQuality, serial.worstCellQuality, "worst cell quality");
    expectNear(reduced.maxNonOrthogonality, serial.maxNonOrthogonality, "max non-orthogonality");
    expectNear(reduced.maxSkewness, serial.maxSkewness, "max skewness");
    EXPECT_EQ(reduced.invertedCellCount, serial.invertedCellCount) << "rank " << worldRank();
    // The same figures on every rank, to the bit.
    double smallest[3] = {}, largest[3] = {};
    const double mine[3] = {reduced.worstCellQuality, reduced.maxNonOrthogonality, reduced.maxSkewness};
    MPI_Allreduce(mine, smallest, 3, MPI_DOUBLE, MPI_MIN, PETSC_COMM_WORLD);
    MPI_Allreduce(mine, largest, 3, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(smallest[k], largest[k]) << "figure " << k;
    // Between steps the evaluator goes (its topology too) and the next evaluation builds it
    // again: the same figures, to the bit.
    partQuality.releaseWorkspaces();
    const StepQuality again = partQuality.evaluateStep(points);
    EXPECT_EQ(again.worstCellQuality, reduced.worstCellQuality);
    EXPECT_EQ(again.maxNonOrthogonality, reduced.maxNonOrthogonality);
    EXPECT_EQ(again.maxSkewness, reduced.maxSkewness);
    EXPECT_EQ(again.invertedCellCount, reduced.invertedCellCount);

    const StepQuality alone = largestOfTheRanksAlone(part.mesh, points);
    if (worldRank() == 0)
        std::printf("[%s, %d ranks] serial: worst quality %.15g, max non-orthogonality %.15g, max skewness %.15g, inverted %d;"
                    " parts: %.15g, %.15g, %.15g, %d; ranks alone: %.15g, %.15g\n",
                    name.c_str(), worldSize(), serial.worstCellQuality, serial.maxNonOrthogonality, serial.maxSkewness,
                    serial.invertedCellCount, reduced.worstCellQuality, reduced.maxNonOrthogonality, reduced.maxSkewness,
                    reduced.invertedCellCount, alone.maxNonOrthogonality, alone.maxSkewness);
    if (worldSize() == 1) return;
    const WorstFaces worst = worstFacesOf(whole, wholePoints);
    if (between == WorstBetweenRanks::NonOrthogonality) {
        EXPECT_TRUE(betweenTwoRanks(whole, cellProcessors, worst.nonOrthogonal)) << "face " << worst.nonOrthogonal;
        EXPECT_LT(alone.maxNonOrthogonality, serial.maxNonOrthogonality - 1.0);
    }
    if (between == WorstBetweenRanks::Skewness) {
        EXPECT_TRUE(betweenTwoRanks(whole, cellProcessors, worst.skew)) << "face " << worst.skew;
        EXPECT_GT(std::abs(alone.maxSkewness - serial.maxSkewness), 0.01 * serial.maxSkewness);
    }
}

// The part against the whole mesh turned and slid across `plane`, and turned with the point of
// the plane nearest to `pushedNear` pushed through a cell.
void checkMotions(const std::string& name, const PolyMesh& whole, std::span<const int> cellProcessors,
                  const io::ProcessorMesh& part, const ShearPlane& plane, const Vector3& pushedNear)
{
    std::vector<Vector3> moved = movedPoints(whole, turningShear, plane);
    checkPartAgainstWholeMesh(name + ", turned", whole, cellProcessors, part, moved, WorstBetweenRanks::NonOrthogonality);
    EXPECT_EQ(serialInvertedCells(whole, moved), 0);
    pushThroughACell(moved, whole, pushedNear, plane.h);
    EXPECT_GT(serialInvertedCells(whole, moved), 0);
    if (worldSize() > 1) {
        EXPECT_GE(ranksWithInvertedCells(part.mesh, processorPoints(moved, part)), 2) << name;
    }
    checkPartAgainstWholeMesh(name + ", turned, a point pushed through a cell", whole, cellProcessors, part, moved,
                              WorstBetweenRanks::Neither);
    moved = movedPoints(whole, slidingShear, plane);
    checkPartAgainstWholeMesh(name + ", slid", whole, cellProcessors, part, moved, WorstBetweenRanks::Skewness);
}

// The box split into `decomposition`'s cells per rank, moved across the plane x = planeX.
void checkBox(const std::string& name, const rbm::test::BoxDecomposition& decomposition, double planeX)
{
    const rbm::test::DecomposedBox box(nx, ny, nz, decomposition);
    const io::ProcessorMesh part = rbm::test::splitProcessorMesh(box.mesh, box.cellRanks, worldRank());
    checkMotions(name, box.mesh, box.cellRanks, part, {planeX, boxCell, 0.0, 0.8}, {planeX, 0.5, 0.4});
}

TEST(PartQuality, SlabsOfABoxGiveTheWholeMeshsFigures)
{
    // Rank r holds the cells with i · ranks / nx = r: planes between ranks at x = i · 0.2.
    const auto slabs = [](Label i, Label, Label, int ranks) { return static_cast<int>(i * ranks / nx); };
    const int ranks = worldSize();
    const Label firstPlane = ranks == 1 ? nx / 2 : (nx + ranks - 1) / ranks;   // between ranks 0 and 1
    checkBox("slabs", slabs, firstPlane * boxCell);
}

TEST(PartQuality, ScatteredCellsOfABoxGiveTheWholeMeshsFigures)
{
    // Cell (i, j, k) on rank (7i + 3j + 5k) mod ranks: every face across x = 0.6 lies between
    // two ranks, and the whole mesh's owner cell of many a face between two ranks is on the
    // higher one (whose processor face is then the whole mesh's; the lower rank's is reversed),
    // where the slabs' are all on the lower (decomposePar's: all but 6 of its 52).
    checkBox("scattered", rbm::test::scatteredDecomposition, 3 * boxCell);
    const rbm::test::DecomposedBox box(nx, ny, nz, rbm::test::scatteredDecomposition);
    Label ownedOnTheHigherRank = 0;
    for (Label f = 0; f < box.mesh.internalFaceCount(); ++f)
        ownedOnTheHigherRank += box.cellRanks[box.mesh.owner[f]] > box.cellRanks[box.mesh.neighbour[f]] ? 1 : 0;
    if (worldSize() > 1) {
        EXPECT_GT(ownedOnTheHigherRank, 50);
    }
}

// decomposePar's split (method simple, n (2 2 1)): the plane x = 0.06 (the fixture's cells are
// 0.02 wide in x) lies between processors 0 and 1 and between 2 and 3.
TEST(PartQuality, DecomposeParsProcessorFoldersGiveTheWholeMeshsFigures)
{
    if (worldSize() != 1 && worldSize() != 4) GTEST_SKIP() << "needs 4 ranks (the fixture has 4 processors) or 1";
    const std::filesystem::path fixture = std::filesystem::path(RBM_TEST_DATA_DIR) / "decomposed";
    const PolyMesh whole = io::readPolyMesh(fixture / "constant" / "polyMesh");
    std::vector<int> cellProcessors(static_cast<std::size_t>(whole.cellCount()), 0);
    io::ProcessorMesh part;
    if (worldSize() == 4) {
        for (int processor = 0; processor < 4; ++processor) {
            const auto polyMesh = fixture / ("processor" + std::to_string(processor)) / "constant" / "polyMesh";
            for (Label c : io::readLabelListFile(polyMesh / "cellProcAddressing", "cell label", cellProcessors.size()))
                cellProcessors[c] = processor;
        }
        part = io::readProcessorMesh(fixture, worldRank());
    } else {
        part.mesh = whole;
        part.pointProcAddressing.resize(whole.points.size());
        std::iota(part.pointProcAddressing.begin(), part.pointProcAddressing.end(), 0);
    }
    checkMotions("decomposePar", whole, cellProcessors, part, {0.06, 0.02, 0.0, 0.08}, {0.06, 0.05, 0.04});
}

// A split into one processor more than there are ranks: the last rank's processor patch
// towards processor `ranks` names no rank. Every rank throws (none waits in a collective call).
TEST(PartQuality, RefusesAProcessorPatchTowardsNoRank)
{
    const int ranks = worldSize();
    const auto slabs = [ranks](Label i, Label, Label, int) { return static_cast<int>(i * (ranks + 1) / nx); };
    const rbm::test::DecomposedBox box(nx, ny, nz, slabs);
    const io::ProcessorMesh part = rbm::test::splitProcessorMesh(box.mesh, box.cellRanks, worldRank());
    EXPECT_THROW(motion::PartQuality(part.mesh, PETSC_COMM_WORLD), std::invalid_argument);
}

} // namespace
