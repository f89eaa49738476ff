// Boundary-motion laws with OpenFOAM v1912 semantics: Function1 types, solid-body motions,
// point-patch displacement conditions, rotation helpers. Expected values are hand computed
// (comments show the arithmetic) or come from OpenFOAM v1912 itself: the cases under
// tests/data/boundaryMotion were moved by moveDynamicMesh (makeBoundaryMotionFixtures.sh).
// No PETSc here.

#include "FoamDictionary.hpp"
#include "Function1.hpp"
#include "InputError.hpp"
#include "PointPatchDisplacement.hpp"
#include "PolyMeshReader.hpp"
#include "Rotation.hpp"
#include "SolidBodyMotion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

using namespace rbm;
using namespace rbm::motion;

namespace {

constexpr double pi = std::numbers::pi;

std::filesystem::path dataPath(const std::string& relative)
{
    return std::filesystem::path(RBM_TEST_DATA_DIR) / "boundaryMotion" / relative;
}

io::Dictionary parse(const std::string& text) { return io::Dictionary::parseText(text, "test.dict"); }

std::unique_ptr<Function1<double>> scalarFunction(const std::string& text, const std::string& name = "f",
                                                 const std::filesystem::path& caseDirectory = {})
{
    const io::Dictionary dict = parse(text);
    return Function1<double>::New(name, dict, caseDirectory);
}

std::unique_ptr<Function1<Vector3>> vectorFunction(const std::string& text, const std::string& name = "f")
{
    const io::Dictionary dict = parse(text);
    return Function1<Vector3>::New(name, dict);
}

std::unique_ptr<SolidBodyMotion> readMotion(const std::string& text, const std::filesystem::path& caseDirectory = {})
{
    const io::Dictionary dict = parse(text);
    return SolidBodyMotion::New(dict, caseDirectory);
}

void expectNear(const Vector3& actual, const Vector3& expected, double tolerance = 1e-12)
{
    EXPECT_NEAR(actual.x, expected.x, tolerance) << "actual " << actual << " expected " << expected;
    EXPECT_NEAR(actual.y, expected.y, tolerance) << "actual " << actual << " expected " << expected;
    EXPECT_NEAR(actual.z, expected.z, tolerance) << "actual " << actual << " expected " << expected;
}

// Runs `action`, expects an rbm::InputError and returns its what().
template <class Action>
std::string inputErrorOf(Action action)
{
    try {
        action();
    } catch (const InputError& error) {
        return error.what();
    }
    ADD_FAILURE() << "no rbm::InputError thrown";
    return {};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

} // namespace

// ===========================================================================================
// Rotation helpers

TEST(Rotation, QuaternionFromAxisAngleMatchesRodriguesMatrix)
{
    const Vector3 axis{0.3, -1.2, 0.7};
    const double angle = 0.83;
    const Quaternion q = Quaternion::fromAxisAngle(axis, angle);
    const Matrix3 r = rotationMatrix(axis, angle);
    for (const Vector3& v : {Vector3{1, 0, 0}, Vector3{0.2, 0.5, -0.9}, Vector3{-3, 2, 1}}) {
        expectNear(q.transform(v), r * v);
        expectNear(q.matrix() * v, r * v);
        expectNear(q.invTransform(q.transform(v)), v);
    }
}

TEST(Rotation, PositiveAngleTurnsCounterClockwiseAboutTheAxis)
{
    // Right-hand rule: +90° about z takes x to y, about x takes y to z, about y takes z to x.
    expectNear(Quaternion::fromAxisAngle({0, 0, 1}, pi / 2).transform({1, 0, 0}), {0, 1, 0});
    expectNear(Quaternion::fromAxisAngle({1, 0, 0}, pi / 2).transform({0, 1, 0}), {0, 0, 1});
    expectNear(Quaternion::fromAxisAngle({0, 1, 0}, pi / 2).transform({0, 0, 1}), {1, 0, 0});
}

TEST(Rotation, EulerSequenceXyzIsRxTimesRyTimesRz)
{
    const Vector3 angles{0.4, -0.7, 1.1};
    const Matrix3 expected = rotationMatrix({1, 0, 0}, angles.x) * rotationMatrix({0, 1, 0}, angles.y) *
                             rotationMatrix({0, 0, 1}, angles.z);
    const Quaternion q = Quaternion::fromEulerAngles(RotationSequence::XYZ, angles);
    for (const Vector3& v : {Vector3{1, 0, 0}, Vector3{0, 1, 0}, Vector3{0.3, 0.2, -0.8}}) expectNear(q.transform(v), expected * v);
    // ZYX is the reverse product.
    const Matrix3 zyx = rotationMatrix({0, 0, 1}, angles.x) * rotationMatrix({0, 1, 0}, angles.y) *
                        rotationMatrix({1, 0, 0}, angles.z);
    expectNear(Quaternion::fromEulerAngles(RotationSequence::ZYX, angles).transform({0.3, 0.2, -0.8}),
               zyx * Vector3{0.3, 0.2, -0.8});
}

TEST(Rotation, SepternionProductAppliesTheRightFactorFirst)
{
    // A = shift by (1,0,0) (OpenFOAM septernion(-d) maps x to x + d); B = 90° about z.
    const Septernion shift(Vector3{-1, 0, 0});
    const Septernion turn(Quaternion::fromAxisAngle({0, 0, 1}, pi / 2));
    const Vector3 x{1, 0, 0};
    expectNear(shift.transformPoint(x), {2, 0, 0});
    // shift*turn: turn (1,0,0) -> (0,1,0), then shift -> (1,1,0).
    expectNear((shift * turn).transformPoint(x), {1, 1, 0});
    Septernion compound = shift;
    compound *= turn;
    expectNear(compound.transformPoint(x), {1, 1, 0});
    // turn*shift: shift -> (2,0,0), then turn -> (0,2,0).
    expectNear((turn * shift).transformPoint(x), {0, 2, 0});
    // x' = R x + d form and the inverse.
    const Septernion s = shift * turn;
    expectNear(s.rotationMatrix() * x + s.translation(), {1, 1, 0});
    expectNear(inverse(s).transformPoint({1, 1, 0}), x);
}

// ===========================================================================================
// Function1

TEST(Function1, PlainNumberIsAConstant)
{
    auto f = scalarFunction("omega 6.25;", "omega");
    EXPECT_EQ(f->type(), "constant");
    EXPECT_TRUE(f->isConstant());
    EXPECT_DOUBLE_EQ(f->value(0.0), 6.25);
    EXPECT_DOUBLE_EQ(f->value(17.0), 6.25);
    EXPECT_DOUBLE_EQ(f->integrate(1.0, 3.0), 12.5);    // 6.25 * 2
    EXPECT_DOUBLE_EQ(f->integrate(3.0, 1.0), -12.5);
}

TEST(Function1, ConstantKeywordVectorAndDictionaryForms)
{
    auto a = vectorFunction("f constant (1 2 3);");
    expectNear(a->value(5.0), {1, 2, 3});
    expectNear(a->integrate(0.0, 2.0), {2, 4, 6});
    auto b = vectorFunction("f (1 -2 0.5);");
    expectNear(b->value(0.3), {1, -2, 0.5});
    auto c = scalarFunction("f { type constant; value 4; }");
    EXPECT_DOUBLE_EQ(c->integrate(0.5, 1.0), 2.0);
    auto d = scalarFunction("f uniform 3;");
    EXPECT_DOUBLE_EQ(d->value(9.0), 3.0);
}

TEST(Function1, ZeroAndOne)
{
    auto zero = vectorFunction("f zero;");
    expectNear(zero->value(3.0), {0, 0, 0});
    expectNear(zero->integrate(0.0, 3.0), {0, 0, 0});
    auto one = vectorFunction("f one;");
    expectNear(one->value(3.0), {1, 1, 1});
    expectNear(one->integrate(1.0, 3.5), {2.5, 2.5, 2.5});
    auto oneScalar = scalarFunction("f { type one; }");
    EXPECT_DOUBLE_EQ(oneScalar->integrate(-1.0, 1.0), 2.0);
}

TEST(Function1, PolynomialValueAndIntegral)
{
    auto f = scalarFunction("omega polynomial ((1 0) (2 1));", "omega");   // 1 + 2t
    EXPECT_DOUBLE_EQ(f->value(0.0), 1.0);
    EXPECT_DOUBLE_EQ(f->value(3.0), 7.0);
    EXPECT_DOUBLE_EQ(f->integrate(0.0, 2.0), 6.0);   // t + t² at 2
    auto g = scalarFunction("f polynomial ((3 2) (-1 0.5));");   // 3t² − √t
    EXPECT_NEAR(g->value(4.0), 46.0, 1e-13);                      // 48 − 2
    EXPECT_NEAR(g->integrate(1.0, 4.0), 63.0 - 14.0 / 3.0, 1e-12); // [t³ − (2/3) t^1.5] from 1 to 4
}

TEST(Function1, VectorPolynomialIsComponentwise)
{
    // c = (1 2 3), e = (0 1 2): (1, 2t, 3t²)
    auto f = vectorFunction("f polynomial (((1 2 3) (0 1 2)));");
    expectNear(f->value(2.0), {1, 4, 12});
    expectNear(f->integrate(0.0, 1.0), {1, 1, 1});
}

TEST(Function1, PolynomialWithExponentMinusOneCannotBeIntegrated)
{
    auto f = scalarFunction("f polynomial ((2 -1));");
    EXPECT_DOUBLE_EQ(f->value(4.0), 0.5);
    const std::string message = inputErrorOf([&] { f->integrate(1.0, 2.0); });
    EXPECT_TRUE(contains(message, "'f'")) << message;
}

TEST(Function1, SineFromCoeffsSubDictionary)
{
    auto f = scalarFunction("f sine; fCoeffs { t0 0.1; amplitude 2; frequency 0.5; scale 3; level 1; }");
    // 2 sin(2π 0.5 (t − 0.1)) 3 + 1 = 6 sin(π (t − 0.1)) + 1
    EXPECT_NEAR(f->value(0.1), 1.0, 1e-14);
    EXPECT_NEAR(f->value(0.6), 7.0, 1e-14);
    EXPECT_NEAR(f->value(1.1), 1.0, 1e-14);
    EXPECT_NEAR(f->value(1.6), -5.0, 1e-14);
    // ∫_{0.1}^{1.1} = 6·2/π + 1
    EXPECT_NEAR(f->integrate(0.1, 1.1), 12.0 / pi + 1.0, 1e-13);
    // A full period integrates to the level only.
    EXPECT_NEAR(f->integrate(0.3, 2.3), 2.0, 1e-13);
}

TEST(Function1, SineCoefficientsInTheParentDictionaryAndVectorScale)
{
    auto f = vectorFunction("f sine; amplitude 1; frequency 1; scale (1 0 2); level (0 5 0);");
    // sin(2π t)(1 0 2) + (0 5 0)
    expectNear(f->value(0.25), {1, 5, 2});
    expectNear(f->value(0.75), {-1, 5, -2});
    // ∫_0^{1/2} sin(2πt) = 1/π
    expectNear(f->integrate(0.0, 0.5), {1.0 / pi, 2.5, 2.0 / pi}, 1e-13);
}

TEST(Function1, SineWithTimeVaryingAmplitudeIntegratesNumerically)
{
    // amplitude t: ∫_0^1 t sin(2πt) dt = −1/(2π)
    auto f = scalarFunction("f { type sine; amplitude polynomial ((1 1)); frequency 1; scale 1; level 0; }");
    EXPECT_NEAR(f->value(0.25), 0.25, 1e-14);
    EXPECT_NEAR(f->integrate(0.0, 1.0), -1.0 / (2.0 * pi), 1e-10);
}

TEST(Function1, SquareWaveWithMarkSpace)
{
    // markSpace 3: +1 for the first 3/4 of each wave, −1 for the last quarter.
    auto f = scalarFunction("f square; fCoeffs { frequency 1; amplitude 2; scale 1; level 0.5; markSpace 3; }");
    EXPECT_DOUBLE_EQ(f->value(0.5), 2.5);
    EXPECT_DOUBLE_EQ(f->value(0.8), -1.5);
    EXPECT_DOUBLE_EQ(f->value(1.2), 2.5);
    EXPECT_DOUBLE_EQ(f->value(-0.1), 2.5);   // before t0 the (negative) fraction is below the mark: +1
    // ∫_0^1 = 2 (0.75 − 0.25) + 0.5 = 1.5; ∫_0^2.9 = 2 (2·0.5 + 0.75 − 0.15) + 0.5·2.9
    EXPECT_NEAR(f->integrate(0.0, 1.0), 1.5, 1e-13);
    EXPECT_NEAR(f->integrate(0.0, 2.9), 2.0 * 1.6 + 1.45, 1e-13);
    auto g = scalarFunction("f square; frequency 2; amplitude 1; scale 1; level 0;");   // default markSpace 1
    EXPECT_DOUBLE_EQ(g->value(0.1), 1.0);    // 0.2 waves
    EXPECT_DOUBLE_EQ(g->value(0.3), -1.0);   // 0.6 waves
    EXPECT_NEAR(g->integrate(0.0, 0.4), 0.25 - 0.15, 1e-13);   // +1 for t < 0.25 (half a wave), then −1
}

TEST(Function1, TableInterpolatesLinearlyAndClampsByDefault)
{
    auto f = scalarFunction("f table ((0 0) (1 2) (3 4));");
    EXPECT_DOUBLE_EQ(f->value(0.5), 1.0);
    EXPECT_DOUBLE_EQ(f->value(2.0), 3.0);
    EXPECT_DOUBLE_EQ(f->value(-1.0), 0.0);
    EXPECT_DOUBLE_EQ(f->value(5.0), 4.0);
    EXPECT_DOUBLE_EQ(f->integrate(0.0, 3.0), 7.0);     // 1 + 6
    EXPECT_DOUBLE_EQ(f->integrate(0.5, 2.0), 0.75 + 2.5);
    EXPECT_DOUBLE_EQ(f->integrate(-1.0, 4.0), 11.0);   // 0 + 7 + 4 (clamped ends)
    auto counted = scalarFunction("f table 2((0 1) (2 3));");
    EXPECT_DOUBLE_EQ(counted->value(1.0), 2.0);
}

TEST(Function1, TableRepeatsPeriodically)
{
    auto f = scalarFunction("f table ((0 0) (1 1)); outOfBounds repeat;");
    EXPECT_DOUBLE_EQ(f->value(1.5), 0.5);
    EXPECT_DOUBLE_EQ(f->value(2.25), 0.25);
    EXPECT_DOUBLE_EQ(f->value(-0.25), 0.75);
    EXPECT_DOUBLE_EQ(f->integrate(0.0, 2.5), 1.125);   // 2 · 0.5 + 0.125
}

TEST(Function1, TableOutOfBoundsErrorAndOutOfOrderTimes)
{
    auto f = scalarFunction("f table ((0 0) (1 1)); fCoeffs { outOfBounds error; }");
    EXPECT_DOUBLE_EQ(f->value(0.5), 0.5);
    EXPECT_TRUE(contains(inputErrorOf([&] { f->value(2.0); }), "'f'"));
    EXPECT_TRUE(contains(inputErrorOf([&] { scalarFunction("f table ((0 0) (2 1) (1 3));"); }), "out-of-order"));
    EXPECT_TRUE(contains(inputErrorOf([&] { scalarFunction("f table ((0 0)); outOfBounds sometimes;"); }), "sometimes"));
}

TEST(Function1, VectorTable)
{
    auto f = vectorFunction("value table ((0 (0 0 0)) (1 (1 0 0)) (2 (1 2 0)));", "value");
    expectNear(f->value(0.25), {0.25, 0, 0});
    expectNear(f->value(1.5), {1, 1, 0});
    expectNear(f->integrate(0.0, 2.0), {1.5, 1, 0});
}

TEST(Function1, TableFileRelativeToTheCaseFolder)
{
    const std::filesystem::path caseDirectory = dataPath("function1");
    // omega(t) = 1 + t on [0, 2]
    auto a = scalarFunction("omega tableFile; omegaCoeffs { file \"$FOAM_CASE/omegaTable.dat\"; }", "omega", caseDirectory);
    EXPECT_DOUBLE_EQ(a->value(1.0), 2.0);
    EXPECT_DOUBLE_EQ(a->integrate(0.0, 2.0), 4.0);
    auto b = scalarFunction("omega { type tableFile; file \"omegaTable.dat\"; outOfBounds clamp; }", "omega", caseDirectory);
    EXPECT_DOUBLE_EQ(b->value(3.0), 3.0);
    const std::string message =
        inputErrorOf([&] { scalarFunction("omega tableFile; file \"missing.dat\";", "omega", caseDirectory); });
    EXPECT_TRUE(contains(message, "missing.dat")) << message;
}

TEST(Function1, UnknownTypeNamesFileLineEntryAndValidTypes)
{
    try {
        scalarFunction("a 1;\nomega cosine 5;\n", "omega");
        FAIL() << "no error";
    } catch (const InputError& error) {
        const std::string message = error.what();
        EXPECT_EQ(error.file(), "test.dict");
        EXPECT_EQ(error.line(), 2);
        EXPECT_TRUE(contains(message, "cosine")) << message;
        EXPECT_TRUE(contains(message, "omega")) << message;
        EXPECT_TRUE(contains(message, "Valid Function1 types are: constant one polynomial sine square table tableFile"))
            << message;
    }
}

TEST(Function1, MissingEntryOrCoefficientIsNamed)
{
    const std::string missingEntry = inputErrorOf([] { scalarFunction("other 1;", "omega"); });
    EXPECT_TRUE(contains(missingEntry, "omega")) << missingEntry;
    const std::string missingCoefficient =
        inputErrorOf([] { scalarFunction("f sine; fCoeffs { amplitude 1; scale 1; level 0; }"); });
    EXPECT_TRUE(contains(missingCoefficient, "frequency")) << missingCoefficient;
    const std::string noInlineData = inputErrorOf([] { scalarFunction("f table;"); });
    EXPECT_TRUE(contains(noInlineData, "'f'")) << noInlineData;
}

// ===========================================================================================
// Solid-body motions

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

// ===========================================================================================
// Point-patch displacement conditions

namespace {

// Two quadrilaterals of a patch "bottom" (normal −z), seen from above:
//   3---2---5        faces (0 3 2 1) and (1 2 5 4): first appearance gives 0 3 2 1 5 4
//   |   |   |
//   0---1---4
PolyMesh twoFacePatchMesh()
{
    PolyMesh mesh;
    mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
    mesh.addFace(std::vector<Label>{0, 3, 2, 1});
    mesh.addFace(std::vector<Label>{1, 2, 5, 4});
    mesh.owner = {0, 1};
    Patch patch;
    patch.name = "bottom";
    patch.type = "wall";
    patch.startFace = 0;
    patch.faceCount = 2;
    mesh.patches.push_back(patch);
    return mesh;
}

std::unique_ptr<PointPatchDisplacement> condition(const std::string& text, const PolyMesh& mesh, Label patchIndex,
                                                  const std::filesystem::path& caseDirectory = {})
{
    const io::Dictionary dict = parse(text);
    const PointPatchContext context = PointPatchContext::forPatch(mesh, patchIndex, {}, caseDirectory, {}, "test.dict");
    return builtinPointPatchDisplacements().create(dict, context);
}

PolyMesh cubeMesh() { return io::readPolyMesh(dataPath("pointPatchConditions/constant/polyMesh")); }

Label patchIndex(const PolyMesh& mesh, const std::string& name)
{
    const Label index = mesh.findPatch(name);
    EXPECT_GE(index, 0) << name;
    return index;
}

} // namespace

TEST(PointPatchDisplacement, PatchPointsAreNumberedByFirstAppearanceOverTheFaces)
{
    const PolyMesh mesh = twoFacePatchMesh();
    EXPECT_EQ(patchMeshPoints(mesh, 0), (std::vector<Label>{0, 3, 2, 1, 5, 4}));
}

TEST(PointPatchDisplacement, NonuniformFixedValueFollowsLocalPointOrder)
{
    const PolyMesh mesh = twoFacePatchMesh();
    auto bc = condition("type fixedValue; value nonuniform List<vector> 6((0 0 0) (3 0 0) (2 0 0) (1 0 0) (5 0 0) (4 0 0));",
                        mesh, 0);
    EXPECT_EQ(bc->nodeClass(), PatchNodeClass::prescribed);
    std::vector<Vector3> displacement(mesh.points.size());
    bc->evaluateOnMesh(0.0, mesh.points, displacement);
    for (Label p = 0; p < 6; ++p) expectNear(displacement[p], {double(p), 0, 0});   // value i went to mesh point i
}

TEST(PointPatchDisplacement, MalformedValuesAreNamed)
{
    const PolyMesh mesh = twoFacePatchMesh();
    const std::string wrongSize =
        inputErrorOf([&] { condition("type fixedValue; value nonuniform List<vector> 2((0 0 0) (1 0 0));", mesh, 0); });
    EXPECT_TRUE(contains(wrongSize, "bottom") && contains(wrongSize, "6 points")) << wrongSize;
    const std::string missingValue = inputErrorOf([&] { condition("type fixedValue;", mesh, 0); });
    EXPECT_TRUE(contains(missingValue, "value") && contains(missingValue, "bottom")) << missingValue;
    const std::string missingOmega =
        inputErrorOf([&] { condition("type oscillatingDisplacement; amplitude (1 0 0);", mesh, 0); });
    EXPECT_TRUE(contains(missingOmega, "omega")) << missingOmega;
}

TEST(PointPatchDisplacement, UnknownTypeListsValidTypes)
{
    const PolyMesh mesh = twoFacePatchMesh();
    const std::string message = inputErrorOf([&] { condition("type movingWallDisplacement;", mesh, 0); });
    EXPECT_TRUE(contains(message, "Unknown patchField type movingWallDisplacement for patch bottom in file test.dict. "
                                  "Valid patchField types are: angularOscillatingDisplacement calculated empty"))
        << message;
}

TEST(PointPatchDisplacement, AngularOscillatingDisplacementIsARotationAboutTheAxis)
{
    const PolyMesh mesh = cubeMesh();
    const Label left = patchIndex(mesh, "left");
    auto bc = condition("type angularOscillatingDisplacement; axis (0 0.2 1); origin (0.5 0.5 0.5);"
                        "angle0 0.1; amplitude 0.3; omega 3;",
                        mesh, left);
    EXPECT_EQ(bc->nodeClass(), PatchNodeClass::prescribed);
    EXPECT_TRUE(bc->isTimeDependent());
    const double t = 0.7;
    const double angle = 0.1 + 0.3 * std::sin(3 * t);
    const Matrix3 r = rotationMatrix({0, 0.2, 1}, angle);
    std::vector<Vector3> points0;
    for (Label p : bc->meshPoints()) points0.push_back(mesh.points[p]);
    std::vector<Vector3> displacement(points0.size());
    bc->evaluate(t, points0, displacement);
    const Vector3 origin{0.5, 0.5, 0.5};
    for (std::size_t i = 0; i < points0.size(); ++i)
        expectNear(points0[i] + displacement[i], origin + r * (points0[i] - origin));
}

TEST(PointPatchDisplacement, NodeClassesAndSlidingNormals)
{
    const PolyMesh mesh = cubeMesh();
    const Label bottom = patchIndex(mesh, "bottom");   // a planar parallelogram, outward normal ∝ (0.1, −1, 0.1)
    const Vector3 bottomNormal = Vector3{0.1, -1, 0.1} / norm(Vector3{0.1, -1, 0.1});
    EXPECT_EQ(condition("type zeroGradient;", mesh, bottom)->nodeClass(), PatchNodeClass::free);
    EXPECT_EQ(condition("type calculated;", mesh, bottom)->nodeClass(), PatchNodeClass::free);
    auto slip = condition("type slip;", mesh, bottom);
    EXPECT_EQ(slip->nodeClass(), PatchNodeClass::sliding);
    for (Label i = 0; i < slip->pointCount(); ++i) expectNear(slip->slidingNormal(i), bottomNormal, 1e-12);
    auto fixedNormal = condition("type fixedNormalSlip; n (0 2 0);", mesh, bottom);
    expectNear(fixedNormal->slidingNormal(3), {0, 1, 0});
    EXPECT_THROW(fixedNormal->evaluate(0.0, {}, {}), std::logic_error);

    // Constraint patches impose their type; a constraint type on an ordinary patch is an error.
    PolyMesh constrained = mesh;
    constrained.patches[bottom].type = "symmetryPlane";
    auto plane = condition("type fixedValue; value uniform (0 0 0);", constrained, bottom);
    EXPECT_EQ(plane->type(), "symmetryPlane");
    EXPECT_EQ(plane->nodeClass(), PatchNodeClass::sliding);
    expectNear(plane->slidingNormal(0), bottomNormal, 1e-12);
    constrained.patches[bottom].type = "empty";
    EXPECT_EQ(condition("type zeroGradient;", constrained, bottom)->nodeClass(), PatchNodeClass::ignored);
    const std::string inconsistent = inputErrorOf([&] { condition("type symmetryPlane;", mesh, bottom); });
    EXPECT_TRUE(contains(inconsistent, "inconsistent patch and patchField types")) << inconsistent;

    // The front face of the sheared cube is not planar: symmetryPlane refuses it, as OpenFOAM does.
    constrained.patches[patchIndex(mesh, "front")].type = "symmetryPlane";
    const std::string notPlanar =
        inputErrorOf([&] { condition("type symmetryPlane;", constrained, patchIndex(mesh, "front")); });
    EXPECT_TRUE(contains(notPlanar, "not planar")) << notPlanar;
}

TEST(PointPatchDisplacement, MatchesOpenFoamDisplacementLaplacianBoundaryPoints)
{
    const std::filesystem::path caseDirectory = dataPath("pointPatchConditions");
    const PolyMesh mesh = io::readPolyMesh(caseDirectory / "constant" / "polyMesh");
    const io::Dictionary field = io::Dictionary::readFile(caseDirectory / "0" / "pointDisplacement");
    const auto conditions = readPointPatchDisplacements(field, mesh, caseDirectory);
    ASSERT_EQ(conditions.size(), mesh.patches.size());

    // Points on exactly one patch.
    std::vector<int> patchCount(mesh.points.size(), 0);
    for (const auto& bc : conditions)
        for (Label p : bc->meshPoints()) ++patchCount[p];

    for (const char* time : {"0.5", "1"}) {
        const std::vector<Vector3> expected = io::readPolyMeshPoints(caseDirectory / time / "polyMesh");
        ASSERT_EQ(expected.size(), mesh.points.size());
        std::vector<Vector3> displacement(mesh.points.size());
        int compared = 0;
        for (const auto& bc : conditions) {
            ASSERT_EQ(bc->nodeClass(), PatchNodeClass::prescribed) << bc->patchName();
            bc->evaluateOnMesh(std::stod(time), mesh.points, displacement);
            for (Label p : bc->meshPoints()) {
                if (patchCount[p] != 1) continue;
                SCOPED_TRACE("time " + std::string(time) + " patch " + bc->patchName() + " point " + std::to_string(p));
                expectNear(mesh.points[p] + displacement[p], expected[p], 1e-13);
                ++compared;
            }
        }
        EXPECT_EQ(compared, 6 * 9);   // 3×3 patch-interior points on each of the six sides
    }
}
