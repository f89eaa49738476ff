#pragma once
// The airfoil pitching with the OpenFOAM-facing solver, in a child process of its own.

#include "Record.hpp"
#include <filesystem>
#include <string>
#include <vector>

namespace rbm::benchmark {

namespace fs = std::filesystem;

// The airfoil pitching for one period in `steps` time steps with RigidBodyMotionSolver:
// solve, quality and points output per step.
Record runPitchingTask(const std::string& variant, int steps, const fs::path& airfoilDir, const fs::path& workDir);

} // namespace rbm::benchmark
