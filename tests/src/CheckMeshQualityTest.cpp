// Agreement of rbm's checkMesh measures with OpenFOAM v1912's own checkMesh output on the
// meshes under tests/data/checkMesh (written, with their logs, by
// tests/data/makeCheckMeshFixtures.sh: blockMesh, gmsh + gmshToFoam, polyDualMesh).
//
// The fixtures' controlDict sets writePrecision 17, which also sets the precision of
// checkMesh's printed numbers: the logs carry full double precision. Measured: every
// figure equals checkMesh's to all 17 printed digits (the same operations in the same
// order); the tests allow 1e-12 relative so that a compiler contracting a*b+c into one
// fused multiply-add cannot fail them.

#include "CellShape.hpp"
#include "CheckMeshQuality.hpp"
#include "MeshGenerators.hpp"
#include "MeshGeometry.hpp"
#include "MeshTopology.hpp"
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
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

using namespace rbm::test::qualityCases;

namespace {

namespace fs = std::filesystem;

const fs::path fixtureRoot = fs::path(RBM_TEST_DATA_DIR) / "checkMesh";

constexpr double relativeTolerance = 1e-12;

std::string readText(const fs::path& path)
{
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open " + path.string());
    std::stringstream buffer;
    buffer << in.rdbuf();
    return buffer.str();
}

// The numbers checkMesh prints, parsed out of one log.
class CheckMeshLog {
public:
    explicit CheckMeshLog(const fs::path& path) : path_(path), text_(readText(path)) {}

    // The capture groups of the first match of `pattern`, as numbers.
    std::optional<std::vector<double>> numbers(const std::string& pattern) const
    {
        std::smatch match;
        if (!std::regex_search(text_, match, std::regex(pattern))) return std::nullopt;
        std::vector<double> values;
        for (std::size_t i = 1; i < match.size(); ++i) values.push_back(std::stod(match[i].str()));
        return values;
    }
    std::optional<double> number(const std::string& pattern) const
    {
        auto values = numbers(pattern);
        if (!values) return std::nullopt;
        return values->at(0);
    }
    bool contains(const std::string& text) const { return text_.find(text) != std::string::npos; }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
    std::string text_;
};

const std::string real = R"(([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?))";
const std::string vector3 = R"(\()" + real + " " + real + " " + real + R"(\))";

double relativeDifference(double actual, double expected)
{
    return std::abs(actual - expected) / std::max(std::abs(expected), 1e-300);
}

#define EXPECT_RELATIVE(actual, expected)                                                                     \
    EXPECT_LE(relativeDifference((actual), (expected)), relativeTolerance)                                    \
        << #actual << " = " << (actual) << ", checkMesh: " << (expected)

struct Fixture {
    std::string name;
    std::string time;    // "" for constant/polyMesh
};

std::ostream& operator<<(std::ostream& os, const Fixture& f) { return os << f.name << (f.time.empty() ? "" : "@" + f.time); }

class CheckMeshAgreement : public ::testing::TestWithParam<Fixture> {
protected:
    void SetUp() override
    {
        const Fixture& f = GetParam();
        const fs::path caseDir = fixtureRoot / f.name;
        mesh_ = rbm::io::readPolyMesh(caseDir / "constant" / "polyMesh");
        if (!f.time.empty()) mesh_.points = rbm::io::readPolyMeshPoints(caseDir / f.time / "polyMesh");
        geometry_ = rbm::computeMeshGeometry(mesh_);
        quality_ = rbm::computeCheckMeshQuality(mesh_, geometry_);
        const std::string suffix = f.time.empty() ? "" : "-" + f.time;
        plainLog_ = caseDir / ("checkMesh" + suffix + ".log");
        allLog_ = caseDir / ("checkMesh-all" + suffix + ".log");
    }

