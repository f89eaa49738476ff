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
