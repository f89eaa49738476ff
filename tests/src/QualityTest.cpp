// Geometry and quality metrics on hand-built cells whose figures are computed by hand:
// MeshGeometry (OpenFOAM's face/cell decomposition), CheckMeshQuality (checkMesh's
// definitions) and ThesisQuality (thesis §2.7).

#include "CheckMeshQuality.hpp"
#include "MeshGenerators.hpp"
#include "MeshGeometry.hpp"
#include "PlanarMesh.hpp"
#include "PolyMeshReader.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "QualityReport.hpp"
#include "ThesisQuality.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <map>
#include <numbers>
#include <tuple>
#include <vector>

namespace {

using rbm::Label;
using rbm::PolyMesh;
using rbm::Vector3;

constexpr double pi = std::numbers::pi;
double degrees(double radians) { return radians * 180.0 / pi; }

// A cell given as its faces, each oriented outward (right-hand normal out of the cell).
using CellFaces = std::vector<std::vector<Label>>;

// Builds an OpenFOAM-ordered PolyMesh from cells given by outward faces: faces shared by
// two cells become internal (owned by the lower cell, oriented as that cell gives them),
// sorted by owner then neighbour; all other faces go to one patch "walls".
PolyMesh buildMesh(std::vector<Vector3> points, const std::vector<CellFaces>& cells)
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
CellFaces hexFaces(Label offset = 0)
{
    auto o = [offset](std::initializer_list<Label> f) {
        std::vector<Label> v;
        for (Label p : f) v.push_back(p + offset);
        return v;
    };
    return {o({0, 4, 7, 3}), o({1, 2, 6, 5}), o({0, 1, 5, 4}), o({3, 7, 6, 2}), o({0, 3, 2, 1}), o({4, 5, 6, 7})};
}

std::vector<Vector3> unitCubePoints(const Vector3& origin = {})
{
    std::vector<Vector3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (auto& x : p) x += origin;
    return p;
}

// The unit cube [0,1]^3 (cell 0) and, sharing its x = 1 face, a parallelepiped whose far
// face is shifted by `shear` in y (cell 1).
PolyMesh shearedPair(double shear)
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

// ---------------------------------------------------------------------------
// MeshGeometry

TEST(MeshGeometry, UnitCubeHasVolumeOneAndCentreAtItsMiddle)
{
    const PolyMesh mesh = buildMesh(unitCubePoints(), {hexFaces()});
    const auto g = rbm::computeMeshGeometry(mesh);
    ASSERT_EQ(g.cellVolumes.size(), 1u);
    EXPECT_NEAR(g.cellVolumes[0], 1.0, 1e-15);
    EXPECT_NEAR(g.cellCentres[0].x, 0.5, 1e-15);
    EXPECT_NEAR(g.cellCentres[0].y, 0.5, 1e-15);
    EXPECT_NEAR(g.cellCentres[0].z, 0.5, 1e-15);
    for (Label f = 0; f < mesh.faceCount(); ++f) {
        // Unit outward area vectors; centres on the face planes at the face middles.
        EXPECT_NEAR(rbm::norm(g.faceAreas[f]), 1.0, 1e-15);
        const Vector3 outward = g.faceCentres[f] - g.cellCentres[0];
        EXPECT_NEAR(rbm::dot(outward, g.faceAreas[f]), 0.5, 1e-15) << "face " << f;
        EXPECT_NEAR(rbm::norm(outward), 0.5, 1e-15) << "face " << f;
    }
}

TEST(MeshGeometry, CubeFarFromTheOriginKeepsItsVolume)
{
    const PolyMesh mesh = buildMesh(unitCubePoints({1e5, -2e5, 3e5}), {hexFaces()});
    const auto g = rbm::computeMeshGeometry(mesh);
    EXPECT_NEAR(g.cellVolumes[0], 1.0, 1e-9);
    EXPECT_NEAR(g.cellCentres[0].x, 1e5 + 0.5, 1e-9);
}

TEST(MeshGeometry, TetrahedronVolumeIsOneSixthOfTheTripleProduct)
{
    const std::vector<Vector3> points = {{0.1, 0.2, 0.3}, {2.1, 0.4, 0.2}, {0.5, 1.7, 0.1}, {0.3, 0.6, 1.4}};
    // (p1-p0) x (p2-p0) points towards p3: outward faces.
    const PolyMesh mesh = buildMesh(points, {{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}});
    const auto g = rbm::computeMeshGeometry(mesh);
    const double expected =
        rbm::dot(rbm::cross(points[1] - points[0], points[2] - points[0]), points[3] - points[0]) / 6.0;
    ASSERT_GT(expected, 0.0);
    EXPECT_NEAR(g.cellVolumes[0], expected, 1e-15);
    const Vector3 centroid = 0.25 * (points[0] + points[1] + points[2] + points[3]);
    EXPECT_NEAR(rbm::norm(g.cellCentres[0] - centroid), 0.0, 1e-15);
}

TEST(MeshGeometry, PrismVolumeIsBaseAreaTimesHeight)
{
    const double h = 0.7;
    const std::vector<Vector3> points = {{0, 0, 0}, {3, 0, 0}, {0, 2, 0}, {0, 0, h}, {3, 0, h}, {0, 2, h}};
    const PolyMesh mesh = buildMesh(points, {{{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}}});
    const auto g = rbm::computeMeshGeometry(mesh);
    EXPECT_NEAR(g.cellVolumes[0], 3.0 * h, 1e-14);   // base area 3
    EXPECT_NEAR(g.cellCentres[0].x, 1.0, 1e-14);
    EXPECT_NEAR(g.cellCentres[0].y, 2.0 / 3.0, 1e-14);
    EXPECT_NEAR(g.cellCentres[0].z, h / 2, 1e-14);
}

TEST(MeshGeometry, PolygonalFaceCentreIsItsAreaCentroidNotItsPointAverage)
{
    // A pentagon: unit square with an extra point on one edge. Point average is off the
    // centroid; OpenFOAM's triangle decomposition gives the true centroid.
    PolyMesh mesh;
    mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 0.25, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<Label> face = {0, 1, 2, 3, 4};
    mesh.addFace(face);
    mesh.owner = {0};
    std::vector<Vector3> centres, areas;
    rbm::computeFaceCentresAndAreas(mesh, mesh.points, centres, areas);
    EXPECT_NEAR(centres[0].x, 0.5, 1e-15);
    EXPECT_NEAR(centres[0].y, 0.5, 1e-15);
    EXPECT_NEAR(areas[0].z, 1.0, 1e-15);
}

TEST(MeshGeometry, MirroredCellHasNegativeVolume)
{
    auto points = unitCubePoints();
    for (auto& p : points) p.x = -p.x;
    const PolyMesh mesh = buildMesh(points, {hexFaces()});
    const auto g = rbm::computeMeshGeometry(mesh);
    EXPECT_NEAR(g.cellVolumes[0], -1.0, 1e-15);
}

TEST(MeshGeometry, MovedPointsReplaceTheMeshPoints)
{
    const PolyMesh mesh = buildMesh(unitCubePoints(), {hexFaces()});
    auto moved = mesh.points;
    for (auto& p : moved) p *= 2.0;
    rbm::MeshGeometry g;
    rbm::updateMeshGeometry(mesh, moved, g);
    EXPECT_NEAR(g.cellVolumes[0], 8.0, 1e-14);
    std::vector<Vector3> wrongCount(3);
    EXPECT_THROW(rbm::updateMeshGeometry(mesh, wrongCount, g), std::invalid_argument);
}

// ---------------------------------------------------------------------------
// CheckMeshQuality

TEST(CheckMeshQuality, ShearedNeighbourHasTheAngleOfItsCentreLine)
{
    // Centres (0.5, 0.5, 0.5) and (1.5, 0.5 + s/2, 0.5); face normal +x: angle atan(s/2).
    const double shear = 1.0;
    const PolyMesh mesh = shearedPair(shear);
    const auto g = rbm::computeMeshGeometry(mesh);
    const auto q = rbm::computeCheckMeshQuality(mesh, g);
    const double expected = degrees(std::atan(shear / 2));   // 26.565051177077990
    EXPECT_NEAR(q.maxNonOrthogonality, expected, 1e-12);
    EXPECT_NEAR(q.averageNonOrthogonality, expected, 1e-12);   // one internal face
    EXPECT_EQ(q.severelyNonOrthogonalFaceCount, 0);
    EXPECT_NEAR(q.totalVolume, 2.0, 1e-14);
    EXPECT_NEAR(q.minCellVolume, 1.0, 1e-14);
}

TEST(CheckMeshQuality, SkewnessOfTheShearedPairFollowsOpenFoamsNormalisation)
{
    const PolyMesh mesh = shearedPair(1.0);
    const auto g = rbm::computeMeshGeometry(mesh);
    // Internal face x = 1: the centre line crosses it at y = 0.75, the face centre is at
    // y = 0.5: |sv| = 0.25; fd = max(0.2 |d|, half the face width 0.5) = 0.5 -> 0.5.
    ASSERT_EQ(mesh.internalFaceCount(), 1);
    EXPECT_NEAR(rbm::faceSkewness(mesh.face(0), mesh.points, g.faceCentres[0], g.faceAreas[0], g.cellCentres[0],
                                  g.cellCentres[1]),
                0.5, 1e-14);
    // The far face x = 2 of cell 1: mirrored neighbour, |sv| = s/2 = 0.5, fd = 0.5 -> 1.
    // The sheared side faces of cell 1: |sv| = sqrt(2)/4, fd = sqrt(2)/2 -> 0.5. The cube's
    // boundary faces: 0. So the largest is 1.
    const auto q = rbm::computeCheckMeshQuality(mesh, g);
    EXPECT_NEAR(q.maxSkewness, 1.0, 1e-14);
    EXPECT_EQ(q.severelySkewFaceCount, 0);
}

TEST(CheckMeshQuality, AspectRatioIsTheRatioOfDirectionalAreaSums)
{
    // Cell 1 of the sheared pair: component-wise |S| sums (4, 2, 2) -> 2, more than the
    // hydraulic measure (4+2+2)/6/V^(2/3) = 4/3. The cube: 1.
    const PolyMesh mesh = shearedPair(1.0);
    const auto q = rbm::computeCheckMeshQuality(mesh, rbm::computeMeshGeometry(mesh));
    EXPECT_NEAR(q.maxAspectRatio, 2.0, 1e-14);
    // A 4 x 1 x 1 box cell: sums (2, 8, 8) -> 4; hydraulic (18/6)/4^(2/3) = 1.19.
    const PolyMesh box = rbm::makeHexBox(1, 1, 1, {0, 0, 0}, {4, 1, 1});
    EXPECT_NEAR(rbm::computeCheckMeshQuality(box, rbm::computeMeshGeometry(box)).maxAspectRatio, 4.0, 1e-14);
    // A flat 1 x 1 x 0.01 cube: sums (0.02, 0.02, 2) -> 100.
    const PolyMesh flat = rbm::makeHexBox(1, 1, 1, {0, 0, 0}, {1, 1, 0.01});
    EXPECT_NEAR(rbm::computeCheckMeshQuality(flat, rbm::computeMeshGeometry(flat)).maxAspectRatio, 100.0, 1e-10);
}

TEST(CheckMeshQuality, TwoDimensionalMeshIgnoresTheEmptyDirectionInAspectRatio)
{
    // One layer 1 x 0.5 in-plane, 0.01 thick, empty front and back: in 3D the ratio would
    // be about 100; checkMesh uses only x and y: sums (2 * 0.005, 2 * 0.01) -> 2.
    const PolyMesh mesh = rbm::makeExtruded2D(1, 1, {0, 0, 0}, {1, 0.5, 0.01});
    const auto q = rbm::computeCheckMeshQuality(mesh, rbm::computeMeshGeometry(mesh));
    EXPECT_EQ(q.geometricDirections, (std::array<int, 3>{1, 1, 0}));
    EXPECT_EQ(q.solutionDirections, (std::array<int, 3>{1, 1, 0}));
    EXPECT_EQ(q.geometricDimensionCount(), 2);
    EXPECT_NEAR(q.maxAspectRatio, 2.0, 1e-12);
}

TEST(CheckMeshQuality, WedgeDirectionIsNotGeometricButStillSolved)
{
    const PolyMesh mesh = rbm::makeWedge2D(3, 2, {0, 0, 0}, {1, 1, 0}, 5.0);
    const auto q = rbm::computeCheckMeshQuality(mesh, rbm::computeMeshGeometry(mesh));
    // The wedge planes straddle z = 0 about the x axis: z is the wedge direction.
    EXPECT_EQ(q.geometricDirections, (std::array<int, 3>{1, 1, 0}));
    EXPECT_EQ(q.solutionDirections, (std::array<int, 3>{1, 1, 1}));
}

TEST(CheckMeshQuality, MirroredCellFailsTheVolumeAndPyramidChecks)
{
    auto points = unitCubePoints();
    for (auto& p : points) p.x = -p.x;
    const PolyMesh mesh = buildMesh(points, {hexFaces()});
    const auto q = rbm::computeCheckMeshQuality(mesh, rbm::computeMeshGeometry(mesh));
    EXPECT_EQ(q.nonPositiveVolumeCellCount, 1);
    EXPECT_NEAR(q.minCellVolume, -1.0, 1e-15);
    EXPECT_EQ(q.incorrectlyOrientedPyramidCount, 6);   // every face's owner pyramid
    EXPECT_TRUE(q.hasInvalidCells());
    // checkMesh's aspect ratio takes V as max(ROOTVSMALL, V): a negative volume gives 1e100,
    // so the closed-cells check fails too: volumes, pyramids, closed cells.
    EXPECT_EQ(q.highAspectRatioCellCount, 1);
    EXPECT_EQ(q.failedCheckCount(), 3);
}

TEST(CheckMeshQuality, CellFoldedBackThroughItsNeighbourIsANonOrthogonalityError)
{
    // Move the far face of the second cell to x = -0.5, behind the shared face x = 1: the
    // cell is inverted (volume -1.5) and its centre (x = 0.25) lies behind the owner's
    // (x = 0.5), so the centre line runs against the face normal: 180 degrees.
    auto mesh = shearedPair(0.0);
    for (Label p = 8; p < 12; ++p) mesh.points[p].x = -0.5;
    const auto g = rbm::computeMeshGeometry(mesh);
    EXPECT_NEAR(g.cellVolumes[1], -1.5, 1e-14);
    const auto q = rbm::computeCheckMeshQuality(mesh, g);
    EXPECT_EQ(q.nonOrthogonalityErrorCount, 1);
    EXPECT_NEAR(q.maxNonOrthogonality, 180.0, 1e-6);
    EXPECT_EQ(q.nonPositiveVolumeCellCount, 1);
    EXPECT_GT(q.incorrectlyOrientedPyramidCount, 0);
    EXPECT_EQ(q.failedCheckCount(), 4);   // volumes, non-orthogonality, pyramids, aspect ratio
    const auto thesis = rbm::computeThesisQuality3D(mesh, g);
    EXPECT_EQ(thesis.invertedCellCount, 1);
    EXPECT_NEAR(thesis.nonOrthogonality.max, 180.0, 1e-6);
}

TEST(CheckMeshQuality, ValidBoxPassesEveryCheck)
{
    const PolyMesh mesh = rbm::makeHexBox(3, 2, 2, {0, 0, 0}, {3, 1, 1});
    const auto q = rbm::computeCheckMeshQuality(mesh, rbm::computeMeshGeometry(mesh));
    EXPECT_EQ(q.failedCheckCount(), 0);
    EXPECT_FALSE(q.hasInvalidCells());
    EXPECT_NEAR(q.maxNonOrthogonality, 0.0, 1e-5);
    EXPECT_NEAR(q.maxSkewness, 0.0, 1e-12);
    EXPECT_NEAR(q.totalVolume, 3.0, 1e-14);
    EXPECT_NEAR(q.maxAspectRatio, 2.0, 1e-14);   // cells 1 x 0.5 x 0.5
    EXPECT_NEAR(q.maxCellOpenness, 0.0, 1e-15);
    EXPECT_NEAR(q.averageFaceWeight, 0.5, 1e-15);
    EXPECT_NEAR(q.minVolumeRatio, 1.0, 1e-15);
}

// ---------------------------------------------------------------------------
// Thesis metrics: elements

TEST(ThesisQuality, EquilateralTriangleHasMeanRatioOne)
{
    EXPECT_NEAR(rbm::triangleMeanRatio({0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}), 1.0, 1e-15);
    // Scale, rotation and translation do not change it.
    const double c = std::cos(0.3), s = std::sin(0.3);
    auto t = [&](double x, double y) { return Vector3{5 + 7 * (c * x - s * y), -2 + 7 * (s * x + c * y), 0}; };
    EXPECT_NEAR(rbm::triangleMeanRatio(t(0, 0), t(1, 0), t(0.5, std::sqrt(3.0) / 2)), 1.0, 1e-14);
}

TEST(ThesisQuality, RightIsoscelesTriangleMeanRatioByHand)
{
    // A_i = I, S_i = W^-1 = [[1, -1/sqrt3], [0, 2/sqrt3]]: det = 2/sqrt3, |S|_F^2 = 8/3,
    // det/|S|^2 = sqrt3/4 at every node, q = 2 * sqrt3/4 = sqrt3/2.
    EXPECT_NEAR(rbm::triangleMeanRatio({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), std::sqrt(3.0) / 2, 1e-15);
}

TEST(ThesisQuality, InvertedTriangleHasNegativeMeanRatioAndDegenerateZero)
{
    EXPECT_NEAR(rbm::triangleMeanRatio({0, 0, 0}, {0, 1, 0}, {1, 0, 0}), -std::sqrt(3.0) / 2, 1e-15);
    EXPECT_EQ(rbm::triangleMeanRatio({0, 0, 0}, {1, 0, 0}, {2, 0, 0}), 0.0);
}

TEST(ThesisQuality, SquareHasShapeOneRectangleAndParallelogramByHand)
{
    EXPECT_NEAR(rbm::quadrilateralShape({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}), 1.0, 1e-15);
    EXPECT_NEAR(rbm::quadrilateralShape({3, 3, 0}, {3.5, 3, 0}, {3.5, 3.5, 0}, {3, 3.5, 0}), 1.0, 1e-15);
    // a x b rectangle: det(A_n) = ab, tr(S_n) = a^2 + b^2 at every corner: F = 2ab/(a^2+b^2).
    EXPECT_NEAR(rbm::quadrilateralShape({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}), 0.8, 1e-15);
    // Rhombus of side 1 and angle 60 degrees: det = sin 60, tr = 2: F = sin 60.
    const double c = 0.5, s = std::sqrt(3.0) / 2;
    EXPECT_NEAR(rbm::quadrilateralShape({0, 0, 0}, {1, 0, 0}, {1 + c, s, 0}, {c, s, 0}), s, 1e-15);
    // Parallelogram with sides 2 and 1 at 45 degrees: F = 2*2*1*sin45/(4+1).
    const double r = std::sqrt(0.5);
    EXPECT_NEAR(rbm::quadrilateralShape({0, 0, 0}, {2, 0, 0}, {2 + r, r, 0}, {r, r, 0}), 4 * r / 5, 1e-15);
}

TEST(ThesisQuality, ClockwiseQuadrilateralHasNegativeShape)
{
    EXPECT_NEAR(rbm::quadrilateralShape({0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}), -1.0, 1e-15);
    EXPECT_EQ(rbm::quadrilateralShape({0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}), 0.0);   // collapsed corner
}

TEST(ThesisQuality, StatisticsArePopulationMeanAndStandardDeviation)
{
    rbm::StatisticsAccumulator a;
    for (double x : {4.0, 1.0, 3.0, 2.0}) a.add(x);
    const auto s = a.result();
    EXPECT_EQ(s.count, 4);
    EXPECT_DOUBLE_EQ(s.mean, 2.5);
    EXPECT_DOUBLE_EQ(s.standardDeviation, std::sqrt(1.25));   // eq 2.98b, 1/N
    EXPECT_EQ(s.min, 1.0);
    EXPECT_EQ(s.max, 4.0);
    EXPECT_EQ(rbm::StatisticsAccumulator{}.result().count, 0);
}

TEST(ThesisQuality, CentreLineSkewnessIsNormalisedByTheCentreDistance)
{
    // Centres (0,0) and (2,1), edge through (1, 0) with normal +x: the line crosses x = 1 at
    // y = 0.5; distance 0.5 to the edge centre, over |d| = sqrt5.
    EXPECT_NEAR(rbm::centreLineSkewness({0, 0, 0}, {2, 1, 0}, {1, 0, 0}, {1, 0, 0}), 0.5 / std::sqrt(5.0), 1e-15);
    EXPECT_NEAR(rbm::nonOrthogonalityAngle({0, 0, 0}, {2, 1, 0}, {3, 0, 0}), degrees(std::atan(0.5)), 1e-12);
}

// ---------------------------------------------------------------------------
// Thesis metrics: meshes

// Two quadrilaterals side by side in 2D: (0,0)-(1,0)-(1,1)-(0,1) and its neighbour whose
// far edge is shifted by `shear` in y.
rbm::PlanarMesh shearedPlanarPair(double shear)
{
    rbm::PlanarMesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, shear, 0}, {2, 1 + shear, 0}};
    m.cellOffsets = {0, 4, 8};
    m.cellPoints = {0, 1, 2, 3, 1, 4, 5, 2};
    // Internal edge first: 1 -> 2 keeps cell 0 on its left.
    m.edgePoints = {1, 2, 0, 1, 2, 3, 3, 0, 1, 4, 4, 5, 5, 2};
    m.edgeOwner = {0, 0, 0, 0, 1, 1, 1};
    m.edgeNeighbour = {1};
    m.patches.push_back({"walls", "wall", 1, 6, 0});
    return m;
}

