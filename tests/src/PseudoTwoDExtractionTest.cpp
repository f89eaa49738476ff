// Detection and extraction of OpenFOAM pseudo-3D (empty / wedge) meshes, and mapping 2D
// positions back to both planes (docs/method.md §6).

#include "CellShape.hpp"
#include "InputError.hpp"
#include "MeshGenerators.hpp"
#include "MeshTopology.hpp"
#include "PseudoTwoDExtraction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

using namespace rbm;

namespace {

// The message of the InputError that extraction throws, or "" when it does not throw.
std::string extractionError(const PolyMesh& mesh)
{
    try {
        extractPseudoTwoD(mesh);
    } catch (const InputError& error) {
        EXPECT_EQ(error.file(), "");
        return error.message();
    }
    return {};
}

// Invariants of any extraction: cells counter-clockwise with positive area, twins paired
// both ways, edges with their owner on the left and internal edges upper-triangular.
void expectConsistent(const PolyMesh& mesh, const PseudoTwoDMesh& flat)
{
    const PlanarMesh& planar = flat.planar;
    ASSERT_EQ(planar.cellCount(), mesh.cellCount());
    for (Label c = 0; c < planar.cellCount(); ++c) EXPECT_GT(planar.signedArea(c), 0.0) << "cell " << c;
    for (Label n = 0; n < flat.nodeCount(); ++n) {
        const Label front = flat.frontPointOfNode[n], back = flat.backPointOfNode[n];
        EXPECT_EQ(flat.twinOfPoint[front], back);
        EXPECT_EQ(flat.twinOfPoint[back], front);
        EXPECT_EQ(flat.nodeOfPoint[front], n);
        EXPECT_EQ(flat.nodeOfPoint[back], n);
    }
    for (Label e = 0; e < planar.edgeCount(); ++e) {
        const auto [a, b] = planar.edge(e);
        // The owner's centroid lies left of a → b.
        Vector3 centroid;
        for (Label p : planar.cell(planar.edgeOwner[e])) centroid += planar.points[p];
        centroid /= static_cast<double>(planar.cell(planar.edgeOwner[e]).size());
        const Vector3 along = planar.points[b] - planar.points[a], toCentre = centroid - planar.points[a];
        EXPECT_GT(along.x * toCentre.y - along.y * toCentre.x, 0.0) << "edge " << e;
        if (e < planar.internalEdgeCount()) {
            EXPECT_LT(planar.edgeOwner[e], planar.edgeNeighbour[e]);
            if (e > 0) {
                EXPECT_LE(std::pair(planar.edgeOwner[e - 1], planar.edgeNeighbour[e - 1]),
                          std::pair(planar.edgeOwner[e], planar.edgeNeighbour[e]));
            }
        }
    }
    Label patchEdges = 0;
    for (const PlanarPatch& patch : planar.patches) {
        EXPECT_EQ(patch.startEdge, planar.internalEdgeCount() + patchEdges) << patch.name;
        patchEdges += patch.edgeCount;
    }
    EXPECT_EQ(planar.internalEdgeCount() + patchEdges, planar.edgeCount());
}

std::vector<Vector3> liftIdentity(const PolyMesh& mesh, const PseudoTwoDMesh& flat)
{
    return flat.liftPositions(mesh.points, flat.planar.points);
}

// A smooth in-plane motion of the 2D nodes.
std::vector<Vector3> movedNodes(const PlanarMesh& planar)
{
    std::vector<Vector3> moved = planar.points;
    for (Vector3& p : moved) {
        const double x = p.x, y = p.y;
        p.x = x + 0.03 * std::sin(3.0 * y) + 0.01;
        p.y = y + 0.02 * std::cos(2.0 * x);
        p.z = 123.0;   // ignored by the lift
    }
    return moved;
}

} // namespace

TEST(PseudoTwoDDetection, RecognisesEmptyWedgeAndPlain3D)
{
    EXPECT_EQ(detectPseudoTwoD(makeExtruded2D(2, 2, {0, 0, 0}, {1, 1, 1})), PseudoTwoDKind::Empty);
    EXPECT_EQ(detectPseudoTwoD(makeWedge2D(2, 2, {0, 0, 0}, {1, 1, 0}, 5.0)), PseudoTwoDKind::Wedge);
    const PolyMesh box = makeHexBox(2, 2, 2, {0, 0, 0}, {1, 1, 1});
    EXPECT_EQ(detectPseudoTwoD(box), PseudoTwoDKind::None);
    EXPECT_NE(extractionError(box).find("no patch of type empty or wedge"), std::string::npos);
}

