// Tests of InvertedCellCounter: the solver's count of inverted cells and worst quality.
#include "InvertedCellCounter.hpp"

#include "MeshGenerators.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbm::motion {
namespace {

TEST(InvertedCellCounter, ACubeMeshIsValidWithQualityOneAndAPointPushedThroughItsCellInvertsIt)
{
    // 2 × 2 × 2 unit cubes: every face pyramid is 1/6 of its cube, so the smallest pyramid
    // over the mean V/6 is 1.
    const PolyMesh mesh = makeHexBox(2, 2, 2, {0, 0, 0}, {2, 2, 2});
    InvertedCellCounter counter(mesh, mesh.points, nullptr);
    std::vector<Vector3> displacement(mesh.points.size());
    double worst = 0.0;
    EXPECT_EQ(counter.count(displacement, &worst), 0);
    EXPECT_NEAR(worst, 1.0, 1e-12);

    // The corner point (0, 0, 0) (label 0, only in cell 0) moved to (1.5, 1.5, 1.5): through
    // the opposite faces of its cube, which turns over.
    displacement[0] = {1.5, 1.5, 1.5};
    std::vector<Label> cells;
    EXPECT_EQ(counter.count(displacement, &worst, &cells), 1);
    EXPECT_EQ(cells, std::vector<Label>{0});
    EXPECT_LT(worst, 0.0);
}

TEST(InvertedCellCounter, APlanarCellWhoseCentroidLeftItCountsAsInvertedThoughItsAreaIsPositive)
{
    // 2 × 2 unit squares; the centre node (1, 1) moved to (0.15, 0.15). The square [0,1]² becomes
    // the chevron (0,0) (1,0) (0.15,0.15) (0,1): area 0.15 (fans +0.075 +0.075), centroid
    // (0.2167, 0.2167), beyond its reflex node, so the triangle over the edge (1,0)→(0.15,0.15)
    // has twice the signed area (-0.85, 0.15) × (-0.7833, 0.2167) = -0.0667 < 0 (OpenFOAM's
    // checkMesh: "Error in face pyramids"). The other three squares stay convex.
    const PolyMesh extruded = makeExtruded2D(2, 2, {0, 0, 0}, {2, 2, 1}, PlanarCellKind::Quadrilaterals);
    const PseudoTwoDMesh twoD = extractPseudoTwoD(extruded);
    InvertedCellCounter counter(extruded, extruded.points, &twoD);
    std::vector<Vector3> displacement(twoD.planar.points.size());
    std::vector<Vector3> moved(twoD.planar.points);
    Label centre = -1;
    for (Label node = 0; node < twoD.planar.nodeCount(); ++node)
        if (std::abs(moved[node].x - 1) < 1e-12 && std::abs(moved[node].y - 1) < 1e-12) centre = node;
    ASSERT_GE(centre, 0);
    displacement[centre] = {-0.85, -0.85, 0.0};
    moved[centre] = moved[centre] + displacement[centre];
    for (Label c = 0; c < twoD.planar.cellCount(); ++c) EXPECT_GT(twoD.planar.signedArea(c, moved), 0.0);
    std::vector<Label> cells;
    double worst = 1.0;
    EXPECT_EQ(counter.count(displacement, &worst, &cells), 1);
    ASSERT_EQ(cells.size(), 1u);
    // The inverted one is the cell whose nodes include (0, 0).
    bool hasOrigin = false;
    for (Label node : twoD.planar.cell(cells[0])) hasOrigin |= std::abs(moved[node].x) + std::abs(moved[node].y) < 1e-12;
    EXPECT_TRUE(hasOrigin);
    // The thesis' F_shape of the chevron stays positive (its corner Jacobians are): the count,
    // not the shape, is what tells the cell's face pyramids turned over.
    EXPECT_GT(worst, 0.0);
}

TEST(InvertedCellCounter, APlanarMeshIsCheckedOnItsPlaneAndTheSameBitsGiveTheSameFigures)
{
    const PolyMesh extruded = makeExtruded2D(2, 2, {0, 0, 0}, {2, 2, 1}, PlanarCellKind::Triangles);
    const PseudoTwoDMesh twoD = extractPseudoTwoD(extruded);
    InvertedCellCounter counter(extruded, extruded.points, &twoD);
    std::vector<Vector3> displacement(twoD.planar.points.size());
    double worst = 0.0;
    EXPECT_EQ(counter.count(displacement, &worst), 0);
    // Right isosceles triangles: the mean ratio 4√3 A / Σ|e|² = 4√3 · 0.5 / 4 = √3/2.
    EXPECT_NEAR(worst, std::sqrt(3.0) / 2.0, 1e-12);

    // The centre node (1, 1) moved to (2.5, 2.5): the triangles whose far side it crosses
    // turn over (8 triangles; those on the (0,0)-(2,2) diagonal keep their area sign unless
    // crossed). Count them from the signed areas directly.
    std::vector<Vector3> moved(twoD.planar.points);
    Label centre = -1;
    for (Label node = 0; node < twoD.planar.nodeCount(); ++node)
        if (std::abs(moved[node].x - 1) < 1e-12 && std::abs(moved[node].y - 1) < 1e-12) centre = node;
    ASSERT_GE(centre, 0);
    displacement[centre] = {1.5, 1.5, 0.0};
    moved[centre] = moved[centre] + displacement[centre];
    Label expected = 0;
    for (Label c = 0; c < twoD.planar.cellCount(); ++c) expected += twoD.planar.signedArea(c, moved) <= 0.0;
    ASSERT_GT(expected, 0);
    const Label first = counter.count(displacement, &worst);
    EXPECT_EQ(first, expected);
    // The remembered check: the same displacement gives the same count and quality.
    double again = 1.0;
    EXPECT_EQ(counter.count(displacement, &again), first);
    EXPECT_EQ(again, worst);
}

} // namespace
} // namespace rbm::motion
