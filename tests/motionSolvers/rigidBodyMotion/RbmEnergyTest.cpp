// Tests of the RBM energy (RbmEnergy): its rotations (planar, rotation vectors, the polar fast path
// against the Kabsch rotation of an SVD, Rodrigues derivatives), gradient and Hessian against
// finite differences, the linearized matrix symmetric positive definite, rigid motions at zero
// energy, and the origin-centred parameters giving the minimiser of the node-local rotations.

#include "CoupledLinearizedSolver.hpp"
#include "CoupledNewtonSolver.hpp"
#include "DecoupledSolver.hpp"
#include "LocalGlobalSolver.hpp"
#include "PetscTestEnvironment.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"
#include "ReducedNewtonSolver.hpp"
#include "RigidMotionModes.hpp"
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

// Solves a x = b by Gaussian elimination with partial pivoting.
std::vector<double> solveDense(DenseMatrix a, std::vector<double> b)
{
    const std::size_t n = b.size();
    for (std::size_t column = 0; column < n; ++column) {
        std::size_t pivot = column;
        for (std::size_t row = column + 1; row < n; ++row)
            if (std::abs(a[row][column]) > std::abs(a[pivot][column])) pivot = row;
        std::swap(a[pivot], a[column]);
        std::swap(b[pivot], b[column]);
        for (std::size_t row = column + 1; row < n; ++row) {
            const double factor = a[row][column] / a[column][column];
            for (std::size_t k = column; k < n; ++k) a[row][k] -= factor * a[column][k];
            b[row] -= factor * b[column];
        }
    }
    std::vector<double> x(n);
    for (std::size_t row = n; row-- > 0;) {
        double value = b[row];
        for (std::size_t k = row + 1; k < n; ++k) value -= a[row][k] * x[k];
        x[row] = value / a[row][row];
    }
    return x;
}

double maximumAbsolute(const DenseMatrix& a)
{
    double largest = 0.0;
    for (const auto& row : a)
        for (double value : row) largest = std::max(largest, std::abs(value));
    return largest;
}

// An irregular mesh (a perturbed structured grid) with a random state, for derivative checks.
struct RandomCase {
    TestMesh mesh;
    std::unique_ptr<RbmProblem> problem;
    std::vector<Vector3> prescribed;
    std::vector<double> unknowns;
};

RandomCase randomCase(int dimension, EdgeWeighting weighting, unsigned seed)
{
    RandomCase c;
    c.mesh = dimension == 2 ? structuredGrid(5, 4, 1, 1.0, {0.3, -0.2, 0.0}) : structuredGrid(4, 4, 3, 1.0, {0.3, -0.2, 0.1});
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> jitter(-0.2, 0.2);
    for (Vector3& point : c.mesh.points) {
        point.x += jitter(random);
        point.y += jitter(random);
        if (dimension == 3) point.z += jitter(random);
    }
    std::vector<NodeConstraint> constraints = prescribeBoundary(c.mesh);
    // Also make a few boundary nodes unknown so unknown–unknown edges at the rim exist.
    for (std::size_t node = 0; node < constraints.size(); node += 5) constraints[node].kind = NodeKind::free;
    c.problem = std::make_unique<RbmProblem>(dimension, c.mesh.points, c.mesh.graph, constraints, weighting);
    std::uniform_real_distribution<double> displacement(-0.3, 0.3);
    std::uniform_real_distribution<double> angle(-1.2, 1.2);
    c.prescribed.assign(c.mesh.points.size(), Vector3{});
    for (std::size_t node = 0; node < constraints.size(); ++node)
        if (constraints[node].kind == NodeKind::prescribed)
            c.prescribed[node] = {displacement(random), displacement(random), dimension == 3 ? displacement(random) : 0.0};
    c.unknowns.resize(c.problem->unknownCount());
    const int bs = c.problem->blockSize();
    for (std::size_t k = 0; k < c.unknowns.size(); ++k)
        c.unknowns[k] = (static_cast<int>(k % bs) < dimension) ? displacement(random) : angle(random);
    return c;
}

TEST(Rotation, PlanarRotationIsCounterClockwiseForPositiveAngles)
{
    const Vector3 turned = planarRotation(degrees(90.0)) * Vector3{1.0, 0.0, 0.0};
    EXPECT_NEAR(turned.x, 0.0, 1e-15);
    EXPECT_NEAR(turned.y, 1.0, 1e-15);
}

