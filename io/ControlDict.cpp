#include "ControlDict.hpp"

#include <cmath>

namespace rbm::io {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void failAt(const Entry& entry, const std::string& message)
{
    throw InputError(entry.file(), entry.line(), "entry '" + entry.keyword() + "' in controlDict: " + message);
}

// A single word (or string) of an entry, checked against the valid choices.
std::string choice(const Dictionary& dictionary, const std::string& keyword, const std::vector<std::string>& valid)
{
    const Entry& entry = dictionary.lookup(keyword);
    const std::string value = dictionary.get<std::string>(keyword);
    for (const std::string& v : valid) {
        if (v == value) return value;
    }
    std::string list;
    for (const std::string& v : valid) list += (list.empty() ? "" : ", ") + v;
    failAt(entry, "unknown value '" + value + "'; valid values are " + list);
}

double positive(const Dictionary& dictionary, const std::string& keyword)
{
    const double value = dictionary.get<double>(keyword);
    if (!(value > 0.0) || !std::isfinite(value)) failAt(dictionary.lookup(keyword), "must be > 0, found " + dictionary.lookup(keyword).valueText());
    return value;
}

int positiveInteger(const Dictionary& dictionary, const std::string& keyword, int fallback)
{
    if (!dictionary.contains(keyword)) return fallback;
    const Label value = dictionary.get<Label>(keyword);
    if (value < 1) failAt(dictionary.lookup(keyword), "must be a whole number >= 1, found " + std::to_string(value));
    return value;
}

} // namespace

ControlDict controlDictFromDictionary(const Dictionary& dictionary)
{
    ControlDict control;
    control.file = dictionary.file();

    if (dictionary.contains("startFrom")) {
        const std::string startFrom = choice(dictionary, "startFrom", {"startTime", "firstTime", "latestTime"});
        control.startFrom = startFrom == "startTime" ? ControlDict::StartFrom::StartTime
                            : startFrom == "firstTime" ? ControlDict::StartFrom::FirstTime
                                                       : ControlDict::StartFrom::LatestTime;
    }
    if (control.startFrom == ControlDict::StartFrom::StartTime) {
        control.startTime = dictionary.get<double>("startTime");  // required: names the keyword when missing
    } else {
        control.startTime = dictionary.getOrDefault<double>("startTime", 0.0);
    }
    control.endTime = dictionary.get<double>("endTime");
    if (control.startFrom == ControlDict::StartFrom::StartTime && control.endTime < control.startTime) {
        failAt(dictionary.lookup("endTime"), "endTime " + dictionary.lookup("endTime").valueText() +
                                                 " is before startTime " + dictionary.lookup("startTime").valueText());
    }
    control.deltaT = positive(dictionary, "deltaT");

    if (dictionary.contains("writeControl")) {
        const std::string writeControl =
            choice(dictionary, "writeControl", {"timeStep", "runTime", "adjustableRunTime", "cpuTime", "clockTime"});
        using W = ControlDict::WriteControl;
        control.writeControl = writeControl == "timeStep"            ? W::TimeStep
                               : writeControl == "runTime"           ? W::RunTime
                               : writeControl == "adjustableRunTime" ? W::AdjustableRunTime
                               : writeControl == "cpuTime"           ? W::CpuTime
                                                                     : W::ClockTime;
    }
    control.writeInterval = positive(dictionary, "writeInterval");
    if (control.writeControl == ControlDict::WriteControl::TimeStep && control.writeInterval < 1.0) {
        failAt(dictionary.lookup("writeInterval"),
               "with writeControl timeStep it counts time steps and must be >= 1, found " +
                   dictionary.lookup("writeInterval").valueText());
    }

    if (dictionary.contains("writeFormat")) {
        control.binary = choice(dictionary, "writeFormat", {"ascii", "binary"}) == "binary";
    }
    control.writePrecision = positiveInteger(dictionary, "writePrecision", 6);
    if (dictionary.contains("writeCompression")) {
        const std::string compression = choice(
            dictionary, "writeCompression", {"on", "off", "compressed", "uncompressed", "true", "false", "yes", "no"});
        control.writeCompression = compression == "on" || compression == "compressed" || compression == "true" ||
                                   compression == "yes";
    }
    if (dictionary.contains("timeFormat")) {
        control.timeFormat = timeFormatFromName(choice(dictionary, "timeFormat", {"general", "fixed", "scientific"}));
    }
    control.timePrecision = positiveInteger(dictionary, "timePrecision", 6);
    return control;
}

ControlDict readControlDict(const fs::path& caseDirectory)
{
    return controlDictFromDictionary(Dictionary::readFile(caseDirectory / "system" / "controlDict"));
}

double resolveStartTime(const ControlDict& control, const fs::path& caseDirectory)
{
    if (control.startFrom == ControlDict::StartFrom::StartTime) return control.startTime;
    const std::vector<TimeDirectory> times = listTimeDirectories(caseDirectory);
    const char* mode = control.startFrom == ControlDict::StartFrom::FirstTime ? "firstTime" : "latestTime";
    if (times.empty()) {
        throw InputError(control.file, 0, std::string("startFrom ") + mode + ": the case " + caseDirectory.string() +
                                              " has no time folder");
    }
    const double start = control.startFrom == ControlDict::StartFrom::FirstTime ? times.front().value : times.back().value;
    if (control.endTime < start) {
        throw InputError(control.file, 0, "endTime " + timeName(control.endTime) + " is before the " + mode + " " +
                                              timeName(start) + " of the case");
    }
    return start;
}

} // namespace rbm::io
