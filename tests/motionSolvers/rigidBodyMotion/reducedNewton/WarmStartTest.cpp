#include "WarmStart.hpp"

#include "PetscTestEnvironment.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace rbm::motion {
namespace {

TEST(WarmStart, AfterAColdSolveTheReferenceMeshIsTheResultBeforeIt)
{
    // No displacement is the exact minimum for a boundary at rest, so a cold solve's result
    // continues a chain from the reference mesh: the next warm start takes the secant predictor.
    // (a) Back to rest after 10°: the secant is exactly −1, the predictor exactly zero, and the
    // solve ends there without an iteration (outside a chain it started from the guess and
    // iterated). (b) A series 10° → 12° → 14° (the default tolerance): the second step's Newton
    // correction is a chain's, so the third step takes the subspace step along it: against the
    // same series without kept corrections (correctionMemory 0), both within 10 tolerances of the
    // minima, and fewer CG iterations at the third step.
    const int n = 16;
    const GridCase grid = gridCase(2, n, false, 29);
    const BodyInBox tenDegrees = bodyInBox(grid, n, 10.0);
    const RbmProblem problem(2, grid.points, grid.problem->graph(), tenDegrees.constraints, EdgeWeighting::inverseDistanceSquared);
    {
        ReducedNewtonSolver solver(problem, roundOffOptions());
        const RbmResult turned = solver.solve(tenDegrees.prescribed);
        ASSERT_TRUE(turned.converged) << turned.reason;
        const RbmResult atRest = solver.solve(std::vector<Vector3>(grid.points.size()), &turned);
        ASSERT_TRUE(atRest.converged) << atRest.reason;
        EXPECT_EQ(atRest.iterations, 0);
        EXPECT_EQ(atRest.linearIterations, 0);
        EXPECT_EQ(largestDifference(atRest.displacement, std::vector<Vector3>(grid.points.size())), 0.0);
    }
    std::vector<std::vector<RbmResult>> series;
    const std::vector<BodyInBox> steps{bodyInBox(grid, n, 10.0), bodyInBox(grid, n, 12.0), bodyInBox(grid, n, 14.0)};
    for (const int memory : {0, 3}) {
        ReducedNewtonOptions options;
        options.correctionMemory = memory;
        ReducedNewtonSolver solver(problem, options);
        std::vector<RbmResult>& results = series.emplace_back();
        for (std::size_t k = 0; k < steps.size(); ++k) {
            results.push_back(solver.solve(steps[k].prescribed, k == 0 ? nullptr : &results.back()));
            ASSERT_TRUE(results.back().converged) << "memory " << memory << ", step " << k + 1 << ": " << results.back().reason;
        }
    }
    // Both within 10 displacement tolerances of the grid's spacing of the minimum solved to round-off.
    const double bound = 10.0 * ReducedNewtonOptions{}.displacementTolerance / n;
    for (std::size_t k = 0; k < steps.size(); ++k) {
        const RbmResult exact = ReducedNewtonSolver(problem, roundOffOptions()).solve(steps[k].prescribed);
        ASSERT_TRUE(exact.converged) << exact.reason;
        for (const std::vector<RbmResult>& results : series)
            EXPECT_LT(largestDifference(results[k].displacement, exact.displacement), bound) << "step " << k + 1;
    }
    std::printf("body in a box, 10 -> 12 -> 14 deg: third step %d Newton / %d CG without kept corrections, %d / %d with\n",
                series[0][2].iterations, series[0][2].linearIterations, series[1][2].iterations,
                series[1][2].linearIterations);
    EXPECT_EQ(series[1][1].linearIterations, series[0][1].linearIterations);   // nothing kept yet
    EXPECT_LT(series[1][2].linearIterations, series[0][2].linearIterations);
}

TEST(WarmStart, ABoundaryBackAtRestStartsFromTheReferenceMeshAndTheChainGoesOn)
{
    // 10° → 5° → 0° → −5° along a chain: at 0° the body is back at rest, which the reference mesh
    // (no displacement) is its exact minimum, so the solve starts there and ends
    // without an iteration, at no displacement exactly (with the secant's start: 4 Newton steps).
    // The chain goes on: −5° reaches the cold solve's minimum (to round-off).
    const int n = 16;
    const GridCase grid = gridCase(2, n, false, 29);
    const std::vector<BodyInBox> bodies{bodyInBox(grid, n, 10.0), bodyInBox(grid, n, 5.0), bodyInBox(grid, n, 0.0),
                                        bodyInBox(grid, n, -5.0)};
    const RbmProblem problem(2, grid.points, grid.problem->graph(), bodies[0].constraints, EdgeWeighting::inverseDistanceSquared);
    ReducedNewtonSolver solver(problem, roundOffOptions());
    std::vector<RbmResult> results;
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        results.push_back(solver.solve(bodies[k].prescribed, k == 0 ? nullptr : &results.back()));
        ASSERT_TRUE(results.back().converged) << "step " << k + 1 << ": " << results.back().reason;
    }
    const std::vector<Vector3> rest(grid.points.size());
    EXPECT_EQ(results[2].iterations, 0);
    EXPECT_EQ(results[2].linearIterations, 0);
    EXPECT_EQ(largestDifference(results[2].displacement, rest), 0.0);
    const RbmResult cold = ReducedNewtonSolver(problem, roundOffOptions()).solve(bodies[3].prescribed);
    ASSERT_TRUE(cold.converged) << cold.reason;
    EXPECT_NEAR(results[3].energy, cold.energy, 1e-10 * cold.energy);
    EXPECT_LT(largestDifference(results[3].displacement, cold.displacement), 1e-8);
    // With the default tolerance, 6° → 4° → 2° → 0° → −2°: the step at rest keeps the secant's
    // miss as the chain's correction, and the step after it converges with the subspace step
    // along it alone (no CG iteration; with the rest start's own zero correction instead: 2).
    ReducedNewtonSolver loose(problem, ReducedNewtonOptions{});
    std::vector<RbmResult> series;
    for (const double degrees : {6.0, 4.0, 2.0, 0.0, -2.0}) {
        series.push_back(loose.solve(bodyInBox(grid, n, degrees).prescribed, series.empty() ? nullptr : &series.back()));
        ASSERT_TRUE(series.back().converged) << degrees << " deg: " << series.back().reason;
    }
    EXPECT_EQ(series[3].iterations, 0);
    EXPECT_EQ(largestDifference(series[3].displacement, rest), 0.0);
    EXPECT_EQ(series[4].linearIterations, 0);
    const RbmResult exact = ReducedNewtonSolver(problem, roundOffOptions()).solve(bodyInBox(grid, n, -2.0).prescribed);
    EXPECT_LT(largestDifference(series[4].displacement, exact.displacement), 10.0 * ReducedNewtonOptions{}.displacementTolerance / n);
}

