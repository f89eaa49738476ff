#pragma once
// The tests' shared fixtures and builders, in one header (tests/README.md). Sections:
//   - small problems of the motion solvers: a jittered structured grid with fixed, prescribed,
//     sliding and free nodes (GridCase), large motions of its top, P (K ⊗ I) P products;
//   - the reduced Newton method's problems and checks (options to round-off, free sides, one
//     rigid body in a fixed box, the comparison of minima);
//   - the OpenFOAM-facing solver over a mesh (makeSolver) and the boundary-layer airfoil;
//   - the small 2D case the tests that run the built rbmMoveMesh write (writeCompressionCase);
//   - what the tests of one area share, each in a namespace of its own that those tests use:
//     coreCases (the RBM core's meshes and cases), boundaryMotionCases, qualityCases,
//     polyMeshIOCases, topologyCases, threadCases, controlDictCases, moveMeshCases,
//     multigridCases, solverCases (the rigidBodyMotionSolver's meshes and motions).

#include "ControlDict.hpp"
#include "CoupledLinearizedSolver.hpp"
#include "CoupledNewtonSolver.hpp"
#include "DecoupledSolver.hpp"
#include "FoamDictionary.hpp"
#include "InputError.hpp"
#include "LocalGlobalSolver.hpp"
#include "MeshGenerators.hpp"
#include "MotionSolverRegistry.hpp"
#include "PolyMesh.hpp"
#include "PolyMeshReader.hpp"
#include "PolyMeshWriter.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"
#include "ReducedNewtonSolver.hpp"
#include "RigidBodyMotionSolver.hpp"
#include "ScratchFiles.hpp"
#include "TimeName.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

// ---------------------------------------------------------------------------------------
// Small test problems of the motion solvers: a jittered structured grid with fixed, prescribed,
// sliding and free nodes (2D or 3D), and large motions of its top.

namespace rbm::motion {

// A jittered structured grid of n^d cells over [0,1]^d (2D: quadrilaterals), its cell-neighbour
// graph built from the cells, and node classes: the bottom (y = 0 in 2D, z = 0 in 3D) fixed,
// the top prescribed, the left side (x = 0) sliding on its plane (a mirror in 3D when asked),
// the right side (x = 1) sliding but no mirror, everything else free.
struct GridCase {
    int dimension = 3;
    std::vector<Vector3> points;
    std::unique_ptr<RbmProblem> problem;
    std::vector<Vector3> prescribed;
};

// The cell-neighbour graph of cells given as point lists: neighbours = points sharing a cell.
inline CellNeighbourGraph graphOfCells(int nodeCount, const std::vector<std::vector<int>>& cells)
{
    std::vector<std::vector<int>> neighbours(nodeCount);
    for (const std::vector<int>& cell : cells)
        for (int a : cell)
            for (int b : cell)
                if (a != b) neighbours[a].push_back(b);
    CellNeighbourGraph graph;
    graph.offsets.assign(1, 0);
    for (std::vector<int>& list : neighbours) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
        graph.neighbours.insert(graph.neighbours.end(), list.begin(), list.end());
        graph.offsets.push_back(static_cast<Label>(graph.neighbours.size()));
    }
    return graph;
}

inline GridCase gridCase(int dimension, int n, bool mirror, unsigned seed)
{
    GridCase c;
    c.dimension = dimension;
    const int layers = dimension == 3 ? n + 1 : 1;
    auto index = [&](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> jitter(-0.2 / n, 0.2 / n);
    for (int k = 0; k < layers; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                Vector3 p{double(i) / n, double(j) / n, dimension == 3 ? double(k) / n : 0.0};
                const bool interior = i > 0 && i < n && j > 0 && j < n && (dimension == 2 || (k > 0 && k < n));
                if (interior) {
                    p.x += jitter(random);
                    p.y += jitter(random);
                    if (dimension == 3) p.z += jitter(random);
                }
                c.points.push_back(p);
            }
    const int nodeCount = static_cast<int>(c.points.size());
    std::vector<std::vector<int>> cells;
    for (int k = 0; k < (dimension == 3 ? n : 1); ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                std::vector<int>& cell = cells.emplace_back();
                for (int dk = 0; dk < (dimension == 3 ? 2 : 1); ++dk)
                    for (int dj = 0; dj < 2; ++dj)
                        for (int di = 0; di < 2; ++di) cell.push_back(index(i + di, j + dj, k + dk));
            }
    CellNeighbourGraph graph = graphOfCells(nodeCount, cells);

    std::vector<NodeConstraint> constraints(nodeCount);
    c.prescribed.assign(nodeCount, Vector3{});
    for (int node = 0; node < nodeCount; ++node) {
        const Vector3& p = c.points[node];
        const double height = dimension == 3 ? p.z : p.y;
        if (height == 0.0 || height == 1.0) {
            constraints[node].kind = NodeKind::prescribed;
            if (height == 1.0) {  // the top: turned 8° about the vertical through (0.5, 0.5) and shifted
                const double angle = 8.0 * 3.14159265358979 / 180.0;
                const double dx = p.x - 0.5, dy = dimension == 3 ? p.y - 0.5 : 0.0;
                c.prescribed[node] = dimension == 3
                                         ? Vector3{std::cos(angle) * dx - std::sin(angle) * dy - dx + 0.05,
                                                   std::sin(angle) * dx + std::cos(angle) * dy - dy, 0.03}
                                         : Vector3{0.1 * (1.0 + dx), 0.04 * dx, 0.0};
            }
        } else if (p.x == 0.0) {
            constraints[node] = {NodeKind::sliding, Vector3{-2.0, 0.0, 0.0}, mirror};
            c.prescribed[node] = {0.01, 0.0, 0.0};  // the plane itself moves by 0.01 along its normal
        } else if (p.x == 1.0) {
            constraints[node] = {NodeKind::sliding, Vector3{1.0, 0.0, 0.0}, false};
        }
    }
    c.problem = std::make_unique<RbmProblem>(dimension, c.points, std::move(graph), constraints,
                                             EdgeWeighting::inverseDistanceSquared);
    return c;
}

inline double largestDifference(const std::vector<Vector3>& a, const std::vector<Vector3>& b)
{
    double largest = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) largest = std::max(largest, norm(a[k] - b[k]));
    return largest;
}

