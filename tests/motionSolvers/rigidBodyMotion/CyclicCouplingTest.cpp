// Tests of plain cyclic patches in the solver (CyclicCoupling, through rigidBodyMotionSolver and
// its rbmMoveMesh front door): a translational channel with a body moved inside, a rotational
// annulus sector whose inner arc turns (solved in 2D, and in 3D between symmetry planes, where
// the cyclic points also slide), slip walls meeting the interface, a rigid translation
// reproduced; the pair's node classes made to agree (or the mismatch named), a transform a 2D
// mesh cannot take, and the variants that refuse cyclic patches. A side's partners are found by brute force from the transform the mesh was
// built with, not by the code under test.

#include "CyclicCoupling.hpp"

#include "PetscTestEnvironment.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>

namespace rbm::motion {

namespace {

using namespace rbm::test::cyclicCases;
using rbm::test::solverCases::RigidMotion;
using rbm::test::solverCases::degrees;
using rbm::test::solverCases::patchDisplacement;

struct PairFigures {
    double mismatch = 0.0;  // max |u_B − q u_A|
    double largest = 0.0;   // max |u_A|
};

PairFigures pairFigures(const MotionSolver& solver, const std::vector<std::pair<Label, Label>>& pairs, const rbm::Matrix3& q)
{
    PairFigures figures;
    const std::vector<Vector3>& u = solver.pointDisplacement();
    for (const auto& [a, b] : pairs) {
        figures.mismatch = std::max(figures.mismatch, norm(u[b] - q * u[a]));
        figures.largest = std::max(figures.largest, norm(u[a]));
    }
    return figures;
}

const char* const channelField = R"(
    inlet  { type cyclic; }
    outlet { type cyclic; }
    walls  { type fixedValue; value uniform (0 0 0); }
    body   { type fixedValue; value uniform (0 0 0); }
    frontAndBack { type empty; })";

// The 4 × 2 channel, 16 × 8 cells, with a 1 × 0.5 body at its centre.
PolyMesh channel() { return channelWithBody(4.0, 2.0, 16, 8, 6, 10, 3, 5); }

// The channel's body turned 10° about its centre and moved 0.15 downstream, 0.1 up; solved.
MotionSolveReport moveChannelBody(MotionSolver& solver)
{
    const RigidMotion motion{{0.0, 0.0, 1.0}, degrees(10.0), {2.0, 1.0, 0.0}, {0.15, 0.1, 0.0}};
    solver.setPatchDisplacement("body", patchDisplacement(solver, "body", [&](const Vector3& x) { return motion.displacement(x); }));
    return solver.solve();
}

} // namespace

TEST(CyclicCoupling, ABodyMovedInsideATranslationalChannelKeepsInletAndOutletTogether)
{
    const PolyMesh mesh = channel();
    const io::Dictionary field = pointDisplacementField(channelField);
    auto solver = rbm::test::makeSolver(mesh, "", &field);
    const MotionSolveReport report = moveChannelBody(*solver);
    ASSERT_TRUE(report.converged) << report.reason;
    EXPECT_EQ(report.invertedCellCount, 0);
    const auto pairs = partnersByGeometry(mesh, "inlet", "outlet", [](const Vector3& x) { return x + Vector3{4.0, 0.0, 0.0}; });
    ASSERT_EQ(pairs.size(), 18u);
    const PairFigures figures = pairFigures(*solver, pairs, rbm::Matrix3::identity());
    std::printf("channel: max |u_outlet - u_inlet| %.3g, max |u_inlet| %.4g\n", figures.mismatch, figures.largest);
    EXPECT_LE(figures.mismatch, 1e-12);
    // Not trivially equal: the inlet's points move (the body's wake of displacement reaches them).
    EXPECT_GT(figures.largest, 1e-3);
}

TEST(CyclicCoupling, ARigidTranslationOfEveryPrescribedPointIsReproduced)
{
    const PolyMesh mesh = channel();
    const io::Dictionary field = pointDisplacementField(channelField);
    // To round-off: with the default displacementTolerance the solve stops within 1e-6 of an
    // edge, at the single-precision harmonic start (3e-8 here).
    auto solver = rbm::test::makeSolver(mesh, "displacementTolerance 0;", &field);
    const Vector3 shift{0.3, 0.2, 0.0};
    for (const char* patch : {"walls", "body"})
        solver->setPatchDisplacement(patch, patchDisplacement(*solver, patch, [&](const Vector3&) { return shift; }));
    const MotionSolveReport report = solver->solve();
    ASSERT_TRUE(report.converged) << report.reason;
    double largest = 0.0;
    for (const Vector3& u : solver->pointDisplacement()) largest = std::max(largest, norm(u - shift));
    std::printf("rigid translation: max |u - t| %.3g\n", largest);
    EXPECT_LE(largest, 1e-12);
}

