// C++20 implementation of the C++17 host interface (HostMotionSolver.hpp).
#include "HostMotionSolver.hpp"

#include "FoamDictionary.hpp"
#include "HostMeshConversion.hpp"
#include "HostPetscSession.hpp"
#include "HostStepReporting.hpp"
#include "InputError.hpp"
#include "RigidBodyMotionSolver.hpp"
#include "RunLog.hpp"
#include "StepAssessment.hpp"
#include "ThreadCount.hpp"

#include <chrono>

namespace rbm::host {

using motion::PetscSession;

struct HostMotionSolver::Impl {
    std::shared_ptr<PetscSession> petsc = sharedPetscSession();
    PolyMesh mesh;
    std::unique_ptr<motion::RigidBodyMotionSolver> solver;
    std::unique_ptr<motion::StepAssessor> assessor;
};

HostMotionSolver::HostMotionSolver(const HostMesh& mesh, const std::string& coefficientsText,
                                   const std::string& coefficientsFile, const std::vector<HostPatchBoundary>& boundary,
                                   const std::string& caseDirectory)
    : impl_(std::make_unique<Impl>())
{
    applyHostThreadCountPolicy();
    try {
        impl_->mesh = toPolyMesh(mesh);
        const io::Dictionary coefficients = io::Dictionary::parseText(coefficientsText, coefficientsFile);
        impl_->solver = std::make_unique<motion::RigidBodyMotionSolver>(
            impl_->mesh, coefficients, toBoundaryDescription(impl_->mesh, boundary, "HostMotionSolver"), caseDirectory);
        impl_->assessor = std::make_unique<motion::StepAssessor>(impl_->mesh);
    } catch (const InputError& error) {
        throw HostInputError(error.file(), error.line(), error.message());
    }
}

HostMotionSolver::~HostMotionSolver()
{
    // PETSc objects before the session that may finalise PETSc.
    if (impl_) impl_->solver.reset();
}

std::size_t HostMotionSolver::pointCount() const { return impl_->mesh.points.size(); }
int HostMotionSolver::dimension() const { return impl_->solver->dimension(); }

HostStepReport HostMotionSolver::solve(int step, double time, const std::string& timeName, double* displacement,
                                       std::size_t valueCount)
{
    const auto started = std::chrono::steady_clock::now();
    motion::RigidBodyMotionSolver& solver = *impl_->solver;
    std::vector<Vector3>& u = solver.pointDisplacement();
    // Only the prescribed points' values matter to solve(); the others are its result.
    const motion::MotionSolveReport solve =
        solveOnHostArray("HostMotionSolver", displacement, valueCount, u, [&solver] { return solver.solve(); });
    io::StepLogRecord record = stepRecord(step, time, timeName);
    const motion::StepVerdict verdict = impl_->assessor->assess(solve, u, solver.curPoints(), record);
    // Not held through the flow solver's step and the next solve (as rbmMoveMesh between steps):
    // the check's geometry and topology, about 330 MB at 10⁶ hexahedra.
    impl_->assessor->releaseWorkspaces();
    record.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    return hostStepReport(record, verdict, solve.warnings, solver.invertedStepAdvice());
}

} // namespace rbm::host