// A large deformation of gridCase's top: turned 40° (2D: sheared by 0.3 and turned 25°), so
// that the exact rotations matter.
inline std::vector<Vector3> largeTopMotion(const GridCase& c)
{
    std::vector<Vector3> prescribed = c.prescribed;
    for (int node = 0; node < c.problem->nodeCount(); ++node) {
        const Vector3& p = c.points[node];
        const double height = c.dimension == 3 ? p.z : p.y;
        if (height != 1.0) continue;
        const double angle = (c.dimension == 3 ? 40.0 : 25.0) * 3.14159265358979 / 180.0;
        const double dx = p.x - 0.5, dy = c.dimension == 3 ? p.y - 0.5 : p.y - 1.0;
        prescribed[node] = {std::cos(angle) * dx - std::sin(angle) * dy - dx + (c.dimension == 2 ? 0.3 : 0.05),
                            std::sin(angle) * dx + std::cos(angle) * dy - dy, c.dimension == 3 ? 0.03 : 0.0};
    }
    return prescribed;
}

// P (K ⊗ I) P z on compact displacement vectors, K's values on problem.blockPattern().
inline std::vector<double> projectedLaplacianTimes(const RbmProblem& problem, const std::vector<double>& laplacian,
                                                   std::vector<double> z)
{
    const int dim = problem.dimension();
    const BlockPattern& pattern = problem.blockPattern();
    problem.projectSliding(z, dim);
    std::vector<double> y(z.size(), 0.0);
    for (int a = 0; a < problem.unknownNodeCount(); ++a)
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
            for (int q = 0; q < dim; ++q)
                y[static_cast<std::size_t>(a) * dim + q] +=
                    laplacian[position] * z[static_cast<std::size_t>(pattern.columns[position]) * dim + q];
    problem.projectSliding(y, dim);
    return y;
}

} // namespace rbm::motion

// ---------------------------------------------------------------------------------------
// Problems and checks shared by the reduced Newton method's tests: options to round-off, the
// grid cases with free sides, one rigid body in a fixed box, and the comparison of minima.

namespace rbm::motion {

// The method to round-off (displacementTolerance 0), for the tests of its exactness; the
// default stops within 1e-6 of each node's shortest edge.
inline ReducedNewtonOptions roundOffOptions()
{
    ReducedNewtonOptions options;
    options.displacementTolerance = 0.0;
    return options;
}

// gridCase with its sliding sides free (no sliding node: K is solved as a scalar system).
inline GridCase withFreeSides(GridCase c)
{
    std::vector<NodeConstraint> constraints(c.points.size());
    for (int node = 0; node < c.problem->nodeCount(); ++node)
        if (c.problem->kind(node) == NodeKind::prescribed) constraints[node].kind = NodeKind::prescribed;
        else c.prescribed[node] = Vector3{};
    c.problem = std::make_unique<RbmProblem>(c.dimension, c.points, c.problem->graph(), constraints,
                                             EdgeWeighting::inverseDistanceSquared);
    return c;
}

// The same boundary solved without and with the turned cold start (options otherwise alike):
// {plain, turned}.
inline std::pair<RbmResult, RbmResult> plainAndTurnedSolves(const RbmProblem& problem, ReducedNewtonOptions options,
                                                     const std::vector<Vector3>& prescribed)
{
    options.turnedStart = false;
    const RbmResult plain = ReducedNewtonSolver(problem, options).solve(prescribed);
    options.turnedStart = true;
    return {plain, ReducedNewtonSolver(problem, options).solve(prescribed)};
}

// Both converged to the same minimum (energy to 1e-10, every node to 1e-8), a non-trivial one.
inline void expectTheSameMinimum(const RbmResult& expected, const RbmResult& result)
{
    ASSERT_TRUE(expected.converged) << expected.reason;
    ASSERT_TRUE(result.converged) << result.reason;
    EXPECT_GT(expected.energy, 1e-3);
    EXPECT_NEAR(result.energy, expected.energy, 1e-10 * expected.energy);
    EXPECT_LT(largestDifference(result.displacement, expected.displacement), 1e-8);
}

// One rigid body in a fixed frame: the nodes of the grid's central square (a body) turned by
// `degrees` about its centre and shifted, the outer boundary fixed, the nodes between free.
// Returns the problem's constraints and the prescribed displacement.
struct BodyInBox {
    std::vector<NodeConstraint> constraints;
    std::vector<Vector3> prescribed;
};
inline BodyInBox bodyInBox(const GridCase& grid, int n, double degrees)
{
    BodyInBox box{std::vector<NodeConstraint>(grid.points.size()), std::vector<Vector3>(grid.points.size())};
    const double angle = degrees * 3.14159265358979 / 180.0;
    for (std::size_t node = 0; node < grid.points.size(); ++node) {
        const int i = static_cast<int>(node) % (n + 1), j = static_cast<int>(node) / (n + 1);
        const bool outer = i == 0 || j == 0 || i == n || j == n;
        const bool body = i >= 6 && i <= 10 && j >= 6 && j <= 10;
        if (!outer && !body) continue;
        box.constraints[node].kind = NodeKind::prescribed;
        if (body) {
            const double dx = grid.points[node].x - 0.5, dy = grid.points[node].y - 0.5;
            box.prescribed[node] = {std::cos(angle) * dx - std::sin(angle) * dy - dx + 0.001 * degrees,
                                    std::sin(angle) * dx + std::cos(angle) * dy - dy - 0.02 * degrees / 30.0, 0.0};
        }
    }
    return box;
}

} // namespace rbm::motion

// ---------------------------------------------------------------------------------------
// Builders shared by the tests of the OpenFOAM-facing solver: a rigidBodyMotionSolver over a
// mesh, made from the entries of its rigidBodyMotionSolverCoeffs, and the boundary-layer
// airfoil fixture (tests/data/airfoilBoundaryLayer).

namespace rbm::test {

// A rigidBodyMotionSolver over `mesh` with the given coefficient entries (the body of
// rigidBodyMotionSolverCoeffs) and, optionally, 0/pointDisplacement's boundaryField.
inline std::unique_ptr<motion::MotionSolver> makeSolver(const PolyMesh& mesh, const std::string& coefficients,
                                                        const io::Dictionary* pointDisplacement = nullptr)
{
    const io::Dictionary dict = io::Dictionary::parseText(
        "motionSolver rigidBodyMotionSolver;\nrigidBodyMotionSolverCoeffs\n{\n" + coefficients + "\n}\n",
        "constant/dynamicMeshDict");
    return motion::builtinMotionSolvers().create(mesh, dict, pointDisplacement, "/nonexistent/case");
}

// The NACA4415 fixture with a hexahedral boundary layer, read once per test program.
inline const PolyMesh& airfoilMesh()
{
    static const PolyMesh mesh =
        io::readPolyMesh(std::filesystem::path(RBM_TEST_DATA_DIR) / "airfoilBoundaryLayer" / "constant" / "polyMesh");
    return mesh;
}

} // namespace rbm::test

