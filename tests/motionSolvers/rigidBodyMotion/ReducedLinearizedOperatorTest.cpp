// Tests of the reduced linearized operator (ReducedLinearizedOperator) of the matrix-free coupled
// linearized solve.

#include "CoupledLinearizedSolver.hpp"
#include "TestCases.hpp"
#include "LocalGlobalSolver.hpp"
#include "MatrixFreeLinearizedSystem.hpp"
#include "PetscTestEnvironment.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"
#include "ReducedLinearizedOperator.hpp"
#include "ThreadCount.hpp"
#include "VectorInstructions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace rbm::motion {

namespace {

TEST(ReducedLinearizedOperator, GradientMatchesFiniteDifferencesOfTheReducedEnergy)
{
    for (int dimension : {2, 3}) {
        const GridCase c = gridCase(dimension, 4, true, 7);
        const RbmProblem& problem = *c.problem;
        const ReducedLinearizedOperator reduced(problem);
        const RbmEnergy energy(problem, RotationModel::smallAngle, c.prescribed);
        std::mt19937 random(3);
        std::uniform_real_distribution<double> value(-0.05, 0.05);
        std::vector<Vector3> displacement = c.prescribed;
        for (int node : problem.unknownNodes())
            displacement[node] = {value(random), value(random), dimension == 3 ? value(random) : 0.0};

        // E_reduced(u) = E(u, best ω(u)), evaluated through the full linearized energy.
        auto reducedEnergy = [&](const std::vector<Vector3>& u) {
            std::vector<Vector3> rotation(problem.nodeCount());
            reduced.bestRotations(u, rotation);
            std::vector<double> unknowns(problem.unknownCount());
            packUnknowns(problem, RbmState{u, rotation}, unknowns);
            return energy.value(unknowns);
        };
        std::vector<double> gradient(reduced.size());
        reduced.gradient(displacement, gradient);

        // The best rotations zero the rotation part of the full gradient, and the
        // displacement part equals the reduced gradient (envelope theorem).
        std::vector<Vector3> rotation(problem.nodeCount());
        reduced.bestRotations(displacement, rotation);
        std::vector<double> unknowns(problem.unknownCount()), fullGradient(problem.unknownCount());
        packUnknowns(problem, RbmState{displacement, rotation}, unknowns);
        energy.gradient(unknowns, fullGradient);
        const int bs = problem.blockSize();
        double largestRotationPart = 0.0, largestMismatch = 0.0, largestGradient = 0.0;
        for (int a = 0; a < problem.unknownNodeCount(); ++a) {
            const int node = problem.unknownNodes()[a];
            for (int q = dimension; q < bs; ++q) {
                double component = fullGradient[a * bs + q];
                // A mirror node's rotation is held to its normal (x): only that part must vanish.
                if (problem.rotatesAboutNormalOnly(node) && q != 3) component = 0.0;
                largestRotationPart = std::max(largestRotationPart, std::abs(component));
            }
            for (int q = 0; q < dimension; ++q) {
                largestMismatch = std::max(largestMismatch, std::abs(fullGradient[a * bs + q] - gradient[a * dimension + q]));
                largestGradient = std::max(largestGradient, std::abs(gradient[a * dimension + q]));
            }
            if (problem.rotatesAboutNormalOnly(node)) {
                EXPECT_EQ(rotation[node].y, 0.0);
                EXPECT_EQ(rotation[node].z, 0.0);
            }
        }
        EXPECT_GT(largestGradient, 1e-2) << dimension;
        EXPECT_LT(largestRotationPart, 1e-12 * largestGradient) << dimension;
        EXPECT_LT(largestMismatch, 1e-12 * largestGradient) << dimension;

        // Central differences are exact for a quadratic up to rounding.
        const double h = 1e-4;
        double largestError = 0.0;
        for (int a = 0; a < problem.unknownNodeCount(); a += 3) {
            for (int q = 0; q < dimension; ++q) {
                std::vector<Vector3> plus = displacement, minus = displacement;
                plus[problem.unknownNodes()[a]][q] += h;
                minus[problem.unknownNodes()[a]][q] -= h;
                const double difference = (reducedEnergy(plus) - reducedEnergy(minus)) / (2.0 * h);
                largestError = std::max(largestError, std::abs(difference - gradient[a * dimension + q]));
            }
        }
        EXPECT_LT(largestError, 1e-7 * largestGradient) << dimension;
    }
}

} // namespace
} // namespace rbm::motion
