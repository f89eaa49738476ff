#include "TransverseGradientPenalty.hpp"

#include "ReducedEnergy.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace rbm::motion {
namespace {

// A displacement near the top's large motion with random interior values, sliding nodes on
// their planes.
std::vector<Vector3> randomDisplacement(const RbmProblem& problem, const std::vector<Vector3>& prescribed,
                                        std::mt19937& random)
{
    std::uniform_real_distribution<double> value(-0.05, 0.05);
    const int dimension = problem.dimension();
    std::vector<Vector3> displacement = prescribed;
    for (int node : problem.unknownNodes()) {
        displacement[node] = 0.5 * prescribed[node] + Vector3{value(random), value(random), dimension == 3 ? value(random) : 0.0};
        if (problem.kind(node) == NodeKind::sliding) {
            const Vector3& n = problem.slidingNormal(node);
            displacement[node] -= (dot(displacement[node], n) - dot(prescribed[node], n)) * n;
        }
    }
    return displacement;
}

std::vector<Vector3> movedAlong(const RbmProblem& problem, std::vector<Vector3> u, const std::vector<double>& direction,
                                double step)
{
    const int dimension = problem.dimension();
    for (int a = 0; a < problem.unknownNodeCount(); ++a)
        for (int q = 0; q < dimension; ++q) u[problem.unknownNodes()[a]][q] += step * direction[a * dimension + q];
    return u;
}

TEST(TransverseGradientPenalty, GradientAndHessianMatchFiniteDifferencesAndTheHessianIsSymmetric)
{
    // (T3) against the slope of (T1) along a random direction, the Hessian product against the
    // difference of gradients, and uᵀ H v = vᵀ H u; 2D and 3D, a direction off the axes.
    for (int dimension : {2, 3}) {
        const GridCase c = gridCase(dimension, dimension == 2 ? 6 : 3, false, 5);
        const RbmProblem& problem = *c.problem;
        const std::vector<Vector3> prescribed = largeTopMotion(c);
        TransverseGradientPenalty penalty(problem, 7.0);
        penalty.setDirection(Vector3{1.0, 0.4, dimension == 3 ? -0.3 : 0.0});
        ASSERT_TRUE(penalty.active());
        std::mt19937 random(13);
        const std::vector<Vector3> displacement = randomDisplacement(problem, prescribed, random);
        const std::size_t size = static_cast<std::size_t>(problem.unknownNodeCount()) * dimension;
        auto gradientAt = [&](const std::vector<Vector3>& u) {
            std::vector<double> g(size, 0.0);
            penalty.addGradient(u, g);
            return g;
        };
        std::uniform_real_distribution<double> value(-1.0, 1.0);
        std::vector<double> direction(size), other(size);
        for (double& d : direction) d = value(random);
        for (double& d : other) d = value(random);
        const double h = 1e-4;
        const double slope = (penalty.energy(movedAlong(problem, displacement, direction, h)) -
                              penalty.energy(movedAlong(problem, displacement, direction, -h))) / (2.0 * h);
        const std::vector<double> gradient = gradientAt(displacement);
        double expectedSlope = 0.0;
        for (std::size_t k = 0; k < size; ++k) expectedSlope += gradient[k] * direction[k];
        EXPECT_GT(std::abs(expectedSlope), 1e-3) << dimension;
        EXPECT_NEAR(slope, expectedSlope, 1e-7 * std::abs(expectedSlope)) << dimension << "D";

        std::vector<double> hessianTimes(size, 0.0), otherTimes(size, 0.0);
        penalty.addHessianProduct(direction, hessianTimes);
        penalty.addHessianProduct(other, otherTimes);
        const std::vector<double> plus = gradientAt(movedAlong(problem, displacement, direction, h));
        const std::vector<double> minus = gradientAt(movedAlong(problem, displacement, direction, -h));
        double largest = 0.0, largestError = 0.0;
        for (std::size_t k = 0; k < size; ++k) {
            largest = std::max(largest, std::abs(hessianTimes[k]));
            largestError = std::max(largestError, std::abs((plus[k] - minus[k]) / (2.0 * h) - hessianTimes[k]));
        }
        EXPECT_GT(largest, 1e-2) << dimension;
        EXPECT_LT(largestError, 1e-8 * largest) << dimension << "D";
        double uHv = 0.0, vHu = 0.0, scale = 0.0;
        for (std::size_t k = 0; k < size; ++k) {
            uHv += other[k] * hessianTimes[k];
            vHu += direction[k] * otherTimes[k];
            scale += std::abs(other[k] * hessianTimes[k]);
        }
        EXPECT_LT(std::abs(uHv - vHu), 1e-12 * scale) << dimension << "D";
    }
}

TEST(TransverseGradientPenalty, ADisplacementThatVariesOnlyAlongTheMotionCostsNothing)
{
    // u = φ(x·m) m for an affine φ: a translation and a uniform compression along m, as the
    // columns ahead of a translating body shorten. Every neighbourhood fits it exactly with
    // g_i = φ' m, (T1); a shear (u along m varying across it) costs.
    for (int dimension : {2, 3}) {
        const GridCase c = gridCase(dimension, 5, false, 3);
        const RbmProblem& problem = *c.problem;
        const Vector3 m = dimension == 2 ? Vector3{0.6, 0.8, 0.0} : Vector3{0.6, 0.0, 0.8};
        TransverseGradientPenalty penalty(problem, 100.0);
        penalty.setDirection(3.0 * m);
        std::vector<Vector3> compressed(problem.nodeCount()), sheared(problem.nodeCount());
        for (int node = 0; node < problem.nodeCount(); ++node) {
            const Vector3& x = problem.referencePoints()[node];
            compressed[node] = (0.2 - 0.5 * dot(x, m)) * m;
            Vector3 across = dimension == 2 ? Vector3{-m.y, m.x, 0.0} : Vector3{0.0, 1.0, 0.0};
            sheared[node] = 0.1 * dot(x, across) * m;   // shear: u along m varying across it
        }
        // Zero to the rounding of Σ w |Δu|² − |b|²/A (each of order λ = 100 here).
        EXPECT_LT(penalty.energy(compressed), 1e-11) << dimension;
        EXPECT_GT(penalty.energy(sheared), 1e-3) << dimension;
        std::vector<double> g(static_cast<std::size_t>(problem.unknownNodeCount()) * dimension, 0.0);
        penalty.addGradient(compressed, g);
        for (double entry : g) EXPECT_LT(std::abs(entry), 1e-10) << dimension;  // rounding: λ c ~ 100 / h
        penalty.setDirection(Vector3{});
        EXPECT_FALSE(penalty.active());
        EXPECT_EQ(penalty.energy(sheared), 0.0);
    }
}

TEST(TransverseGradientPenalty, TheCommonTranslationIsFoundOnlyWhereEveryMovingPrescribedNodeMovesByItAndAppliesTowardsFixedWalls)
{
    const GridCase c = gridCase(2, 4, false, 1);
    const RbmProblem& problem = *c.problem;
    std::vector<Vector3> prescribed(problem.nodeCount());
    EXPECT_EQ(TransverseGradientPenalty::commonTranslation(problem, prescribed), Vector3{});  // no motion
    // The top translates, the bottom stays: the top's vector.
    int moving = 0;
    for (int node = 0; node < problem.nodeCount(); ++node)
        if (!problem.isUnknown(node) && problem.referencePoints()[node].y > 0.5) {
            prescribed[node] = Vector3{0.3, -0.1, 0.0};
            ++moving;
        }
    ASSERT_GT(moving, 1);
    EXPECT_EQ(TransverseGradientPenalty::commonTranslation(problem, prescribed), (Vector3{0.3, -0.1, 0.0}));
    // The fixed bottom (y = 0) runs along x: the penalty applies to a translation across it
    // (towards it) only, not to one with a component along it.
    EXPECT_EQ(TransverseGradientPenalty::translationTowardsFixedWalls(problem, prescribed), Vector3{});
    for (Vector3& u : prescribed)
        if (!(u == Vector3{})) u = Vector3{0.0, -0.1, 0.0};
    EXPECT_EQ(TransverseGradientPenalty::translationTowardsFixedWalls(problem, prescribed), (Vector3{0.0, -0.1, 0.0}));
    // One node moving otherwise (a turn, a deformation): none.
    for (int node = 0; node < problem.nodeCount(); ++node)
        if (!problem.isUnknown(node) && problem.referencePoints()[node].y > 0.5) {
            prescribed[node].x += 1e-3;
            break;
        }
    EXPECT_EQ(TransverseGradientPenalty::commonTranslation(problem, prescribed), Vector3{});
}

TEST(TransverseGradientPenalty, ReducedEnergyAddsThePenaltyAndItsDerivatives)
{
    // Ẽ + E_t through ReducedEnergy: its value, projected gradient and Hessian product are the
    // RBM energy's plus the penalty's (projected), in 2D and 3D.
    for (int dimension : {2, 3}) {
        const GridCase c = gridCase(dimension, dimension == 2 ? 6 : 3, false, 5);
        const RbmProblem& problem = *c.problem;
        const std::vector<Vector3> prescribed = largeTopMotion(c);
        ReducedEnergy plain(problem);
        ReducedEnergy with(problem, NeighbourhoodScaling{}, 5.0);
        const Vector3 m{1.0, 0.0, 0.0};
        EXPECT_TRUE(with.setTranslation(m));
        TransverseGradientPenalty penalty(problem, 5.0);
        penalty.setDirection(m);
        std::mt19937 random(17);
        const std::vector<Vector3> displacement = randomDisplacement(problem, prescribed, random);
        std::vector<Matrix3> rotations;
        const double expected = plain.fitAndEnergy(displacement, rotations) + penalty.energy(displacement);
        EXPECT_NEAR(with.fitAndEnergy(displacement, rotations), expected, 1e-12 * expected) << dimension;
        const std::size_t size = static_cast<std::size_t>(problem.unknownNodeCount()) * dimension;
        std::vector<double> gPlain(size), gWith(size), gPenalty(size, 0.0);
        plain.gradient(displacement, rotations, gPlain);
        with.gradient(displacement, rotations, gWith);
        penalty.addGradient(displacement, gPenalty);
        problem.projectSliding(gPenalty, dimension);
        for (std::size_t k = 0; k < size; ++k)
            EXPECT_NEAR(gWith[k], gPlain[k] + gPenalty[k], 1e-10 * (1.0 + std::abs(gWith[k]))) << dimension;
        std::vector<double> v(size), yPlain(size), yWith(size), yPenalty(size, 0.0);
        std::uniform_real_distribution<double> value(-1.0, 1.0);
        for (double& entry : v) entry = value(random);
        problem.projectSliding(v, dimension);
        plain.prepareHessian(displacement, rotations);
        with.prepareHessian(displacement, rotations);
        plain.applyHessian(v, yPlain);
        with.applyHessian(v, yWith);
        penalty.addHessianProduct(v, yPenalty);
        problem.projectSliding(yPenalty, dimension);
        for (std::size_t k = 0; k < size; ++k)
            EXPECT_NEAR(yWith[k], yPlain[k] + yPenalty[k], 1e-10 * (1.0 + std::abs(yWith[k]))) << dimension;
    }
}

} // namespace
} // namespace rbm::motion
