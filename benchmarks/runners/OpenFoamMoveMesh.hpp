#pragma once
// OpenFOAM's moveMesh (displacementLaplacian) on a case, where OpenFOAM is installed.

#include "Record.hpp"
#include <filesystem>
#include <string>
#include <vector>

namespace rbm::benchmark {

namespace fs = std::filesystem;

// OpenFOAM: the environment of its bashrc, when installed.
struct OpenFoam {
    bool available = false;
    std::vector<std::string> environment;
    std::string version;
};

OpenFoam detectOpenFoam(const fs::path& logDir);

std::string laplacianDynamicMeshDict(const std::string& diffusivity, const std::string& movingPatch);

Record runOpenFoamMoveMesh(const OpenFoam& openfoam, const std::string& caseName, const fs::path& polyMeshSource,
                           const fs::path& dir, const std::string& diffusivity, const std::string& boundaryField,
                           int steps, const std::string& label);

} // namespace rbm::benchmark
