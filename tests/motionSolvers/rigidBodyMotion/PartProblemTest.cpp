// The RBM problem of one rank's part (PartProblem) and the reduced energy evaluated on it
// (ReducedEnergy, ReducedHessian3D, fitNodeRotations on a part) against the whole problem:
// CTest runs this program under mpiexec with 1 to 4 ranks. The box's bottom is fixed, its
// top turned, its x-min side slides; the displacements of the other nodes are a smooth
// field. Each rank's energy summed over the ranks, and its owned rows of the gradient and of
// the reduced Hessian's product, must equal the whole problem's to rounding; the ghosts'
// entries of the product's input are NaN, so a ghost value that is not fetched from its owner
// shows.

#include "PetscTestEnvironment.hpp"

#include "BoxConstraints.hpp"
#include "DecomposedBox.hpp"
#include "LaplacianPreconditioner.hpp"
#include "MeshPart.hpp"
#include "PartProblem.hpp"
#include "ReducedEnergy.hpp"
#include "ReducedNewtonSolver.hpp"
#include "TurnedStart.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace {

using namespace rbm;
using namespace rbm::motion;
using rbm::test::DecomposedBox;

constexpr Label nx = 6, ny = 5, nz = 4;

std::vector<NodeConstraint> constraintsOf(const DecomposedBox& box) { return rbm::test::boxConstraints(box, Vector3{1.0, 0.0, 0.0}); }

// The top turned 25° about the vertical axis through the box's centre, faded down the height,
// with a ripple: a state far from the rest state, so the rotation fits matter.
Vector3 displacementAt(const Vector3& x)
{
    const double angle = 25.0 * M_PI / 180.0 * x.z / 0.8;
    const double dx = x.x - 0.6, dy = x.y - 0.5;
    return {std::cos(angle) * dx - std::sin(angle) * dy - dx + 0.02 * std::sin(5 * x.y),
            std::sin(angle) * dx + std::cos(angle) * dy - dy, 0.03 * std::sin(4 * x.x) * x.z};
}

Vector3 directionAt(const Vector3& x) { return {std::cos(3 * x.y + x.z), x.x * x.z, std::sin(2 * x.x) - x.y}; }

struct Evaluation {
    double energy = 0.0;
    double roundingLevel = 0.0;
    std::vector<double> gradient, product;  // 3 per unknown node
};

// E, P∇Ẽ, P S P v and the rounding level on `problem` at the displacements of displacementAt;
// v = directionAt at the unknown nodes, NaN at the ghosts'.
Evaluation evaluate(const RbmProblem& problem)
{
    ReducedEnergy energy(problem);
    std::vector<Vector3> u;
    for (const Vector3& x : problem.referencePoints()) u.push_back(displacementAt(x));
    std::vector<Matrix3> rotations;
    Evaluation result;
    result.energy = energy.fitAndEnergy(u, rotations);
    result.gradient.assign(3 * static_cast<std::size_t>(problem.unknownNodeCount()), 0.0);
    energy.gradient(u, rotations, result.gradient);
    energy.prepareHessian(u, rotations);
    std::vector<double> v(result.gradient.size(), std::numeric_limits<double>::quiet_NaN());
    for (int a = 0; a < problem.ownedUnknownCount(); ++a) {
        const Vector3 d = directionAt(problem.referencePoints()[problem.unknownNodes()[a]]);
        for (int q = 0; q < 3; ++q) v[3 * a + q] = d[q];
    }
    result.product.assign(v.size(), 0.0);
    energy.applyHessian(v, result.product);
    result.roundingLevel = energy.gradientRoundoffNorm(u);
    return result;
}

double largestMagnitude(const std::vector<double>& values)
{
    double largest = 0.0;
    for (double value : values) largest = std::max(largest, std::abs(value));
    return largest;
}

void checkPartAgainstWhole(const rbm::test::BoxDecomposition& decomposition)
{
    const DecomposedBox box(nx, ny, nz, decomposition);
    const std::vector<NodeConstraint> wholeConstraints = constraintsOf(box);
    const RbmProblem whole(3, box.mesh.points, box.graph, wholeConstraints);
    const Evaluation expected = evaluate(whole);

    const MeshPart part(PETSC_COMM_WORLD, box.localCells(rbm::test::worldRank()));
    const RbmProblem problem = partProblem(3, part, rbm::test::partConstraints(part, wholeConstraints));
    ASSERT_TRUE(problem.isPart());
    ASSERT_EQ(problem.ownedNodeCount(), part.ownedNodeCount());
    const Evaluation evaluated = evaluate(problem);

    EXPECT_NEAR(evaluated.energy, expected.energy, 1e-13 * expected.energy);
    EXPECT_NEAR(evaluated.roundingLevel, expected.roundingLevel, 1e-12 * expected.roundingLevel);
    const double gradientScale = largestMagnitude(expected.gradient);
    const double productScale = largestMagnitude(expected.product);
    ASSERT_GT(gradientScale, 0.0);
    ASSERT_GT(productScale, 0.0);
    for (int a = 0; a < problem.ownedUnknownCount(); ++a) {
        const Label g = part.nodeGlobalIds()[problem.unknownNodes()[a]];
        const int wholeRow = whole.unknownIndex()[g];
        ASSERT_GE(wholeRow, 0);
        for (int q = 0; q < 3; ++q) {
            EXPECT_NEAR(evaluated.gradient[3 * a + q], expected.gradient[3 * wholeRow + q], 1e-13 * gradientScale)
                << "global point " << g;
            EXPECT_NEAR(evaluated.product[3 * a + q], expected.product[3 * wholeRow + q], 1e-13 * productScale)
                << "global point " << g;
        }
    }
    for (std::size_t k = 3 * static_cast<std::size_t>(problem.ownedUnknownCount()); k < evaluated.product.size(); ++k) {
        EXPECT_EQ(evaluated.gradient[k], 0.0);
        EXPECT_EQ(evaluated.product[k], 0.0);
    }
}