TEST(WarmStart, AtABoundaryMetBeforeTheDisplacementTestComesBeforeTheSubspaceStep)
{
    // 2° → 4° → 6° → 4° (default tolerance): at the turning point the secant predictor is the
    // kept 4° result, which meets the boundary to rounding and is its minimum already. The
    // displacement test then comes first and ends the solve: no subspace step (with its three S
    // products) is tried, which -rbm_reduced_monitor shows, and the result is the kept one.
    const int n = 16;
    const GridCase grid = gridCase(2, n, false, 29);
    const RbmProblem problem(2, grid.points, grid.problem->graph(), bodyInBox(grid, n, 2.0).constraints,
                             EdgeWeighting::inverseDistanceSquared);
    // The solver reads -rbm_reduced_monitor when it is built; only the last solve's lines are kept.
    ASSERT_EQ(PetscOptionsSetValue(nullptr, "-rbm_reduced_monitor", nullptr), 0);
    ReducedNewtonSolver solver(problem, ReducedNewtonOptions{});
    ASSERT_EQ(PetscOptionsClearValue(nullptr, "-rbm_reduced_monitor"), 0);
    std::vector<RbmResult> series;
    std::string printed;
    for (const double degrees : {2.0, 4.0, 6.0, 4.0}) {
        const bool last = series.size() == 3;
        if (last) {
            std::fflush(stdout);
            ::testing::internal::CaptureStdout();
        }
        series.push_back(solver.solve(bodyInBox(grid, n, degrees).prescribed, series.empty() ? nullptr : &series.back()));
        if (last) {
            std::fflush(stdout);
            printed = ::testing::internal::GetCapturedStdout();
        }
        ASSERT_TRUE(series.back().converged) << degrees << " deg: " << series.back().reason;
    }
    EXPECT_NE(printed.find("displacement test at the reproduced boundary"), std::string::npos) << printed;
    EXPECT_EQ(printed.find("subspace"), std::string::npos) << printed;
    EXPECT_EQ(series[3].iterations, 0);
    EXPECT_EQ(series[3].linearIterations, 0);
    EXPECT_EQ(series[3].reason, "CONVERGED_DISPLACEMENT");
    EXPECT_LT(largestDifference(series[3].displacement, series[1].displacement), 1e-12);
}

