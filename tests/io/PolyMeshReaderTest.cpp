// Tests of the polyMesh reader (io/PolyMeshReader): the committed fixtures in every format
// variant, and every malformed file named with its line and what was expected.

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

// The mesh of tests/data/makeFixtures.sh: blocks of 6 and 4 cells in x (0..0.6..1), 5 in y
// (0..0.5, last/first cell size 3), 4 in z (0..0.2).
constexpr int nx = 10, ny = 5, nz = 4;

constexpr int pointCount = (nx + 1) * (ny + 1) * (nz + 1);                                    // 330
constexpr int cellCount = nx * ny * nz;                                                      // 200
constexpr int internalFaceCount = (nx - 1) * ny * nz + nx * (ny - 1) * nz + nx * ny * (nz - 1);  // 490
constexpr int boundaryFaceCount = 2 * (ny * nz + nx * nz + nx * ny);                          // 220

// y of grid line j: cell sizes grow by r = 3^(1/4) per cell, 5 cells over 0.5.
double gradedY(int j)
{
    const double r = std::pow(3.0, 0.25);
    return 0.5 * (std::pow(r, j) - 1.0) / (std::pow(r, ny) - 1.0);
}

// Copies a fixture's polyMesh into `dir`/polyMesh and returns that folder.
fs::path copyPolyMesh(const std::string& variant, const fs::path& dir)
{
    const fs::path target = dir / "polyMesh";
    fs::create_directories(target);
    fs::copy(polyMeshOf(variant), target, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    return target;
}

// Replaces the first occurrence of `from` in the file (which must contain it).
void replaceInFile(const fs::path& path, const std::string& from, const std::string& to)
{
    std::string text = readText(path);
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << "'" << from << "' not in " << path;
    text.replace(at, from.size(), to);
    writeText(path, text);
}

} // namespace

class PolyMeshFixtureVariant : public ::testing::TestWithParam<std::string> {};

TEST_P(PolyMeshFixtureVariant, HasTheCountsOfTheBlockMeshDict)
{
    const PolyMesh mesh = rbm::io::readPolyMesh(polyMeshOf(GetParam()));
    EXPECT_EQ(mesh.pointCount(), pointCount);
    EXPECT_EQ(mesh.cellCount(), cellCount);
    EXPECT_EQ(mesh.faceCount(), internalFaceCount + boundaryFaceCount);
    EXPECT_EQ(mesh.internalFaceCount(), internalFaceCount);
    // Hexahedra only: every face is a quadrilateral.
    EXPECT_EQ(mesh.facePoints.size(), 4u * static_cast<std::size_t>(mesh.faceCount()));
    // Every cell of a hexahedral mesh has 6 faces.
    std::vector<int> facesOfCell(cellCount, 0);
    for (Label c : mesh.owner) ++facesOfCell[static_cast<std::size_t>(c)];
    for (Label c : mesh.neighbour) ++facesOfCell[static_cast<std::size_t>(c)];
    EXPECT_TRUE(std::all_of(facesOfCell.begin(), facesOfCell.end(), [](int n) { return n == 6; }));
}