TEST(PartProblem, BlocksEvaluateAsTheWholeProblem) { checkPartAgainstWhole(rbm::test::blockDecomposition(nx, ny)); }

TEST(PartProblem, ScatteredCellsEvaluateAsTheWholeProblem)
{
    checkPartAgainstWhole(rbm::test::scatteredDecomposition);
}

// The prescribed displacements of a turn of the top by `degrees` (the bottom as displacementAt
// has it, nearly zero), one per node of `problem`.
std::vector<Vector3> turnedTop(const RbmProblem& problem, double degrees)
{
    std::vector<Vector3> prescribed;
    for (const Vector3& x : problem.referencePoints()) prescribed.push_back(degrees / 25.0 * displacementAt(x));
    return prescribed;
}

// The box's top turned rigidly by `degrees` about the vertical axis through its centre, its
// bottom fixed, every other node free (no sliding side): where the turned start applies.
std::vector<NodeConstraint> lidConstraints(const DecomposedBox& box)
{
    std::vector<NodeConstraint> constraints = constraintsOf(box);
    for (NodeConstraint& constraint : constraints)
        if (constraint.kind == NodeKind::sliding) constraint = NodeConstraint{};
    return constraints;
}

std::vector<Vector3> turnedLid(const RbmProblem& problem, double degrees)
{
    const double angle = degrees * M_PI / 180.0;
    std::vector<Vector3> prescribed;
    for (const Vector3& x : problem.referencePoints()) {
        const double dx = x.x - 0.6, dy = x.y - 0.5;
        prescribed.push_back(x.z > 0.4 ? Vector3{std::cos(angle) * dx - std::sin(angle) * dy - dx,
                                                 std::sin(angle) * dx + std::cos(angle) * dy - dy, 0.0}
                                       : Vector3{});
    }
    return prescribed;
}

// The box's constraints and the prescribed displacements of a turn by some degrees.
using Constraints = std::vector<NodeConstraint> (*)(const DecomposedBox&);
using Motion = std::vector<Vector3> (*)(const RbmProblem&, double);

// The reduced Newton solver on the parts ends where it ends on the whole problem: a cold solve
// of the top turned by the first angle and a warm one (from it) turned by the second, within
// 1e-6 of the shortest edge.
void checkSolveAgainstWhole(const rbm::test::BoxDecomposition& decomposition, Constraints constraintsOfBox,
                            Motion motion, std::array<double, 2> angles, bool lastRankOwnsNoUnknown = false)
{
    const DecomposedBox box(nx, ny, nz, decomposition);
    const std::vector<NodeConstraint> wholeConstraints = constraintsOfBox(box);
    const RbmProblem whole(3, box.mesh.points, box.graph, wholeConstraints);
    const MeshPart part(PETSC_COMM_WORLD, box.localCells(rbm::test::worldRank()));
    const RbmProblem problem = partProblem(3, part, rbm::test::partConstraints(part, wholeConstraints));
    if (lastRankOwnsNoUnknown && rbm::test::worldSize() > 1 && rbm::test::worldRank() == rbm::test::worldSize() - 1) {
        EXPECT_EQ(problem.ownedUnknownCount(), 0);
        EXPECT_GT(problem.unknownNodeCount(), 0) << "its ghosts";
    }
    ReducedNewtonOptions options;
    options.displacementTolerance = 1e-9;
    options.laplacianRelativeTolerance = 1e-6;
    ReducedNewtonSolver wholeSolver(whole, options);
    ReducedNewtonSolver partSolver(problem, options);
    RbmResult wholeResult, partResult;
    for (double degrees : angles) {
        const bool warm = degrees > angles[0];
        wholeResult = wholeSolver.solve(motion(whole, degrees), warm ? &wholeResult : nullptr);
        partResult = partSolver.solve(motion(problem, degrees), warm ? &partResult : nullptr);
        ASSERT_TRUE(wholeResult.converged) << wholeResult.reason;
        ASSERT_TRUE(partResult.converged) << partResult.reason;
        EXPECT_GE(partResult.iterations, 1);
        EXPECT_NEAR(partResult.energy, wholeResult.energy, 1e-6 * wholeResult.energy);
        double largestMiss = 0.0, moved = 0.0;
        for (Label node = 0; node < part.nodeCount(); ++node) {
            const Label g = part.nodeGlobalIds()[node];
            largestMiss = std::max(largestMiss, norm(partResult.displacement[node] - wholeResult.displacement[g]) /
                                                    whole.shortestNeighbourDistance(g));
            moved = std::max(moved, norm(wholeResult.displacement[g]));
        }
        EXPECT_LT(largestMiss, 1e-6) << degrees << "°";
        EXPECT_GT(moved, 0.1) << "the interior moves";
    }
}

