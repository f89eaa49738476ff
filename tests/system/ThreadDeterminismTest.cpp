// The threaded loops (src/ThreadCount.hpp) give bitwise the same results with 1, 2 and 3
// threads: the cell-neighbour graph, the energy's value, gradient and Hessian blocks (2D
// and 3D, exact and small-angle rotations), the quality metrics, and whole local/global,
// Newton and decoupled solves. The threaded energy (which gathers each edge's terms at both
// ends) is also compared, bit for bit, with a plain serial transcription of its formula that
// scatters them (the order the threaded version reproduces). Each test checks that its problem is
// big enough to be threaded and that OpenMP really ran that many threads.

#include "CoupledNewtonSolver.hpp"
#include "DecoupledSolver.hpp"
#include "LocalGlobalSolver.hpp"
#include "MeshGenerators.hpp"
#include "MeshTopology.hpp"
#include "PetscTestEnvironment.hpp"
#include "PolyMeshReader.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "QualityReport.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"
#include "TestCases.hpp"
#include "ReducedNewtonSolver.hpp"
#include "SavedThreadSettings.hpp"
#include "ThreadCount.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace rbm::test::threadCases;

using namespace rbm;
using namespace rbm::motion;

namespace {

constexpr int threadCounts[] = {1, 2, 3};

// Runs compute() with each thread count and expects every result to equal the 1-thread one
// byte for byte. T must be trivially comparable through its bytes (vectors of doubles etc.
// are compared element-wise by the caller's projection).
template <class Result>
void expectSameForEveryThreadCount(const std::function<Result()>& compute,
                                   const std::function<std::vector<double>(const Result&)>& numbers,
                                   const char* what)
{
    const int before = threadCount();
#ifdef _OPENMP
    const int adaptsBefore = omp_get_dynamic();
#endif
    std::vector<double> reference;
    for (const int threads : threadCounts) {
        setThreadCount(threads);
#ifdef _OPENMP
        ASSERT_EQ(threadCount(), threads);
        ASSERT_EQ(threadsInAParallelRegion(), threads);
#endif
        const std::vector<double> values = numbers(compute());
        if (threads == 1) {
            reference = values;
            ASSERT_FALSE(reference.empty()) << what;
            continue;
        }
        ASSERT_EQ(values.size(), reference.size()) << what << ", " << threads << " threads";
        EXPECT_EQ(std::memcmp(values.data(), reference.data(), values.size() * sizeof(double)), 0)
            << what << ": " << threads << " threads differ from 1 thread";
    }
    setThreadCount(before);
#ifdef _OPENMP
    omp_set_dynamic(adaptsBefore);
#endif
}

template <class T>
std::vector<double> asDoubles(const std::vector<T>& values)
{
    static_assert(sizeof(T) % sizeof(double) == 0);
    std::vector<double> flat(values.size() * (sizeof(T) / sizeof(double)));
    std::memcpy(flat.data(), values.data(), flat.size() * sizeof(double));
    return flat;
}

std::vector<double> labelsAsDoubles(const CellNeighbourGraph& graph)
{
    std::vector<double> flat(graph.offsets.begin(), graph.offsets.end());
    flat.insert(flat.end(), graph.neighbours.begin(), graph.neighbours.end());
    return flat;
}

using rbm::test::airfoilMesh;

const PseudoTwoDMesh& airfoilPlane()
{
    static const PseudoTwoDMesh twoD = extractPseudoTwoD(airfoilMesh(), buildMeshTopology(airfoilMesh()));
    return twoD;
}

// A problem and the prescribed displacements of one step.
struct Case {
    std::unique_ptr<RbmProblem> problem;
    std::vector<Vector3> prescribed;
};

// The boundary-layer airfoil's plane: the airfoil turned 4° about its trailing edge (1, 0),
// the far field fixed, 1/|d|² weights.
Case airfoilCase()
{
    const PlanarMesh& planar = airfoilPlane().planar;
    std::vector<NodeConstraint> constraints(planar.nodeCount());
    Case c;
    c.prescribed.assign(planar.nodeCount(), Vector3{});
    const double angle = 4.0 * std::numbers::pi / 180.0;
    for (const PlanarPatch& patch : planar.patches) {
        for (Label e = patch.startEdge; e < patch.startEdge + patch.edgeCount; ++e) {
            for (const Label node : planar.edge(e)) {
                constraints[node].kind = NodeKind::prescribed;
                if (patch.name != "airfoil") continue;
                const Vector3 arm = planar.points[node] - Vector3{1.0, 0.0, 0.0};
                const Vector3 turned{std::cos(angle) * arm.x - std::sin(angle) * arm.y,
                                     std::sin(angle) * arm.x + std::cos(angle) * arm.y, 0.0};
                c.prescribed[node] = turned - arm;
            }
        }
    }
    c.problem = std::make_unique<RbmProblem>(2, planar.points, buildCellNeighbourGraph(planar), constraints);
    return c;
}

// A 10³ hexahedral box with jittered interior points: bottom fixed, top turned 20° about the
// vertical axis through its centre, the x = 0 side sliding on its plane, the rest free.
Case twistedBoxCase()
{
    constexpr Label n = 10;
    PolyMesh mesh = makeHexBox(n, n, n, {0, 0, 0}, {1, 1, 1});
    std::mt19937 random(7);
    std::uniform_real_distribution<double> jitter(-0.2 / n, 0.2 / n);
    std::vector<NodeConstraint> constraints(mesh.points.size());
    Case c;
    c.prescribed.assign(mesh.points.size(), Vector3{});
    const double angle = 20.0 * std::numbers::pi / 180.0;
    for (std::size_t p = 0; p < mesh.points.size(); ++p) {
        Vector3& x = mesh.points[p];
        const bool onSide = x.x == 0.0 || x.x == 1.0 || x.y == 0.0 || x.y == 1.0;
        if (x.z == 0.0 || x.z == 1.0) {
            constraints[p].kind = NodeKind::prescribed;
            if (x.z == 1.0) {
                const Vector3 arm = x - Vector3{0.5, 0.5, 1.0};
                c.prescribed[p] = Vector3{std::cos(angle) * arm.x - std::sin(angle) * arm.y,
                                          std::sin(angle) * arm.x + std::cos(angle) * arm.y, 0.0} - arm;
            }
        } else if (x.x == 0.0) {
            constraints[p].kind = NodeKind::sliding;
            constraints[p].normal = {1.0, 0.0, 0.0};
        } else if (!onSide) {
            x += Vector3{jitter(random), jitter(random), jitter(random)};
        }
    }
    c.problem = std::make_unique<RbmProblem>(3, mesh.points, buildCellNeighbourGraph(mesh), constraints);
    return c;
}

// A state near the solution with rotations of up to ~0.3 rad, so that every term of the
// exact Hessian (curvature included) is exercised.
std::vector<double> perturbedUnknowns(const RbmProblem& problem, unsigned seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> value(-0.3, 0.3);
    std::vector<double> unknowns(problem.unknownCount());
    for (double& u : unknowns) u = value(random) * (problem.meanEdgeLength() + 0.1);
    return unknowns;
}

// The energy, gradient and Hessian as a plain serial pass over the edges (i → j), each edge
// adding its terms to both ends as it goes (RbmEnergy.hpp, thesis eqs 2.27–2.47): the order
// the threaded evaluation must reproduce.
struct SerialEvaluation {
    double energy = 0.0;
    std::vector<double> gradient;
    std::vector<double> hessian;
};

SerialEvaluation serialScatterEvaluation(const RbmProblem& problem, RotationModel model,
                                         std::vector<Vector3> prescribed, const std::vector<double>& unknowns)
{
    const int dim = problem.dimension();
    const int bs = problem.blockSize();
    const int rotations = problem.rotationSize();
    const std::size_t area = static_cast<std::size_t>(bs) * bs;
    const CellNeighbourGraph& graph = problem.graph();
    if (dim == 2)
        for (Vector3& u : prescribed) u.z = 0.0;
    SerialEvaluation out;
    out.gradient.assign(unknowns.size(), 0.0);
    out.hessian.assign(area * problem.blockPattern().blockCount(), 0.0);
    auto displacement = [&](int node) {
        const int b = problem.unknownIndex()[node];
        if (b < 0) return prescribed[node];
        const double* block = unknowns.data() + static_cast<std::size_t>(b) * bs;
        return Vector3{block[0], block[1], dim == 3 ? block[2] : 0.0};
    };
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        const int i = problem.unknownNodes()[a];
        const RotationDerivatives R = rotationDerivatives(dim, model, unknowns.data() + static_cast<std::size_t>(a) * bs + dim);
        const Vector3 ui = displacement(i);
        double* gi = out.gradient.data() + static_cast<std::size_t>(a) * bs;
        double* hii = out.hessian.data() + area * problem.blockPattern().diagonal[a];
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            const double w = problem.edgeWeights()[e];
            Vector3 d = problem.referencePoints()[j] - problem.referencePoints()[i];
            if (dim == 2) d.z = 0.0;
            const Vector3 rotated = R.rotation * d;
            const Vector3 r = displacement(j) - ui + (d - rotated);
            out.energy += 0.5 * w * normSquared(r);
            std::array<Vector3, 3> a_;
            for (int k = 0; k < rotations; ++k) a_[k] = R.first[k] * d;
            const int b = problem.unknownIndex()[j];
            for (int q = 0; q < dim; ++q) gi[q] -= w * r[q];
            for (int k = 0; k < rotations; ++k) gi[dim + k] -= w * dot(a_[k], r);
            for (int q = 0; q < dim; ++q) hii[q * bs + q] += w;
            for (int k = 0; k < rotations; ++k) {
                for (int q = 0; q < dim; ++q) {
                    hii[q * bs + dim + k] += w * a_[k][q];
                    hii[(dim + k) * bs + q] += w * a_[k][q];
                }
                for (int l = 0; l < rotations; ++l)
                    hii[(dim + k) * bs + dim + l] += w * (dot(a_[k], a_[l]) - dot(r, R.second[symmetricIndex(k, l)] * d));
            }
            if (b < 0) continue;
            double* gj = out.gradient.data() + static_cast<std::size_t>(b) * bs;
            for (int q = 0; q < dim; ++q) gj[q] += w * r[q];
            double* hjj = out.hessian.data() + area * problem.blockPattern().diagonal[b];
            double* hij = out.hessian.data() + area * problem.edgeBlock()[e];
            double* hji = out.hessian.data() + area * problem.edgeTransposeBlock()[e];
            for (int q = 0; q < dim; ++q) {
                hjj[q * bs + q] += w;
                hij[q * bs + q] -= w;
                hji[q * bs + q] -= w;
            }
            for (int k = 0; k < rotations; ++k)
                for (int q = 0; q < dim; ++q) {
                    hij[(dim + k) * bs + q] -= w * a_[k][q];
                    hji[q * bs + dim + k] -= w * a_[k][q];
                }
        }
    }
    return out;
}