TEST_P(PolyMeshFixtureVariant, HasThePatchesOfTheBlockMeshDict)
{
    const PolyMesh mesh = rbm::io::readPolyMesh(polyMeshOf(GetParam()));
    struct Expected {
        const char* name;
        const char* type;
        int faceCount;
        std::vector<std::string> inGroups;
    };
    const std::vector<Expected> expected = {
        {"inlet", "patch", ny * nz, {}},
        {"outlet", "patch", ny * nz, {"farField", "openBoundaries"}},
        {"lowerWall", "wall", nx * nz, {"movingWalls", "wall"}},
        {"upperWall", "wall", nx * nz, {"wall"}},
        {"front", "cyclic", nx * ny, {"cyclic"}},
        {"back", "cyclic", nx * ny, {"cyclic"}},
    };
    ASSERT_EQ(mesh.patches.size(), expected.size());
    int start = internalFaceCount;
    for (std::size_t p = 0; p < expected.size(); ++p) {
        SCOPED_TRACE(expected[p].name);
        EXPECT_EQ(mesh.patches[p].name, expected[p].name);
        EXPECT_EQ(mesh.patches[p].type, expected[p].type);
        EXPECT_EQ(mesh.patches[p].faceCount, expected[p].faceCount);
        EXPECT_EQ(mesh.patches[p].startFace, start);
        EXPECT_EQ(mesh.patches[p].inGroups, expected[p].inGroups);
        start += expected[p].faceCount;
    }
    // The cyclic's own entries are kept verbatim, in file order.
    const std::vector<std::pair<std::string, std::string>> frontEntries = {
        {"matchTolerance", "0.0001"}, {"transform", "unknown"}, {"neighbourPatch", "back"}};
    EXPECT_EQ(mesh.patches[4].otherEntries, frontEntries);
    EXPECT_TRUE(mesh.patches[0].otherEntries.empty());
}

TEST_P(PolyMeshFixtureVariant, HasTheZonesOfBlockMeshAndTopoSet)
{
    const PolyMesh mesh = rbm::io::readPolyMesh(polyMeshOf(GetParam()));
    // cellZones from the named blocks: left 6x5x4, right 4x5x4, together every cell once.
    ASSERT_EQ(mesh.cellZones.size(), 2u);
    EXPECT_EQ(mesh.cellZones[0].name, "left");
    EXPECT_EQ(mesh.cellZones[1].name, "right");
    EXPECT_EQ(mesh.cellZones[0].labels.size(), 6u * ny * nz);
    EXPECT_EQ(mesh.cellZones[1].labels.size(), 4u * ny * nz);
    std::set<Label> allCells(mesh.cellZones[0].labels.begin(), mesh.cellZones[0].labels.end());
    allCells.insert(mesh.cellZones[1].labels.begin(), mesh.cellZones[1].labels.end());
    EXPECT_EQ(allCells.size(), static_cast<std::size_t>(cellCount));
    // Every point of a left cell has x <= 0.6.
    std::vector<bool> isLeft(cellCount, false);
    for (Label c : mesh.cellZones[0].labels) isLeft[static_cast<std::size_t>(c)] = true;
    for (Label f = 0; f < mesh.faceCount(); ++f) {
        const bool leftFace = isLeft[static_cast<std::size_t>(mesh.owner[static_cast<std::size_t>(f)])] ||
                              (f < mesh.internalFaceCount() && isLeft[static_cast<std::size_t>(mesh.neighbour[static_cast<std::size_t>(f)])]);
        if (!leftFace) continue;
        for (Label p : mesh.face(f)) ASSERT_LE(mesh.points[static_cast<std::size_t>(p)].x, 0.6 + 1e-12) << "face " << f;
    }

    // faceZone "interface": the 5 x 4 internal faces on x = 0.6, flipped where y > 0.25
    // (2 of the 5 graded rows have their centre above y = 0.25).
    ASSERT_EQ(mesh.faceZones.size(), 1u);
    const rbm::Zone& interface = mesh.faceZones[0];
    EXPECT_EQ(interface.name, "interface");
    ASSERT_EQ(interface.labels.size(), static_cast<std::size_t>(ny * nz));
    ASSERT_EQ(interface.flipMap.size(), interface.labels.size());
    for (std::size_t k = 0; k < interface.labels.size(); ++k) {
        const Label f = interface.labels[k];
        EXPECT_LT(f, internalFaceCount);
        double centreY = 0.0;
        for (Label p : mesh.face(f)) {
            EXPECT_NEAR(mesh.points[static_cast<std::size_t>(p)].x, 0.6, 1e-12);
            centreY += mesh.points[static_cast<std::size_t>(p)].y / 4;
        }
        EXPECT_EQ(interface.flipMap[k], centreY > 0.25) << "face " << f;
    }
    EXPECT_EQ(std::count(interface.flipMap.begin(), interface.flipMap.end(), true), 2 * nz);

    // pointZone "corner": the 3 x 2 x 2 points in the box x < 0.25, y < 0.1, z < 0.06, plus the
    // cyclic partners (z = 0.2) of the 6 of them on z = 0, which topoSet adds to keep the set
    // consistent across the front/back cyclic.
    ASSERT_EQ(mesh.pointZones.size(), 1u);
    EXPECT_EQ(mesh.pointZones[0].name, "corner");
    EXPECT_EQ(mesh.pointZones[0].labels.size(), 18u);
    for (Label p : mesh.pointZones[0].labels) {
        const Vector3& x = mesh.points[static_cast<std::size_t>(p)];
        EXPECT_LT(x.x, 0.25);
        EXPECT_LT(x.y, 0.1);
        EXPECT_TRUE(x.z < 0.06 || std::abs(x.z - 0.2) < 1e-12) << x;
    }
}

