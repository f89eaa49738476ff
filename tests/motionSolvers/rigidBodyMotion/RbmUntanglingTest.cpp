// Tests of line nodes in the OpenFOAM-facing solver and of the untangling stage (issue 13.3):
// the slip box whose top turns while its four sides slip, a prescribed boundary that itself
// inverts a cell, and the stage's guarantees (prescribed points bit-for-bit, sliding points on
// their planes and lines, valid meshes untouched).

#include "PetscTestEnvironment.hpp"

#include "MeshGenerators.hpp"
#include "MotionSolverRegistry.hpp"
#include "PointPatchDisplacement.hpp"
#include "RbmEnergy.hpp"
#include "TestCases.hpp"
#include "RigidBodyMotionSolver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <tuple>

namespace {

using namespace rbm;
using namespace rbm::motion;

double degrees(double angle) { return angle * std::numbers::pi / 180.0; }

// The slip box (issue 13.3): n³ hexahedra in [0, 1]³, the bottom fixed, the four sides `slip`,
// the top turned by `angle` about the vertical axis through its centre.
PolyMesh slipBoxMesh(Label n, Label nz = 0, double height = 1.0)
{
    return makeHexBox(n, n, nz > 0 ? nz : n, {0, 0, 0}, {1, 1, height},
                      {BoxPatch{"xMin"}, BoxPatch{"xMax"}, BoxPatch{"yMin"}, BoxPatch{"yMax"}, BoxPatch{"bottom"},
                       BoxPatch{"top"}});
}

std::unique_ptr<MotionSolver> slipBoxSolver(const PolyMesh& mesh, double angle, const std::string& coefficients)
{
    const io::Dictionary field = io::Dictionary::parseText(R"field(
        boundaryField
        {
            "(xMin|xMax|yMin|yMax)" { type slip; }
            bottom { type fixedValue; value uniform (0 0 0); }
            top { type fixedValue; value uniform (0 0 0); }
        })field", "0/pointDisplacement");
    std::unique_ptr<MotionSolver> solver = rbm::test::makeSolver(mesh, coefficients, &field);
    const Label top = mesh.findPatch("top");
    const std::vector<Label> points = patchMeshPoints(mesh, top);
    const Matrix3 rotation = rotationFromVector({0.0, 0.0, angle});
    const Vector3 centre{0.5, 0.5, mesh.points[points.front()].z};
    std::vector<Vector3> displacement;
    for (Label p : points) displacement.push_back(rotation * (mesh.points[p] - centre) + centre - mesh.points[p]);
    solver->setPatchDisplacement("top", displacement);
    return solver;
}

// The points of a patch, by name.
std::vector<Label> pointsOf(const PolyMesh& mesh, const std::string& patch)
{
    return patchMeshPoints(mesh, mesh.findPatch(patch));
}

// A flat slip box (10 × 10 × 4 cells, height 0.2) whose top turns 45°, moved by decoupled RBM
// in one step: the solve leaves 4 inverted cells at the vertical edges one layer below the
// top (where the line nodes meet the prescribed top corners that have left both planes).
TEST(SlipBox, DefaultEndsWithoutInvertedCellsAndUntangleOffDoesNot)
{
    const PolyMesh mesh = slipBoxMesh(10, 4, 0.2);
    const std::string variant = "coupling decoupled; maxSubStepSplits 0; ";
    auto plain = slipBoxSolver(mesh, degrees(45.0), variant + "untangle off;");
    auto untangled = slipBoxSolver(mesh, degrees(45.0), variant);
    const MotionSolveReport before = plain->solve();
    const MotionSolveReport after = untangled->solve();
    std::printf("slip box 10x10x4: untangle off %d inverted (worst %.4f); on %d inverted, %d untangled (worst %.4f, "
                "%.3f s vs %.3f s): %s\n",
                before.invertedCellCount, before.worstQuality, after.invertedCellCount, after.untangledCellCount,
                after.worstQuality, after.wallSeconds, before.wallSeconds, after.reason.c_str());
    EXPECT_EQ(before.invertedCellCount, 4);
    EXPECT_EQ(before.untangledCellCount, 0);
    EXPECT_EQ(after.invertedCellCount, 0);
    EXPECT_EQ(after.untangledCellCount, 4);
    EXPECT_NE(after.reason.find("; untangled 4 inverted cells"), std::string::npos) << after.reason;
    EXPECT_GT(after.worstQuality, 0.0);

    const std::vector<Vector3> moved = untangled->curPoints();
    const std::vector<Vector3> reference = plain->curPoints();
    // Prescribed points (top and bottom) are those of the plain solve, bit for bit.
    for (const char* patch : {"top", "bottom"})
        for (Label p : pointsOf(mesh, patch)) EXPECT_EQ(moved[p], reference[p]) << patch << " point " << p;
    // Sliding points stay on their planes, line points on both (to 1e-12), and some moved.
    double largestMove = 0.0;
    for (Label p = 0; p < mesh.pointCount(); ++p) {
        const Vector3& x = mesh.points[p];
        if (x.z == 0.0 || x.z == 0.2) continue;
        for (int axis = 0; axis < 2; ++axis)
            if (x[axis] == 0.0 || x[axis] == 1.0) {
                EXPECT_NEAR(moved[p][axis], x[axis], 1e-12) << p;
            }
        largestMove = std::max(largestMove, norm(moved[p] - reference[p]));
    }
    EXPECT_GT(largestMove, 1e-3);
}

TEST(SlipBox, LineNodesSlideAlongTheEdgeAndTheStageLeavesAValidMeshUntouched)
{
    // The unit cube (10³ cells) turned 30° stays valid without untangling; the stage must then
    // change nothing, bit for bit. Its vertical edges' points slide along the edge: x and y
    // stay, z moves (held, as before line nodes, they could not).
    const PolyMesh mesh = slipBoxMesh(10);
    auto on = slipBoxSolver(mesh, degrees(30.0), "");
    auto off = slipBoxSolver(mesh, degrees(30.0), "untangle off;");
    const MotionSolveReport withStage = on->solve();
    const MotionSolveReport without = off->solve();
    EXPECT_EQ(without.invertedCellCount, 0);
    EXPECT_EQ(withStage.untangledCellCount, 0);
    EXPECT_EQ(withStage.reason, without.reason);
    const std::vector<Vector3> a = on->curPoints(), b = off->curPoints();
    for (Label p = 0; p < mesh.pointCount(); ++p) ASSERT_EQ(a[p], b[p]) << p;

    const RbmProblem& problem = *dynamic_cast<const RigidBodyMotionSolver&>(*on).problem();
    double alongEdge = 0.0;
    for (Label p = 0; p < mesh.pointCount(); ++p) {
        const Vector3& x = mesh.points[p];
        const bool onTwoSides = (x.x == 0.0 || x.x == 1.0) && (x.y == 0.0 || x.y == 1.0);
        if (!onTwoSides || x.z == 0.0 || x.z == 1.0) continue;
        EXPECT_EQ(problem.kind(p), NodeKind::sliding) << p;
        EXPECT_TRUE(problem.slidesOnLine(p)) << p;
        EXPECT_NEAR(a[p].x, x.x, 1e-12);
        EXPECT_NEAR(a[p].y, x.y, 1e-12);
        alongEdge = std::max(alongEdge, std::abs(a[p].z - x.z));
    }
    EXPECT_GT(alongEdge, 1e-4);
    // A point on three planes (a bottom corner: bottom is prescribed anyway; use xMin ∩ yMin
    // ∩ a slip bottom) is held: see ThreePlanesHoldAPoint.
}

TEST(SlipBox, ThreePlanesHoldAPoint)
{
    // Every side and the bottom slip, the top turns: the bottom corners lie on three planes
    // (held), the bottom edges on two (a line), the bottom faces' points on one.
    const PolyMesh mesh = slipBoxMesh(4);
    const io::Dictionary field = io::Dictionary::parseText(R"field(
        boundaryField
        {
            "(xMin|xMax|yMin|yMax|bottom)" { type slip; }
            top { type fixedValue; value uniform (0 0 0); }
        })field", "0/pointDisplacement");
    const io::Dictionary dict = io::Dictionary::parseText("motionSolver rigidBodyMotionSolver;\n", "constant/dynamicMeshDict");
    auto solver = builtinMotionSolvers().create(mesh, dict, &field, "/nonexistent/case");
    const std::vector<Label> top = pointsOf(mesh, "top");
    std::vector<Vector3> displacement(top.size(), Vector3{0.05, 0.02, 0.0});
    solver->setPatchDisplacement("top", displacement);
    const MotionSolveReport report = solver->solve();
    EXPECT_TRUE(report.converged) << report.reason;
    const RbmProblem& problem = *dynamic_cast<const RigidBodyMotionSolver&>(*solver).problem();
    auto point = [](int i, int j, int k) { return i + 5 * (j + 5 * k); };
    EXPECT_EQ(problem.kind(point(0, 0, 0)), NodeKind::prescribed);  // three planes
    EXPECT_EQ(problem.kind(point(4, 4, 0)), NodeKind::prescribed);
    EXPECT_TRUE(problem.slidesOnLine(point(2, 0, 0)));              // yMin ∩ bottom: along x
    EXPECT_TRUE(problem.slidesOnLine(point(0, 0, 2)));              // xMin ∩ yMin: along z
    EXPECT_FALSE(problem.slidesOnLine(point(2, 2, 0)));             // bottom only
    const std::vector<Vector3> points = solver->curPoints();
    EXPECT_EQ(points[point(0, 0, 0)], mesh.points[point(0, 0, 0)]);
    EXPECT_NEAR(points[point(2, 0, 0)].y, 0.0, 1e-12);
    EXPECT_NEAR(points[point(2, 0, 0)].z, 0.0, 1e-12);
    EXPECT_GT(std::abs(points[point(2, 0, 0)].x - 0.5), 1e-4);      // the top's shift along x drags it
}

TEST(Untangling, APrescribedBoundaryThatInvertsACellIsReportedWithWhereItIs)
{
    // One layer of cells whose top is pushed below the bottom: every point is prescribed, no
    // position of the others can help; the reason must say so and name a cell and its patches.
    const PolyMesh mesh = slipBoxMesh(3, 1, 0.1);
    auto solver = slipBoxSolver(mesh, 0.0, "");
    std::vector<Vector3> down(pointsOf(mesh, "top").size(), Vector3{0.0, 0.0, -0.15});
    solver->setPatchDisplacement("top", down);
    const MotionSolveReport report = solver->solve();
    std::printf("%s\n", report.reason.c_str());
    EXPECT_EQ(report.invertedCellCount, 9);
    EXPECT_EQ(report.untangledCellCount, 0);
    EXPECT_NE(report.reason.find("9 cell(s) stay inverted"), std::string::npos) << report.reason;
    EXPECT_NE(report.reason.find("no valid position exists"), std::string::npos) << report.reason;
    EXPECT_NE(report.reason.find("cell 0 at (0.166667 0.166667 -0.025)"), std::string::npos) << report.reason;
    EXPECT_NE(report.reason.find("patch bottom, top, xMin, yMin"), std::string::npos) << report.reason;
}

TEST(SlipBox, DISABLED_MeasureQuick)
{
    for (const auto& [n, nz, height] : {std::tuple{10, 10, 0.2}, {20, 4, 0.2}, {10, 4, 0.2}, {10, 2, 0.1}})
        for (double angle : {30.0, 45.0}) {
            const PolyMesh mesh = slipBoxMesh(n, nz, height);
            for (const char* coefficients : {"maxSubStepSplits 0;", "subSteps 1; formulation linearized;", "coupling decoupled; maxSubStepSplits 0;"}) {
                for (const char* stage : {"untangle off;", ""}) {
                    auto solver = slipBoxSolver(mesh, degrees(angle), std::string(coefficients) + stage);
                    const MotionSolveReport report = solver->solve();
                    std::printf("%dx%dx%d h %.1f %2.0f deg %-25s %-14s inverted %2d worst %.4f %.2f s %s\n", n, n, nz,
                                height, angle, coefficients, stage, report.invertedCellCount, report.worstQuality,
                                report.wallSeconds, report.reason.c_str());
                    std::fflush(stdout);
                }
            }
        }
}

TEST(SlipBox, DISABLED_Measure)
{
    for (const auto& [n, nz, height] : {std::tuple{10, 10, 1.0}, {10, 10, 0.2}, {20, 4, 0.2}})
        for (double angle : {30.0, 45.0, 60.0}) {
            const PolyMesh mesh = slipBoxMesh(n, nz, height);
            for (const char* coefficients : {"", "formulation linearized;", "coupling decoupled;"}) {
                for (const char* stage : {"untangle off;", ""}) {
                    auto solver = slipBoxSolver(mesh, degrees(angle), std::string(coefficients) + stage);
                    const MotionSolveReport report = solver->solve();
                    std::printf("%dx%dx%d h %.1f %2.0f deg %-25s %-14s inverted %2d worst %.4f %.2f s %s\n", n, n, nz,
                                height, angle, coefficients, stage, report.invertedCellCount, report.worstQuality,
                                report.wallSeconds, report.reason.c_str());
                }
            }
        }
}

} // namespace