std::vector<double> energyGradientHessian(const RbmEnergy& energy, const std::vector<double>& unknowns)
{
    const RbmProblem& problem = energy.problem();
    std::vector<double> gradient(problem.unknownCount());
    std::vector<double> hessian(static_cast<std::size_t>(problem.blockPattern().blockCount()) * problem.blockSize() *
                                problem.blockSize());
    std::vector<double> out{energy.value(unknowns), energy.gradient(unknowns, gradient),
                            energy.projectedGradientNorm(unknowns), energy.gradientRoundoffNorm(unknowns)};
    energy.hessian(unknowns, hessian);
    out.insert(out.end(), gradient.begin(), gradient.end());
    out.insert(out.end(), hessian.begin(), hessian.end());
    energy.hessian(unknowns, hessian, false);
    out.insert(out.end(), hessian.begin(), hessian.end());
    return out;
}

void expectEnergyIsThreadIndependentAndSerial(const Case& c, RotationModel model, const char* what)
{
    const RbmProblem& problem = *c.problem;
    ASSERT_TRUE(worthThreading(problem.graph().neighbours.size())) << what << ": too small to be threaded";
    const std::vector<double> unknowns = perturbedUnknowns(problem, 11);
    const RbmEnergy energy(problem, model, c.prescribed);
    expectSameForEveryThreadCount<std::vector<double>>([&] { return energyGradientHessian(energy, unknowns); },
                                                       [](const std::vector<double>& v) { return v; }, what);

    // Against the serial scatter pass, bit for bit, with 3 threads.
    const SerialEvaluation serial = serialScatterEvaluation(problem, model, c.prescribed, unknowns);
    const int before = threadCount();
    setThreadCount(3);
    std::vector<double> gradient(problem.unknownCount());
    std::vector<double> hessian(serial.hessian.size());
    const double value = energy.gradient(unknowns, gradient);
    energy.hessian(unknowns, hessian);
    setThreadCount(before);
    EXPECT_EQ(std::memcmp(&value, &serial.energy, sizeof value), 0) << what << ": " << value << " vs " << serial.energy;
    EXPECT_EQ(std::memcmp(gradient.data(), serial.gradient.data(), gradient.size() * sizeof(double)), 0) << what;
    EXPECT_EQ(std::memcmp(hessian.data(), serial.hessian.data(), hessian.size() * sizeof(double)), 0) << what;
    EXPECT_GT(value, 0.0);
}

