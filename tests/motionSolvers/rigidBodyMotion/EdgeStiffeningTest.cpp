// Tests of EdgeStiffening: the edge factors (h_min / d)^k towards the listed patches,
// `stiffening auto`'s rule (applied while every prescribed patch moves rigidly) and its split
// into the moving and the fixed patches (movingAndFixed).
#include "EdgeStiffening.hpp"

#include "InputError.hpp"
#include "MeshGenerators.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbm::motion {
namespace {

RigidBodyMotionOptions optionsOf(const std::string& text)
{
    return RigidBodyMotionOptions::read(io::Dictionary::parseText(text, "dynamicMeshDict"));
}

double factorOf(const CellNeighbourGraph& graph, const std::vector<double>& factors, int from, int to)
{
    for (int e = graph.offsets[from]; e < graph.offsets[from + 1]; ++e)
        if (graph.neighbours[e] == to) return factors[e];
    ADD_FAILURE() << "no edge " << from << "-" << to;
    return 0.0;
}

TEST(EdgeStiffening, FactorsAreTheShortestEdgeOverTheDistanceToThePatches)
{
    // Four unit cubes along x; stiffening towards xMax (x = 4); h_min = 1.
    const PolyMesh mesh = makeHexBox(4, 1, 1, {0, 0, 0}, {4, 1, 1});
    const CellNeighbourGraph graph = buildCellNeighbourGraph(mesh);
    const EdgeStiffening linear(optionsOf("stiffening inverseDistance (xMax);"), mesh, mesh.points, nullptr, graph,
                                mesh.points, 3);
    ASSERT_TRUE(linear.factors());
    EXPECT_FALSE(linear.automatic());
    EXPECT_EQ(linear.patches(), std::vector<Label>{mesh.findPatch("xMax")});
    // Point (i, 0, 0) has label i. Edge 0-1: midpoint x = 0.5, 3.5 from the patch.
    EXPECT_NEAR(factorOf(graph, *linear.factors(), 0, 1), 1.0 / 3.5, 1e-12);
    EXPECT_NEAR(factorOf(graph, *linear.factors(), 2, 3), 1.0 / 1.5, 1e-12);
    // Edge 3-4 touches the patch: the distance is clipped at h_min, the factor is 1.
    EXPECT_NEAR(factorOf(graph, *linear.factors(), 3, 4), 1.0, 1e-12);

    const EdgeStiffening quadratic(optionsOf("stiffening quadratic inverseDistance (xMax);"), mesh, mesh.points,
                                   nullptr, graph, mesh.points, 3);
    EXPECT_NEAR(factorOf(graph, *quadratic.factors(), 0, 1), 1.0 / (3.5 * 3.5), 1e-12);

    const EdgeStiffening none(optionsOf("stiffening none;"), mesh, mesh.points, nullptr, graph, mesh.points, 3);
    EXPECT_FALSE(none.factors());
}

TEST(EdgeStiffening, AutomaticFollowsWhetherThePrescribedPatchesMoveRigidly)
{
    const PolyMesh mesh = makeHexBox(4, 1, 1, {0, 0, 0}, {4, 1, 1});
    const CellNeighbourGraph graph = buildCellNeighbourGraph(mesh);
    // The split (auto's in 2D) computes its factors when first applied.
    EdgeStiffening automatic(optionsOf("stiffening movingAndFixed 0.75 0.2;"), mesh, mesh.points, nullptr, graph,
                             mesh.points, 3);
    ASSERT_TRUE(automatic.automatic());
    EXPECT_FALSE(automatic.factors());   // computed when first applied
    std::vector<bool> moved(mesh.patches.size(), false);
    moved[mesh.findPatch("xMax")] = true;
    EXPECT_FALSE(automatic.followMotion(false, moved));   // a deforming patch: not computed, off
    EXPECT_FALSE(automatic.factors());
    EXPECT_TRUE(automatic.followMotion(true, moved));
    const auto factors = automatic.factors();
    ASSERT_TRUE(factors);
    EXPECT_FALSE(automatic.followMotion(true, moved));   // already applied
    EXPECT_TRUE(automatic.followMotion(false, moved));   // a deforming patch: off
    EXPECT_FALSE(automatic.factors());
    EXPECT_FALSE(automatic.followMotion(false, moved));
    EXPECT_TRUE(automatic.followMotion(true, moved));    // rigid again: the same factors, not recomputed
    EXPECT_EQ(automatic.factors(), factors);
}

TEST(EdgeStiffening, ReleasedFactorsComeBackTheSameWhenAppliedAgain)
{
    // auto in 3D (no split): the factors are computed at construction and in effect.
    const PolyMesh mesh = makeHexBox(4, 1, 1, {0, 0, 0}, {4, 1, 1});
    const CellNeighbourGraph graph = buildCellNeighbourGraph(mesh);
    EdgeStiffening automatic(optionsOf("stiffening auto;"), mesh, mesh.points, nullptr, graph, mesh.points, 3);
    ASSERT_TRUE(automatic.automatic());
    ASSERT_TRUE(automatic.factors());
    const std::vector<double> original = *automatic.factors();
    const std::vector<bool> moved(mesh.patches.size(), true);
    automatic.releaseFactors();
    EXPECT_FALSE(automatic.factors());
    EXPECT_FALSE(automatic.followMotion(true, moved));   // still applied: nothing to rebuild
    EXPECT_FALSE(automatic.factors());
    EXPECT_TRUE(automatic.followMotion(false, moved));   // a deforming patch: off
    EXPECT_FALSE(automatic.factors());
    EXPECT_TRUE(automatic.followMotion(true, moved));    // rigid again: computed again, bit for bit
    ASSERT_TRUE(automatic.factors());
    EXPECT_EQ(*automatic.factors(), original);
    // Released while off, then applied.
    EXPECT_TRUE(automatic.followMotion(false, moved));
    automatic.releaseFactors();
    EXPECT_FALSE(automatic.followMotion(false, moved));
    EXPECT_TRUE(automatic.followMotion(true, moved));
    ASSERT_TRUE(automatic.factors());
    EXPECT_EQ(*automatic.factors(), original);
}

TEST(EdgeStiffening, MovingAndFixedIsTheProductOfTheFactorsTowardsTheMovingAndTheOtherPatches)
{
    // A 6³ box of unit cubes (h_min = 1); xMin moves, every other side is fixed.
    const PolyMesh mesh = makeHexBox(6, 6, 6, {0, 0, 0}, {6, 6, 6});
    const CellNeighbourGraph graph = buildCellNeighbourGraph(mesh);
    EdgeStiffening split(optionsOf("stiffening movingAndFixed 0.75 0.2;"), mesh, mesh.points, nullptr, graph,
                         mesh.points, 3);
    ASSERT_TRUE(split.automatic());
    EXPECT_FALSE(split.factors());   // which patches move is known at the first solve
    std::vector<bool> moved(mesh.patches.size(), false);
    moved[mesh.findPatch("xMin")] = true;
    EXPECT_TRUE(split.followMotion(true, moved));
    ASSERT_TRUE(split.factors());
    EXPECT_EQ(split.movingPatches(), std::vector<Label>{mesh.findPatch("xMin")});
    auto point = [](int i, int j, int k) { return i + 7 * (j + 7 * k); };
    // Midpoint (1.5, 3, 3): 1.5 from xMin, 3 from the nearest other side (y, z).
    EXPECT_NEAR(factorOf(graph, *split.factors(), point(1, 3, 3), point(2, 3, 3)),
                std::pow(1.0 / 1.5, 0.75) * std::pow(1.0 / 3.0, 0.2), 1e-14);
    // Midpoint (4.5, 3, 3): 4.5 from xMin, 1.5 from xMax.
    EXPECT_NEAR(factorOf(graph, *split.factors(), point(4, 3, 3), point(5, 3, 3)),
                std::pow(1.0 / 4.5, 0.75) * std::pow(1.0 / 1.5, 0.2), 1e-14);
    const auto factors = split.factors();
    EXPECT_FALSE(split.followMotion(true, moved));   // the same patches move: not recomputed
    EXPECT_EQ(split.factors(), factors);
    EXPECT_TRUE(split.followMotion(false, moved));   // a deforming patch: off, as auto
    EXPECT_FALSE(split.factors());

    // Nothing to tell apart (every automatic patch moves): the single factor towards all of
    // them, bit for bit.
    const EdgeStiffening single(optionsOf("stiffening power 0.8 inverseDistance (xMin xMax yMin yMax zMin zMax);"),
                                mesh, mesh.points, nullptr, graph, mesh.points, 3);
    EdgeStiffening allMoving(optionsOf("stiffening movingAndFixed 0.75 0.2;"), mesh, mesh.points, nullptr, graph,
                             mesh.points, 3);
    EXPECT_TRUE(allMoving.followMotion(true, std::vector<bool>(mesh.patches.size(), true)));
    EXPECT_TRUE(allMoving.movingPatches().empty());
    EXPECT_EQ(*allMoving.factors(), *single.factors());
    // A second patch starts moving: the factors follow the larger moving set.
    moved[mesh.findPatch("xMax")] = true;
    EXPECT_TRUE(split.followMotion(true, moved));
    EXPECT_EQ(split.movingPatches(), (std::vector<Label>{mesh.findPatch("xMin"), mesh.findPatch("xMax")}));
    EXPECT_NEAR(factorOf(graph, *split.factors(), point(4, 3, 3), point(5, 3, 3)),
                std::pow(1.0 / 1.5, 0.75) * std::pow(1.0 / 3.0, 0.2), 1e-14);
}

// auto's split is for planar problems: in 3D auto is the single exponent towards all its
// patches, bit for bit, while movingAndFixed written out splits in 3D too.
TEST(EdgeStiffening, AutoSplitsInTwoDimensionsOnlyAndAWrittenSplitEverywhere)
{
    const PolyMesh mesh = makeHexBox(6, 6, 6, {0, 0, 0}, {6, 6, 6});
    const CellNeighbourGraph graph = buildCellNeighbourGraph(mesh);
    std::vector<bool> moved(mesh.patches.size(), false);
    moved[mesh.findPatch("xMin")] = true;
    EdgeStiffening automatic(optionsOf("stiffening auto;"), mesh, mesh.points, nullptr, graph, mesh.points, 3);
    const EdgeStiffening single(optionsOf("stiffening power 0.8 inverseDistance (xMin xMax yMin yMax zMin zMax);"),
                                mesh, mesh.points, nullptr, graph, mesh.points, 3);
    ASSERT_TRUE(automatic.factors()) << "the single exponent's factors are known at once";
    automatic.followMotion(true, moved);
    EXPECT_TRUE(automatic.movingPatches().empty());
    EXPECT_EQ(*automatic.factors(), *single.factors());
    EdgeStiffening written(optionsOf("stiffening movingAndFixed 0.75 0.2;"), mesh, mesh.points, nullptr, graph,
                           mesh.points, 3);
    EXPECT_TRUE(written.followMotion(true, moved));
    EXPECT_EQ(written.movingPatches(), std::vector<Label>{mesh.findPatch("xMin")});
    EXPECT_NE(*written.factors(), *single.factors());
}

TEST(EdgeStiffening, AutoIsMovingAndFixedWhichNeedsTwoExponentsInRange)
{
    const auto errorOf = [](const std::string& text) {
        try {
            optionsOf(text);
        } catch (const InputError& error) {
            return std::string(error.what());
        }
        return std::string("no error");
    };
    // The default is movingAndFixed 0.75 0.2; the explicit forms have no split.
    EXPECT_EQ(RigidBodyMotionOptions{}.stiffening.split, defaultSplitStiffening);
    EXPECT_EQ(optionsOf("stiffening auto;").stiffening.split, (SplitStiffeningExponents{0.75, 0.2}));
    EXPECT_FALSE(optionsOf("stiffening none;").stiffening.split);
    EXPECT_FALSE(optionsOf("stiffening power 0.8 inverseDistance (a);").stiffening.split);
    EXPECT_EQ(optionsOf("stiffening movingAndFixed 1 0.4;").stiffening.split, (SplitStiffeningExponents{1.0, 0.4}));
    EXPECT_EQ(optionsOf("stiffening movingAndFixed 0.75 0.2;").stiffening.split->moving, 0.75);
    EXPECT_EQ(optionsOf("stiffening movingAndFixed 0.75 0.2;").stiffening.split->fixed, 0.2);
    EXPECT_TRUE(optionsOf("stiffening movingAndFixed 0.75 0.2;").stiffening.automaticPatches);
    EXPECT_NE(errorOf("stiffening movingAndFixed 0.75;").find("needs two exponents"), std::string::npos);
    EXPECT_NE(errorOf("stiffening movingAndFixed 5 0.2;").find("must be in [0, 4], got 5"), std::string::npos);
    EXPECT_NE(errorOf("stiffening movingAndFixed 0 0;").find("stiffens nothing"), std::string::npos);
    EXPECT_NE(errorOf("stiffening movingAndFixed 1 1 (a);").find("unexpected '('"), std::string::npos);
}

TEST(EdgeStiffening, AnUnknownPatchIsAnErrorAtItsLineListingThePatches)
{
    const PolyMesh mesh = makeHexBox(1, 1, 1, {0, 0, 0}, {1, 1, 1});
    const CellNeighbourGraph graph = buildCellNeighbourGraph(mesh);
    try {
        EdgeStiffening(optionsOf("\n\nstiffening inverseDistance (wing);"), mesh, mesh.points, nullptr, graph,
                       mesh.points, 3);
        FAIL() << "expected an InputError";
    } catch (const InputError& error) {
        EXPECT_EQ(error.line(), 3);
        EXPECT_NE(std::string(error.what()).find("unknown patch wing. Valid patches are: xMin"), std::string::npos)
            << error.what();
    }
}

} // namespace
} // namespace rbm::motion
