// Tests of the quality report (src/QualityReport): the full report and the per-step figures
// (StepQuality) the time loop logs.

#include "CheckMeshQuality.hpp"
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
    // The topology goes too: a 3D step builds only the cells' faces again, the whole topology
    // comes back when asked for, the mesh's own.
    const rbm::MeshTopology built = rbm::buildMeshTopology(box);
    evaluator.releaseWorkspaces();
    const rbm::StepQuality after = evaluator.evaluateStep(moved);
    EXPECT_EQ(evaluator.cellFaceTopology().cellFaceOffsets, built.cellFaceOffsets);
    EXPECT_EQ(evaluator.cellFaceTopology().cellFaces, built.cellFaces);
    EXPECT_TRUE(evaluator.cellFaceTopology().cellPoints.empty());
    EXPECT_EQ(evaluator.topology().cellFaces, built.cellFaces);
    EXPECT_EQ(evaluator.topology().cellPoints, built.cellPoints);
    EXPECT_EQ(evaluator.topology().pointCells, built.pointCells);
    EXPECT_EQ(evaluator.topology().cellCount, 12);
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

} // namespace