    rbm::PolyMesh mesh_;
    rbm::MeshGeometry geometry_;
    rbm::CheckMeshQuality quality_;
    fs::path plainLog_;
    fs::path allLog_;
};

TEST_P(CheckMeshAgreement, MeshStatsAndCellTypesMatch)
{
    const CheckMeshLog log(plainLog_);
    EXPECT_EQ(quality_.pointCount, log.number(R"(points:\s+(\d+))").value());
    EXPECT_EQ(quality_.faceCount, log.number(R"(\n\s+faces:\s+(\d+))").value());
    EXPECT_EQ(quality_.internalFaceCount, log.number(R"(internal faces:\s+(\d+))").value());
    EXPECT_EQ(quality_.cellCount, log.number(R"(cells:\s+(\d+))").value());

    const auto shapes = rbm::countCellShapes(mesh_, rbm::buildMeshTopology(mesh_));
    using rbm::CellShape;
    EXPECT_EQ(shapes[static_cast<int>(CellShape::Hexahedron)], log.number(R"(hexahedra:\s+(\d+))").value());
    EXPECT_EQ(shapes[static_cast<int>(CellShape::Prism)], log.number(R"(prisms:\s+(\d+))").value());
    EXPECT_EQ(shapes[static_cast<int>(CellShape::Pyramid)], log.number(R"(pyramids:\s+(\d+))").value());
    EXPECT_EQ(shapes[static_cast<int>(CellShape::Tetrahedron)], log.number(R"(tetrahedra:\s+(\d+))").value());
    // checkMesh's "wedges" and "tet wedges" are polyhedra for rbm; the fixtures have none.
    EXPECT_EQ(log.number(R"(\n\s+wedges:\s+(\d+))").value() + log.number(R"(tet wedges:\s+(\d+))").value(), 0.0);
    EXPECT_EQ(shapes[static_cast<int>(CellShape::Polyhedron)], log.number(R"(polyhedra:\s+(\d+))").value());
}

TEST_P(CheckMeshAgreement, BoundingBoxAndDirectionsMatch)
{
    const CheckMeshLog log(plainLog_);
    const auto box = log.numbers("Overall domain bounding box " + vector3 + " " + vector3).value();
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(quality_.boundingBoxMin[i], box[i]);
        EXPECT_EQ(quality_.boundingBoxMax[i], box[3 + i]);
    }
    const auto geometric = log.numbers(R"(geometric \(non-empty/wedge\) directions \((\d) (\d) (\d)\))").value();
    const auto solution = log.numbers(R"(solution \(non-empty\) directions \((\d) (\d) (\d)\))").value();
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(quality_.geometricDirections[i], geometric[i]);
        EXPECT_EQ(quality_.solutionDirections[i], solution[i]);
    }
}

TEST_P(CheckMeshAgreement, ClosednessAndAspectRatioMatch)
{
    const CheckMeshLog log(plainLog_);
    // Openness is round-off (1e-16): only its order of magnitude can agree.
    const auto openness = log.numbers("Boundary openness " + vector3).value();
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(quality_.boundaryOpenness[i], openness[i], 1e-14);
    // checkMesh prints the cell openness only when neither open nor high-aspect cells exist.
    if (const auto cellOpenness = log.number("Max cell openness = " + real)) {
        EXPECT_NEAR(quality_.maxCellOpenness, *cellOpenness, 1e-14);
    } else {
        EXPECT_LE(quality_.maxCellOpenness, rbm::CheckMeshQuality::closedThreshold);
    }

    const auto aspect = log.number("Max aspect ratio = " + real);
    const auto highAspect = log.numbers("High aspect ratio cells found, Max aspect ratio: " + real +
                                        R"(, number of cells (\d+))");
    ASSERT_TRUE(aspect || highAspect) << log.path();
    if (aspect) {
        EXPECT_RELATIVE(quality_.maxAspectRatio, *aspect);
        EXPECT_EQ(quality_.highAspectRatioCellCount, 0);
    } else {
        EXPECT_RELATIVE(quality_.maxAspectRatio, highAspect->at(0));
        EXPECT_EQ(quality_.highAspectRatioCellCount, highAspect->at(1));
    }
}

TEST_P(CheckMeshAgreement, FaceAreasAndCellVolumesMatch)
{
    const CheckMeshLog log(plainLog_);
    const auto areas = log.numbers("Minimum face area = " + real + R"(\. Maximum face area = )" + real).value();
    EXPECT_RELATIVE(quality_.minFaceArea, areas[0]);
    EXPECT_RELATIVE(quality_.maxFaceArea, areas[1]);

    const auto volumes =
        log.numbers("Min volume = " + real + R"(\. Max volume = )" + real + R"(\.  Total volume = )" + real);
    const auto negative = log.numbers("Minimum negative volume: " + real + R"(, Number of negative volume cells: (\d+))");
    ASSERT_TRUE(volumes || negative) << log.path();
    if (volumes) {
        EXPECT_RELATIVE(quality_.minCellVolume, volumes->at(0));
        EXPECT_RELATIVE(quality_.maxCellVolume, volumes->at(1));
        EXPECT_RELATIVE(quality_.totalVolume, volumes->at(2));
        EXPECT_EQ(quality_.nonPositiveVolumeCellCount, 0);
    } else {
        EXPECT_RELATIVE(quality_.minCellVolume, negative->at(0));
        EXPECT_EQ(quality_.nonPositiveVolumeCellCount, negative->at(1));
    }
}

