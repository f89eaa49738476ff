// The coupled solves distributed over MPI ranks (BlockRowLayout) against the same solves on
// one rank: CTest runs this program under `mpiexec -n 2` (RBM_EXPECTED_RANKS=2), and every
// rank solves each case twice, serially (PETSC_COMM_SELF) and distributed
// (PETSC_COMM_WORLD). Issue 5 asks for identical results within 1e-8 of the mesh size.

#include "PetscTestEnvironment.hpp"

#include "BlockRowLayout.hpp"
#include "MeshGenerators.hpp"
#include "MoveMeshRun.hpp"
#include "PolyMeshReader.hpp"
#include "MotionSolverRegistry.hpp"
#include "PointPatchDisplacement.hpp"
#include "RbmEnergy.hpp"
#include "TestCases.hpp"
#include "RigidBodyMotionSolver.hpp"
#include "ShortestEdges.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <unistd.h>

namespace {

using namespace rbm;
using namespace rbm::motion;
using namespace rbm::app;

int worldSize()
{
    int size = 1;
    MPI_Comm_size(PETSC_COMM_WORLD, &size);
    return size;
}

// Restores the serial default whatever a test does.
struct SolverCommunicatorScope {
    explicit SolverCommunicatorScope(MPI_Comm communicator) { setSolverCommunicator(communicator); }
    ~SolverCommunicatorScope() { setSolverCommunicator(PETSC_COMM_SELF); }
};

struct Solved {
    std::vector<Vector3> points;
    MotionSolveReport report;
};

// Moves patch `moving` of `mesh` by `displacementOf` and solves with the given coefficients
// on `communicator`.
Solved solveOn(MPI_Comm communicator, const PolyMesh& mesh, const std::string& coefficients, const std::string& moving,
               const std::function<Vector3(const Vector3&)>& displacementOf)
{
    const SolverCommunicatorScope scope(communicator);
    auto solver = rbm::test::makeSolver(mesh, coefficients);
    std::vector<Vector3> values;
    for (Label p : patchMeshPoints(mesh, mesh.findPatch(moving))) values.push_back(displacementOf(mesh.points[p]));
    solver->setPatchDisplacement(moving, values);
    Solved solved;
    solved.report = solver->solve();
    solved.points = solver->curPoints();
    return solved;
}

double largestDifference(const std::vector<Vector3>& a, const std::vector<Vector3>& b)
{
    double largest = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) largest = std::max(largest, norm(a[k] - b[k]));
    return largest;
}

// The displacement of a turn by `degrees` about the z axis through `centre`, in the x-y plane.
std::function<Vector3(const Vector3&)> inPlaneTurn(double degrees, Vector3 centre)
{
    const Matrix3 turn = planarRotation(degrees * M_PI / 180.0);
    return [turn, centre](const Vector3& x) {
        Vector3 relative = x - centre;
        relative.z = 0.0;
        Vector3 moved = turn * relative - relative;
        moved.z = 0.0;
        return moved;
    };
}

void expectSameOnAllRanks(const PolyMesh& mesh, const std::string& moving,
                          const std::function<Vector3(const Vector3&)>& displacementOf, double cellSize,
                          const std::vector<std::string>& variants)
{
    for (const std::string& coefficients : variants) {
        const Solved serial = solveOn(PETSC_COMM_SELF, mesh, coefficients, moving, displacementOf);
        const Solved distributed = solveOn(PETSC_COMM_WORLD, mesh, coefficients, moving, displacementOf);
        ASSERT_TRUE(serial.report.converged) << coefficients << ": " << serial.report.reason;
        ASSERT_TRUE(distributed.report.converged) << coefficients << ": " << distributed.report.reason;
        EXPECT_EQ(distributed.report.invertedCellCount, serial.report.invertedCellCount) << coefficients;
        // The motion is not trivial, and the two runs agree to 1e-8 of a cell.
        EXPECT_GT(largestDifference(serial.points, mesh.points), 0.1 * cellSize) << coefficients;
        EXPECT_LT(largestDifference(serial.points, distributed.points), 1e-8 * cellSize) << coefficients;
    }
}

