// Tests of UnconstrainedPatches: a patch whose condition neither prescribes nor slides its
// points (zeroGradient) keeps its surface by default, floats when listed in floatingPatches,
// and a floating planar patch that leaves its plane is reported.
#include "PetscTestEnvironment.hpp"
#include "InputError.hpp"
#include "MeshGenerators.hpp"
#include "MotionSolverRegistry.hpp"
#include "TestCases.hpp"
#include "RigidBodyMotionSolver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace {

using namespace rbm;
using namespace rbm::motion;

// A 4 × 3 × 3 box: xMin moves by (0.4, 0.3, 0.2) as a rigid wall, xMax is fixed, the other
// four sides are zeroGradient. Left free, those sides bulge with the moving wall.
const char* const boxConditions = R"(
    boundaryField
    {
        xMin { type fixedValue; value uniform (0.4 0.3 0.2); }
        xMax { type fixedValue; value uniform (0 0 0); }
        ".*" { type zeroGradient; }
    })";

std::unique_ptr<MotionSolver> boxSolver(const PolyMesh& mesh, const std::string& coefficients)
{
    const io::Dictionary field = io::Dictionary::parseText(boxConditions, "0/pointDisplacement");
    return rbm::test::makeSolver(mesh, coefficients, &field);
}

// Largest distance of the patch's points (those on no prescribed patch) from its initial plane
// `coordinate` = `value`.
double largestOffPlane(const PolyMesh& mesh, const std::vector<Vector3>& points, const std::string& patch,
                       int coordinate, double value)
{
    double largest = 0.0;
    for (Label p : patchMeshPoints(mesh, mesh.findPatch(patch))) {
        const Vector3& x0 = mesh.points[p];
        if (x0.x == 0.0 || x0.x == 4.0) continue;   // on xMin or xMax: prescribed
        const double moved = coordinate == 1 ? points[p].y : points[p].z;
        largest = std::max(largest, std::abs(moved - value));
    }
    return largest;
}

TEST(UnconstrainedPatches, ByDefaultAZeroGradientWallKeepsItsPlaneAndItsPointsSlideOnIt)
{
    const PolyMesh mesh = makeHexBox(4, 3, 3, {0, 0, 0}, {4, 3, 3});
    auto solver = boxSolver(mesh, "");
    const MotionSolveReport report = solver->solve();
    ASSERT_TRUE(report.converged) << report.reason;
    EXPECT_EQ(report.invertedCellCount, 0);
    EXPECT_TRUE(report.warnings.empty());
    const std::vector<Vector3> points = solver->curPoints();
    EXPECT_LT(largestOffPlane(mesh, points, "yMin", 1, 0.0), 1e-12);
    EXPECT_LT(largestOffPlane(mesh, points, "yMax", 1, 3.0), 1e-12);
    EXPECT_LT(largestOffPlane(mesh, points, "zMin", 2, 0.0), 1e-12);
    EXPECT_LT(largestOffPlane(mesh, points, "zMax", 2, 3.0), 1e-12);
    // They slide: a point in the middle of yMin follows the wall along x.
    const Label p = [&] {
        for (Label q = 0; q < mesh.pointCount(); ++q)
            if (mesh.points[q] == Vector3{1, 0, 1}) return q;
        return Label{-1};
    }();
    ASSERT_GE(p, 0);
    EXPECT_GT(points[p].x - 1.0, 0.05);
    // Where two such walls meet, the point stays on both: the edge line y = 0, z = 0.
    for (Label q = 0; q < mesh.pointCount(); ++q) {
        const Vector3& x0 = mesh.points[q];
        if (x0.y != 0.0 || x0.z != 0.0 || x0.x == 0.0 || x0.x == 4.0) continue;
        EXPECT_LT(std::abs(points[q].y) + std::abs(points[q].z), 1e-12) << q;
    }
}

TEST(UnconstrainedPatches, AFloatingPatchMovesLikeTheInteriorAndLeavingItsPlaneIsReported)
{
    const PolyMesh mesh = makeHexBox(4, 3, 3, {0, 0, 0}, {4, 3, 3});
    auto solver = boxSolver(mesh, "floatingPatches (yMax \"z.*\");");
    const MotionSolveReport report = solver->solve();
    ASSERT_TRUE(report.converged) << report.reason;
    const std::vector<Vector3> points = solver->curPoints();
    EXPECT_GT(largestOffPlane(mesh, points, "yMax", 1, 3.0), 0.01);
    EXPECT_GT(largestOffPlane(mesh, points, "zMax", 2, 3.0), 0.01);
    EXPECT_LT(largestOffPlane(mesh, points, "yMin", 1, 0.0), 1e-12);   // not listed: kept
    // One warning per floating patch that left its plane, naming it.
    ASSERT_EQ(report.warnings.size(), 3u);
    std::string all;
    for (const std::string& warning : report.warnings) all += warning + "\n";
    for (const char* name : {"patch yMax ", "patch zMin ", "patch zMax "})
        EXPECT_NE(all.find(name), std::string::npos) << all;
    EXPECT_NE(all.find("leave its plane by up to"), std::string::npos) << all;
}

TEST(UnconstrainedPatches, AFloatingPatchNameThatMatchesNoPatchIsAnInputErrorListingThePatches)
{
    const PolyMesh mesh = makeHexBox(2, 2, 2, {0, 0, 0}, {1, 1, 1});
    try {
        boxSolver(mesh, "floatingPatches (outlet);");
        FAIL() << "no InputError";
    } catch (const InputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("floatingPatches: no patch matches outlet"), std::string::npos) << message;
        EXPECT_NE(message.find("Valid patches are: xMin"), std::string::npos) << message;
        EXPECT_EQ(error.line(), 4) << message;
    }
}

} // namespace
