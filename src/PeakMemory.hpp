#pragma once
// The largest resident memory this process has had (Linux: getrusage's ru_maxrss, the kernel's
// VmHWM), in MiB; 0 where the system does not say. What a decomposed run reports per rank.

#include <sys/resource.h>

namespace rbm {

inline double peakResidentMebibytes()
{
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
    return static_cast<double>(usage.ru_maxrss) / 1024.0;   // KiB on Linux
}

} // namespace rbm
