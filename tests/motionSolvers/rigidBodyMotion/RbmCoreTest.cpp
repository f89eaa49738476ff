// Tests of the numerical core of the RBM solver (motionSolvers/): energy, gradient and
// Hessian, the coupled linearized and Newton solvers, local/global, decoupled and
// sub-steps, on small structured meshes built here (no files).

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

static ::testing::Environment* const petscEnvironment =
    ::testing::AddGlobalTestEnvironment(new rbm::test::PetscTestEnvironment);

namespace rbm::motion {
namespace {

constexpr double pi = std::numbers::pi;
double degrees(double value) { return value * pi / 180.0; }

// ---------------------------------------------------------------------------------------
// Test meshes

// Nodes sharing a cell are neighbours (the definition of docs/method.md §1), built directly so
// these tests do not depend on buildCellNeighbourGraph.
CellNeighbourGraph graphFromCells(int nodeCount, const std::vector<int>& cellOffsets, const std::vector<int>& cellPoints)
{
    std::vector<std::vector<int>> adjacency(nodeCount);
    for (std::size_t c = 0; c + 1 < cellOffsets.size(); ++c)
        for (int p = cellOffsets[c]; p < cellOffsets[c + 1]; ++p)
            for (int q = cellOffsets[c]; q < cellOffsets[c + 1]; ++q)
                if (cellPoints[p] != cellPoints[q]) adjacency[cellPoints[p]].push_back(cellPoints[q]);
    CellNeighbourGraph graph;
    graph.offsets.assign(1, 0);
    for (auto& list : adjacency) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
        graph.neighbours.insert(graph.neighbours.end(), list.begin(), list.end());
        graph.offsets.push_back(static_cast<int>(graph.neighbours.size()));
    }
    return graph;
}

struct TestMesh {
    int dimension = 2;
    std::vector<Vector3> points;
    std::vector<std::array<int, 3>> gridIndex;  // structured (i, j, k) of every node
    std::vector<int> cellOffsets{0};
    std::vector<int> cellPoints;
    CellNeighbourGraph graph;
};

// Structured grid of (nx × ny × nz) nodes, spacing h, first node at origin; nz = 1 gives a
// 2D quad mesh. Cells for which `skipCell(i, j, k)` is true are left out (holes), and nodes
// no cell uses are dropped.
TestMesh structuredGrid(int nx, int ny, int nz, double h, Vector3 origin,
                        const std::function<bool(int, int, int)>& skipCell = {})
{
    TestMesh mesh;
    mesh.dimension = nz == 1 ? 2 : 3;
    auto gridNode = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
    std::vector<int> rawCellPoints;
    std::vector<int> rawOffsets{0};
    const int cellsZ = mesh.dimension == 2 ? 1 : nz - 1;
    for (int k = 0; k < cellsZ; ++k) {
        for (int j = 0; j + 1 < ny; ++j) {
            for (int i = 0; i + 1 < nx; ++i) {
                if (skipCell && skipCell(i, j, k)) continue;
                if (mesh.dimension == 2) {
                    for (int node : {gridNode(i, j, 0), gridNode(i + 1, j, 0), gridNode(i + 1, j + 1, 0),
                                     gridNode(i, j + 1, 0)})
                        rawCellPoints.push_back(node);
                } else {
                    for (int dk = 0; dk < 2; ++dk)
                        for (int node : {gridNode(i, j, k + dk), gridNode(i + 1, j, k + dk),
                                         gridNode(i + 1, j + 1, k + dk), gridNode(i, j + 1, k + dk)})
                            rawCellPoints.push_back(node);
                }
                rawOffsets.push_back(static_cast<int>(rawCellPoints.size()));
            }
        }
    }
    std::vector<int> compact(nx * ny * nz, -1);
    for (int node : rawCellPoints) compact[node] = 0;
    for (int k = 0; k < nz; ++k) {
        for (int j = 0; j < ny; ++j) {
            for (int i = 0; i < nx; ++i) {
                int& index = compact[gridNode(i, j, k)];
                if (index < 0) continue;
                index = static_cast<int>(mesh.points.size());
                mesh.points.push_back(origin + Vector3{i * h, j * h, k * h});
                mesh.gridIndex.push_back({i, j, k});
            }
        }
    }
    for (int node : rawCellPoints) mesh.cellPoints.push_back(compact[node]);
    mesh.cellOffsets = rawOffsets;
    mesh.graph = graphFromCells(static_cast<int>(mesh.points.size()), mesh.cellOffsets, mesh.cellPoints);
    return mesh;
}

// Moves every node by a random offset of up to `fraction` × h per coordinate (an
// irregular mesh: a node is no longer the centroid of its neighbours) and rebuilds nothing
// else (the topology stays).
void jitter(TestMesh& mesh, double amplitude, unsigned seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> offset(-amplitude, amplitude);
    for (Vector3& point : mesh.points) {
        point.x += offset(random);
        point.y += offset(random);
        if (mesh.dimension == 3) point.z += offset(random);
    }
}

// Nodes on the boundary of the mesh: nodes with fewer neighbours than an interior node.
std::vector<bool> boundaryNodes(const TestMesh& mesh)
{
    const int interiorCount = mesh.dimension == 2 ? 8 : 26;
    std::vector<bool> boundary(mesh.points.size());
    for (int node = 0; node < static_cast<int>(mesh.points.size()); ++node)
        boundary[node] = mesh.graph.offsets[node + 1] - mesh.graph.offsets[node] < interiorCount;
    return boundary;
}

std::vector<NodeConstraint> prescribeBoundary(const TestMesh& mesh)
{
    const std::vector<bool> boundary = boundaryNodes(mesh);
    std::vector<NodeConstraint> constraints(mesh.points.size());
    for (std::size_t node = 0; node < boundary.size(); ++node)
        if (boundary[node]) constraints[node].kind = NodeKind::prescribed;
    return constraints;
}

// Rigid motion p = R (x − centre) + centre + translation.
struct RigidMotion {
    Matrix3 rotation = Matrix3::identity();
    Vector3 centre{};
    Vector3 translation{};
    Vector3 displacement(const Vector3& x) const { return rotation * (x - centre) + centre + translation - x; }
};

std::vector<Vector3> prescribedFrom(const TestMesh& mesh, const std::vector<NodeConstraint>& constraints,
                                    const std::function<Vector3(const Vector3&)>& displacement)
{
    std::vector<Vector3> values(mesh.points.size());
    for (std::size_t node = 0; node < values.size(); ++node)
        if (constraints[node].kind != NodeKind::free) values[node] = displacement(mesh.points[node]);
    return values;
}

// ---------------------------------------------------------------------------------------
// Dense helpers

using DenseMatrix = std::vector<std::vector<double>>;

DenseMatrix denseFromBlocks(const RbmProblem& problem, const std::vector<double>& blocks, int bs)
{
    const int n = problem.unknownNodeCount() * bs;
    DenseMatrix dense(n, std::vector<double>(n, 0.0));
    const BlockPattern& pattern = problem.blockPattern();
    for (int a = 0; a < pattern.rowCount(); ++a)
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position) {
            const int b = pattern.columns[position];
            for (int p = 0; p < bs; ++p)
                for (int q = 0; q < bs; ++q) dense[a * bs + p][b * bs + q] = blocks[(position * bs + p) * bs + q];
        }
    return dense;
}

