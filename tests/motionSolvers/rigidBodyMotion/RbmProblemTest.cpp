// Tests of the RBM problem (RbmProblem) and its solvers through the RbmSolver interface: rigid
// motions reproduced by every solver, the coupled solvers on the thesis' rotating squares,
// sliding and line nodes, and the checks of the problem's input.

#include "CoupledLinearizedSolver.hpp"
#include "CoupledNewtonSolver.hpp"
#include "DecoupledSolver.hpp"
#include "LocalGlobalSolver.hpp"
#include "PetscTestEnvironment.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"
#include "ReducedNewtonSolver.hpp"
#include "RigidMotionModes.hpp"
#include "Rotation.hpp"
#include "SubStepping.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <numeric>
#include <ostream>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace rbm::motion::coreCases;

namespace rbm::motion {

namespace {

struct RigidParameters {
    int dimension;
    double angleDegrees;
    EdgeWeighting weighting;
};

void PrintTo(const RigidParameters& parameters, std::ostream* out)
{
    *out << parameters.dimension << "D, " << parameters.angleDegrees << " degrees, "
         << edgeWeightingName(parameters.weighting) << " weights";
}

class RigidMotionIsReproduced : public ::testing::TestWithParam<RigidParameters> {};

TEST_P(RigidMotionIsReproduced, ByNewton)
{
    const RigidParameters parameters = GetParam();
    const RigidCase c = rigidCase(parameters.dimension, degrees(parameters.angleDegrees), parameters.weighting);
    CoupledNewtonSolver solver(*c.problem);
    const RbmResult result = solver.solve(c.prescribed);
    EXPECT_TRUE(result.converged) << result.reason;
    EXPECT_LT(maximumPositionError(c, result), 1e-9 * c.meshSize) << result.reason << " after " << result.iterations;
    EXPECT_LT(result.energy, 1e-15);
    // The rotation of every free node is the body's rotation.
    for (int node : c.problem->unknownNodes()) {
        const Matrix3 rotation = parameters.dimension == 2 ? planarRotation(result.rotation[node].z)
                                                           : rotationFromVector(result.rotation[node]);
        for (int r = 0; r < 3; ++r)
            for (int col = 0; col < 3; ++col) ASSERT_NEAR(rotation.m[r][col], c.motion.rotation.m[r][col], 1e-9);
    }
}

TEST_P(RigidMotionIsReproduced, ByLocalGlobal)
{
    const RigidParameters parameters = GetParam();
    const RigidCase c = rigidCase(parameters.dimension, degrees(parameters.angleDegrees), parameters.weighting);
    LocalGlobalSolver solver(*c.problem);
    const RbmResult result = solver.solve(c.prescribed);
    EXPECT_TRUE(result.converged) << result.reason;
    EXPECT_LT(maximumPositionError(c, result), 1e-9 * c.meshSize) << result.reason;
    EXPECT_LT(result.energy, 1e-15);
}

TEST_P(RigidMotionIsReproduced, ByDecoupledNonlinear)
{
    const RigidParameters parameters = GetParam();
    const RigidCase c = rigidCase(parameters.dimension, degrees(parameters.angleDegrees), parameters.weighting);
    DecoupledSolver solver(*c.problem);
    const RbmResult result = solver.solve(c.prescribed);
    EXPECT_TRUE(result.converged) << result.reason;
    EXPECT_LT(maximumPositionError(c, result), 1e-9 * c.meshSize) << result.reason;
    EXPECT_LT(result.energy, 1e-15);
}

std::string rigidName(const ::testing::TestParamInfo<RigidParameters>& info)
{
    return std::to_string(info.param.dimension) + "D" + std::to_string(static_cast<int>(info.param.angleDegrees)) +
           "Degrees" + std::string(edgeWeightingName(info.param.weighting));
}

INSTANTIATE_TEST_SUITE_P(LargeAngles, RigidMotionIsReproduced,
                         ::testing::Values(RigidParameters{2, 60.0, EdgeWeighting::uniform},
                                           RigidParameters{2, 120.0, EdgeWeighting::inverseDistanceSquared},
                                           RigidParameters{2, 120.0, EdgeWeighting::uniform},
                                           RigidParameters{3, 60.0, EdgeWeighting::inverseDistance},
                                           RigidParameters{3, 120.0, EdgeWeighting::uniform},
                                           RigidParameters{3, 120.0, EdgeWeighting::inverseDistanceSquared}),
                         rigidName);

// Every variant, as a factory, for tests that run them all.
struct NamedFactory {
    const char* name;
    RbmSolverFactory make;
    bool nonlinear;
};

std::vector<NamedFactory> allVariants()
{
    return {
        {"Newton", [](const RbmProblem& p) { return std::make_unique<CoupledNewtonSolver>(p); }, true},
        {"LocalGlobal", [](const RbmProblem& p) { return std::make_unique<LocalGlobalSolver>(p); }, true},
        {"DecoupledNonlinear", [](const RbmProblem& p) { return std::make_unique<DecoupledSolver>(p); }, true},
        {"CoupledLinearized", [](const RbmProblem& p) { return std::make_unique<CoupledLinearizedSolver>(p); }, false},
        {"DecoupledLinearized",
         [](const RbmProblem& p) {
             DecoupledOptions options;
             options.model = DecoupledModel::linearized;
             return std::make_unique<DecoupledSolver>(p, options);
         },
         false},
    };
}

TEST(CoupledSolvers, NewtonAndLocalGlobalReachTheSameEnergyOnTheRotatedSquares)
{
    // 21 × 21 nodes with a 4-cell hole turned by 10°: not a rigid motion.
    const SquaresCase c = squaresCase(21, 4, degrees(10.0));
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    CoupledNewtonSolver newton(problem);
    LocalGlobalSolver localGlobal(problem);
    const RbmResult byNewton = newton.solve(c.prescribed);
    const RbmResult byLocalGlobal = localGlobal.solve(c.prescribed);
    ASSERT_TRUE(byNewton.converged) << byNewton.reason;
    ASSERT_TRUE(byLocalGlobal.converged) << byLocalGlobal.reason;
    EXPECT_GT(byNewton.energy, 1.0);  // genuinely deformed
    EXPECT_NEAR(byLocalGlobal.energy, byNewton.energy, 1e-9 * byNewton.energy);
    double largest = 0.0;
    for (std::size_t node = 0; node < c.mesh.points.size(); ++node)
        largest = std::max(largest, norm(byNewton.displacement[node] - byLocalGlobal.displacement[node]));
    EXPECT_LT(largest, 1e-7 * 10.0);
}

TEST(CoupledSolvers, WarmStartedNewtonFollowsATimeSeriesInFewIterations)
{
    // A pitching-like series: the hole turns 2°, 4°, ... 20°, each step warm-started from
    // the previous one (as rbmMoveMesh does). The linear predictor for the boundary change
    // must keep Newton at a few iterations per step, and every step must reach the same
    // minimum as a cold solve of that step.
    const SquaresCase reference = squaresCase(31, 6, 0.0);
    const RbmProblem problem(2, reference.mesh.points, reference.mesh.graph, reference.constraints,
                             EdgeWeighting::inverseDistanceSquared);
    CoupledNewtonSolver warm(problem);
    CoupledNewtonSolver cold(problem);
    RbmResult previous;
    for (int step = 1; step <= 10; ++step) {
        const SquaresCase c = squaresCase(31, 6, degrees(2.0 * step));
        const RbmResult result = warm.solve(c.prescribed, step > 1 ? &previous : nullptr);
        ASSERT_TRUE(result.converged) << "step " << step << ": " << result.reason;
        EXPECT_LE(result.iterations, 3) << "step " << step;
        const RbmResult fromScratch = cold.solve(c.prescribed);
        EXPECT_NEAR(result.energy, fromScratch.energy, 1e-9 * fromScratch.energy) << "step " << step;
        double largest = 0.0;
        for (std::size_t node = 0; node < c.mesh.points.size(); ++node)
            largest = std::max(largest, norm(result.displacement[node] - fromScratch.displacement[node]));
        EXPECT_LT(largest, 1e-7 * 10.0) << "step " << step;
        previous = result;
    }
}

TEST(CoupledSolvers, ThesisRotatingSquaresReachTheMeasuredEnergy)
{
    // Full size (§3.1: 101 × 101 nodes, 20-cell hole, 9360 free nodes), 10°, uniform
    // weights: an independent prototype gave E = 7725.3 for the coupled nonlinear method
    // (docs/method.md §10).
    const SquaresCase c = squaresCase(101, 20, degrees(10.0));
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    ASSERT_EQ(problem.nodeCount(), 9840);
    ASSERT_EQ(problem.unknownNodeCount(), 9360);
    CoupledNewtonSolver newton(problem);
    const RbmResult result = newton.solve(c.prescribed);
    ASSERT_TRUE(result.converged) << result.reason;
    EXPECT_NEAR(result.energy, 7725.3, 0.05);
}

TEST(CoupledSolvers, RotatingSquaresWithAFreeOuterBoundaryTurnRigidly)
{
    // Thesis §3.1.3 (Fig 3.7): 11 × 11 nodes (120 nodes, 96 quadrilaterals), the 2-cell inner
    // square turned by 45°, every other node free: the ideal grid is the whole mesh turned
    // rigidly, and it has zero energy, so every nonlinear variant must find it.
    const SquaresCase c = squaresCase(11, 2, degrees(45.0));
    std::vector<NodeConstraint> constraints = c.constraints;
    for (std::size_t node = 0; node < constraints.size(); ++node)
        if (norm(c.prescribed[node]) == 0.0) constraints[node].kind = NodeKind::free;
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, constraints, EdgeWeighting::uniform);
    ASSERT_EQ(problem.nodeCount(), 120);
    ASSERT_EQ(problem.unknownNodeCount(), 112);
    RigidMotion turn;
    turn.rotation = planarRotation(degrees(45.0));
    turn.centre = {50.0, 50.0, 0.0};
    for (const NamedFactory& variant : allVariants()) {
        if (!variant.nonlinear) continue;
        const std::unique_ptr<RbmSolver> solver = variant.make(problem);
        const RbmResult result = solver->solve(c.prescribed);
        EXPECT_TRUE(result.converged) << variant.name << ": " << result.reason;
        double largest = 0.0;
        for (std::size_t node = 0; node < c.mesh.points.size(); ++node)
            largest = std::max(largest, norm(result.displacement[node] - turn.displacement(c.mesh.points[node])));
        EXPECT_LT(largest, 1e-9 * 10.0) << variant.name << " after " << result.iterations << " iterations";
    }
}

TEST(SlidingNodes, FollowARigidMotionThatKeepsTheirPlane)
{
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, false}, {3, true}}) {
        // The rotation is about the plane normal, so it is allowed on a mirror plane too.
        const SlidingCase c = slidingCase(dimension, degrees(60.0), 0.25, EdgeWeighting::inverseDistanceSquared, mirror);
        ASSERT_TRUE(c.problem->hasSlidingNodes());
        for (const NamedFactory& variant : allVariants()) {
            // The linearized variants are exact only without rotation (2D here).
            if (!variant.nonlinear && dimension == 3) continue;
            const std::unique_ptr<RbmSolver> solver = variant.make(*c.problem);
            const RbmResult result = solver->solve(c.prescribed);
            EXPECT_TRUE(result.converged) << variant.name << ": " << result.reason;
            double largest = 0.0;
            for (std::size_t node = 0; node < c.mesh.points.size(); ++node)
                largest = std::max(largest, norm(result.displacement[node] - c.motion.displacement(c.mesh.points[node])));
            EXPECT_LT(largest, 1e-9) << dimension << "D " << variant.name << (mirror ? " mirror" : "");
        }
    }
}