std::vector<double> resultNumbers(const RbmResult& result)
{
    std::vector<double> out = asDoubles(result.displacement);
    const std::vector<double> rotation = asDoubles(result.rotation);
    out.insert(out.end(), rotation.begin(), rotation.end());
    out.push_back(result.energy);
    out.push_back(result.residualNorm);
    out.push_back(result.iterations);
    out.push_back(result.linearIterations);
    out.push_back(result.converged ? 1.0 : 0.0);
    return out;
}

} // namespace

TEST(ThreadDeterminism, CellNeighbourGraphsAreTheSameForOneTwoAndThreeThreads)
{
    const PolyMesh& mesh = airfoilMesh();
    const MeshTopology topology = buildMeshTopology(mesh);
    ASSERT_TRUE(worthThreading(topology.cellPoints.size()));
    expectSameForEveryThreadCount<CellNeighbourGraph>([&] { return buildCellNeighbourGraph(topology); },
                                                      labelsAsDoubles, "3D graph of the airfoil mesh");
    ASSERT_TRUE(worthThreading(airfoilPlane().planar.cellPoints.size()));
    expectSameForEveryThreadCount<CellNeighbourGraph>([&] { return buildCellNeighbourGraph(airfoilPlane().planar); },
                                                      labelsAsDoubles, "2D graph of the airfoil plane");
    // Independent check of one row: node 0's neighbours are the other points of its cells.
    const CellNeighbourGraph graph = buildCellNeighbourGraph(topology);
    std::vector<Label> expected;
    for (const Label c : topology.cellsOf(0))
        for (const Label p : topology.pointsOf(c))
            if (p != 0) expected.push_back(p);
    std::sort(expected.begin(), expected.end());
    expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
    const auto row = graph.neighboursOf(0);
    EXPECT_EQ(std::vector<Label>(row.begin(), row.end()), expected);
}

