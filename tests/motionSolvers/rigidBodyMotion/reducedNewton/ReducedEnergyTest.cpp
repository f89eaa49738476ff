#include "ReducedEnergy.hpp"

#include "TestCases.hpp"
#include "LocalGlobalSolver.hpp"
#include "PetscTestEnvironment.hpp"
#include "VectorInstructions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace rbm::motion {
namespace {

double energyAt(const ReducedEnergy& energy, const std::vector<Vector3>& displacement)
{
    std::vector<Matrix3> rotations;
    return energy.fitAndEnergy(displacement, rotations);
}

// P∇Ẽ at u (compact).
std::vector<double> gradientAt(const ReducedEnergy& energy, const std::vector<Vector3>& displacement,
                               const RbmProblem& problem)
{
    std::vector<Matrix3> rotations;
    energy.fitAndEnergy(displacement, rotations);
    std::vector<double> g(static_cast<std::size_t>(problem.unknownNodeCount()) * problem.dimension());
    energy.gradient(displacement, rotations, g);
    return g;
}

// P S P v at u (compact).
std::vector<double> hessianProduct(ReducedEnergy& energy, const std::vector<Vector3>& displacement,
                                   const std::vector<double>& direction)
{
    std::vector<Matrix3> rotations;
    energy.fitAndEnergy(displacement, rotations);
    energy.prepareHessian(displacement, rotations);
    std::vector<double> y(direction.size());
    energy.applyHessian(direction, y);
    return y;
}

// The largest |S v| and the largest difference between S v and the central difference of the
// gradients at u ± h v.
std::pair<double, double> hessianAgainstGradientDifferences(const std::vector<double>& hessianTimes,
                                                            const std::vector<double>& plus,
                                                            const std::vector<double>& minus, double h)
{
    double largest = 0.0, largestError = 0.0;
    for (std::size_t k = 0; k < hessianTimes.size(); ++k) {
        largest = std::max(largest, std::abs(hessianTimes[k]));
        largestError = std::max(largestError, std::abs((plus[k] - minus[k]) / (2.0 * h) - hessianTimes[k]));
    }
    return {largest, largestError};
}

TEST(ReducedEnergy, GradientAndHessianMatchFiniteDifferencesOfTheReducedEnergy)
{
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, false}, {3, true}}) {
        const GridCase c = gridCase(dimension, 4, mirror, 5);
        const RbmProblem& problem = *c.problem;
        const std::vector<Vector3> prescribed = largeTopMotion(c);
        ReducedEnergy energy(problem);
        std::mt19937 random(9);
        std::uniform_real_distribution<double> value(-0.05, 0.05);
        std::vector<Vector3> displacement = prescribed;
        for (int node : problem.unknownNodes()) {
            displacement[node] = 0.5 * prescribed[node] +
                                 Vector3{value(random), value(random), dimension == 3 ? value(random) : 0.0};
            if (problem.kind(node) == NodeKind::sliding) {  // onto its plane: u·n = c
                const Vector3& n = problem.slidingNormal(node);
                displacement[node] -= (dot(displacement[node], n) - dot(prescribed[node], n)) * n;
            }
        }
        const std::vector<double> gradient = gradientAt(energy, displacement, problem);
        // The slope of Ẽ along a random (projected) direction.
        std::vector<double> direction(gradient.size());
        for (double& d : direction) d = value(random);
        problem.projectSliding(direction, dimension);
        auto moved = [&](double step) {
            std::vector<Vector3> u = displacement;
            for (int a = 0; a < problem.unknownNodeCount(); ++a)
                for (int q = 0; q < dimension; ++q) u[problem.unknownNodes()[a]][q] += step * direction[a * dimension + q];
            return u;
        };
        const double h = 1e-5;
        const double slope = (energyAt(energy, moved(h)) - energyAt(energy, moved(-h))) / (2.0 * h);
        double expectedSlope = 0.0;
        for (std::size_t k = 0; k < gradient.size(); ++k) expectedSlope += gradient[k] * direction[k];
        EXPECT_GT(std::abs(expectedSlope), 1e-3) << dimension;
        EXPECT_NEAR(slope, expectedSlope, 1e-6 * std::abs(expectedSlope)) << dimension << "D mirror " << mirror;

        // S v against the difference of gradients (∇²Ẽ = the Schur complement, file comment).
        const std::vector<double> hessianTimes = hessianProduct(energy, displacement, direction);
        const auto [largest, largestError] = hessianAgainstGradientDifferences(
            hessianTimes, gradientAt(energy, moved(h), problem), gradientAt(energy, moved(-h), problem), h);
        EXPECT_GT(largest, 1e-2) << dimension;
        EXPECT_LT(largestError, 1e-5 * largest) << dimension << "D mirror " << mirror;
    }
}