TEST_P(PolyMeshFixtureVariant, PointsLieOnTheGradedBlockGrid)
{
    const PolyMesh mesh = rbm::io::readPolyMesh(polyMeshOf(GetParam()));
    // Ascii files carry 10 significant digits (blockMesh writes points with at least 10).
    const double tolerance = GetParam().rfind("ascii", 0) == 0 ? 1e-10 : 1e-14;
    std::set<int> rowsSeen;
    for (const Vector3& x : mesh.points) {
        EXPECT_NEAR(x.x * 10, std::round(x.x * 10), 1e-12) << x;
        EXPECT_NEAR(x.z * 20, std::round(x.z * 20), 1e-12) << x;
        int row = -1;
        for (int j = 0; j <= ny; ++j) {
            if (std::abs(x.y - gradedY(j)) <= tolerance) row = j;
        }
        EXPECT_GE(row, 0) << "y = " << x.y << " is on no grid line";
        rowsSeen.insert(row);
    }
    EXPECT_EQ(rowsSeen.size(), static_cast<std::size_t>(ny + 1));
}

INSTANTIATE_TEST_SUITE_P(AllFormats, PolyMeshFixtureVariant,
                         ::testing::Values("ascii", "binary", "asciiGzip", "binaryGzip", "asciiFaceCompactList", "binaryLabel64"));

TEST(PolyMeshReader, BinaryVariantsAreBitIdentical)
{
    const PolyMesh& binary = binaryFixture();
    for (const char* variant : {"binaryGzip", "binaryLabel64"}) {
        SCOPED_TRACE(variant);
        const PolyMesh other = rbm::io::readPolyMesh(polyMeshOf(variant));
        EXPECT_TRUE(bitIdentical(other.points, binary.points));
        expectSameTopology(other, binary);
    }
}

TEST(PolyMeshReader, AsciiVariantsEqualBinaryToTheWrittenPrecision)
{
    const PolyMesh& binary = binaryFixture();
    for (const char* variant : {"ascii", "asciiGzip", "asciiFaceCompactList"}) {
        SCOPED_TRACE(variant);
        const PolyMesh ascii = rbm::io::readPolyMesh(polyMeshOf(variant));
        expectSameTopology(ascii, binary);
        expectPointsEqualToDigits(ascii.points, binary.points, 10);
        // The files really are rounded: 10 digits do not reproduce the graded y exactly.
        EXPECT_FALSE(bitIdentical(ascii.points, binary.points));
    }
}

