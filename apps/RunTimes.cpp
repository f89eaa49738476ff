#include "RunTimes.hpp"

#include "CompressedFile.hpp"
#include "InputError.hpp"
#include "TimeName.hpp"

#include "NumberText.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace rbm::app {

RunTimes readRunTimes(const std::filesystem::path& caseDirectory, const std::filesystem::path& timeFolders)
{
    RunTimes times;
    times.control = io::readControlDict(caseDirectory);
    const io::ControlDict& control = times.control;
    times.startTime = io::resolveStartTime(control, timeFolders);
    if (control.endTime < times.startTime) {
        throw InputError(control.file, 0,
                         "endTime " + general(control.endTime) + " is before the start time " + general(times.startTime));
    }
    // Steps up to endTime within 1e-9 deltaT, or within the rounding of the times themselves
    // when they are large against deltaT (16 ulps: 1.0000002 − 1 is 1.9999999 steps of 1e-7).
    const double span = (control.endTime - times.startTime) / control.deltaT;
    const double roundingInSteps = 16.0 * std::numeric_limits<double>::epsilon() *
                                   std::max(std::abs(times.startTime), std::abs(control.endTime)) / control.deltaT;
    times.endTolerance = std::max(1e-9, roundingInSteps);
    if (span + times.endTolerance >= static_cast<double>(std::numeric_limits<int>::max())) {
        throw InputError(control.file, 0, "(endTime - startTime)/deltaT = " + general(span) + " steps: too many");
    }
    times.stepCount = static_cast<int>(std::floor(span + times.endTolerance));

    // The start folder and the folder of the boundary conditions.
    const std::vector<io::TimeDirectory> folders = io::listTimeDirectories(timeFolders);
    const double timeTolerance = 1e-9 * control.deltaT;
    times.startTimeName = control.timeName(times.startTime);
    for (const io::TimeDirectory& time : folders) {
        if (std::abs(time.value - times.startTime) <= timeTolerance) times.startTimeName = time.name;
    }
    for (const io::TimeDirectory& time : folders) {
        if (time.value > times.startTime + timeTolerance) break;
        if (io::existsMaybeCompressed(timeFolders / time.name / "pointDisplacement")) {
            times.boundaryFieldFile = timeFolders / time.name / "pointDisplacement";
            break;
        }
    }
    if (times.boundaryFieldFile.empty()) {
        throw InputError((timeFolders / times.startTimeName / "pointDisplacement").string(), 0,
                         "no point displacement field: rbmMoveMesh takes the boundary conditions of the motion "
                         "from <time>/pointDisplacement of the earliest time folder up to the start time " +
                             times.startTimeName);
    }
    return times;
}

} // namespace rbm::app