TEST(Rotation, RotationVectorFollowsTheRightHandRule)
{
    // A quarter turn about +z takes +x to +y; about +x it takes +y to +z.
    const Vector3 aboutZ = rotationFromVector({0.0, 0.0, pi / 2}) * Vector3{1.0, 0.0, 0.0};
    EXPECT_NEAR(aboutZ.y, 1.0, 1e-15);
    const Vector3 aboutX = rotationFromVector({pi / 2, 0.0, 0.0}) * Vector3{0.0, 1.0, 0.0};
    EXPECT_NEAR(aboutX.z, 1.0, 1e-15);
}

TEST(Rotation, RotationVectorRoundTripsThroughTheMatrix)
{
    for (const Vector3& w : {Vector3{0.1, -0.2, 0.3}, Vector3{1e-9, 2e-9, 0.0}, Vector3{2.0, -1.0, 0.5},
                             Vector3{0.0, 0.0, 3.1}, Vector3{0.0, 0.0, 0.0}}) {
        const Vector3 back = rotationVectorFromMatrix(rotationFromVector(w));
        EXPECT_NEAR(norm(back - w), 0.0, 1e-12) << w;
    }
}

// The Kabsch rotation from the SVD alone (bestRotation's fallback), to compare the polar fast path with.
Matrix3 kabschBySvd(const Matrix3& covariance)
{
    SingularValueDecomposition svd = singularValueDecomposition(covariance);
    auto determinant = [](const Matrix3& a) {
        return dot(Vector3{a.m[0][0], a.m[1][0], a.m[2][0]},
                   cross(Vector3{a.m[0][1], a.m[1][1], a.m[2][1]}, Vector3{a.m[0][2], a.m[1][2], a.m[2][2]}));
    };
    if (determinant(svd.u) * determinant(svd.v) < 0.0)
        for (int i = 0; i < 3; ++i) svd.u.m[i][2] = -svd.u.m[i][2];
    return svd.u * svd.v.transposed();
}

double largestDifference(const Matrix3& a, const Matrix3& b)
{
    double largest = 0.0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(a.m[r][c] - b.m[r][c]));
    return largest;
}

TEST(Rotation, PolarFastPathGivesTheKabschRotationOfTheSvd)
{
    std::mt19937 random(7);
    std::uniform_real_distribution<double> entry(-1.0, 1.0);
    int polarTaken = 0;
    for (int sample = 0; sample < 2000; ++sample) {
        // Rotation × symmetric positive definite (a stretched neighbourhood), plus a general part
        // of growing size: conditions from 1 to ~10⁴, and some with det ≤ 0 (reflections).
        const Matrix3 turn = rotationFromVector({2.0 * entry(random), 2.0 * entry(random), 2.0 * entry(random)});
        Matrix3 stretch;
        const double spread = std::pow(10.0, 4.0 * (sample % 5) / 4.0);
        for (int k = 0; k < 3; ++k) stretch.m[k][k] = 1.0 + spread * std::abs(entry(random));
        stretch.m[0][1] = stretch.m[1][0] = 0.3 * entry(random);
        Matrix3 covariance = turn * stretch;
        const double noise = (sample % 7) * 0.4;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) covariance.m[r][c] = 25.0 * (covariance.m[r][c] + noise * entry(random));
        Matrix3 polar;
        const bool fast = polarRotation(covariance, polar);
        polarTaken += fast ? 1 : 0;
        const Matrix3 expected = kabschBySvd(covariance);
        const Matrix3 fitted = bestRotation(covariance);
        EXPECT_LT(largestDifference(fitted, expected), 1e-12) << "sample " << sample;
        if (fast) {
            EXPECT_EQ(largestDifference(fitted, polar), 0.0);
        }
        // A proper rotation either way.
        EXPECT_LT(largestDifference(fitted * fitted.transposed(), Matrix3::identity()), 1e-14);
    }
    // Most samples take the fast path; the reflections and the near-singular ones do not.
    EXPECT_GT(polarTaken, 1000);
    EXPECT_LT(polarTaken, 2000);
}

TEST(Rotation, PolarFastPathReturnsTheRotationOfARigidlyTurnedNeighbourhood)
{
    // S = R C with C = Σ d dᵀ symmetric positive definite: the fit is R, to rounding.
    const Matrix3 turn = rotationFromVector({0.4, -1.3, 0.9});
    Matrix3 spread;
    spread.m[0][0] = 9.0, spread.m[1][1] = 8.5, spread.m[2][2] = 8.0, spread.m[0][2] = spread.m[2][0] = 0.25;
    Matrix3 polar;
    ASSERT_TRUE(polarRotation(turn * spread, polar));
    EXPECT_LT(largestDifference(polar, turn), 4e-16);
    // Reflections and rank-deficient (planar) neighbourhoods are left to the SVD.
    Matrix3 mirrored = spread;
    for (int c = 0; c < 3; ++c) mirrored.m[2][c] = -mirrored.m[2][c];
    EXPECT_FALSE(polarRotation(mirrored, polar));
    Matrix3 flat = spread;
    for (int c = 0; c < 3; ++c) flat.m[2][c] = 0.0;
    EXPECT_FALSE(polarRotation(flat, polar));
    EXPECT_LT(largestDifference(bestRotation(flat) * bestRotation(flat).transposed(), Matrix3::identity()), 1e-15);
}