TEST(SlidingNodes, StayOnTheirPlaneAndNewtonAndLocalGlobalAgree)
{
    // Non-rigid: the box's top is sheared; sliding nodes must keep u·n = c exactly.
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, false}, {3, true}}) {
        const SlidingCase c = slidingCase(dimension, degrees(20.0), 0.25, EdgeWeighting::uniform, mirror);
        std::vector<Vector3> prescribed = c.prescribed;
        for (std::size_t node = 0; node < prescribed.size(); ++node)
            if (c.problem->kind(static_cast<int>(node)) == NodeKind::prescribed)
                prescribed[node] += 0.1 * dot(c.mesh.points[node], c.normal) * Vector3{c.normal.y, -c.normal.x, 0.0};
        CoupledNewtonSolver newton(*c.problem);
        LocalGlobalSolver localGlobal(*c.problem);
        const RbmResult byNewton = newton.solve(prescribed);
        const RbmResult byLocalGlobal = localGlobal.solve(prescribed);
        ASSERT_TRUE(byNewton.converged) << byNewton.reason;
        ASSERT_TRUE(byLocalGlobal.converged) << byLocalGlobal.reason;
        EXPECT_GT(byNewton.energy, 1e-4);
        EXPECT_NEAR(byLocalGlobal.energy, byNewton.energy, 1e-9 * byNewton.energy) << dimension << "D" << mirror;
        const double planeOffset = dot(c.motion.translation, c.normal);  // the plane's own motion
        int sliding = 0;
        double inPlaneRotation = 0.0;
        for (int node = 0; node < c.problem->nodeCount(); ++node) {
            if (c.problem->kind(node) != NodeKind::sliding) continue;
            ++sliding;
            EXPECT_NEAR(dot(byNewton.displacement[node], c.normal), planeOffset, 1e-13);
            EXPECT_NEAR(dot(byLocalGlobal.displacement[node], c.normal), planeOffset, 1e-13);
            EXPECT_LT(norm(byNewton.displacement[node] - byLocalGlobal.displacement[node]), 1e-8);
            if (mirror) {  // a mirror node turns about the normal only
                for (const RbmResult* result : {&byNewton, &byLocalGlobal}) {
                    const Vector3& omega = result->rotation[node];
                    EXPECT_LT(norm(omega - dot(omega, c.normal) * c.normal), 1e-13) << node;
                }
            } else if (dimension == 3) {
                inPlaneRotation = std::max(inPlaneRotation, norm(byNewton.rotation[node] -
                                                                 dot(byNewton.rotation[node], c.normal) * c.normal));
            }
        }
        // Without the mirror the shear does tilt the plane's nodes (so the check above can fail).
        if (dimension == 3 && !mirror) {
            EXPECT_GT(inPlaneRotation, 1e-3);
        }
        EXPECT_GT(sliding, 3);
    }
}

