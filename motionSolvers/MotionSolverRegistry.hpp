#pragma once
// Run-time selection of motion solvers by name, like OpenFOAM's, with plain C++: a map
// from name to factory, filled by one explicit registerBuiltinMotionSolvers() call (static
// self-registration from a static library is silently dropped by the linker).
//
// constant/dynamicMeshDict:
//     motionSolver    rigidBodyMotionSolver;     // or OpenFOAM's newer keyword: solver
//     rigidBodyMotionSolverCoeffs { ... }        // optional; the solver's options

#include "FoamDictionary.hpp"
#include "MotionSolver.hpp"
#include "PolyMesh.hpp"

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace rbm::motion {

using MotionSolverFactory = std::function<std::unique_ptr<MotionSolver>(
    const PolyMesh& mesh, const io::Dictionary& coefficients, const io::Dictionary* pointDisplacement,
    const std::filesystem::path& caseDirectory)>;

// The motion solver dynamicMeshDict names (`motionSolver` or `solver`, at the top level or in
// OpenFOAM 13's `mover`), where, and its `<name>Coeffs` sub-dictionary (empty when absent).
// Throws InputError when no solver is named.
struct MotionSolverSelection {
    std::string name;
    std::string file;
    int line = 0;
    io::Dictionary coefficients;
};
MotionSolverSelection selectedMotionSolver(const io::Dictionary& dynamicMeshDict);

class MotionSolverRegistry {
public:
    void add(const std::string& name, MotionSolverFactory factory);
    bool contains(const std::string& name) const { return factories_.count(name) != 0; }
    std::vector<std::string> names() const;

    // Reads `motionSolver` (or `solver`) from dynamicMeshDict and builds that solver with
    // its `<name>Coeffs` sub-dictionary (empty when absent). An unknown name is an
    // rbm::InputError naming the file, the line and the valid names.
    std::unique_ptr<MotionSolver> create(const PolyMesh& mesh, const io::Dictionary& dynamicMeshDict,
                                         const io::Dictionary* pointDisplacement,
                                         const std::filesystem::path& caseDirectory) const;

private:
    std::map<std::string, MotionSolverFactory> factories_;
};

// Adds rbm's own solvers (rigidBodyMotionSolver).
void registerBuiltinMotionSolvers(MotionSolverRegistry& registry);

// The registry with the built-in solvers.
const MotionSolverRegistry& builtinMotionSolvers();

} // namespace rbm::motion