TEST(ThesisQuality, PlanarPairHasHandComputedMetrics)
{
    const auto q = rbm::computeThesisQuality2D(shearedPlanarPair(1.0));
    EXPECT_EQ(q.dimension, 2);
    EXPECT_EQ(q.cellCount, 2);
    EXPECT_EQ(q.invertedCellCount, 0);
    // Centroids (0.5, 0.5) and (1.5, 1.0): angle atan(0.5) with the edge normal +x; the
    // line crosses x = 1 at y = 0.75, 0.25 from the edge middle, over |d| = sqrt(1.25).
    EXPECT_EQ(q.nonOrthogonality.count, 1);
    EXPECT_NEAR(q.nonOrthogonality.max, degrees(std::atan(0.5)), 1e-12);
    EXPECT_NEAR(q.skewness.max, 0.25 / std::sqrt(1.25), 1e-15);
    // F_shape: the square 1, the rhombus-like parallelogram (sides 1 and sqrt2 at 45
    // degrees): 2 * sqrt2 * sin45 / 3 = 2/3.
    EXPECT_EQ(q.quadrilateralShape.count, 2);
    EXPECT_NEAR(q.quadrilateralShape.max, 1.0, 1e-15);
    EXPECT_NEAR(q.quadrilateralShape.min, 2.0 / 3.0, 1e-15);
    EXPECT_NEAR(q.quadrilateralShape.mean, (1.0 + 2.0 / 3.0) / 2, 1e-15);
    EXPECT_NEAR(q.quadrilateralShape.standardDeviation, (1.0 - 2.0 / 3.0) / 2, 1e-15);
    EXPECT_EQ(q.triangleMeanRatio.count, 0);
}