// Line nodes: a box (5 × 5 × 4 nodes, turned by `frame`) whose faces x = 0 and y = 0 are
// sliding planes; the nodes of their common edge (i = j = 0, inner k) slide on the line
// where both planes meet, the other boundary nodes are prescribed.
struct LineCase {
    TestMesh mesh;
    std::unique_ptr<RbmProblem> problem;
    Vector3 normalX, normalY, direction;  // the two planes' unit normals and the line's direction
    std::vector<int> lineNodes;
};

LineCase lineCase(EdgeWeighting weighting)
{
    LineCase c;
    c.mesh = structuredGrid(5, 5, 4, 1.0, {0.0, 0.0, 0.0});
    const Matrix3 frame = rotationFromVector({0.3, -0.5, 0.2});
    c.normalX = frame * Vector3{1.0, 0.0, 0.0};
    c.normalY = frame * Vector3{0.0, 1.0, 0.0};
    c.direction = frame * Vector3{0.0, 0.0, 1.0};
    std::vector<NodeConstraint> constraints = prescribeBoundary(c.mesh);
    for (std::size_t node = 0; node < c.mesh.points.size(); ++node) {
        const auto [i, j, k] = c.mesh.gridIndex[node];
        if (k == 0 || k == 3) continue;
        const bool onX = i == 0 && j > 0 && j < 4, onY = j == 0 && i > 0 && i < 4;
        if (onX) constraints[node] = {NodeKind::sliding, 2.0 * c.normalX};
        if (onY) constraints[node] = {NodeKind::sliding, c.normalY};
        if (i == 0 && j == 0) {
            // Any lengths, and a second normal not orthogonal to the first (the problem
            // orthogonalises it).
            constraints[node] = {NodeKind::sliding, 0.5 * c.normalX, false, 3.0 * c.normalY + c.normalX};
            c.lineNodes.push_back(static_cast<int>(node));
        }
    }
    for (Vector3& point : c.mesh.points) point = frame * point;
    c.problem = std::make_unique<RbmProblem>(3, c.mesh.points, c.mesh.graph, constraints, weighting);
    return c;
}