TEST(PseudoTwoDExtraction, HexahedraGiveQuadrilateralsWithTheGridsAreaAndPatches)
{
    const PolyMesh mesh = makeExtruded2D(4, 3, {0, 0, -0.05}, {2, 1.5, 0.05});
    const PseudoTwoDMesh flat = extractPseudoTwoD(mesh);
    EXPECT_EQ(flat.kind, PseudoTwoDKind::Empty);
    expectConsistent(mesh, flat);
    EXPECT_EQ(flat.frame.axis, 2);
    EXPECT_EQ(flat.frame.normal, (Vector3{0, 0, 1}));
    ASSERT_EQ(flat.nodeCount(), 20);
    ASSERT_EQ(flat.planar.cellCount(), 12);
    for (Label c = 0; c < 12; ++c) {
        EXPECT_EQ(flat.planar.cell(c).size(), 4u);
        EXPECT_DOUBLE_EQ(flat.planar.signedArea(c), 0.25);   // 0.5 × 0.5
    }
    // The front plane (z = -0.05) comes first in the generator: node n is point n, twin n + 20.
    for (Label n = 0; n < 20; ++n) {
        EXPECT_EQ(flat.frontPointOfNode[n], n);
        EXPECT_EQ(flat.backPointOfNode[n], n + 20);
        EXPECT_EQ(flat.planar.points[n], mesh.points[n]);   // plane coordinate kept as z
    }
    // Internal edges (nx-1) ny + nx (ny-1); boundary: left/right 3 each, bottom/top 4 each.
    EXPECT_EQ(flat.planar.internalEdgeCount(), 3 * 3 + 4 * 2);
    ASSERT_EQ(flat.planar.patches.size(), 4u);
    const std::vector<std::string> names{"left", "right", "bottom", "top"};
    const std::vector<Label> counts{3, 3, 4, 4};
    for (std::size_t p = 0; p < 4; ++p) {
        EXPECT_EQ(flat.planar.patches[p].name, names[p]);
        EXPECT_EQ(flat.planar.patches[p].edgeCount, counts[p]);
        EXPECT_EQ(flat.planar.patches[p].polyMeshPatch, static_cast<Label>(p));
    }
    // Every 2D edge comes from the 3D side face with the same owner.
    for (Label e = 0; e < flat.planar.edgeCount(); ++e) EXPECT_EQ(mesh.owner[flat.faceOfEdge[e]], flat.planar.edgeOwner[e]);
}

TEST(PseudoTwoDExtraction, PrismsGiveTriangles)
{
    const PolyMesh mesh = makeExtruded2D(3, 2, {0, 0, 0}, {3, 2, 1}, PlanarCellKind::Triangles);
    const PseudoTwoDMesh flat = extractPseudoTwoD(mesh);
    expectConsistent(mesh, flat);
    ASSERT_EQ(flat.planar.cellCount(), 12);
    for (Label c = 0; c < 12; ++c) {
        EXPECT_EQ(polygonShape(flat.planar.cell(c).size()), PolygonShape::Triangle);
        EXPECT_DOUBLE_EQ(flat.planar.signedArea(c), 0.5);
    }
    // Edges: 2D Euler count, nodes − edges + cells = 1 for a disc.
    EXPECT_EQ(flat.nodeCount() - flat.planar.edgeCount() + flat.planar.cellCount(), 1);
}

TEST(PseudoTwoDExtraction, MixedAndPolygonalMeshesKeepTheirCellSizes)
{
    const PolyMesh mixed = makeExtruded2D(4, 2, {0, 0, 0}, {4, 2, 1}, PlanarCellKind::Mixed, {2, true});
    const PseudoTwoDMesh flatMixed = extractPseudoTwoD(mixed);
    expectConsistent(mixed, flatMixed);
    Label triangles = 0, quads = 0;
    for (Label c = 0; c < flatMixed.planar.cellCount(); ++c) {
        (flatMixed.planar.cell(c).size() == 3 ? triangles : quads) += 1;
    }
    EXPECT_EQ(triangles, 8);
    EXPECT_EQ(quads, 4);

    const PolyMesh polygons = makeExtruded2D(4, 2, {0, 0, 0}, {4, 2, 1}, PlanarCellKind::Polygons);
    const PseudoTwoDMesh flatPolygons = extractPseudoTwoD(polygons);
    expectConsistent(polygons, flatPolygons);
    ASSERT_EQ(flatPolygons.planar.cellCount(), 4);
    for (Label c = 0; c < 4; ++c) {
        EXPECT_EQ(flatPolygons.planar.cell(c).size(), 6u);
        EXPECT_DOUBLE_EQ(flatPolygons.planar.signedArea(c), 2.0);
    }
}