TEST(Rotation, RodriguesDerivativesMatchFiniteDifferences)
{
    // Covers the series branch (|ω| < 1) and the closed-form branch.
    for (const Vector3& w : {Vector3{0.3, -0.2, 0.1}, Vector3{1.5, 0.7, -1.1}, Vector3{1e-4, 0.0, 2e-4}}) {
        const double parameters[3] = {w.x, w.y, w.z};
        const RotationDerivatives exact = rotationDerivatives(3, RotationModel::exact, parameters);
        const double step = 1e-5;
        for (int k = 0; k < 3; ++k) {
            double plus[3] = {w.x, w.y, w.z}, minus[3] = {w.x, w.y, w.z};
            plus[k] += step;
            minus[k] -= step;
            const RotationDerivatives up = rotationDerivatives(3, RotationModel::exact, plus);
            const RotationDerivatives down = rotationDerivatives(3, RotationModel::exact, minus);
            for (int r = 0; r < 3; ++r) {
                for (int c = 0; c < 3; ++c) {
                    const double first = (up.rotation.m[r][c] - down.rotation.m[r][c]) / (2 * step);
                    EXPECT_NEAR(exact.first[k].m[r][c], first, 1e-9);
                    for (int l = 0; l < 3; ++l) {
                        const double second = (up.first[l].m[r][c] - down.first[l].m[r][c]) / (2 * step);
                        EXPECT_NEAR(exact.second[symmetricIndex(k, l)].m[r][c], second, 1e-9);
                    }
                }
            }
        }
    }
}

class EnergyDerivatives : public ::testing::TestWithParam<std::tuple<int, RotationModel>> {};

TEST_P(EnergyDerivatives, GradientMatchesFiniteDifferencesOfTheEnergy)
{
    const auto [dimension, model] = GetParam();
    RandomCase c = randomCase(dimension, EdgeWeighting::inverseDistanceSquared, 11);
    const RbmEnergy energy(*c.problem, model, c.prescribed);
    std::vector<double> gradient(c.unknowns.size());
    energy.gradient(c.unknowns, gradient);
    double largest = 0.0;
    for (double g : gradient) largest = std::max(largest, std::abs(g));
    ASSERT_GT(largest, 0.1);  // a generic state, far from a minimum
    const double step = 1e-6;
    for (std::size_t k = 0; k < c.unknowns.size(); ++k) {
        std::vector<double> z = c.unknowns;
        z[k] += step;
        const double up = energy.value(z);
        z[k] -= 2 * step;
        const double down = energy.value(z);
        EXPECT_NEAR(gradient[k], (up - down) / (2 * step), 1e-6 * largest) << "unknown " << k;
    }
}

TEST_P(EnergyDerivatives, AnalyticHessianMatchesFiniteDifferencesOfTheGradient)
{
    const auto [dimension, model] = GetParam();
    RandomCase c = randomCase(dimension, EdgeWeighting::inverseDistanceSquared, 17);
    const RbmProblem& problem = *c.problem;
    const int bs = problem.blockSize();
    const RbmEnergy energy(problem, model, c.prescribed);
    std::vector<double> blocks(static_cast<std::size_t>(problem.blockPattern().blockCount()) * bs * bs);
    energy.hessian(c.unknowns, blocks);
    const DenseMatrix hessian = denseFromBlocks(problem, blocks, bs);
    const double largest = maximumAbsolute(hessian);
    const double step = 1e-6;
    const std::size_t n = c.unknowns.size();
    std::vector<double> up(n), down(n);
    for (std::size_t k = 0; k < n; ++k) {
        std::vector<double> z = c.unknowns;
        z[k] += step;
        energy.gradient(z, up);
        z[k] -= 2 * step;
        energy.gradient(z, down);
        for (std::size_t row = 0; row < n; ++row)
            ASSERT_NEAR(hessian[row][k], (up[row] - down[row]) / (2 * step), 1e-6 * largest)
                << "row " << row << " column " << k;
    }
}