TEST(CyclicCoupling, SlipWallsMeetTheInterfaceAndItsCornersSlideAlikeOnBothSides)
{
    // The walls slip: the interface's end points slide on the walls on both sides (the pair's
    // planes are images of each other), through the projected Laplacian's factor.
    const PolyMesh mesh = channel();
    std::string slipField = channelField;
    slipField.replace(slipField.find("walls  { type fixedValue; value uniform (0 0 0); }"),
                      std::string("walls  { type fixedValue; value uniform (0 0 0); }").size(), "walls  { type slip; }");
    const io::Dictionary field = pointDisplacementField(slipField);
    auto solver = rbm::test::makeSolver(mesh, "", &field);
    const MotionSolveReport report = moveChannelBody(*solver);
    ASSERT_TRUE(report.converged) << report.reason;
    EXPECT_EQ(report.invertedCellCount, 0);
    const auto pairs = partnersByGeometry(mesh, "inlet", "outlet", [](const Vector3& x) { return x + Vector3{4.0, 0.0, 0.0}; });
    const PairFigures figures = pairFigures(*solver, pairs, rbm::Matrix3::identity());
    // The inlet's corners: on the walls (y = 0 or 2), moved along them only.
    double cornerAlong = 0.0, cornerAcross = 0.0;
    for (const auto& [a, b] : pairs) {
        const Vector3& x = mesh.points[a];
        if (x.y != 0.0 && x.y != 2.0) continue;
        cornerAlong = std::max(cornerAlong, std::abs(solver->pointDisplacement()[a].x));
        cornerAcross = std::max(cornerAcross, std::abs(solver->pointDisplacement()[a].y));
    }
    std::printf("slip walls: max |u_outlet - u_inlet| %.3g, max |u_inlet| %.4g, corners along %.4g, across %.3g\n",
                figures.mismatch, figures.largest, cornerAlong, cornerAcross);
    EXPECT_LE(figures.mismatch, 1e-12);
    EXPECT_GT(cornerAlong, 1e-3);
    EXPECT_LE(cornerAcross, 1e-12);
}

namespace {

// The 60° sector of the annulus 1 ≤ r ≤ 2, 8 × 16 cells, its inner arc turned 15° about z.
struct SectorRun {
    MotionSolveReport report;
    PairFigures figures;
    double largestNormal = 0.0;  // 3D: max |u_z| (the symmetry planes)
    // The sector with its cyclic sides stands for the whole annulus, whose mesh is its own
    // image under turns of one cell, so every ring of points turns by one angle there. rbm's
    // energy keeps a best rotation for each side of a pair (the whole mesh has one per node), so
    // the rings' angles spread by 8e-5 rad (1e-4 in 3D; to round-off the same): 0.1 % of the
    // middle ring's 5.1°. Counting the interface's edges on both sides (no halving) spread them
    // by 5e-4, sides sliding on their planes instead of coupled by the whole turn, ~0.09.
    // The largest spread of the turn angles over a ring (radians), and the turn of the middle ring.
    double ringSpread = 0.0;
    double middleTurn = 0.0;
};

// The turn angle of every ring of points about z (points grouped by radius).
void measureRings(const MotionSolver& solver, SectorRun& run)
{
    std::map<long long, std::pair<double, double>> ranges;  // ring (radius in 1e-9) → min, max angle
    for (std::size_t p = 0; p < solver.points0().size(); ++p) {
        const Vector3 x = solver.points0()[p], moved = x + solver.pointDisplacement()[p];
        const double angle = std::atan2(x.x * moved.y - x.y * moved.x, x.x * moved.x + x.y * moved.y);
        const long long ring = std::llround(std::hypot(x.x, x.y) * 1e9);
        auto [at, inserted] = ranges.try_emplace(ring, angle, angle);
        at->second = {std::min(at->second.first, angle), std::max(at->second.second, angle)};
    }
    for (const auto& [ring, range] : ranges) run.ringSpread = std::max(run.ringSpread, range.second - range.first);
    run.middleTurn = ranges.at(1500000000).first;
}

SectorRun turnSector(bool threeD, const std::string& coefficients = "")
{
    const PolyMesh mesh = annulusSector(1.0, 2.0, 60.0, 8, 16, threeD ? "symmetryPlane" : "empty", threeD);
    const std::string planes = threeD ? "front { type symmetryPlane; }\n back { type symmetryPlane; }"
                                      : "frontAndBack { type empty; }";
    const io::Dictionary field = pointDisplacementField(R"(
        sideA { type cyclic; }
        sideB { type cyclic; }
        inner { type fixedValue; value uniform (0 0 0); }
        outer { type fixedValue; value uniform (0 0 0); }
        )" + planes);
    auto solver = rbm::test::makeSolver(mesh, coefficients, &field);
    EXPECT_EQ(solver->twoDMesh() != nullptr, !threeD);
    const RigidMotion turn{{0.0, 0.0, 1.0}, degrees(15.0), {}, {}};
    solver->setPatchDisplacement("inner", patchDisplacement(*solver, "inner", [&](const Vector3& x) { return turn.displacement(x); }));
    SectorRun run;
    run.report = solver->solve();
    const rbm::Matrix3 sixty = rbm::rotationMatrix({0.0, 0.0, 1.0}, degrees(60.0));
    const auto pairs = partnersByGeometry(mesh, "sideA", "sideB", [&](const Vector3& x) { return sixty * x; });
    EXPECT_EQ(pairs.size(), 18u);
    run.figures = pairFigures(*solver, pairs, sixty);
    for (const Vector3& u : solver->pointDisplacement()) run.largestNormal = std::max(run.largestNormal, std::abs(u.z));
    measureRings(*solver, run);
    return run;
}

} // namespace