// ---------------------------------------------------------------------------------------
// A small 2D OpenFOAM case for the tests that run the built rbmMoveMesh on a case of their
// own (KillDuringWriteTest, WriteFailureTest, CaseLockTest): n × n quadrilaterals on the
// unit square, one layer; the left side moves right, the right side is fixed, top and
// bottom slide: a smooth compression, no inverted cell. deltaT 0.1, every step written as
// ascii with 17 digits (large files: writing takes a noticeable part of a step).

namespace rbm::test {

inline std::string foamHeader(const std::string& className, const std::string& location, const std::string& object)
{
    return "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class " + className + ";\n    location \"" +
           location + "\";\n    object " + object + ";\n}\n\n";
}

inline std::string controlDict(bool compressed, const std::string& endTime = "0.3")
{
    return foamHeader("dictionary", "system", "controlDict") +
           "application rbmMoveMesh;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\nendTime " + endTime +
           ";\ndeltaT 0.1;\nwriteControl timeStep;\nwriteInterval 1;\nwriteFormat ascii;\nwritePrecision 17;\n"
           "writeCompression " +
           std::string(compressed ? "on" : "off") + ";\ntimeFormat general;\ntimePrecision 6;\n";
}

// The left side moves right by `speed` per unit time.
inline std::string pointDisplacement(const std::string& speed)
{
    return foamHeader("pointVectorField", "0", "pointDisplacement") +
           "dimensions [0 1 0 0 0 0 0];\ninternalField uniform (0 0 0);\nboundaryField\n{\n"
           "    left { type uniformFixedValue; uniformValue table ((0 (0 0 0)) (1 (" +
           speed +
           " 0 0))); value uniform (0 0 0); }\n"
           "    right { type fixedValue; value uniform (0 0 0); }\n"
           "    \"(top|bottom)\" { type slip; }\n"
           "    frontAndBack { type empty; }\n}\n";
}

// The case with `cells` × `cells` quadrilaterals (mesh in binary, to read fast), steps up to
// `endTime`, written gzip-compressed or not.
inline void writeCompressionCase(const std::filesystem::path& caseDir, Label cells, const std::string& endTime,
                                 bool compressed = true)
{
    const PolyMesh mesh = makeExtruded2D(cells, cells, Vector3{0, 0, 0}, Vector3{1, 1, 0.01});
    io::FoamWriteOptions binary;
    binary.binary = true;
    io::writePolyMesh(caseDir / "constant" / "polyMesh", mesh, binary);
    writeText(caseDir / "system" / "controlDict", controlDict(compressed, endTime));
    writeText(caseDir / "constant" / "dynamicMeshDict",
              foamHeader("dictionary", "constant", "dynamicMeshDict") +
                  "dynamicFvMesh dynamicMotionSolverFvMesh;\nmotionSolver rigidBodyMotionSolver;\n"
                  "rigidBodyMotionSolverCoeffs\n{\n    formulation linearized;\n    subSteps 1;\n}\n");
    writeText(caseDir / "0" / "pointDisplacement", pointDisplacement("0.2"));
}

} // namespace rbm::test

// ---------------------------------------------------------------------------------------
// The RBM core's test meshes and cases (the tests of the energy, the problem and its solvers).

