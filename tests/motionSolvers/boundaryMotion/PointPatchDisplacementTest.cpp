// Tests of the point patch conditions of 0/pointDisplacement (boundaryMotion/PointPatchDisplacement).

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
                                  "Valid patchField types are: angularOscillatingDisplacement calculated cyclic empty"))
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
    const rbm::Matrix3 r = rotationMatrix({0, 0.2, 1}, angle);
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