TEST_P(CheckMeshAgreement, NonOrthogonalityMatches)
{
    const CheckMeshLog log(plainLog_);
    const auto angles = log.numbers("Mesh non-orthogonality Max: " + real + " average: " + real).value();
    EXPECT_RELATIVE(quality_.maxNonOrthogonality, angles[0]);
    EXPECT_RELATIVE(quality_.averageNonOrthogonality, angles[1]);
    EXPECT_EQ(quality_.severelyNonOrthogonalFaceCount,
              log.number(R"(Number of severely non-orthogonal \(> 70 degrees\) faces: (\d+))").value_or(0));
    EXPECT_EQ(quality_.nonOrthogonalityErrorCount, log.number(R"(Number of non-orthogonality errors: (\d+))").value_or(0));

    // The thesis' 3D non-orthogonality is the same angle per internal face.
    const auto thesis = rbm::computeThesisQuality3D(mesh_, geometry_);
    EXPECT_RELATIVE(thesis.nonOrthogonality.max, angles[0]);
    EXPECT_EQ(thesis.nonOrthogonality.count, quality_.internalFaceCount);
}

TEST_P(CheckMeshAgreement, FacePyramidsAndSkewnessMatch)
{
    const CheckMeshLog log(plainLog_);
    const auto pyramids = log.number(R"(Error in face pyramids: (\d+) faces are incorrectly oriented)");
    EXPECT_EQ(pyramids.has_value(), !log.contains("Face pyramids OK."));
    EXPECT_EQ(quality_.incorrectlyOrientedPyramidCount, pyramids.value_or(0));

    const auto skew = log.number("Max skewness = " + real);
    ASSERT_TRUE(skew) << log.path();
    EXPECT_RELATIVE(quality_.maxSkewness, *skew);
    EXPECT_EQ(quality_.severelySkewFaceCount, log.number(R"(, (\d+) highly skew faces detected)").value_or(0));
}

TEST_P(CheckMeshAgreement, AllGeometryWeightsAndVolumeRatiosMatch)
{
    const CheckMeshLog log(allLog_);
    const auto weights = log.numbers("Face interpolation weight : minimum: " + real + " average: " + real).value();
    EXPECT_RELATIVE(quality_.minFaceWeight, weights[0]);
    EXPECT_RELATIVE(quality_.averageFaceWeight, weights[1]);
    EXPECT_EQ(quality_.lowWeightFaceCount,
              log.number(R"(Faces with small interpolation weight \(< [0-9.e-]+\) found, number of faces: (\d+))")
                  .value_or(0));
    const auto ratios = log.numbers("Face volume ratio : minimum: " + real + " average: " + real).value();
    EXPECT_RELATIVE(quality_.minVolumeRatio, ratios[0]);
    EXPECT_RELATIVE(quality_.averageVolumeRatio, ratios[1]);
    EXPECT_EQ(quality_.lowVolumeRatioFaceCount,
              log.number(R"(Faces with small volume ratio \(< [0-9.e-]+\) found, number of faces: (\d+))").value_or(0));
}

TEST_P(CheckMeshAgreement, FailedCheckCountMatchesPlainCheckMesh)
{
    // Plain checkMesh on a 2D case also checks edge alignment, which rbm does not; every
    // fixture passes that check, so the counts agree.
    const CheckMeshLog log(plainLog_);
    const auto failed = log.number(R"(Failed (\d+) mesh checks)");
    EXPECT_EQ(failed.has_value(), !log.contains("\nMesh OK."));
    EXPECT_EQ(quality_.failedCheckCount(), failed.value_or(0));
}

TEST_P(CheckMeshAgreement, QualityReportCarriesTheSameFigures)
{
    const rbm::QualityReport report = rbm::computeQualityReport(mesh_);
    EXPECT_EQ(report.cellCount, quality_.cellCount);
    EXPECT_EQ(report.checkMesh.maxNonOrthogonality, quality_.maxNonOrthogonality);
    EXPECT_EQ(report.checkMesh.maxSkewness, quality_.maxSkewness);
    // Valid unless checkMesh reports one of its errors (its warnings about aspect ratio and
    // skewness do not count).
    const CheckMeshLog log(plainLog_);
    bool checkMeshError = false;
    for (const char* error : {"***Zero or negative cell volume", "***Error in face pyramids", "***Open cells",
                              "***Number of non-orthogonality errors", "***Zero or negative face area"}) {
        checkMeshError = checkMeshError || log.contains(error);
    }
    EXPECT_EQ(report.isValid(), !checkMeshError);
}

