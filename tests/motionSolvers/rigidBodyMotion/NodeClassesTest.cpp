// Tests of classifyNodes: the node classes of the RBM problem from a boundary description.
#include "NodeClasses.hpp"

#include "CellNeighbourGraph.hpp"
#include "MeshGenerators.hpp"
#include "RigidBodyMotionOptions.hpp"

#include <gtest/gtest.h>

namespace rbm::motion {
namespace {

TEST(NodeClasses, PrescribedBeatsSlidingBeatsFreeAndPlanesMeetInLinesAndCorners)
{
    // A 3 × 3 × 3 box: xMin prescribed, yMin and zMin slip walls, the other sides
    // unconstrained (zeroGradient: they slide on their own planes), yMax listed as floating.
    const PolyMesh mesh = makeHexBox(3, 3, 3, {0, 0, 0}, {3, 3, 3});
    const CellNeighbourGraph graph = buildCellNeighbourGraph(mesh);
    RigidBodyMotionOptions options;
    options.floatingPatches = {"yMax"};
    UnconstrainedPatches unconstrained(mesh, mesh.points, options);
    BoundaryDescription boundary(mesh.patches.size());
    for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
        BoundaryPatchDescription& patch = boundary[p];
        patch.meshPoints = patchMeshPoints(mesh, static_cast<Label>(p));
        const std::string& name = mesh.patches[p].name;
        if (name == "xMin") {
            patch.nodeClass = BoundaryNodeClass::prescribed;
        } else if (name == "yMin" || name == "zMin") {
            patch.nodeClass = BoundaryNodeClass::sliding;
            patch.slidingNormals.assign(patch.meshPoints.size(), name == "yMin" ? Vector3{0, 1, 0} : Vector3{0, 0, 1});
        } else {
            patch.nodeClass = BoundaryNodeClass::free;
        }
    }
    const NodeClasses classes = classifyNodes(boundary, nullptr, graph, unconstrained);
    auto point = [](int i, int j, int k) { return i + 4 * (j + 4 * k); };
    auto kind = [&](int i, int j, int k) { return classes.constraints[point(i, j, k)].kind; };
    const Label xMin = mesh.findPatch("xMin");

    EXPECT_EQ(kind(0, 0, 0), NodeKind::prescribed);                  // xMin beats both slip walls
    EXPECT_EQ(classes.prescribingPatch[point(0, 1, 1)], xMin);
    EXPECT_EQ(kind(1, 0, 1), NodeKind::sliding);                     // yMin
    EXPECT_EQ(classes.constraints[point(1, 0, 1)].normal, (Vector3{0, 1, 0}));
    EXPECT_EQ(kind(1, 0, 0), NodeKind::sliding);                     // yMin ∩ zMin: the line along x
    EXPECT_EQ(classes.constraints[point(1, 0, 0)].secondNormal, (Vector3{0, 0, 1}));
    EXPECT_EQ(kind(3, 0, 0), NodeKind::prescribed);                  // three planes: held
    EXPECT_EQ(classes.prescribingPatch[point(3, 0, 0)], heldNode);
    EXPECT_EQ(kind(3, 1, 1), NodeKind::sliding);                     // xMax, unconstrained: its plane
    EXPECT_NEAR(classes.constraints[point(3, 1, 1)].normal.x, 1.0, 1e-15);
    EXPECT_EQ(kind(1, 3, 1), NodeKind::free);                        // yMax floats
    EXPECT_EQ(kind(1, 1, 1), NodeKind::free);                        // interior
    EXPECT_EQ(classes.prescribingPatch[point(1, 1, 1)], -1);
}

} // namespace
} // namespace rbm::motion