namespace rbm::motion::coreCases {

constexpr double pi = std::numbers::pi;

inline double degrees(double value) { return value * pi / 180.0; }

// Nodes sharing a cell are neighbours (the definition of docs/method.md §1), built directly so
// these tests do not depend on buildCellNeighbourGraph.
inline CellNeighbourGraph graphFromCells(int nodeCount, const std::vector<int>& cellOffsets, const std::vector<int>& cellPoints)
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
inline TestMesh structuredGrid(int nx, int ny, int nz, double h, Vector3 origin,
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
inline void jitter(TestMesh& mesh, double amplitude, unsigned seed)
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
inline std::vector<bool> boundaryNodes(const TestMesh& mesh)
{
    const int interiorCount = mesh.dimension == 2 ? 8 : 26;
    std::vector<bool> boundary(mesh.points.size());
    for (int node = 0; node < static_cast<int>(mesh.points.size()); ++node)
        boundary[node] = mesh.graph.offsets[node + 1] - mesh.graph.offsets[node] < interiorCount;
    return boundary;
}

inline std::vector<NodeConstraint> prescribeBoundary(const TestMesh& mesh)
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

inline std::vector<Vector3> prescribedFrom(const TestMesh& mesh, const std::vector<NodeConstraint>& constraints,
                                    const std::function<Vector3(const Vector3&)>& displacement)
{
    std::vector<Vector3> values(mesh.points.size());
    for (std::size_t node = 0; node < values.size(); ++node)
        if (constraints[node].kind != NodeKind::free) values[node] = displacement(mesh.points[node]);
    return values;
}

using DenseMatrix = std::vector<std::vector<double>>;

inline DenseMatrix denseFromBlocks(const RbmProblem& problem, const std::vector<double>& blocks, int bs)
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
inline bool choleskySucceeds(DenseMatrix a)
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

struct RigidCase {
    TestMesh mesh;
    std::unique_ptr<RbmProblem> problem;
    RigidMotion motion;
    std::vector<Vector3> prescribed;
    double meshSize = 1.0;
};

// 2D: 9 × 9 nodes, spacing 0.5, boundary prescribed; 3D: 5 × 5 × 5 nodes, spacing 1.
inline RigidCase rigidCase(int dimension, double angle, EdgeWeighting weighting)
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

inline double maximumPositionError(const RigidCase& c, const RbmResult& result)
{
    double largest = 0.0;
    for (std::size_t node = 0; node < c.mesh.points.size(); ++node)
        largest = std::max(largest, norm(result.displacement[node] - c.motion.displacement(c.mesh.points[node])));
    return largest;
}

struct SquaresCase {
    TestMesh mesh;
    std::vector<NodeConstraint> constraints;
    std::vector<Vector3> prescribed;
};

inline SquaresCase squaresCase(int outerNodes, int innerCells, double angle, double jitterAmplitude = 0.0)
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

inline SlidingCase slidingCase(int dimension, double angle, double lift, EdgeWeighting weighting, bool mirror = false)
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

} // namespace rbm::motion::coreCases

// ---------------------------------------------------------------------------------------
// The boundary-motion tests' fixtures (tests/data/boundaryMotion) and checks: dictionaries from
// text, vectors to a tolerance, the message of an rbm::InputError.

namespace rbm::test::boundaryMotionCases {

constexpr double pi = std::numbers::pi;

inline std::filesystem::path dataPath(const std::string& relative)
{
    return std::filesystem::path(RBM_TEST_DATA_DIR) / "boundaryMotion" / relative;
}

inline io::Dictionary parse(const std::string& text) { return io::Dictionary::parseText(text, "test.dict"); }

inline void expectNear(const Vector3& actual, const Vector3& expected, double tolerance = 1e-12)
{
    EXPECT_NEAR(actual.x, expected.x, tolerance) << "actual " << actual << " expected " << expected;
    EXPECT_NEAR(actual.y, expected.y, tolerance) << "actual " << actual << " expected " << expected;
    EXPECT_NEAR(actual.z, expected.z, tolerance) << "actual " << actual << " expected " << expected;
}

// Runs `action`, expects an rbm::InputError and returns its what().
template <class Action>
std::string inputErrorOf(Action action)
{
    try {
        action();
    } catch (const InputError& error) {
        return error.what();
    }
    ADD_FAILURE() << "no rbm::InputError thrown";
    return {};
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

} // namespace rbm::test::boundaryMotionCases

// ---------------------------------------------------------------------------------------
// The quality tests' hand-built meshes (a cell from its faces, the unit cube, sheared pairs).

namespace rbm::test::qualityCases {

using rbm::Label;
using rbm::PolyMesh;
using rbm::Vector3;

constexpr double pi = std::numbers::pi;

inline double degrees(double radians) { return radians * 180.0 / pi; }

// A cell given as its faces, each oriented outward (right-hand normal out of the cell).
using CellFaces = std::vector<std::vector<Label>>;

// Builds an OpenFOAM-ordered PolyMesh from cells given by outward faces: faces shared by
// two cells become internal (owned by the lower cell, oriented as that cell gives them),
// sorted by owner then neighbour; all other faces go to one patch "walls".
inline PolyMesh buildMesh(std::vector<Vector3> points, const std::vector<CellFaces>& cells)
{
    struct FaceRecord {
        std::vector<Label> points;
        Label owner = -1;
        Label neighbour = -1;
    };
    std::map<std::vector<Label>, FaceRecord> faces;
    for (Label c = 0; c < static_cast<Label>(cells.size()); ++c) {
        for (const auto& face : cells[c]) {
            auto key = face;
            std::sort(key.begin(), key.end());
            auto [it, inserted] = faces.try_emplace(key);
            if (inserted) {
                it->second.points = face;
                it->second.owner = c;
            } else {
                it->second.neighbour = c;
            }
        }
    }
    std::vector<const FaceRecord*> internal;
    std::vector<const FaceRecord*> boundary;
    for (const auto& [key, record] : faces) (record.neighbour >= 0 ? internal : boundary).push_back(&record);
    std::sort(internal.begin(), internal.end(), [](const FaceRecord* a, const FaceRecord* b) {
        return std::tie(a->owner, a->neighbour) < std::tie(b->owner, b->neighbour);
    });
    std::sort(boundary.begin(), boundary.end(), [](const FaceRecord* a, const FaceRecord* b) { return a->owner < b->owner; });

    PolyMesh mesh;
    mesh.points = std::move(points);
    for (const FaceRecord* face : internal) {
        mesh.addFace(face->points);
        mesh.owner.push_back(face->owner);
        mesh.neighbour.push_back(face->neighbour);
    }
    for (const FaceRecord* face : boundary) {
        mesh.addFace(face->points);
        mesh.owner.push_back(face->owner);
    }
    rbm::Patch walls;
    walls.name = "walls";
    walls.type = "wall";
    walls.startFace = static_cast<Label>(internal.size());
    walls.faceCount = static_cast<Label>(boundary.size());
    mesh.patches.push_back(walls);
    return mesh;
}

// Hexahedron with points p0..p3 (bottom, counter-clockwise seen from above) and p4..p7
// above them: outward faces in OpenFOAM's hex model order.
inline CellFaces hexFaces(Label offset = 0)
{
    auto o = [offset](std::initializer_list<Label> f) {
        std::vector<Label> v;
        for (Label p : f) v.push_back(p + offset);
        return v;
    };
    return {o({0, 4, 7, 3}), o({1, 2, 6, 5}), o({0, 1, 5, 4}), o({3, 7, 6, 2}), o({0, 3, 2, 1}), o({4, 5, 6, 7})};
}

inline std::vector<Vector3> unitCubePoints(const Vector3& origin = {})
{
    std::vector<Vector3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (auto& x : p) x += origin;
    return p;
}

// The unit cube [0,1]^3 (cell 0) and, sharing its x = 1 face, a parallelepiped whose far
// face is shifted by `shear` in y (cell 1).
inline PolyMesh shearedPair(double shear)
{
    auto points = unitCubePoints();
    // Far points of cell 1: (2, shear + {0,1}, {0,1}).
    points.push_back({2, shear, 0});       // 8
    points.push_back({2, 1 + shear, 0});   // 9
    points.push_back({2, 1 + shear, 1});   // 10
    points.push_back({2, shear, 1});       // 11
    // Cell 1 as a hex: bottom (1, 8, 9, 2), top (5, 11, 10, 6).
    const std::vector<Label> map = {1, 8, 9, 2, 5, 11, 10, 6};
    CellFaces second;
    for (const auto& face : hexFaces()) {
        std::vector<Label> f;
        for (Label p : face) f.push_back(map[p]);
        second.push_back(f);
    }
    return buildMesh(points, {hexFaces(), second});
}

} // namespace rbm::test::qualityCases

// ---------------------------------------------------------------------------------------
// The polyMesh reader's and writer's fixtures (tests/data/formats) and checks.

namespace rbm::test::polyMeshIOCases {

namespace fs = std::filesystem;
using rbm::Label;
using rbm::PolyMesh;
using rbm::Vector3;
using rbm::io::FoamWriteOptions;
using rbm::test::TempDir;
using rbm::test::readText;
using rbm::test::writeText;

inline const fs::path formatsDir = fs::path(RBM_TEST_DATA_DIR) / "formats";

inline fs::path polyMeshOf(const std::string& variant)
{
    return formatsDir / variant / "constant" / "polyMesh";
}

// Runs `read` and checks that it throws an InputError whose message contains every fragment.
inline void expectInputError(const std::function<void()>& read, const std::vector<std::string>& fragments, int line = -1)
{
    try {
        read();
        ADD_FAILURE() << "expected an rbm::InputError";
    } catch (const rbm::InputError& e) {
        for (const std::string& fragment : fragments)
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << "'" << fragment << "' not in: " << e.what();
        if (line >= 0) {
            EXPECT_EQ(e.line(), line) << e.what();
        }
    }
}

inline void expectSameTopology(const PolyMesh& a, const PolyMesh& b)
{
    EXPECT_EQ(a.faceOffsets, b.faceOffsets);
    EXPECT_EQ(a.facePoints, b.facePoints);
    EXPECT_EQ(a.owner, b.owner);
    EXPECT_EQ(a.neighbour, b.neighbour);
    ASSERT_EQ(a.patches.size(), b.patches.size());
    for (std::size_t p = 0; p < a.patches.size(); ++p) {
        EXPECT_EQ(a.patches[p].name, b.patches[p].name);
        EXPECT_EQ(a.patches[p].type, b.patches[p].type);
        EXPECT_EQ(a.patches[p].inGroups, b.patches[p].inGroups);
        EXPECT_EQ(a.patches[p].startFace, b.patches[p].startFace);
        EXPECT_EQ(a.patches[p].faceCount, b.patches[p].faceCount);
        EXPECT_EQ(a.patches[p].otherEntries, b.patches[p].otherEntries);
    }
    for (auto zones : {&PolyMesh::pointZones, &PolyMesh::faceZones, &PolyMesh::cellZones}) {
        ASSERT_EQ((a.*zones).size(), (b.*zones).size());
        for (std::size_t z = 0; z < (a.*zones).size(); ++z) {
            EXPECT_EQ((a.*zones)[z].name, (b.*zones)[z].name);
            EXPECT_EQ((a.*zones)[z].labels, (b.*zones)[z].labels);
            EXPECT_EQ((a.*zones)[z].flipMap, (b.*zones)[z].flipMap);
        }
    }
}

// Points equal to `digits` significant digits: |a - b| <= 0.5e-(digits-1) |b| per component.
inline void expectPointsEqualToDigits(const std::vector<Vector3>& a, const std::vector<Vector3>& b, int digits)
{
    ASSERT_EQ(a.size(), b.size());
    const double relative = 0.5 * std::pow(10.0, 1 - digits) * (1 + 1e-9);
    for (std::size_t i = 0; i < a.size(); ++i) {
        for (int c = 0; c < 3; ++c)
            ASSERT_LE(std::abs(a[i][c] - b[i][c]), relative * std::abs(b[i][c])) << "point " << i << " component " << c;
    }
}

inline bool bitIdentical(const std::vector<Vector3>& a, const std::vector<Vector3>& b)
{
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vector3)) == 0;
}

inline const PolyMesh& binaryFixture()
{
    static const PolyMesh mesh = rbm::io::readPolyMesh(polyMeshOf("binary"));
    return mesh;
}

} // namespace rbm::test::polyMeshIOCases

