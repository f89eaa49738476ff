// Tests of the thesis' quality measures (src/ThesisQuality): shape quality of triangles and
// quadrilaterals, minimum angles, their extremes.

#include "CheckMeshQuality.hpp"
#include "InvertedCell.hpp"
#include "MeshGenerators.hpp"
#include "MeshGeometry.hpp"
#include "PlanarMesh.hpp"
#include "PolyMeshReader.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "QualityReport.hpp"
#include "TestCases.hpp"
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

using namespace rbm::test::qualityCases;

namespace {

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

TEST(ThesisQuality, AConcaveQuadrilateralWhoseCentroidLeftItIsInvertedThoughItsAreaIsPositive)
{
    // The chevron (0,0) (2,1) (0,2) (1.5,1), counter-clockwise: area 2 - 1.5 = 0.5 (fans about
    // (0,0): +2 and -1.5), centroid ((2·2/3 - 1.5·0.5) / 0.5, 1) = (7/6, 1), left of its reflex
    // node (1.5, 1): the triangles over the edges into and out of it have twice the signed
    // area (1.5, -1) × (7/6, -1) = -1/3 and (-1.5, -1) × (-1/3, 0) = -1/3 (OpenFOAM's checkMesh:
    // "Error in face pyramids" on the extruded cell).
    const std::vector<Vector3> chevron = {{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {1.5, 1, 0}};
    const std::vector<Label> polygon = {0, 1, 2, 3};
    double area = 0.0;
    const Vector3 centroid = rbm::polygonCentroid(polygon, chevron, area);
    EXPECT_NEAR(area, 0.5, 1e-15);
    EXPECT_NEAR(centroid.x, 7.0 / 6.0, 1e-15);
    EXPECT_NEAR(centroid.y, 1.0, 1e-15);
    EXPECT_NEAR(rbm::smallestEdgeTriangle(polygon, chevron, centroid), -1.0 / 3.0, 1e-15);
    EXPECT_TRUE(rbm::isInvertedPolygon(area, rbm::smallestEdgeTriangle(polygon, chevron, centroid)));

    // The reflex node at (0.4, 1) instead: area 2 - 0.4 = 1.6, centroid ((4/3 - 0.4 · 0.4/3) / 1.6,
    // 1) = (0.8, 1), inside; edge triangles 1.2, 1.2, 0.4, 0.4: concave but valid.
    const std::vector<Vector3> shallow = {{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {0.4, 1, 0}};
    const Vector3 inside = rbm::polygonCentroid(polygon, shallow, area);
    EXPECT_NEAR(area, 1.6, 1e-15);
    EXPECT_NEAR(inside.x, 0.8, 1e-15);
    EXPECT_NEAR(rbm::smallestEdgeTriangle(polygon, shallow, inside), 0.4, 1e-15);
    EXPECT_FALSE(rbm::isInvertedPolygon(area, rbm::smallestEdgeTriangle(polygon, shallow, inside)));

    // The whole-mesh figures count it: the pair's second quad made a chevron the same way.
    auto m = shearedPlanarPair(0.0);
    std::vector<Vector3> moved = m.points;
    moved[5] = {1.15, 0.15, 0.0};   // (1,0) (2,0) (2,1)→(1.15,0.15) (1,1): reflex at (1.15, 0.15)
    rbm::ThesisQualityWorkspace workspace;
    EXPECT_GT(rbm::polygonSignedArea(std::vector<Label>{1, 4, 5, 2}, moved), 0.0);
    EXPECT_EQ(rbm::computeThesisQuality2D(m, moved, workspace).invertedCellCount, 1);
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

} // namespace
