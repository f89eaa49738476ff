// Tests of EdgeStiffening: the edge factors (h_min / d)^k towards the listed patches, and
// `stiffening auto`'s rule (applied while every prescribed patch moves rigidly).
#include "EdgeStiffening.hpp"

#include "InputError.hpp"
#include "MeshGenerators.hpp"

#include <gtest/gtest.h>

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
    EdgeStiffening automatic(RigidBodyMotionOptions{}, mesh, mesh.points, nullptr, graph, mesh.points, 3);
    ASSERT_TRUE(automatic.automatic());
    const auto factors = automatic.factors();
    ASSERT_TRUE(factors);
    EXPECT_FALSE(automatic.followMotion(true));   // already applied
    EXPECT_TRUE(automatic.followMotion(false));   // a deforming patch: off
    EXPECT_FALSE(automatic.factors());
    EXPECT_FALSE(automatic.followMotion(false));
    EXPECT_TRUE(automatic.followMotion(true));    // rigid again: the same factors, not recomputed
    EXPECT_EQ(automatic.factors(), factors);
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
