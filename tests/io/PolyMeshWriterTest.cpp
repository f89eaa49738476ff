// Tests of the polyMesh writer (io/PolyMeshWriter): what it writes, and the round trip.

#include "CompressedFile.hpp"
#include "FoamDictionary.hpp"
#include "FoamListIO.hpp"
#include "InputError.hpp"
#include "PolyMeshReader.hpp"
#include "PolyMeshWriter.hpp"
#include "ScratchFiles.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numeric>
#include <set>
#include <string>
#include <unistd.h>

using namespace rbm::test::polyMeshIOCases;

namespace {

} // namespace

struct WriteCase {
    bool binary;
    bool compressed;
};

class PolyMeshRoundTrip : public ::testing::TestWithParam<WriteCase> {};

TEST_P(PolyMeshRoundTrip, ReproducesTheMesh)
{
    const auto [binary, compressed] = GetParam();
    TempDir dir(std::string("roundTrip") + (binary ? "Binary" : "Ascii") + (compressed ? "Gz" : ""));
    // Translate the points by an amount that is not a short decimal, so ascii rounding shows.
    PolyMesh mesh = binaryFixture();
    for (Vector3& x : mesh.points) x += Vector3{1.0 / 3.0, -2.0 / 7.0, 0.1};
    const fs::path polyMeshDir = dir.path() / "constant" / "polyMesh";
    rbm::io::writePolyMesh(polyMeshDir, mesh, FoamWriteOptions{.binary = binary, .precision = 6, .compressed = compressed});

    for (const char* name : {"points", "faces", "owner", "neighbour", "cellZones", "faceZones", "pointZones"})
        EXPECT_TRUE(fs::exists(polyMeshDir / (std::string(name) + (compressed ? ".gz" : "")))) << name;
    EXPECT_TRUE(fs::exists(polyMeshDir / "boundary"));   // never compressed, as in OpenFOAM

    const PolyMesh back = rbm::io::readPolyMesh(polyMeshDir);
    expectSameTopology(back, mesh);
    if (binary) {
        EXPECT_TRUE(bitIdentical(back.points, mesh.points));
    } else {
        // writePrecision 6, raised to 10 digits for points as OpenFOAM's mesh tools do.
        expectPointsEqualToDigits(back.points, mesh.points, 10);
        EXPECT_FALSE(bitIdentical(back.points, mesh.points));
    }
}

INSTANTIATE_TEST_SUITE_P(AllFormats, PolyMeshRoundTrip,
                         ::testing::Values(WriteCase{false, false}, WriteCase{true, false}, WriteCase{false, true},
                                           WriteCase{true, true}),
                         [](const auto& info) {
                             return std::string(info.param.binary ? "Binary" : "Ascii") + (info.param.compressed ? "Gzip" : "");
                         });

TEST(PolyMeshWriter, AsciiPointsHonourThePrecisionWhenNoMinimumIsSet)
{
    TempDir dir("precision");
    std::vector<Vector3> points = binaryFixture().points;
    for (Vector3& x : points) x += Vector3{1.0 / 3.0, 0.0, 0.0};
    for (int digits : {3, 6, 12, 17}) {
        SCOPED_TRACE(digits);
        const fs::path file = rbm::io::writePointsFile(dir.path() / "points", points, "constant/polyMesh",
                                                       FoamWriteOptions{.precision = digits, .minimumPointPrecision = 0});
        const std::vector<Vector3> back = rbm::io::readPolyMeshPoints(file);
        expectPointsEqualToDigits(back, points, digits);
        // One digit fewer than written would not do (else the precision was ignored).
        const double coarser = 0.5 * std::pow(10.0, 2 - digits);
        bool anyNeedsAllDigits = false;
        for (std::size_t i = 0; i < points.size(); ++i)
            anyNeedsAllDigits |= std::abs(back[i].x - points[i].x) > 0.05 * coarser * std::abs(points[i].x);
        if (digits < 17) {
            EXPECT_TRUE(anyNeedsAllDigits);
        }
        if (digits == 17) {
            EXPECT_TRUE(bitIdentical(back, points));   // 17 digits round-trip a double
        }
    }
    // "1/3 + 0" written with 6 digits is the text 0.333333.
    rbm::io::writePointsFile(dir.path() / "points", std::vector<Vector3>{{1.0 / 3.0, 0.0, -2.5e-7}}, "constant/polyMesh",
                             FoamWriteOptions{.precision = 6, .minimumPointPrecision = 0});
    EXPECT_NE(readText(dir.path() / "points").find("\n(0.333333 0 -2.5e-07)\n"), std::string::npos);
}

