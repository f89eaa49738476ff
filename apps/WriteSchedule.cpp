#include "WriteSchedule.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>

namespace rbm::app {

namespace {

double cpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

} // namespace

WriteSchedule::WriteSchedule(const io::ControlDict& control, double startTime)
    : control_(control), startTime_(startTime), cpuStart_(cpuSeconds()), clockStart_(std::chrono::steady_clock::now())
{
}

bool WriteSchedule::crossed(double elapsed)
{
    const auto index = static_cast<long long>(elapsed / control_.writeInterval);
    if (index <= writeTimeIndex_) return false;
    writeTimeIndex_ = index;
    return true;
}

bool WriteSchedule::isWriteTime(int step, double time)
{
    switch (control_.writeControl) {
    case io::ControlDict::WriteControl::TimeStep: {
        const long long interval = std::max<long long>(1, std::llround(control_.writeInterval));
        return step % interval == 0;
    }
    case io::ControlDict::WriteControl::RunTime:
    case io::ControlDict::WriteControl::AdjustableRunTime:
        // label(((t − startTime) + 0.5 deltaT)/writeInterval) grows.
        return crossed((time - startTime_) + 0.5 * control_.deltaT);
    case io::ControlDict::WriteControl::CpuTime:
        return crossed(cpuSeconds() - cpuStart_);
    case io::ControlDict::WriteControl::ClockTime:
        return crossed(std::chrono::duration<double>(std::chrono::steady_clock::now() - clockStart_).count());
    }
    return false;
}

} // namespace rbm::app
