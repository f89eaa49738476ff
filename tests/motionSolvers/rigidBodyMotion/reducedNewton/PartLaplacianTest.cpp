// K⁻¹ on one rank's part (PartLaplacian) against the whole problem's factorised K⁻¹
// (LaplacianPreconditioner, direct): CTest runs this program under mpiexec with 1 to 4 ranks.
// The cycle is the default (two-level aggregation) unless a test says otherwise.
// The box's bottom and top are prescribed and its x-min side slides, so the solve is the
// projected vector system; solved to a relative tolerance of 1e-10, every owned row must
// equal the factorised solve's to 1e-8 of its largest entry.

#include "PetscTestEnvironment.hpp"

#include "BoxConstraints.hpp"
#include "DecomposedBox.hpp"
#include "LaplacianPreconditioner.hpp"
#include "MeshPart.hpp"
#include "PartLaplacian.hpp"
#include "PartProblem.hpp"
#include "ReducedLinearizedOperator.hpp"
#include "ScopedPetscOptions.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

using namespace rbm;
using namespace rbm::motion;
using rbm::test::DecomposedBox;

constexpr Label nx = 7, ny = 6, nz = 5;

std::vector<NodeConstraint> constraintsOf(const DecomposedBox& box) { return rbm::test::boxConstraints(box, Vector3{1.0, 0.2, 0.0}); }

using rbm::test::partConstraints;

Vector3 rightHandSideAt(const Vector3& x) { return {std::sin(4 * x.x + x.y), x.z - 0.3, std::cos(3 * x.y) * x.x}; }

std::vector<double> rightHandSide(const RbmProblem& problem)
{
    std::vector<double> r(3 * static_cast<std::size_t>(problem.unknownNodeCount()));
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        const Vector3 value = rightHandSideAt(problem.referencePoints()[problem.unknownNodes()[a]]);
        for (int q = 0; q < 3; ++q) r[3 * a + q] = value[q];
    }
    return r;
}

// This rank's part of the box split in blocks, with the box's constraints.
struct BlockPart {
    DecomposedBox box{nx, ny, nz, rbm::test::blockDecomposition(nx, ny)};
    MeshPart part{PETSC_COMM_WORLD, box.localCells(rbm::test::worldRank())};
    RbmProblem problem{partProblem(3, part, partConstraints(part, constraintsOf(box)))};
};

void checkPartAgainstWhole(const rbm::test::BoxDecomposition& decomposition)
{
    const DecomposedBox box(nx, ny, nz, decomposition);
    const std::vector<NodeConstraint> wholeConstraints = constraintsOf(box);
    const RbmProblem whole(3, box.mesh.points, box.graph, wholeConstraints);
    LaplacianPreconditioner factorised(whole, LinearSolverKind::direct, 1e-12);
    const std::vector<double> wholeRight = rightHandSide(whole);
    std::vector<double> expected(wholeRight.size());
    ASSERT_TRUE(factorised.apply(wholeRight, expected));

    const MeshPart part(PETSC_COMM_WORLD, box.localCells(rbm::test::worldRank()));
    const RbmProblem problem = partProblem(3, part, partConstraints(part, wholeConstraints));
    PartLaplacian laplacian(problem, coupledDisplacementLaplacian(problem), 1e-10, true);
    laplacian.setUp();  // the array above is a temporary: the matrix holds its copy
    const std::vector<double> right = rightHandSide(problem);
    std::vector<double> solution(right.size(), 1.0);
    ASSERT_TRUE(laplacian.apply(right, solution));
    EXPECT_GT(laplacian.lastIterations(), 0);

    double scale = 0.0;
    for (double value : expected) scale = std::max(scale, std::abs(value));
    ASSERT_GT(scale, 0.0);
    for (int a = 0; a < problem.ownedUnknownCount(); ++a) {
        const int wholeRow = whole.unknownIndex()[part.nodeGlobalIds()[problem.unknownNodes()[a]]];
        for (int q = 0; q < 3; ++q)
            EXPECT_NEAR(solution[3 * a + q], expected[3 * wholeRow + q], 1e-8 * scale)
                << "global point " << part.nodeGlobalIds()[problem.unknownNodes()[a]];
    }
    for (std::size_t k = 3 * static_cast<std::size_t>(problem.ownedUnknownCount()); k < solution.size(); ++k)
        EXPECT_EQ(solution[k], 0.0);
}

TEST(PartLaplacian, BlocksSolveAsTheWholeFactorisation) { checkPartAgainstWhole(rbm::test::blockDecomposition(nx, ny)); }

TEST(PartLaplacian, ScatteredCellsSolveAsTheWholeFactorisation)
{
    checkPartAgainstWhole(rbm::test::scatteredDecomposition);
}

TEST(PartLaplacian, WithGamgsCycleBlocksSolveAsTheWholeFactorisation)
{
    const ScopedPetscOptions gamg(std::vector<std::pair<std::string, std::string>>{{"-rbm_reduced_part_cycle", "gamg"}});
    checkPartAgainstWhole(rbm::test::blockDecomposition(nx, ny));
}