TEST(PolyMeshReader, FaceCompactListAndFaceListFilesGiveTheSameFaces)
{
    EXPECT_NE(readText(polyMeshOf("ascii") / "faces").find("class       faceList;"), std::string::npos);
    EXPECT_NE(readText(polyMeshOf("asciiFaceCompactList") / "faces").find("class       faceCompactList;"), std::string::npos);
    const PolyMesh faceList = rbm::io::readPolyMesh(polyMeshOf("ascii"));
    const PolyMesh compact = rbm::io::readPolyMesh(polyMeshOf("asciiFaceCompactList"));
    EXPECT_EQ(faceList.faceOffsets, compact.faceOffsets);
    EXPECT_EQ(faceList.facePoints, compact.facePoints);
}

TEST(PolyMeshReader, ReadsTheOutwardNormalConventionOfBlockMesh)
{
    // Boundary face normals (right-hand rule) point out of the domain: the inlet (x = 0)
    // faces point in -x, the upper wall (y = 0.5) faces in +y.
    const PolyMesh& mesh = binaryFixture();
    const auto normalOf = [&](Label f) {
        const auto face = mesh.face(f);
        const Vector3& a = mesh.points[static_cast<std::size_t>(face[0])];
        const Vector3& b = mesh.points[static_cast<std::size_t>(face[1])];
        const Vector3& c = mesh.points[static_cast<std::size_t>(face[2])];
        return rbm::cross(b - a, c - a);
    };
    const rbm::Patch& inlet = mesh.patches[static_cast<std::size_t>(mesh.findPatch("inlet"))];
    for (Label f = inlet.startFace; f < inlet.startFace + inlet.faceCount; ++f) EXPECT_LT(normalOf(f).x, 0.0);
    const rbm::Patch& upper = mesh.patches[static_cast<std::size_t>(mesh.findPatch("upperWall"))];
    for (Label f = upper.startFace; f < upper.startFace + upper.faceCount; ++f) EXPECT_GT(normalOf(f).y, 0.0);
}

TEST(PolyMeshReader, ReadsTheMovedPointsOfATimeFolder)
{
    TempDir dir("timePoints");
    const fs::path written = rbm::io::writePolyMeshPoints(dir.path(), "0.5", binaryFixture().points, FoamWriteOptions{.binary = true});
    EXPECT_EQ(written, dir.path() / "0.5" / "polyMesh" / "points");
    EXPECT_TRUE(bitIdentical(rbm::io::readPolyMeshPoints(dir.path() / "0.5" / "polyMesh"), binaryFixture().points));
    EXPECT_TRUE(bitIdentical(rbm::io::readPolyMeshPoints(written), binaryFixture().points));
    EXPECT_TRUE(bitIdentical(rbm::io::readPolyMeshPoints(dir.path() / "0.5"), binaryFixture().points));
    expectInputError([&] { rbm::io::readPolyMeshPoints(dir.path() / "0.7"); }, {"0.7", "not found", "expected a time folder"});
}

class PolyMeshMalformed : public ::testing::Test {
protected:
    PolyMeshMalformed() : dir_(::testing::UnitTest::GetInstance()->current_test_info()->name()) {}
    fs::path copy(const std::string& variant) { return copyPolyMesh(variant, dir_.path()); }
    TempDir dir_;
};

TEST_F(PolyMeshMalformed, TruncatedPointsFile)
{
    const fs::path mesh = copy("ascii");
    std::string text = readText(mesh / "points");
    // Cut before point (0.5 0.5 0.2): i = 5, j = 5, k = 4 of the left block's 7 x 6 x 5 points,
    // label 5 + 7 * 5 + 42 * 4 = 208, on line 21 + 208.
    text.resize(text.find("(0.5 0.5 0.2)"));
    writeText(mesh / "points", text);
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"points", "truncated", "file ends after 208 entries"}, 229);
}

TEST_F(PolyMeshMalformed, TruncatedBinaryFile)
{
    const fs::path mesh = copy("binary");
    std::string text = readText(mesh / "owner");
    text.resize(text.size() - 500);
    writeText(mesh / "owner", text);
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"owner", "2840 bytes", "truncated"});
}

