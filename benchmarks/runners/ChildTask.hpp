#pragma once
// Child runs: the parent starts `rbmBenchmark --run-one TASK ...` for each measurement; the
// child prints its record between RBM_BENCHMARK_RECORD_BEGIN / _END on standard output.

#include "Record.hpp"
#include <filesystem>
#include <string>
#include <vector>

namespace rbm::benchmark {

namespace fs = std::filesystem;

int runOne(const std::vector<std::string>& args);

// Runs a child task; a failure becomes a record with failed = true.
Record runChild(const std::vector<std::string>& taskArgs, const fs::path& logDir, const std::string& logName,
                const Record& identity);

} // namespace rbm::benchmark
