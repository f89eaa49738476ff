#pragma once
// One variant on one case, one step, in a child process of its own (a clean peak memory).

#include "Record.hpp"
#include <filesystem>
#include <string>
#include <vector>

namespace rbm::benchmark {

namespace fs = std::filesystem;

// One variant, one step: read, graph, problem, solver, solve, solve again, quality, write.
Record runVariantTask(const std::string& caseName, const std::string& variant, const fs::path& meshCase,
                      double memoryLimitBytes);

} // namespace rbm::benchmark
