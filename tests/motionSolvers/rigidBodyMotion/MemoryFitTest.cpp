// Tests of fitSolveIntoMemory against MemoryEstimate.hpp's model, figures derived by hand.
#include "MemoryFit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace rbm::motion {
namespace {

// An 8 × 8 square in 2D with its left and right sides prescribed: 63 unknown nodes (189 rows),
// 63 + 2 × 206 = 475 blocks (each node and its unknown neighbours through the quads).
SolveSize squareSize()
{
    SolveSize size;
    size.dimension = 2;
    size.unknownNodes = 63;
    size.blocks = 475;
    return size;
}

TEST(MemoryFit, AutomaticGoesMatrixFreeWhenOnlyThatFits)
{
    RigidBodyMotionOptions options;
    options.formulation = RbmFormulation::linearized;
    options.subSteps = 1;
    // Direct: 130 × 189 × log2(189) bytes = 181.4 KiB; matrix-free: 40 × 475 + 400 × 63 = 44 200 bytes.
    const double direct = 130.0 * 189.0 * std::log2(189.0);
    EXPECT_TRUE(fitSolveIntoMemory(options, squareSize(), {direct + 1.0, "test"}).note.empty());
    const MemoryFit fit = fitSolveIntoMemory(options, squareSize(), {102.4 * 1024.0, "test"});
    ASSERT_TRUE(fit.linearSolver);
    EXPECT_EQ(*fit.linearSolver, LinearSolverKind::matrixFree);
    EXPECT_EQ(fit.note, "the direct factorisation would need about 181.4 KiB, only 102.4 KiB is available (test): "
                        "solving matrix-free (linearSolver matrixFree, about 43.2 KiB)");
}

TEST(MemoryFit, NothingFitsStopsWithWhatItNeedsAndAChoiceTheUserMadeStands)
{
    RigidBodyMotionOptions newton;
    newton.algorithm = RbmAlgorithm::newton;
    // Newton keeps its Hessian's LU beside the factor: 2.3 × 181.4 KiB = 417.3 KiB.
    try {
        (void)fitSolveIntoMemory(newton, squareSize(), {256.0 * 1024.0, "test"});
        FAIL() << "expected the solve not to fit";
    } catch (const std::runtime_error& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("the solve needs about 417.3 KiB of memory, but only 256.0 KiB is available (test)"),
                  std::string::npos)
            << message;
        EXPECT_NE(message.find("direct factorisation of 189 unknowns (63 nodes in 2D)"), std::string::npos) << message;
    }
    RigidBodyMotionOptions direct;
    direct.formulation = RbmFormulation::linearized;
    direct.subSteps = 1;
    direct.linearSolver = LinearSolverKind::direct;
    EXPECT_THROW((void)fitSolveIntoMemory(direct, squareSize(), {102.4 * 1024.0, "test"}), std::runtime_error);
}

} // namespace
} // namespace rbm::motion