TEST(ParallelSolve, RunsOnTheExpectedNumberOfRanks)
{
    const char* expected = std::getenv("RBM_EXPECTED_RANKS");
    if (!expected) GTEST_SKIP() << "run by CTest under mpiexec with RBM_EXPECTED_RANKS set";
    EXPECT_EQ(worldSize(), std::atoi(expected));
}

TEST(ParallelSolve, LayoutSplitsTheRowsOverTheRanksAndGathersThemBack)
{
    // A 1D chain of 40 rows: every rank owns some, all rows are owned exactly once.
    std::vector<int> offsets{0}, columns;
    const int rows = 40;
    for (int row = 0; row < rows; ++row) {
        for (int column = std::max(0, row - 1); column <= std::min(rows - 1, row + 1); ++column) columns.push_back(column);
        offsets.push_back(static_cast<int>(columns.size()));
    }
    const BlockRowLayout layout(PETSC_COMM_WORLD, offsets, columns);
    EXPECT_EQ(layout.isDistributed(), worldSize() > 1);
    EXPECT_GT(layout.ownedRowCount(), 0);
    int total = layout.ownedRowCount();
    MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
    EXPECT_EQ(total, rows);
    for (int row : layout.ownedRows()) {
        EXPECT_GE(layout.petscRow(row), layout.ownedBegin());
        EXPECT_LT(layout.petscRow(row), layout.ownedEnd());
    }
    // scatter then gather is the identity on the whole array (block size 2).
    std::vector<double> natural(2 * rows), back(2 * rows, -1.0);
    for (int k = 0; k < 2 * rows; ++k) natural[k] = 0.5 * k + 1.0;
    PetscVec vector = layout.createVector(2);
    layout.scatter(natural, vector, 2);
    layout.gather(vector, back, 2);
    EXPECT_EQ(back, natural);
}

TEST(ParallelSolve, TwoDimensionalAirfoilLikeTurnMatchesTheSerialSolve)
{
    // Pseudo-3D quads, the bottom edge turned 8° about its middle, the rest held.
    const PolyMesh mesh = makeExtruded2D(24, 16, {0, 0, 0}, {2.4, 1.6, 0.1});
    expectSameOnAllRanks(mesh, "bottom", inPlaneTurn(8.0, {1.2, 0.0, 0.0}), 0.1,
                         {"subSteps 1;", "formulation linearized; subSteps 1;", "algorithm localGlobal; subSteps 1;",
                          "coupling decoupled; subSteps 1;", ""});
}

TEST(ParallelSolve, ThreeDimensionalTwistWithSlidingSidesMatchesTheSerialSolve)
{
    // Hex box, top turned 20° about the vertical axis, bottom fixed, x sides sliding (symmetryPlane).
    const PolyMesh mesh = makeHexBox(6, 6, 6, {0, 0, 0}, {1, 1, 1},
                                     {BoxPatch{"xMin", "symmetryPlane"}, BoxPatch{"xMax", "symmetryPlane"},
                                      BoxPatch{"front"}, BoxPatch{"back"}, BoxPatch{"bottom"}, BoxPatch{"top"}});
    const Matrix3 turn = rotationFromVector({0.0, 0.0, 20.0 * M_PI / 180.0});
    const Vector3 centre{0.5, 0.5, 1.0};
    auto displacementOf = [&](const Vector3& x) { return turn * (x - centre) - (x - centre); };
    expectSameOnAllRanks(mesh, "top", displacementOf, 1.0 / 6.0,
                         {"subSteps 1;", "formulation linearized; subSteps 1;", "coupling decoupled; subSteps 1;",
                          "linearSolver iterative; subSteps 1;"});
}

