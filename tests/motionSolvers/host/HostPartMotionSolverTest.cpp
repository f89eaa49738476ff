// The host interface on one rank's part of a decomposed mesh (motionSolvers/host/
// HostPartMotionSolver.hpp) without OpenFOAM, under mpiexec with 2 and 4 ranks: each rank hands
// over its processor mesh of tests/data/decomposedTwist/np<ranks> (decomposePar's cut through
// the lid's edge, the sides and their edges) with its pointProcAddressing as the global labels,
// as the OpenFOAM plugin does with OpenFOAM's local mesh. The expectation is the whole-mesh host
// solver (HostMotionSolver, what the plugin's gathered path runs) on the undecomposed mesh with
// the same conditions: the lid turned 20° about its vertical centre line, the bottom fixed, the
// rest unconstrained (sliding in their planes).
//  - Every local point within 2.5e-6 of its shortest edge of the whole-mesh solution (each
//    solve stops within displacementTolerance 1e-6 of the same minimum, along a different
//    path), and the report's quality figures the whole mesh's.
//  - Bad coefficients on one rank only: a HostInputError on every rank naming that processor,
//    the value and the dictionary, so no rank waits in a collective call.
//  - solvesVariant: the default variant yes, the others no.
#include "HostPartMotionSolver.hpp"

#include "DecomposedCase.hpp"
#include "HostMeshes.hpp"
#include "PetscTestEnvironment.hpp"
#include "PolyMeshReader.hpp"
#include "ShortestEdges.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace rbm::motion {
namespace {

namespace fs = std::filesystem;
using rbm::test::toHostMesh;

int rankCount()
{
    int ranks = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    return ranks;
}

int myRank()
{
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    return rank;
}

fs::path fixture() { return fs::path(RBM_TEST_DATA_DIR) / "decomposedTwist" / ("np" + std::to_string(rankCount())); }

// The fixture's conditions: bottom fixed, lid prescribed, processor patches ignored, the rest
// unconstrained (sliding on their planes, which the solvers derive from the faces).
std::vector<host::HostPatchBoundary> hostBoundary(const PolyMesh& mesh)
{
    std::vector<host::HostPatchBoundary> boundary(mesh.patches.size());
    for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
        const Patch& patch = mesh.patches[p];
        if (patch.name == "bottom" || patch.name == "lid") boundary[p].nodeClass = host::HostNodeClass::prescribed;
        if (patch.type == "processor") boundary[p].nodeClass = host::HostNodeClass::ignored;
    }
    return boundary;
}

// The host's evaluation of its conditions: the lid's points turned by `angle` about the vertical
// line through (0.025, 0.04) (the fixture's angularOscillatingDisplacement), zero elsewhere.
std::vector<double> prescribedDisplacement(const PolyMesh& mesh, double angle)
{
    std::vector<double> displacement(3 * mesh.points.size(), 0.0);
    const Label lid = mesh.findPatch("lid");
    for (Label p : patchMeshPoints(mesh, lid)) {
        const double x = mesh.points[p].x - 0.025, y = mesh.points[p].y - 0.04;
        displacement[3 * p] = std::cos(angle) * x - std::sin(angle) * y - x;
        displacement[3 * p + 1] = std::sin(angle) * x + std::cos(angle) * y - y;
    }
    return displacement;
}

const double twenty = 20.0 * M_PI / 180.0;
const std::string coefficientsFile = "constant/dynamicMeshDict.rigidBodyMotionSolverCoeffs";