TEST_F(PolyMeshMalformed, ListSizeLargerThanItsData)
{
    const fs::path mesh = copy("ascii");
    replaceInFile(mesh / "points", "\n330\n(", "\n331\n(");
    // The count is on line 19, '(' on 20, the 330 points on 21-350, so ')' is on line 351.
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"points", "331 points", "ends after 330"}, 351);
}

TEST_F(PolyMeshMalformed, ListSizeSmallerThanItsData)
{
    const fs::path mesh = copy("ascii");
    replaceInFile(mesh / "owner", "\n710\n(", "\n709\n(");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"owner", "709", "more entries than its size", "expected ')'"});
}

TEST_F(PolyMeshMalformed, HugeCountsAreRejectedBeforeAllocating)
{
    const fs::path mesh = copy("ascii");
    replaceInFile(mesh / "points", "\n330\n(", "\n2147483648\n(");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"points", "2147483648", "32-bit"});
    replaceInFile(mesh / "points", "\n2147483648\n(", "\n2000000000\n(");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"points", "2000000000 points", "bytes left"});
    replaceInFile(mesh / "points", "\n2000000000\n(", "\n2000000000{(0 0 0)}\n(");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"points", "uniform list of 2000000000"});

    const fs::path binaryMesh = copy("binary");
    replaceInFile(binaryMesh / "owner", "\n710\n(", "\n2000000000\n(");
    expectInputError([&] { rbm::io::readPolyMesh(binaryMesh); }, {"owner", "2000000000", "needs 8000000000 bytes"});
}

TEST_F(PolyMeshMalformed, FaceWithTwoPoints)
{
    const fs::path mesh = copy("ascii");
    const std::string text = readText(mesh / "faces");
    const std::size_t firstFace = text.find("4(1 8 50 43)");
    ASSERT_NE(firstFace, std::string::npos);
    replaceInFile(mesh / "faces", "4(1 8 50 43)", "2(1 8)");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"faces", "face 0 has 2 points", "at least 3"}, 21);
}

TEST_F(PolyMeshMalformed, FaceCompactListWithInconsistentOffsets)
{
    const fs::path mesh = copy("asciiFaceCompactList");
    replaceInFile(mesh / "faces", "\n2840\n)", "\n2841\n)");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"faces", "offsets end at 2841", "2840 point labels"});
}

TEST_F(PolyMeshMalformed, PointLabelOutOfRange)
{
    const fs::path mesh = copy("ascii");
    replaceInFile(mesh / "faces", "4(1 8 50 43)", "4(1 8 50 330)");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"faces", "face 0 refers to point 330", "330 points"});
}

TEST_F(PolyMeshMalformed, LabelThatIsNotAnInteger)
{
    const fs::path mesh = copy("ascii");
    replaceInFile(mesh / "faces", "4(1 8 50 43)", "4(1 8 50.5 43)");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"faces", "expected point label (an integer)", "'50.5"}, 21);
}

TEST_F(PolyMeshMalformed, OwnerListShorterThanTheFaces)
{
    const fs::path mesh = copy("ascii");
    std::string text = readText(mesh / "owner");
    const std::size_t last = text.rfind("\n)\n");
    const std::size_t lastEntry = text.rfind('\n', last - 1);
    text.erase(lastEntry, last - lastEntry);
    const std::size_t count = text.find("\n710\n(");
    text.replace(count, 6, "\n709\n(");
    writeText(mesh / "owner", text);
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"owner", "709 entries", "710 faces"});
}

TEST_F(PolyMeshMalformed, NegativeCellLabel)
{
    const fs::path mesh = copy("ascii");
    replaceInFile(mesh / "neighbour", "\n(\n1\n", "\n(\n-1\n");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"neighbour", "face 0", "-1", "negative"});
}