TEST(PartLaplacian, APreconditionerNamedForTheCycleIsPetscsOnPetscsK)
{
    // As tutorials/wing3D documents for a factorisation on ranks, with one application (no CG,
    // rbm's default): the factorisation needs PETSc's K as the cycle's operator, where rbm's
    // cycle would read its single-precision K (a shell PETSc cannot factorise).
    const ScopedPetscOptions factorisation(std::vector<std::pair<std::string, std::string>>{
        {"-rbm_reduced_cycle_pc_type", "cholesky"}, {"-rbm_reduced_cycle_pc_factor_mat_solver_type", "mumps"}});
    const BlockPart block;
    const RbmProblem& problem = block.problem;
    PartLaplacian laplacian(problem, coupledDisplacementLaplacian(problem), 1e-10, false);
    laplacian.setUp();
    const std::vector<double> right = rightHandSide(problem);
    std::vector<double> solution(right.size(), 1.0);
    ASSERT_TRUE(laplacian.apply(right, solution));
    for (double value : solution) ASSERT_TRUE(std::isfinite(value));
}

TEST(PartLaplacian, TheScalarSolveIsTheWholeFactorisationsOnEveryUnknownNodeGhostsIncluded)
{
    // s = K⁻¹ b (the turned start's harmonic share) by CG with the parts' cycle to 1e-12, against
    // the whole problem's factorised scalar solve (no sliding side: K alone). The CG multiplies by
    // K as the cycle reads it, in single precision: equal to 10⁻⁶ of the largest entry (measured
    // 6·10⁻⁸; a ghost without its owner's value would be off by the entry itself).
    const DecomposedBox box(nx, ny, nz, rbm::test::scatteredDecomposition);
    std::vector<NodeConstraint> wholeConstraints = constraintsOf(box);
    for (NodeConstraint& constraint : wholeConstraints)
        if (constraint.kind == NodeKind::sliding) constraint = NodeConstraint{};
    const RbmProblem whole(3, box.mesh.points, box.graph, wholeConstraints);
    LaplacianPreconditioner factorised(whole, LinearSolverKind::direct, 1e-12);
    ASSERT_TRUE(factorised.hasScalarSolve());
    std::vector<double> wholeRight, expected(static_cast<std::size_t>(whole.unknownNodeCount()));
    for (int a = 0; a < whole.unknownNodeCount(); ++a) wholeRight.push_back(rightHandSideAt(whole.referencePoints()[whole.unknownNodes()[a]]).x);
    ASSERT_TRUE(factorised.solveScalar(wholeRight, expected));

    const MeshPart part(PETSC_COMM_WORLD, box.localCells(rbm::test::worldRank()));
    const RbmProblem problem = partProblem(3, part, partConstraints(part, wholeConstraints));
    PartLaplacian laplacian(problem, coupledDisplacementLaplacian(problem), 1e-10, false);
    laplacian.setUp();
    ASSERT_TRUE(laplacian.hasScalarSolve());
    std::vector<double> right, solution(static_cast<std::size_t>(problem.unknownNodeCount()), 7.0);
    for (int a = 0; a < problem.unknownNodeCount(); ++a) right.push_back(rightHandSideAt(problem.referencePoints()[problem.unknownNodes()[a]]).x);
    ASSERT_TRUE(laplacian.solveScalar(right, solution, 1e-12, 200));
    double scale = 0.0;
    for (double value : expected) scale = std::max(scale, std::abs(value));
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        const int wholeRow = whole.unknownIndex()[part.nodeGlobalIds()[problem.unknownNodes()[a]]];
        EXPECT_NEAR(solution[a], expected[wholeRow], 1e-6 * scale) << (a < problem.ownedUnknownCount() ? "owned" : "ghost");
    }
}

TEST(PartLaplacian, TheRanksOwnCycleHasNoScalarSolve)
{
    const ScopedPetscOptions local(std::vector<std::pair<std::string, std::string>>{{"-rbm_reduced_part_cycle", "local"}});
    const BlockPart block;
    const RbmProblem& problem = block.problem;
    PartLaplacian laplacian(problem, coupledDisplacementLaplacian(problem), 1e-10, false);
    laplacian.setUp();
    EXPECT_FALSE(laplacian.hasScalarSolve());
}

TEST(PartLaplacian, AnUnknownCycleIsNamed)
{
    const ScopedPetscOptions wrong(std::vector<std::pair<std::string, std::string>>{{"-rbm_reduced_part_cycle", "jacobi"}});
    const BlockPart block;
    const RbmProblem& problem = block.problem;
    try {
        PartLaplacian laplacian(problem, coupledDisplacementLaplacian(problem), 1e-10, true);
        FAIL() << "no error";
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find("jacobi: expected aggregation, gamg or local"), std::string::npos)
            << error.what();
    }
}

TEST(PartLaplacian, NeedsAPart)
{
    const DecomposedBox box(nx, ny, nz, rbm::test::blockDecomposition(nx, ny));
    const RbmProblem whole(3, box.mesh.points, box.graph, constraintsOf(box));
    EXPECT_THROW(PartLaplacian(whole, coupledDisplacementLaplacian(whole), 1e-8, true), std::invalid_argument);
}

} // namespace