INSTANTIATE_TEST_SUITE_P(TwoAndThreeDimensions, EnergyDerivatives,
                         ::testing::Values(std::tuple{2, RotationModel::exact}, std::tuple{3, RotationModel::exact},
                                           std::tuple{2, RotationModel::smallAngle},
                                           std::tuple{3, RotationModel::smallAngle}),
                         [](const auto& info) {
                             return std::to_string(std::get<0>(info.param)) + "D" +
                                    (std::get<1>(info.param) == RotationModel::exact ? "Exact" : "SmallAngle");
                         });

TEST(Energy, LinearizedMatrixIsSymmetricPositiveDefinite)
{
    for (int dimension : {2, 3}) {
        RandomCase c = randomCase(dimension, EdgeWeighting::inverseDistanceSquared, 5);
        const RbmProblem& problem = *c.problem;
        const int bs = problem.blockSize();
        const RbmEnergy energy(problem, RotationModel::smallAngle, c.prescribed);
        std::vector<double> blocks(static_cast<std::size_t>(problem.blockPattern().blockCount()) * bs * bs);
        energy.hessian(c.unknowns, blocks);
        const DenseMatrix matrix = denseFromBlocks(problem, blocks, bs);
        const double largest = maximumAbsolute(matrix);
        for (std::size_t i = 0; i < matrix.size(); ++i)
            for (std::size_t j = 0; j < i; ++j) ASSERT_NEAR(matrix[i][j], matrix[j][i], 1e-14 * largest);
        EXPECT_TRUE(choleskySucceeds(matrix)) << dimension << "D";
    }
}

TEST(Energy, RigidMotionHasZeroEnergy)
{
    // u_i = R x_i + t − x_i with every node rotated by R is a zero of every residual.
    for (int dimension : {2, 3}) {
        RandomCase c = randomCase(dimension, EdgeWeighting::uniform, 3);
        RigidMotion motion;
        motion.rotation = dimension == 2 ? planarRotation(degrees(120.0)) : rotationFromVector({0.9, -1.2, 0.8});
        motion.translation = {1.5, -2.0, dimension == 3 ? 0.7 : 0.0};
        RbmState state;
        for (const Vector3& x : c.mesh.points) {
            state.displacement.push_back(motion.displacement(x));
            state.rotation.push_back(dimension == 2 ? Vector3{0.0, 0.0, degrees(120.0)} : Vector3{0.9, -1.2, 0.8});
        }
        std::vector<double> unknowns(c.problem->unknownCount());
        packUnknowns(*c.problem, state, unknowns);
        const RbmEnergy energy(*c.problem, RotationModel::exact, state.displacement);
        EXPECT_NEAR(energy.value(unknowns), 0.0, 1e-25);
        EXPECT_NEAR(energy.projectedGradientNorm(unknowns), 0.0, 1e-12);
    }
}

Matrix3 thesisRotation(double theta) { return planarRotation(-theta); }

struct OriginCentredMinimum {
    std::vector<double> parameters;  // (Δx, Δy, θ) per unknown node
    double energy = 0.0;
};

