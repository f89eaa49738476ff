// Tests of the cyclic patch entries (io/CyclicPatchEntries): a boundary file with a
// translational pair as OpenFOAM v1912 writes it and a rotational pair as OpenFOAM 13 writes
// it, and the errors that name the patch.

#include "CyclicPatchEntries.hpp"
#include "InputError.hpp"
#include "PolyMeshReader.hpp"
#include "ScratchFiles.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace rbm::io {

namespace {

// The boundary file's patches with `entries` in the last patch (a cyclic "sideB"), read back.
PolyMesh meshWithBoundary(const rbm::test::TempDir& dir, const std::string& sideBEntries)
{
    const std::string text = R"(FoamFile { version 2.0; format ascii; class polyBoundaryMesh; object boundary; }
5
(
    inlet  { type cyclic; inGroups 1(cyclic); nFaces 2; startFace 10; matchTolerance 0.0001;
             transform translational; neighbourPatch outlet; separationVector (4 0 0); }
    outlet { type cyclic; inGroups 1(cyclic); nFaces 2; startFace 12; matchTolerance 0.0001;
             transform translational; neighbourPatch inlet; separationVector (-4 0 0); }
    walls  { type wall; nFaces 2; startFace 14; }
    sideA  { type cyclic; nFaces 2; startFace 16; neighbourPatch sideB; transformType rotational;
             rotationAxis (0 0 1); rotationCentre (0.5 0 0); rotationAngle 60; }
    sideB  { type cyclic; nFaces 2; startFace 18; )" + sideBEntries + R"( }
)
)";
    rbm::test::writeText(dir.path() / "boundary", text);
    PolyMesh mesh;
    mesh.patches = readBoundaryFile(dir.path() / "boundary");
    return mesh;
}

std::string errorOf(const PolyMesh& mesh)
{
    try {
        readCyclicPatchSpecs(mesh, "constant/polyMesh/boundary");
    } catch (const InputError& error) {
        return error.what();
    }
    return "no InputError";
}

} // namespace

TEST(CyclicPatchEntries, ReadsTranslationalAndRotationalPairsOfBothOpenFOAMs)
{
    const rbm::test::TempDir dir("cyclicEntries");
    const PolyMesh mesh = meshWithBoundary(
        dir, "neighbourPatch sideA; transformType rotational; rotationAxis (0 0 1); rotationCentre (0.5 0 0);");
    const std::vector<CyclicPatchSpec> specs = readCyclicPatchSpecs(mesh, "boundary");
    ASSERT_EQ(specs.size(), 4u);  // the wall is not cyclic
    EXPECT_EQ(specs[0].patch, 0);
    EXPECT_EQ(specs[0].neighbourPatch, "outlet");
    EXPECT_EQ(specs[0].transform, CyclicTransformKind::translational);
    EXPECT_EQ(specs[1].neighbourPatch, "inlet");
    EXPECT_EQ(specs[2].patch, 3);
    EXPECT_EQ(specs[2].neighbourPatch, "sideB");
    EXPECT_EQ(specs[2].transform, CyclicTransformKind::rotational);
    EXPECT_EQ(specs[2].rotationAxis, (Vector3{0.0, 0.0, 1.0}));
    EXPECT_EQ(specs[2].rotationCentre, (Vector3{0.5, 0.0, 0.0}));
    EXPECT_EQ(specs[3].patch, 4);
    EXPECT_EQ(specs[3].transform, CyclicTransformKind::rotational);
}

TEST(CyclicPatchEntries, WithoutATransformTheKindIsUnspecified)
{
    const rbm::test::TempDir dir("cyclicEntriesUnspecified");
    const PolyMesh mesh = meshWithBoundary(dir, "neighbourPatch sideA;");
    EXPECT_EQ(readCyclicPatchSpecs(mesh, "boundary")[3].transform, CyclicTransformKind::unspecified);
}

TEST(CyclicPatchEntries, ErrorsNameThePatchAndTheEntry)
{
    const rbm::test::TempDir dir("cyclicEntriesErrors");
    std::string error = errorOf(meshWithBoundary(dir, "neighbourPatch sideA; transform rotational; rotationAxis (0 0 1);"));
    EXPECT_NE(error.find("constant/polyMesh/boundary"), std::string::npos) << error;
    EXPECT_NE(error.find("cyclic patch 'sideB' has transform rotational but no rotationCentre"), std::string::npos) << error;
    error = errorOf(meshWithBoundary(dir, "neighbourPatch sideA; transform spiral;"));
    EXPECT_NE(error.find("cyclic patch 'sideB': unknown transform spiral. Valid transforms are:"), std::string::npos)
        << error;
    error = errorOf(meshWithBoundary(dir, "transform translational;"));
    EXPECT_NE(error.find("cyclic patch 'sideB' has no neighbourPatch"), std::string::npos) << error;
    error = errorOf(meshWithBoundary(dir, "neighbourPatch sideA; transform rotational; rotationAxis z; rotationCentre (0 0 0);"));
    EXPECT_NE(error.find("cyclic patch 'sideB': "), std::string::npos) << error;
}

} // namespace rbm::io