TEST(ReducedEnergy, WithScalingGradientAndHessianMatchFiniteDifferencesAndStaySymmetric)
{
    // Neighbourhoods that scale (NeighbourhoodScaling.hpp), 2D: ∇Ẽ against the slope of Ẽ and
    // S v against the difference of gradients, for a free scale (similar) and a stiff one.
    const GridCase c = gridCase(2, 6, false, 5);
    const RbmProblem& problem = *c.problem;
    const std::vector<Vector3> prescribed = largeTopMotion(c);
    for (double stiffness : {0.0, 0.5}) {
        ReducedEnergy energy(problem, NeighbourhoodScaling{stiffness});
        std::mt19937 random(11);
        std::uniform_real_distribution<double> value(-0.05, 0.05);
        std::vector<Vector3> displacement = prescribed;
        for (int node : problem.unknownNodes()) {
            displacement[node] = 0.5 * prescribed[node] + Vector3{value(random), value(random), 0.0};
            if (problem.kind(node) == NodeKind::sliding) {
                const Vector3& n = problem.slidingNormal(node);
                displacement[node] -= (dot(displacement[node], n) - dot(prescribed[node], n)) * n;
            }
        }
        // The scaled energy is below the rigid one (the rigid fit is one of its candidates).
        EXPECT_LT(energyAt(energy, displacement), energyAt(ReducedEnergy(problem), displacement));
        const std::vector<double> gradient = gradientAt(energy, displacement, problem);
        std::vector<double> direction(gradient.size());
        for (double& d : direction) d = value(random);
        problem.projectSliding(direction, 2);
        auto moved = [&](double step) {
            std::vector<Vector3> u = displacement;
            for (int a = 0; a < problem.unknownNodeCount(); ++a)
                for (int q = 0; q < 2; ++q) u[problem.unknownNodes()[a]][q] += step * direction[a * 2 + q];
            return u;
        };
        const double h = 1e-5;
        const double slope = (energyAt(energy, moved(h)) - energyAt(energy, moved(-h))) / (2.0 * h);
        double expectedSlope = 0.0;
        for (std::size_t k = 0; k < gradient.size(); ++k) expectedSlope += gradient[k] * direction[k];
        EXPECT_GT(std::abs(expectedSlope), 1e-3);
        EXPECT_NEAR(slope, expectedSlope, 1e-6 * std::abs(expectedSlope)) << "stiffness " << stiffness;

        const std::vector<double> hessianTimes = hessianProduct(energy, displacement, direction);
        const auto [largest, largestError] = hessianAgainstGradientDifferences(
            hessianTimes, gradientAt(energy, moved(h), problem), gradientAt(energy, moved(-h), problem), h);
        EXPECT_GT(largest, 1e-2);
        // S's per-edge data are single precision (PlanarReducedKernels.hpp): 1e-6 relative.
        EXPECT_LT(largestError, 1e-5 * largest) << "stiffness " << stiffness;

        std::vector<double> other(direction.size());
        for (double& d : other) d = value(random);
        const std::vector<double> otherTimes = hessianProduct(energy, displacement, other);
        double uSv = 0.0, vSu = 0.0, scale = 0.0;
        for (std::size_t k = 0; k < other.size(); ++k) {
            uSv += other[k] * hessianTimes[k];
            vSu += direction[k] * otherTimes[k];
            scale += std::abs(other[k] * hessianTimes[k]);
        }
        EXPECT_LT(std::abs(uSv - vSu), 1e-12 * scale) << "stiffness " << stiffness;
    }
}