// Every variant plus the matrix-free linearized solve and reduced Newton (their own
// projection code).
std::vector<NamedFactory> allVariantsWithMatrixFree()
{
    std::vector<NamedFactory> variants = allVariants();
    variants.push_back({"ReducedNewton", [](const RbmProblem& p) { return std::make_unique<ReducedNewtonSolver>(p); }, true});
    variants.push_back({"MatrixFreeLinearized",
                        [](const RbmProblem& p) {
                            CoupledLinearizedOptions options;
                            options.linearSolver = LinearSolverKind::matrixFree;
                            return std::make_unique<CoupledLinearizedSolver>(p, options);
                        },
                        false});
    return variants;
}

TEST(LineNodes, FollowATranslationAlongTheLineWhileBothPlanesMove)
{
    // A rigid translation along the line (and across both planes: the planes themselves
    // move, which the line nodes' offsets c n + c' m̂ carry) is the exact minimiser (E = 0).
    const LineCase c = lineCase(EdgeWeighting::inverseDistanceSquared);
    ASSERT_EQ(c.lineNodes.size(), 2u);
    for (int node : c.lineNodes) {
        ASSERT_TRUE(c.problem->slidesOnLine(node));
        EXPECT_NEAR(dot(c.problem->secondSlidingNormal(node), c.normalY), 1.0, 1e-15);
    }
    const Vector3 translation = 0.6 * c.direction + 0.25 * c.normalX - 0.15 * c.normalY;
    const std::vector<Vector3> prescribed(c.mesh.points.size(), translation);
    for (const NamedFactory& variant : allVariantsWithMatrixFree()) {
        const RbmResult result = variant.make(*c.problem)->solve(prescribed);
        EXPECT_TRUE(result.converged) << variant.name << ": " << result.reason;
        double largest = 0.0;
        for (const Vector3& u : result.displacement) largest = std::max(largest, norm(u - translation));
        EXPECT_LT(largest, 1e-9) << variant.name;
    }
}

TEST(LineNodes, StayOnBothPlanesAndAreAConstrainedMinimumAlongTheLine)
{
    // Non-rigid: the prescribed nodes are twisted about the line's direction and pushed
    // along it, so the line nodes are pulled off both planes unless held; they must stay
    // on both to rounding, and the energy must be stationary along the line (a central
    // difference of E along d vanishes) while it is not across it (the constraint is active).
    for (const EdgeWeighting weighting : {EdgeWeighting::uniform, EdgeWeighting::inverseDistanceSquared}) {
        const LineCase c = lineCase(weighting);
        const Vector3 centre = c.mesh.points[c.lineNodes[0]];
        std::vector<Vector3> prescribed(c.mesh.points.size());
        for (int node = 0; node < c.problem->nodeCount(); ++node) {
            const Vector3 x = c.mesh.points[node] - centre;
            const double height = dot(x, c.direction);
            prescribed[node] = rotationFromVector(0.15 * height * c.direction) * x - x + 0.1 * height * c.direction +
                               0.2 * dot(x, c.normalX) * c.normalY;
            if (c.problem->kind(node) == NodeKind::sliding) prescribed[node] = {};  // the planes stay
        }
        for (const NamedFactory& variant : allVariantsWithMatrixFree()) {
            const RbmResult result = variant.make(*c.problem)->solve(prescribed);
            ASSERT_TRUE(result.converged) << variant.name << ": " << result.reason;
            double alongLine = 0.0;
            for (int node : c.lineNodes) {
                const Vector3& u = result.displacement[node];
                EXPECT_LT(std::abs(dot(u, c.normalX)), 1e-12) << variant.name;
                EXPECT_LT(std::abs(dot(u, c.normalY)), 1e-12) << variant.name;
                alongLine = std::max(alongLine, std::abs(dot(u, c.direction)));
            }
            EXPECT_GT(alongLine, 1e-3) << variant.name << ": the line nodes do move along their line";
            if (!variant.nonlinear || std::string(variant.name) == "DecoupledNonlinear") continue;
            // (ReducedNewton's rotations are its best fits: the slope test applies to it too.)
            // Coupled nonlinear minimisers: ∂E/∂s along d is zero, across (n_x) it is not.
            const RbmEnergy energy(*c.problem, RotationModel::exact, prescribed);
            std::vector<double> unknowns(c.problem->unknownCount());
            packUnknowns(*c.problem, result, unknowns);
            const double h = 1e-6;
            auto slope = [&](int node, const Vector3& direction) {
                std::vector<double> plus(unknowns), minus(unknowns);
                const int a = c.problem->unknownIndex()[node];
                for (int q = 0; q < 3; ++q) {
                    plus[6 * a + q] += h * direction[q];
                    minus[6 * a + q] -= h * direction[q];
                }
                return (energy.value(plus) - energy.value(minus)) / (2.0 * h);
            };
            double across = 0.0;
            for (int node : c.lineNodes) {
                EXPECT_LT(std::abs(slope(node, c.direction)), 1e-6 * result.energy) << variant.name;
                across = std::max(across, std::abs(slope(node, c.normalX)));
            }
            EXPECT_GT(across, 1e-2 * result.energy) << variant.name;
        }
    }
}

