#pragma once
// Running a program and measuring it (wall and CPU time, peak memory), and what this process
// knows of itself (/proc).

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rbm::benchmark {

namespace fs = std::filesystem;

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start);

// CPU time of this process, all threads (OpenBLAS may use several).
double processCpuSeconds();

// A "Vm..." entry of /proc/self/status in MiB (NaN when not available).
double procStatusMiB(const std::string& name);

std::string firstLineWith(const std::string& file, const std::string& prefix);

std::string afterColon(const std::string& line);

std::uintmax_t directoryBytes(const fs::path& directory);

fs::path selfExecutable();

struct ProcessResult {
    int exitCode = -1;
    double wallSeconds = 0.0;
    double maxRssMiB = 0.0;
    double userSeconds = 0.0;
    double systemSeconds = 0.0;
    std::string output;  // standard output (unless redirected to a file)
};

// Runs argv[0] with its arguments; standard output captured (or to stdoutFile), standard
// error to stderrFile; environment = the parent's unless given.
ProcessResult runProcess(const std::vector<std::string>& argv, const fs::path& stderrFile,
                         const std::vector<std::string>* environment = nullptr, const fs::path& stdoutFile = {},
                         const fs::path& workingDirectory = {});

std::string trim(const std::string& text);

std::string readTail(const fs::path& file, std::size_t bytes = 600);

std::vector<std::string> environmentWith(const std::vector<std::string>& additions);

} // namespace rbm::benchmark