// Cholesky factorisation; false when a pivot is not positive.
bool choleskySucceeds(DenseMatrix a)
{
    const std::size_t n = a.size();
    for (std::size_t j = 0; j < n; ++j) {
        double diagonal = a[j][j];
        for (std::size_t k = 0; k < j; ++k) diagonal -= a[j][k] * a[j][k];
        if (!(diagonal > 0.0)) return false;
        a[j][j] = std::sqrt(diagonal);
        for (std::size_t i = j + 1; i < n; ++i) {
            double value = a[i][j];
            for (std::size_t k = 0; k < j; ++k) value -= a[i][k] * a[j][k];
            a[i][j] = value / a[j][j];
        }
    }
    return true;
}

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

// ---------------------------------------------------------------------------------------
// Rotations

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

// ---------------------------------------------------------------------------------------
// Energy derivatives

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

// ---------------------------------------------------------------------------------------
// Rigid motions: every nonlinear variant must reproduce them exactly (energy 0).

struct RigidCase {
    TestMesh mesh;
    std::unique_ptr<RbmProblem> problem;
    RigidMotion motion;
    std::vector<Vector3> prescribed;
    double meshSize = 1.0;
};

// 2D: 9 × 9 nodes, spacing 0.5, boundary prescribed; 3D: 5 × 5 × 5 nodes, spacing 1.
RigidCase rigidCase(int dimension, double angle, EdgeWeighting weighting)
{
    RigidCase c;
    c.meshSize = dimension == 2 ? 0.5 : 1.0;
    c.mesh = dimension == 2 ? structuredGrid(9, 9, 1, 0.5, {1.0, -2.0, 0.0}) : structuredGrid(5, 5, 5, 1.0, {1.0, -2.0, 0.5});
    jitter(c.mesh, 0.15 * c.meshSize, 7);  // irregular: no node is the centroid of its neighbours
    const std::vector<NodeConstraint> constraints = prescribeBoundary(c.mesh);
    c.problem = std::make_unique<RbmProblem>(dimension, c.mesh.points, c.mesh.graph, constraints, weighting);
    if (dimension == 2) {
        c.motion.rotation = planarRotation(angle);
        c.motion.centre = {2.0, -1.0, 0.0};
        c.motion.translation = {0.7, -0.4, 0.0};
    } else {
        const Vector3 axis = Vector3{1.0, 2.0, 2.0} / 3.0;
        c.motion.rotation = rotationFromVector(axis * angle);
        c.motion.centre = {3.0, 0.0, 2.5};
        c.motion.translation = {0.7, -0.4, 1.1};
    }
    c.prescribed = prescribedFrom(c.mesh, constraints, [&](const Vector3& x) { return c.motion.displacement(x); });
    return c;
}

