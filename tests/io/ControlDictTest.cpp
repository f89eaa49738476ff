// Tests of system/controlDict reading (io/ControlDict.hpp) and OpenFOAM's time-folder names
// (io/TimeName.hpp). Expected names are those OpenFOAM v1912 writes (Time::timeName).

#include "ControlDict.hpp"
#include "TestCases.hpp"
#include "TimeName.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace rbm::test::controlDictCases;

using rbm::InputError;
using rbm::io::ControlDict;
using rbm::io::Dictionary;
using rbm::io::TimeFormat;

namespace {

ControlDict parse(const std::string& body)
{
    return rbm::io::controlDictFromDictionary(Dictionary::parseText(body, "case/system/controlDict"));
}

InputError parseError(const std::string& body)
{
    try {
        parse(body);
    } catch (const InputError& error) {
        return error;
    }
    ADD_FAILURE() << "no InputError for:\n" << body;
    return InputError("", 0, "");
}

const std::string minimal = "startTime 0;\nendTime 1;\ndeltaT 0.005;\nwriteInterval 20;\n";

} // namespace

TEST(ControlDict, ReadsEveryEntry)
{
    fs::path folder = scratchCase("full");
    std::ofstream(folder / "system" / "controlDict") << R"(FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application     moveMesh;
startFrom       startTime;
startTime       0.5;
stopAt          endTime;
endTime         2;
deltaT          0.01;
writeControl    adjustableRunTime;
writeInterval   0.1;
purgeWrite      0;
writeFormat     binary;
writePrecision  12;
writeCompression compressed;
timeFormat      fixed;
timePrecision   4;
runTimeModifiable true;
functions { #includeFunc residuals }
)";
    const ControlDict control = rbm::io::readControlDict(folder);
    EXPECT_EQ(control.startFrom, ControlDict::StartFrom::StartTime);
    EXPECT_DOUBLE_EQ(control.startTime, 0.5);
    EXPECT_DOUBLE_EQ(control.endTime, 2.0);
    EXPECT_DOUBLE_EQ(control.deltaT, 0.01);
    EXPECT_EQ(control.writeControl, ControlDict::WriteControl::AdjustableRunTime);
    EXPECT_DOUBLE_EQ(control.writeInterval, 0.1);
    EXPECT_TRUE(control.binary);
    EXPECT_EQ(control.writePrecision, 12);
    EXPECT_TRUE(control.writeCompression);
    EXPECT_EQ(control.timeFormat, TimeFormat::Fixed);
    EXPECT_EQ(control.timePrecision, 4);
    EXPECT_EQ(control.timeName(0.5), "0.5000");
    EXPECT_EQ(rbm::io::resolveStartTime(control, folder), 0.5);
}

TEST(ControlDict, DefaultsAreOpenFoams)
{
    const ControlDict control = parse(minimal);
    EXPECT_EQ(control.startFrom, ControlDict::StartFrom::StartTime);
    EXPECT_EQ(control.writeControl, ControlDict::WriteControl::TimeStep);
    EXPECT_FALSE(control.binary);
    EXPECT_EQ(control.writePrecision, 6);
    EXPECT_FALSE(control.writeCompression);
    EXPECT_EQ(control.timeFormat, TimeFormat::General);
    EXPECT_EQ(control.timePrecision, 6);
    EXPECT_EQ(control.timeName(0.005), "0.005");
}

TEST(ControlDict, WriteCompressionSpellings)
{
    for (const char* on : {"on", "compressed", "true", "yes"}) {
        EXPECT_TRUE(parse(minimal + "writeCompression " + on + ";\n").writeCompression) << on;
    }
    for (const char* off : {"off", "uncompressed", "false", "no"}) {
        EXPECT_FALSE(parse(minimal + "writeCompression " + off + ";\n").writeCompression) << off;
    }
}

