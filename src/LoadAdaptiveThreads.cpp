#include "LoadAdaptiveThreads.hpp"

#include "ThreadCount.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace rbm {

namespace {

// Intervals shorter than this say little about the load: the count is kept.
constexpr double shortestInterval = 0.01;   // s

} // namespace

LoadAdaptiveThreads::LoadAdaptiveThreads(int most) : most_(std::max(1, most)), current_(std::max(1, most))
{
    const char* requested = std::getenv("OMP_NUM_THREADS");
    const long online = sysconf(_SC_NPROCESSORS_ONLN);
    cores_ = online > 0 ? static_cast<int>(online) : 1;
    last_ = sample();
    active_ = most_ > 1 && (requested == nullptr || *requested == '\0') && last_.valid;
}

LoadAdaptiveThreads::Sample LoadAdaptiveThreads::sample()
{
    Sample s;
    s.at = std::chrono::steady_clock::now();
    std::ifstream stat("/proc/stat");
    std::string line;
    if (!stat || !std::getline(stat, line) || line.rfind("cpu ", 0) != 0) return s;
    std::istringstream fields(line.substr(4));
    // user nice system idle iowait irq softirq steal: busy = all but idle and iowait.
    double value = 0.0, total = 0.0, idle = 0.0;
    for (int k = 0; k < 8 && fields >> value; ++k) {
        total += value;
        if (k == 3 || k == 4) idle += value;
    }
    const long ticks = sysconf(_SC_CLK_TCK);
    if (ticks <= 0) return s;
    s.busySeconds = (total - idle) / static_cast<double>(ticks);
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return s;
    s.ownSeconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                   1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    s.valid = true;
    return s;
}

int LoadAdaptiveThreads::update()
{
    if (!active_) return current_;
    const Sample now = sample();
    const double wall = std::chrono::duration<double>(now.at - last_.at).count();
    if (!now.valid || wall < shortestInterval) return current_;
    const double others = ((now.busySeconds - last_.busySeconds) - (now.ownSeconds - last_.ownSeconds)) / wall;
    last_ = now;
    otherLoad_ = std::clamp(others, 0.0, static_cast<double>(cores_));
    const int free = static_cast<int>(std::floor(static_cast<double>(cores_) - otherLoad_ + 0.5));
    const int threads = std::clamp(free, 1, most_);
    if (threads != current_) {
        setThreadCount(threads);
        current_ = threads;
    }
    return current_;
}

} // namespace rbm