TEST(PseudoTwoDExtraction, NormalAlongXOrYGivesTheSame2DMesh)
{
    const Vector3 min{0.5, -1, 2}, max{2.5, 1, 2.25};
    const PolyMesh alongZ = makeExtruded2D(4, 3, min, max, PlanarCellKind::Mixed);
    const PseudoTwoDMesh reference = extractPseudoTwoD(alongZ);
    for (int axis = 0; axis < 2; ++axis) {
        const PolyMesh mesh = makeExtruded2D(4, 3, min, max, PlanarCellKind::Mixed, {axis, false});
        const PseudoTwoDMesh flat = extractPseudoTwoD(mesh);
        expectConsistent(mesh, flat);
        EXPECT_EQ(flat.frame.axis, axis);
        Vector3 expectedNormal;
        expectedNormal[axis] = 1.0;
        EXPECT_EQ(flat.frame.normal, expectedNormal);
        // Local coordinates (u, v, w) come out exactly: same points, cells and areas as along z.
        EXPECT_EQ(flat.planar.points, reference.planar.points);
        EXPECT_EQ(flat.planar.cellPoints, reference.planar.cellPoints);
        EXPECT_EQ(flat.planar.edgePoints, reference.planar.edgePoints);
        for (Label n = 0; n < flat.nodeCount(); ++n) EXPECT_EQ(flat.planar.points[n].z, 2.0);
    }
}

TEST(PseudoTwoDExtraction, IdentityLiftRestoresEveryPointExactly)
{
    std::vector<PolyMesh> meshes{
        makeExtruded2D(5, 4, {0.1, 0.2, -0.3}, {1.7, 1.1, 0.4}, PlanarCellKind::Triangles),
        makeExtruded2D(5, 4, {0.1, 0.2, -0.3}, {1.7, 1.1, 0.4}, PlanarCellKind::Mixed, {0, false}),
        makeExtruded2D(4, 4, {0.1, 0.2, -0.3}, {1.7, 1.1, 0.4}, PlanarCellKind::Polygons, {1, true}),
        makeWedge2D(5, 4, {0, 0, 0}, {1, 0.7, 0}, 5.0, PlanarCellKind::Mixed),
        makeWedge2D(5, 4, {0, 0.3, 0}, {1, 0.7, 0}, 7.0),
    };
    for (const PolyMesh& mesh : meshes) {
        const PseudoTwoDMesh flat = extractPseudoTwoD(mesh);
        EXPECT_EQ(liftIdentity(mesh, flat), mesh.points);
        const auto zero = flat.liftDisplacements(std::vector<Vector3>(static_cast<std::size_t>(flat.nodeCount())));
        for (const Vector3& d : zero) EXPECT_EQ(d, (Vector3{}));
    }
}

TEST(PseudoTwoDExtraction, MovedNodesReachBothPlanesWithTheOutOfPlaneCoordinateUnchanged)
{
    for (int axis = 0; axis < 3; ++axis) {
        const PolyMesh mesh = makeExtruded2D(5, 4, {0, 0, -0.5}, {1, 1, 0.25}, PlanarCellKind::Mixed, {axis, false});
        const PseudoTwoDMesh flat = extractPseudoTwoD(mesh);
        const std::vector<Vector3> moved = movedNodes(flat.planar);
        const std::vector<Vector3> lifted = flat.liftPositions(mesh.points, moved);
        ASSERT_EQ(lifted.size(), mesh.points.size());
        for (Label p = 0; p < mesh.pointCount(); ++p) {
            const Label n = flat.nodeOfPoint[p];
            // Out-of-plane coordinate untouched, in-plane coordinates the 2D ones (exactly,
            // since front and back share in-plane coordinates in a clean extrusion).
            EXPECT_EQ(lifted[p][axis], mesh.points[p][axis]);
            const Vector3 local = flat.frame.toLocal(lifted[p]);
            EXPECT_EQ(local.x, moved[n].x);
            EXPECT_EQ(local.y, moved[n].y);
        }
        // The displacement form agrees.
        std::vector<Vector3> displacement(moved.size());
        for (std::size_t n = 0; n < moved.size(); ++n) displacement[n] = moved[n] - flat.planar.points[n];
        const auto lifted3D = flat.liftDisplacements(displacement);
        for (Label p = 0; p < mesh.pointCount(); ++p) {
            EXPECT_EQ(lifted3D[p][axis], 0.0);
            EXPECT_NEAR(norm(mesh.points[p] + lifted3D[p] - lifted[p]), 0.0, 1e-15);
        }
    }
}

