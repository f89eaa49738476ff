#pragma once
// OpenFOAM's names of time folders and the listing of a case's time folders.
//
// OpenFOAM names a time folder with Time::timeName(t, precision): the value written by a C++
// stream with controlDict's timeFormat (general: no floatfield flag, i.e. printf "%.*g";
// fixed; scientific) and timePrecision significant digits. With the defaults (general, 6):
// 0 -> "0", 0.005 -> "0.005", 1 -> "1", 1e-05 -> "1e-05", 100 -> "100", 1234567 -> "1.23457e+06".

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace rbm::io {

enum class TimeFormat { General, Fixed, Scientific };

// "general", "fixed" or "scientific"; throws std::invalid_argument for anything else.
TimeFormat timeFormatFromName(std::string_view name);

// The folder name OpenFOAM uses for time `time`. -0 is written as "0".
std::string timeName(double time, TimeFormat format = TimeFormat::General, int precision = 6);

// OpenFOAM raises timePrecision when a new time would not be told apart by its name (Time's
// "Increased the timePrecision from 6 to 7 to distinguish between timeNames"): the smallest
// precision >= `precision` (at most 18, OpenFOAM's maximum) whose name reads back to within
// max(min(10^-precision, 0.1 deltaT), 1e-15) of `time`.
int adjustedTimePrecision(double time, double deltaT, TimeFormat format, int precision);

// One time folder of a case.
struct TimeDirectory {
    double value = 0.0;
    std::string name;   // as on disk, e.g. "0.005"
};

// The time folders of a case: sub-folders whose whole name reads as a number ("0", "0.5",
// "1e-05"; not "constant", "system", "0.orig"), sorted by value, as OpenFOAM's findTimes.
// Throws rbm::InputError naming the folder when it does not exist.
std::vector<TimeDirectory> listTimeDirectories(const std::filesystem::path& caseDirectory);

// The numeric value of a time folder name; false when the name is not a number.
bool parseTimeName(std::string_view name, double& value);

} // namespace rbm::io