TEST(WarmStart, AfterARestartTheSecondStepTakesASubspaceStepAlongTheFirstStepsCorrection)
{
    // A restart: a new solver warm-started from another's result at 10° (no history: outside a
    // chain), then 20° → 30° → 40°. Its second solve (30°) is a warm start outside a chain too
    // (one result kept): its turned start misses the minimum by nearly the field the first
    // solve's turned start missed by, so a Galerkin step along the first solve's Newton
    // correction comes first. The solve after it (the first of a chain) does not use it: the
    // secant predictor misses differently. Against the same restart without the subspace step
    // (correctionMemory 0): the same minima to round-off, fewer CG iterations at 30°, the same
    // iterations at 40°.
    const int n = 16;
    const GridCase grid = gridCase(2, n, false, 29);
    const std::vector<BodyInBox> bodies{bodyInBox(grid, n, 10.0), bodyInBox(grid, n, 20.0), bodyInBox(grid, n, 30.0),
                                        bodyInBox(grid, n, 40.0)};
    const RbmProblem problem(2, grid.points, grid.problem->graph(), bodies[0].constraints, EdgeWeighting::inverseDistanceSquared);
    const RbmResult before = ReducedNewtonSolver(problem, roundOffOptions()).solve(bodies[0].prescribed);
    ASSERT_TRUE(before.converged) << before.reason;
    std::vector<std::vector<RbmResult>> series;
    for (const int memory : {0, 3}) {
        ReducedNewtonOptions options = roundOffOptions();
        options.correctionMemory = memory;
        ReducedNewtonSolver restarted(problem, options);
        std::vector<RbmResult>& results = series.emplace_back();
        for (std::size_t k = 1; k < bodies.size(); ++k) {
            results.push_back(restarted.solve(bodies[k].prescribed, k == 1 ? &before : &results.back()));
            ASSERT_TRUE(results.back().converged) << "memory " << memory << ", " << 10 * (k + 1) << " deg: " << results.back().reason;
        }
    }
    for (std::size_t k = 0; k < series[0].size(); ++k) expectTheSameMinimum(series[0][k], series[1][k]);
    std::printf("body in a box, restart at 10 deg -> 20 -> 30 -> 40 deg: 30 deg %d Newton / %d CG without the subspace "
                "step, %d / %d with it; 40 deg %d / %d and %d / %d\n",
                series[0][1].iterations, series[0][1].linearIterations, series[1][1].iterations,
                series[1][1].linearIterations, series[0][2].iterations, series[0][2].linearIterations,
                series[1][2].iterations, series[1][2].linearIterations);
    EXPECT_LT(series[1][1].linearIterations, series[0][1].linearIterations);
    EXPECT_EQ(series[1][2].iterations, series[0][2].iterations);
    EXPECT_EQ(series[1][2].linearIterations, series[0][2].linearIterations);
}