TEST(ParallelSolve, IterativeLaplacianOnTheBoundaryLayerAirfoilReachesTheSerialFactorisedStep)
{
    // Issue 12 ("no trap in the options"): the default reduced Newton in 2D with `linearSolver
    // iterative` on several ranks, where rbm's own multigrid cycle (one rank's) is not there
    // and PETSc's CG solves K. With GAMG that CG did not converge on a boundary-layer mesh (the
    // benchmark's airfoil: DIVERGED_LINEAR_SOLVE, exit 1); BoomerAMG is the default there now.
    // The NACA4415 fixture with a hex boundary layer (aspect ratio ~780), the airfoil turned 4°
    // about its trailing edge: the distributed step must end where the serial factorised one
    // ends, within the displacement tolerance's bound of each point's shortest edge.
    if (worldSize() == 1) GTEST_SKIP() << "needs mpiexec -n 2";
    const PolyMesh mesh =
        io::readPolyMesh(std::filesystem::path(RBM_TEST_DATA_DIR) / "airfoilBoundaryLayer" / "constant" / "polyMesh");
    const auto displacementOf = inPlaneTurn(4.0, {1.0, 0.0, 0.0});  // about the trailing edge
    const Solved serial = solveOn(PETSC_COMM_SELF, mesh, "subSteps 1;", "airfoil", displacementOf);
    const Solved distributed =
        solveOn(PETSC_COMM_WORLD, mesh, "subSteps 1; linearSolver iterative;", "airfoil", displacementOf);
    ASSERT_TRUE(serial.report.converged) << serial.report.reason;
    ASSERT_TRUE(distributed.report.converged) << distributed.report.reason;
    EXPECT_EQ(distributed.report.invertedCellCount, 0);
    const std::vector<double> shortestEdge = rbm::test::shortestEdgeAtEachPoint(mesh);
    double largestRelative = 0.0;
    for (std::size_t i = 0; i < serial.points.size(); ++i)
        largestRelative = std::max(largestRelative, norm(serial.points[i] - distributed.points[i]) / shortestEdge[i]);
    // As the one-rank iterative K (RigidBodyMotionSolverTimeSteps.IterativeLaplacian…): the
    // two stops lie within a few times displacementTolerance (1e-6) of each shortest edge.
    EXPECT_LT(largestRelative, 50e-6);
    EXPECT_GT(largestDifference(serial.points, mesh.points), 0.01);  // the turn moved the mesh
}