double maximumPositionError(const RigidCase& c, const RbmResult& result)
{
    double largest = 0.0;
    for (std::size_t node = 0; node < c.mesh.points.size(); ++node)
        largest = std::max(largest, norm(result.displacement[node] - c.motion.displacement(c.mesh.points[node])));
    return largest;
}

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

TEST(CoupledLinearized, ReproducesATranslationExactly)
{
    // Without rotation the small-angle model is exact: every free node translates. (A direct
    // solve, so that only the model is tested: the 3D default, matrix-free CG, stops at its
    // Krylov tolerance, 1e-10; MatrixFreeLinearizedTest checks it with a tighter one.)
    for (int dimension : {2, 3}) {
        const RigidCase c = rigidCase(dimension, 0.0, EdgeWeighting::inverseDistanceSquared);
        CoupledLinearizedSolver solver(*c.problem, {LinearSolverKind::direct});
        const RbmResult result = solver.solve(c.prescribed);
        EXPECT_TRUE(result.converged) << result.reason;
        EXPECT_LT(maximumPositionError(c, result), 1e-12);
        EXPECT_LT(result.energy, 1e-24);
    }
}

TEST(CoupledLinearized, ErrorOfASmallRotationShrinksWithTheSquareOfTheAngle)
{
    // The small-angle model errs by O(θ²) (eq 2.48: cos θ ≈ 1 drops θ²/2).
    for (int dimension : {2, 3}) {
        const RigidCase small = rigidCase(dimension, degrees(1.0), EdgeWeighting::uniform);
        const RigidCase half = rigidCase(dimension, degrees(0.5), EdgeWeighting::uniform);
        CoupledLinearizedSolver solverSmall(*small.problem);
        CoupledLinearizedSolver solverHalf(*half.problem);
        const double errorSmall = maximumPositionError(small, solverSmall.solve(small.prescribed));
        const double errorHalf = maximumPositionError(half, solverHalf.solve(half.prescribed));
        EXPECT_GT(errorSmall, 1e-6);
        EXPECT_NEAR(errorSmall / errorHalf, 4.0, 0.1) << dimension << "D";
    }
}

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

// ---------------------------------------------------------------------------------------
// The thesis' rotating squares (§3.1.1): a square of (N × N) nodes, spacing 10, with a
// square hole of `innerCells` cells at its centre; the hole's rim turns by `angle`
// (counter-clockwise) about the centre, the outer boundary is fixed.

struct SquaresCase {
    TestMesh mesh;
    std::vector<NodeConstraint> constraints;
    std::vector<Vector3> prescribed;
};

