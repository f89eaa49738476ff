// The host interface (motionSolvers/host/HostMotionSolver.hpp) without OpenFOAM: a host that
// evaluates its own boundary conditions and describes the boundary must get exactly what
// rbmMoveMesh's front door gets from the same conditions written in a pointDisplacement
// dictionary (rbm's own boundary conditions, checked against OpenFOAM in BoundaryMotionTest).
// The OpenFOAM plugin's tests (OpenFOAMPluginTest.cmake) check the same through OpenFOAM.
#include "HostMotionSolver.hpp"

#include "FoamDictionary.hpp"
#include "HostMeshes.hpp"
#include "MeshGenerators.hpp"
#include "MotionSolverRegistry.hpp"
#include "PetscTestEnvironment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace rbm::motion {
namespace {

using rbm::test::toHostMesh;

// Box [0,4]×[0,3]×[0,2]: xMin moves by (0.3, 0.1, 0) (prescribed), xMax fixed, yMin a slip wall
// (normal -y), zMin a symmetry plane (normal -z, mirror), yMax and zMax free.
constexpr double shift[3] = {0.3, 0.1, 0.0};

std::vector<host::HostPatchBoundary> hostBoundary(const PolyMesh& mesh)
{
    std::vector<host::HostPatchBoundary> boundary(mesh.patches.size());
    for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
        const std::string& name = mesh.patches[p].name;
        const std::size_t points = patchMeshPoints(mesh, static_cast<Label>(p)).size();
        host::HostPatchBoundary& b = boundary[p];
        if (name == "xMin" || name == "xMax") {
            b.nodeClass = host::HostNodeClass::prescribed;
        } else if (name == "yMin" || name == "zMin") {
            b.nodeClass = host::HostNodeClass::sliding;
            b.mirror = name == "zMin";
            for (std::size_t k = 0; k < points; ++k)
                b.slidingNormals.insert(b.slidingNormals.end(), name == "yMin" ? std::initializer_list<double>{0, -1, 0}
                                                                                : std::initializer_list<double>{0, 0, -1});
        }
    }
    return boundary;
}

const char* const pointDisplacementText = R"(
boundaryField
{
    xMin { type fixedValue; value uniform (0.3 0.1 0); }
    xMax { type fixedValue; value uniform (0 0 0); }
    yMin { type slip; }
    zMin { type symmetryPlane; }
    yMax { type zeroGradient; }
    zMax { type zeroGradient; }
}
)";