TEST(PartProblem, ReducedNewtonOnThePartsEndsAsOnTheWholeProblem)
{
    checkSolveAgainstWhole(rbm::test::blockDecomposition(nx, ny), constraintsOf, turnedTop, {25.0, 35.0});
}

TEST(PartProblem, ReducedNewtonOnScatteredPartsEndsAsOnTheWholeProblem)
{
    checkSolveAgainstWhole(rbm::test::scatteredDecomposition, constraintsOf, turnedTop, {25.0, 35.0});
}

// A rank that owns no unknown node takes part in every collective step all the same.
TEST(PartProblem, ReducedNewtonWithARankWithoutUnknownsEndsAsOnTheWholeProblem)
{
    checkSolveAgainstWhole(rbm::test::topLayerDecomposition(nx, nz), constraintsOf, turnedTop, {25.0, 35.0}, true);
}

TEST(PartProblem, TheTurnedStartOnThePartsIsTheWholeProblems)
{
    // The lid's motion is fitted from sums over the ranks and the harmonic share solved by the
    // parts' cycle (to 10⁻² of its right-hand side, as the serial cycle's): every unknown node's
    // start, ghosts included, is the whole problem's (factorised) to that share's accuracy.
    const DecomposedBox box(nx, ny, nz, rbm::test::scatteredDecomposition);
    const std::vector<NodeConstraint> wholeConstraints = lidConstraints(box);
    const RbmProblem whole(3, box.mesh.points, box.graph, wholeConstraints);
    const MeshPart part(PETSC_COMM_WORLD, box.localCells(rbm::test::worldRank()));
    const RbmProblem problem = partProblem(3, part, rbm::test::partConstraints(part, wholeConstraints));
    LaplacianPreconditioner wholeInverse(whole, LinearSolverKind::direct, 1e-12);
    LaplacianPreconditioner partInverse(problem, LinearSolverKind::automatic, 1e-6);
    std::vector<Vector3> wholeStart(static_cast<std::size_t>(whole.nodeCount())), partStart(static_cast<std::size_t>(problem.nodeCount()));
    ASSERT_TRUE(turnedHarmonicStart(whole, wholeInverse, turnedLid(whole, 30.0), wholeStart));
    ASSERT_TRUE(turnedHarmonicStart(problem, partInverse, turnedLid(problem, 30.0), partStart));
    double largest = 0.0, miss = 0.0;
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        const int node = problem.unknownNodes()[a];
        const Vector3& expected = wholeStart[part.nodeGlobalIds()[node]];
        largest = std::max(largest, norm(expected));
        miss = std::max(miss, norm(partStart[node] - expected));
    }
    largest = problem.maximumOverRanks(largest);
    EXPECT_GT(largest, 0.05) << "the interior turns";
    EXPECT_LT(miss, 0.02 * largest);
    // Not one rigid motion: refused on every rank alike.
    std::vector<Vector3> bent = turnedLid(problem, 30.0);
    for (int node = 0; node < problem.nodeCount(); ++node) {
        const Vector3& x = problem.referencePoints()[node];
        if (x.z > 0.4) bent[node].z += 1e-2 * x.x * x.x;  // the lid bent along x
    }
    EXPECT_FALSE(turnedHarmonicStart(problem, partInverse, bent, partStart));
}

TEST(PartProblem, ReducedNewtonOnThePartsEndsAsOnTheWholeProblemWithTheTurnedStart)
{
    // The lid turned 30° cold, 45° warm, the sides free: the parts may start turned as the whole
    // problem does (every rank taking the same choice), and end where it does.
    checkSolveAgainstWhole(rbm::test::blockDecomposition(nx, ny), lidConstraints, turnedLid, {30.0, 45.0});
}

TEST(PartProblem, ConstraintsMustCoverEveryNode)
{
    const DecomposedBox box(nx, ny, nz, rbm::test::blockDecomposition(nx, ny));
    const MeshPart part(PETSC_COMM_WORLD, box.localCells(rbm::test::worldRank()));
    EXPECT_THROW(partProblem(3, part, std::vector<NodeConstraint>(1)), std::invalid_argument);
}

} // namespace