TEST(ThesisQuality, PlanarInvertedCellIsCounted)
{
    auto m = shearedPlanarPair(0.0);
    std::vector<Vector3> moved = m.points;
    moved[4].x = moved[5].x = -0.5;   // the second quad folds back over the first
    rbm::ThesisQualityWorkspace workspace;
    const auto q = rbm::computeThesisQuality2D(m, moved, workspace);
    EXPECT_EQ(q.invertedCellCount, 1);
    EXPECT_LT(q.quadrilateralShape.min, 0.0);
    EXPECT_GT(q.nonOrthogonality.max, 90.0);   // centres on the wrong sides of the edge
}

TEST(ThesisQuality, ThreeDimensionalMetricsOfTheShearedPair)
{
    const PolyMesh mesh = shearedPair(1.0);
    const auto q = rbm::computeThesisQuality3D(mesh, rbm::computeMeshGeometry(mesh));
    EXPECT_EQ(q.dimension, 3);
    EXPECT_EQ(q.invertedCellCount, 0);
    EXPECT_NEAR(q.nonOrthogonality.mean, degrees(std::atan(0.5)), 1e-12);
    EXPECT_NEAR(q.skewness.mean, 0.25 / std::sqrt(1.25), 1e-15);
}

// ---------------------------------------------------------------------------
// QualityReport