OriginCentredMinimum minimiseOriginCentred(const RbmProblem& problem, const std::vector<Vector3>& prescribed)
{
    const CellNeighbourGraph& graph = problem.graph();
    const std::vector<Vector3>& x = problem.referencePoints();
    const int m = problem.unknownNodeCount();
    const int n = 3 * m;
    auto position = [&](const std::vector<double>& z, int node) {
        const int a = problem.unknownIndex()[node];
        if (a < 0) return x[node] + prescribed[node];
        return thesisRotation(z[3 * a + 2]) * x[node] + Vector3{z[3 * a], z[3 * a + 1], 0.0};
    };
    // Residuals and their Jacobian (d/dθ T(θ) v = [−sin cos; −cos −sin] v).
    auto evaluate = [&](const std::vector<double>& z, std::vector<double>& r, DenseMatrix* jacobian) {
        r.clear();
        if (jacobian) jacobian->clear();
        for (int a = 0; a < m; ++a) {
            const int i = problem.unknownNodes()[a];
            const double theta = z[3 * a + 2];
            for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
                const int j = graph.neighbours[e];
                const double s = std::sqrt(problem.edgeWeights()[e]);
                const Vector3 ideal = thesisRotation(theta) * x[j] + Vector3{z[3 * a], z[3 * a + 1], 0.0};
                const Vector3 actual = position(z, j);
                for (int q = 0; q < 2; ++q) {
                    r.push_back(s * (ideal[q] - actual[q]));
                    if (!jacobian) continue;
                    std::vector<double> row(n, 0.0);
                    const Vector3 dIdeal{-std::sin(theta) * x[j].x + std::cos(theta) * x[j].y,
                                         -std::cos(theta) * x[j].x - std::sin(theta) * x[j].y, 0.0};
                    row[3 * a + q] += s;
                    row[3 * a + 2] += s * dIdeal[q];
                    const int b = problem.unknownIndex()[j];
                    if (b >= 0) {
                        const double thetaJ = z[3 * b + 2];
                        const Vector3 dActual{-std::sin(thetaJ) * x[j].x + std::cos(thetaJ) * x[j].y,
                                              -std::cos(thetaJ) * x[j].x - std::sin(thetaJ) * x[j].y, 0.0};
                        row[3 * b + q] -= s;
                        row[3 * b + 2] -= s * dActual[q];
                    }
                    jacobian->push_back(std::move(row));
                }
            }
        }
    };
    auto cost = [](const std::vector<double>& r) {
        double sum = 0.0;
        for (double value : r) sum += value * value;
        return 0.5 * sum;
    };
    std::vector<double> z(n, 0.0), r, trialResiduals;
    DenseMatrix jacobian;
    double damping = 1e-3;
    for (int iteration = 0; iteration < 200; ++iteration) {
        evaluate(z, r, &jacobian);
        DenseMatrix normal(n, std::vector<double>(n, 0.0));
        std::vector<double> gradient(n, 0.0);
        for (std::size_t row = 0; row < r.size(); ++row)
            for (int p = 0; p < n; ++p) {
                if (jacobian[row][p] == 0.0) continue;
                gradient[p] += jacobian[row][p] * r[row];
                for (int q = 0; q < n; ++q) normal[p][q] += jacobian[row][p] * jacobian[row][q];
            }
        double gradientNorm = 0.0;
        for (double g : gradient) gradientNorm = std::max(gradientNorm, std::abs(g));
        if (gradientNorm < 1e-13) break;
        for (;;) {
            DenseMatrix damped = normal;
            for (int p = 0; p < n; ++p) damped[p][p] *= 1.0 + damping;
            std::vector<double> minusGradient(n);
            for (int p = 0; p < n; ++p) minusGradient[p] = -gradient[p];
            const std::vector<double> step = solveDense(damped, minusGradient);
            std::vector<double> trial = z;
            for (int p = 0; p < n; ++p) trial[p] += step[p];
            evaluate(trial, trialResiduals, nullptr);
            if (cost(trialResiduals) <= cost(r)) {
                z = trial;
                damping = std::max(damping / 10.0, 1e-15);
                break;
            }
            damping *= 10.0;
            if (damping > 1e12) return {z, cost(r)};
        }
    }
    evaluate(z, r, nullptr);
    return {z, cost(r)};
}

TEST(OriginCentredParameters, GiveTheSameMinimiserAsNodeLocalRotations)
{
    // 6 × 6 nodes away from the origin, boundary moved by a smooth non-rigid field.
    const TestMesh mesh = structuredGrid(6, 6, 1, 1.0, {3.0, 2.0, 0.0});
    const std::vector<NodeConstraint> constraints = prescribeBoundary(mesh);
    const RbmProblem problem(2, mesh.points, mesh.graph, constraints, EdgeWeighting::uniform);
    const std::vector<Vector3> prescribed = prescribedFrom(mesh, constraints, [](const Vector3& x) {
        return Vector3{0.3 * std::sin(x.y) + 0.05 * x.x * x.y, 0.2 * x.x - 0.04 * x.y * x.y, 0.0};
    });
    CoupledNewtonSolver newton(problem);
    const RbmResult nodeLocal = newton.solve(prescribed);
    ASSERT_TRUE(nodeLocal.converged) << nodeLocal.reason;
    const OriginCentredMinimum originCentred = minimiseOriginCentred(problem, prescribed);
    EXPECT_GT(nodeLocal.energy, 1e-3);
    EXPECT_NEAR(originCentred.energy, nodeLocal.energy, 1e-10 * nodeLocal.energy);
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        const int node = problem.unknownNodes()[a];
        const double theta = originCentred.parameters[3 * a + 2];
        const Vector3 position = thesisRotation(theta) * mesh.points[node] +
                                 Vector3{originCentred.parameters[3 * a], originCentred.parameters[3 * a + 1], 0.0};
        EXPECT_LT(norm(position - (mesh.points[node] + nodeLocal.displacement[node])), 1e-8) << "node " << node;
        // The thesis' clockwise θ is minus our counter-clockwise rotation.
        EXPECT_NEAR(std::remainder(theta + nodeLocal.rotation[node].z, 2 * pi), 0.0, 1e-8);
    }
}

} // namespace
} // namespace rbm::motion