TEST(WarmStart, SubspaceOfPastCorrectionsSavesIterationsAndKeepsTheMinima)
{
    // A smooth series (the top's motion scaled by sin, warm-started from each result): from the
    // fourth step on, the first step of every solve is the Galerkin step in the span of the
    // last three Newton corrections (correctionMemory, the default). Solved to round-off, every
    // step ends where the series without it ends (the minima do not move); with the default
    // displacementTolerance, every node within 10 tolerances of the grid spacing of it, and
    // with fewer CG iterations: the secant predictor misses by nearly the same field each step.
    // Measured (10 steps): 2D 57 → 38 CG iterations, 3D 63 → 44 (to round-off 128 → 111 and
    // 167 → 140, where the last Newton steps' CG to the rounding level dominates).
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, true}}) {
        const GridCase c = gridCase(dimension, dimension == 2 ? 16 : 6, mirror, 31);
        const std::vector<Vector3> top = largeTopMotion(c);
        const double spacing = 1.0 / (dimension == 2 ? 16 : 6);
        for (const bool toRoundOff : {true, false}) {
            ReducedNewtonOptions without = toRoundOff ? roundOffOptions() : ReducedNewtonOptions{};
            ReducedNewtonOptions with = without;
            ASSERT_EQ(with.correctionMemory, 3);  // the default
            without.correctionMemory = 0;
            const double bound = toRoundOff ? 1e-8 : 10.0 * with.displacementTolerance * spacing;
            ReducedNewtonSolver plain(*c.problem, without), recycling(*c.problem, with);
            RbmResult plainState, recyclingState;
            int plainIterations = 0, recyclingIterations = 0;
            for (int step = 1; step <= 10; ++step) {
                std::vector<Vector3> boundary = top;
                for (Vector3& v : boundary) v = std::sin(0.15 * step) * v;
                const RbmResult a = plain.solve(boundary, step == 1 ? nullptr : &plainState);
                const RbmResult b = recycling.solve(boundary, step == 1 ? nullptr : &recyclingState);
                ASSERT_TRUE(a.converged) << a.reason;
                ASSERT_TRUE(b.converged) << b.reason;
                EXPECT_LT(largestDifference(b.displacement, a.displacement), bound)
                    << dimension << "D step " << step << (toRoundOff ? ", to round-off" : "");
                if (toRoundOff) {
                    EXPECT_NEAR(b.energy, a.energy, 1e-10 * a.energy) << dimension << "D step " << step;
                }
                plainIterations += a.linearIterations;
                recyclingIterations += b.linearIterations;
                plainState = a;
                recyclingState = b;
            }
            std::printf("%dD%s: CG iterations %d without, %d with the subspace step\n", dimension,
                        toRoundOff ? " to round-off" : "", plainIterations, recyclingIterations);
            if (!toRoundOff) {
                EXPECT_LT(recyclingIterations, 0.8 * plainIterations) << dimension << "D";
            }
        }
    }
}

TEST(WarmStart, AfterATurningPointTheStartIsTheResultOfTheSameBoundary)
{
    // The top's motion scaled by sin(π k / 10), k = 1…7: a turning point at k = 5, and k = 6, 7
    // repeat the boundaries of k = 4, 3. At k = 7 the secant through the results of k = 6 (= 4)
    // and 5 would extrapolate by α = (s7 − s6)/(s6 − s5) = 2.9, clamped to 2, the wrong way; the
    // fit on the boundary over the kept results picks the result of k = 3 instead, and the
    // solve stops at the displacement test with no iteration.
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, true}}) {
        const GridCase c = gridCase(dimension, dimension == 2 ? 16 : 6, mirror, 41);
        const std::vector<Vector3> top = largeTopMotion(c);
        ReducedNewtonSolver solver(*c.problem);
        std::vector<RbmResult> results(8);
        for (int k = 1; k <= 7; ++k) {
            std::vector<Vector3> boundary = top;
            for (Vector3& v : boundary) v = std::sin(M_PI * k / 10.0) * v;
            results[k] = solver.solve(boundary, k == 1 ? nullptr : &results[k - 1]);
            ASSERT_TRUE(results[k].converged) << dimension << "D step " << k << ": " << results[k].reason;
        }
        EXPECT_EQ(results[7].iterations, 0) << dimension << "D";
        EXPECT_EQ(results[7].linearIterations, 0) << dimension << "D";
        EXPECT_LT(largestDifference(results[7].displacement, results[3].displacement), 1e-12) << dimension << "D";
        EXPECT_GT(largestDifference(results[7].displacement, results[6].displacement), 1e-3) << dimension << "D";
    }
}

