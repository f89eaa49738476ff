// Tests of the OpenFOAM list reader (io/FoamListIO).

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

TEST(FoamListReader, ParsesAMillionAsciiPointsQuickly)
{
    std::vector<Vector3> points(1000000);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double t = static_cast<double>(i);
        points[i] = {std::sin(t) * 12.5, std::cos(t) * 0.001, t * 1e-6 - 0.5};
    }
    std::string text = "FoamFile { version 2.0; format ascii; class vectorField; object points; }\n";
    const std::size_t body = text.size();
    rbm::io::appendVectorList(text, points, false, 10);
    const auto start = std::chrono::steady_clock::now();
    rbm::io::FoamListReader reader(text, body, "points", rbm::io::FoamFileHeader{});
    const std::vector<Vector3> back = reader.readVectorList("point", text.size());
    reader.expectEnd();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    RecordProperty("secondsToParse", std::to_string(seconds));
    expectPointsEqualToDigits(back, points, 10);
    // Well under a second in a Release build; the bound is loose for debug builds and a busy machine.
    EXPECT_LT(seconds, 5.0);
}

TEST(FoamListReader, ReadsUniformUncountedAndEmptyBinaryLists)
{
    const rbm::io::FoamFileHeader ascii;
    {
        const std::string text = "5{7}  (1 2 3)  3(4 5 6) 0()";
        rbm::io::FoamListReader reader(text, 0, "labels", ascii);
        EXPECT_EQ(reader.readLabelList("label", 100), (std::vector<Label>{7, 7, 7, 7, 7}));
        EXPECT_EQ(reader.readLabelList("label", 100), (std::vector<Label>{1, 2, 3}));
        EXPECT_EQ(reader.readLabelList("label", 100), (std::vector<Label>{4, 5, 6}));
        EXPECT_TRUE(reader.readLabelList("label", 100).empty());
        reader.expectEnd();
    }
    {
        // A face with more than 10 points is written over several lines, with comments around.
        const std::string text = "2 // two faces\n(\n3(0 1 2)\n12\n(\n0\n1\n2\n3\n4\n5\n6\n7\n8\n9\n10\n11\n)\n) /* end */";
        std::vector<Label> offsets{0}, labels;
        rbm::io::FoamListReader reader(text, 0, "faces", ascii);
        reader.readFaceList(offsets, labels);
        reader.expectEnd();
        EXPECT_EQ(offsets, (std::vector<Label>{0, 3, 15}));
        EXPECT_EQ(labels.size(), 15u);
    }
    {
        // Binary: an empty list is a bare "0"; a faceList is a list of binary label lists.
        rbm::io::FoamFileHeader binary;
        binary.format = "binary";
        std::string text = "\n0\n\n2\n(\n3\n(";
        const std::int32_t face0[3] = {0, 1, 2}, face1[4] = {2, 1, 3, 4};
        text.append(reinterpret_cast<const char*>(face0), sizeof face0);
        text += ")\n4\n(";
        text.append(reinterpret_cast<const char*>(face1), sizeof face1);
        text += ")\n)\n";
        rbm::io::FoamListReader reader(text, 0, "faces", binary);
        EXPECT_TRUE(reader.readLabelList("label", 0).empty());
        std::vector<Label> offsets{0}, labels;
        reader.readFaceList(offsets, labels);
        reader.expectEnd();
        EXPECT_EQ(offsets, (std::vector<Label>{0, 3, 7}));
        EXPECT_EQ(labels, (std::vector<Label>{0, 1, 2, 2, 1, 3, 4}));
    }
}

TEST(FoamListReader, ReadsUnderflowAsZeroAndRejectsOverflow)
{
    const std::string text = "2((1e-400 -2.5e-320 +3) (0 0 0))";
    rbm::io::FoamListReader reader(text, 0, "points", rbm::io::FoamFileHeader{});
    const std::vector<Vector3> points = reader.readVectorList("point", 10);
    EXPECT_EQ(points[0].x, 0.0);
    EXPECT_LT(points[0].y, 0.0);
    EXPECT_GT(points[0].y, -1e-300);
    EXPECT_EQ(points[0].z, 3.0);
    const std::string overflow = "1((1e400 0 0))";
    rbm::io::FoamListReader bad(overflow, 0, "points", rbm::io::FoamFileHeader{});
    expectInputError([&] { bad.readVectorList("point", 10); }, {"points:1", "finite coordinate", "'1e400"});
}
