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

namespace {

// The dictionary that names the motion solver: OpenFOAM 13 puts it into `mover { type
// motionSolver; motionSolver ...; }`, v1912 at the top level of dynamicMeshDict.
const io::Dictionary& motionSolverDictionary(const io::Dictionary& dynamicMeshDict)
{
    const io::Entry* moverEntry = dynamicMeshDict.find("mover");
    if (!moverEntry) return dynamicMeshDict;
    if (!moverEntry->isDictionary())
        throw InputError(moverEntry->file(), moverEntry->line(),
                         "'mover' must be a dictionary (OpenFOAM 13: mover { type motionSolver; motionSolver ...; })");
    const io::Dictionary& mover = moverEntry->dictionary();
    if (mover.contains("type") && mover.get<std::string>("type") != "motionSolver") {
        const io::Entry& type = mover.lookup("type");
        throw InputError(type.file(), type.line(),
                         "mover type " + mover.get<std::string>("type") +
                             ": rbmMoveMesh moves meshes with a motion solver only; expected 'type motionSolver;'");
    }
    return mover;
}

} // namespace

MotionSolverSelection selectedMotionSolver(const io::Dictionary& dynamicMeshDict)
{
    const io::Dictionary& dictionary = motionSolverDictionary(dynamicMeshDict);
    const char* keyword = dictionary.contains("motionSolver") ? "motionSolver" : "solver";
    if (!dictionary.contains(keyword)) {
        throw InputError(dictionary.file(), dictionary.line(),
                         "keyword 'motionSolver' (or 'solver') is missing: it names the motion solver");
    }
    const io::Entry& entry = dictionary.lookup(keyword);
    MotionSolverSelection selection{dictionary.get<std::string>(keyword), entry.file(), entry.line(),
                                    io::Dictionary(dictionary.name() + "/" + dictionary.get<std::string>(keyword) +
                                                       "Coeffs",
                                                   dictionary.file(), 0)};
    if (const io::Dictionary* coefficients = dictionary.findDictionary(selection.name + "Coeffs"))
        selection.coefficients = *coefficients;
    return selection;
}

std::unique_ptr<MotionSolver> MotionSolverRegistry::create(const PolyMesh& mesh, const io::Dictionary& dynamicMeshDict,
                                                           const io::Dictionary* pointDisplacement,
                                                           const std::filesystem::path& caseDirectory) const
{
    const MotionSolverSelection selection = selectedMotionSolver(dynamicMeshDict);
    const auto factory = factories_.find(selection.name);
    if (factory == factories_.end()) {
        std::string valid;
        for (const std::string& known : names()) valid += (valid.empty() ? "" : " ") + known;
        throw InputError(selection.file, selection.line,
                         "Unknown motionSolver type " + selection.name + ". Valid motionSolver types are: " + valid);
    }
    return factory->second(mesh, selection.coefficients, pointDisplacement, caseDirectory);
}

void registerBuiltinMotionSolvers(MotionSolverRegistry& registry)
{
    const MotionSolverFactory rbm = [](const PolyMesh& mesh, const io::Dictionary& coefficients,
                                       const io::Dictionary* pointDisplacement,
                                       const std::filesystem::path& caseDirectory) -> std::unique_ptr<MotionSolver> {
        return std::make_unique<RigidBodyMotionSolver>(
            mesh, coefficients, makePatchBoundaryConditions(mesh, pointDisplacement, caseDirectory), caseDirectory);
    };
    registry.add(std::string(RigidBodyMotionSolver::typeNameString), rbm);
    // The plugin's second name, which does not collide with OpenFOAM's own 6-DoF
    // rigidBodyMotionSolver: a case switched with it moves the same in rbmMoveMesh.
    registry.add("rbmMotionSolver", rbm);
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
