// Tests of the time folder names (io/TimeName): OpenFOAM's timeFormat and timePrecision.

#include "ControlDict.hpp"
#include "TestCases.hpp"
#include "TimeName.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace rbm::test::controlDictCases;

using rbm::InputError;
using rbm::io::TimeFormat;

TEST(TimeName, GeneralFormatWithPrecisionSixMatchesOpenFoam)
{
    EXPECT_EQ(rbm::io::timeName(0.0), "0");
    EXPECT_EQ(rbm::io::timeName(0.005), "0.005");
    EXPECT_EQ(rbm::io::timeName(1.0), "1");
    EXPECT_EQ(rbm::io::timeName(1e-05), "1e-05");
    EXPECT_EQ(rbm::io::timeName(0.1), "0.1");
    EXPECT_EQ(rbm::io::timeName(100.0), "100");
    EXPECT_EQ(rbm::io::timeName(1234567.0), "1.23457e+06");
    EXPECT_EQ(rbm::io::timeName(0.1 + 0.2), "0.3");          // 0.30000000000000004 rounds at 6 digits
    EXPECT_EQ(rbm::io::timeName(200 * 0.005), "1");          // accumulated steps still name "1"
    EXPECT_EQ(rbm::io::timeName(-0.0), "0");
    EXPECT_EQ(rbm::io::timeName(0.0001), "0.0001");
    EXPECT_EQ(rbm::io::timeName(0.00001234567), "1.23457e-05");
}

TEST(TimeName, FixedAndScientificFormats)
{
    EXPECT_EQ(rbm::io::timeName(0.005, TimeFormat::Fixed, 3), "0.005");
    EXPECT_EQ(rbm::io::timeName(1.0, TimeFormat::Fixed, 3), "1.000");
    EXPECT_EQ(rbm::io::timeName(0.005, TimeFormat::Scientific, 2), "5.00e-03");
    EXPECT_EQ(rbm::io::timeName(0.125, TimeFormat::General, 2), "0.12");  // round half to even of the binary value
    EXPECT_EQ(rbm::io::timeFormatFromName("scientific"), TimeFormat::Scientific);
    EXPECT_THROW(rbm::io::timeFormatFromName("engineering"), std::invalid_argument);
}

TEST(TimeName, PrecisionIsRaisedUntilTheNameDistinguishesTheTime)
{
    // 1.0000001 with 6 digits is "1"; the tolerance is 0.1 deltaT = 1e-8, which needs 8 digits.
    EXPECT_EQ(rbm::io::adjustedTimePrecision(1.0000001, 1e-7, TimeFormat::General, 6), 8);
    EXPECT_EQ(rbm::io::timeName(1.0000001, TimeFormat::General, 8), "1.0000001");
    EXPECT_EQ(rbm::io::adjustedTimePrecision(0.005, 0.005, TimeFormat::General, 6), 6);
    EXPECT_EQ(rbm::io::adjustedTimePrecision(1.5, 0.5, TimeFormat::General, 1), 2);  // "2" -> "1.5"
}

TEST(TimeName, ListsNumericFoldersSortedByValue)
{
    fs::path folder = scratchCase("times");
    for (const char* name : {"10", "0", "0.5", "1e-05", "2", "constant", "0.orig", "processor0"}) {
        fs::create_directories(folder / name);
    }
    std::ofstream(folder / "3") << "a file, not a time folder";
    const auto times = rbm::io::listTimeDirectories(folder);
    ASSERT_EQ(times.size(), 5u);
    EXPECT_EQ(times[0].name, "0");
    EXPECT_EQ(times[1].name, "1e-05");
    EXPECT_DOUBLE_EQ(times[1].value, 1e-5);
    EXPECT_EQ(times[2].name, "0.5");
    EXPECT_EQ(times[3].name, "2");
    EXPECT_EQ(times[4].name, "10");
    EXPECT_THROW(rbm::io::listTimeDirectories(folder / "missing"), InputError);
}