TEST(WarmStart, ARigidBodysSeriesTakesThePredictorsHarmonicCorrectionFromFewExtensions)
{
    // The top turned by θ_k = θ sin(π k / 8) about its centre and shifted along x by
    // 0.1 sin(π k / 8), k = 1…12: every change of the prescribed displacement between steps is
    // (cos θ' − cos θ)(x − c) + (sin θ' − sin θ) ẑ × (x − c) + s e_x on the top and zero below,
    // a vector of one fixed three-dimensional space. So at most three extensions K⁻¹ B m are
    // kept, the later warm starts take their correction from them, and the series ends where
    // the same series with a back-substitution at every step ends (both to round-off). (Free
    // sides: with sliding nodes the boundary enters b through their offsets too, and no basis
    // is kept.)
    for (const int dimension : {2, 3}) {
        const GridCase c = withFreeSides(gridCase(dimension, dimension == 2 ? 14 : 5, false, 43));
        const double amplitude = (dimension == 2 ? 25.0 : 30.0) * 3.14159265358979 / 180.0;
        ReducedNewtonOptions withBasis;
        withBasis.displacementTolerance = 0.0;
        ReducedNewtonOptions withoutBasis = withBasis;
        withoutBasis.harmonicBasis = false;
        ReducedNewtonSolver fromBasis(*c.problem, withBasis), solving(*c.problem, withoutBasis);
        RbmResult last, lastSolved;
        const int steps = 12;
        for (int k = 1; k <= steps; ++k) {
            const double phase = std::sin(3.14159265358979 * k / 8.0);
            std::vector<Vector3> boundary = c.prescribed;
            for (int node = 0; node < c.problem->nodeCount(); ++node) {
                const Vector3& p = c.points[node];
                if ((dimension == 3 ? p.z : p.y) != 1.0) continue;
                const double angle = amplitude * phase;
                const double dx = p.x - 0.5, dy = dimension == 3 ? p.y - 0.5 : p.y - 1.0;
                boundary[node] = {std::cos(angle) * dx - std::sin(angle) * dy - dx + 0.1 * phase,
                                  std::sin(angle) * dx + std::cos(angle) * dy - dy, 0.0};
            }
            last = fromBasis.solve(boundary, k == 1 ? nullptr : &last);
            lastSolved = solving.solve(boundary, k == 1 ? nullptr : &lastSolved);
            ASSERT_TRUE(last.converged) << dimension << "D step " << k << ": " << last.reason;
            ASSERT_TRUE(lastSolved.converged) << dimension << "D step " << k << ": " << lastSolved.reason;
            EXPECT_LT(largestDifference(last.displacement, lastSolved.displacement), 1e-9) << dimension << "D step " << k;
            // The same start to rounding: the same iterations (a wrong combination would be
            // corrected by Newton, but not in the same steps).
            EXPECT_EQ(last.iterations, lastSolved.iterations) << dimension << "D step " << k;
            EXPECT_EQ(last.linearIterations, lastSolved.linearIterations) << dimension << "D step " << k;
        }
        EXPECT_LE(fromBasis.harmonicBasisSize(), 3u) << dimension << "D";
        EXPECT_GE(fromBasis.correctionsFromHarmonicBasis(), steps - 1 - 3) << dimension << "D";
        EXPECT_EQ(solving.harmonicBasisSize(), 0u) << dimension << "D";
        EXPECT_EQ(solving.correctionsFromHarmonicBasis(), 0) << dimension << "D";
        std::printf("%dD: %zu extensions kept, %d of %d warm starts took the correction from them\n", dimension,
                    fromBasis.harmonicBasisSize(), fromBasis.correctionsFromHarmonicBasis(), steps - 1);
    }
}

} // namespace
} // namespace rbm::motion