TEST(QualityReport, OneLayerMixedMeshIsMeasuredInTwoDimensions)
{
    // 4 x 2 unit cells: quads for i < 2, the rest cut into right isosceles triangles.
    const PolyMesh mesh = rbm::makeExtruded2D(4, 2, {0, 0, 0}, {4, 2, 0.1}, rbm::PlanarCellKind::Mixed);
    const auto report = rbm::computeQualityReport(mesh);
    EXPECT_EQ(report.pseudoTwoD, rbm::PseudoTwoDKind::Empty);
    ASSERT_EQ(report.thesis.dimension, 2) << report.twoDExtractionProblem;
    EXPECT_EQ(report.thesis.quadrilateralShape.count, 4);
    EXPECT_NEAR(report.thesis.quadrilateralShape.mean, 1.0, 1e-14);
    EXPECT_EQ(report.thesis.triangleMeanRatio.count, 8);
    EXPECT_NEAR(report.thesis.triangleMeanRatio.mean, std::sqrt(3.0) / 2, 1e-14);
    EXPECT_NEAR(report.thesis.triangleMeanRatio.standardDeviation, 0.0, 1e-14);
    // Triangles across a vertical edge: centroids (i + 2/3, 1/3) and (i + 4/3, 2/3), normal
    // +x: atan(1/2). Across a diagonal or between squares: 0.
    EXPECT_NEAR(report.thesis.nonOrthogonality.max, degrees(std::atan(0.5)), 1e-10);
    EXPECT_NEAR(report.thesis.nonOrthogonality.min, 0.0, 1e-6);
    EXPECT_NEAR(report.checkMesh.maxNonOrthogonality, degrees(std::atan(0.5)), 1e-10);
    EXPECT_TRUE(report.isValid());
    const std::string text = rbm::formatQualityReport(report);
    EXPECT_NE(text.find("Mesh is 2D"), std::string::npos) << text;
    EXPECT_NE(text.find("Mesh OK."), std::string::npos) << text;
    const std::string json = rbm::qualityReportJson(report);
    EXPECT_NE(json.find("\"dimension\": 2"), std::string::npos) << json;
}