TEST(ReducedEnergy, HessianIsSymmetric)
{
    // CG needs uᵀ S v = vᵀ S u. In 2D S's per-edge data are kept in single precision (w q of
    // edge a→j and w q_back of edge j→a are the same product rounded the same way), so the
    // products stay symmetric to double round-off, not just to single precision.
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, false}, {3, true}}) {
        const GridCase c = gridCase(dimension, dimension == 2 ? 10 : 4, mirror, 7);
        const RbmProblem& problem = *c.problem;
        const std::vector<Vector3> prescribed = largeTopMotion(c);
        ReducedEnergy energy(problem);
        std::vector<Vector3> displacement = prescribed;
        for (int node : problem.unknownNodes()) displacement[node] = 0.5 * prescribed[node];
        std::mt19937 random(3);
        std::uniform_real_distribution<double> value(-1.0, 1.0);
        const std::size_t size = static_cast<std::size_t>(problem.unknownNodeCount()) * dimension;
        std::vector<double> u(size), v(size);
        for (double& entry : u) entry = value(random);
        for (double& entry : v) entry = value(random);
        const std::vector<double> su = hessianProduct(energy, displacement, u);
        const std::vector<double> sv = hessianProduct(energy, displacement, v);
        double uSv = 0.0, vSu = 0.0, scale = 0.0;
        for (std::size_t k = 0; k < size; ++k) {
            uSv += u[k] * sv[k];
            vSu += v[k] * su[k];
            scale += std::abs(u[k] * sv[k]);
        }
        EXPECT_GT(std::abs(uSv), 1e-3 * scale) << dimension;
        EXPECT_LT(std::abs(uSv - vSu), 1e-12 * scale) << dimension << "D mirror " << mirror;
    }
}

// (S v)_k in 3D by the per-edge formulas of ReducedNewtonSolver.hpp's file comment, written out
// plainly (no per-node shortcuts): y_i = H_δδ,i⁻¹ Σ_j w q_ij × (v_j − v_i), q = R_i d,
// (S v)_k = Σ_j w [(1 + t_j)(v_k − v_j) + y_k × R_k d + t_j y_j × R_j d], projected onto the
// sliding planes. No mirror nodes (their rotation is restricted to the normal).
std::vector<double> hessianTimesByEdges(const RbmProblem& problem, const std::vector<Vector3>& displacement,
                                        const std::vector<double>& direction)
{
    std::vector<Matrix3> rotations;
    fitNodeRotations(problem, displacement, rotations);
    const CellNeighbourGraph& graph = problem.graph();
    const std::vector<Vector3>& x = problem.referencePoints();
    const std::vector<int>& nodes = problem.unknownNodes();
    std::vector<Vector3> v(problem.nodeCount()), y(problem.nodeCount());
    for (std::size_t a = 0; a < nodes.size(); ++a) v[nodes[a]] = {direction[3 * a], direction[3 * a + 1], direction[3 * a + 2]};
    for (int i : nodes) {
        Matrix3 h;
        Vector3 b{};
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            const double w = problem.edgeWeights()[e];
            const Vector3 d = x[j] - x[i];
            const Vector3 edge = d + displacement[j] - displacement[i];
            const Vector3 q = rotations[i] * d;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    h.m[r][c] += w * ((r == c ? dot(q, edge) : 0.0) - 0.5 * (edge[r] * q[c] + q[r] * edge[c]));
            b += w * cross(q, v[j] - v[i]);
        }
        // y = H⁻¹ b by Cramer's rule.
        const Vector3 c0{h.m[0][0], h.m[1][0], h.m[2][0]}, c1{h.m[0][1], h.m[1][1], h.m[2][1]},
            c2{h.m[0][2], h.m[1][2], h.m[2][2]};
        const double determinant = dot(c0, cross(c1, c2));
        y[i] = Vector3{dot(b, cross(c1, c2)), dot(c0, cross(b, c2)), dot(c0, cross(c1, b))} / determinant;
    }
    std::vector<double> result(direction.size());
    for (std::size_t a = 0; a < nodes.size(); ++a) {
        const int k = nodes[a];
        Vector3 sum{};
        for (int e = graph.offsets[k]; e < graph.offsets[k + 1]; ++e) {
            const int j = graph.neighbours[e];
            const double w = problem.edgeWeights()[e];
            const Vector3 d = x[j] - x[k];
            const double t = problem.isUnknown(j) ? 1.0 : 0.0;
            sum += w * ((1.0 + t) * (v[k] - v[j]) + cross(y[k], rotations[k] * d) + t * cross(y[j], rotations[j] * d));
        }
        for (int q = 0; q < 3; ++q) result[3 * a + q] = sum[q];
    }
    problem.projectSliding(result, 3);  // P S P v (direction is projected already)
    return result;
}