TEST(LineNodes, ProjectionsAreTheProjectorOntoTheLine)
{
    // projectSliding and projectSlidingBlocks apply P = d dᵀ to a line node's displacement:
    // P v = (v·d) d, and the block form keeps P H P + s (I − P) symmetric positive definite.
    const LineCase c = lineCase(EdgeWeighting::uniform);
    const int a = c.problem->unknownIndex()[c.lineNodes[0]];
    std::vector<double> vector(c.problem->unknownCount(), 0.0);
    const Vector3 v{0.3, -1.1, 0.7};
    for (int q = 0; q < 3; ++q) vector[6 * a + q] = v[q];
    c.problem->projectSliding(vector);
    for (int q = 0; q < 3; ++q) EXPECT_NEAR(vector[6 * a + q], dot(v, c.direction) * c.direction[q], 1e-15);
    const RbmEnergy energy(*c.problem, RotationModel::smallAngle, std::vector<Vector3>(c.mesh.points.size()));
    std::vector<double> blocks(static_cast<std::size_t>(c.problem->blockPattern().blockCount()) * 36);
    energy.hessian(std::vector<double>(c.problem->unknownCount(), 0.0), blocks);
    c.problem->projectSlidingBlocks(blocks, 6);
    const DenseMatrix dense = denseFromBlocks(*c.problem, blocks, 6);
    EXPECT_TRUE(choleskySucceeds(dense));
    // (P H P)(n_x at node a) = s n_x: the row block of node a maps the normals onto themselves.
    for (int r = 0; r < static_cast<int>(dense.size()); ++r) {
        double product = 0.0;
        for (int q = 0; q < 3; ++q) product += dense[r][6 * a + q] * c.normalY[q];
        if (r / 6 != a || r % 6 >= 3) {
            EXPECT_NEAR(product, 0.0, 1e-12) << r;
        }
    }
}

namespace {

// A 5 × 5 × 4 grid with its boundary prescribed and two interior nodes tied by a 30° turn about
// z, node a sliding on the plane normal to `normalA` and b on its image (`normalB`).
struct PairCase {
    TestMesh mesh;
    std::vector<NodeConstraint> constraints;
    int a = -1, b = -1;
    rbm::Matrix3 q = rbm::rotationMatrix({0.0, 0.0, 1.0}, 30.0 * std::numbers::pi / 180.0);
};

// q's rows, as CoupledPair holds them.
std::array<Vector3, 3> rowsOf(const rbm::Matrix3& q)
{
    return {Vector3{q(0, 0), q(0, 1), q(0, 2)}, Vector3{q(1, 0), q(1, 1), q(1, 2)}, Vector3{q(2, 0), q(2, 1), q(2, 2)}};
}

PairCase pairCase()
{
    PairCase c;
    c.mesh = structuredGrid(5, 5, 4, 1.0, {0.0, 0.0, 0.0});
    c.constraints = prescribeBoundary(c.mesh);
    for (std::size_t node = 0; node < c.mesh.points.size(); ++node) {
        const auto [i, j, k] = c.mesh.gridIndex[node];
        if (i == 1 && j == 1 && k == 1) c.a = static_cast<int>(node);
        if (i == 3 && j == 2 && k == 2) c.b = static_cast<int>(node);
    }
    return c;
}

} // namespace

