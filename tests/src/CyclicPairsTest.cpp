// Tests of the point pairs of cyclic patches (src/CyclicPairs): a translational channel and a
// rotational sector paired against the transforms they were built with, and the errors for
// patches that do not match.

#include "CyclicPairs.hpp"
#include "InputError.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace rbm {

namespace {

using namespace rbm::test::cyclicCases;

std::vector<CyclicPatchSpec> specsOf(const PolyMesh& mesh, CyclicTransformKind kind, const Vector3& axis = {})
{
    std::vector<CyclicPatchSpec> specs;
    for (Label p = 0; p < static_cast<Label>(mesh.patches.size()); ++p) {
        if (mesh.patches[p].type != "cyclic") continue;
        CyclicPatchSpec spec;
        spec.patch = p;
        spec.neighbourPatch = mesh.patches[p].otherEntries.front().second;
        spec.transform = kind;
        spec.rotationAxis = axis;
        specs.push_back(spec);
    }
    return specs;
}

std::string errorOf(const PolyMesh& mesh, const std::vector<CyclicPatchSpec>& specs)
{
    try {
        pairCyclicPatches(mesh, mesh.points, specs, "constant/polyMesh/boundary");
    } catch (const InputError& error) {
        return error.what();
    }
    return "no InputError";
}

} // namespace

TEST(CyclicPairs, TranslationalChannelPairsEveryInletPointWithTheOutletPointOneLengthAlong)
{
    const PolyMesh mesh = channelWithBody(4.0, 2.0, 16, 8, 6, 10, 3, 5);
    const std::vector<CyclicPatchPairing> pairings =
        pairCyclicPatches(mesh, mesh.points, specsOf(mesh, CyclicTransformKind::translational), "boundary");
    ASSERT_EQ(pairings.size(), 1u);
    const CyclicPatchPairing& pairing = pairings.front();
    EXPECT_EQ(mesh.patches[pairing.patchA].name, "inlet");
    EXPECT_EQ(mesh.patches[pairing.patchB].name, "outlet");
    EXPECT_LT(norm(pairing.separation - Vector3{4.0, 0.0, 0.0}), 1e-14);
    // 9 points up the inlet on each of the two planes, each with the point 4 along x.
    ASSERT_EQ(pairing.points.size(), 18u);
    for (const auto& [a, b] : pairing.points) EXPECT_EQ(mesh.points[b] - mesh.points[a], (Vector3{4.0, 0.0, 0.0}));
}

TEST(CyclicPairs, WithoutATransformGivenTheSeparationIsMeasured)
{
    const PolyMesh mesh = channelWithBody(4.0, 2.0, 16, 8, 6, 10, 3, 5);
    const std::vector<CyclicPatchPairing> pairings =
        pairCyclicPatches(mesh, mesh.points, specsOf(mesh, CyclicTransformKind::unspecified), "boundary");
    ASSERT_EQ(pairings.size(), 1u);
    EXPECT_LT(norm(pairings.front().separation - Vector3{4.0, 0.0, 0.0}), 1e-14);
    EXPECT_EQ(pairings.front().points.size(), 18u);
}

TEST(CyclicPairs, RotationalSectorMeasuresItsAngleFromTheFaces)
{
    const PolyMesh mesh = annulusSector(1.0, 2.0, 60.0, 8, 16);
    const std::vector<CyclicPatchPairing> pairings =
        pairCyclicPatches(mesh, mesh.points, specsOf(mesh, CyclicTransformKind::rotational, {0.0, 0.0, 2.0}), "boundary");
    ASSERT_EQ(pairings.size(), 1u);
    const CyclicPatchPairing& pairing = pairings.front();
    // The rotation of 60° about z (counter-clockwise: side A at θ = 0 to side B at θ = 60°).
    const double c = 0.5, s = std::sqrt(3.0) / 2.0;
    const double expected[3][3] = {{c, -s, 0.0}, {s, c, 0.0}, {0.0, 0.0, 1.0}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(pairing.rotation(i, j), expected[i][j], 1e-14) << i << " " << j;
    ASSERT_EQ(pairing.points.size(), 18u);
    for (const auto& [a, b] : pairing.points) {
        const Vector3 x = mesh.points[a];
        EXPECT_LT(norm(mesh.points[b] - Vector3{c * x.x - s * x.y, s * x.x + c * x.y, x.z}), 1e-14);
    }
}

TEST(CyclicPairs, AnUnmatchedPointIsAnErrorNamingBothPatches)
{
    PolyMesh mesh = channelWithBody(4.0, 2.0, 16, 8, 6, 10, 3, 5);
    // One outlet point 0.01 (4 % of the 0.25 edges) off its place: no inlet point finds it.
    mesh.points[patchMeshPoints(mesh, mesh.findPatch("outlet"))[3]].y += 0.01;
    const std::string error = errorOf(mesh, specsOf(mesh, CyclicTransformKind::translational));
    EXPECT_NE(error.find("constant/polyMesh/boundary"), std::string::npos) << error;
    EXPECT_NE(error.find("cyclic patch 'inlet'"), std::string::npos) << error;
    EXPECT_NE(error.find("has no partner on 'outlet'"), std::string::npos) << error;
}

TEST(CyclicPairs, AWrongRotationAxisLeavesThePointsWithoutPartners)
{
    const PolyMesh mesh = annulusSector(1.0, 2.0, 60.0, 8, 16);
    const std::string error = errorOf(mesh, specsOf(mesh, CyclicTransformKind::rotational, {1.0, 0.0, 0.0}));
    EXPECT_NE(error.find("cyclic patch 'sideA'"), std::string::npos) << error;
    EXPECT_NE(error.find("no partner"), std::string::npos) << error;
}

TEST(CyclicPairs, ANeighbourThatDoesNotNameThePatchBackIsAnError)
{
    const PolyMesh mesh = channelWithBody(4.0, 2.0, 16, 8, 6, 10, 3, 5);
    std::vector<CyclicPatchSpec> specs = specsOf(mesh, CyclicTransformKind::translational);
    specs[1].neighbourPatch = "walls";
    const std::string error = errorOf(mesh, specs);
    EXPECT_NE(error.find("cyclic patch 'inlet' names 'outlet'"), std::string::npos) << error;
    specs[0].neighbourPatch = "nowhere";
    EXPECT_NE(errorOf(mesh, specs).find("its neighbourPatch 'nowhere' is not another cyclic patch"), std::string::npos);
}

} // namespace rbm