TEST(ReducedEnergy, In3DTheHessianProductIsTheEdgeFormulaWithAndWithoutAvx)
{
    // ReducedHessian3D (per-node data, AVX where the CPU has it) against the plain per-edge
    // formula to 1e-12, and its AVX and baseline variants bit for bit (also with mirror nodes).
    for (bool mirror : {false, true}) {
        const GridCase c = gridCase(3, 5, mirror, 11);
        const RbmProblem& problem = *c.problem;
        const std::vector<Vector3> prescribed = largeTopMotion(c);
        std::mt19937 random(4);
        std::uniform_real_distribution<double> value(-0.05, 0.05);
        std::vector<Vector3> displacement = prescribed;
        for (int node : problem.unknownNodes()) {
            displacement[node] = 0.5 * prescribed[node] + Vector3{value(random), value(random), value(random)};
            if (problem.kind(node) == NodeKind::sliding) {
                const Vector3& n = problem.slidingNormal(node);
                displacement[node] -= (dot(displacement[node], n) - dot(prescribed[node], n)) * n;
            }
        }
        std::vector<double> direction(3 * static_cast<std::size_t>(problem.unknownNodeCount()));
        for (double& d : direction) d = value(random);
        problem.projectSliding(direction, 3);
        ReducedEnergy energy(problem);
        const std::vector<double> product = hessianProduct(energy, displacement, direction);
        avxKernelsAllowed() = false;
        const std::vector<double> baseline = hessianProduct(energy, displacement, direction);
        avxKernelsAllowed() = true;
        ASSERT_EQ(product.size(), baseline.size());
        for (std::size_t k = 0; k < product.size(); ++k) ASSERT_EQ(product[k], baseline[k]) << k;
        if (mirror) continue;  // the plain formula has no mirror restriction
        const std::vector<double> expected = hessianTimesByEdges(problem, displacement, direction);
        double largest = 0.0, largestError = 0.0;
        for (std::size_t k = 0; k < product.size(); ++k) {
            largest = std::max(largest, std::abs(expected[k]));
            largestError = std::max(largestError, std::abs(product[k] - expected[k]));
        }
        EXPECT_GT(largest, 1e-2);
        EXPECT_LT(largestError, 1e-12 * largest);
    }
}

TEST(ReducedEnergy, In3DTheReleasedHessianIsPreparedAgainToTheLastBit)
{
    // The solver frees the Hessian's per-node data between solves (releaseHessian): the next
    // prepareHessian computes it again, the same bits, with mirror nodes as well; a product
    // without it is refused, not computed from freed data.
    for (bool mirror : {false, true}) {
        const GridCase c = gridCase(3, 5, mirror, 11);
        const RbmProblem& problem = *c.problem;
        const std::vector<Vector3> prescribed = largeTopMotion(c);
        std::vector<Vector3> displacement = prescribed;
        for (int node : problem.unknownNodes()) displacement[node] = 0.4 * prescribed[node];
        std::vector<double> direction(3 * static_cast<std::size_t>(problem.unknownNodeCount()));
        for (std::size_t k = 0; k < direction.size(); ++k) direction[k] = std::sin(0.7 * static_cast<double>(k));
        problem.projectSliding(direction, 3);
        ReducedEnergy energy(problem);
        const std::vector<double> before = hessianProduct(energy, displacement, direction);
        energy.releaseHessian();
        std::vector<double> y(direction.size());
        EXPECT_THROW(energy.applyHessian(direction, y), std::logic_error);
        const std::vector<double> after = hessianProduct(energy, displacement, direction);
        ASSERT_EQ(after.size(), before.size());
        double largest = 0.0;
        for (std::size_t k = 0; k < after.size(); ++k) {
            ASSERT_EQ(after[k], before[k]) << k;
            largest = std::max(largest, std::abs(after[k]));
        }
        EXPECT_GT(largest, 1e-2);
    }
}

TEST(ReducedEnergy, IsZeroAtRestAndItsRoundingLevelGrowsWithTheDisplacement)
{
    const GridCase c = gridCase(2, 4, false, 5);
    ReducedEnergy energy(*c.problem);
    const std::vector<Vector3> rest(c.points.size());
    EXPECT_EQ(energyAt(energy, rest), 0.0);
    const std::vector<double> g = gradientAt(energy, rest, *c.problem);
    EXPECT_TRUE(std::all_of(g.begin(), g.end(), [](double value) { return value == 0.0; }));
    const double atRest = energy.gradientRoundoffNorm(rest);
    EXPECT_GT(atRest, 0.0);
    EXPECT_LT(atRest, 1e-12);
    EXPECT_GT(energy.gradientRoundoffNorm(largeTopMotion(c)), atRest);
}

} // namespace
} // namespace rbm::motion