TEST_P(CheckMeshAgreement, StepFiguresAreCheckMeshsAndTheFullReports)
{
    // QualityEvaluator::evaluateStep (what rbmMoveMesh's log line prints every step): the
    // maxima checkMesh printed, and each of its four figures the full report's, bit for bit
    // (a pseudo-2D mesh's checkMesh extremes: to rounding, QualityReport.hpp).
    const Fixture& f = GetParam();
    const rbm::PolyMesh initial = rbm::io::readPolyMesh(fixtureRoot / f.name / "constant" / "polyMesh");
    rbm::QualityEvaluator evaluator(initial);
    const rbm::StepQuality step = evaluator.evaluateStep(mesh_.points);
    const CheckMeshLog log(plainLog_);
    const auto angles = log.numbers("Mesh non-orthogonality Max: " + real + " average: " + real).value();
    EXPECT_RELATIVE(step.maxNonOrthogonality, angles[0]);
    EXPECT_RELATIVE(step.maxSkewness, log.number("Max skewness = " + real).value());
    EXPECT_EQ(step.invertedCellCount, log.number(R"(Number of negative volume cells: (\d+))").value_or(0));

    const rbm::QualityReport full = evaluator.evaluate(mesh_.points);
    if (full.thesis.dimension == 2) {
        // An extrusion's extremes come from the 2D closed forms (QualityReport.hpp): to rounding.
        EXPECT_RELATIVE(step.maxNonOrthogonality, full.checkMesh.maxNonOrthogonality);
        EXPECT_RELATIVE(step.maxSkewness, full.checkMesh.maxSkewness);
    } else {
        EXPECT_EQ(step.maxNonOrthogonality, full.checkMesh.maxNonOrthogonality);
        EXPECT_EQ(step.maxSkewness, full.checkMesh.maxSkewness);
    }
    EXPECT_EQ(step.invertedCellCount, full.invertedCellCount());
    if (full.thesis.dimension == 2) {
        double worst = std::numeric_limits<double>::infinity();
        if (full.thesis.triangleMeanRatio.count > 0) worst = std::min(worst, full.thesis.triangleMeanRatio.min);
        if (full.thesis.quadrilateralShape.count > 0) worst = std::min(worst, full.thesis.quadrilateralShape.min);
        EXPECT_EQ(step.worstCellQuality, worst);
    } else {
        // The smallest face pyramid (apex at the cell centre) over the mean one, cell by cell.
        const rbm::MeshTopology topology = rbm::buildMeshTopology(initial);
        const rbm::MeshGeometry& geometry = evaluator.geometry();
        double worst = std::numeric_limits<double>::infinity();
        for (Label c = 0; c < topology.cellCount; ++c) {
            double smallest = std::numeric_limits<double>::infinity();
            for (const Label face : topology.facesOf(c)) {
                const rbm::Vector3 area = initial.owner[face] == c ? geometry.faceAreas[face] : -geometry.faceAreas[face];
                smallest = std::min(smallest, rbm::dot(area, geometry.faceCentres[face] - geometry.cellCentres[c]) / 3.0);
            }
            worst = std::min(worst, static_cast<double>(topology.facesOf(c).size()) * smallest /
                                        std::abs(geometry.cellVolumes[c]));
        }
        EXPECT_EQ(step.worstCellQuality, worst);
    }
}

INSTANTIATE_TEST_SUITE_P(Fixtures, CheckMeshAgreement,
                         ::testing::Values(Fixture{"skewedHex", ""}, Fixture{"stretchedSkewed", ""}, Fixture{"quad2D", ""},
                                           Fixture{"prism2D", ""},
                                           Fixture{"tet", ""}, Fixture{"polyDual", ""},
                                           Fixture{"quad2DMoved", "0.5"}),
                         [](const ::testing::TestParamInfo<Fixture>& info) {
                             std::string name = info.param.name;
                             if (!info.param.time.empty()) name += "AtTime" + info.param.time;
                             for (char& c : name) {
                                 if (c == '.') c = 'p';
                             }
                             return name;
                         });

} // namespace