TEST_F(PolyMeshMalformed, NeighbourListDisagreesWithThePatches)
{
    // One internal face fewer: the first patch no longer starts where the internal faces end.
    const fs::path mesh = copy("ascii");
    std::string text = readText(mesh / "neighbour");
    const std::size_t last = text.rfind("\n)\n");
    text.erase(text.rfind('\n', last - 1), last - text.rfind('\n', last - 1));
    text.replace(text.find("\n490\n("), 6, "\n489\n(");
    writeText(mesh / "neighbour", text);
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"boundary", "patch 'inlet' starts at face 490", "internal faces", "gap of 1 face", "expected startFace 489"});
}

TEST_F(PolyMeshMalformed, OverlappingPatches)
{
    const fs::path mesh = copy("ascii");
    replaceInFile(mesh / "boundary", "startFace       510;", "startFace       505;");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"boundary", "patch 'outlet' starts at face 505", "'inlet' ends at face 510", "overlap of 5 faces", "expected startFace 510"});
}

TEST_F(PolyMeshMalformed, PatchPastTheLastFace)
{
    const fs::path mesh = copy("ascii");
    std::string text = readText(mesh / "boundary");
    const std::size_t back = text.find("    back\n");
    text.replace(text.find("nFaces          50;", back), 19, "nFaces          60;");
    writeText(mesh / "boundary", text);
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"boundary", "patch 'back'", "runs past the last face", "710 faces"});
}

TEST_F(PolyMeshMalformed, FacesOutsideEveryPatch)
{
    const fs::path mesh = copy("ascii");
    std::string text = readText(mesh / "boundary");
    const std::size_t back = text.find("    back\n");
    text.replace(text.find("nFaces          50;", back), 19, "nFaces          40;");
    writeText(mesh / "boundary", text);
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"boundary", "the last 10 faces belong to no patch"});
}

TEST_F(PolyMeshMalformed, NotANumberCoordinate)
{
    const fs::path mesh = copy("ascii");
    replaceInFile(mesh / "points", "(0.1 0 0)", "(0.1 nan 0)");
    // Point 1 is on line 22 (point 0 on line 21).
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"points", "finite", "'nan"}, 22);
}

TEST_F(PolyMeshMalformed, InfiniteCoordinateInBinary)
{
    const fs::path mesh = copy("binary");
    std::string text = readText(mesh / "points");
    const std::size_t data = text.find("\n330\n(") + 6;
    const double infinity = HUGE_VAL;
    std::memcpy(text.data() + data + 24 * 7 + 8, &infinity, 8);   // y of point 7
    writeText(mesh / "points", text);
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"points", "point 7", "not finite"});
}

TEST_F(PolyMeshMalformed, BinarySizeThatDisagreesWithTheArch)
{
    // 32-bit data declared as 64-bit labels: 710 labels need 5680 bytes, there are 2840.
    const fs::path mesh = copy("binary");
    replaceInFile(mesh / "owner", "label=32", "label=64");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"owner", "arch"});
    // 64-bit scalars declared as 32-bit: the list ends 3960 bytes early, where no ')' is.
    const fs::path mesh2 = copy("binary");
    replaceInFile(mesh2 / "points", "scalar=64", "scalar=32");
    expectInputError([&] { rbm::io::readPolyMesh(mesh2); }, {"points", "expected ')'", "arch"});
}

TEST_F(PolyMeshMalformed, SixtyFourBitLabelTooLargeForRbm)
{
    const fs::path mesh = copy("binaryLabel64");
    std::string text = readText(mesh / "owner");
    const std::size_t data = text.find("\n710\n(") + 6;
    const std::int64_t large = std::int64_t(1) << 32;
    std::memcpy(text.data() + data + 8 * 3, &large, 8);
    writeText(mesh / "owner", text);
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"owner", "4294967296", "32-bit label"});
}

TEST_F(PolyMeshMalformed, ZoneLabelOutOfRange)
{
    const fs::path mesh = copy("ascii");
    replaceInFile(mesh / "pointZones", "\n177\n)", "\n330\n)");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"pointZones", "corner", "330", "out of range"});
}

