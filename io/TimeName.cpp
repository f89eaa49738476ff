#include "TimeName.hpp"

#include "InputError.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace rbm::io {

namespace fs = std::filesystem;

TimeFormat timeFormatFromName(std::string_view name)
{
    if (name == "general") return TimeFormat::General;
    if (name == "fixed") return TimeFormat::Fixed;
    if (name == "scientific") return TimeFormat::Scientific;
    throw std::invalid_argument("unknown timeFormat '" + std::string(name) + "'; valid formats are general, fixed, scientific");
}

std::string timeName(double time, TimeFormat format, int precision)
{
    if (time == 0.0) time = 0.0;  // -0 -> 0
    // A stream, as OpenFOAM's Time::timeName does, so every format matches it digit for digit.
    std::ostringstream out;
    if (format == TimeFormat::Fixed) out.setf(std::ios_base::fixed, std::ios_base::floatfield);
    if (format == TimeFormat::Scientific) out.setf(std::ios_base::scientific, std::ios_base::floatfield);
    out.precision(precision);
    out << time;
    return out.str();
}

bool parseTimeName(std::string_view name, double& value)
{
    if (name.empty()) return false;
    if (name.front() == '+') name.remove_prefix(1);
    const auto result = std::from_chars(name.data(), name.data() + name.size(), value);
    return result.ec == std::errc() && result.ptr == name.data() + name.size() && std::isfinite(value);
}

int adjustedTimePrecision(double time, double deltaT, TimeFormat format, int precision)
{
    constexpr int maximumPrecision = 18;  // OpenFOAM: 3 - log10(SMALL) with SMALL = 1e-15
    constexpr double small = 1e-15;
    const double tolerance = std::max(std::min(std::pow(10.0, -precision), 0.1 * deltaT), small);
    int adjusted = precision;
    while (adjusted < maximumPrecision) {
        double readBack = 0.0;
        if (parseTimeName(timeName(time, format, adjusted), readBack) && std::abs(readBack - time) <= tolerance) break;
        ++adjusted;
    }
    return adjusted;
}

std::vector<TimeDirectory> listTimeDirectories(const fs::path& caseDirectory)
{
    std::error_code error;
    if (!fs::is_directory(caseDirectory, error)) {
        throw InputError(caseDirectory.string(), 0, "case folder does not exist or is not a folder");
    }
    std::vector<TimeDirectory> times;
    for (const fs::directory_entry& entry : fs::directory_iterator(caseDirectory)) {
        if (!entry.is_directory()) continue;
        const std::string name = entry.path().filename().string();
        double value = 0.0;
        if (parseTimeName(name, value)) times.push_back({value, name});
    }
    std::stable_sort(times.begin(), times.end(),
                     [](const TimeDirectory& a, const TimeDirectory& b) { return a.value < b.value; });
    return times;
}

} // namespace rbm::io