namespace {

// On a clean one-layer extrusion the 2D centroids are the 3D cell centres and the edge
// normals the side-face normals: the thesis' 2D non-orthogonality of every internal edge is
// checkMesh's angle of the matching internal face.
class TwoDimensionalAgreement : public ::testing::TestWithParam<std::string> {};

TEST_P(TwoDimensionalAgreement, PlanarNonOrthogonalityEqualsCheckMeshs)
{
    const fs::path caseDir = fixtureRoot / GetParam();
    const rbm::PolyMesh mesh = rbm::io::readPolyMesh(caseDir / "constant" / "polyMesh");
    const rbm::QualityReport report = rbm::computeQualityReport(mesh);
    ASSERT_EQ(report.thesis.dimension, 2) << report.twoDExtractionProblem;
    const CheckMeshLog log(caseDir / "checkMesh.log");
    const auto angles = log.numbers("Mesh non-orthogonality Max: " + real + " average: " + real).value();
    EXPECT_EQ(report.thesis.nonOrthogonality.count, mesh.internalFaceCount());
    EXPECT_NEAR(report.thesis.nonOrthogonality.max, angles[0], 1e-9);
    EXPECT_EQ(report.thesis.invertedCellCount, 0);
    // Shape metrics in (0, 1] on a valid mesh; every cell has one.
    EXPECT_EQ(report.thesis.triangleMeanRatio.count + report.thesis.quadrilateralShape.count, report.cellCount);
    for (const auto* s : {&report.thesis.triangleMeanRatio, &report.thesis.quadrilateralShape}) {
        if (s->count == 0) continue;
        EXPECT_GT(s->min, 0.0);
        EXPECT_LE(s->max, 1.0 + 1e-12);
    }
}

INSTANTIATE_TEST_SUITE_P(Fixtures, TwoDimensionalAgreement, ::testing::Values("quad2D", "prism2D"));

TEST(TwoDimensionalAgreement, FoldedCellsOfAMovedTwoDimensionalMeshAreInvertedPlanarCells)
{
    // The extraction is made on the valid initial mesh; the moved points are measured
    // through it, so the two cells checkMesh finds with negative volume are the two
    // inverted 2D cells.
    const fs::path caseDir = fixtureRoot / "quad2DMoved";
    const rbm::PolyMesh mesh = rbm::io::readPolyMesh(caseDir / "constant" / "polyMesh");
    const auto moved = rbm::io::readPolyMeshPoints(caseDir / "0.5" / "polyMesh");
    rbm::QualityEvaluator evaluator(mesh);
    ASSERT_TRUE(evaluator.isTwoD());
    const rbm::QualityReport report = evaluator.evaluate(moved);
    EXPECT_EQ(report.thesis.dimension, 2);
    const CheckMeshLog log(caseDir / "checkMesh-0.5.log");
    EXPECT_EQ(report.thesis.invertedCellCount, log.number(R"(Number of negative volume cells: (\d+))").value());
    EXPECT_FALSE(report.isValid());
    // Evaluating the initial points again gives the valid mesh back.
    EXPECT_TRUE(evaluator.evaluate(mesh.points).isValid());
}

TEST(TwoDimensionalAgreement, AChevronWhoseCentroidLeftItIsInvertedWhereCheckMeshFindsItsPyramidsTurned)
{
    // Time 0.25 of the fixture: one cell made a chevron (makeCheckMeshFixtures.sh). checkMesh
    // finds no negative volume but 2 face pyramids incorrectly oriented (the side faces into and
    // out of its reflex corner); rbm counts that cell as one inverted planar cell, where the
    // area alone would pass it.
    const fs::path caseDir = fixtureRoot / "quad2DMoved";
    const rbm::PolyMesh mesh = rbm::io::readPolyMesh(caseDir / "constant" / "polyMesh");
    const auto moved = rbm::io::readPolyMeshPoints(caseDir / "0.25" / "polyMesh");
    rbm::QualityEvaluator evaluator(mesh);
    const rbm::QualityReport report = evaluator.evaluate(moved);
    const CheckMeshLog log(caseDir / "checkMesh-0.25.log");
    EXPECT_FALSE(log.number(R"(Number of negative volume cells: (\d+))").has_value());
    const double wrongPyramids = log.number(R"(Error in face pyramids: (\d+) faces)").value();
    EXPECT_EQ(wrongPyramids, 2.0);
    EXPECT_EQ(report.checkMesh.incorrectlyOrientedPyramidCount, 2);
    EXPECT_GT(report.checkMesh.minCellVolume, 0.0);
    EXPECT_EQ(report.thesis.invertedCellCount, 1);
    EXPECT_FALSE(report.isValid());
}

} // namespace

namespace {

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