TEST(CoupledPairs, ProjectionIsTheOrthogonalProjectorOntoThePairAndItsPlanes)
{
    PairCase c = pairCase();
    const Vector3 normalA = Vector3{1.0, 2.0, 0.5} / std::sqrt(5.25);
    c.constraints[c.a] = {NodeKind::sliding, normalA};
    c.constraints[c.b] = {NodeKind::sliding, 3.0 * (c.q * normalA)};  // any length
    RbmProblem problem(3, c.mesh.points, c.mesh.graph, c.constraints);
    problem.setCoupledPairs({{c.a, c.b, rowsOf(c.q)}});
    std::mt19937 random(7);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    const std::size_t size = static_cast<std::size_t>(problem.unknownNodeCount()) * 3;
    std::vector<double> x(size), y(size);
    for (std::size_t k = 0; k < size; ++k) {
        x[k] = uniform(random);
        y[k] = uniform(random);
    }
    std::vector<double> px = x, py = y;
    problem.projectSliding(px, 3);
    problem.projectSliding(py, 3);
    // Symmetric: x·Py = Px·y; idempotent: P(Px) = Px.
    double xPy = 0.0, pxY = 0.0;
    for (std::size_t k = 0; k < size; ++k) {
        xPy += x[k] * py[k];
        pxY += px[k] * y[k];
    }
    EXPECT_NEAR(xPy, pxY, 1e-13);
    std::vector<double> twice = px;
    problem.projectSliding(twice, 3);
    for (std::size_t k = 0; k < size; ++k) EXPECT_NEAR(twice[k], px[k], 1e-15);
    // In the subspace: u_b = q u_a, u_a on its plane; a free node untouched.
    const int ia = problem.unknownIndex()[c.a], ib = problem.unknownIndex()[c.b];
    const Vector3 ua{px[3 * ia], px[3 * ia + 1], px[3 * ia + 2]}, ub{px[3 * ib], px[3 * ib + 1], px[3 * ib + 2]};
    EXPECT_LT(norm(ub - c.q * ua), 1e-15);
    EXPECT_NEAR(dot(ua, normalA), 0.0, 1e-15);
    EXPECT_GT(norm(ua), 0.1);
    const int other = problem.unknownIndex()[c.a + 1];
    for (int q = 0; q < 3; ++q) EXPECT_EQ(px[3 * other + q], x[3 * other + q]);
    // The exact pair after rounding.
    std::vector<Vector3> displacement(c.mesh.points.size(), Vector3{0.1, 0.2, 0.3});
    problem.enforceCoupledPairs(displacement);
    EXPECT_EQ(displacement[c.b], (c.q * Vector3{0.1, 0.2, 0.3}));
}

TEST(CoupledPairs, RejectsPairsTheProjectionCannotTake)
{
    PairCase c = pairCase();
    c.constraints[c.a] = {NodeKind::sliding, {1.0, 0.0, 0.0}};
    c.constraints[c.b] = {NodeKind::sliding, {1.0, 0.0, 0.0}};  // not the image of a's plane
    RbmProblem problem(3, c.mesh.points, c.mesh.graph, c.constraints);
    EXPECT_THROW(problem.setCoupledPairs({{c.a, c.b, rowsOf(c.q)}}), std::invalid_argument);
    c.constraints[c.b] = {};
    RbmProblem free(3, c.mesh.points, c.mesh.graph, c.constraints);
    EXPECT_THROW(free.setCoupledPairs({{c.a, c.b, rowsOf(c.q)}}), std::invalid_argument);  // one plane against none
    EXPECT_THROW(free.setCoupledPairs({{c.a, 0, rowsOf(c.q)}}), std::invalid_argument);    // node 0 is prescribed
    rbm::Matrix3 stretched = c.q;
    stretched.m[0][0] *= 1.1;
    RbmProblem plain(3, c.mesh.points, c.mesh.graph, prescribeBoundary(c.mesh));
    EXPECT_THROW(plain.setCoupledPairs({{c.a, c.b, rowsOf(stretched)}}), std::invalid_argument);
    EXPECT_THROW(plain.setCoupledPairs({{c.a, c.b, rowsOf(c.q)}, {c.b, c.a + 1, rowsOf(c.q)}}), std::invalid_argument);  // b twice
    EXPECT_NO_THROW(plain.setCoupledPairs({{c.a, c.b, rowsOf(c.q)}}));
}

TEST(RbmProblemInput, EdgeWeightFactorsScaleTheWeightsAndSurviveANewReference)
{
    TestMesh mesh = structuredGrid(5, 5, 1, 1.0, {0.0, 0.0, 0.0});
    RbmProblem problem(2, mesh.points, mesh.graph, prescribeBoundary(mesh), EdgeWeighting::inverseDistanceSquared);
    // f_ij = 1 + x_i + x_j: symmetric, different on every column pair.
    const CellNeighbourGraph& graph = problem.graph();
    std::vector<double> factors(graph.neighbours.size());
    for (int i = 0; i < problem.nodeCount(); ++i)
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
            factors[e] = 1.0 + mesh.points[i].x + mesh.points[graph.neighbours[e]].x;
    problem.setEdgeWeightFactors(factors);
    for (int i = 0; i < problem.nodeCount(); ++i)
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const double length = norm(mesh.points[graph.neighbours[e]] - mesh.points[i]);
            ASSERT_NEAR(problem.edgeWeights()[e], factors[e] / (length * length), 1e-15);
        }
    std::vector<Vector3> doubled = mesh.points;
    for (Vector3& point : doubled) point *= 2.0;
    const RbmProblem moved = problem.withReferencePoints(doubled);
    EXPECT_NEAR(moved.edgeWeights()[0], problem.edgeWeights()[0] / 4.0, 1e-15);
    std::vector<double> lopsided = factors;
    lopsided[0] *= 2.0;
    EXPECT_THROW(problem.setEdgeWeightFactors(lopsided), std::invalid_argument);
    EXPECT_THROW(problem.setEdgeWeightFactors(std::vector<double>(3, 1.0)), std::invalid_argument);
}