// The program end to end: `mpiexec -n 2 rbmMoveMesh -case C -parallel` (moveMeshMain on
// every rank) against a serial run of the same case, three steps of the pitching airfoil
// (13 575 nodes per plane; warm-started Newton). Rank 0 alone writes.
TEST(ParallelMoveMesh, PitchingAirfoilStepsMatchTheSerialRunAndOnlyRankZeroWrites)
{
    namespace fs = std::filesystem;
    int rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    // One scratch folder for all ranks: rank 0 names it.
    std::string root = (fs::temp_directory_path() / ("rbmParallelMoveMesh-" + std::to_string(getpid()))).string();
    {
        int length = static_cast<int>(root.size());
        MPI_Bcast(&length, 1, MPI_INT, 0, PETSC_COMM_WORLD);
        root.resize(static_cast<std::size_t>(length));
        MPI_Bcast(root.data(), length, MPI_CHAR, 0, PETSC_COMM_WORLD);
    }
    const fs::path serialCase = fs::path(root) / "serial";
    const fs::path parallelCase = fs::path(root) / "parallel";
    if (rank == 0) {
        for (const fs::path& target : {serialCase, parallelCase}) {
            // The case's inputs only: a run of the tutorial in place leaves time folders there.
            const fs::path tutorial = fs::path(RBM_TEST_DATA_DIR) / "../../tutorials/naca4415Pitching";
            for (const char* part : {"0", "constant", "system"}) {
                fs::create_directories(target / part);
                fs::copy(tutorial / part, target / part, fs::copy_options::recursive);
            }
            const fs::path controlDict = target / "system" / "controlDict";
            std::stringstream text;
            text << std::ifstream(controlDict).rdbuf();
            std::string edited = std::regex_replace(text.str(), std::regex("endTime +2;"), "endTime 0.075;");
            edited = std::regex_replace(edited, std::regex("writeInterval +10;"), "writeInterval 1;");
            std::ofstream(controlDict) << edited;
            // Both runs to round-off (displacementTolerance 0): one rank starts from the turned
            // harmonic interpolation (rbm's own factorisation of K), two ranks from the plain
            // one, and with the default tolerance each would stop at its own point within it.
            const fs::path dynamicMeshDict = target / "constant" / "dynamicMeshDict";
            std::stringstream dictionary;
            dictionary << std::ifstream(dynamicMeshDict).rdbuf();
            std::ofstream(dynamicMeshDict) << std::regex_replace(dictionary.str(), std::regex("subSteps +auto;"),
                                                                 "subSteps auto; displacementTolerance 0;");
        }
        std::ostringstream out, err;
        MoveMeshOptions options;
        options.caseDirectory = serialCase;
        options.writeVtk = false;
        ASSERT_EQ(runMoveMesh(options, out, err), exitSuccess) << err.str();
    }
    MPI_Barrier(PETSC_COMM_WORLD);

    const std::string caseArgument = parallelCase.string();
    std::vector<std::string> arguments{"rbmMoveMesh", "-case", caseArgument, "-noVTK", "-parallel"};
    std::vector<char*> argv;
    for (std::string& argument : arguments) argv.push_back(argument.data());
    argv.push_back(nullptr);
    std::ostringstream out, err;
    const int status = moveMeshMain(static_cast<int>(arguments.size()), argv.data(), out, err);
    EXPECT_EQ(status, exitSuccess) << err.str();
    if (rank != 0) {
        EXPECT_TRUE(out.str().empty()) << "only rank 0 prints";
    }
    MPI_Barrier(PETSC_COMM_WORLD);

    if (rank == 0) {
        EXPECT_NE(out.str().find("Time = 0.075"), std::string::npos) << out.str();
        for (const std::string time : {"0.025", "0.05", "0.075"}) {
            const std::vector<Vector3> serial = io::readPolyMeshPoints(serialCase / time / "polyMesh" / "points.gz");
            const std::vector<Vector3> parallel = io::readPolyMeshPoints(parallelCase / time / "polyMesh" / "points.gz");
            const std::vector<Vector3> initial = io::readPolyMeshPoints(serialCase / "constant" / "polyMesh" / "points.gz");
            ASSERT_EQ(serial.size(), parallel.size());
            // Both converged from different starts, each within displacementTolerance (1e-6 of
            // a node's shortest edge, ~1e-3 here) of the minimum, so they may differ by twice
            // that: measured 1.4e-10 with rigid neighbourhoods and 1.24e-9 with the 2D
            // default's scaling (the stiffened far field, where the weighted gradient hardly
            // sees a node).
            EXPECT_LT(largestDifference(serial, parallel), 2e-9) << time;
            EXPECT_GT(largestDifference(serial, initial), 1e-3) << time;
        }
        // No stray output from the other rank: exactly the serial run's time folders.
        std::vector<std::string> serialEntries, parallelEntries;
        for (const auto& entry : fs::directory_iterator(serialCase)) serialEntries.push_back(entry.path().filename());
        for (const auto& entry : fs::directory_iterator(parallelCase)) parallelEntries.push_back(entry.path().filename());
        std::sort(serialEntries.begin(), serialEntries.end());
        std::sort(parallelEntries.begin(), parallelEntries.end());
        EXPECT_EQ(serialEntries, parallelEntries);
        fs::remove_all(root);
    }
}

TEST(ParallelMoveMesh, SeveralRanksWithoutParallelIsABadCommandLine)
{
    if (worldSize() == 1) GTEST_SKIP() << "needs mpiexec -n 2";
    std::vector<std::string> arguments{"rbmMoveMesh", "-case", "/nonexistent"};
    std::vector<char*> argv;
    for (std::string& argument : arguments) argv.push_back(argument.data());
    argv.push_back(nullptr);
    std::ostringstream out, err;
    EXPECT_EQ(moveMeshMain(static_cast<int>(arguments.size()), argv.data(), out, err), exitBadInput);
}

} // namespace
