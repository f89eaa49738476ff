// Tests of the solidBodyMotion functions (boundaryMotion/SolidBodyMotion), against formulas and
// against OpenFOAM's own output.

#include "FoamDictionary.hpp"
#include "Function1.hpp"
#include "InputError.hpp"
#include "PointPatchDisplacement.hpp"
#include "PolyMeshReader.hpp"
#include "Rotation.hpp"
#include "SolidBodyMotion.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

using namespace rbm::test::boundaryMotionCases;

using namespace rbm;
using namespace rbm::motion;

namespace {

std::unique_ptr<SolidBodyMotion> readMotion(const std::string& text, const std::filesystem::path& caseDirectory = {})
{
    const io::Dictionary dict = parse(text);
    return SolidBodyMotion::New(dict, caseDirectory);
}

} // namespace

TEST(SolidBodyMotion, RotatingMotionQuarterTurnAboutZ)
{
    auto m = readMotion("solidBodyMotionFunction rotatingMotion;"
                    "rotatingMotionCoeffs { origin (0 0 0); axis (0 0 1); omega 1.5707963267948966; }");
    EXPECT_EQ(m->type(), "rotatingMotion");
    expectNear(m->transformPoint(1.0, {1, 0, 0}), {0, 1, 0});
    expectNear(m->transformPoint(2.0, {1, 0, 0}), {-1, 0, 0});
    expectNear(m->transformPoint(0.0, {1, 2, 3}), {1, 2, 3});
}

TEST(SolidBodyMotion, RotatingMotionAboutAnOffsetOriginWithUnnormalisedAxisAndIntegratedOmega)
{
    // Coefficients directly in the dictionary; axis of length 5; omega = 2t so angle = t².
    auto m = readMotion("solidBodyMotionFunction rotatingMotion; origin (1 0 0); axis (0 0 5);"
                    "omega polynomial ((2 1));");
    const double t = std::sqrt(pi / 2);   // angle 90°
    expectNear(m->transformPoint(t, {2, 0, 0}), {1, 1, 0});
    expectNear(m->transformPoint(t, {1, 0, 7}), {1, 0, 7});   // on the axis
}

TEST(SolidBodyMotion, LinearAndOscillatingLinearMotion)
{
    auto linear = readMotion("solidBodyMotionFunction linearMotion; linearMotionCoeffs { velocity (1 2 3); }");
    expectNear(linear->transformPoint(2.0, {1, 1, 1}), {3, 5, 7});
    auto oscillating =
        readMotion("solidBodyMotionFunction oscillatingLinearMotion; amplitude (1 0 -2); omega 2;");
    expectNear(oscillating->transformPoint(pi / 4, {0, 0, 0}), {1, 0, -2});   // sin(π/2) = 1
    expectNear(oscillating->transformPoint(pi / 12, {0, 0, 0}), {0.5, 0, -1});   // sin(π/6)
}

TEST(SolidBodyMotion, OscillatingRotatingMotionTurnsAboutEachAxisInDegrees)
{
    // amplitude 90° and t = π/2, omega 1: sin = 1, a quarter turn.
    const double t = pi / 2;
    auto aboutX = readMotion("solidBodyMotionFunction oscillatingRotatingMotion; origin (0 0 0); amplitude (90 0 0); omega 1;");
    expectNear(aboutX->transformPoint(t, {0, 1, 0}), {0, 0, 1});
    auto aboutY = readMotion("solidBodyMotionFunction oscillatingRotatingMotion; origin (0 0 0); amplitude (0 90 0); omega 1;");
    expectNear(aboutY->transformPoint(t, {0, 0, 1}), {1, 0, 0});
    auto aboutZ = readMotion("solidBodyMotionFunction oscillatingRotatingMotion; origin (1 1 0); amplitude (0 0 90); omega 1;");
    expectNear(aboutZ->transformPoint(t, {2, 1, 0}), {1, 2, 0});
    // 30° at sin(π/6): amplitude 60, t = π/6.
    auto partial = readMotion("solidBodyMotionFunction oscillatingRotatingMotion; origin (0 0 0); amplitude (0 0 60); omega 1;");
    expectNear(partial->transformPoint(pi / 6, {1, 0, 0}), {std::cos(pi / 6), 0.5, 0});
}

