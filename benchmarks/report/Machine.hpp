#pragma once
// The machine and the time of a benchmark run, for the report's header.

#include "Record.hpp"

#include <filesystem>
#include <string>

namespace rbm::benchmark {

namespace fs = std::filesystem;

std::string todayIso();

std::string nowIso();

Record machineRecord(const fs::path& logDir);

std::string loadAverage();

} // namespace rbm::benchmark