TEST(RbmProblemInput, SharedEdgeWeightFactorsAreOneArrayForEveryProblemBuiltFromThem)
{
    // The motion solver's stiffening factors are one array of 8 bytes per directed edge (210 MB
    // at 10⁶ hexahedra): the problems built from it, and their moved copies, share it instead
    // of copying it, with the weights the copying setter gives to the last bit.
    TestMesh mesh = structuredGrid(5, 5, 1, 1.0, {0.0, 0.0, 0.0});
    RbmProblem copying(2, mesh.points, mesh.graph, prescribeBoundary(mesh), EdgeWeighting::inverseDistanceSquared);
    RbmProblem sharing = copying;
    const CellNeighbourGraph& graph = copying.graph();
    std::vector<double> factors(graph.neighbours.size());
    for (int i = 0; i < copying.nodeCount(); ++i)
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
            factors[e] = 0.5 + mesh.points[i].y * mesh.points[graph.neighbours[e]].y;
    copying.setEdgeWeightFactors(factors);
    const auto shared = std::make_shared<const std::vector<double>>(factors);
    sharing.setEdgeWeightFactors(shared);
    EXPECT_EQ(sharing.edgeWeightFactors().data(), shared->data());
    EXPECT_NE(copying.edgeWeightFactors().data(), factors.data());
    EXPECT_EQ(sharing.edgeWeights(), copying.edgeWeights());
    std::vector<Vector3> stretched = mesh.points;
    for (Vector3& point : stretched) point.x *= 3.0;
    const RbmProblem moved = sharing.withReferencePoints(stretched);
    EXPECT_EQ(moved.edgeWeightFactors().data(), shared->data());
    EXPECT_EQ(shared.use_count(), 3);  // this test, sharing, moved
    EXPECT_EQ(moved.edgeWeights(), copying.withReferencePoints(stretched).edgeWeights());
    // A factor that is not positive is refused as from the copying setter; null restores the plain weights.
    auto negative = std::make_shared<std::vector<double>>(factors);
    (*negative)[3] = -1.0;
    EXPECT_THROW(sharing.setEdgeWeightFactors(std::shared_ptr<const std::vector<double>>(negative)), std::invalid_argument);
    sharing.setEdgeWeightFactors(std::shared_ptr<const std::vector<double>>());
    EXPECT_TRUE(sharing.edgeWeightFactors().empty());
    // Released: the weights keep the factors, the problem no longer holds the array; a moved
    // copy (a sub-step's problem) takes them back out of the weights, to a few units in the
    // last place, and holds no array either.
    const std::vector<double> stiffened = copying.edgeWeights();
    RbmProblem releasing = copying;
    releasing.setEdgeWeightFactors(shared);
    releasing.releaseEdgeWeightFactors();
    EXPECT_TRUE(releasing.edgeWeightFactors().empty());
    EXPECT_EQ(shared.use_count(), 2);  // this test and moved; releasing let go of it
    EXPECT_EQ(releasing.edgeWeights(), stiffened);
    const std::vector<double> recovered = releasing.edgeWeightFactorsFromWeights();
    ASSERT_EQ(recovered.size(), factors.size());
    for (std::size_t e = 0; e < factors.size(); ++e) EXPECT_NEAR(recovered[e], factors[e], 4e-16 * factors[e]);
    const RbmProblem movedReleased = releasing.withReferencePoints(stretched);
    EXPECT_TRUE(movedReleased.edgeWeightFactors().empty());
    EXPECT_EQ(shared.use_count(), 2);
    const std::vector<double>& expected = moved.edgeWeights();
    ASSERT_EQ(movedReleased.edgeWeights().size(), expected.size());
    for (std::size_t e = 0; e < expected.size(); ++e)
        EXPECT_NEAR(movedReleased.edgeWeights()[e], expected[e], 1e-15 * expected[e]);
    const CellNeighbourGraph& g = releasing.graph();
    for (int i = 0; i < releasing.nodeCount(); ++i)  // symmetric, as the factors given
        for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
            const int j = g.neighbours[e];
            const auto row = g.neighboursOf(j);
            const auto reverse = g.offsets[j] + (std::lower_bound(row.begin(), row.end(), i) - row.begin());
            EXPECT_EQ(recovered[e], recovered[reverse]);
        }
    const RbmProblem plain(2, mesh.points, mesh.graph, prescribeBoundary(mesh), EdgeWeighting::inverseDistanceSquared);
    EXPECT_EQ(sharing.edgeWeights(), plain.edgeWeights());
}