TEST(PseudoTwoDExtraction, WedgeSharesAxisPointsAndRotatesTheBackPlane)
{
    const double angle = 5.0;
    const PolyMesh mesh = makeWedge2D(4, 3, {0, 0, 0}, {2, 1.5, 0}, angle);
    const PseudoTwoDMesh flat = extractPseudoTwoD(mesh);
    EXPECT_EQ(flat.kind, PseudoTwoDKind::Wedge);
    expectConsistent(mesh, flat);
    EXPECT_NEAR(flat.wedgeAngle, angle * std::numbers::pi / 180.0, 1e-12);
    EXPECT_NEAR(norm(flat.wedgeAxis - Vector3{1, 0, 0}), 0.0, 1e-12);
    EXPECT_NEAR(flat.wedgeAxisPoint.y, 0.0, 1e-12);
    EXPECT_NEAR(flat.wedgeAxisPoint.z, 0.0, 1e-12);
    // 5 × 4 grid nodes; the 5 on the axis are one 3D point each (twin = itself).
    ASSERT_EQ(flat.nodeCount(), 20);
    EXPECT_EQ(mesh.pointCount(), 20 + 15);
    for (Label n = 0; n < 5; ++n) EXPECT_EQ(flat.frontPointOfNode[n], flat.backPointOfNode[n]);
    // The 2D coordinates are (axial, radius) of the generator's grid.
    for (Label n = 0; n < flat.nodeCount(); ++n) {
        EXPECT_NEAR(flat.planar.points[n].x, 0.5 * (n % 5), 1e-12);
        EXPECT_NEAR(flat.planar.points[n].y, 0.5 * (n / 5), 1e-12);
    }
    // The collapsed axis faces become boundary edges of the empty "axis" patch.
    ASSERT_EQ(flat.planar.patches.size(), 4u);
    EXPECT_EQ(flat.planar.patches[2].name, "top");
    EXPECT_EQ(flat.planar.patches[3].name, "axis");
    EXPECT_EQ(flat.planar.patches[3].edgeCount, 4);
    EXPECT_EQ(flat.planar.patches[3].polyMeshPatch, mesh.findPatch("axis"));
    for (Label e = flat.planar.patches[3].startEdge; e < flat.planar.edgeCount(); ++e) EXPECT_EQ(flat.faceOfEdge[e], -1);

    // Move the nodes (axis nodes only along the axis): both planes stay at ∓angle/2.
    std::vector<Vector3> moved = flat.planar.points;
    for (Vector3& p : moved) {
        p.x += 0.05 * p.y + 0.01;
        p.y *= 1.0 + 0.1 * p.x;
    }
    const auto lifted = flat.liftPositions(mesh.points, moved);
    const double half = 0.5 * angle * std::numbers::pi / 180.0;
    for (Label p = 0; p < mesh.pointCount(); ++p) {
        const Label n = flat.nodeOfPoint[p];
        const double radius = std::hypot(lifted[p].y, lifted[p].z);
        EXPECT_NEAR(lifted[p].x, moved[n].x, 1e-12);
        EXPECT_NEAR(radius, moved[n].y, 1e-12);
        if (radius > 0.0) {
            const double phi = std::atan2(lifted[p].z, lifted[p].y);
            EXPECT_NEAR(phi, flat.frontPointOfNode[n] == p ? -half : half, 1e-12) << "point " << p;
        }
    }
}

TEST(PseudoTwoDExtraction, WedgeAwayFromTheAxisPairsEveryPoint)
{
    const PolyMesh mesh = makeWedge2D(3, 2, {-1, 0.5, 0}, {1, 1.5, 0}, 10.0, PlanarCellKind::Triangles);
    const PseudoTwoDMesh flat = extractPseudoTwoD(mesh);
    expectConsistent(mesh, flat);
    EXPECT_EQ(2 * flat.nodeCount(), mesh.pointCount());
    for (Label n = 0; n < flat.nodeCount(); ++n) EXPECT_NE(flat.frontPointOfNode[n], flat.backPointOfNode[n]);
    EXPECT_EQ(flat.planar.patches.size(), 4u);   // left, right, bottom, top: no axis
    // Back point = front point rotated by 10° about x.
    for (Label n = 0; n < flat.nodeCount(); ++n) {
        const Vector3 rotated = flat.rotateFrontToBack(mesh.points[flat.frontPointOfNode[n]] - flat.wedgeAxisPoint)
                                + flat.wedgeAxisPoint;
        EXPECT_NEAR(norm(rotated - mesh.points[flat.backPointOfNode[n]]), 0.0, 1e-12);
    }
}

