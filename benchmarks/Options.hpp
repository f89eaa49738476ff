#pragma once
// rbmBenchmark's command line.

#include <filesystem>
#include <string>
#include <vector>

namespace rbm::benchmark {

namespace fs = std::filesystem;

struct Options {
    std::vector<double> sizes{1e4, 1e5, 1e6};
    bool sizesGiven = false;
    std::vector<std::string> variants{"decoupled", "linearized", "newton", "localGlobal"};
    std::vector<std::string> cases{"quad2D", "tri2D", "hex3D", "tet3D", "twist3D", "airfoil"};
    fs::path json;
    fs::path markdown;
    bool quick = false;
    std::string openfoam = "auto";
    std::string wholeProcess = "auto";
    int pitchingSteps = 100;           // coupled linearized
    int pitchingNonlinearSteps = 10;   // Newton and local/global (tens of seconds per step)
    double memoryLimitGiB = 10.0;
    int runTimeout = 1800;             // seconds per child run
    fs::path airfoilDir = fs::path(RBM_SOURCE_DIR) / "benchmarks" / "airfoilMesh";
    fs::path workDir;
    bool keep = false;
    std::string diffusivity = "inverseDistance";
    std::vector<int> ranks;            // --ranks: twist3D decomposed over each count too
    std::string commandLine;
};

std::vector<std::string> splitList(const std::string& text);

extern const char* usage;

Options parseOptions(int argc, char** argv);

} // namespace rbm::benchmark