TEST(RbmProblemInput, EdgeTransposeBlockIsThePositionOfTheReverseBlock)
{
    // Built at its first use (only the assembled Hessians need it): for every edge i → j
    // between unknowns, the position of block (j, i) in row index(j); −1 where either end is
    // prescribed. Copies of the problem give the same array.
    const TestMesh mesh = structuredGrid(6, 4, 1, 1.0, {0.0, 0.0, 0.0});
    const RbmProblem problem(2, mesh.points, mesh.graph, prescribeBoundary(mesh), EdgeWeighting::inverseDistanceSquared);
    const CellNeighbourGraph& graph = problem.graph();
    const BlockPattern& pattern = problem.blockPattern();
    const std::vector<int>& transpose = problem.edgeTransposeBlock();
    ASSERT_EQ(transpose.size(), graph.neighbours.size());
    int checked = 0;
    for (int i = 0; i < problem.nodeCount(); ++i)
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            const int a = problem.unknownIndex()[i], b = problem.unknownIndex()[j];
            if (a < 0 || b < 0) {
                EXPECT_EQ(transpose[e], -1);
                continue;
            }
            ASSERT_GE(transpose[e], pattern.rowOffsets[b]);
            ASSERT_LT(transpose[e], pattern.rowOffsets[b + 1]);
            EXPECT_EQ(pattern.columns[transpose[e]], a);
            EXPECT_EQ(pattern.columns[problem.edgeBlock()[e]], b);
            ++checked;
        }
    EXPECT_GT(checked, 20);
    const RbmProblem copy = problem;
    EXPECT_EQ(copy.edgeTransposeBlock(), transpose);
    // The symmetry is still checked when the problem is built: a graph whose node 8 lists
    // node 9 without the reverse is refused (both unknown, inside the boundary).
    TestMesh lopsided = mesh;
    const int from = 8, to = 9;
    ASSERT_GE(problem.unknownIndex()[from], 0);
    ASSERT_GE(problem.unknownIndex()[to], 0);
    std::vector<int>& neighbours = lopsided.graph.neighbours;
    const auto reverse = std::find(neighbours.begin() + lopsided.graph.offsets[to],
                                   neighbours.begin() + lopsided.graph.offsets[to + 1], from);
    ASSERT_NE(reverse, neighbours.begin() + lopsided.graph.offsets[to + 1]);
    neighbours.erase(reverse);
    for (std::size_t k = to + 1; k < lopsided.graph.offsets.size(); ++k) --lopsided.graph.offsets[k];
    try {
        const RbmProblem refused(2, lopsided.points, lopsided.graph, prescribeBoundary(mesh),
                                 EdgeWeighting::inverseDistanceSquared);
        ADD_FAILURE() << "a graph that is not symmetric was accepted";
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find("not symmetric (node 8 lists 9 but not the reverse)"), std::string::npos)
            << error.what();
    }
}

TEST(RbmProblemInput, AProblemWithoutUnknownsReturnsThePrescribedMotion)
{
    const TestMesh mesh = structuredGrid(3, 3, 1, 1.0, {0.0, 0.0, 0.0});
    const std::vector<NodeConstraint> constraints(mesh.points.size(), NodeConstraint{NodeKind::prescribed, {}});
    const RbmProblem problem(2, mesh.points, mesh.graph, constraints);
    const std::vector<Vector3> prescribed(mesh.points.size(), Vector3{0.5, -0.25, 0.0});
    for (const NamedFactory& variant : allVariants()) {
        const RbmResult result = variant.make(problem)->solve(prescribed);
        EXPECT_TRUE(result.converged) << variant.name;
        EXPECT_EQ(result.displacement, prescribed) << variant.name;
        EXPECT_EQ(result.energy, 0.0);
    }
}

TEST(RbmProblemInput, RejectsWhatCannotBeSolved)
{
    const TestMesh mesh = structuredGrid(4, 4, 1, 1.0, {0.0, 0.0, 0.0});
    const std::vector<NodeConstraint> constraints = prescribeBoundary(mesh);
    auto expectError = [](const std::function<void()>& build, const std::string& fragment) {
        try {
            build();
            ADD_FAILURE() << "accepted; expected an error containing '" << fragment << "'";
        } catch (const std::invalid_argument& error) {
            EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
        }
    };
    expectError([&] { RbmProblem(4, mesh.points, mesh.graph, constraints); }, "dimension must be 2 or 3");
    expectError([&] { RbmProblem(2, {mesh.points.begin(), mesh.points.end() - 1}, mesh.graph, constraints); },
                "reference points");
    std::vector<NodeConstraint> allFree(mesh.points.size());
    expectError([&] { RbmProblem(2, mesh.points, mesh.graph, allFree); }, "no prescribed neighbour");
    std::vector<NodeConstraint> zeroNormal = constraints;
    zeroNormal[1] = {NodeKind::sliding, Vector3{0.0, 0.0, 0.0}};
    expectError([&] { RbmProblem(2, mesh.points, mesh.graph, zeroNormal); }, "zero or invalid plane normal");
    std::vector<Vector3> collapsed = mesh.points;
    collapsed[5] = collapsed[6];
    expectError([&] { RbmProblem(2, collapsed, mesh.graph, constraints); }, "same position");
    expectError([] { (void)edgeWeightingFromName("cubic"); }, "Valid weightings are: uniform inverseDistance inverseDistanceSquared");
    const RbmProblem problem(2, mesh.points, mesh.graph, constraints);
    CoupledLinearizedSolver solver(problem);
    expectError([&] { (void)solver.solve(std::vector<Vector3>(3)); }, "one per node");
}

} // namespace
} // namespace rbm::motion