SquaresCase squaresCase(int outerNodes, int innerCells, double angle, double jitterAmplitude = 0.0)
{
    SquaresCase c;
    const int first = (outerNodes - 1 - innerCells) / 2;
    const int last = first + innerCells;
    auto inHole = [=](int i, int j, int) { return i >= first && i < last && j >= first && j < last; };
    c.mesh = structuredGrid(outerNodes, outerNodes, 1, 10.0, {0.0, 0.0, 0.0}, inHole);
    if (jitterAmplitude > 0.0) jitter(c.mesh, jitterAmplitude, 3);
    const double middle = 10.0 * (outerNodes - 1) / 2.0;
    RigidMotion turn;
    turn.rotation = planarRotation(angle);
    turn.centre = {middle, middle, 0.0};
    c.constraints.assign(c.mesh.points.size(), NodeConstraint{});
    c.prescribed.assign(c.mesh.points.size(), Vector3{});
    for (std::size_t node = 0; node < c.mesh.points.size(); ++node) {
        const auto [i, j, k] = c.mesh.gridIndex[node];
        if (i == 0 || j == 0 || i == outerNodes - 1 || j == outerNodes - 1) {
            c.constraints[node].kind = NodeKind::prescribed;
        } else if (i >= first && i <= last && j >= first && j <= last) {
            c.constraints[node].kind = NodeKind::prescribed;
            c.prescribed[node] = turn.displacement(c.mesh.points[node]);
        }
    }
    return c;
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

TEST(LocalGlobal, AndersonAccelerationReachesTheSameMinimumInFewerIterations)
{
    // The loosely held case of §3.1.3, where the plain alternation crawls.
    const SquaresCase c = squaresCase(11, 2, degrees(45.0));
    std::vector<NodeConstraint> constraints = c.constraints;
    for (std::size_t node = 0; node < constraints.size(); ++node)
        if (norm(c.prescribed[node]) == 0.0) constraints[node].kind = NodeKind::free;
    // Pull one outer corner so the answer is not a rigid motion.
    std::vector<Vector3> prescribed = c.prescribed;
    constraints[0].kind = NodeKind::prescribed;
    prescribed[0] = {-5.0, 3.0, 0.0};
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, constraints, EdgeWeighting::uniform);
    LocalGlobalOptions plainOptions;
    plainOptions.accelerationDepth = 0;
    LocalGlobalSolver plain(problem, plainOptions);
    LocalGlobalSolver accelerated(problem);
    const RbmResult slow = plain.solve(prescribed);
    const RbmResult fast = accelerated.solve(prescribed);
    ASSERT_TRUE(slow.converged) << slow.reason;
    ASSERT_TRUE(fast.converged) << fast.reason;
    EXPECT_GT(slow.energy, 1e-3);
    EXPECT_NEAR(fast.energy, slow.energy, 1e-8 * slow.energy);
    EXPECT_LT(fast.iterations * 5, slow.iterations) << fast.reason << " vs " << slow.reason;
}

// ---------------------------------------------------------------------------------------
// The thesis' origin-centred parameters (eqs 2.1, 2.10–2.13): node i moves to
// p_i = T(θ_i) x_i + Δ_i with T(θ) = [cos θ  sin θ; −sin θ  cos θ] (clockwise for θ > 0),
// and the ideal position of neighbour j is T(θ_i) x_j + Δ_i. Minimised here by an
// independent dense Levenberg–Marquardt on the residuals √w (ideal − actual).

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

// ---------------------------------------------------------------------------------------
// Decoupled method

// The same mesh with its nodes renumbered by `order` (new node k is old node order[k]).
struct Renumbered {
    std::vector<Vector3> points;
    CellNeighbourGraph graph;
    std::vector<NodeConstraint> constraints;
    std::vector<Vector3> prescribed;
};

Renumbered renumber(const SquaresCase& c, const std::vector<int>& order)
{
    const int n = static_cast<int>(order.size());
    std::vector<int> newIndex(n);
    for (int k = 0; k < n; ++k) newIndex[order[k]] = k;
    Renumbered r;
    std::vector<int> cellPoints(c.mesh.cellPoints.size());
    for (std::size_t p = 0; p < cellPoints.size(); ++p) cellPoints[p] = newIndex[c.mesh.cellPoints[p]];
    r.graph = graphFromCells(n, c.mesh.cellOffsets, cellPoints);
    for (int k = 0; k < n; ++k) {
        r.points.push_back(c.mesh.points[order[k]]);
        r.constraints.push_back(c.constraints[order[k]]);
        r.prescribed.push_back(c.prescribed[order[k]]);
    }
    return r;
}