TEST_F(PolyMeshMalformed, WrongFacesClass)
{
    const fs::path mesh = copy("ascii");
    replaceInFile(mesh / "faces", "class       faceList;", "class       labelList;");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"faces", "labelList", "faceList or faceCompactList"});
}

TEST_F(PolyMeshMalformed, MissingFile)
{
    const fs::path mesh = copy("ascii");
    fs::remove(mesh / "owner");
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"owner", "owner.gz", "not found"});
}

TEST(PolyMeshReader, KeepsUnknownPatchEntriesThroughARoundTrip)
{
    TempDir dir("otherEntries");
    const fs::path mesh = copyPolyMesh("ascii", dir.path());
    replaceInFile(mesh / "boundary", "        startFace       490;\n",
                  "        startFace       490;\n        physicalType    inlet;\n        offset          (0 0 1);\n"
                  "        coefficients    { alpha 1; names (a b); }\n");
    const PolyMesh read = rbm::io::readPolyMesh(mesh);
    const auto& entries = read.patches[0].otherEntries;
    ASSERT_EQ(entries.size(), 3u);
    EXPECT_EQ(entries[0].first, "physicalType");
    EXPECT_EQ(entries[0].second, "inlet");
    EXPECT_EQ(entries[1].first, "offset");
    EXPECT_EQ(entries[2].first, "coefficients");
    EXPECT_EQ(entries[2].second.front(), '{');

    for (bool binary : {false, true}) {
        const fs::path written = dir.path() / (binary ? "binary" : "ascii") / "polyMesh";
        rbm::io::writePolyMesh(written, read, FoamWriteOptions{.binary = binary});
        const PolyMesh back = rbm::io::readPolyMesh(written);
        EXPECT_EQ(back.patches[0].otherEntries, entries);
        expectSameTopology(back, read);
    }
}

TEST(PolyMeshReader, ReadsEmptyAndUniformZones)
{
    TempDir dir("emptyZones");
    PolyMesh mesh = binaryFixture();
    mesh.cellZones.push_back({"nothing", {}, {}});
    mesh.faceZones.push_back({"noFaces", {}, {}});
    mesh.pointZones.push_back({"single", {329}, {}});
    for (bool binary : {false, true}) {
        SCOPED_TRACE(binary ? "binary" : "ascii");
        const fs::path written = dir.path() / (binary ? "binary" : "ascii") / "polyMesh";
        rbm::io::writePolyMesh(written, mesh, FoamWriteOptions{.binary = binary});
        const PolyMesh back = rbm::io::readPolyMesh(written);
        expectSameTopology(back, mesh);
        EXPECT_TRUE(back.cellZones.back().labels.empty());
        EXPECT_EQ(back.pointZones.back().labels, std::vector<Label>{329});
    }
    // OpenFOAM writes a list of identical values as N{value} in ascii.
    const fs::path ascii = dir.path() / "ascii" / "polyMesh";
    std::string text = readText(ascii / "pointZones");
    const std::size_t single = text.find("single");
    text.replace(text.find("List<label> \n1\n(\n329\n)", single), 23, "List<label> 3{329}");
    writeText(ascii / "pointZones", text);
    EXPECT_EQ(rbm::io::readPolyMesh(ascii).pointZones.back().labels, (std::vector<Label>{329, 329, 329}));
}

TEST_F(PolyMeshMalformed, CellWithTooFewFaces)
{
    // The last boundary face handed to a new cell 200: that cell has 1 face.
    const fs::path mesh = copy("ascii");
    std::string text = readText(mesh / "owner");
    const std::size_t last = text.rfind("\n)\n");
    const std::size_t lastEntry = text.rfind('\n', last - 1) + 1;
    text.replace(lastEntry, last - lastEntry, "200");
    writeText(mesh / "owner", text);
    expectInputError([&] { rbm::io::readPolyMesh(mesh); }, {"owner", "cell 200 has 1 faces", "at least 4"});
}