TEST(SolidBodyMotion, OscillatingRotatingMotionAppliesTheZTurnFirst)
{
    // Rx(90°) Rz(90°) (1,0,0): Rz gives (0,1,0), Rx gives (0,0,1). (x first would give (0,1,0).)
    auto m = readMotion("solidBodyMotionFunction oscillatingRotatingMotion; origin (0 0 0); amplitude (90 0 90); omega 1;");
    expectNear(m->transformPoint(pi / 2, {1, 0, 0}), {0, 0, 1});
}

TEST(SolidBodyMotion, MultiMotionAppliesTheLastListedMotionFirst)
{
    const std::string rotation =
        "rotation { solidBodyMotionFunction rotatingMotion; origin (0 0 0); axis (0 0 1); omega 1.5707963267948966; }";
    const std::string translation = "translation { solidBodyMotionFunction linearMotion; velocity (1 0 0); }";
    // [rotation, translation]: translate (0,0,0) to (1,0,0), then turn to (0,1,0).
    auto rotationThenTranslationListed =
        readMotion("solidBodyMotionFunction multiMotion; multiMotionCoeffs {" + rotation + translation + "}");
    expectNear(rotationThenTranslationListed->transformPoint(1.0, {0, 0, 0}), {0, 1, 0});
    expectNear(rotationThenTranslationListed->transformPoint(1.0, {1, 0, 0}), {0, 2, 0});
    // [translation, rotation]: turn (0,0,0) (stays), then translate to (1,0,0).
    auto translationThenRotationListed =
        readMotion("solidBodyMotionFunction multiMotion; multiMotionCoeffs {" + translation + rotation + "}");
    expectNear(translationThenRotationListed->transformPoint(1.0, {0, 0, 0}), {1, 0, 0});
    expectNear(translationThenRotationListed->transformPoint(1.0, {1, 0, 0}), {1, 1, 0});
}

TEST(SolidBodyMotion, RigidMotionPreservesDistances)
{
    auto m = readMotion(R"(
        solidBodyMotionFunction multiMotion;
        multiMotionCoeffs
        {
            a { solidBodyMotionFunction oscillatingRotatingMotion; origin (0.3 0.1 0); amplitude (20 -35 50); omega 1.3; }
            b { solidBodyMotionFunction rotatingMotion; origin (1 2 3); axis (1 -1 2); omega table ((0 0.5) (2 1.5)); }
            c { solidBodyMotionFunction linearMotion; velocity (0.4 -0.2 1); }
        })");
    const std::vector<Vector3> points0{{0, 0, 0}, {1, 0, 0}, {0.3, 2, -1}, {5, -4, 2}, {-1, 0.5, 0.25}};
    std::vector<Vector3> points(points0.size());
    for (double t : {0.3, 1.1, 2.7}) {
        m->transformPoints(t, points0, points);
        for (std::size_t i = 0; i < points0.size(); ++i)
            for (std::size_t j = i + 1; j < points0.size(); ++j)
                EXPECT_NEAR(norm(points[i] - points[j]), norm(points0[i] - points0[j]), 1e-12);
        // Orientation kept: the triple product of three edges.
        const double before = dot(cross(points0[1] - points0[0], points0[2] - points0[0]), points0[3] - points0[0]);
        const double after = dot(cross(points[1] - points[0], points[2] - points[0]), points[3] - points[0]);
        EXPECT_NEAR(after, before, 1e-11);
    }
}