TEST(Decoupled, ResultDoesNotDependOnTheNodeNumbering)
{
    // Irregular nodes: on the regular grid every node is the centroid of its neighbours
    // and the decoupled method reduces to Laplacian smoothing, rotations play no part.
    const SquaresCase c = squaresCase(21, 4, degrees(10.0), 2.0);
    std::vector<int> order(c.mesh.points.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937(42));
    const Renumbered shuffled = renumber(c, order);
    const RbmProblem original(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    const RbmProblem permuted(2, shuffled.points, shuffled.graph, shuffled.constraints, EdgeWeighting::uniform);
    for (DecoupledModel model : {DecoupledModel::nonlinear, DecoupledModel::linearized}) {
        DecoupledOptions options;
        options.model = model;
        DecoupledSolver first(original, options);
        DecoupledSolver second(permuted, options);
        const RbmResult a = first.solve(c.prescribed);
        const RbmResult b = second.solve(shuffled.prescribed);
        ASSERT_TRUE(a.converged) << a.reason;
        ASSERT_TRUE(b.converged) << b.reason;
        double largest = 0.0, moved = 0.0;
        for (std::size_t k = 0; k < order.size(); ++k) {
            largest = std::max(largest, norm(b.displacement[k] - a.displacement[order[k]]));
            moved = std::max(moved, norm(a.displacement[order[k]]));
        }
        EXPECT_GT(moved, 1.0);
        EXPECT_LT(largest, 1e-9 * 10.0) << (model == DecoupledModel::nonlinear ? "nonlinear" : "linearized");
    }
}

TEST(Decoupled, EveryNodeIsTheBestRigidFitOfItsNeighbours)
{
    // At the fixed point, each node's (p_i, R_i) is the closed-form optimum of its own F_i
    // (docs/method.md §3): R_i the best rotation of the centred neighbour vectors, then
    // p_i = mean_j (p_j − R_i (x_j − x_i)), here with uniform weights.
    const SquaresCase c = squaresCase(21, 4, degrees(10.0), 2.0);
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    DecoupledSolver solver(problem);
    const RbmResult result = solver.solve(c.prescribed);
    ASSERT_TRUE(result.converged) << result.reason;
    const auto& x = c.mesh.points;
    for (int i : problem.unknownNodes()) {
        const auto neighbours = problem.graph().neighboursOf(i);
        Vector3 referenceCentre, currentCentre;
        for (int j : neighbours) {
            referenceCentre += x[j] / static_cast<double>(neighbours.size());
            currentCentre += (x[j] + result.displacement[j]) / static_cast<double>(neighbours.size());
        }
        double crossSum = 0.0, dotSum = 0.0;
        for (int j : neighbours) {
            const Vector3 a = x[j] - referenceCentre;
            const Vector3 b = x[j] + result.displacement[j] - currentCentre;
            crossSum += a.x * b.y - a.y * b.x;
            dotSum += a.x * b.x + a.y * b.y;
        }
        const Matrix3 rotation = planarRotation(std::atan2(crossSum, dotSum));
        const Vector3 best = currentCentre - rotation * (referenceCentre - x[i]);
        ASSERT_LT(norm(best - (x[i] + result.displacement[i])), 1e-8) << "node " << i;
    }
}

TEST(Decoupled, HasAHigherCoupledEnergyThanTheCoupledMinimum)
{
    const SquaresCase c = squaresCase(21, 4, degrees(10.0), 2.0);
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    DecoupledSolver decoupled(problem);
    CoupledNewtonSolver coupled(problem);
    const double decoupledEnergy = decoupled.solve(c.prescribed).energy;
    const double coupledEnergy = coupled.solve(c.prescribed).energy;
    EXPECT_GT(decoupledEnergy, coupledEnergy * (1.0 + 1e-6));
}

// ---------------------------------------------------------------------------------------
// Sliding nodes

// A box whose bottom face (2D: edge) slides on its plane (normal e_z, 2D e_y) while the rest
// of the boundary follows a rigid motion that keeps that plane: a rotation about the
// normal and a translation along the plane (and, for `lift`, across it: the plane moves).
// Everything is then turned by `frame` so the plane normal is not a coordinate axis.
struct SlidingCase {
    TestMesh mesh;
    std::unique_ptr<RbmProblem> problem;
    RigidMotion motion;
    std::vector<Vector3> prescribed;
    Vector3 normal;
};

SlidingCase slidingCase(int dimension, double angle, double lift, EdgeWeighting weighting, bool mirror = false)
{
    SlidingCase c;
    c.mesh = dimension == 2 ? structuredGrid(8, 6, 1, 1.0, {0.0, 0.0, 0.0}) : structuredGrid(5, 5, 4, 1.0, {0.0, 0.0, 0.0});
    const Matrix3 frame = dimension == 2 ? planarRotation(0.4) : rotationFromVector({0.3, -0.5, 0.2});
    std::vector<NodeConstraint> constraints = prescribeBoundary(c.mesh);
    const Vector3 localNormal = dimension == 2 ? Vector3{0.0, 1.0, 0.0} : Vector3{0.0, 0.0, 1.0};
    c.normal = frame * localNormal;
    for (std::size_t node = 0; node < c.mesh.points.size(); ++node) {
        const auto [i, j, k] = c.mesh.gridIndex[node];
        const bool onPlane = dimension == 2 ? j == 0 : k == 0;
        const bool onRim = dimension == 2 ? (i == 0 || i == 7) : (i == 0 || i == 4 || j == 0 || j == 4);
        if (onPlane && !onRim) constraints[node] = {NodeKind::sliding, 3.0 * c.normal, mirror};  // any length
    }
    for (Vector3& point : c.mesh.points) point = frame * point;
    c.problem = std::make_unique<RbmProblem>(dimension, c.mesh.points, c.mesh.graph, constraints, weighting);
    c.motion.rotation = dimension == 2 ? Matrix3::identity() : rotationFromVector(angle * c.normal);
    c.motion.centre = frame * Vector3{2.0, 2.0, 0.0};
    const Vector3 along = dimension == 2 ? frame * Vector3{1.0, 0.0, 0.0} : frame * Vector3{1.0, 0.5, 0.0};
    c.motion.translation = 0.6 * along + lift * c.normal;
    c.prescribed = prescribedFrom(c.mesh, constraints, [&](const Vector3& x) { return c.motion.displacement(x); });
    return c;
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

// ---------------------------------------------------------------------------------------
// Rigid motion modes (the near null space handed to GAMG)

TEST(RigidMotionModes, AreOrthonormalAndCostNoEnergyAwayFromPrescribedNodes)
{
    // The sliding cases, and a 3D box large enough to have nodes away from its boundary.
    const TestMesh box = structuredGrid(6, 6, 6, 1.0, {0.0, 0.0, 0.0});
    const RbmProblem boxProblem(3, box.points, box.graph, prescribeBoundary(box), EdgeWeighting::inverseDistanceSquared);
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, false}, {3, true}, {0, false}}) {
        const SlidingCase c = slidingCase(dimension == 0 ? 3 : dimension, 0.0, 0.0, EdgeWeighting::inverseDistanceSquared, mirror);
        const RbmProblem& problem = dimension == 0 ? boxProblem : *c.problem;
        const std::vector<std::vector<double>> modes = rigidMotionModes(problem);
        // Sliding nodes remove the normal translation; a mirror plane also the rotations about
        // in-plane axes. Whatever is left is orthonormal.
        const std::size_t expected = problem.dimension() == 2 ? 3 : 6;
        EXPECT_EQ(modes.size(), expected) << dimension << "D" << mirror;
        for (std::size_t a = 0; a < modes.size(); ++a)
            for (std::size_t b = 0; b < modes.size(); ++b) {
                double product = 0.0;
                for (std::size_t k = 0; k < modes[a].size(); ++k) product += modes[a][k] * modes[b][k];
                EXPECT_NEAR(product, a == b ? 1.0 : 0.0, 1e-12);
            }
        // H m = 0 in every row away from prescribed and sliding nodes: a rigid motion of the
        // unknown nodes strains only the edges to prescribed (fixed) nodes, and the sliding
        // constraint cut the modes' normal parts at the plane.
        const int bs = problem.blockSize();
        const std::vector<Vector3> zero(problem.nodeCount());
        const RbmEnergy energy(problem, RotationModel::smallAngle, zero);
        const BlockPattern& pattern = problem.blockPattern();
        std::vector<double> blocks(static_cast<std::size_t>(pattern.blockCount()) * bs * bs);
        energy.hessian(std::vector<double>(problem.unknownCount(), 0.0), blocks);
        problem.projectSlidingBlocks(blocks, bs);
        const CellNeighbourGraph& graph = problem.graph();
        int interiorRows = 0;
        for (const std::vector<double>& mode : modes) {
            for (int a = 0; a < pattern.rowCount(); ++a) {
                const int node = problem.unknownNodes()[a];
                bool nearPrescribed = problem.kind(node) == NodeKind::sliding;
                for (int e = graph.offsets[node]; e < graph.offsets[node + 1]; ++e)
                    nearPrescribed = nearPrescribed || problem.kind(graph.neighbours[e]) != NodeKind::free;
                if (nearPrescribed) continue;
                ++interiorRows;
                for (int p = 0; p < bs; ++p) {
                    double row = 0.0;
                    for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
                        for (int q = 0; q < bs; ++q)
                            row += blocks[(static_cast<std::size_t>(position) * bs + p) * bs + q] *
                                   mode[static_cast<std::size_t>(pattern.columns[position]) * bs + q];
                    EXPECT_NEAR(row, 0.0, 1e-9) << dimension << "D row " << a;
                }
            }
        }
        if (dimension != 3) {
            EXPECT_GT(interiorRows, 0);  // the small sliding boxes have none
        }
    }
}

