#pragma once
// The whole program rbmMoveMesh on a case.

#include "Record.hpp"
#include <filesystem>
#include <string>
#include <vector>

namespace rbm::benchmark {

namespace fs = std::filesystem;

std::string rbmDynamicMeshDict(const std::string& variant);

// Open MPI settings that make a single-process MPI_Init fast (no orted daemon, no network
// transports probed): 0.4 s -> 0.06 s on the benchmark machine.
const std::vector<std::string>& fastMpiStartEnvironment();

std::string fastMpiStartText();

Record runRbmMoveMesh(const fs::path& program, const std::string& caseName, const fs::path& polyMeshSource,
                      const fs::path& dir, const std::string& variant, const std::string& boundaryField, int steps,
                      bool fastMpiStart = false);

} // namespace rbm::benchmark