TEST(ControlDict, LatestAndFirstTimeComeFromTheTimeFolders)
{
    fs::path folder = scratchCase("latest");
    for (const char* name : {"0", "0.25", "1.5", "constant"}) fs::create_directories(folder / name);
    ControlDict control = parse("startFrom latestTime;\nendTime 3;\ndeltaT 0.25;\nwriteInterval 1;\n");
    EXPECT_EQ(control.startFrom, ControlDict::StartFrom::LatestTime);
    EXPECT_DOUBLE_EQ(rbm::io::resolveStartTime(control, folder), 1.5);
    control.startFrom = ControlDict::StartFrom::FirstTime;
    EXPECT_DOUBLE_EQ(rbm::io::resolveStartTime(control, folder), 0.0);
    control.endTime = 1.0;
    control.startFrom = ControlDict::StartFrom::LatestTime;
    EXPECT_THROW(rbm::io::resolveStartTime(control, folder), InputError);  // endTime before latestTime
    fs::path empty = scratchCase("noTimes");
    EXPECT_THROW(rbm::io::resolveStartTime(control, empty), InputError);
}

TEST(ControlDictErrors, NonPositiveDeltaTNamesEntryAndLine)
{
    const InputError error = parseError("startTime 0;\nendTime 1;\n\ndeltaT 0;\nwriteInterval 1;\n");
    EXPECT_EQ(error.file(), "case/system/controlDict");
    EXPECT_EQ(error.line(), 4);
    EXPECT_NE(error.message().find("'deltaT'"), std::string::npos) << error.message();
    EXPECT_NE(error.message().find("> 0"), std::string::npos) << error.message();
}

TEST(ControlDictErrors, EndTimeBeforeStartTime)
{
    const InputError error = parseError("startTime 2;\nendTime 1;\ndeltaT 0.1;\nwriteInterval 1;\n");
    EXPECT_EQ(error.line(), 2);
    EXPECT_NE(error.message().find("'endTime'"), std::string::npos) << error.message();
    EXPECT_NE(error.message().find("before startTime 2"), std::string::npos) << error.message();
}

TEST(ControlDictErrors, UnknownChoiceListsTheValidOnes)
{
    const InputError error = parseError(minimal + "writeControl\teveryStep;\n");
    EXPECT_EQ(error.line(), 5);
    EXPECT_NE(error.message().find("unknown value 'everyStep'; valid values are timeStep, runTime, adjustableRunTime"),
              std::string::npos)
        << error.message();
    EXPECT_EQ(parseError(minimal + "startFrom now;\n").line(), 5);
    EXPECT_EQ(parseError(minimal + "writeFormat text;\n").line(), 5);
    EXPECT_EQ(parseError(minimal + "timeFormat engineering;\n").line(), 5);
    EXPECT_EQ(parseError(minimal + "writeCompression maybe;\n").line(), 5);
}

TEST(ControlDictErrors, MissingRequiredEntryIsNamed)
{
    const InputError error = parseError("startTime 0;\ndeltaT 0.1;\nwriteInterval 1;\n");
    EXPECT_EQ(error.file(), "case/system/controlDict");
    EXPECT_NE(error.message().find("keyword endTime is undefined"), std::string::npos) << error.message();
    EXPECT_NE(parseError("endTime 1;\ndeltaT 0.1;\nwriteInterval 1;\n").message().find("startTime"), std::string::npos);
}

TEST(ControlDictErrors, FractionalTimeStepWriteIntervalAndBadPrecisions)
{
    EXPECT_EQ(parseError("startTime 0;\nendTime 1;\ndeltaT 0.1;\nwriteInterval 0.5;\n").line(), 4);
    const InputError precision = parseError(minimal + "timePrecision 0;\n");
    EXPECT_EQ(precision.line(), 5);
    EXPECT_NE(precision.message().find("'timePrecision'"), std::string::npos);
    EXPECT_EQ(parseError(minimal + "writePrecision 6.5;\n").line(), 5);
    EXPECT_EQ(parseError("startTime 0;\nendTime 1;\ndeltaT -0.1;\nwriteInterval 1;\n").line(), 3);
}
