// Tests of OpenFOAM's Function1 as rbmMoveMesh reads them (boundaryMotion/Function1): constants,
// tables, polynomials, sines and squares, their errors.

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

} // namespace

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