// ---------------------------------------------------------------------------------------
// Single cells of the topology and cell-shape tests.

namespace rbm::test::topologyCases {

using namespace rbm;

// A single cell from outward-oriented faces, all in one boundary patch "walls".
inline PolyMesh singleCell(std::vector<Vector3> points, const std::vector<std::vector<Label>>& faces)
{
    PolyMesh mesh;
    mesh.points = std::move(points);
    for (const auto& face : faces) {
        mesh.addFace(face);
        mesh.owner.push_back(0);
    }
    Patch walls;
    walls.name = "walls";
    walls.type = "wall";
    walls.startFace = 0;
    walls.faceCount = static_cast<Label>(faces.size());
    mesh.patches.push_back(walls);
    return mesh;
}

inline PolyMesh unitTetrahedron()
{
    return singleCell({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

} // namespace rbm::test::topologyCases

// ---------------------------------------------------------------------------------------
// How many threads a parallel region has (the thread tests).

namespace rbm::test::threadCases {

// Threads OpenMP actually starts in a parallel region with the current setting.
inline int threadsInAParallelRegion()
{
    int seen = 1;
#ifdef _OPENMP
#pragma omp parallel
    {
#pragma omp single
        seen = omp_get_num_threads();
    }
#endif
    return seen;
}

} // namespace rbm::test::threadCases

// ---------------------------------------------------------------------------------------
// A scratch case of the controlDict and time-name tests.

namespace rbm::test::controlDictCases {

namespace fs = std::filesystem;

inline fs::path scratchCase(const std::string& name)
{
    fs::path folder = fs::path(testing::TempDir()) / ("rbmControlDictTest_" + name);
    fs::remove_all(folder);
    fs::create_directories(folder / "system");
    return folder;
}

} // namespace rbm::test::controlDictCases

// ---------------------------------------------------------------------------------------
// The time loop's checks: time folders, no temporary files left, the flat JSON of a log line.

namespace rbm::test::moveMeshCases {

using rbm::test::TempDir;
using rbm::test::readText;
using rbm::test::writeText;
namespace fs = std::filesystem;

// Names of the time folders of a case.
inline std::set<std::string> timeFolders(const fs::path& caseDir)
{
    std::set<std::string> names;
    for (const auto& time : io::listTimeDirectories(caseDir)) names.insert(time.name);
    return names;
}

inline void expectNoTemporaryFiles(const fs::path& caseDir)
{
    for (const auto& entry : fs::recursive_directory_iterator(caseDir)) {
        EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
            << "left behind: " << entry.path();
    }
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A minimal JSON reader for the flat objects of log.jsonl: string, number, true, false,
// null values. Returns false for anything that is not such an object.
struct JsonValue {
    enum class Kind { String, Number, Bool, Null } kind = Kind::Null;
    std::string text;
    double number = 0.0;
    bool boolean = false;
};

inline bool parseFlatJsonObject(const std::string& line, std::map<std::string, JsonValue>& object)
{
    std::size_t i = 0;
    auto skip = [&] {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    };
    auto parseString = [&](std::string& out) {
        if (i >= line.size() || line[i] != '"') return false;
        for (++i; i < line.size() && line[i] != '"'; ++i) {
            if (line[i] == '\\') {
                if (++i >= line.size()) return false;
                const char c = line[i];
                out += c == 'n' ? '\n' : c == 't' ? '\t' : c;
            } else {
                out += line[i];
            }
        }
        if (i >= line.size()) return false;
        ++i;
        return true;
    };
    skip();
    if (i >= line.size() || line[i++] != '{') return false;
    while (true) {
        skip();
        std::string key;
        if (!parseString(key)) return false;
        skip();
        if (i >= line.size() || line[i++] != ':') return false;
        skip();
        JsonValue value;
        if (i < line.size() && line[i] == '"') {
            value.kind = JsonValue::Kind::String;
            if (!parseString(value.text)) return false;
        } else if (line.compare(i, 4, "true") == 0 || line.compare(i, 5, "false") == 0) {
            value.kind = JsonValue::Kind::Bool;
            value.boolean = line[i] == 't';
            i += value.boolean ? 4 : 5;
        } else if (line.compare(i, 4, "null") == 0) {
            value.kind = JsonValue::Kind::Null;
            i += 4;
        } else {
            const char* begin = line.c_str() + i;
            char* end = nullptr;
            value.kind = JsonValue::Kind::Number;
            value.number = std::strtod(begin, &end);
            if (end == begin) return false;
            i += static_cast<std::size_t>(end - begin);
        }
        if (object.count(key)) return false;   // duplicate key
        object[key] = value;
        skip();
        if (i < line.size() && line[i] == ',') {
            ++i;
            continue;
        }
        if (i < line.size() && line[i] == '}') {
            ++i;
            skip();
            return i == line.size();
        }
        return false;
    }
}

} // namespace rbm::test::moveMeshCases

// ---------------------------------------------------------------------------------------
// Laplacians of the multigrid tests.

namespace rbm::test::multigridCases {

using namespace rbm::motion;

// K on the (n − 1)³ interior nodes of an n³-cell unit cube: neighbours = the 26 nodes sharing a
// cell, weight 1/|d|², K_ii = Σ_j w (boundary neighbours fixed), K_ij = −w. Rows sorted.
struct Laplacian {
    int rows = 0;
    std::vector<int> offsets{0}, columns;
    std::vector<double> values;

    std::vector<double> times(const std::vector<double>& x) const  // 3 interleaved vectors
    {
        std::vector<double> y(x.size(), 0.0);
        for (int row = 0; row < rows; ++row)
            for (int k = offsets[row]; k < offsets[row + 1]; ++k)
                for (int c = 0; c < 3; ++c) y[3 * row + c] += values[k] * x[3 * columns[k] + c];
        return y;
    }
};

inline Laplacian hexLaplacian(int n)
{
    Laplacian K;
    const int m = n - 1;
    K.rows = m * m * m;
    const double h = 1.0 / n;
    auto index = [m](int i, int j, int k) { return (i - 1) + m * ((j - 1) + m * (k - 1)); };
    for (int k = 1; k <= m; ++k)
        for (int j = 1; j <= m; ++j)
            for (int i = 1; i <= m; ++i) {
                double diagonal = 0.0;
                std::vector<std::pair<int, double>> row;
                for (int dk = -1; dk <= 1; ++dk)
                    for (int dj = -1; dj <= 1; ++dj)
                        for (int di = -1; di <= 1; ++di) {
                            if (di == 0 && dj == 0 && dk == 0) continue;
                            const double w = 1.0 / ((di * di + dj * dj + dk * dk) * h * h);
                            diagonal += w;
                            const int a = i + di, b = j + dj, c = k + dk;
                            if (a >= 1 && a <= m && b >= 1 && b <= m && c >= 1 && c <= m) row.emplace_back(index(a, b, c), -w);
                        }
                row.emplace_back(index(i, j, k), diagonal);
                std::sort(row.begin(), row.end());
                for (const auto& [column, value] : row) {
                    K.columns.push_back(column);
                    K.values.push_back(value);
                }
                K.offsets.push_back(static_cast<int>(K.columns.size()));
            }
    return K;
}

} // namespace rbm::test::multigridCases

// ---------------------------------------------------------------------------------------
// Meshes and motions of the OpenFOAM-facing solver's tests (rigidBodyMotionSolver, stiffening).

namespace rbm::test::solverCases {

using namespace rbm::motion;

inline double degrees(double angle) { return angle * std::numbers::pi / 180.0; }

// One layer of cells extruded from 2D polygons (nodes in the xy-plane, polygons
// counter-clockwise) between z0 and z1, with OpenFOAM's face order: internal faces sorted by
// owner then neighbour, then the boundary faces patch by patch. `sidePatchOf(a, b)` names the
// patch of the boundary edge a–b (one of `sidePatches`); the front (z0) and back (z1) faces go
// to one patch "frontAndBack" or, with `separateFrontAndBack`, to "front" and "back", of type
// `planeType`.
inline PolyMesh extrudePolygons(const std::vector<Vector3>& nodes, const std::vector<std::vector<Label>>& polygons,
                         const std::vector<Patch>& sidePatches,
                         const std::function<std::string(const Vector3&, const Vector3&)>& sidePatchOf, double z0,
                         double z1, const std::string& planeType = "empty", bool separateFrontAndBack = false)
{
    const Label n = static_cast<Label>(nodes.size());
    PolyMesh mesh;
    for (const Vector3& node : nodes) mesh.points.push_back({node.x, node.y, z0});
    for (const Vector3& node : nodes) mesh.points.push_back({node.x, node.y, z1});

    struct EdgeUse {
        Label cell, a, b;
    };
    std::map<std::pair<Label, Label>, std::vector<EdgeUse>> edges;
    for (Label c = 0; c < static_cast<Label>(polygons.size()); ++c) {
        const auto& polygon = polygons[c];
        for (std::size_t k = 0; k < polygon.size(); ++k) {
            const Label a = polygon[k];
            const Label b = polygon[(k + 1) % polygon.size()];
            edges[{std::min(a, b), std::max(a, b)}].push_back({c, a, b});
        }
    }
    struct Internal {
        Label owner, neighbour, a, b;
    };
    std::vector<Internal> internal;
    std::map<std::string, std::vector<EdgeUse>> boundary;
    for (const auto& [key, uses] : edges) {
        if (uses.size() == 2) {
            const EdgeUse& first = uses[0].cell < uses[1].cell ? uses[0] : uses[1];
            const EdgeUse& second = uses[0].cell < uses[1].cell ? uses[1] : uses[0];
            internal.push_back({first.cell, second.cell, first.a, first.b});
        } else {
            boundary[sidePatchOf(nodes[uses[0].a], nodes[uses[0].b])].push_back(uses[0]);
        }
    }
    std::sort(internal.begin(), internal.end(), [](const Internal& l, const Internal& r) {
        return std::pair(l.owner, l.neighbour) < std::pair(r.owner, r.neighbour);
    });
    // Side face of edge a -> b (owner's counter-clockwise order): normal points out of the owner.
    auto addSide = [&](Label a, Label b, Label owner) {
        mesh.addFace(std::vector<Label>{a, b, b + n, a + n});
        mesh.owner.push_back(owner);
    };
    for (const Internal& face : internal) {
        addSide(face.a, face.b, face.owner);
        mesh.neighbour.push_back(face.neighbour);
    }
    for (const Patch& side : sidePatches) {
        Patch patch = side;
        patch.startFace = mesh.faceCount();
        for (const EdgeUse& use : boundary[side.name]) addSide(use.a, use.b, use.cell);
        patch.faceCount = mesh.faceCount() - patch.startFace;
        mesh.patches.push_back(patch);
    }
    auto addPlane = [&](bool front) {
        for (Label c = 0; c < static_cast<Label>(polygons.size()); ++c) {
            std::vector<Label> face;
            if (front) {
                for (auto it = polygons[c].rbegin(); it != polygons[c].rend(); ++it) face.push_back(*it);  // normal -z
            } else {
                for (Label p : polygons[c]) face.push_back(p + n);  // normal +z
            }
            mesh.addFace(face);
            mesh.owner.push_back(c);
        }
    };
    if (separateFrontAndBack) {
        for (bool front : {true, false}) {
            Patch patch{front ? "front" : "back", planeType, {}, mesh.faceCount(), 0, {}};
            addPlane(front);
            patch.faceCount = mesh.faceCount() - patch.startFace;
            mesh.patches.push_back(patch);
        }
    } else {
        Patch patch{"frontAndBack", planeType, {}, mesh.faceCount(), 0, {}};
        addPlane(true);
        addPlane(false);
        patch.faceCount = mesh.faceCount() - patch.startFace;
        mesh.patches.push_back(patch);
    }
    return mesh;
}

// The thesis' squares (§3.1): a square of cells × cells squares of side `spacing`, with a
// square hole of holeCells × holeCells cells at its centre. Patches: "inner" (the hole's
// rim), "outer", and the front and back planes. cells = 100, holeCells = 20, spacing = 10 is
// the thesis' grid: 101 nodes per side, inner side 200, 9840 nodes, 9600 quadrilaterals.
inline PolyMesh squaresMesh(int cells, int holeCells, double spacing, const std::string& planeType = "empty",
                     bool separateFrontAndBack = false)
{
    const int first = (cells - holeCells) / 2;
    const int last = first + holeCells;
    auto inHoleInterior = [&](int i, int j) { return i > first && i < last && j > first && j < last; };
    std::vector<Vector3> nodes;
    std::vector<Label> index((cells + 1) * (cells + 1), -1);
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
            if (inHoleInterior(i, j)) continue;
            index[i + (cells + 1) * j] = static_cast<Label>(nodes.size());
            nodes.push_back({spacing * i, spacing * j, 0.0});
        }
    std::vector<std::vector<Label>> polygons;
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            if (i >= first && i < last && j >= first && j < last) continue;
            auto at = [&](int a, int b) { return index[a + (cells + 1) * b]; };
            polygons.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    const double size = spacing * cells;
    auto side = [size](const Vector3& a, const Vector3& b) {
        const Vector3 m = 0.5 * (a + b);
        const bool outer = m.x == 0.0 || m.y == 0.0 || m.x == size || m.y == size;
        return std::string(outer ? "outer" : "inner");
    };
    return extrudePolygons(nodes, polygons, {Patch{"inner", "wall", {}, 0, 0, {}}, Patch{"outer", "patch", {}, 0, 0, {}}}, side, 0.0, spacing,
                           planeType, separateFrontAndBack);
}

// Rigid motion x -> centre + R (x − centre) + translation, R by `angle` about `axis`.
struct RigidMotion {
    Vector3 axis{0.0, 0.0, 1.0};
    double angle = 0.0;
    Vector3 centre;
    Vector3 translation;

    Vector3 apply(const Vector3& x) const
    {
        const motion::Matrix3 rotation = motion::rotationFromVector(angle / norm(axis) * axis);
        return centre + rotation * (x - centre) + translation;
    }
    Vector3 displacement(const Vector3& x) const { return apply(x) - x; }
};

inline std::vector<Vector3> patchDisplacement(const MotionSolver& solver, const std::string& patch,
                                       const std::function<Vector3(const Vector3&)>& displacementOf)
{
    const PolyMesh& mesh = solver.mesh();
    const std::vector<Label> points = patchMeshPoints(mesh, mesh.findPatch(patch));
    std::vector<Vector3> values;
    for (Label p : points) values.push_back(displacementOf(solver.points0()[p]));
    return values;
}

inline const RigidBodyMotionSolver& asRbm(const MotionSolver& solver) { return dynamic_cast<const RigidBodyMotionSolver&>(solver); }

inline std::string errorOf(const std::function<void()>& action)
{
    try {
        action();
    } catch (const InputError& error) {
        return error.what();
    }
    return "no InputError";
}

} // namespace rbm::test::solverCases

// ---------------------------------------------------------------------------------------
// Cyclic patches (CyclicPairsTest, CyclicCouplingTest): one-layer meshes whose opposite sides
// are the two halves of a cyclic interface, built with extrudePolygons, and the partners of a
// cyclic side's points found by brute force from the known transform.

namespace rbm::test::cyclicCases {

using namespace rbm::motion;

inline Patch cyclicPatch(const std::string& name, const std::string& neighbour,
                         std::vector<std::pair<std::string, std::string>> transformEntries)
{
    Patch patch{name, "cyclic", {}, 0, 0, {{"neighbourPatch", neighbour}}};
    for (auto& entry : transformEntries) patch.otherEntries.push_back(std::move(entry));
    return patch;
}

// A channel [0, length] × [0, height] of nx × ny square-ish quadrilaterals, one layer
// (z in [0, 0.1]), with a rectangular body cut out of cells [bodyI0, bodyI1) × [bodyJ0, bodyJ1).
// Patches: "inlet" (x = 0) and "outlet" (x = length), a translational cyclic pair; "walls"
// (y = 0 and y = height); "body"; then the planes (`planeType`, "frontAndBack" or, with
// separateFrontAndBack, "front" and "back").
inline PolyMesh channelWithBody(double length, double height, int nx, int ny, int bodyI0, int bodyI1, int bodyJ0,
                                int bodyJ1, const std::string& planeType = "empty", bool separateFrontAndBack = false)
{
    auto inBody = [&](int i, int j) { return i >= bodyI0 && i < bodyI1 && j >= bodyJ0 && j < bodyJ1; };
    std::vector<Vector3> nodes;
    std::vector<Label> index((nx + 1) * (ny + 1), -1);
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            if (i > bodyI0 && i < bodyI1 && j > bodyJ0 && j < bodyJ1) continue;  // inside the body
            index[i + (nx + 1) * j] = static_cast<Label>(nodes.size());
            nodes.push_back({length * i / nx, height * j / ny, 0.0});
        }
    std::vector<std::vector<Label>> polygons;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            if (inBody(i, j)) continue;
            auto at = [&](int a, int b) { return index[a + (nx + 1) * b]; };
            polygons.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    auto side = [=](const Vector3& a, const Vector3& b) {
        const Vector3 m = 0.5 * (a + b);
        if (m.x == 0.0) return std::string("inlet");
        if (m.x == length) return std::string("outlet");
        if (m.y == 0.0 || m.y == height) return std::string("walls");
        return std::string("body");
    };
    const std::string separation = "(" + std::to_string(length) + " 0 0)";
    return solverCases::extrudePolygons(
        nodes, polygons,
        {cyclicPatch("inlet", "outlet", {{"transform", "translational"}, {"separationVector", separation}}),
         cyclicPatch("outlet", "inlet", {{"transform", "translational"}, {"separationVector", "(-" + separation.substr(1)}}),
         Patch{"walls", "wall", {}, 0, 0, {}}, Patch{"body", "wall", {}, 0, 0, {}}},
        side, 0.0, 0.1, planeType, separateFrontAndBack);
}

// The sector r in [rInner, rOuter], θ in [0, sectorDegrees] of an annulus about the z axis,
// nr × nθ cells, one layer (z in [0, 0.1]). Patches: "sideA" (θ = 0) and "sideB" (θ = sector),
// a rotational cyclic pair about z through the origin, written as OpenFOAM 13 writes it
// (transformType, no angle); "inner", "outer"; then the planes as in channelWithBody.
inline PolyMesh annulusSector(double rInner, double rOuter, double sectorDegrees, int nr, int ntheta,
                              const std::string& planeType = "empty", bool separateFrontAndBack = false)
{
    std::vector<Vector3> nodes;
    for (int j = 0; j <= ntheta; ++j)
        for (int i = 0; i <= nr; ++i) {
            const double r = rInner + (rOuter - rInner) * i / nr;
            const double theta = solverCases::degrees(sectorDegrees) * j / ntheta;
            nodes.push_back({r * std::cos(theta), r * std::sin(theta), 0.0});
        }
    std::vector<std::vector<Label>> polygons;
    for (int j = 0; j < ntheta; ++j)
        for (int i = 0; i < nr; ++i) {
            auto at = [&](int a, int b) { return static_cast<Label>(a + (nr + 1) * b); };
            polygons.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    const double sector = solverCases::degrees(sectorDegrees);
    auto side = [=](const Vector3& a, const Vector3& b) {
        const Vector3 m = 0.5 * (a + b);
        const double theta = std::atan2(m.y, m.x);
        if (std::abs(theta) < 1e-9) return std::string("sideA");
        if (std::abs(theta - sector) < 1e-9) return std::string("sideB");
        return std::string(norm(m) < 0.5 * (rInner + rOuter) ? "inner" : "outer");
    };
    const std::vector<std::pair<std::string, std::string>> rotation{
        {"transformType", "rotational"}, {"rotationAxis", "(0 0 1)"}, {"rotationCentre", "(0 0 0)"}};
    return solverCases::extrudePolygons(nodes, polygons,
                                        {cyclicPatch("sideA", "sideB", rotation), cyclicPatch("sideB", "sideA", rotation),
                                         Patch{"inner", "wall", {}, 0, 0, {}}, Patch{"outer", "wall", {}, 0, 0, {}}},
                                        side, 0.0, 0.1, planeType, separateFrontAndBack);
}

// For every point of patch `a`, the point of patch `b` nearest to image(x_a), by brute force.
inline std::vector<std::pair<Label, Label>> partnersByGeometry(const PolyMesh& mesh, const std::string& a,
                                                               const std::string& b,
                                                               const std::function<Vector3(const Vector3&)>& image)
{
    const std::vector<Label> pointsA = patchMeshPoints(mesh, mesh.findPatch(a));
    const std::vector<Label> pointsB = patchMeshPoints(mesh, mesh.findPatch(b));
    std::vector<std::pair<Label, Label>> pairs;
    for (Label pa : pointsA) {
        const Vector3 target = image(mesh.points[pa]);
        Label best = pointsB.front();
        for (Label pb : pointsB)
            if (norm(mesh.points[pb] - target) < norm(mesh.points[best] - target)) best = pb;
        pairs.emplace_back(pa, best);
    }
    return pairs;
}

// The pointDisplacement field of a case: `boundaryField` is the text inside boundaryField { }.
inline io::Dictionary pointDisplacementField(const std::string& boundaryField)
{
    return io::Dictionary::parseText("dimensions [0 1 0 0 0 0 0];\ninternalField uniform (0 0 0);\nboundaryField\n{\n" +
                                         boundaryField + "\n}\n",
                                     "0/pointDisplacement");
}

} // namespace rbm::test::cyclicCases