TEST(CyclicCoupling, AnAnnulusSectorTurnedInsideARotationalCyclicKeepsItsSidesTogether)
{
    // Rigid neighbourhoods (the thesis' energy) and the 2D default's scaling (scaling auto):
    // each side of a pair keeps its own fit, so the rings of the whole annulus, which would
    // each turn by one angle, spread a little; more where the two sides' scales differ too.
    for (const auto& [coefficients, spreadBound] : {std::pair{"scaling rigid;", 2e-4}, {"", 2e-3}}) {
        const SectorRun run = turnSector(false, coefficients);
        ASSERT_TRUE(run.report.converged) << run.report.reason;
        EXPECT_EQ(run.report.invertedCellCount, 0);
        std::printf("sector 2D [%s]: max |u_B - R u_A| %.3g, max |u_A| %.4g, ring spread %.3g rad, middle ring %.4f "
                    "deg, iterations %d\n",
                    coefficients, run.figures.mismatch, run.figures.largest, run.ringSpread,
                    run.middleTurn * 180.0 / std::numbers::pi, run.report.iterations);
        EXPECT_LE(run.figures.mismatch, 1e-12);
        EXPECT_GT(run.figures.largest, 0.01);     // the sides turn with the inner arc
        EXPECT_LE(run.ringSpread, spreadBound);  // nearly as the whole annulus would
        EXPECT_GT(run.middleTurn, degrees(1.0));
        EXPECT_LT(run.middleTurn, degrees(14.0));
    }
}

TEST(CyclicCoupling, InThreeDTheCyclicPointsOnSymmetryPlanesSlideAndStayPaired)
{
    const SectorRun run = turnSector(true);
    ASSERT_TRUE(run.report.converged) << run.report.reason;
    EXPECT_EQ(run.report.invertedCellCount, 0);
    std::printf("sector 3D: max |u_B - R u_A| %.3g, max |u_A| %.4g, max |u_z| %.3g, ring spread %.3g rad, "
                "iterations %d\n",
                run.figures.mismatch, run.figures.largest, run.largestNormal, run.ringSpread, run.report.iterations);
    EXPECT_LE(run.figures.mismatch, 1e-12);
    EXPECT_LE(run.ringSpread, 2e-4);
    EXPECT_GT(run.figures.largest, 0.01);
    EXPECT_LE(run.largestNormal, 1e-12);  // every point on its symmetry plane
}