// ---------------------------------------------------------------------------------------
// Sub-steps (thesis §2.6)

TEST(SubSteps, AutomaticCountMatchesAHandComputation)
{
    // A 4 × 3 grid with columns at x = 0, 1, 1.5, 3.5 and rows at y = 0, 2, 2.5.
    TestMesh mesh = structuredGrid(4, 3, 1, 1.0, {0.0, 0.0, 0.0});
    const double columns[4] = {0.0, 1.0, 1.5, 3.5};
    const double rows[3] = {0.0, 2.0, 2.5};
    for (std::size_t node = 0; node < mesh.points.size(); ++node)
        mesh.points[node] = {columns[mesh.gridIndex[node][0]], rows[mesh.gridIndex[node][1]], 0.0};
    std::vector<NodeConstraint> constraints = prescribeBoundary(mesh);
    const RbmProblem problem(2, mesh.points, mesh.graph, constraints, EdgeWeighting::uniform);
    auto nodeAt = [&](int i, int j) {
        for (std::size_t node = 0; node < mesh.points.size(); ++node)
            if (mesh.gridIndex[node][0] == i && mesh.gridIndex[node][1] == j) return static_cast<int>(node);
        return -1;
    };
    std::vector<Vector3> prescribed(mesh.points.size());
    EXPECT_EQ(automaticSubStepCount(problem, prescribed), 1);  // nothing moves
    // (3.5, 0): nearest neighbours (1.5, 0) and (3.5, 2) at 2; |u| = 5 → 5/2 = 2.5 → 3 steps.
    prescribed[nodeAt(3, 0)] = {3.0, 4.0, 0.0};
    EXPECT_EQ(automaticSubStepCount(problem, prescribed), 3);
    // (0, 2.5): nearest (0, 2) at 0.5; |u| = 0.5 → exactly one shortest distance → 2 steps.
    prescribed[nodeAt(0, 2)] = {0.3, 0.4, 0.0};
    EXPECT_EQ(automaticSubStepCount(problem, prescribed), 3);
    // (1.5, 0): nearest (1, 0) at 0.5; |u| = 2 → 4 → 5 steps, the largest.
    prescribed[nodeAt(2, 0)] = {1.2, -1.6, 0.0};
    EXPECT_EQ(automaticSubStepCount(problem, prescribed), 5);
    // A free node's entry does not count.
    prescribed[nodeAt(1, 1)] = {100.0, 0.0, 0.0};
    EXPECT_EQ(automaticSubStepCount(problem, prescribed), 5);
}

