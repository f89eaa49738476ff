#pragma once
// Numbers as rbmMoveMesh prints them in its header, step lines and summary.

#include <cmath>
#include <cstdio>
#include <string>

namespace rbm::app {

// `decimals` digits after the point; "n/a" for NaN or infinity.
inline std::string fixed(double value, int decimals)
{
    if (!std::isfinite(value)) return "n/a";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    return buffer;
}

// printf's %g with `digits` significant digits.
inline std::string general(double value, int digits = 6)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    return buffer;
}

} // namespace rbm::app
