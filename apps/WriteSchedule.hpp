#pragma once
// When a step is written: controlDict's writeControl and writeInterval as OpenFOAM v1912's
// Time::operator++ applies them. timeStep writes every writeInterval steps; runTime,
// adjustableRunTime (the time step is fixed here), cpuTime and clockTime write when the index
// of the current write interval grows.

#include "ControlDict.hpp"

#include <chrono>

namespace rbm::app {

class WriteSchedule {
public:
    // The cpu and clock intervals count from now.
    WriteSchedule(const io::ControlDict& control, double startTime);
    // Whether step `step` at `time` is written. Call it once per step, in order: it keeps state.
    bool isWriteTime(int step, double time);

private:
    bool crossed(double elapsed);

    const io::ControlDict& control_;
    double startTime_;
    long long writeTimeIndex_ = 0;  // OpenFOAM's Time::writeTimeIndex_
    double cpuStart_;
    std::chrono::steady_clock::time_point clockStart_;
};

} // namespace rbm::app