TEST(SubSteps, IncrementalLinearizedStepsConvergeToALargeRigidRotation)
{
    // Each increment turns the previous mesh by θ/n; the small-angle model errs by O((θ/n)²)
    // per increment, O(θ²/n) in total: the error must fall like 1/n.
    const double angle = degrees(60.0);
    const RigidCase c = rigidCase(2, angle, EdgeWeighting::inverseDistanceSquared);
    const BoundaryMotion turn = [&](double fraction) {
        RigidMotion partial = c.motion;
        partial.rotation = planarRotation(fraction * angle);
        partial.translation = fraction * c.motion.translation;
        return prescribedFrom(c.mesh, c.problem->constraints(), [&](const Vector3& x) { return partial.displacement(x); });
    };
    const RbmSolverFactory linearized = [](const RbmProblem& p) { return std::make_unique<CoupledLinearizedSolver>(p); };
    std::vector<double> errors;
    for (int count : {1, 10, 40}) {
        SubStepOptions options;
        options.count = count;
        const SubSteppedResult result = solveInSubSteps(*c.problem, turn, linearized, options);
        ASSERT_TRUE(result.converged) << result.reason;
        EXPECT_EQ(result.subStepCount, count);
        errors.push_back(maximumPositionError(c, result));
        // The rotations compose to the body's rotation.
        if (count == 40) {
            for (int node : c.problem->unknownNodes()) EXPECT_NEAR(result.rotation[node].z, angle, 0.02);
        }
    }
    EXPECT_GT(errors[0], 0.05 * c.meshSize);  // one linearized step cannot turn by 60°
    EXPECT_NEAR(errors[1] / errors[2], 4.0, 0.6);
    EXPECT_LT(errors[2], errors[0] / 20.0);
}

TEST(SubSteps, NewtonInSubStepsOnTheInitialMeshReachesTheDirectResult)
{
    // Continuation against the initial mesh: the result depends only on the final boundary.
    const SquaresCase c = squaresCase(21, 4, degrees(30.0));
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::inverseDistanceSquared);
    CoupledNewtonSolver newton(problem);
    const RbmResult direct = newton.solve(c.prescribed);
    SubStepOptions options;
    options.reference = SubStepReference::initialMesh;
    const SubSteppedResult stepped = solveInSubSteps(
        problem, c.prescribed, [](const RbmProblem& p) { return std::make_unique<CoupledNewtonSolver>(p); }, options);
    EXPECT_GT(stepped.subStepCount, 1);  // the rim moves by more than a cell
    ASSERT_TRUE(stepped.converged) << stepped.reason;
    EXPECT_NEAR(stepped.energy, direct.energy, 1e-9 * direct.energy);
    for (std::size_t node = 0; node < c.mesh.points.size(); ++node)
        ASSERT_LT(norm(stepped.displacement[node] - direct.displacement[node]), 1e-7);
}

