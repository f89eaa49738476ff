#pragma once
// Wall and CPU time of one phase of a run, stored in its record.

#include "Process.hpp"
#include "Record.hpp"

#include <string>
#include <utility>

namespace rbm::benchmark {

// Wall and CPU time of one phase, stored as <name>Seconds and <name>CpuSeconds.
class PhaseTimer {
public:
    PhaseTimer(Record& record, std::string name) : record_(record), name_(std::move(name)) {}
    ~PhaseTimer() { stop(); }
    void stop()
    {
        if (stopped_) return;
        stopped_ = true;
        record_.set(name_ + "Seconds", secondsSince(wall_));
        record_.set(name_ + "CpuSeconds", processCpuSeconds() - cpu_);
    }

private:
    Record& record_;
    std::string name_;
    Clock::time_point wall_ = Clock::now();
    double cpu_ = processCpuSeconds();
    bool stopped_ = false;
};

} // namespace rbm::benchmark
