#pragma once
// The whole program rbmMoveMesh on a case.

#include "Record.hpp"
#include <filesystem>
#include <string>
#include <vector>

namespace rbm::benchmark {

namespace fs = std::filesystem;

// The dynamicMeshDict of an rbm run. `floatingPatches`: the case's free patches
// (PatchRole::free, zeroGradient in 0/pointDisplacement). OpenFOAM's displacementLaplacian
// leaves a zeroGradient patch's points free, while rbm makes them slide on the patch's own
// surface unless the patch floats; floating them keeps both programs on the same problem (the
// twisted cube's sides: sliding on their planes they cannot follow the turned top's corners).
std::string rbmDynamicMeshDict(const std::string& variant, const std::vector<std::string>& floatingPatches = {});

// The names of the patches of `caseName` whose role is PatchRole::free.
std::vector<std::string> floatingPatchNames(const std::string& caseName, const fs::path& polyMeshSource);

// Open MPI settings that make a single-process MPI_Init fast (no orted daemon, no network
// transports probed): 0.4 s -> 0.06 s on the benchmark machine.
const std::vector<std::string>& fastMpiStartEnvironment();

std::string fastMpiStartText();

Record runRbmMoveMesh(const fs::path& program, const std::string& caseName, const fs::path& polyMeshSource,
                      const fs::path& dir, const std::string& variant, const std::string& boundaryField, int steps,
                      bool fastMpiStart = false);

} // namespace rbm::benchmark