// ---------------------------------------------------------------------------------------
// PETSc layer and input checks

TEST(PetscSupport, CheckPetscTurnsAnErrorIntoAnExceptionWithPetscsMessage)
{
    PetscKsp ksp;
    RBM_CHECK_PETSC(KSPCreate(PETSC_COMM_SELF, ksp.out()));
    try {
        RBM_CHECK_PETSC(KSPSetType(ksp, "noSuchKrylovMethod"));
        FAIL() << "no exception";
    } catch (const PetscException& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("KSPSetType(ksp, \"noSuchKrylovMethod\")"), std::string::npos) << message;
        EXPECT_NE(message.find("Unable to find requested KSP type noSuchKrylovMethod"), std::string::npos) << message;
        EXPECT_NE(error.code(), 0);
    }
}

// Sets PETSc options for one test and removes them afterwards.
class ScopedOptions {
public:
    explicit ScopedOptions(std::vector<std::pair<std::string, std::string>> options) : options_(std::move(options))
    {
        for (const auto& [name, value] : options_)
            RBM_CHECK_PETSC(PetscOptionsSetValue(nullptr, name.c_str(), value.empty() ? nullptr : value.c_str()));
    }
    ~ScopedOptions()
    {
        for (const auto& option : options_) (void)PetscOptionsClearValue(nullptr, option.first.c_str());
    }

private:
    std::vector<std::pair<std::string, std::string>> options_;
};

TEST(PetscSupport, SolverOptionsWithTheRbmPrefixOverrideTheDefaults)
{
    // 2D defaults to a direct factorisation (0 Krylov iterations); the options ask for CG.
    const SquaresCase c = squaresCase(21, 4, degrees(10.0));
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    CoupledLinearizedSolver direct(problem);
    const RbmResult byDirect = direct.solve(c.prescribed);
    EXPECT_EQ(byDirect.linearIterations, 0);
    const ScopedOptions options({{"-rbm_linearized_ksp_type", "cg"}, {"-rbm_linearized_pc_type", "jacobi"},
                                 {"-rbm_linearized_ksp_rtol", "1e-13"}});
    CoupledLinearizedSolver iterative(problem);
    const RbmResult byIterative = iterative.solve(c.prescribed);
    ASSERT_TRUE(byIterative.converged) << byIterative.reason;
    EXPECT_GT(byIterative.linearIterations, 10);
    for (std::size_t node = 0; node < c.mesh.points.size(); ++node)
        ASSERT_LT(norm(byIterative.displacement[node] - byDirect.displacement[node]), 1e-8);
}

TEST(PetscSupport, GlobalSolverOptionsAreHonoured)
{
    const SquaresCase c = squaresCase(21, 4, degrees(10.0));
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    const ScopedOptions options({{"-ksp_type", "cg"}, {"-pc_type", "icc"}});
    LocalGlobalSolver solver(problem);
    const RbmResult result = solver.solve(c.prescribed);
    ASSERT_TRUE(result.converged) << result.reason;
    EXPECT_GT(result.linearIterations, result.iterations);  // Krylov iterations in every Laplacian solve
}

TEST(PetscSupport, GlobalViewOptionsReachTheSolversAndSpecificOnesWin)
{
    // -snes_converged_reason is looked up at solve time under the solver's prefix.
    const SquaresCase c = squaresCase(11, 2, degrees(10.0));
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    std::string printed;
    {
        const ScopedOptions options({{"-snes_converged_reason", ""}, {"-ksp_converged_reason", ""},
                                     {"-rbm_linearized_ksp_converged_reason", "::failed"}});
        CoupledNewtonSolver solver(problem);
        ::testing::internal::CaptureStdout();
        const RbmResult result = solver.solve(c.prescribed);
        printed = ::testing::internal::GetCapturedStdout();
        ASSERT_TRUE(result.converged) << result.reason;
    }
    EXPECT_NE(printed.find("Nonlinear rbm_newton_ solve converged"), std::string::npos) << printed;
    EXPECT_NE(printed.find("Linear rbm_newton_ solve converged"), std::string::npos) << printed;
    EXPECT_EQ(printed.find("Linear rbm_linearized_ solve"), std::string::npos) << printed;  // only failures
    // The copies under rbm_newton_ leave with the solver.
    PetscBool left = PETSC_TRUE;
    RBM_CHECK_PETSC(PetscOptionsHasName(nullptr, nullptr, "-rbm_newton_snes_converged_reason", &left));
    EXPECT_EQ(left, PETSC_FALSE);
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
