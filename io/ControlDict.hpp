#pragma once
// The run controls of system/controlDict that rbm uses, with OpenFOAM v1912's names, defaults
// and meanings:
//
//   startFrom        startTime | firstTime | latestTime;   (default startTime)
//   startTime        0;          required with startFrom startTime
//   endTime          1;          required, >= startTime
//   deltaT           0.005;      required, > 0
//   writeControl     timeStep | runTime | adjustableRunTime | cpuTime | clockTime;  (default timeStep)
//   writeInterval    20;         required, > 0 (a whole number >= 1 with timeStep)
//   writeFormat      ascii | binary;                       (default ascii)
//   writePrecision   6;          (default 6)
//   writeCompression on | off | compressed | uncompressed | true | false;  (default off)
//   timeFormat       general | fixed | scientific;         (default general)
//   timePrecision    6;          (default 6)
//
// Every other entry (application, functions, ...) is ignored. Errors are rbm::InputError
// naming the file, the entry's line and the entry.

#include "FoamDictionary.hpp"
#include "TimeName.hpp"

#include <filesystem>
#include <string>

namespace rbm::io {

struct ControlDict {
    enum class StartFrom { StartTime, FirstTime, LatestTime };
    enum class WriteControl { TimeStep, RunTime, AdjustableRunTime, CpuTime, ClockTime };

    StartFrom startFrom = StartFrom::StartTime;
    double startTime = 0.0;          // as given; see resolveStartTime for firstTime/latestTime
    double endTime = 0.0;
    double deltaT = 0.0;
    WriteControl writeControl = WriteControl::TimeStep;
    double writeInterval = 1.0;      // steps for timeStep, seconds otherwise
    bool binary = false;             // writeFormat binary
    int writePrecision = 6;
    bool writeCompression = false;
    TimeFormat timeFormat = TimeFormat::General;
    int timePrecision = 6;
    std::string file;                // where it was read from, for later messages

    // The folder name of time t with this dictionary's timeFormat and timePrecision.
    std::string timeName(double t) const { return io::timeName(t, timeFormat, timePrecision); }
};

// Reads and validates `caseDirectory`/system/controlDict (or controlDict.gz).
ControlDict readControlDict(const std::filesystem::path& caseDirectory);
// Validates an already parsed controlDict.
ControlDict controlDictFromDictionary(const Dictionary& dictionary);

// The start time the run begins from: startTime, or the first / latest time folder of the case
// (OpenFOAM's -latestTime). Throws rbm::InputError when the case has no time folder, or when
// endTime is before the resolved start time.
double resolveStartTime(const ControlDict& controlDict, const std::filesystem::path& caseDirectory);

} // namespace rbm::io