TEST(CyclicCoupling, PairClassesAgreeOrTheMismatchIsNamed)
{
    // Classes set by hand on the channel's mesh (its patch names serve the messages); nodes
    // 10 and 20 stand for a pair through inlet and outlet, q a quarter turn about z.
    const PolyMesh mesh = channel();
    CyclicCoupling coupling;
    coupling.pairs.push_back({10, 20, rbm::rotationMatrix({0.0, 0.0, 1.0}, std::numbers::pi / 2.0), 0, 1});
    const int n = static_cast<int>(mesh.points.size());
    auto classes = [&](NodeConstraint a, int prescriberA, NodeConstraint b, int prescriberB) {
        NodeClasses result{std::vector<NodeConstraint>(n), std::vector<int>(n, -1)};
        result.constraints[10] = a;
        result.prescribingPatch[10] = prescriberA;
        result.constraints[20] = b;
        result.prescribingPatch[20] = prescriberB;
        return result;
    };
    const NodeConstraint prescribed{NodeKind::prescribed, {}};
    // A slip plane on b's side acts on a through its image, and b keeps the image of a's.
    NodeClasses sliding = classes({}, -1, {NodeKind::sliding, {1.0, 0.0, 0.0}}, -1);
    const std::vector<CoupledPair> pairs = unifyCoupledClasses(coupling, sliding, false, mesh, "boundary");
    ASSERT_EQ(pairs.size(), 1u);
    EXPECT_EQ(sliding.constraints[10].kind, NodeKind::sliding);
    EXPECT_LT(norm(sliding.constraints[10].normal - Vector3{0.0, -1.0, 0.0}), 1e-15);  // qᵀ x = −y
    EXPECT_LT(norm(sliding.constraints[20].normal - Vector3{1.0, 0.0, 0.0}), 1e-15);
    // Held on one side: held on both, no pair left.
    NodeClasses held = classes(prescribed, heldNode, {}, -1);
    EXPECT_TRUE(unifyCoupledClasses(coupling, held, false, mesh, "boundary").empty());
    EXPECT_EQ(held.constraints[20].kind, NodeKind::prescribed);
    EXPECT_EQ(held.prescribingPatch[20], heldNode);
    // Prescribed by a patch on one side only: the interface would open.
    NodeClasses open = classes({}, -1, prescribed, 2);
    const std::string error = rbm::test::solverCases::errorOf([&] { unifyCoupledClasses(coupling, open, false, mesh, "boundary"); });
    EXPECT_NE(error.find("cyclic patches 'inlet' and 'outlet'"), std::string::npos) << error;
    EXPECT_NE(error.find("prescribed by patch 'walls'"), std::string::npos) << error;
}

TEST(CyclicCoupling, ATransformThatTurnsThePlaneOfATwoDMeshIsRefused)
{
    const PolyMesh mesh = channel();
    const auto twoD = std::make_unique<PseudoTwoDMesh>(extractPseudoTwoD(mesh));
    CyclicPatchPairing pairing;
    pairing.patchA = 0;
    pairing.patchB = 1;
    pairing.rotation = rbm::rotationMatrix({1.0, 0.0, 0.0}, 0.3);
    pairing.points = partnersByGeometry(mesh, "inlet", "outlet", [](const Vector3& x) { return x + Vector3{4.0, 0.0, 0.0}; });
    const std::string error = rbm::test::solverCases::errorOf([&] { coupleCyclicNodes(mesh, std::vector{pairing}, twoD.get(), "boundary"); });
    EXPECT_NE(error.find("cyclic patches 'inlet' and 'outlet': their rotation axis is not normal to the plane"),
              std::string::npos)
        << error;
    pairing.rotation = rbm::Matrix3::identity();
    const CyclicCoupling coupling = coupleCyclicNodes(mesh, std::vector{pairing}, twoD.get(), "boundary");
    EXPECT_EQ(coupling.pairs.size(), 9u);  // the front plane's nodes: both planes' points give the same pairs
}

TEST(CyclicCoupling, TheThesisVariantsRefuseCyclicPatchesNamingThePatchAndTheVariant)
{
    const PolyMesh mesh = channel();
    const io::Dictionary field = pointDisplacementField(channelField);
    for (const char* coefficients : {"formulation linearized;", "algorithm newton;", "coupling decoupled;"}) {
        const std::string error =
            rbm::test::solverCases::errorOf([&] { rbm::test::makeSolver(mesh, coefficients, &field); });
        EXPECT_NE(error.find("cyclic patch 'inlet'"), std::string::npos) << error;
        EXPECT_NE(error.find("does not support cyclic patches"), std::string::npos) << error;
    }
    const std::string error =
        rbm::test::solverCases::errorOf([&] { rbm::test::makeSolver(mesh, "formulation linearized;", &field); });
    EXPECT_NE(error.find("formulation linearized"), std::string::npos) << error;
}

} // namespace rbm::motion