TEST(PseudoTwoDExtraction, GeneralPlaneFrameIsRightHanded)
{
    const Vector3 n = Vector3{1, 2, 2} / 3.0;
    const PlaneFrame frame = PlaneFrame::fromNormal(n, {1, 0, 0});
    EXPECT_EQ(frame.axis, -1);
    EXPECT_NEAR(norm(cross(frame.e1, frame.e2) - n), 0.0, 1e-15);
    EXPECT_NEAR(dot(frame.e1, n), 0.0, 1e-15);
    const Vector3 p{0.3, -1.2, 4.0};
    EXPECT_NEAR(norm(frame.toGlobal(frame.toLocal(p)) - p), 0.0, 1e-14);
}

// ------------------------------------------------------------------------------------------
// Malformed meshes get errors that say what is wrong

TEST(PseudoTwoDErrors, TwoLayersOfCells)
{
    PolyMesh mesh = makeHexBox(3, 2, 2, {0, 0, 0}, {3, 2, 1});
    mesh.patches[4].type = "empty";   // zMin
    mesh.patches[5].type = "empty";   // zMax
    EXPECT_EQ(extractionError(mesh), "cell 0 has 1 face on empty patches; expected exactly 2, one on each plane "
                                     "(the mesh must be one layer of cells)");
}

TEST(PseudoTwoDErrors, FrontPointWithoutTwin)
{
    // One cell whose front face has an extra (collinear) point 4 on edge 0-1 that no side
    // face joins to the back plane.
    PolyMesh mesh;
    mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const std::vector<std::vector<Label>> faces{{0, 1, 6, 5}, {1, 2, 7, 6}, {2, 3, 8, 7}, {3, 0, 5, 8},
                                                {3, 2, 1, 4, 0}, {5, 6, 7, 8}};
    for (const auto& face : faces) {
        mesh.addFace(face);
        mesh.owner.push_back(0);
    }
    Patch sides;
    sides.name = "sides";
    sides.type = "patch";
    sides.faceCount = 4;
    Patch frontAndBack;
    frontAndBack.name = "frontAndBack";
    frontAndBack.type = "empty";
    frontAndBack.startFace = 4;
    frontAndBack.faceCount = 2;
    mesh.patches = {sides, frontAndBack};
    EXPECT_EQ(extractionError(mesh), "point 4 (0.5 0 0) on the front plane has no twin on the other plane: no side "
                                     "face joins it to the other plane");
}

TEST(PseudoTwoDErrors, NonPlanarEmptyPlane)
{
    PolyMesh mesh = makeExtruded2D(3, 3, {0, 0, 0}, {1, 1, 0.1});
    mesh.points[5].z = 0.01;
    const std::string message = extractionError(mesh);
    EXPECT_NE(message.find("the front empty plane is not planar: point 5"), std::string::npos) << message;
}

TEST(PseudoTwoDErrors, SideFaceInAnEmptyPatch)
{
    PolyMesh mesh = makeExtruded2D(3, 3, {0, 0, 0}, {1, 1, 0.1});
    mesh.patches[0].type = "empty";   // "left": its faces are perpendicular to the planes
    const std::string message = extractionError(mesh);
    EXPECT_NE(message.find("(patch 'left') is not parallel to the empty planes"), std::string::npos) << message;
}

TEST(PseudoTwoDErrors, WedgeWithOnlyOneWedgePatch)
{
    PolyMesh mesh = makeWedge2D(3, 3, {0, 0, 0}, {1, 1, 0}, 5.0);
    mesh.patches[mesh.findPatch("back")].type = "patch";
    EXPECT_EQ(extractionError(mesh),
              "the mesh has 1 wedge patches with faces; expected exactly 2 (the front and back planes of the wedge)");
}

TEST(PseudoTwoDErrors, WedgeTwinsNotRelatedByTheRotation)
{
    PolyMesh mesh = makeWedge2D(3, 3, {0, 0.5, 0}, {1, 1.5, 0}, 5.0);
    const PseudoTwoDMesh flat = extractPseudoTwoD(mesh);
    // Slide one back point within the back plane: planes stay planar, the pairing breaks.
    const Label back = flat.backPointOfNode[5];
    mesh.points[back] += 0.01 * flat.rotateFrontToBack(Vector3{1, 0, 0});
    const std::string message = extractionError(mesh);
    EXPECT_NE(message.find("are not related by the wedge rotation of 5 degrees"), std::string::npos) << message;
}