TEST(QualityReport, WedgeMeshIsMeasuredInTwoDimensions)
{
    const PolyMesh mesh = rbm::makeWedge2D(3, 2, {0, 0.5, 0}, {1, 1.5, 0}, 5.0);
    const auto report = rbm::computeQualityReport(mesh);
    EXPECT_EQ(report.pseudoTwoD, rbm::PseudoTwoDKind::Wedge);
    ASSERT_EQ(report.thesis.dimension, 2) << report.twoDExtractionProblem;
    EXPECT_EQ(report.thesis.quadrilateralShape.count, 6);
    EXPECT_EQ(report.thesis.invertedCellCount, 0);
}

TEST(QualityReport, EvaluatorMeasuresMovedPointsAndComesBack)
{
    const PolyMesh mesh = rbm::makeExtruded2D(3, 3, {0, 0, 0}, {3, 3, 1});
    rbm::QualityEvaluator evaluator(mesh);
    ASSERT_TRUE(evaluator.isTwoD());
    auto moved = mesh.points;
    // Push the interior node (1, 1) on both planes to x = 4, past the nodes at x = 2 and 3:
    // the cells on its right fold (cell x 1..2, y 0..1 gets signed area -0.5).
    for (auto& p : moved) {
        if (p.x == 1.0 && p.y == 1.0) p.x = 4.0;
    }
    const auto folded = evaluator.evaluate(moved);
    EXPECT_FALSE(folded.isValid());
    EXPECT_GT(folded.thesis.invertedCellCount, 0);
    EXPECT_GT(folded.checkMesh.nonPositiveVolumeCellCount, 0);
    EXPECT_NE(rbm::formatQualityReport(folded).find("Failed"), std::string::npos);
    EXPECT_TRUE(evaluator.evaluate(mesh.points).isValid());
}

