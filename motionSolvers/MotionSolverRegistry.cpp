#include "MotionSolverRegistry.hpp"

#include "InputError.hpp"
#include "PatchBoundaryConditions.hpp"
#include "RigidBodyMotionSolver.hpp"

#include <stdexcept>

namespace rbm::motion {

void MotionSolverRegistry::add(const std::string& name, MotionSolverFactory factory)
{
    factories_[name] = std::move(factory);
}

std::vector<std::string> MotionSolverRegistry::names() const
{
    std::vector<std::string> result;
    for (const auto& [name, factory] : factories_) result.push_back(name);
    return result;
}

std::unique_ptr<MotionSolver> MotionSolverRegistry::create(const PolyMesh& mesh, const io::Dictionary& dynamicMeshDict,
                                                           const io::Dictionary* pointDisplacement,
                                                           const std::filesystem::path& caseDirectory) const
{
    const char* keyword = dynamicMeshDict.contains("motionSolver") ? "motionSolver" : "solver";
    if (!dynamicMeshDict.contains(keyword)) {
        throw InputError(dynamicMeshDict.file(), 0,
                         "keyword 'motionSolver' (or 'solver') is missing: it names the motion solver");
    }
    const io::Entry& entry = dynamicMeshDict.lookup(keyword);
    const std::string name = dynamicMeshDict.get<std::string>(keyword);
    const auto factory = factories_.find(name);
    if (factory == factories_.end()) {
        std::string valid;
        for (const std::string& known : names()) valid += (valid.empty() ? "" : " ") + known;
        throw InputError(entry.file(), entry.line(),
                         "Unknown motionSolver type " + name + ". Valid motionSolver types are: " + valid);
    }
    const io::Dictionary* coefficients = dynamicMeshDict.findDictionary(name + "Coeffs");
    const io::Dictionary empty(dynamicMeshDict.name() + "/" + name + "Coeffs", dynamicMeshDict.file(), 0);
    return factory->second(mesh, coefficients ? *coefficients : empty, pointDisplacement, caseDirectory);
}

void registerBuiltinMotionSolvers(MotionSolverRegistry& registry)
{
    registry.add(std::string(RigidBodyMotionSolver::typeNameString),
                 [](const PolyMesh& mesh, const io::Dictionary& coefficients, const io::Dictionary* pointDisplacement,
                    const std::filesystem::path& caseDirectory) -> std::unique_ptr<MotionSolver> {
                     return std::make_unique<RigidBodyMotionSolver>(
                         mesh, coefficients, makePatchBoundaryConditions(mesh, pointDisplacement, caseDirectory),
                         caseDirectory);
                 });
}

const MotionSolverRegistry& builtinMotionSolvers()
{
    static const MotionSolverRegistry registry = [] {
        MotionSolverRegistry r;
        registerBuiltinMotionSolvers(r);
        return r;
    }();
    return registry;
}

} // namespace rbm::motion