TEST(SolidBodyMotion, Tabulated6DoFMotionOnALinearTable)
{
    // Rows linear in time: translation (t, 2t, 0), rotation (0, 0, 90t)°; CofG (1 0 0).
    auto m = readMotion("solidBodyMotionFunction tabulated6DoFMotion;"
                    "tabulated6DoFMotionCoeffs { CofG (1 0 0); timeDataFileName \"linear6DoF.dat\"; }",
                    dataPath("function1"));
    // t = 1: 90° about z through CofG, then shift (1,2,0): (2,0,0) -> (1,1,0) -> (2,3,0).
    expectNear(m->transformPoint(1.0, {2, 0, 0}), {2, 3, 0});
    // t = 0.5: 45°, shift (0.5,1,0): (2,0,0) -> (1+cos45°, sin45°, 0) + (0.5,1,0).
    expectNear(m->transformPoint(0.5, {2, 0, 0}), {1.5 + std::sqrt(0.5), 1 + std::sqrt(0.5), 0});
    // t = 1.5 (Catmull-Rom between rows 1 and 2 of a linear table is linear): 135°.
    expectNear(m->transformPoint(1.5, {2, 0, 0}), {1 + std::cos(0.75 * pi) + 1.5, std::sin(0.75 * pi) + 3, 0});
    const std::string message = inputErrorOf([&] { m->transformation(2.5); });
    EXPECT_TRUE(contains(message, "outside")) << message;
}

TEST(SolidBodyMotion, UnknownTypeAndMissingCoefficientAreNamed)
{
    try {
        readMotion("solidBodyMotionFunction wobblingMotion;");
        FAIL() << "no error";
    } catch (const InputError& error) {
        const std::string message = error.what();
        EXPECT_EQ(error.line(), 1);
        EXPECT_TRUE(contains(message, "wobblingMotion")) << message;
        EXPECT_TRUE(contains(message, "linearMotion multiMotion oscillatingLinearMotion oscillatingRotatingMotion "
                                      "rotatingMotion tabulated6DoFMotion"))
            << message;
    }
    const std::string missing =
        inputErrorOf([] { readMotion("solidBodyMotionFunction rotatingMotion; rotatingMotionCoeffs { origin (0 0 0); omega 1; }"); });
    EXPECT_TRUE(contains(missing, "axis")) << missing;
    const std::string emptyMulti = inputErrorOf([] { readMotion("solidBodyMotionFunction multiMotion; multiMotionCoeffs { }"); });
    EXPECT_TRUE(contains(emptyMulti, "multiMotion")) << emptyMulti;
}

// Each case was moved by OpenFOAM v1912's moveDynamicMesh with the solidBody motion solver.
class SolidBodyMotionAgainstOpenFoam : public ::testing::TestWithParam<std::string> {};

TEST_P(SolidBodyMotionAgainstOpenFoam, MovesPointsAsOpenFoamDoes)
{
    const std::filesystem::path caseDirectory = dataPath(GetParam());
    const io::Dictionary dynamicMeshDict = io::Dictionary::readFile(caseDirectory / "constant" / "dynamicMeshDict");
    auto m = SolidBodyMotion::New(dynamicMeshDict.subDictionary("solidBodyCoeffs"), caseDirectory);
    const std::vector<Vector3> points0 = io::readPolyMeshPoints(caseDirectory / "constant" / "polyMesh");
    ASSERT_EQ(points0.size(), 27u);
    std::vector<Vector3> points(points0.size());
    for (const char* time : {"0.25", "0.5", "0.75", "1"}) {
        const std::vector<Vector3> expected = io::readPolyMeshPoints(caseDirectory / time / "polyMesh");
        ASSERT_EQ(expected.size(), points0.size());
        m->transformPoints(std::stod(time), points0, points);
        for (std::size_t i = 0; i < points.size(); ++i) {
            SCOPED_TRACE("time " + std::string(time) + " point " + std::to_string(i));
            expectNear(points[i], expected[i], 1e-13);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(OpenFoamCases, SolidBodyMotionAgainstOpenFoam,
                         ::testing::Values("multiRotationTranslation", "multiTranslationRotation", "oscillatingRotation",
                                           "rotationPolynomialOmega", "rotationTableOmega", "tabulated6DoF"));
