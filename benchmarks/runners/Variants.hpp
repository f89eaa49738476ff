#pragma once
// The RBM variants the benchmark compares: the solver of each in process, its memory model, and
// its coefficients for the OpenFOAM-facing solver (rbmMoveMesh runs, pitching).

#include "RbmProblem.hpp"

#include <memory>
#include <string>
#include <vector>

namespace rbm::benchmark {

const std::vector<std::string>& allVariants();

bool isCoupledVariant(const std::string& variant);

// Solver options as RigidBodyMotionSolver sets them from its defaults.
std::unique_ptr<motion::RbmSolver> makeSolver(const std::string& variant, const motion::RbmProblem& problem);

// Rough memory of a variant's linear algebra (bytes), to skip runs that cannot fit: the
// model of motionSolvers/rigidBodyMotion/MemoryEstimate.hpp (rbmMoveMesh checks the same before it assembles).
double estimatedMatrixBytes(const std::string& variant, const motion::RbmProblem& problem);

// The OpenFOAM-facing solver's coefficients for a variant name of the program runs.
std::string solverCoefficients(const std::string& variant);

} // namespace rbm::benchmark