TEST(HostMotionSolver, EqualsTheDictionaryDrivenSolverOnTheSameConditions)
{
    // zMin a symmetryPlane patch in the mesh too, as OpenFOAM's mesh would have it (the
    // default stiffening leaves symmetry patches out, so both paths must see the same type).
    PolyMesh mesh = makeHexBox(8, 6, 4, {0, 0, 0}, {4, 3, 2});
    mesh.patches[static_cast<std::size_t>(mesh.findPatch("zMin"))].type = "symmetryPlane";
    const std::string coefficients = "coupling coupled; formulation nonlinear;";
    host::HostMotionSolver hostSolver(toHostMesh(mesh), coefficients, "dynamicMeshDict.rigidBodyMotionSolverCoeffs",
                                      hostBoundary(mesh), "/nonexistent/case");
    ASSERT_EQ(hostSolver.pointCount(), mesh.points.size());
    EXPECT_EQ(hostSolver.dimension(), 3);

    // The host's evaluation of its conditions: xMin's points move, every other value is
    // garbage that solve() must overwrite (only prescribed points are read).
    std::vector<double> displacement(3 * mesh.points.size(), 99.0);
    const Label xMin = mesh.findPatch("xMin");
    const Label xMax = mesh.findPatch("xMax");
    std::vector<bool> onXMin(mesh.points.size(), false);
    for (Label p : patchMeshPoints(mesh, xMin)) onXMin[p] = true;
    for (Label p : patchMeshPoints(mesh, xMax))
        for (int c = 0; c < 3; ++c) displacement[3 * p + c] = 0.0;
    for (Label p : patchMeshPoints(mesh, xMin))
        for (int c = 0; c < 3; ++c) displacement[3 * p + c] = shift[c];
    const host::HostStepReport report = hostSolver.solve(1, 0.5, "0.5", displacement.data(), displacement.size());
    ASSERT_TRUE(report.valid) << report.problem;
    EXPECT_TRUE(report.converged);
    EXPECT_EQ(report.invertedCells, 0);
    // Inside OpenFOAM, which prints "Time = 0.5" itself: one line that log parsers (foamLog)
    // do not count as a second time step.
    EXPECT_EQ(report.logLine.rfind("rigidBodyMotionSolver: sub-steps  1  iterations", 0), 0u) << report.logLine;
    EXPECT_EQ(report.logLine.find("Time ="), std::string::npos) << report.logLine;
    EXPECT_NE(report.logLine.find("inverted 0"), std::string::npos) << report.logLine;

    // The reference: rbmMoveMesh's path, rbm's own conditions from a pointDisplacement
    // dictionary; zMin a symmetryPlane patch (a mirror, as the host described it).
    const PolyMesh& mirrored = mesh;
    const io::Dictionary field = io::Dictionary::parseText(pointDisplacementText, "pointDisplacement");
    const io::Dictionary dict = io::Dictionary::parseText(
        "motionSolver rigidBodyMotionSolver; rigidBodyMotionSolverCoeffs { " + coefficients + " }", "dynamicMeshDict");
    const auto reference = builtinMotionSolvers().create(mirrored, dict, &field, "/nonexistent/case");
    reference->updateBoundaryConditions(0.5);
    const MotionSolveReport expected = reference->solve();
    ASSERT_TRUE(expected.converged);

    double largest = 0.0;
    double moved = 0.0;
    for (std::size_t p = 0; p < mesh.points.size(); ++p) {
        const Vector3& u = reference->pointDisplacement()[p];
        const Vector3 got{displacement[3 * p], displacement[3 * p + 1], displacement[3 * p + 2]};
        largest = std::max(largest, norm(got - u));
        if (!onXMin[p]) moved = std::max(moved, norm(got));
    }
    EXPECT_LT(largest, 1e-10);
    EXPECT_GT(moved, 0.05);  // the interior moved: the comparison is not of two zero fields
    EXPECT_EQ(report.iterations, expected.iterations);
}

TEST(HostMotionSolver, BadCoefficientIsAHostInputErrorNamingTheEntry)
{
    const PolyMesh mesh = makeHexBox(2, 2, 2, {0, 0, 0}, {1, 1, 1});
    try {
        host::HostMotionSolver solver(toHostMesh(mesh), "coupling bogus;", "constant/dynamicMeshDict.coeffs",
                                      hostBoundary(mesh), "/nonexistent/case");
        FAIL() << "no error for coupling bogus";
    } catch (const host::HostInputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("coupling"), std::string::npos) << message;
        EXPECT_NE(message.find("bogus"), std::string::npos) << message;
        EXPECT_EQ(error.file(), "constant/dynamicMeshDict.coeffs");
    }
}

TEST(HostMotionSolver, WrongBoundaryShapesAreRejected)
{
    const PolyMesh mesh = makeHexBox(2, 2, 2, {0, 0, 0}, {1, 1, 1});
    std::vector<host::HostPatchBoundary> boundary = hostBoundary(mesh);
    boundary.pop_back();
    EXPECT_THROW(host::HostMotionSolver(toHostMesh(mesh), "", "coeffs", boundary, "/nonexistent/case"),
                 std::invalid_argument);
    boundary = hostBoundary(mesh);
    boundary[static_cast<std::size_t>(mesh.findPatch("yMin"))].slidingNormals.pop_back();
    EXPECT_THROW(host::HostMotionSolver(toHostMesh(mesh), "", "coeffs", boundary, "/nonexistent/case"),
                 std::invalid_argument);

    host::HostMotionSolver solver(toHostMesh(mesh), "", "coeffs", hostBoundary(mesh), "/nonexistent/case");
    std::vector<double> tooShort(3 * mesh.points.size() - 1, 0.0);
    EXPECT_THROW(solver.solve(1, 1.0, "1", tooShort.data(), tooShort.size()), std::invalid_argument);
}

} // namespace
} // namespace rbm::motion