TEST(ThreadDeterminism, EnergyGradientAndHessianAreTheSerialOnesBitForBit)
{
    const Case airfoil = airfoilCase();
    expectEnergyIsThreadIndependentAndSerial(airfoil, RotationModel::exact, "airfoil, exact rotations");
    expectEnergyIsThreadIndependentAndSerial(airfoil, RotationModel::smallAngle, "airfoil, small angles");
    const Case box = twistedBoxCase();
    expectEnergyIsThreadIndependentAndSerial(box, RotationModel::exact, "3D box, exact rotations");
    expectEnergyIsThreadIndependentAndSerial(box, RotationModel::smallAngle, "3D box, small angles");
}

TEST(ThreadDeterminism, QualityMetricsAreTheSameForOneTwoAndThreeThreads)
{
    const PolyMesh& mesh = airfoilMesh();
    QualityEvaluator evaluator(mesh);
    // Moved points: the mesh sheared, enough to change every metric.
    std::vector<Vector3> points = mesh.points;
    for (Vector3& p : points) p.x += 0.05 * std::sin(3.0 * p.y) * std::cos(2.0 * p.x);
    ASSERT_TRUE(worthThreading(static_cast<std::size_t>(mesh.faceCount())));
    expectSameForEveryThreadCount<std::string>([&] { return qualityReportJson(evaluator.evaluate(points)); },
                                               [](const std::string& json) {
                                                   // The JSON holds every figure in shortest round-trip form: equal text
                                                   // is equal bits. Compared as bytes, packed into doubles.
                                                   std::vector<double> packed((json.size() + 7) / 8, 0.0);
                                                   std::memcpy(packed.data(), json.data(), json.size());
                                                   return packed;
                                               },
                                               "quality report of the sheared airfoil mesh");
    const QualityReport report = evaluator.evaluate(points);
    EXPECT_EQ(report.thesis.dimension, 2);
    EXPECT_GT(report.checkMesh.maxNonOrthogonality, 0.0);
    EXPECT_GT(report.thesis.quadrilateralShape.count + report.thesis.triangleMeanRatio.count, 0);

    // A 3D mesh (the thesis metrics over faces): a 22³ hexahedral box with jittered points.
    const PolyMesh box = makeHexBox(22, 22, 22, {0, 0, 0}, {1, 1, 1});
    ASSERT_TRUE(worthThreading(static_cast<std::size_t>(box.internalFaceCount())));
    std::vector<Vector3> jittered = box.points;
    std::mt19937 random(3);
    std::uniform_real_distribution<double> jitter(-0.01, 0.01);
    for (Vector3& p : jittered) p += Vector3{jitter(random), jitter(random), jitter(random)};
    QualityEvaluator boxEvaluator(box);
    expectSameForEveryThreadCount<std::string>([&] { return qualityReportJson(boxEvaluator.evaluate(jittered)); },
                                               [](const std::string& json) {
                                                   std::vector<double> packed((json.size() + 7) / 8, 0.0);
                                                   std::memcpy(packed.data(), json.data(), json.size());
                                                   return packed;
                                               },
                                               "quality report of the jittered box");
    const QualityReport boxReport = boxEvaluator.evaluate(jittered);
    EXPECT_EQ(boxReport.thesis.dimension, 3);
    EXPECT_GT(boxReport.thesis.skewness.max, 0.0);

    // The log line's figures (evaluateStep), 2D and 3D.
    const auto stepFigures = [](const StepQuality& q) {
        return std::vector<double>{q.maxNonOrthogonality, q.maxSkewness, q.worstCellQuality,
                                   static_cast<double>(q.invertedCellCount)};
    };
    expectSameForEveryThreadCount<StepQuality>([&] { return evaluator.evaluateStep(points); }, stepFigures,
                                               "step figures of the sheared airfoil mesh");
    expectSameForEveryThreadCount<StepQuality>([&] { return boxEvaluator.evaluateStep(jittered); }, stepFigures,
                                               "step figures of the jittered box");
}

