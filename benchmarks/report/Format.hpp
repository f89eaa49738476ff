#pragma once
// Numbers as the report prints them.

#include <string>

namespace rbm::benchmark {

std::string fixed(double value, int digits);

// Seconds with three significant digits (at least 3 decimals below 1 s).
std::string seconds(double value);

std::string count(double value);

std::string sizeLabel(double size);

} // namespace rbm::benchmark