TEST(PolyMeshWriter, WritesTheHeaderOpenFoamWrites)
{
    TempDir dir("header");
    rbm::io::writePolyMeshPoints(dir.path(), "0.005", binaryFixture().points, FoamWriteOptions{.binary = true});
    const std::string text = readText(dir.path() / "0.005" / "polyMesh" / "points");
    EXPECT_EQ(text.rfind("/*--------------------------------*- C++ -*----------------------------------*\\\n", 0), 0u);
    for (const char* line : {"    version     2.0;\n", "    format      binary;\n", "    class       vectorField;\n",
                             "    arch        \"LSB;label=32;scalar=64\";\n", "    location    \"0.005/polyMesh\";\n",
                             "    object      points;\n", "\n330\n("}) {
        EXPECT_NE(text.find(line), std::string::npos) << line;
    }
    // Size: header + 330 points of 24 bytes.
    EXPECT_GT(text.size(), 330u * 24u);

    const fs::path polyMeshDir = dir.path() / "constant" / "polyMesh";
    rbm::io::writePolyMesh(polyMeshDir, binaryFixture(), FoamWriteOptions{});
    const std::string owner = readText(polyMeshDir / "owner");
    EXPECT_NE(owner.find("note        \"nPoints:330  nCells:200  nFaces:710  nInternalFaces:490\";"), std::string::npos);
    EXPECT_NE(owner.find("location    \"constant/polyMesh\";"), std::string::npos);
    EXPECT_NE(readText(polyMeshDir / "faces").find("class       faceList;"), std::string::npos);
    const std::string boundary = readText(polyMeshDir / "boundary");
    EXPECT_NE(boundary.find("        inGroups        2(movingWalls wall);\n"), std::string::npos);
    EXPECT_NE(boundary.find("        neighbourPatch  front;\n"), std::string::npos);
    // OpenFOAM writes binary faces as a faceCompactList.
    rbm::io::writePolyMesh(polyMeshDir, binaryFixture(), FoamWriteOptions{.binary = true});
    EXPECT_NE(readText(polyMeshDir / "faces").find("class       faceCompactList;"), std::string::npos);
}

TEST(PolyMeshWriter, PointsWrittenInPiecesAreTheWholeTextWrite)
{
    // The points file streamed in pieces of 256 bytes (ascii: ~50 pieces; binary: the raw
    // block larger than a piece) is the text the whole-string writer built (header, the list
    // of FoamListIO's std::string appendVectorList, footer), in every format.
    TempDir dir("pieces");
    const std::vector<Vector3>& points = binaryFixture().points;
    for (const bool binary : {false, true}) {
        for (const bool compressed : {false, true}) {
            SCOPED_TRACE(std::string(binary ? "binary" : "ascii") + (compressed ? " gzip" : ""));
            const FoamWriteOptions options{.binary = binary, .compressed = compressed};
            std::string whole = rbm::io::foamFileHeaderText(binary, "vectorField", "1/polyMesh", "points");
            rbm::io::appendVectorList(whole, points, binary, std::max(options.precision, options.minimumPointPrecision));
            whole += rbm::io::foamFileFooterText();
            ASSERT_GT(whole.size(), 20u * 256);
            const fs::path written = rbm::io::writePointsFile(dir.path() / "points", points, "1/polyMesh", options, 256);
            EXPECT_EQ(written.filename(), compressed ? "points.gz" : "points");
            EXPECT_EQ(rbm::io::readFileContents(written), whole);
            if (!compressed) {
                EXPECT_EQ(readText(written), whole);
            }
            EXPECT_FALSE(fs::exists(compressed ? dir.path() / "points" : dir.path() / "points.gz"));  // the twin
            EXPECT_EQ(rbm::io::readPolyMeshPoints(written).size(), points.size());
        }
    }
}

TEST(PolyMeshWriter, ReplacesTheStaleTwinOfACompressedFile)
{
    TempDir dir("twin");
    std::vector<Vector3> moved = binaryFixture().points;
    for (Vector3& x : moved) x.x += 1.0;
    rbm::io::writePolyMeshPoints(dir.path(), "1", binaryFixture().points, FoamWriteOptions{});
    rbm::io::writePolyMeshPoints(dir.path(), "1", moved, FoamWriteOptions{.compressed = true});
    // A left-over uncompressed file would be read first and hide the new points.
    EXPECT_FALSE(fs::exists(dir.path() / "1" / "polyMesh" / "points"));
    expectPointsEqualToDigits(rbm::io::readPolyMeshPoints(dir.path() / "1" / "polyMesh"), moved, 10);
    rbm::io::writePolyMeshPoints(dir.path(), "1", binaryFixture().points, FoamWriteOptions{});
    EXPECT_FALSE(fs::exists(dir.path() / "1" / "polyMesh" / "points.gz"));
}