// QualityEvaluator::evaluateStep: the log line's four figures, by hand.

TEST(StepQuality, OneLayerMixedMeshHasTheWorstTriangleAndTheCentreLineAngle)
{
    // As OneLayerMixedMeshIsMeasuredInTwoDimensions: squares (F_shape 1) and right isosceles
    // triangles (q = 4 sqrt(3) (1/2) / (1 + 1 + 2) = sqrt(3)/2), worst = sqrt(3)/2; the
    // largest non-orthogonality atan(1/2) across a vertical edge between triangles.
    const PolyMesh mesh = rbm::makeExtruded2D(4, 2, {0, 0, 0}, {4, 2, 0.1}, rbm::PlanarCellKind::Mixed);
    rbm::QualityEvaluator evaluator(mesh);
    const rbm::StepQuality step = evaluator.evaluateStep(mesh.points);
    EXPECT_NEAR(step.worstCellQuality, std::sqrt(3.0) / 2, 1e-14);
    EXPECT_NEAR(step.maxNonOrthogonality, degrees(std::atan(0.5)), 1e-10);
    EXPECT_EQ(step.invertedCellCount, 0);
    // The same figures as the full report: the worst quality to the last bit; the checkMesh
    // extremes of this exact extrusion from the 2D closed forms, to rounding.
    const rbm::QualityReport full = evaluator.evaluate(mesh.points);
    EXPECT_NEAR(step.maxNonOrthogonality, full.checkMesh.maxNonOrthogonality, 1e-12 * full.checkMesh.maxNonOrthogonality);
    EXPECT_NEAR(step.maxSkewness, full.checkMesh.maxSkewness, 1e-12 * full.checkMesh.maxSkewness);
    EXPECT_GT(full.checkMesh.maxSkewness, 0.1);
    EXPECT_EQ(step.worstCellQuality, std::min(full.thesis.triangleMeanRatio.min, full.thesis.quadrilateralShape.min));
}

TEST(StepQuality, FoldedTwoDimensionalCellsAreCountedByTheirArea)
{
    // As EvaluatorMeasuresMovedPointsAndComesBack: node (1, 1) pushed to x = 4 folds the two
    // cells on its right, (1,0) (2,0) (2,1) (4,1) and (4,1) (2,1) (2,2) (1,2): signed area
    // -0.5 each (shoelace), F_shape 8 / (11/1 + 2/1 + 5/-2 + 14/-2) = 16/7: positive although
    // folded, so F_shape alone does not flag them; the area does. Worst: the two stretched
    // cells on its left, (0,0) (1,0) (4,1) (0,1): corner terms tr/det 2/1 + 11/1 + 26/4 + 17/4
    // = 95/4, F_shape 32/95.
    const PolyMesh mesh = rbm::makeExtruded2D(3, 3, {0, 0, 0}, {3, 3, 1});
    rbm::QualityEvaluator evaluator(mesh);
    auto moved = mesh.points;
    for (auto& p : moved) {
        if (p.x == 1.0 && p.y == 1.0) p.x = 4.0;
    }
    const rbm::StepQuality step = evaluator.evaluateStep(moved);
    const rbm::QualityReport full = evaluator.evaluate(moved);
    EXPECT_EQ(step.invertedCellCount, 2);
    EXPECT_EQ(step.invertedCellCount, full.thesis.invertedCellCount);
    EXPECT_NEAR(step.worstCellQuality, 32.0 / 95.0, 1e-15);
    EXPECT_EQ(step.worstCellQuality, full.thesis.quadrilateralShape.min);
    EXPECT_EQ(step.maxNonOrthogonality, full.checkMesh.maxNonOrthogonality);
    EXPECT_EQ(step.maxSkewness, full.checkMesh.maxSkewness);
    // Back at the initial points: unit squares, F_shape 1, nothing inverted, orthogonal.
    const rbm::StepQuality back = evaluator.evaluateStep(mesh.points);
    EXPECT_EQ(back.invertedCellCount, 0);
    EXPECT_NEAR(back.worstCellQuality, 1.0, 1e-15);
    EXPECT_NEAR(back.maxNonOrthogonality, 0.0, 1e-6);
    EXPECT_NEAR(back.maxSkewness, 0.0, 1e-12);
}

