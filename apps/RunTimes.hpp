#pragma once
// The times of a moveMesh run as rbmMoveMesh takes them from system/controlDict and the time
// folders (docs/rbmMoveMesh.md): the start time and its folder's name, the number of steps,
// and the pointDisplacement file that holds the boundary conditions. A decomposed case keeps
// its time folders in each processorN/, the controlDict in the case.

#include "ControlDict.hpp"

#include <filesystem>
#include <string>

namespace rbm::app {

struct RunTimes {
    io::ControlDict control;
    double startTime = 0.0;
    std::string startTimeName;
    // Steps k = 1..stepCount at startTime + k deltaT: the largest k with t_k <= endTime within
    // endTolerance steps (1e-9, or the rounding of the times when they are large against deltaT).
    int stepCount = 0;
    double endTolerance = 1e-9;
    // <time>/pointDisplacement of the earliest time folder up to the start time that has one.
    std::filesystem::path boundaryFieldFile;

    double stepTime(int step) const { return startTime + step * control.deltaT; }
};

// `timeFolders`: where the time folders are (the case, or one processorN of a decomposed
// case). Throws InputError for an endTime before the start, too many steps, or no
// pointDisplacement up to the start time.
RunTimes readRunTimes(const std::filesystem::path& caseDirectory, const std::filesystem::path& timeFolders);

} // namespace rbm::app