TEST(HostPartMotionSolver, EveryPartMovesAsTheWholeMeshSolver)
{
    ASSERT_TRUE(rankCount() == 2 || rankCount() == 4) << "the fixtures are decomposed in 2 and 4";
    const io::ProcessorMesh local = io::readProcessorMesh(fixture(), myRank());
    const std::vector<int> globalLabels(local.pointProcAddressing.begin(), local.pointProcAddressing.end());
    host::HostPartMotionSolver part(toHostMesh(local.mesh), globalLabels, "", coefficientsFile,
                                    hostBoundary(local.mesh));
    const PolyMesh whole = io::readPolyMesh(fixture() / "constant" / "polyMesh");
    EXPECT_EQ(part.pointCount(), local.mesh.points.size());
    EXPECT_EQ(part.globalPointCount(), static_cast<long long>(whole.points.size()));

    host::HostMotionSolver reference(toHostMesh(whole), "", coefficientsFile, hostBoundary(whole), "/nonexistent/case");
    std::vector<double> expected = prescribedDisplacement(whole, twenty);
    const host::HostStepReport expectedReport = reference.solve(1, 1.0, "1", expected.data(), expected.size());
    ASSERT_TRUE(expectedReport.valid) << expectedReport.problem;

    // Garbage away from the prescribed patches: solve() reads the prescribed points only.
    std::vector<double> displacement = prescribedDisplacement(local.mesh, twenty);
    std::vector<bool> prescribed(local.mesh.points.size(), false);
    for (const char* name : {"bottom", "lid"})
        for (Label p : patchMeshPoints(local.mesh, local.mesh.findPatch(name))) prescribed[p] = true;
    for (std::size_t p = 0; p < local.mesh.points.size(); ++p)
        if (!prescribed[p]) displacement[3 * p + 2] = 99.0;
    const host::HostStepReport report = part.solve(1, 1.0, "1", displacement.data(), displacement.size());
    ASSERT_TRUE(report.valid) << report.problem;
    EXPECT_EQ(report.logLine.rfind("rigidBodyMotionSolver: sub-steps  1  iterations", 0), 0u) << report.logLine;
    EXPECT_EQ(report.invertedCells, expectedReport.invertedCells);
    // The same cells and faces (those between the ranks included) at points within 1e-6 of a
    // cell apart: the figures agree far below the log line's 4 decimals.
    EXPECT_NEAR(report.worstQuality, expectedReport.worstQuality, 1e-5);
    EXPECT_NEAR(report.maxNonOrthogonality, expectedReport.maxNonOrthogonality, 1e-4);

    const std::vector<double> shortest = rbm::test::shortestEdgeAtEachPoint(whole);
    double largestMiss = 0.0, largestMove = 0.0;
    for (std::size_t k = 0; k < local.mesh.points.size(); ++k) {
        const auto g = static_cast<std::size_t>(local.pointProcAddressing[k]);
        const Vector3 got{displacement[3 * k], displacement[3 * k + 1], displacement[3 * k + 2]};
        const Vector3 want{expected[3 * g], expected[3 * g + 1], expected[3 * g + 2]};
        largestMiss = std::max(largestMiss, norm(got - want) / shortest[g]);
        largestMove = std::max(largestMove, norm(want) / shortest[g]);
    }
    EXPECT_LT(largestMiss, 2.5e-6);
    // Some rank's points moved by more than a cell (not every part reaches the lid).
    ASSERT_EQ(MPI_Allreduce(MPI_IN_PLACE, &largestMove, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD), MPI_SUCCESS);
    EXPECT_GT(largestMove, 1.0) << "the lid moved by more than a cell";
}

TEST(HostPartMotionSolver, BadCoefficientsOnOneRankAreAnErrorOnEveryRank)
{
    const io::ProcessorMesh local = io::readProcessorMesh(fixture(), myRank());
    const std::vector<int> globalLabels(local.pointProcAddressing.begin(), local.pointProcAddressing.end());
    const int last = rankCount() - 1;
    const std::string coefficients = myRank() == last ? "tolerance bogus;" : "";
    try {
        host::HostPartMotionSolver part(toHostMesh(local.mesh), globalLabels, coefficients, coefficientsFile,
                                        hostBoundary(local.mesh));
        FAIL() << "no error for tolerance bogus on processor " << last;
    } catch (const host::HostInputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("processor " + std::to_string(last) + ": "), std::string::npos) << message;
        EXPECT_NE(message.find("bogus"), std::string::npos) << message;
        EXPECT_EQ(error.file(), coefficientsFile);
    }
}

TEST(HostPartMotionSolver, SolvesTheDefaultVariantOnly)
{
    EXPECT_TRUE(host::HostPartMotionSolver::solvesVariant("", coefficientsFile));
    EXPECT_TRUE(host::HostPartMotionSolver::solvesVariant("stiffening none;", coefficientsFile));
    EXPECT_FALSE(host::HostPartMotionSolver::solvesVariant("coupling decoupled;", coefficientsFile));
    EXPECT_FALSE(host::HostPartMotionSolver::solvesVariant("formulation linearized;", coefficientsFile));
    // A part solves each step whole: sub-steps take the gathered path.
    EXPECT_FALSE(host::HostPartMotionSolver::solvesVariant("subSteps 4;", coefficientsFile));
    EXPECT_TRUE(host::HostPartMotionSolver::solvesVariant("subSteps 1;", coefficientsFile));
    EXPECT_FALSE(host::HostPartMotionSolver::solvesVariant("algorithm newton;", coefficientsFile));
    EXPECT_THROW(host::HostPartMotionSolver::solvesVariant("coupling bogus;", coefficientsFile),
                 host::HostInputError);
}

} // namespace
} // namespace rbm::motion