TEST(StepQuality, ThreeDimensionalWorstIsTheSmallestPyramidOverTheMeanOne)
{
    // Sheared pair, shear s: the cube's six pyramids are 1/6 each (ratio 1). The
    // parallelepiped (volume 1): apex at its centre (1.5, 0.5 + s/2, 0.5); its x = 1 face
    // (area 1, normal -x) gives 0.5/3, the x = 2 face likewise, the y faces (area vectors
    // (-s, ±1, 0)·... ) and z faces each 1/6: ratio 6 · (1/6) / 1 = 1 again for a pure
    // parallelepiped. A non-planar cell gives less: push one far point of cell 1 out in z.
    const PolyMesh pair = shearedPair(0.5);
    rbm::QualityEvaluator evaluator(pair);
    const rbm::StepQuality step = evaluator.evaluateStep(pair.points);
    EXPECT_NEAR(step.worstCellQuality, 1.0, 1e-14);
    EXPECT_EQ(step.invertedCellCount, 0);
    EXPECT_NEAR(step.maxNonOrthogonality, degrees(std::atan(0.5 / 2)), 1e-10)
        << "centre line (1, s/2, 0) against the face normal (1, 0, 0)";

    // Mirror cell 1 through x = 1 (its far points to x = 0): it turns inside out, volume < 0.
    auto mirrored = pair.points;
    for (std::size_t p = 8; p < mirrored.size(); ++p) mirrored[p].x = 0.0;
    const rbm::StepQuality inverted = evaluator.evaluateStep(mirrored);
    const rbm::QualityReport full = evaluator.evaluate(mirrored);
    EXPECT_EQ(inverted.invertedCellCount, 1);
    EXPECT_EQ(full.thesis.invertedCellCount, 1);
    EXPECT_LE(inverted.worstCellQuality, 0.0);
    EXPECT_EQ(inverted.maxNonOrthogonality, full.checkMesh.maxNonOrthogonality);
    EXPECT_EQ(inverted.maxSkewness, full.checkMesh.maxSkewness);
}

TEST(StepQuality, ReleasedWorkspacesGiveTheSameFiguresAndGeometryAgain)
{
    // rbmMoveMesh gives the evaluator's arrays back between time steps (the peak of a large
    // run): the next evaluateStep and geometryAt compute them again, to the last bit.
    const PolyMesh box = rbm::makeHexBox(3, 2, 2, {0, 0, 0}, {3, 2, 2});
    auto moved = box.points;
    for (std::size_t p = 0; p < moved.size(); ++p) moved[p].y += 0.1 * moved[p].x * moved[p].z;
    rbm::QualityEvaluator evaluator(box);
    const rbm::StepQuality before = evaluator.evaluateStep(moved);
    const rbm::MeshGeometry geometry = evaluator.geometryAt(moved);
    ASSERT_EQ(geometry.cellVolumes.size(), 12u);
    evaluator.releaseWorkspaces();
    EXPECT_TRUE(evaluator.geometry().faceCentres.empty());
    const rbm::MeshGeometry& again = evaluator.geometryAt(moved);  // computed again, nothing evaluated in between
    EXPECT_EQ(again.faceCentres, geometry.faceCentres);
    EXPECT_EQ(again.cellVolumes, geometry.cellVolumes);
    evaluator.releaseWorkspaces();
    const rbm::StepQuality after = evaluator.evaluateStep(moved);
    EXPECT_EQ(after.worstCellQuality, before.worstCellQuality);
    EXPECT_EQ(after.maxNonOrthogonality, before.maxNonOrthogonality);
    EXPECT_EQ(after.maxSkewness, before.maxSkewness);
    EXPECT_EQ(after.invertedCellCount, before.invertedCellCount);
    EXPECT_GT(after.maxNonOrthogonality, 1.0);
}

TEST(StepQuality, PolygonSignedAreaIsPolygonCentroidsToTheLastBit)
{
    // Far from the origin, where the fan about the first node matters.
    const std::vector<Vector3> positions = {{1e6 + 0.1, 3e5 + 0.7, 0}, {1e6 + 1.3, 3e5 + 0.2, 0},
                                            {1e6 + 1.9, 3e5 + 1.1, 0}, {1e6 + 0.4, 3e5 + 1.6, 0},
                                            {1e6 - 0.3, 3e5 + 1.2, 0}};
    for (const std::vector<Label>& polygon : std::vector<std::vector<Label>>{{0, 1, 2}, {0, 1, 2, 3}, {0, 1, 2, 3, 4},
                                                                               {4, 3, 2, 1, 0}}) {
        double area = 0.0;
        (void)rbm::polygonCentroid(polygon, positions, area);
        EXPECT_EQ(rbm::polygonSignedArea(polygon, positions), area);
    }
    // The unit square: 1; clockwise: -1.
    const std::vector<Vector3> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    EXPECT_EQ(rbm::polygonSignedArea(std::vector<Label>{0, 1, 2, 3}, square), 1.0);
    EXPECT_EQ(rbm::polygonSignedArea(std::vector<Label>{3, 2, 1, 0}, square), -1.0);
}