TEST(ThreadDeterminism, LocalGlobalSolvesAreTheSameForOneTwoAndThreeThreads)
{
    const Case box = twistedBoxCase();
    ASSERT_TRUE(worthThreading(box.problem->graph().neighbours.size()));
    expectSameForEveryThreadCount<RbmResult>(
        [&] {
            LocalGlobalSolver solver(*box.problem);
            const RbmResult result = solver.solve(box.prescribed);
            EXPECT_TRUE(result.converged) << result.reason;
            return result;
        },
        resultNumbers, "local/global on the twisted box");
}

TEST(ThreadDeterminism, NewtonSolvesAreTheSameForOneTwoAndThreeThreads)
{
    const Case box = twistedBoxCase();
    ASSERT_TRUE(worthThreading(box.problem->graph().neighbours.size()));
    expectSameForEveryThreadCount<RbmResult>(
        [&] {
            CoupledNewtonSolver solver(*box.problem);
            const RbmResult result = solver.solve(box.prescribed);
            EXPECT_TRUE(result.converged) << result.reason;
            EXPECT_GT(result.energy, 1e-3);   // a real deformation, not a trivial solve
            return result;
        },
        resultNumbers, "Newton on the twisted box");
}

TEST(ThreadDeterminism, ReducedNewtonSolvesAreTheSameForOneTwoAndThreeThreads)
{
    for (int which = 0; which < 2; ++which) {
        const Case c = which == 0 ? twistedBoxCase() : airfoilCase();
        ASSERT_TRUE(worthThreading(c.problem->graph().neighbours.size()));
        expectSameForEveryThreadCount<RbmResult>(
            [&] {
                ReducedNewtonSolver solver(*c.problem);
                const RbmResult result = solver.solve(c.prescribed);
                EXPECT_TRUE(result.converged) << result.reason;
                EXPECT_GT(result.energy, 1e-6);
                return result;
            },
            resultNumbers, "reduced Newton");
    }
}

TEST(ThreadDeterminism, DecoupledLinearizedSolvesAreTheSameForOneTwoAndThreeThreads)
{
    const Case box = twistedBoxCase();
    ASSERT_TRUE(worthThreading(box.problem->graph().neighbours.size()));
    DecoupledOptions linearized;
    linearized.model = DecoupledModel::linearized;
    expectSameForEveryThreadCount<RbmResult>(
        [&] {
            DecoupledSolver solver(*box.problem, linearized);
            return solver.solve(box.prescribed);
        },
        resultNumbers, "decoupled linearized on the twisted box");
}
