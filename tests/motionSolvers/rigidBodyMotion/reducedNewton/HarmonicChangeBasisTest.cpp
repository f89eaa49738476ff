#include "HarmonicChangeBasis.hpp"

#include "OrderedSums.hpp"
#include "PetscTestEnvironment.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace rbm::motion {
namespace {

TEST(HarmonicChangeBasis, ACombinationOfRememberedChangesNeedsNoSolveAndANewOneDoes)
{
    const GridCase c = withFreeSides(gridCase(2, 6, false, 3));
    const RbmProblem& problem = *c.problem;
    LaplacianPreconditioner preconditioner(problem, LinearSolverKind::automatic, 1e-4);
    ASSERT_TRUE(preconditioner.isFixedLinearMap());
    HarmonicChangeBasis basis(problem, preconditioner, true);
    const std::vector<Vector3> rest(c.points.size());
    std::vector<double> boundaryChange, correction;
    // A new change: declined, then remembered with its solved extension (any vector will do here).
    ASSERT_FALSE(basis.correctionFromBasis(c.prescribed, rest, boundaryChange, correction));
    ASSERT_FALSE(boundaryChange.empty());
    std::vector<double> extension(static_cast<std::size_t>(problem.unknownNodeCount()) * 2);
    for (std::size_t k = 0; k < extension.size(); ++k) extension[k] = 1.0 + static_cast<double>(k % 7);
    basis.remember(boundaryChange, extension);
    EXPECT_EQ(basis.size(), 1u);
    // Twice the change: twice the extension, from the basis.
    std::vector<Vector3> twice = c.prescribed;
    for (Vector3& v : twice) v = 2.0 * v;
    ASSERT_TRUE(basis.correctionFromBasis(twice, rest, boundaryChange, correction));
    for (std::size_t k = 0; k < extension.size(); ++k) EXPECT_NEAR(correction[k], 2.0 * extension[k], 1e-12 * extension[k]);
    EXPECT_EQ(basis.correctionsFromBasis(), 1);
    // A change outside the basis: declined.
    std::vector<Vector3> other = c.prescribed;
    for (std::size_t node = 0; node < other.size(); ++node)
        if (!problem.isUnknown(static_cast<int>(node))) other[node].y += c.points[node].x;
    EXPECT_FALSE(basis.correctionFromBasis(other, rest, boundaryChange, correction));
    // Disabled: always declined.
    HarmonicChangeBasis off(problem, preconditioner, false);
    EXPECT_FALSE(off.correctionFromBasis(c.prescribed, rest, boundaryChange, correction));
}

} // namespace
} // namespace rbm::motion