TEST(QualityReport, JsonWritesNonFiniteNumbersAsNull)
{
    rbm::QualityReport report;
    report.checkMesh.maxAspectRatio = std::numeric_limits<double>::infinity();
    const std::string json = rbm::qualityReportJson(report);
    EXPECT_NE(json.find("\"maxAspectRatio\": null"), std::string::npos) << json;
    EXPECT_EQ(json.find("inf"), std::string::npos) << json;
}

// computeExtrusionCheckMeshExtremes: the closed forms of a one-layer extrusion against
// OpenFOAM's decompositions (computeCheckMeshExtremes after updateMeshGeometry).

// Both ways for `mesh` at `points`; the extrusion's result must exist.
void expectExtrusionExtremesLikeTheDecompositions(const PolyMesh& mesh, const std::vector<Vector3>& points,
                                                  const std::string& name)
{
    const rbm::PseudoTwoDMesh twoD = rbm::extractPseudoTwoD(mesh, rbm::buildMeshTopology(mesh));
    rbm::ExtrusionExtremesWorkspace workspace;
    const auto fast = rbm::computeExtrusionCheckMeshExtremes(mesh, twoD, points, workspace);
    ASSERT_TRUE(fast.has_value()) << name;
    rbm::MeshGeometry geometry;
    rbm::updateMeshGeometry(mesh, points, geometry);
    rbm::CheckMeshExtremesWorkspace extremesWorkspace;
    const rbm::CheckMeshExtremes expected = rbm::computeCheckMeshExtremes(mesh, points, geometry, extremesWorkspace);
    std::printf("%s: max non-orthogonality %.17g (decompositions %.17g), max skewness %.17g (%.17g)\n", name.c_str(),
                fast->maxNonOrthogonality, expected.maxNonOrthogonality, fast->maxSkewness, expected.maxSkewness);
    EXPECT_GT(expected.maxNonOrthogonality, 1.0) << name;  // not a trivial grid
    EXPECT_NEAR(fast->maxNonOrthogonality, expected.maxNonOrthogonality, 1e-12 * expected.maxNonOrthogonality) << name;
    EXPECT_NEAR(fast->maxSkewness, expected.maxSkewness, 1e-12 * expected.maxSkewness) << name;
}

// The 2D checkMesh fixtures and the boundary-layer airfoil (aspect ratio ~780), the latter also
// moved: every node turned about the trailing edge by an angle falling off with the distance,
// front and back alike (as rbm's 2D path moves them).
TEST(ExtrusionExtremes, AreTheDecompositionsFiguresToRounding)
{
    const std::filesystem::path data(RBM_TEST_DATA_DIR);
    // (quad2D: blockMesh's arcs round each plane on its own, so its twins differ in the last
    // bits and its back plane has five values of z: an extrusion to rounding.)
    for (const char* fixture : {"checkMesh/quad2D", "checkMesh/prism2D", "airfoilBoundaryLayer"}) {
        const PolyMesh mesh = rbm::io::readPolyMesh(data / fixture / "constant" / "polyMesh");
        expectExtrusionExtremesLikeTheDecompositions(mesh, mesh.points, fixture);
    }
    const PolyMesh airfoil = rbm::io::readPolyMesh(data / "airfoilBoundaryLayer" / "constant" / "polyMesh");
    std::vector<Vector3> moved = airfoil.points;
    for (Vector3& p : moved) {
        const double dx = p.x - 1.0, dy = p.y;
        const double angle = 0.07 * std::exp(-0.5 * (dx * dx + dy * dy));
        p.x = 1.0 + std::cos(angle) * dx - std::sin(angle) * dy;
        p.y = std::sin(angle) * dx + std::cos(angle) * dy;
        if (p.z > 0.0) p.z += 2e-17;  // as a turned body's rotation rounds it (0.1 + 2e-17)
    }
    expectExtrusionExtremesLikeTheDecompositions(airfoil, moved, "turned airfoil");
}

TEST(ExtrusionExtremes, LeaveNonExtrusionsAndInvertedCellsToTheDecompositions)
{
    const PolyMesh mesh = rbm::makeExtruded2D(3, 3, {0, 0, 0}, {3, 3, 1});
    const rbm::PseudoTwoDMesh twoD = rbm::extractPseudoTwoD(mesh, rbm::buildMeshTopology(mesh));
    rbm::ExtrusionExtremesWorkspace workspace;
    ASSERT_TRUE(rbm::computeExtrusionCheckMeshExtremes(mesh, twoD, mesh.points, workspace).has_value());
    // One back point moved in its plane without its front twin: no longer an extrusion.
    std::vector<Vector3> sheared = mesh.points;
    sheared[twoD.backPointOfNode[5]].x += 0.1;
    EXPECT_FALSE(rbm::computeExtrusionCheckMeshExtremes(mesh, twoD, sheared, workspace).has_value());
    // One point out of its plane.
    std::vector<Vector3> bent = mesh.points;
    bent[twoD.frontPointOfNode[5]].z += 0.01;
    EXPECT_FALSE(rbm::computeExtrusionCheckMeshExtremes(mesh, twoD, bent, workspace).has_value());
    // Node (1, 1) pushed to x = 4 on both planes folds two cells (StepQuality.Folded...).
    std::vector<Vector3> folded = mesh.points;
    for (Vector3& p : folded)
        if (p.x == 1.0 && p.y == 1.0) p.x = 4.0;
    EXPECT_FALSE(rbm::computeExtrusionCheckMeshExtremes(mesh, twoD, folded, workspace).has_value());
}

} // namespace
