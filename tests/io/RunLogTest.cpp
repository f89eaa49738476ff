// Tests of the run log (io/RunLog): the per-step lines rbmMoveMesh writes.

#include "FoamDictionaryWriter.hpp"
#include "MeshGenerators.hpp"
#include "PetscTestEnvironment.hpp"
#include "PointVectorField.hpp"
#include "PolyMeshReader.hpp"
#include "PolyMeshWriter.hpp"
#include "RigidBodyMotionSolver.hpp"
#include "RunLog.hpp"
#include "ScratchFiles.hpp"
#include "TestCases.hpp"
#include "TimeFolderWriter.hpp"
#include "TimeName.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace rbm::test::moveMeshCases;

namespace {

using namespace rbm;

io::StepLogRecord sampleRecord()
{
    io::StepLogRecord record;
    record.step = 1;
    record.time = 0.025;
    record.timeName = "0.025";
    record.subSteps = 1;
    record.iterations = 3;
    record.residual = 2.1e-10;
    record.energy = 0.5;
    record.converged = true;
    record.reason = "CONVERGED_RTOL";
    record.worstQuality = 0.31;
    record.maxNonOrthogonality = 28.4;
    record.maxSkewness = 0.8;
    record.invertedCells = 0;
    record.wallSeconds = 0.12;
    return record;
}

TEST(RunLog, FormatsTheStepLineInFixedColumns)
{
    io::StepLogRecord record = sampleRecord();
    EXPECT_EQ(io::formatStepLogLine(record),
              "Time = 0.025     sub-steps  1  iterations    3  residual 2.10e-10  worst quality  0.3100"
              "  max non-orthogonality  28.40  inverted 0  wall   0.120 s");
    // Another time name and other figures of the usual widths: the same columns.
    io::StepLogRecord other = record;
    other.timeName = "1";
    other.subSteps = 12;
    other.iterations = 250;
    other.worstQuality = -0.5;
    other.maxNonOrthogonality = 5.0;
    const std::string first = io::formatStepLogLine(record);
    const std::string second = io::formatStepLogLine(other);
    for (const char* column : {"sub-steps", "iterations", "residual", "worst quality", "max non-orthogonality",
                               "inverted", "wall"}) {
        EXPECT_EQ(first.find(column), second.find(column)) << column << "\n" << first << "\n" << second;
    }
}

TEST(RunLog, MarksFailedAndWrittenSteps)
{
    io::StepLogRecord record = sampleRecord();
    record.written = true;
    EXPECT_TRUE(contains(io::formatStepLogLine(record), "wall   0.120 s  written"));
    record.converged = false;
    record.reason = "DIVERGED_ITS";
    record.invertedCells = 4;
    record.written = false;
    const std::string line = io::formatStepLogLine(record);
    EXPECT_TRUE(contains(line, "inverted 4")) << line;
    EXPECT_TRUE(contains(line, "NOT CONVERGED (DIVERGED_ITS)  INVALID")) << line;
    EXPECT_FALSE(contains(line, "written")) << line;
}

TEST(RunLog, JsonLineHoldsEveryFieldWithNullForNonFiniteNumbers)
{
    io::StepLogRecord record = sampleRecord();
    record.worstQuality = std::nan("");
    record.reason = "say \"why\"\n";
    record.written = true;
    const std::string line = io::stepLogJson(record);
    EXPECT_EQ(line.find('\n'), std::string::npos);
    std::map<std::string, JsonValue> object;
    ASSERT_TRUE(parseFlatJsonObject(line, object)) << line;
    const std::vector<std::string> keys = {"step",     "time",        "timeName",     "subSteps",
                                           "iterations", "residual",  "energy",       "converged",
                                           "reason",   "worstQuality", "maxNonOrthogonality", "maxSkewness",
                                           "invertedCells", "wallSeconds", "written"};
    EXPECT_EQ(object.size(), keys.size());
    for (const std::string& key : keys) EXPECT_EQ(object.count(key), 1u) << key;
    EXPECT_EQ(object["time"].number, 0.025);
    EXPECT_EQ(object["timeName"].text, "0.025");
    EXPECT_EQ(object["iterations"].number, 3);
    EXPECT_EQ(object["residual"].number, 2.1e-10);
    EXPECT_TRUE(object["converged"].boolean);
    EXPECT_EQ(object["reason"].text, "say \"why\"\n");
    EXPECT_EQ(object["worstQuality"].kind, JsonValue::Kind::Null);
    EXPECT_EQ(object["maxNonOrthogonality"].number, 28.4);
    EXPECT_TRUE(object["written"].boolean);
}

TEST(RunLog, JsonNumbersReadBackToTheSameDouble)
{
    for (const double value : {0.1 + 0.2, 1.0 / 3.0, 6.02214076e23, -4.9e-324, 0.0}) {
        EXPECT_EQ(std::strtod(io::jsonNumber(value).c_str(), nullptr), value) << io::jsonNumber(value);
    }
    EXPECT_EQ(io::jsonNumber(INFINITY), "null");
}

} // namespace
